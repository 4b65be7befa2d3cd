"""Cross-check of motor BB on the records' own times: the noise-free output of simulators_bb.py
against circuitsim's simulation of the declared netlists (motor_bb_case3.yaml,
motor_bb_case5.yaml, motor_bb_case6.yaml) with NO effect: first at the netlists' DECLARED values
(on an even 20 kHz grid of each case, and on the times of be01 (even, case 3), be02 (jittered,
case 6), be06 (even 50 kHz, case 6) and be12 (even 30 kHz, case 5)), then on every record's
times at the record's TRUE values (the declared parameters it frees set to their true values
through circuitsim's parameter overrides, ``params``). The records' effects are not run through
circuitsim here (this blind set keeps circuitsim to the null models).

The three netlists must declare the same motor and connector: their parameters but the filter's
and all components but the source and the filter's are compared first, and each netlist's
declared values must be the simulator's (``simulators_bb.params``). The set's generator and
simulator must not touch circuitsim: their sources (make_records_bb.py, simulators_bb.py and the
recordkit.py they share) are read first and any import of circuitsim in them fails the check;
and at the end no module of the diagnosis's package (``circuitsim.loop``) may have been imported
by anything run here.

    python benchmarks/diagnosis/validate_bb.py              # every record
    python benchmarks/diagnosis/validate_bb.py be04,be14    # some

Prints, per probe, the largest difference relative to the signal's range at the record's
sample times. Target 1e-7 of the range; exit status 1 above it. Nothing here runs a
diagnosis.
"""

from __future__ import annotations

import os
import sys
import tempfile
import warnings
from pathlib import Path
from types import SimpleNamespace
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import crosscheck
import simulators_bb as sy
from make_records_bb import record_specs, scale_marginal, times

NETLISTS = {case: HERE / "netlists" / f"motor_bb_case{case}.yaml" for case in sy.CASES}
#: each case's source and filter components (the rest is the motor and the connector)
FILTER_PARTS = {3: ("Vin", "Rf", "Cf"), 5: ("Vin", "Lf", "Cf"), 6: ("Vin", "Lf", "Rs", "Cs")}
TARGET = 1e-7
NULL_ON = ("be01", "be02", "be06", "be12")
#: the set's own code, which must not import circuitsim (nor its diagnosis, circuitsim.loop)
OWN_CODE = ("make_records_bb.py", "simulators_bb.py", "recordkit.py")


def simulator(case: int, t: Any) -> SimpleNamespace:
    """The scipy model of ``case`` as crosscheck.compare takes a simulator module (one
    regime, ``fast``, on the times ``t``)."""
    return SimpleNamespace(grid=lambda regime: t,
                           simulate=lambda regime, tt, fx=None, p=None:
                           sy.simulate(case, tt, fx, p),
                           PROBES=sy.PROBES)


def compare(cs: Any, case: int, t: Any, label: str, fx: dict,
            values: dict[str, float] | None = None) -> float:
    """Motor BB's scipy model of ``case`` against circuitsim at the times ``t`` [s]
    (``values``: circuitsim's parameter overrides)."""
    return crosscheck.compare(cs, simulator(case, t), f"BB case {case}", sy.params(case),
                              {"fast": NETLISTS[case]}, "fast", label, fx, None, values)


def check(cs: Any, s: dict) -> float:
    """One record's comparisons: the declared null on its times (NULL_ON) and the true null
    (the overrides), both without any effect."""
    worst = 0.0
    kind = s["timestamps"].split(":")[0]
    t = times(s)
    if s["id"] in NULL_ON:
        worst = compare(cs, s["case"], t, f"declared null on {s['id']}'s {kind} times", {})
    return max(worst, compare(cs, s["case"], t, f"true null of {s['id']} ({kind} times)",
                              {"p": dict(s["ptrue"])}, dict(s["ptrue"])))


def same_motor(cs: Any) -> bool:
    """Whether the three netlists declare the same motor and connector (parameters and
    components but the source's and the filter's)."""
    def motor(case: int) -> tuple:
        raw = cs.load(NETLISTS[case]).raw
        filt = set(FILTER_PARTS[case])
        comps = [dict(c[0]) for c in raw.comps if str(c[0]["name"]) not in filt]
        pars = {k: v for k, (v, _) in raw.params.items() if k in sy.MOTOR}
        return repr(pars), repr(comps)

    first, *rest = sy.CASES
    same = all(motor(case) == motor(first) for case in rest)
    print(f"motor BB: the netlists of cases {', '.join(map(str, sy.CASES))} declare the same "
          f"motor and connector: {same}")
    return same


#: the simulator's parameter -> the compiled netlist's component parameters that carry it
WHERE = {"Ra": ("Ra.R",), "La": ("La.L",), "L_conn": ("Lc1.L", "Lc2.L"), "Rv": ("Var.R",),
         "Cv": ("Var.C",), "J": ("Jr.J",), "B": ("Bv.b",), "k_t": ("M.k_t",),
         "k_e": ("M.k_e",), "e0": ("M.e0",), "A8_slope": ("M.harmonics[0].slope",),
         "A8_offset": ("M.harmonics[0].offset",), "Cf": ("Cf.C",), "Lf": ("Lf.L",),
         "Rs": ("Rs.R",), "Cs": ("Cs.C",)}


def declared_values(cs: Any) -> bool:
    """Whether each netlist's declared values [SI] are the simulator's (to 1e-12): its
    parameters, the EMF's harmonic order, the supply's pwl and the brake's step."""
    ok = True
    for case in sy.CASES:
        got = cs.compile(cs.load(NETLISTS[case])).param_values()
        where = {**WHERE, "Rf": ("Lf.R",) if case == 5 else ("Rf.R",)}
        want: dict[str, float] = {}
        for name, v in sy.params(case).items():
            want.update({key: v for key in where[name]})
        want["M.harmonics[0].order"] = 8.0
        want["M.harmonics[0].phase"] = 0.0
        for k, (tk, vk) in enumerate(sy.POINTS):
            want[f"Vin.V.t{k}"], want[f"Vin.V.v{k}"] = tk, vk
        t0, rise, v1 = sy.BRAKE
        want.update({"Tl.T.v0": 0.0, "Tl.T.v1": v1, "Tl.T.t0": t0, "Tl.T.rise": rise})
        bad = [k for k, v in want.items()
               if k not in got or abs(float(got[k]) - v) > 1e-12 * max(abs(v), 1e-300)]
        print(f"motor BB case {case}: {len(want)} declared values, the supply's and the "
              f"brake's included, as the simulator's: {'yes' if not bad else bad}")
        ok = ok and not bad
    return ok


def main() -> int:
    """Every record of fresh53; exit status 1 above TARGET (or if the netlists differ, or if
    the set's code imports circuitsim, or if circuitsim.loop was imported)."""
    clean = crosscheck.own_code_clean(HERE, OWN_CODE)
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    same = same_motor(cs)
    values = declared_values(cs)
    worst = max(compare(cs, case, sy.grid(20e3), "declared null, even 20 kHz grid", {})
                for case in sy.CASES)
    status = crosscheck.check_records(cs, record_specs(), times, scale_marginal, check,
                                      TARGET, sys.argv[1:2])
    print(f"declared nulls on the even grids: worst max |diff|/range {worst:.2e}")
    if worst >= TARGET:
        status = 1
    loaded = sorted(m for m in sys.modules if m.startswith("circuitsim.loop"))
    if loaded:
        print(f"the diagnosis's package was imported ({', '.join(loaded)}): the check is void")
        return 1
    print("circuitsim.loop: not imported")
    if not clean:
        print("the set's generator or simulator imports circuitsim: the check is void")
        return 1
    return status if (same and values) else 1


if __name__ == "__main__":
    sys.exit(main())
