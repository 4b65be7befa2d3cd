"""Command line: ``circuitsim run|sweep|op|ac|pss|fit|diagnose|identify|check|equations|
components``. A thin face over the API.

Exit codes: 0 success; 1 solver failure (the message names the simulated time and the variable)
or, for a sweep, runs that failed; 2 bad input (the message names file, line, component and the
fix; also an output that is an input or a folder); 3 an output could not be written (disk full,
read-only folder); 130 interrupted (Ctrl-C), 143 terminated (SIGTERM).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import signal
import sys
import warnings
from pathlib import Path

from circuitsim.cli.argtypes import quantity
from circuitsim.errors import CircuitsimError, ParameterError, SolverError
from circuitsim.files import atomic_write, check_output
from circuitsim.report.plots import _bode, _lean_import, plot

ALLOW_HELP = ("let the netlist include or read tables from files outside its own folder tree "
              "(refused by default: a netlist from someone else must not read your files)")


def _parse_sets(model, items: list[str]) -> dict[str, float]:
    """``NAME=VALUE`` pairs -> SI floats, units checked against the parameter."""
    from circuitsim.netlist.load import typed_value
    from circuitsim.units import unit_info

    out: dict[str, float] = {}
    comp_units = {n: v.unit for c in model.netlist.components for n, v in c.values.items()}
    for item in items:
        if "=" not in item:
            raise ParameterError(f"--set takes NAME=VALUE, got '{item}'")
        name, text = (s.strip() for s in item.split("=", 1))
        if name in model.netlist.parameters:
            target, unit = model.netlist.parameters[name].dim, None  # named by its dimension
        else:
            unit = comp_units.get(name)
            target = unit_info(unit)[1] if unit and unit != "1" else None
        try:
            value = typed_value(text, target, unit)
        except ValueError as exc:
            raise ParameterError(f"--set {name}: {exc}") from None
        out[name] = value
    return out


def summarize(res, window: float) -> dict:
    """Mean, final value and ripple of each probe over the last ``window`` of the run.

    A ripple is reported only for a periodic steady state with a significant spectral line
    (``signal.ripple_summary``); otherwise its state says 'settling' or 'none' (a significant
    line of a transient, such as a decaying ring, is still given for information).
    """
    from circuitsim import signal
    from circuitsim.solve.alias import Aliasing

    out = {}
    m = res.window(window)
    aliasing = Aliasing(res, window)
    for name in res.probes:
        x = res[name]
        entry = {"mean": float(x[m].mean()), "final": float(x[-1]),
                 "unit": res.model.meta["units"].get(name, "")}
        try:
            r = signal.ripple_summary(res.t[m], x[m])
            entry["mean"] = r.mean
            entry["ripple"] = {"state": r.state, "frequency": r.frequency,
                               "amplitude": r.amplitude, "p_value": r.p_value}
            alias = aliasing.of(r.frequency) if r.state != "none" else None
            if alias is not None:  # the grid's line is not the circuit's: never its number
                entry["ripple"].update(state="aliased", frequency=alias.true,
                                       seen=alias.seen, order=alias.order,
                                       shaft=alias.shaft, words=alias.words())
        except ValueError:  # too few samples in the window to say anything
            entry["ripple"] = {"state": "too few points", "points": int(m.sum()),
                               "frequency": 0.0, "amplitude": 0.0, "p_value": 1.0}
        out[name] = entry
    return out


def _ripple_text(e: dict) -> str:
    r, u = e["ripple"], e["unit"]
    if r["state"] == "periodic":
        return f"{r['frequency']:.6g} Hz, {_fmt(r['amplitude'], u)} peak"
    if r["state"] == "aliased":
        return (f"aliased: order {r['order']} of {r['shaft']} at {r['frequency']:.6g} Hz, seen "
                f"at {r['seen']:.6g} Hz on the output grid (lower the step)")
    if r["state"] == "too few points":  # not 'no ripple': nothing could be seen
        return f"{r['points']} output point(s) in the window: too few to judge (lower the step)"
    return "settling" if r["state"] == "settling" else "no periodic ripple"


def _run_outputs(args, net) -> dict[str, str]:
    """The files ``run`` will write, checked before the run (never an input, never a folder)."""
    if args.no_files:
        return {}
    stem = Path(args.netlist).stem
    files = {"csv": args.out or f"{stem}.csv", "plot": args.plot or f"{stem}.png"}
    for kind, path in files.items():
        check_output(path, net.inputs, "--out" if kind == "csv" else "--plot")
    return files


def _check_names(model, names: list[str]) -> list[str]:
    known = {*model.probe_names, *model.meta["observed"], *model.state_names}
    for n in names:
        if n not in known:
            import difflib

            close = difflib.get_close_matches(n, sorted(known), n=3)
            raise ParameterError(f"--probe {n}: no such probe or variable" +
                                 (f" (did you mean {', '.join(close)}?)" if close else
                                  f"; probes: {', '.join(model.probe_names)}"))
    return names


def write_run_csv(res, path: str, names: list[str], after: float = 0.0,
                  decimate: int = 1, units: bool = True) -> None:
    """Time and the named series, atomically; only the points at or after ``after`` [s],
    every ``decimate``-th of them. ``units``: the header says them (``v_out [V]``; the
    record reader checks them against the probes, the table reader drops them)."""
    import numpy as np

    keep = np.flatnonzero(res.t >= after)[::decimate]
    header = res.csv_header(names, units)
    data = np.column_stack([res.t[keep]] + [res[n][keep] for n in names])

    def write(tmp: str) -> None:
        with open(tmp, "w", encoding="utf-8") as fh:
            fh.write(",".join(header) + "\n")
            np.savetxt(fh, data, delimiter=",", fmt="%.12g")

    atomic_write(path, write)


def _simulate(model, args, overrides: dict[str, float]):
    from circuitsim.cli.progress import time_bar
    from circuitsim.netlist.load import MAX_OUTPUT_POINTS, output_points, too_many_points

    stop = args.stop if args.stop is not None else model.netlist.analysis.stop
    step = args.step if args.step is not None else model.netlist.analysis.step
    if step is not None and not 0 < step <= stop:
        raise ParameterError(f"{args.netlist}: --step {step:g} s must be positive and at most "
                             f"the stop time {stop:g} s")
    points = output_points(stop, step)
    if points > MAX_OUTPUT_POINTS:
        raise ParameterError(f"{args.netlist}: {too_many_points(points)}")
    # points before --after are not written: do not keep them in memory either, except the
    # first and the whole steady window (the summary needs every point of it)
    if args.after > stop:  # the CSV would hold its header alone, written as a success
        raise ParameterError(f"{args.netlist}: --after {args.after:g} s is after the "
                             f"stop time {stop:g} s, so no row would be written; give an "
                             f"earlier --after or a later --stop")
    opts = {}
    if args.after > 0:
        opts = {"keep_after": min(args.after, stop * (1 - args.window)), "decimate": 1 << 62}
    with time_bar(stop, quiet=args.quiet or args.json) as bar:
        return model.simulate(stop=args.stop, step=args.step, params=overrides, progress=bar,
                              **opts)


def cmd_run(args) -> int:
    from circuitsim.compiler.model import compile as compile_model
    from circuitsim.netlist.load import load

    net = load(args.netlist, allow_outside=args.allow_outside)
    files = _run_outputs(args, net)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        model = compile_model(net)
    overrides = _parse_sets(model, args.set or [])
    if overrides:
        model.param_values(overrides)  # validate before integrating
    names = _check_names(model, _split_names(args.probe)) or \
        list(model.probe_names or model.state_names)
    msgs = [str(w.message) for w in caught] + \
        ([] if not overrides else [w for w in model.physics_warnings(
            model.param_values(overrides)) if w not in model.warnings])
    if not args.json:
        for w in msgs:
            print(f"warning: {w}", file=sys.stderr)
    res = _simulate(model, args, overrides)
    if res.t.size and files:
        write_run_csv(res, files["csv"], names, args.after, args.decimate, args.header_units)
        _lean_import()  # a process that ends here needs no artist docstrings
        plot(res, files["plot"], names=names, window=args.window)
    else:
        files = {}
    if not res.success:
        print(f"error: {net.path}: simulation failed {res.message}", file=sys.stderr)
        if args.json:
            print(json.dumps({"success": False, "message": res.message, "files": files}))
        return 1
    summary = summarize(res, args.window)
    said = set()
    for name, e in summary.items():
        words = e["ripple"].get("words")
        if words and words not in said:
            said.add(words)
            msgs.append(f"{name}: its ripple on the output grid is {words}")
            if not args.json:
                print(f"warning: {msgs[-1]}", file=sys.stderr)
    _print_run(args, net, res, summary, msgs, files)
    return 0


def _print_run(args, net, res, summary: dict, msgs: list[str], files: dict) -> None:
    if args.json:
        print(json.dumps({"netlist": args.netlist, "success": True, "stop": float(res.t[-1]),
                          "window": args.window, "probes": summary, "warnings": msgs,
                          "files": files, "stats": {"nfev": res.nfev, "njev": res.njev,
                                                    "points": int(res.t.size)}}, indent=1))
        return
    print(f"{net.title}: {res.t[-1]:g} s simulated, {res.nfev} residual calls; "
          f"steady window = last {args.window:.0%}")
    print(f"{'probe':<14}{'mean':>20}{'final':>20}   ripple")
    for name, e in summary.items():
        u = e["unit"]
        print(f"{name:<14}{_fmt(e['mean'], u):>20}{_fmt(e['final'], u):>20}   "
              f"{_ripple_text(e)}")
    for kind, f in files.items():
        print(f"{kind}: {f}")


def _split_names(items: list[str] | None) -> list[str]:
    """``--probe a --probe b,c`` -> [a, b, c]."""
    return [s.strip() for item in items or [] for s in item.split(",") if s.strip()]


def _fmt(x: float, unit: str) -> str:
    return f"{x:.7g} {unit}".strip() if math.isfinite(x) else str(x)


def cmd_check(args) -> int:
    from circuitsim.compiler.model import CompiledModel, derive
    from circuitsim.netlist.load import load

    net = load(args.netlist, allow_outside=args.allow_outside)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        cg, dae, idx = derive(net)
    print(f"{net.path}: {net.title}")
    print(cg.summary())
    print(f"MNA DAE: {len(dae.equations)} equations, {len(dae.unknowns)} unknowns, "
          f"{len(dae.differentiated())} differentiated")
    for line in idx.report:
        print(f"  {line}")
    print(f"index-1 system: {len(idx.states)} unknowns ({idx.n_diff} differential: "
          f"{', '.join(s.name for s in idx.states[:idx.n_diff])}; "
          f"{len(idx.states) - idx.n_diff} algebraic)")
    print("parameters: " + ", ".join(f"{k} = {p.value:g}" for k, p in net.parameters.items()))
    print("probes: " + ", ".join(f"{k} = {p.text}" for k, p in net.probes.items()))
    probe = CompiledModel(net, "", {"params": [p.name for p in dae.params]})
    for w in [str(c.message) for c in caught] + probe.physics_warnings(probe.param_values()):
        print(f"warning: {w}")
    print("ok")
    return 0


def cmd_equations(args) -> int:
    from circuitsim.compiler.model import derive
    from circuitsim.netlist.load import load

    net = load(args.netlist, allow_outside=args.allow_outside)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        _, dae, idx = derive(net)
    if args.reduced:
        print(idx.pretty(latex=args.latex))
    else:
        print(dae.pretty(latex=args.latex))
    return 0


def component_table(markdown: bool = False) -> str:
    """The component registry as a table (type, ports, parameters, summary)."""
    import circuitsim_components  # noqa: F401
    from circuitsim.component import COMPONENTS, Expression, Option, Param, RecordList, Signal

    rows = []
    seen = set()
    for _name, cls in sorted(COMPONENTS.items()):
        if cls in seen:
            continue
        seen.add(cls)
        ports = ", ".join(f"{p.name} ({p.domain.name[:4]})" for p in cls.ports)
        params = []
        for k, d in cls.declared().items():
            if isinstance(d, (Param, Signal)):
                params.append(f"{k} [{d.unit}]")
            elif isinstance(d, Expression):
                params.append(f"{k}: expression [{d.unit}]")
            elif isinstance(d, RecordList):
                params.append(f"{k}: list of {{{', '.join(d.fields)}}}")
            elif isinstance(d, Option):
                params.append(f"{k}: {'/'.join(map(str, d.choices))}")
        doc = (cls.__doc__ or "").strip().splitlines()[0]
        rows.append((" / ".join(f"`{n}`" if markdown else n for n in cls.type_names), ports,
                     "; ".join(params), doc))
    if markdown:
        lines = ["| type | ports | parameters | model |", "|---|---|---|---|"]
        lines += [f"| {a} | {b} | {c} | {d} |" for a, b, c, d in rows]
        return "\n".join(lines)
    return "\n".join(f"{a:<20} {b:<40} {c}\n{'':<20} {d}" for a, b, c, d in rows)


#: What the table cannot say about the parameters it lists as expressions and waveforms.
COMPONENTS_NOTE = """
Expressions (BV, BI, btorque, bforce; m of pwm_leg, half_bridge): t, parameters, NODE.v, SHAFT.w,
COMP.i, ...; + - * / ^, sin cos tan exp log sqrt atan tanh, abs sign min max clamp,
< <= > >= == !=, if(cond, then, else), smooth_abs(x, eps), smooth_sign(x, eps).
A relation (< <= > >=, also inside abs, sign, min, max, clamp, if) of t or of a circuit
quantity switches by events: held between them, flipped at the root IDA finds, restarted
consistently (SimResult.t_events). smooth_abs and smooth_sign never switch.
Waveforms: every corner is a breakpoint; a table source's rows are stops of the integrator."""


def cmd_components(args) -> int:
    print(component_table(markdown=args.markdown))
    if not args.markdown:
        print(COMPONENTS_NOTE)
    return 0


def _sweep_grid(first, items: list[str]) -> dict[str, list[float]]:
    from circuitsim.studies.sweep import parse_range

    units = {n: v.unit for c in first.components for n, v in c.values.items()}
    grid: dict[str, list[float]] = {}
    for item in items:
        if "=" not in item:
            raise ParameterError(f"--set takes NAME=RANGE (e.g. Lf=1e-9..1e-1:log:9), "
                                 f"got '{item}'")
        name, text = (x.strip() for x in item.split("=", 1))
        if name in grid:  # a later --set would silently replace the earlier axis
            raise ParameterError(f"--set {name} is given twice; sweep each parameter on one "
                                 f"axis (a list as 1,2,5 or a range as 1..10:lin:5)")
        gp = first.parameters.get(name)
        grid[name] = parse_range(text, unit=None if gp else units.get(name),
                                 dim=gp.dim if gp else None)
    return grid


def cmd_sweep(args) -> int:
    from circuitsim.cli.progress import count_bar
    from circuitsim.netlist.load import MAX_OUTPUT_POINTS, load, output_points, too_many_points
    from circuitsim.studies.sweep import Metrics, sweep

    nets = [load(n, allow_outside=args.allow_outside) for n in args.netlists]
    first = nets[0]
    for net in nets:
        points = output_points(args.stop or net.analysis.stop, net.analysis.step)
        if points > MAX_OUTPUT_POINTS:
            raise ParameterError(f"{net.path}: {too_many_points(points)}")
    inputs = [i for n in nets for i in n.inputs]
    for path, what in ((args.out, "--out"), (args.plot, "--plot")):
        if path:
            check_output(path, inputs, what)
    grid = _sweep_grid(first, args.set or [])
    probes = _split_names(args.probe)
    metrics = Metrics(probes=tuple(probes) if probes else None, order=args.order,
                      window=args.window, energy=not args.no_energy)
    with count_bar(0, "sweep", quiet=args.quiet) as bar:
        rows = sweep(args.netlists, grid, mode="zip" if args.zip else "product",
                     metrics=metrics, stop=args.stop, jobs=args.jobs, out=args.out,
                     resume=args.resume, progress=bar,
                     allow_outside=args.allow_outside)
    failed = [r for r in rows if r.get("status") != "ok"]
    print(f"{len(rows)} runs, {len(failed)} failed" + (f"; table: {args.out}" if args.out
                                                          else ""), file=sys.stderr)
    if args.plot:
        _sweep_plot(args, rows, grid, probes)
    if not args.out:
        keys = list(dict.fromkeys(k for r in rows for k in r))
        print(",".join(keys))
        for r in rows:
            print(",".join(str(r.get(k, "")) for k in keys))
    # a failed run is data the table keeps, but the sweep is not finished: exit 1 (a resume
    # retries those runs)
    return 1 if failed else 0


def _sweep_plot(args, rows: list[dict], grid: dict, probes: list[str]) -> None:
    from circuitsim.report.plots import plot_sweep

    swept = [k for k, v in grid.items() if len(v) > 1]
    metric = args.metric
    if metric is None:
        probe = (probes or [None])[0] or next(
            (k[:-len(".ripple_amp")] for k in rows[0] if k.endswith(".ripple_amp")), None)
        metric = f"{probe}.ripple_amp" if probe else None
    if metric and rows and all(metric not in r for r in rows):
        columns = ", ".join(k for k in rows[0] if k not in ("netlist", "message"))
        raise ParameterError(f"--metric {metric}: the table has no such column (the table is "
                             f"kept, no plot drawn); columns: {columns}")
    if swept and metric:
        plot_sweep(rows, swept[0], metric, args.plot)
        print(f"plot: {args.plot}", file=sys.stderr)


def _load_model(path: str, allow_outside: bool = False):
    from circuitsim.compiler.model import compile as compile_model
    from circuitsim.netlist.load import load

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return compile_model(load(path, allow_outside=allow_outside))


def _freqs(text: str, points: int) -> list[float]:
    from circuitsim.studies.sweep import parse_range

    if ".." in text and ":" not in text:
        text = f"{text}:log:{points}"
    return parse_range(text, unit="Hz")


def cmd_op(args) -> int:
    from circuitsim.solve.op import operating_point, probe_values
    from circuitsim.solve.watch import huge_parameters

    model = _load_model(args.netlist, args.allow_outside)
    params = _parse_sets(model, args.set or [])
    op = operating_point(model, params, t=args.time)
    probes = probe_values(model, op, params, t=args.time)
    bad = [k for k, v in probes.items() if not math.isfinite(v)]
    if bad:
        # a parameter beyond any physical value overflows a probe (V i at V = 1e301) whether
        # or not Newton converged: name it, not the expression
        huge = huge_parameters(model, model.frozen_vector(params))
        raise SolverError(f"operating point: probe '{bad[0]}' is {probes[bad[0]]}" + (
            huge or ": its expression has no real value at the operating point (a division "
            "by zero, a negative number to a fractional power); guard it, e.g. with "
            "max(..., small)"))
    if args.json:
        print(json.dumps({"states": dict(zip(op.names, op.y.tolist(), strict=True)),
                          "rates": {n: float(r) for n, r in zip(op.names, op.yp, strict=True)
                                    if r}, "probes": probes, "iterations": op.iterations},
                         indent=1))
        return 0
    print(f"operating point of {model.netlist.title} at t = {args.time:g} s ({op.iterations} "
          f"Newton steps; shaft ripple averaged over a turn)")
    for name, v in probes.items():
        print(f"  {name:<16}{_fmt(v, model.meta['units'].get(name, '')):>22}")
    for name, y, r in zip(op.names, op.y, op.yp, strict=True):
        extra = f"   (d/dt = {r:.8g})" if r else ""
        print(f"  [{name}]{'':<4}{y:>22.10g}{extra}")
    return 0


def cmd_ac(args) -> int:
    from circuitsim.solve.ac import ac, harmonic_response, linearize

    model = _load_model(args.netlist, args.allow_outside)
    if args.plot:
        check_output(args.plot, model.netlist.inputs, "--plot")
    params = _parse_sets(model, args.set or [])
    lin = linearize(model, params)
    if args.order is not None:
        if args.order < 1:
            raise ParameterError(f"--order {args.order}: the shaft harmonic's order is a whole "
                                 f"number >= 1 (per revolution)")
        try:
            h = harmonic_response(model, args.order, args.output, params, lin=lin)
        except ValueError as exc:
            raise ParameterError(f"ac --order: {exc}") from None
        if args.json:
            print(json.dumps({"order": h.order, "frequency": h.frequency,
                              "amplitude": h.amplitude, "phase": h.phase}))
        else:
            print(f"order-{h.order:g} response of {args.output}: {h.amplitude:.7g} at "
                  f"{h.frequency:.6g} Hz (phase {h.phase:.4f} rad)")
        return 0
    if not args.input:
        raise ParameterError("ac needs --input SOURCE (or --order K for a shaft harmonic)")
    try:
        res = ac(model, args.input, args.output, _freqs(args.f, args.points), params, lin=lin)
    except ValueError as exc:
        raise ParameterError(str(exc)) from None
    if args.plot:
        _bode(res, args.plot)
    if args.json:
        print(json.dumps(res.as_dict()))
        return 0
    print(f"{'f [Hz]':>14}{'|H|':>16}{'phase [deg]':>14}")
    for f, m, ph in zip(res.frequency, res.magnitude, res.phase, strict=True):
        print(f"{f:>14.6g}{m:>16.8g}{ph:>14.4f}")
    return 0


def cmd_pss(args) -> int:
    from circuitsim.solve.pss import periodic_steady_state

    model = _load_model(args.netlist, args.allow_outside)
    params = _parse_sets(model, args.set or [])
    if args.period is None and not model.shafts:
        raise ParameterError(f"{args.netlist}: pss of a circuit without a shaft needs the "
                             f"period of its driving source: add --period (e.g. --period 1ms)")
    try:
        ps = periodic_steady_state(model, params, order=args.order, period=args.period)
    except ValueError as exc:
        raise ParameterError(f"pss: {exc}") from None
    out = {"period": ps.period, "frequency": 1 / ps.period, "iterations": ps.iterations,
           "probes": {}}
    for name in model.probe_names:
        x = ps[name]
        f, amp, ph = ps.harmonic(name, 1)
        out["probes"][name] = {"mean": float(x.mean()), "min": float(x.min()),
                               "max": float(x.max()),
                               "fundamental": {"frequency": f, "amplitude": amp, "phase": ph}}
    if args.json:
        print(json.dumps(out, indent=1))
        return 0
    print(f"periodic steady state: period {ps.period:.9g} s ({1 / ps.period:.8g} Hz), "
          f"{ps.iterations} Newton steps")
    for name, e in out["probes"].items():
        u = model.meta["units"].get(name, "")
        print(f"  {name:<14} mean {_fmt(e['mean'], u):>18}   fundamental "
              f"{_fmt(e['fundamental']['amplitude'], u):>16}")
    return 0


def _add_run(sub) -> None:
    r = sub.add_parser("run", help="transient simulation; summary, CSV and PNG",
                       description="Integrate the netlist from rest, print each probe's mean, "
                       "final value and ripple over the steady window, write a CSV (units in "
                       "the header) and a PNG.")
    r.add_argument("netlist", help="netlist YAML file")
    r.add_argument("--allow-outside", action="store_true", help=ALLOW_HELP)
    r.add_argument("--set", action="append", metavar="NAME=VALUE",
                   help="override a parameter (units or SPICE suffixes: --set La=0.9mH, R=2k)")
    r.add_argument("--stop", type=quantity("s"), help="stop time (e.g. 0.1, 10ms)")
    r.add_argument("--step", type=quantity("s"),
                   help="output step (e.g. 10us; default: the netlist's analysis step): the "
                        "grid the CSV, the plot and the summary read")
    r.add_argument("--out", help="CSV file (default: NETLIST_STEM.csv; folders are created)")
    r.add_argument("--plot", help="PNG file (default: NETLIST_STEM.png)")
    r.add_argument("--no-files", action="store_true", help="write no CSV or PNG")
    r.add_argument("--probe", "--probes", action="append", metavar="NAME[,NAME]",
                   help="series to write and plot: probes or any variable (default: all probes)")
    r.add_argument("--after", type=quantity("s", inclusive=True), default=0.0,
                   help="write only the points at or after this time (e.g. 0.8s); also "
                        "keeps the earlier points out of memory")
    r.add_argument("--decimate", type=int, default=1, metavar="N",
                   help="write every N-th point (the summary uses all of them)")
    r.add_argument("--header-units", action=argparse.BooleanOptionalAction, default=True,
                   help="units in the CSV header, 'time [s]', 'v_out [V]' (default; fit and "
                        "diagnose read them); --no-header-units writes the names alone")
    r.add_argument("--json", action="store_true", help="print one JSON object")
    r.add_argument("--quiet", action="store_true", help="no progress bar")
    r.add_argument("--window", type=float, default=0.2,
                   help="steady window as a fraction of the run (default 0.2)")
    r.set_defaults(func=cmd_run)


def _add_sweep(sub) -> None:
    w = sub.add_parser("sweep", help="parameter/topology sweep into a table")
    w.add_argument("netlists", nargs="+", help="netlist YAML files (one topology each)")
    w.add_argument("--allow-outside", action="store_true", help=ALLOW_HELP)
    w.add_argument("--set", action="append", metavar="NAME=RANGE",
                   help="sweep axis: 1e-9..1e-1:log:9, 0..1:lin:5, or 1,2,5 (units and SPICE "
                        "suffixes allowed: 1k..100k:log:5)")
    w.add_argument("--zip", action="store_true", help="combine axes element-wise, not as a "
                   "Cartesian product")
    w.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                   help="local worker processes (default: all cores)")
    w.add_argument("--out", help="CSV table; rows are appended as runs finish")
    w.add_argument("--resume", action="store_true", help="skip runs already done in --out; "
                   "retry the failed ones")
    w.add_argument("--plot", help="PNG of a metric against the first swept parameter")
    w.add_argument("--metric", help="column to plot (default: PROBE.ripple_amp)")
    w.add_argument("--probe", "--probes", action="append", metavar="NAME[,NAME]",
                   help="probe(s) to report (default: all)")
    w.add_argument("--order", type=quantity("1"), help="ripple order per shaft revolution "
                   "(default: the dominant ripple)")
    w.add_argument("--stop", type=quantity("s"), help="stop time (e.g. 0.1, 10ms)")
    w.add_argument("--window", type=float, default=0.2,
                   help="steady window as a fraction of each run (default 0.2)")
    w.add_argument("--no-energy", action="store_true", help="skip the energy audit columns")
    w.add_argument("--quiet", action="store_true", help="no progress bar")
    w.set_defaults(func=cmd_sweep)


def _add_analyses(sub) -> None:
    o = sub.add_parser("op", help="DC operating point (rotating machines: averaged model)")
    o.add_argument("netlist", help="netlist YAML file")
    o.add_argument("--allow-outside", action="store_true", help=ALLOW_HELP)
    o.add_argument("--time", type=quantity("s", inclusive=True), default=0.0,
                   help="time at which the sources are taken (e.g. after a load step: 0.3s)")
    o.add_argument("--set", action="append", metavar="NAME=VALUE", help="override a parameter")
    o.add_argument("--json", action="store_true", help="print one JSON object")
    o.set_defaults(func=cmd_op)
    a = sub.add_parser("ac", help="small-signal transfer function around the operating point")
    a.add_argument("netlist", help="netlist YAML file")
    a.add_argument("--allow-outside", action="store_true", help=ALLOW_HELP)
    a.add_argument("--input", help="source component or parameter (e.g. Vin, M.e0)")
    a.add_argument("--output", required=True, help="probe or variable")
    a.add_argument("--f", default="10..100e3", help="frequencies [Hz]: 10..100k, 10Hz..1kHz, "
                   "or a list 50,60")
    a.add_argument("--points", type=int, default=50, help="points of a log range")
    a.add_argument("--order", type=int, help="instead of --input: the response to the order-K "
                   "harmonic of the shaft angle in the circuit's equations (back-EMF ripple)")
    a.add_argument("--set", action="append", metavar="NAME=VALUE", help="override a parameter")
    a.add_argument("--plot", help="Bode plot PNG (magnitude in dB, unwrapped phase)")
    a.add_argument("--json", action="store_true", help="print one JSON object")
    a.set_defaults(func=cmd_ac)
    q = sub.add_parser("pss", help="periodic steady state by shooting")
    q.add_argument("netlist", help="netlist YAML file")
    q.add_argument("--allow-outside", action="store_true", help=ALLOW_HELP)
    q.add_argument("--order", type=quantity("1"), default=1.0,
                   help="rotating circuits: the period is 1/ORDER of a shaft turn (default 1)")
    q.add_argument("--period", type=quantity("s"),
                   help="driven circuits: the source period (e.g. 1ms, 20e-3)")
    q.add_argument("--set", action="append", metavar="NAME=VALUE", help="override a parameter")
    q.add_argument("--json", action="store_true", help="print one JSON object")
    q.set_defaults(func=cmd_pss)


def _add_inspection(sub) -> None:
    c = sub.add_parser("check", help="validate; show the graph and equation counts")
    c.add_argument("netlist", help="netlist YAML file")
    c.add_argument("--allow-outside", action="store_true", help=ALLOW_HELP)
    c.set_defaults(func=cmd_check)
    e = sub.add_parser("equations", help="print the DAE F(t, x, x', p) = 0")
    e.add_argument("netlist", help="netlist YAML file")
    e.add_argument("--allow-outside", action="store_true", help=ALLOW_HELP)
    e.add_argument("--latex", action="store_true", help="LaTeX instead of text")
    e.add_argument("--reduced", action="store_true", help="the index-1 form handed to IDA")
    e.set_defaults(func=cmd_equations)
    k = sub.add_parser("components", help="list the component library")
    k.add_argument("--markdown", action="store_true", help="a Markdown table (as in README)")
    k.set_defaults(func=cmd_components)


# Verbs whose parser needs none of the study modules below
CORE_VERBS = frozenset({"run", "sweep", "op", "ac", "pss", "check", "equations", "components"})


def build_parser(argv: list[str] | None = None) -> argparse.ArgumentParser:
    """The whole command line; for ``argv`` naming a core verb, without the study verbs
    (fit, diagnose, identify), whose modules take ~50 ms to import and that argv cannot
    reach (help and error messages that list every verb get the whole parser)."""
    import circuitsim

    ap = argparse.ArgumentParser(
        prog="circuitsim", description="Acausal circuit-network simulator for "
        "electromechanical systems: a YAML netlist in; transients, operating points, AC, "
        "periodic steady states, sweeps, fits and diagnoses out. `circuitsim COMMAND -h` "
        "for a command's options.", epilog=__doc__.split("\n\n")[1].replace("\n", " "))
    ap.add_argument("--version", action="version", version=f"circuitsim {circuitsim.__version__}")
    sub = ap.add_subparsers(dest="command", required=True, metavar="COMMAND")
    _add_run(sub)
    _add_sweep(sub)
    _add_analyses(sub)
    # Studies that live in their own modules register their subcommands themselves
    # (each module keeps its top-level imports light: this runs on every CLI call).
    import importlib

    if not (argv and argv[0] in CORE_VERBS):
        for study in ("circuitsim.cli.fit", "circuitsim.cli.diagnose",
                      "circuitsim.cli.identify", "circuitsim.cli.cache"):
            importlib.import_module(study).add_cli(sub)
    _add_inspection(sub)
    return ap


def _terminate(signum: int, _frame) -> None:
    # SIGTERM ends like Ctrl-C: 'finally' clauses run, so no temporary file is left behind
    raise SystemExit(128 + signum)


def main(argv: list[str] | None = None) -> int:
    try:
        if threading_main():
            signal.signal(signal.SIGTERM, _terminate)
        argv = sys.argv[1:] if argv is None else argv
        args = build_parser(argv).parse_args(argv)
        window = getattr(args, "window", 0.2)
        if window is not None and not 0 < window <= 1:
            print("error: --window is a fraction in (0, 1]", file=sys.stderr)
            return 2
        for flag in ("decimate", "jobs"):
            if getattr(args, flag, 1) < 1:
                print(f"error: --{flag} is a whole number >= 1", file=sys.stderr)
                return 2
        return int(args.func(args))
    except CircuitsimError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return exc.exit_code
    except OSError as exc:
        if isinstance(exc, BrokenPipeError):  # output piped into `head`: not an error of ours
            sys.stderr.close()
            return 0
        print(f"error: {exc.filename or ''}: {exc.strerror or exc}".replace(": : ", ": "),
              file=sys.stderr)
        return 3
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    except RecursionError:
        print("error: the input is nested too deeply to read", file=sys.stderr)
        return 2


def threading_main() -> bool:
    """Signal handlers can only be installed from the main thread (tests call main() from
    others)."""
    import threading

    return threading.current_thread() is threading.main_thread()


if __name__ == "__main__":
    sys.exit(main())
