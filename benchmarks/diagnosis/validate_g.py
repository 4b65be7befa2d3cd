"""Cross-check of motor G: the noise-free null output of simulators_g.py against circuitsim's
simulation of the declared netlists (motor_g.yaml, fast; motor_g_slow.yaml, slow); each
catalog and two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates) at the truth's expected values; and the outside records
whose law circuitsim's components can state (the Hall sensor as a probe law, the tracking
loop as an RLC low-pass, the log brush contact as a behavioural voltage, the diode-fed bus
with its bank and chopper as behavioural sources and a capacitor).

    PYTHONPATH=<circuitsim checkout> python benchmarks/diagnosis/validate_g.py

Prints, per probe, the largest difference relative to the signal's range on the record grid,
and the effect's own size on that scale. Target 1e-5 of the range; exit status 1 above it.
Nothing here runs a diagnosis.
"""

from __future__ import annotations

import math
import os
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import simulators_g as sg
from make_records_g import record_specs, scale_marginal

NETLISTS = {"fast": HERE / "netlists" / "motor_g.yaml",
            "slow": HERE / "netlists" / "motor_g_slow.yaml"}
UNITS = {"current": "A", "speed": "rad/s", "load_speed": "rad/s"}
TARGET = 1e-5
#: the truth's physical names -> the catalog's parameter suffixes
SUFFIX = {"gain": "g", "offset": "o", "delay": "tau"}


def patched(net, regime: str, effects: list[dict]):
    """The declared netlist's raw form with each truth effect's catalog patch applied, and
    the patch parameters' values."""
    from circuitsim.loop.effects import candidates

    orders: dict[str, list[int]] = {}
    for e in effects:
        if "order" in e:
            shaft = "rotor" if e["effect"] == "emf-harmonic" else e["target"]
            orders.setdefault(shaft, []).append(int(e["order"]))
    pool = candidates(net, orders=orders, probes={p: UNITS[p] for p in sg.PROBES[regime]},
                      duration=sg.REGIMES[regime][1])
    raw, values = net.raw, {}
    for e in effects:
        keys = [SUFFIX.get(k, k) for k in e["expected"]]
        cand = next(c for c in pool if c.effect == e["effect"] and c.target == e["target"]
                    and c.fixed.get("order", e.get("order")) == e.get("order")
                    and all(any(n.endswith("_" + k) for n in c.free) for k in keys))
        raw = cand.apply(raw)
        for k, v in e["expected"].items():
            name = next(n for n in cand.free if n.endswith("_" + SUFFIX.get(k, k)))
            values[name] = float(v) - 1.0 if k == "gain" else float(v)
    return raw, values


# ---------------------------------------------------------------------- outside laws

def hall(raw, fx):
    s = fx["hall_sat"]
    text, loc = raw.probes["current"]
    raw.probes["current"] = (f"{s!r}[A]*tanh(({text})/{s!r}[A])", loc)


def rdc(raw, fx):
    """The tracking loop's velocity is w_n^2/(s^2 + 2 zeta w_n s + w_n^2) of the speed: a
    series R-L-C low-pass driven by one volt per rad/s, read across C."""
    from circuitsim.loop.effects import _add

    fn, zeta = fx["rdc"]
    wn = 2.0 * math.pi * fn
    c = 1e-3
    text, loc = raw.probes["speed"]
    _add(raw, {"name": "RDV", "type": "BV", "p": "rdc_in", "n": "gnd",
               "expr": f"({text})*1[V]/1[rad/s]"})
    _add(raw, {"name": "RDR", "type": "R", "p": "rdc_in", "n": "rdc_m",
               "R": 2.0 * zeta / (wn * c)})
    _add(raw, {"name": "RDL", "type": "L", "p": "rdc_m", "n": "rdc_out", "L": 1.0 / (wn**2 * c)})
    _add(raw, {"name": "RDC", "type": "C", "p": "rdc_out", "n": "gnd", "C": c})
    raw.probes["speed"] = ("rdc_out.v*1[rad/s]/1[V]", loc)


def logbrush(raw, fx):
    from circuitsim.loop.effects import _insert_series

    v1, i1 = fx["logbrush"]
    _insert_series(raw, "M", "LBR",
                   f"{v1!r}[V]*log(1 + abs(M.i)/{i1!r}[A])*sign(M.i)")


def bus(raw, fx):
    """The source becomes d Vbus (d = u/Vs, u read on a node of its own); the bank C starts
    at Vs, fed by the smooth diode and bled by the chopper as behavioural currents, and the
    bridge draws d i from it."""
    from circuitsim.loop.effects import _add

    vs, rs, cb, vcl, rbr = fx["bus"]
    src = next(e for e, _, _ in raw.comps if e.get("name") == "Vin")
    src["p"] = "cmd"
    _add(raw, {"name": "CMDR", "type": "R", "p": "cmd", "n": "gnd", "R": 1.0})
    _add(raw, {"name": "BR", "type": "BV", "p": "a", "n": "gnd",
               "expr": f"cmd.v/{vs!r}[V]*bus.v"})
    _add(raw, {"name": "CB", "type": "C", "p": "bus", "n": "gnd", "C": cb, "v0": vs})
    _add(raw, {"name": "DIN", "type": "BI", "p": "gnd", "n": "bus",
               "expr": f"0.5*(({vs!r}[V] - bus.v) + sqrt(({vs!r}[V] - bus.v)^2 + "
                       f"1e-6[V^2]))/{rs!r}[ohm]"})
    _add(raw, {"name": "CHOP", "type": "BI", "p": "bus", "n": "gnd",
               "expr": f"0.5*((bus.v - {vcl!r}[V]) + sqrt((bus.v - {vcl!r}[V])^2 + "
                       f"1e-6[V^2]))/{rbr!r}[ohm]"})
    _add(raw, {"name": "DRAW", "type": "BI", "p": "bus", "n": "gnd",
               "expr": f"cmd.v/{vs!r}[V]*Ra.i"})


OUTSIDE_LAWS = {"hall_sat": hall, "rdc": rdc, "logbrush": logbrush, "bus": bus}


# ---------------------------------------------------------------------- comparison

def compare(cs, regime: str, label: str, fx: dict, raw=None, values=None) -> float:
    from circuitsim.netlist.load import build

    t = sg.grid(regime)
    fx = dict(fx)
    p = {**sg.MOTOR_G, **fx.pop("p", {})}
    ref = sg.simulate(regime, t, fx, p)
    base = sg.simulate(regime, t) if (fx or p != sg.MOTOR_G) else None
    net = cs.load(NETLISTS[regime]) if raw is None else build(raw)
    t0 = time.perf_counter()
    res = cs.compile(net).simulate(stop=float(t[-1]), t_eval=t, params=values or None,
                                   rtol=1e-10, atol=1e-12)
    t_cs = time.perf_counter() - t0
    worst = 0.0
    for pr in sg.PROBES[regime]:
        a, b = np.asarray(ref[pr]), np.asarray(res[pr])
        rng = float(np.ptp(b))
        mx = float(np.max(np.abs(a - b)) / rng)
        worst = max(worst, mx)
        size = "" if base is None else \
            f"; effect {np.max(np.abs(a - base[pr])) / rng:.1e} of range"
        print(f"motor G {regime:4s} {label:52s} {pr:10s}: max |diff|/range {mx:.1e} "
              f"(range {rng:.4g}{size}; circuitsim {t_cs:.1f} s)", flush=True)
    return worst


def main() -> int:
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    worst = max(compare(cs, r, "null", {}) for r in ("fast", "slow"))
    for s in record_specs():
        regime = s["regime"]
        if s["marginal"] is not None:
            scale_marginal(s)
        if s["class"] in ("catalog", "two"):
            raw, values = patched(cs.load(NETLISTS[regime]), regime, s["effects"])
            label = s["id"] + " " + " + ".join(e["effect"] + "@" + e["target"]
                                               for e in s["effects"])
            worst = max(worst, compare(cs, regime, label, s["fx"], raw, values))
        else:
            law = next((f for k, f in OUTSIDE_LAWS.items() if k in s["fx"]), None)
            if law is None:
                continue
            raw = cs.load(NETLISTS[regime]).raw.copy()
            law(raw, s["fx"])
            worst = max(worst, compare(cs, regime, f"{s['id']} outside, as components",
                                       s["fx"], raw))
    print(f"worst max |diff|/range {worst:.2e} -> {'OK' if worst < TARGET else 'ABOVE'} "
          f"(target {TARGET:g})")
    return 0 if worst < TARGET else 1


if __name__ == "__main__":
    sys.exit(main())
