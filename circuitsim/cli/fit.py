"""``circuitsim fit``."""

from __future__ import annotations

import argparse
import json
import sys
import warnings

from circuitsim.cli.progress import status_line
from circuitsim.files import atomic_write, check_output
from circuitsim.loop.fit import FitError, fit_features, fit_record, format_result
from circuitsim.loop.record import DataError, FeatureSet
from circuitsim.netlist.load import analysis_problem


def _rtol(text: str) -> float:
    """An argparse ``type``: the integrator's relative tolerance, refused outside (0, 0.01]."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number") from None
    problem = analysis_problem("rtol", value)
    if problem:
        raise argparse.ArgumentTypeError(problem)
    return value


def add_cli(sub) -> None:
    """Register ``circuitsim fit`` on an argparse subparsers action."""
    from circuitsim.cli.main import ALLOW_HELP

    f = sub.add_parser("fit", help="fit free parameters to a measured record or features",
                       description="Nonlinear least squares of free netlist parameters against "
                       "a CSV record (time + one column per probe, SI or with the unit in brackets: "
                       "'time [s],i [A]') or a features YAML "
                       "(steady means, harmonic amplitude/frequency).")
    f.add_argument("netlist", help="netlist YAML file")
    f.add_argument("--allow-outside", action="store_true", help=ALLOW_HELP)
    f.add_argument("data", help="CSV record or features YAML")
    f.add_argument("--free", default="", metavar="NAME,...",
                   help="parameters to estimate (netlist 'La' or component 'La.L'); none: "
                        "just the residuals of the netlist's values")
    f.add_argument("--set", action="append", metavar="NAME=VALUE",
                   help="override a parameter; for a free one, its start value")
    f.add_argument("--report", metavar="FIT.json", help="write the full report (JSON)")
    f.add_argument("--probe", "--probes", dest="probes", action="append", metavar="NAME[,NAME]",
                   help="record: probe columns to compare (default: all the record has)")
    f.add_argument("--single-stage", action="store_true",
                   help="record: skip the slow-feature stage (naive waveform fit)")
    f.add_argument("--harmonic", choices=("small-signal", "pss"), default="small-signal",
                   help="features: harmonic model (default small-signal; pss: exact, slower)")
    f.add_argument("--time", default="time", help="record: name of the time column [s]")
    f.add_argument("--inputs", default="", metavar="NAME,...",
                   help="record: other columns that are not probes (measured inputs, ignored "
                        "unless a table source reads them)")
    f.add_argument("--rtol", type=_rtol, default=1e-8,
                   help="record: integrator rtol (at most 0.01)")
    f.add_argument("--full-record", action="store_true",
                   help="record: fit every row, even of a long record sampled far faster than "
                        "its content needs (by default such a record is filtered and reduced "
                        "to a working resolution, and the report says how)")
    f.add_argument("--json", action="store_true", help="print the report as JSON")
    f.add_argument("--quiet", action="store_true", help="no progress bar")
    f.set_defaults(func=cmd_fit)


def _split(text: str) -> list[str]:
    return [s.strip() for s in text.split(",") if s.strip()]


def cmd_fit(args) -> int:
    from circuitsim.cli.main import _parse_sets
    from circuitsim.compiler.model import compile as compile_model
    from circuitsim.loop.record import load_data
    from circuitsim.netlist.load import load

    net = load(args.netlist, allow_outside=args.allow_outside)
    if args.report:
        check_output(args.report, (*net.inputs, args.data), "--report")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        model = compile_model(net)
    inputs = [t.label.split(":", 1)[1] for c in net.components for t in c.tables]
    inputs += _split(args.inputs)
    overrides = _parse_sets(model, args.set or [])
    free = _split(args.free)
    probes = _split(",".join(args.probes or []))
    with warnings.catch_warnings(record=True) as fit_caught, \
            status_line("fit", quiet=args.quiet or args.json) as bar:
        warnings.simplefilter("always")
        if bar is not None:
            bar(f"reading {args.data}")
        data = load_data(args.data, model.probe_names, inputs=inputs, time=args.time,
                         units=model.meta["units"])
        if isinstance(data, FeatureSet):
            if probes or args.single_stage or args.full_record:
                raise FitError("--probes, --single-stage and --full-record apply to a CSV "
                               "record, not to features")
            result = fit_features(model, data, free, params=overrides, harmonic=args.harmonic,
                                  progress=bar)
        else:
            check_columns(probes, data.names, args.data)
            result = fit_record(model, data, free, params=overrides, probes=probes or None,
                                staged=not args.single_stage, rtol=args.rtol,
                                reduce=not args.full_record, progress=bar)
    physics = [str(w.message) for w in caught]
    report = {"netlist": args.netlist, "data": args.data, **result.as_dict(),
              "model_warnings": physics}
    if args.report:
        _write_json(args.report, report)
    if args.json:
        print(json.dumps(report, indent=1))
    else:
        for w in physics:
            print(f"warning: {w}", file=sys.stderr)
        print(format_result(result, title=f"{net.title} <- {args.data}"))
        if args.report:
            print(f"report: {args.report}")
    del fit_caught  # the result carries its warnings; the report prints them
    return 0 if result.success else 1


def check_columns(probes: list[str], columns, data: str) -> None:
    """Refuse --probe names the record has no column for (exit 2, naming the columns)."""
    missing = [p for p in probes if p not in columns]
    if missing:
        raise DataError(f"{data}: --probe {missing[0]}: the record has no such column "
                        f"(columns: {', '.join(columns)})")


def _write_json(path: str, obj: dict) -> None:
    """Write atomically: a killed run leaves the old report or none, never half of one."""
    atomic_write(path, json.dumps(obj, indent=1, allow_nan=False) + "\n")
