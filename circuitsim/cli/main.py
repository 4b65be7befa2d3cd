"""Command line: ``circuitsim run|check|equations|components``. A thin face over the API.

Exit codes: 0 success, 2 bad input (the message names file, line, component and the fix),
1 solver failure (the message names the simulated time and the variable).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import warnings
from pathlib import Path

from circuitsim.errors import CircuitsimError, ParameterError, SolverError
from circuitsim.report.plots import _bode, plot


def _parse_sets(model, items: list[str]) -> dict[str, float]:
    """``NAME=VALUE`` pairs -> SI floats, units checked against the parameter."""
    from circuitsim.netlist import expr as ex
    from circuitsim.units import compatible, explain_mismatch, unit_info

    out: dict[str, float] = {}
    comp_units = {n: v.unit for c in model.netlist.components for n, v in c.values.items()}
    for item in items:
        if "=" not in item:
            raise ParameterError(f"--set takes NAME=VALUE, got '{item}'")
        name, text = (s.strip() for s in item.split("=", 1))
        try:
            node = ex.parse(text)
            if ex.names(node):
                raise ex.ExprError("--set values may not name parameters", text, 0)
            value = ex.evaluate(node, {})
            dim = ex.dimension(node, {})
        except (ex.ExprError, ValueError, ZeroDivisionError) as exc:
            raise ParameterError(f"--set {name}: {exc}") from None
        if node.kind == "unit":
            if name in model.netlist.parameters:
                target = model.netlist.parameters[name].dim
                unit = str(target) if target else None
            else:
                unit = comp_units.get(name)
                target = unit_info(unit)[1] if unit and unit != "1" else None
            if target is not None and dim is not None and not compatible(dim, target):
                raise ParameterError(f"--set {name}: {explain_mismatch(dim, target, unit or '')}")
        out[name] = value
    return out


def summarize(res, window: float) -> dict:
    """Steady value and dominant ripple of each probe over the last ``window`` of the run."""
    from circuitsim import signal

    out = {}
    m = res.window(window)
    for name in res.probes:
        x = res[name]
        entry = {"mean": float(x[m].mean()), "final": float(x[-1]),
                 "unit": res.model.meta["units"].get(name, "")}
        try:
            h = signal.dominant_ripple(res.t[m], x[m])
            if h.amplitude > 0:
                # the fit's offset is the mean free of a partial ripple period
                entry["mean"] = float(h.offset)
            entry["ripple"] = {"frequency": float(h.frequency), "amplitude": float(h.amplitude)}
        except ValueError:
            entry["ripple"] = {"frequency": 0.0, "amplitude": 0.0}
        out[name] = entry
    return out


def cmd_run(args) -> int:
    from circuitsim.compiler.model import compile as compile_model
    from circuitsim.netlist.load import load

    net = load(args.netlist)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        model = compile_model(net)
    overrides = _parse_sets(model, args.set or [])
    if overrides:
        model.param_values(overrides)  # validate before integrating
    msgs = [str(w.message) for w in caught] + \
        ([] if not overrides else [w for w in model.physics_warnings(
            model.param_values(overrides)) if w not in model.warnings])
    if not args.json:
        for w in msgs:
            print(f"warning: {w}", file=sys.stderr)
    res = model.simulate(stop=args.stop, params=overrides)
    stem = Path(args.netlist).stem
    files = {}
    if res.t.size and not args.no_files:
        csv = args.out or f"{stem}.csv"
        res.to_csv(csv)
        files["csv"] = csv
        png = args.plot or f"{stem}.png"
        plot(res, png)
        files["plot"] = png
    if not res.success:
        print(f"error: {net.path}: simulation failed {res.message}", file=sys.stderr)
        if args.json:
            print(json.dumps({"success": False, "message": res.message, "files": files}))
        return 1
    summary = summarize(res, args.window)
    if args.json:
        print(json.dumps({"netlist": args.netlist, "success": True, "stop": float(res.t[-1]),
                          "window": args.window, "probes": summary, "warnings": msgs,
                          "files": files, "stats": {"nfev": res.nfev, "njev": res.njev,
                                                    "points": int(res.t.size)}}, indent=1))
        return 0
    print(f"{net.title}: {res.t[-1]:g} s simulated, {res.nfev} residual calls; "
          f"steady window = last {args.window:.0%}")
    print(f"{'probe':<14}{'mean':>20}{'final':>20}{'ripple freq':>16}{'ripple amplitude':>20}")
    for name, e in summary.items():
        u = e["unit"]
        print(f"{name:<14}{_fmt(e['mean'], u):>20}{_fmt(e['final'], u):>20}"
              f"{e['ripple']['frequency']:>13.7g} Hz{_fmt(e['ripple']['amplitude'], u):>20}")
    for kind, f in files.items():
        print(f"{kind}: {f}")
    return 0


def _fmt(x: float, unit: str) -> str:
    return f"{x:.7g} {unit}".strip() if math.isfinite(x) else str(x)


def cmd_check(args) -> int:
    from circuitsim.compiler.model import CompiledModel, derive
    from circuitsim.netlist.load import load

    net = load(args.netlist)
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

    net = load(args.netlist)
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


def cmd_components(args) -> int:
    print(component_table(markdown=args.markdown))
    return 0


def cmd_sweep(args) -> int:
    from circuitsim.netlist.load import load
    from circuitsim.report.plots import plot_sweep
    from circuitsim.studies.sweep import Metrics, parse_range, progress_bar, sweep

    first = load(args.netlists[0])
    units = {n: v.unit for c in first.components for n, v in c.values.items()}
    grid: dict[str, list[float]] = {}
    for item in args.set or []:
        if "=" not in item:
            raise ParameterError(f"--set takes NAME=RANGE (e.g. Lf=1e-9..1e-1:log:9), "
                                 f"got '{item}'")
        name, text = (x.strip() for x in item.split("=", 1))
        gp = first.parameters.get(name)
        grid[name] = parse_range(text, unit=None if gp else units.get(name),
                                 dim=gp.dim if gp else None)
    metrics = Metrics(probes=tuple(args.probe) if args.probe else None, order=args.order,
                      window=args.window, energy=not args.no_energy)
    rows = sweep(args.netlists, grid, mode="zip" if args.zip else "product", metrics=metrics,
                 stop=args.stop, jobs=args.jobs, out=args.out, resume=args.resume,
                 progress=None if args.quiet else progress_bar())
    failed = [r for r in rows if r.get("status") != "ok"]
    print(f"{len(rows)} runs, {len(failed)} failed" + (f"; table: {args.out}" if args.out
                                                          else ""))
    if args.plot:
        swept = [k for k, v in grid.items() if len(v) > 1]
        probe = (args.probe or [None])[0] or next(
            (k[:-len(".ripple_amp")] for k in rows[0] if k.endswith(".ripple_amp")), None)
        if swept and probe:
            plot_sweep(rows, swept[0], f"{probe}.ripple_amp", args.plot)
            print(f"plot: {args.plot}")
    if not args.out:
        keys = list(dict.fromkeys(k for r in rows for k in r))
        print(",".join(keys))
        for r in rows:
            print(",".join(str(r.get(k, "")) for k in keys))
    return 1 if failed and len(failed) == len(rows) else 0


def _load_model(path: str):
    from circuitsim.compiler.model import compile as compile_model
    from circuitsim.netlist.load import load

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return compile_model(load(path))


def _freqs(text: str, points: int) -> list[float]:
    from circuitsim.studies.sweep import parse_range

    if ".." in text and ":" not in text:
        text = f"{text}:log:{points}"
    return parse_range(text, unit="Hz")


def cmd_op(args) -> int:
    from circuitsim.solve.op import operating_point, probe_values

    model = _load_model(args.netlist)
    params = _parse_sets(model, args.set or [])
    op = operating_point(model, params)
    probes = probe_values(model, op, params)
    bad = [k for k, v in probes.items() if not math.isfinite(v)]
    if bad:
        raise SolverError(f"operating point: probe '{bad[0]}' is {probes[bad[0]]}: its "
                          f"expression has no real value at the operating point (a division "
                          f"by zero, a negative number to a fractional power); guard it, e.g. "
                          f"with max(..., small)")
    if args.json:
        print(json.dumps({"states": dict(zip(op.names, op.y.tolist(), strict=True)),
                          "rates": {n: float(r) for n, r in zip(op.names, op.yp, strict=True)
                                    if r}, "probes": probes, "iterations": op.iterations},
                         indent=1))
        return 0
    print(f"operating point of {model.netlist.title} ({op.iterations} Newton steps; shaft "
          f"ripple averaged over a turn)")
    for name, v in probes.items():
        print(f"  {name:<16}{_fmt(v, model.meta['units'].get(name, '')):>22}")
    for name, y, r in zip(op.names, op.y, op.yp, strict=True):
        extra = f"   (d/dt = {r:.8g})" if r else ""
        print(f"  [{name}]{'':<4}{y:>22.10g}{extra}")
    return 0


def cmd_ac(args) -> int:
    from circuitsim.solve.ac import ac, harmonic_response, linearize

    model = _load_model(args.netlist)
    params = _parse_sets(model, args.set or [])
    lin = linearize(model, params)
    if args.order is not None:
        h = harmonic_response(model, args.order, args.output, params, lin=lin)
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

    model = _load_model(args.netlist)
    params = _parse_sets(model, args.set or [])
    ps = periodic_steady_state(model, params, order=args.order, period=args.period)
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


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="circuitsim", description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="transient simulation; summary, CSV and PNG")
    r.add_argument("netlist")
    r.add_argument("--set", action="append", metavar="NAME=VALUE",
                   help="override a parameter (units allowed: --set La=0.9mH)")
    r.add_argument("--stop", type=float, help="stop time [s]")
    r.add_argument("--out", help="CSV file (default: NETLIST_STEM.csv)")
    r.add_argument("--plot", help="PNG file (default: NETLIST_STEM.png)")
    r.add_argument("--no-files", action="store_true", help="write no CSV or PNG")
    r.add_argument("--json", action="store_true", help="print one JSON object")
    r.add_argument("--window", type=float, default=0.2,
                   help="steady window as a fraction of the run (default 0.2)")
    r.set_defaults(func=cmd_run)
    w = sub.add_parser("sweep", help="parameter/topology sweep into a table")
    w.add_argument("netlists", nargs="+")
    w.add_argument("--set", action="append", metavar="NAME=RANGE",
                   help="sweep axis: 1e-9..1e-1:log:9, 0..1:lin:5, or 1,2,5 (units allowed)")
    w.add_argument("--zip", action="store_true", help="combine axes element-wise, not as a "
                   "Cartesian product")
    w.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                   help="local worker processes (default: all cores)")
    w.add_argument("--out", help="CSV table; rows are appended as runs finish")
    w.add_argument("--resume", action="store_true", help="skip runs already in --out")
    w.add_argument("--plot", help="PNG of ripple amplitude against the first swept parameter")
    w.add_argument("--probe", action="append", help="probe(s) to report (default: all)")
    w.add_argument("--order", type=float, help="ripple order per shaft revolution "
                   "(default: the dominant ripple)")
    w.add_argument("--stop", type=float, help="stop time [s]")
    w.add_argument("--window", type=float, default=0.2)
    w.add_argument("--no-energy", action="store_true", help="skip the energy audit columns")
    w.add_argument("--quiet", action="store_true", help="no progress bar")
    w.set_defaults(func=cmd_sweep)
    o = sub.add_parser("op", help="DC operating point (rotating machines: averaged model)")
    o.add_argument("netlist")
    o.add_argument("--set", action="append", metavar="NAME=VALUE")
    o.add_argument("--json", action="store_true")
    o.set_defaults(func=cmd_op)
    a = sub.add_parser("ac", help="small-signal transfer function around the operating point")
    a.add_argument("netlist")
    a.add_argument("--input", help="source component or parameter (e.g. Vin, M.e0)")
    a.add_argument("--output", required=True, help="probe or variable")
    a.add_argument("--f", default="10..100e3", help="frequencies [Hz]: 10..100kHz, or a list")
    a.add_argument("--points", type=int, default=50, help="points of a log range")
    a.add_argument("--order", type=int, help="instead of --input: the response to the order-K "
                   "harmonic of the shaft angle in the circuit's equations (back-EMF ripple)")
    a.add_argument("--set", action="append", metavar="NAME=VALUE")
    a.add_argument("--plot", help="Bode plot PNG")
    a.add_argument("--json", action="store_true")
    a.set_defaults(func=cmd_ac)
    q = sub.add_parser("pss", help="periodic steady state by shooting")
    q.add_argument("netlist")
    q.add_argument("--order", type=float, default=1,
                   help="rotating circuits: the period is 1/ORDER of a shaft turn (default 1)")
    q.add_argument("--period", type=float, help="driven circuits: the source period [s]")
    q.add_argument("--set", action="append", metavar="NAME=VALUE")
    q.add_argument("--json", action="store_true")
    q.set_defaults(func=cmd_pss)
    # Studies that live in their own modules register their subcommands themselves
    # (each module keeps its top-level imports light: this runs on every CLI call).
    import importlib

    for study in ("circuitsim.cli.fit", "circuitsim.cli.diagnose", "circuitsim.cli.identify"):
        importlib.import_module(study).add_cli(sub)
    c = sub.add_parser("check", help="validate; show the graph and equation counts")
    c.add_argument("netlist")
    c.set_defaults(func=cmd_check)
    e = sub.add_parser("equations", help="print the DAE F(t, x, x', p) = 0")
    e.add_argument("netlist")
    e.add_argument("--latex", action="store_true")
    e.add_argument("--reduced", action="store_true", help="the index-1 form handed to IDA")
    e.set_defaults(func=cmd_equations)
    k = sub.add_parser("components", help="list the component library")
    k.add_argument("--markdown", action="store_true")
    k.set_defaults(func=cmd_components)
    return ap


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    if getattr(args, "window", 0.2) is not None and not 0 < getattr(args, "window", 0.2) <= 1:
        print("error: --window is a fraction in (0, 1]", file=sys.stderr)
        return 2
    try:
        return int(args.func(args))
    except CircuitsimError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return exc.exit_code
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:  # output piped into `head`: not an error of ours
        sys.stderr.close()
        return 0


if __name__ == "__main__":
    sys.exit(main())
