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
import warnings
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import crosscheck
import simulators_g as sg
from make_records_g import record_specs, scale_marginal

NETLISTS = {"fast": HERE / "netlists" / "motor_g.yaml",
            "slow": HERE / "netlists" / "motor_g_slow.yaml"}
TARGET = 1e-5


def patched(net, regime: str, effects: list[dict]):
    """The declared netlist with the truth's catalog patches (``catalog_patch``)."""
    return crosscheck.truth_patch(net, effects, sg.PROBES[regime], sg.REGIMES[regime][1])


# ---------------------------------------------------------------------- outside laws

def hall(raw, fx):
    s = fx["hall_sat"]
    text, loc = raw.probes["current"]
    raw.probes["current"] = (f"{s!r}[A]*tanh(({text})/{s!r}[A])", loc)


def rdc(raw, fx):
    """The tracking loop's velocity is w_n^2/(s^2 + 2 zeta w_n s + w_n^2) of the speed: a
    series R-L-C low-pass driven by one volt per rad/s, read across C."""
    from circuitsim.loop.effects import add_part

    fn, zeta = fx["rdc"]
    wn = 2.0 * math.pi * fn
    c = 1e-3
    text, loc = raw.probes["speed"]
    add_part(raw, {"name": "RDV", "type": "BV", "p": "rdc_in", "n": "gnd",
               "expr": f"({text})*1[V]/1[rad/s]"})
    add_part(raw, {"name": "RDR", "type": "R", "p": "rdc_in", "n": "rdc_m",
               "R": 2.0 * zeta / (wn * c)})
    add_part(raw, {"name": "RDL", "type": "L", "p": "rdc_m", "n": "rdc_out",
                   "L": 1.0 / (wn**2 * c)})
    add_part(raw, {"name": "RDC", "type": "C", "p": "rdc_out", "n": "gnd", "C": c})
    raw.probes["speed"] = ("rdc_out.v*1[rad/s]/1[V]", loc)


def logbrush(raw, fx):
    from circuitsim.loop.effects import insert_series

    v1, i1 = fx["logbrush"]
    insert_series(raw, "M", "LBR",
                   f"{v1!r}[V]*log(1 + abs(M.i)/{i1!r}[A])*sign(M.i)")


def bus(raw, fx):
    """The source becomes d Vbus (d = u/Vs, u read on a node of its own); the bank C starts
    at Vs, fed by the smooth diode and bled by the chopper as behavioural currents, and the
    bridge draws d i from it."""
    from circuitsim.loop.effects import add_part

    vs, rs, cb, vcl, rbr = fx["bus"]
    src = next(e for e, _, _ in raw.comps if e.get("name") == "Vin")
    src["p"] = "cmd"
    add_part(raw, {"name": "CMDR", "type": "R", "p": "cmd", "n": "gnd", "R": 1.0})
    add_part(raw, {"name": "BR", "type": "BV", "p": "a", "n": "gnd",
               "expr": f"cmd.v/{vs!r}[V]*bus.v"})
    add_part(raw, {"name": "CB", "type": "C", "p": "bus", "n": "gnd", "C": cb, "v0": vs})
    add_part(raw, {"name": "DIN", "type": "BI", "p": "gnd", "n": "bus",
               "expr": f"0.5*(({vs!r}[V] - bus.v) + sqrt(({vs!r}[V] - bus.v)^2 + "
                       f"1e-6[V^2]))/{rs!r}[ohm]"})
    add_part(raw, {"name": "CHOP", "type": "BI", "p": "bus", "n": "gnd",
               "expr": f"0.5*((bus.v - {vcl!r}[V]) + sqrt((bus.v - {vcl!r}[V])^2 + "
                       f"1e-6[V^2]))/{rbr!r}[ohm]"})
    add_part(raw, {"name": "DRAW", "type": "BI", "p": "bus", "n": "gnd",
               "expr": f"cmd.v/{vs!r}[V]*Ra.i"})


OUTSIDE_LAWS = {"hall_sat": hall, "rdc": rdc, "logbrush": logbrush, "bus": bus}


# ---------------------------------------------------------------------- comparison

def compare(cs, regime: str, label: str, fx: dict, raw=None, values=None) -> float:
    """Motor G's scipy model against circuitsim (``crosscheck.compare``)."""
    return crosscheck.compare(cs, sg, "G", sg.MOTOR_G, NETLISTS, regime,
                              label, fx, raw, values)


def main() -> int:
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    return crosscheck.check_set(cs, "G", record_specs(), scale_marginal, patched,
                                OUTSIDE_LAWS, compare, NETLISTS, TARGET)


if __name__ == "__main__":
    sys.exit(main())
