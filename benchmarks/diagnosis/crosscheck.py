"""What the validate_g/h/j/k.py cross-checks share: a truth's catalog effects as the catalog's
own netlist patches (the declared netlist carrying each effect's patch at the truth's values
must give what the scipy simulator gives with the effect written out by hand), and the
comparison of a scipy model with circuitsim on the record grid. Each motor's simulator stays
its own, written independently; only this plumbing is shared."""

from __future__ import annotations

import ast
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

UNITS = {"current": "A", "speed": "rad/s", "load_speed": "rad/s"}
#: the truth's physical names -> the catalog's parameter suffixes
SUFFIX = {"gain": "g", "offset": "o", "delay": "tau"}


def circuitsim_imports(path: Path) -> list[str]:
    """The modules of circuitsim that the Python source ``path`` imports (any line of it,
    at any depth)."""
    found = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            names = [node.module or ""]
        else:
            continue
        found += [n for n in names if n == "circuitsim" or n.startswith("circuitsim.")]
    return found


def own_code_clean(folder: Path, names: Sequence[str]) -> bool:
    """Whether the blind set's own code (``names`` in ``folder``: its generator, its
    simulator, recordkit) imports nothing of circuitsim; prints each file's imports."""
    clean = True
    for name in names:
        bad = circuitsim_imports(folder / name)
        loop = [m for m in bad if m.startswith("circuitsim.loop")]
        print(f"{name}: imports of circuitsim: {bad or 'none'}"
              + (f" (the diagnosis's package: {loop})" if loop else ""))
        clean = clean and not bad
    return clean


def truth_patch(net: Any, effects: list[dict], probes: Sequence[str], duration: float
                ) -> tuple[Any, dict[str, float]]:
    """The declared netlist's raw form with each truth effect's catalog patch applied, and
    the patch parameters' values [SI]; ``probes``: the record's probes, ``duration``: its
    length [s] (a warm-up's time constant starts from it)."""
    from circuitsim.loop.effects import candidates

    orders: dict[str, list[int]] = {}
    for e in effects:
        if "order" in e:
            shaft = "rotor" if e["effect"] == "emf-harmonic" else e["target"]
            orders.setdefault(shaft, []).append(int(e["order"]))
    pool = candidates(net, orders=orders, probes={p: UNITS[p] for p in probes},
                      duration=duration)
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


def compare(cs: Any, sim: Any, motor: str, nominal: Mapping[str, float],
            netlists: Mapping[str, Path], regime: str, label: str, fx: dict, raw: Any = None,
            values: Mapping[str, float] | None = None) -> float:
    """The largest |scipy - circuitsim| over a probe's range on the record grid, printed per
    probe with the rms difference and the effect's own size. ``sim``: the motor's simulator
    module (``grid``, ``simulate``, ``PROBES``), ``nominal``: its declared parameters,
    ``fx``: the effects written out for it (``"p"``: parameters changed), ``raw`` and
    ``values``: the netlist to run instead of the declared one, and its parameters."""
    from circuitsim.netlist.load import build

    t = sim.grid(regime)
    fx = dict(fx)
    p = {**nominal, **fx.pop("p", {})}
    ref = sim.simulate(regime, t, fx, p)
    base = sim.simulate(regime, t) if (fx or p != dict(nominal)) else None
    net = cs.load(netlists[regime]) if raw is None else build(raw)
    t0 = time.perf_counter()
    res = cs.compile(net).simulate(stop=float(t[-1]), t_eval=t, params=values or None,
                                   rtol=1e-10, atol=1e-12)
    t_cs = time.perf_counter() - t0
    worst = 0.0
    for pr in sim.PROBES[regime]:
        a, b = np.asarray(ref[pr]), np.asarray(res[pr])
        rng = float(np.ptp(b))
        mx = float(np.max(np.abs(a - b)) / rng)
        rms = float(np.sqrt(np.mean((a - b) ** 2)) / np.std(b))
        worst = max(worst, mx)
        size = "" if base is None else \
            f"; effect {np.max(np.abs(a - base[pr])) / rng:.1e} of range"
        print(f"motor {motor} {regime:4s} {label:52s} {pr:10s}: max |diff|/range {mx:.1e}, "
              f"rms/std {rms:.1e} (range {rng:.4g}{size}; circuitsim {t_cs:.1f} s)",
              flush=True)
    return worst


def check_set(cs: Any, motor: str, specs: list[dict], scale_marginal: Any, patched: Any,
              outside_laws: Mapping[str, Any], compare: Any, netlists: Mapping[str, Path],
              target: float) -> int:
    """The null of each regime, every catalog and two-effect record through the catalog's
    own patch, and every outside record whose law a component states, against the scipy
    model; prints the worst difference and returns the exit status (0: below ``target``)."""
    worst = max(compare(cs, r, "null", {}) for r in ("fast", "slow"))
    for s in specs:
        regime = s["regime"]
        if s["marginal"] is not None:
            scale_marginal(s)
        if s["class"] in ("catalog", "two"):
            raw, values = patched(cs.load(netlists[regime]), regime, s["effects"])
            # the id and class only: the effects stay in truth.json (the set is blind)
            label = f"{s['id']} {s['class']}, the catalog's patch"
            worst = max(worst, compare(cs, regime, label, s["fx"], raw, values))
        elif s["class"] == "outside":
            law = next((f for k, f in outside_laws.items() if k in s["fx"]), None)
            if law is None:
                print(f"motor {motor} {regime:4s} {s['id']} outside: no component states its "
                      "law (not compared)")
                continue
            raw = cs.load(netlists[regime]).raw.copy()
            law(raw, s["fx"])
            worst = max(worst, compare(cs, regime, f"{s['id']} outside, as components",
                                       s["fx"], raw))
    print(f"worst max |diff|/range {worst:.2e} -> {'OK' if worst < target else 'ABOVE'} "
          f"(target {target:g})")
    return 0 if worst < target else 1


def check_records(cs: Any, specs: list[dict], times: Any, scale_marginal: Any, check: Any,
                  target: float, argv: Sequence[str] = ()) -> int:
    """Each record of a set sampled at its own times (``times`` fills them in), marginal
    ones scaled first, through the set's ``check`` (worst difference relative to a probe's
    range); ``argv[0]``, when given, selects record ids, comma-separated. Prints the worst
    difference and returns the exit status (0: below ``target``)."""
    only = set(argv[0].split(",")) if argv else None
    worst = 0.0
    for s in specs:
        if only and s["id"] not in only:
            continue
        times(s)
        if s["marginal"] is not None:
            scale_marginal(s)
        worst = max(worst, check(cs, s))
    print(f"worst max |diff|/range {worst:.2e} -> {'OK' if worst < target else 'ABOVE'} "
          f"(target {target:g})")
    return 0 if worst < target else 1
