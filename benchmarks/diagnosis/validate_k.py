"""Cross-check of motor K: the noise-free null output of simulators_k.py against circuitsim's
simulation of the declared netlists (motor_k.yaml, fast; motor_k_slow.yaml, slow); each
catalog and two-effect record against the declared netlist carrying the catalog's own patch
(circuitsim.loop.effects.candidates, through crosscheck.truth_patch) at the truth's expected
values; and the outside records whose law circuitsim's components can state (the compliant
hose as a 1 F capacitor charged by a behavioural current with the load as a behavioural
torque, the eccentric coupling, the direction-dependent load and the cavitating pump as
behavioural torques). The current sensor's drifting offset (a law of the probe's reading)
has no component and is not compared.

    PYTHONPATH=<circuitsim checkout> python benchmarks/diagnosis/validate_k.py

Prints, per probe, the largest difference relative to the signal's range on the record grid,
and the effect's own size on that scale. Target 1e-5 of the range; exit status 1 above it.
Nothing here runs a diagnosis.
"""

from __future__ import annotations

import os
import sys
import tempfile
import warnings
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import crosscheck
import simulators_k as sk
from make_records_k import record_specs, scale_marginal

NETLISTS = {"fast": HERE / "netlists" / "motor_k.yaml",
            "slow": HERE / "netlists" / "motor_k_slow.yaml"}
TARGET = 1e-5


def patched(net, regime: str, effects: list[dict]):
    """The declared netlist with the truth's catalog patches (``catalog_patch``)."""
    return crosscheck.truth_patch(net, effects, sk.PROBES[regime], sk.REGIMES[regime][1])


# ---------------------------------------------------------------------- outside laws

def _add(raw, entry):
    from circuitsim.loop.effects import add_part

    add_part(raw, entry)


def _drop(raw, *names):
    raw.comps = [c for c in raw.comps if c[0].get("name") not in names]


def hose(raw, fx):
    """The load bp x, x the voltage of a 1 F capacitor charged by (pump.w - x)/tau."""
    tau = fx["hose"]
    _drop(raw, "Bp")
    _add(raw, {"name": "HSC", "type": "C", "p": "hx", "n": "gnd", "C": 1.0})
    _add(raw, {"name": "HSI", "type": "BI", "p": "gnd", "n": "hx",
               "expr": f"(pump.w - hx.v)/{tau!r}"})
    _add(raw, {"name": "HSL", "type": "btorque", "shaft": "pump",
               "expr": f"-{sk.MOTOR_K['bp']!r}*hx.v"})


def ecc(raw, fx):
    eps, ph = fx["ecc"]
    _drop(raw, "MCp", "MCh")
    tq = f"Tm*(1 + {eps!r}*cos(hub.phi + {ph!r}))*sin(np*(hub.phi - pump.phi))"
    _add(raw, {"name": "MCp2", "type": "btorque", "shaft": "pump", "expr": tq})
    _add(raw, {"name": "MCh2", "type": "btorque", "shaft": "hub", "expr": f"-{tq}"})


def asym(raw, fx):
    b2 = fx["asym"]
    _add(raw, {"name": "ASY", "type": "btorque", "shaft": "pump",
               "expr": f"-{b2 * 0.5!r}[N*m*s/rad]*(pump.w - sqrt(pump.w^2 + "
                       f"({sk.W_ASYM!r}[rad/s])^2))"})


def cavit(raw, fx):
    wc = fx["cavit"]
    _drop(raw, "Bp")
    _add(raw, {"name": "CAV", "type": "btorque", "shaft": "pump",
               "expr": f"-bp*{wc!r}[rad/s]*tanh(pump.w/{wc!r}[rad/s])"})


OUTSIDE_LAWS = {"hose": hose, "ecc": ecc, "asym": asym, "cavit": cavit}


# ---------------------------------------------------------------------- comparison

def compare(cs, regime: str, label: str, fx: dict, raw=None, values=None) -> float:
    """Motor K's scipy model against circuitsim (``crosscheck.compare``)."""
    return crosscheck.compare(cs, sk, "K", sk.MOTOR_K, NETLISTS, regime,
                              label, fx, raw, values)


def main() -> int:
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    return crosscheck.check_set(cs, "K", record_specs(), scale_marginal, patched,
                                OUTSIDE_LAWS, compare, NETLISTS, TARGET)


if __name__ == "__main__":
    sys.exit(main())
