"""Cross-check of motor J: the noise-free null output of simulators_j.py against circuitsim's
simulation of the declared netlists (motor_j.yaml, fast; motor_j_slow.yaml, slow); each
catalog and two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates) at the truth's expected values; and the outside records
whose law circuitsim's components can state (the transmission error and the cable harness
and the dragging brake as behavioural torques, the demagnetisation as a peak detector on a
capacitor driving a behavioural voltage and torque). The current sensor's hysteresis (a play
operator on the samples) has no component and is not compared.

    PYTHONPATH=<circuitsim checkout> python benchmarks/diagnosis/validate_j.py

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
import simulators_j as sj
from make_records_j import record_specs, scale_marginal

NETLISTS = {"fast": HERE / "netlists" / "motor_j.yaml",
            "slow": HERE / "netlists" / "motor_j_slow.yaml"}
TARGET = 1e-5


def patched(net, regime: str, effects: list[dict]):
    """The declared netlist with the truth's catalog patches (``catalog_patch``)."""
    return crosscheck.truth_patch(net, effects, sj.PROBES[regime], sj.REGIMES[regime][1])


# ---------------------------------------------------------------------- outside laws

def _add(raw, entry):
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def kinerr(raw, fx):
    """The flexspline K as behavioural torques: its input angle leads hd by
    eps sin(2 th + phase); the arm receives T_K, the cup -T_K (reaching the rotor as -T_K/N
    through the gear) and the rotor -T_K 2 eps cos(2 th + phase). The record starts at rest
    with the flexspline relaxed: the arm's angle starts at eps sin(phase)."""
    eps, ph = fx["kinerr"]
    p = sj.MOTOR_J
    raw.comps = [c for c in raw.comps if c[0].get("name") != "K"]
    # the record starts at rest with the flexspline relaxed: the arm at the gear's error
    raw.component_entry("Ja")["phi0"] = eps * math.sin(ph)
    cosx = f"cos(2*rotor.phi + {ph!r})"
    tk = (f"({p['c']!r}[N*m/rad]*(hd.phi + {eps!r}[rad]*sin(2*rotor.phi + {ph!r}) - arm.phi)"
          f" + {p['d']!r}[N*m*s/rad]*(hd.w + 2*{eps!r}*rotor.w*{cosx} - arm.w))")
    _add(raw, {"name": "TK_arm", "type": "btorque", "shaft": "arm", "expr": tk})
    _add(raw, {"name": "TK_hd", "type": "btorque", "shaft": "hd", "expr": f"-{tk}"})
    _add(raw, {"name": "TK_rotor", "type": "btorque", "shaft": "rotor",
               "expr": f"-{tk}*2*{eps!r}*{cosx}"})


def harness(raw, fx):
    kc, th0 = fx["harness"]
    _add(raw, {"name": "HARN", "type": "btorque", "shaft": "arm",
               "expr": f"-{kc!r}[N*m/rad]*(arm.phi - {th0!r}[rad])"})


def brake(raw, fx):
    tb, ph = fx["brake"]
    _add(raw, {"name": "BRK", "type": "btorque", "shaft": "rotor",
               "expr": f"-{tb!r}[N*m]*0.5*(1 + cos(rotor.phi + {ph!r}))"
                       f"*tanh(rotor.w/{sj.W_SIGN!r}[rad/s])"})


def demag(raw, fx):
    """The peak current m as the voltage of a 1 F capacitor charged by G relu(|i| - m); the
    flux lost, D(m), as a voltage -k D w in series with M and a torque -k D i on the rotor."""
    from circuitsim.loop.effects import insert_series

    delta, i1, iw, g = fx["demag"]
    k = sj.MOTOR_J["k"]
    _add(raw, {"name": "PKC", "type": "C", "p": "pk", "n": "gnd", "C": 1.0})
    _add(raw, {"name": "PKI", "type": "BI", "p": "gnd", "n": "pk",
               "expr": f"{g!r}*0.5*((sqrt(Ra.i^2 + 1e-6) - pk.v) + "
                       f"sqrt((sqrt(Ra.i^2 + 1e-6) - pk.v)^2 + 1e-6))"})
    loss = f"{delta!r}*(1 - exp(-(max(pk.v - {i1!r}, 0)/{iw!r})^2))"
    insert_series(raw, "M", "DMV", f"-{k!r}*{loss}*rotor.w")
    _add(raw, {"name": "DMT", "type": "btorque", "shaft": "rotor",
               "expr": f"-{k!r}[N*m/A]*{loss}*Ra.i"})


OUTSIDE_LAWS = {"kinerr": kinerr, "harness": harness, "brake": brake, "demag": demag}


# ---------------------------------------------------------------------- comparison

def compare(cs, regime: str, label: str, fx: dict, raw=None, values=None) -> float:
    """Motor J's scipy model against circuitsim (``crosscheck.compare``)."""
    return crosscheck.compare(cs, sj, "J", sj.MOTOR_J, NETLISTS, regime,
                              label, fx, raw, values)


def main() -> int:
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    return crosscheck.check_set(cs, "J", record_specs(), scale_marginal, patched,
                                OUTSIDE_LAWS, compare, NETLISTS, TARGET)


if __name__ == "__main__":
    sys.exit(main())
