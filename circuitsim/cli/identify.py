"""``circuitsim identify``: the BLDC identification steps (Kapun et al. 2008) on CSV data."""

from __future__ import annotations

import argparse
import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from circuitsim.cli.argtypes import fraction, positive, whole
from circuitsim.loop.identify import (
    MAX_ORDER,
    ObserverResult,
    _col,
    _emf_arg,
    _ints,
    _read_csv,
    disturbance_error_curve,
    disturbance_observer,
    emf_constants,
    emf_error_curve,
    fit_back_emf,
    fit_disturbance,
    fit_periodic_map,
    mutual_torque,
    peak_cogging,
    relevant_orders,
)
from circuitsim.loop.record import DataError
from circuitsim.report.identify import _plot_curve, _plot_map


@dataclass
class _Args:
    """Shared options of the record-based subcommands."""

    common: list[tuple[tuple[str, ...], dict]] = field(default_factory=lambda: [
        (("--pp",), {"type": whole(1, 500), "required": True, "help": "pole pairs p [1]"}),
        (("--theta",), {"default": "theta", "help": "rotor angle column [rad]"}),
        (("--omega",), {"default": "omega", "help": "rotor speed column [rad/s]"}),
    ])

    def add(self, parser: argparse.ArgumentParser) -> None:
        for flags, kw in self.common:
            parser.add_argument(*flags, **kw)


def _ts(rec, path, time_col: str) -> float:
    t = _col(rec, time_col, path)
    dt = np.diff(t)
    if dt.size == 0 or np.any(dt <= 0) or np.ptp(dt) > 1e-6 * np.mean(dt):
        raise DataError(f"{path}: column '{time_col}' must be uniformly sampled and increasing "
                        f"(the observer runs at a fixed sample time)")
    return float(np.mean(dt))


def _check_outputs(args) -> None:
    """Refuse before any work an output that is the input record or a folder."""
    from circuitsim.files import check_output

    for what in ("plot", "out"):
        path = getattr(args, what, None)
        if path:
            check_output(path, [args.file], f"--{what}")


def _cmd_emf(args) -> int:
    _check_outputs(args)
    rec = _read_csv(args.file)
    th, w, v = (_col(rec, c, args.file) for c in (args.theta, args.omega, args.voltage))
    curve = emf_error_curve(th, w, v, args.pp, args.k_max, shift=args.shift)
    rel = relevant_orders(curve, args.rel_tol)
    orders = _ints(args.orders) if args.orders else list(range(1, max(rel) + 1)) if rel else [1]
    fit = fit_back_emf(th, w, v, args.pp, orders, shift=args.shift)
    peak, rms = emf_constants(fit)
    if args.plot:
        _plot_curve(curve, "number of harmonics K", "J_min [V^2]", args.plot)
    if args.json:
        print(json.dumps({"jmin": curve.tolist(), "relevant_orders": list(rel),
                          "a": {str(k): v for k, v in fit.a.items()},
                          "b": {str(k): v for k, v in fit.b.items()},
                          "Ke_peak": peak, "Ke_rms": rms}))
        return 0
    print(f"back-EMF least squares, {len(v)} samples, p = {args.pp}")
    print("K   J_min [V^2]")
    for K, j in enumerate(curve):
        print(f"{K:<3d} {j:.6g}")
    print(f"relevant harmonics (drop > {args.rel_tol:g} of the signal energy): "
          f"{', '.join(map(str, rel))}")
    print("order   L_ra [1e-6 H]   L_rb [1e-6 H]")
    for k in fit.orders:
        print(f"{k:<7d} {fit.a[k] * 1e6:13.3f} {fit.b[k] * 1e6:15.3f}")
    print(f"voltage constant: peak {peak * 1e3:.2f} mV*s/rad, RMS {rms * 1e3:.2f} mV*s/rad")
    return 0


def _observer_from_args(args, rec) -> tuple[ObserverResult, np.ndarray, np.ndarray]:
    th = _col(rec, args.theta, args.file)
    w = _col(rec, args.omega, args.file)
    if args.emf is None or args.J is None:
        raise DataError("the observer needs --J (total inertia) and --emf (back-EMF "
                        "coefficients ORDER:A[:B],...)")
    emf = _emf_arg(args.emf, args.pp)
    cur = [_col(rec, c, args.file) for c in args.currents.split(",")]
    tm = mutual_torque(th, cur, emf)
    obs = disturbance_observer(w, tm, args.J, _ts(rec, args.file, args.time), args.bandwidth)
    return obs, th, w


def _cmd_observer(args) -> int:
    _check_outputs(args)
    rec = _read_csv(args.file)
    obs, th, w = _observer_from_args(args, rec)
    t = _col(rec, args.time, args.file)
    out = args.out or str(Path(args.file).with_suffix("")) + "_dist.csv"
    np.savetxt(out, np.column_stack([t, th, w, obs.omega_hat, obs.t_dist]), delimiter=",",
               header="time,theta,omega,omega_hat,T_dist", comments="", fmt="%.10g")
    print(f"disturbance observer: J = {args.J:g} kg*m^2, bandwidth {args.bandwidth:g} Hz; "
          f"max |speed error| {np.max(np.abs(obs.error)):.3g} rad/s; wrote {out}")
    return 0


def _cmd_cogging(args) -> int:
    _check_outputs(args)
    rec = _read_csv(args.file)
    obs = None
    if args.t_dist in rec:
        th, w = _col(rec, args.theta, args.file), _col(rec, args.omega, args.file)
        td = _col(rec, args.t_dist, args.file)
    else:
        obs, th, w = _observer_from_args(args, rec)
        td = obs.t_dist
    orders = _ints(args.orders)
    kw = {"unbalance": not args.no_unbalance, "coulomb": not args.no_coulomb}
    use = obs if (obs is not None and not args.raw) else None
    if args.k_max:
        curve = disturbance_error_curve(th, w, td, args.pp, args.k_max, observer=use, **kw)
        print("K   J_min [N^2 m^2]")
        for K, j in enumerate(curve):
            print(f"{K:<3d} {j:.6g}")
        if args.plot:
            _plot_curve(curve, "number of cogging harmonics K", "J_min [N^2 m^2]", args.plot)
    fit = fit_disturbance(th, w, td, args.pp, orders, observer=use, **kw)
    peak, at = peak_cogging(fit, args.pp, orders)
    if args.json:
        print(json.dumps({**fit.fit.as_dict(), "peak_cogging": peak, "peak_angle": at}))
        return 0
    print(f"disturbance least squares, {fit.fit.n} samples, orders {orders} of p*theta"
          + (" (regressors through the observer loop)" if use is not None else ""))
    for n, v in fit.fit.as_dict().items():
        print(f"  {n:<8} {v * 1e6:12.3f} x 1e-6   (+- {fit.fit.std(n) * 1e6:.3f})")
    print(f"peak cogging torque {peak * 1e3:.3f} mN*m at theta = {at:.4f} rad")
    return 0


def _cmd_map(args) -> int:
    _check_outputs(args)
    rec = _read_csv(args.file, args.where)
    th = _col(rec, args.angle, args.file)
    x = _col(rec, args.value, args.file)
    direction = None
    if args.direction:
        raw = rec.get(args.direction)
        if raw is None:
            raise DataError(f"{args.file}: no column '{args.direction}'")
        direction = np.array([1.0 if str(v).strip().lower() in ("forward", "+1", "1", "1.0")
                              else -1.0 for v in raw])
    fit = fit_periodic_map(th, x, args.count, args.k_max, direction,
                           _ints(args.orders) if args.orders else None)
    if args.plot:
        _plot_map(th, x, fit, direction, args.plot)
    if args.json:
        print(json.dumps({"orders": list(fit.orders), "jmin": list(fit.curve),
                          "amplitude": {str(k): fit.amplitude(k) for k in fit.orders},
                          **fit.fit.as_dict()}))
        return 0
    print(f"periodic map, {len(x)} samples; orders per shaft turn, greedy by J_min")
    print(f"  mean {fit.fit['c0']:.6g}" + (f", Coulomb-like C {fit.fit['C']:.6g}"
                                          if "C" in fit.fit.names else ""))
    print("  order   amplitude     J_min after")
    for k, j in zip(fit.orders, fit.curve[1:], strict=False):
        print(f"  {k:<7d} {fit.amplitude(k):.5g}   {j:.5g}")
    return 0


def _add_observer_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("--time", default="time", help="time column [s], uniform")
    p.add_argument("--currents", default="i1,i2,i3", help="phase current columns [A]")
    p.add_argument("--emf", help="back-EMF coefficients ORDER:A[:B],... [H] "
                   "(e.g. 1:5817e-6,3:57e-6,5:28e-6, from `identify emf`)")
    p.add_argument("--J", type=positive, help="total inertia [kg*m^2]")
    p.add_argument("--bandwidth", type=positive, default=1000.0, help="observer loop [Hz]")


def add_cli(subparsers) -> None:
    """Register ``circuitsim identify {emf, observer, cogging, map}``."""
    ident = subparsers.add_parser("identify", help="identify BLDC parameters from records "
                                  "(Kapun 2008: back-EMF, disturbance observer, cogging)")
    sub = ident.add_subparsers(dest="identify_command", required=True, metavar="STEP",
                               help="identification step")
    shared = _Args()
    e = sub.add_parser("emf", help="back-EMF harmonics from open-circuit phase voltage")
    e.add_argument("file", help="CSV with angle, speed and phase-to-neutral voltage")
    shared.add(e)
    e.add_argument("--voltage", default="e1", help="phase-to-neutral voltage column [V]")
    e.add_argument("--shift", type=float, default=0.0, help="electrical phase of this phase")
    e.add_argument("--k-max", type=whole(1, MAX_ORDER), default=9,
                   help="largest K of the J_min curve")
    e.add_argument("--rel-tol", type=fraction, default=1e-4,
                   help="relevant order: J_min drop above this fraction of the signal energy")
    e.add_argument("--orders", help="fit these orders (default 1..largest relevant)")
    e.add_argument("--plot", help="PNG of J_min versus K")
    e.add_argument("--json", action="store_true", help="print one JSON object")
    e.set_defaults(func=_cmd_emf)
    o = sub.add_parser("observer", help="disturbance torque by a closed-loop observer")
    o.add_argument("file", help="CSV with time, angle, speed and phase currents")
    shared.add(o)
    _add_observer_args(o)
    o.add_argument("--out", help="CSV of the disturbance (default FILE_dist.csv)")
    o.set_defaults(func=_cmd_observer)
    c = sub.add_parser("cogging", help="cogging harmonics, B, C, unbalance by least squares")
    c.add_argument("file", help="CSV with a T_dist column, or a raw record (then give "
                   "--J and --emf and the observer runs first)")
    shared.add(c)
    _add_observer_args(c)
    c.add_argument("--t-dist", default="T_dist", help="disturbance torque column [N*m]")
    c.add_argument("--orders", default="3,6", help="cogging orders k of p*theta")
    c.add_argument("--no-unbalance", action="store_true", help="no 1-per-turn terms")
    c.add_argument("--no-coulomb", action="store_true", help="no C sign(w) term")
    c.add_argument("--raw", action="store_true",
                   help="take the compensator output as the disturbance (Kapun's plain fit)")
    c.add_argument("--k-max", type=whole(0, MAX_ORDER), default=0,
                   help="print J_min for K = 0..K_MAX")
    c.add_argument("--plot", help="PNG of J_min versus K (with --k-max)")
    c.add_argument("--json", action="store_true", help="print one JSON object")
    c.set_defaults(func=_cmd_cogging)
    m = sub.add_parser("map", help="dominant orders of a measured cogging map")
    m.add_argument("file", help="CSV with shaft angle and torque (or holding current)")
    m.add_argument("--angle", default="angle_rad", help="shaft angle column [rad]")
    m.add_argument("--value", default="iq_hold_A", help="torque or current column")
    m.add_argument("--where", action="append", help="keep rows with COLUMN=VALUE")
    m.add_argument("--direction", help="sweep direction column (forward/reverse): adds C")
    m.add_argument("--count", type=whole(1, MAX_ORDER), default=8, help="orders to select")
    m.add_argument("--k-max", type=whole(1, MAX_ORDER), default=100, help="largest order searched")
    m.add_argument("--orders", help="fit these orders instead of searching")
    m.add_argument("--plot", help="PNG of the map and the fit")
    m.add_argument("--json", action="store_true", help="print one JSON object")
    m.set_defaults(func=_cmd_map)
