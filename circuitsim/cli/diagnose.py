"""``circuitsim diagnose``."""

from __future__ import annotations

import json
import sys
import warnings

from circuitsim.cli.argtypes import whole
from circuitsim.cli.fit import _rtol
from circuitsim.files import atomic_write, check_output
from circuitsim.loop.diagnose import diagnose, diagnose_features
from circuitsim.loop.diagnose.context import MAX_EFFECTS
from circuitsim.report.diagnosis import write_html


def _atomic_text(path: str, text: str) -> None:
    atomic_write(path, text, make_dirs=False)


def add_cli(sub) -> None:
    """Register ``circuitsim diagnose`` on an argparse subparsers action."""
    from circuitsim.cli.main import ALLOW_HELP

    d = sub.add_parser("diagnose", help="trace the residual against measured data to a "
                       "physical effect the model lacks")
    d.add_argument("netlist", help="netlist YAML file")
    d.add_argument("--allow-outside", action="store_true", help=ALLOW_HELP)
    d.add_argument("data", help="CSV record: time + one column per probe, SI or with the "
                   "unit in brackets ('time [s],i [A]')")
    d.add_argument("--free", default="", help="declared free parameters, comma-separated")
    d.add_argument("--probe", "--probes", dest="probes", action="append", metavar="NAME[,NAME]",
                   help="probe columns to use (default: all)")
    d.add_argument("--report", help="diag.json")
    d.add_argument("--html", help="diag.html with plots")
    d.add_argument("--write-netlist", help="the netlist with the effects added")
    d.add_argument("--time", default="time", help="name of the time column [s]")
    d.add_argument("--inputs", default="", help="other columns of the CSV that are not "
                   "probes (measured inputs, unused signals), comma-separated")
    d.add_argument("--max-effects", default=MAX_EFFECTS, type=whole(
                       0, hint=" (0: fit the declared model and describe its residual)"),
                   help=f"largest number of effects to add (default {MAX_EFFECTS})")
    d.add_argument("--set", action="append", metavar="NAME=VALUE",
                   help="override a parameter (units checked); for a declared free one, its "
                        "start value. The written netlist carries the value")
    d.add_argument("--full-record", action="store_true",
                   help="use every row, even of a long record sampled far faster than its "
                        "content needs (by default such a record is filtered and reduced to a "
                        "working resolution, and the report says how)")
    d.add_argument("--rtol", type=_rtol, default=1e-8,
                   help="record: the integrator's rtol in every fit (default 1e-8, at most "
                        "0.01); a looser one for a model that chatters on a switch's threshold")
    d.add_argument("--json", action="store_true", help="print the report (as --report) as JSON")
    d.add_argument("--quiet", action="store_true", help="no progress messages")
    d.set_defaults(func=cmd_diagnose)


def cmd_diagnose(args) -> int:
    from circuitsim.compiler.model import compile as compile_model
    from circuitsim.netlist.load import load

    net = load(args.netlist, allow_outside=args.allow_outside)
    for path, what in ((args.report, "--report"), (args.html, "--html"),
                       (args.write_netlist, "--write-netlist")):
        if path:
            check_output(path, (*net.inputs, args.data), what)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = compile_model(net)
    free = [s.strip() for s in args.free.split(",") if s.strip()]
    from circuitsim.cli.main import _parse_sets

    overrides = _parse_sets(model, args.set or [])
    with _progress(args) as say:
        diag = _run_diagnosis(args, net, model, free, overrides, say)
    if args.json:
        print(json.dumps(diag.as_dict(), indent=1))
    else:
        _print(diag)
    _write_outputs(args, net, diag)
    return 0


def _progress(args):
    """Messages on a terminal as a status line (tqdm), as plain lines on a pipe; none with
    --quiet or --json (stdout then holds only the JSON)."""
    import contextlib

    from circuitsim.cli.progress import enabled, status_line

    if args.quiet or args.json:
        return contextlib.nullcontext(None)
    if enabled():
        return status_line("diagnose")
    return contextlib.nullcontext(lambda m: print(f"  {m}", file=sys.stderr))


def _run_diagnosis(args, net, model, free, overrides, say):
    from circuitsim.cli.fit import check_columns
    from circuitsim.loop.record import load_record

    if str(args.data).endswith((".yaml", ".yml")):
        from circuitsim.loop.record import load_features

        feats = load_features(args.data)
        feats.check(model)
        return diagnose_features(net, feats, free, max_effects=args.max_effects,
                                 params=overrides, progress=say)
    inputs = [t.label.split(":")[-1] for c in net.components for t in c.tables]
    inputs += [s.strip() for s in args.inputs.split(",") if s.strip()]
    record = load_record(args.data, model.probe_names, inputs=inputs, time=args.time,
                         units=model.meta["units"])
    probes = [s.strip() for item in args.probes or [] for s in item.split(",") if s.strip()]
    check_columns(probes, record.names, args.data)
    return diagnose(net, record, free, probes=probes or None, max_effects=args.max_effects,
                    params=overrides, progress=say, reduce=not args.full_record,
                    rtol=args.rtol)


def _print(diag) -> None:
    if diag.reduction is not None and diag.reduction.reduced:
        print(diag.reduction.note())
    print(diag.summary())
    for a in diag.effects:
        print(f"  + {a.effect} on {a.target}: " + ", ".join(
            f"{k} = {v:.5g}" + (f" +- {a.stderr[k]:.2g}" if a.stderr.get(k) else "")
            for k, v in a.parameters.items()) + f"  (error {a.error_after:.4g})")
    final = diag.final_parameters()
    if final:
        print("final fit (all free parameters together):")
        for n, v in final.items():
            print(f"  {n} = {v['estimate']:.6g}" +
                  (f" +- {v['stderr']:.2g}" if v["stderr"] is not None else ""))
    for s in diag.indistinct:
        print(f"  ! {s}")


def _write_outputs(args, net, diag) -> None:
    out = sys.stderr if args.json else sys.stdout
    if args.report:
        _atomic_text(args.report, json.dumps(diag.as_dict(), indent=1))
        print(f"report: {args.report}", file=out)
    if args.html:
        write_html(diag, args.html, f"diagnosis of {net.title}")
        print(f"html: {args.html}", file=out)
    if args.write_netlist:
        header = (f"{net.title}, with the effects circuitsim diagnose found in {args.data}:\n" +
                  "\n".join(f"- {a.effect} on {a.target}: {a.evidence['what']}"
                            for a in diag.effects) +
                  f"\nerror {diag.error_before:.4g} -> {diag.error_after:.4g}")
        diag.raw.dump(args.write_netlist, header)
        print(f"netlist: {args.write_netlist}", file=out)
