"""Cross-check of motor M on the records' own times: the noise-free null output of
simulators_m.py against circuitsim's plain simulation of the declared netlists
(motor_m.yaml, fast; motor_m_slow.yaml, slow) on the times of each null record (u01: even,
u02: a logger's uneven times) and of one more record of each regime (u03: jittered, u06:
even); then each record whose effects circuitsim's ordinary components can state, written
out by hand in a copy of the netlists (a resistor or a behavioural voltage in the supply lead,
a `Lsat` for `La`, a damper, a friction or a behavioural torque on the fan). The NTC's
thermal law, the sensor offset and the eccentric encoder (laws of a reading) are not
compared. Nothing here imports circuitsim's diagnosis (circuitsim.loop) or runs a diagnosis:
only ``circuitsim.load`` and ``compile(...).simulate``.

    python benchmarks/diagnosis/validate_m.py

Prints, per probe, the largest difference relative to the signal's range at the record's
sample times (and the rms difference over the standard deviation). Target 1e-5 of the
range; exit status 1 above it.
"""

from __future__ import annotations

import os
import shutil
import sys
import tempfile
import time
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import yaml

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import simulators_m as sm
from make_records_m import record_specs, scale_marginal, times

NETS = HERE / "netlists"
FILES = {"fast": "motor_m.yaml", "slow": "motor_m_slow.yaml"}
MOTOR_FILE = "motor_m_motor.yaml"
TARGET = 1e-5
Edit = tuple[list[dict], dict[str, dict]]


# ---------------------------------------------------------------------- laws as components

def laws(fx: dict[str, Any]) -> Edit | None:
    """The added components and the replaced ones of the effects ``fx``, or None when one
    of them has no component."""
    added: list[dict] = []
    repl: dict[str, dict] = {}
    lead: list[str] = []
    for key, val in fx.items():
        if key == "Rser":
            lead.append(f"{val!r}[ohm]*Ra.i")
        elif key == "Vb":
            lead.append(f"{val!r}[V]*tanh(Ra.i/{sm.I_SIGN!r}[A])")
        elif key == "warmup":
            lead.append(f"R*{val[0]!r}*(1 - exp(-t/{val[1]!r}[s]))*Ra.i")
        elif key == "chopper":
            lead.append(f"{val[0]!r}[ohm]*(1 - tanh(Ra.i/{val[1]!r}[A]))/2*Ra.i")
        elif key == "lsat":
            repl["La"] = {"name": "La", "type": "Lsat", "p": "m1", "n": "m2", "Lzer": "L",
                          "Linf": sm.MOTOR_M["L"] * val[1], "Ipar": val[0]}
        elif key in ("cog", "coul", "visc", "stribeck", "rub", "damper"):
            added.extend(torques(key, val))
        else:
            return None
    if lead:
        added.append({"name": "X", "type": "BV", "p": "s", "n": "a",
                      "expr": " + ".join(lead)})
    return added, repl


def torques(key: str, val: Any) -> list[dict]:
    """The fan-side (or rotor-side) components of one mechanical effect."""
    out = []
    w = f"tanh({{n}}.w/{sm.W_SIGN!r}[rad/s])"
    if key == "cog":
        for node, harm in val.items():
            for j, (order, a, b) in enumerate(harm):
                out.append({"name": f"CG{node}{j}", "type": "btorque", "shaft": node,
                            "expr": f"{a!r}[N*m]*sin({order}*{node}.phi) + "
                                    f"{b!r}[N*m]*cos({order}*{node}.phi)"})
    elif key == "coul":
        out += [{"name": f"FX{node}", "type": "friction", "shaft": node, "tau_c": c,
                 "w_brk": 0.1} for node, c in val.items()]
    elif key == "visc":
        out += [{"name": f"BX{node}", "type": "damper", "shaft": node, "b": b}
                for node, b in val.items()]
    elif key == "stribeck":
        out += [{"name": f"ST{node}", "type": "btorque", "shaft": node,
                 "expr": f"-{s!r}[N*m]*exp(-({node}.w/{ws!r}[rad/s])^2)*"
                         + w.format(n=node)} for node, (s, ws) in val.items()]
    elif key == "rub":
        tr, kappa, ph = val
        out.append({"name": "RUB", "type": "btorque", "shaft": "fan",
                    "expr": f"-{tr!r}[N*m]*exp({kappa!r}*(cos(fan.phi - {ph!r}) - 1))*"
                            + w.format(n="fan")})
    elif key == "damper":
        drop, t1, tr = val
        out.append({"name": "DMP", "type": "btorque", "shaft": "fan",
                    "expr": f"cf*{drop!r}*(1 + tanh((t - {t1!r}[s])/{tr!r}[s]))/2*"
                            "fan.w*abs(fan.w)"})
    return out


def netlist_copy(folder: Path, regime: str, edit: Edit | None) -> Path:
    """The regime's netlist, its include and its table copied into ``folder`` with the
    components of ``edit`` added (the supply moved to node ``s`` behind a lead element) and
    replaced; returns the regime file's path."""
    (folder / "inputs").mkdir(parents=True, exist_ok=True)
    shutil.copy(NETS / "inputs" / "motor_m_profile.csv", folder / "inputs")
    motor = yaml.safe_load((NETS / MOTOR_FILE).read_text())
    top = yaml.safe_load((NETS / FILES[regime]).read_text())
    if edit is not None:
        added, repl = edit
        motor["components"] = [repl.get(c["name"], c) for c in motor["components"]]
        if any(c.get("p") == "s" for c in added):
            top["components"][0]["p"] = "s"
        top["components"] = top["components"] + added
    (folder / MOTOR_FILE).write_text(yaml.safe_dump(motor, sort_keys=False))
    path = folder / f"variant_{regime}.yaml"
    path.write_text(yaml.safe_dump(top, sort_keys=False))
    return path


# ---------------------------------------------------------------------- comparison

def compare(cs: Any, s: dict, label: str, fx: dict, edit: Edit | None) -> float:
    """The largest |scipy - circuitsim| over a probe's range at the record's times,
    printed per probe with the effect's own size on that scale."""
    regime, t = s["regime"], times(s)
    ref = sm.simulate(regime, t, fx)
    base = sm.simulate(regime, t) if fx else None
    with tempfile.TemporaryDirectory(prefix="validate-m-") as tmp:
        net = cs.load(netlist_copy(Path(tmp), regime, edit))
        t0 = time.perf_counter()
        res = cs.compile(net).simulate(stop=float(t[-1]), t_eval=t, rtol=1e-10, atol=1e-12)
        t_cs = time.perf_counter() - t0
    worst = 0.0
    for pr in sm.PROBES[regime]:
        a, b = np.asarray(ref[pr]), np.asarray(res[pr])
        rng = float(np.ptp(b))
        mx = float(np.max(np.abs(a - b)) / rng)
        rms = float(np.sqrt(np.mean((a - b) ** 2)) / np.std(b))
        worst = max(worst, mx)
        size = "" if base is None else \
            f"; effect {np.max(np.abs(a - base[pr])) / rng:.1e} of range"
        print(f"motor M {regime:4s} {label:40s} {pr:10s}: max |diff|/range {mx:.1e}, "
              f"rms/std {rms:.1e} (range {rng:.4g}{size}; circuitsim {t_cs:.1f} s)",
              flush=True)
    return worst


def check(cs: Any, s: dict, nulls: set[str]) -> float:
    """One record's comparisons (the worst difference over a probe's range), or 0."""
    worst = 0.0
    times(s)
    if s["id"] in nulls:
        kind = "uneven" if "timestamps" in s else "even"
        worst = compare(cs, s, f"null on {s['id']}'s {kind} times", {}, None)
    if s["class"] == "null":
        return worst
    edit = laws(s["fx"])
    if edit is None:
        print(f"motor M {s['regime']:4s} {s['id']} {s['class']}: a law no component states "
              "(not compared)")
        return worst
    # the id and class only: the effects stay in truth.json (the set is blind)
    return max(worst, compare(cs, s, f"{s['id']} {s['class']}, as components", s["fx"],
                              edit))


def main(select: Callable[[dict], bool] = lambda s: True) -> int:
    """The null of each regime on several records' times and every record whose law
    components state; exit status 1 above TARGET."""
    os.environ.setdefault("CIRCUITSIM_CACHE", tempfile.mkdtemp(prefix="diagbench-cache-"))
    warnings.simplefilter("ignore")
    import circuitsim as cs

    worst = 0.0
    for s in record_specs():
        if not select(s):
            continue
        if s["marginal"] is not None:
            scale_marginal(s)
        worst = max(worst, check(cs, s, {"u01", "u02", "u03", "u06"}))
    print(f"worst max |diff|/range {worst:.2e} -> {'OK' if worst < TARGET else 'ABOVE'} "
          f"(target {TARGET:g})")
    return 0 if worst < TARGET else 1


if __name__ == "__main__":
    sys.exit(main())
