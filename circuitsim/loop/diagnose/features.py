"""The diagnosis on features (steady values, harmonic amplitudes and frequencies)."""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from typing import Any

from circuitsim.errors import CircuitsimError
from circuitsim.loop.diagnose.context import MAX_EFFECTS, compile_raw
from circuitsim.loop.diagnose.decide import BIC_MARGIN
from circuitsim.loop.diagnose.netlist_out import _with_values, build_raw
from circuitsim.loop.diagnose.result import Accepted, Diagnosis, DiagnosisError


def diagnose_features(netlist, features, free: Sequence[str] = (), *,
                      max_effects: int = MAX_EFFECTS,
                      params: Mapping[str, float] | None = None,
                      progress=None) -> Diagnosis:
    """The diagnosis on features (steady values, harmonic amplitudes and frequencies).

    A handful of numbers carries no spectrum and no whiteness: every candidate of the catalog
    is refitted directly (``fit.fit_features``; effects invisible at their null value start
    from their grid), and one is accepted when it lowers chi-square by more than
    ``BIC_MARGIN`` + k ln n and by at least half; repeated greedily. Features need sigmas.
    """
    import time

    from circuitsim.loop import effects
    from circuitsim.netlist.load import Netlist, load

    say = progress or (lambda msg: None)
    start = time.perf_counter()
    net = netlist if isinstance(netlist, Netlist) else load(netlist)
    _need_sigmas(features)
    n = len(features.features)
    run = _runner(features)
    model = compile_raw(net.raw)
    fit0 = run(model, list(free), dict(params or {}), {})
    raw, cur_free, params, bounds, fit = net.raw, list(free), dict(fit0.params), {}, fit0
    accepted: list[Accepted] = []
    rejected: list[dict[str, Any]] = []
    indistinct: list[str] = []
    tried: set[str] = set()
    while len(accepted) < max_effects:
        c0 = chi2(fit)
        if c0 <= BIC_MARGIN + math.log(max(n, 2)):
            break  # no effect could lower chi-square by what acceptance asks: stop here
        best, round_results = _features_round(
            effects.candidates(build_raw(raw)), tried, raw, cur_free, params, bounds, n, run,
            chi2, rejected, say, c0)
        if best is None:
            break
        cand, f, b = best
        tried.add(cand.key)
        k = len(cand.free)
        if not (c0 - chi2(f) > BIC_MARGIN + k * math.log(max(n, 2)) and chi2(f) < 0.5 * c0):
            rejected.append({"effect": cand.effect, "target": cand.target,
                             "chi2_before": c0, "chi2_after": chi2(f),
                             "reason": "not significant"})
            break
        indistinct += _ties(cand, f, round_results, chi2, indistinct)
        raw = cand.apply(raw)
        cur_free += list(cand.free)
        params, bounds, fit = dict(f.params), b, f
        accepted.append(Accepted(
            cand.effect, cand.target, {nm: f.estimate[nm] for nm in cand.free},
            {nm: (f.stderr[nm] if math.isfinite(f.stderr[nm]) else None)
             for nm in cand.free}, f.error,
            {"what": cand.what, "chi2_before": c0, "chi2_after": chi2(f),
             "predicted": dict(f.predicted),
             **_interpolation(len(cur_free), n)}))
        say(f"accepted {cand.key}: chi2 {chi2(f):.4g}")
    return _features_report(raw, fit0, fit, n, accepted, indistinct, rejected,
                            time.perf_counter() - start)


def _features_report(raw, fit0, fit, n: int, accepted, indistinct, rejected,
                     seconds: float) -> Diagnosis:
    left = chi2(fit)
    remaining = {"structure": bool(left > n + 3 * math.sqrt(2 * n)), "chi2": left,
                 "note": f"chi-square {left:.3g} for {n} features"}
    return Diagnosis(fit0.error, fit.error, dict(fit0.errors), dict(fit.errors), accepted,
                     indistinct, remaining, {"predicted": dict(fit0.predicted)},
                     {"predicted": dict(fit.predicted)}, _with_values(raw, fit.params), fit0,
                     fit, None, {"total": seconds}, rejected)


def _features_round(cands, tried, raw, cur_free, params, bounds, n, run, chi2, rejected, say,
                    c0):
    """Refit every untried candidate on the features; the best, and every result."""
    best = None
    results: list[tuple[Any, float]] = []
    for cand in cands:
        if cand.key in tried:
            continue
        m = compile_raw(cand.apply(raw))
        b = {**bounds, **{k: (lo, hi) for k, (_, lo, hi) in cand.free.items()}}
        starts = [{}]
        if cand.grid:  # saturation: start from knee currents around the operating point
            first = next(iter(cand.free))
            starts = [{first: g} for g in (1e-3, 1e-2, 0.1, 1.0)]
        for st in starts:
            try:
                f = run(m, [*cur_free, *cand.free],
                        {**params, **{k: v[0] for k, v in cand.free.items()}, **st}, b)
            except CircuitsimError:
                continue
            say(f"  {cand.key}: chi2 {c0:.4g} -> {chi2(f):.4g}")
            results.append((cand, chi2(f)))
            if best is None or chi2(f) < chi2(best[1]):
                best = (cand, f, b)
    return best, results


def _ties(cand, f, results, chi2, known) -> list[str]:
    out = []
    for other, x2 in results:
        if other.key != cand.key and x2 - chi2(f) < BIC_MARGIN and \
                not any(other.effect in t and other.target in t for t in [*known, *out]):
            out.append(f"{cand.effect} on {cand.target} and {other.effect} on "
                       f"{other.target} explain these features almost equally "
                       f"well (chi-square {chi2(f):.3g} vs {x2:.3g}): the data "
                       f"cannot tell them apart")
    return out


def _interpolation(k: int, n: int) -> dict[str, str]:
    """As many free parameters as feature numbers (or more) fit them exactly whatever the
    physics: such a fit is interpolation, not evidence, and is labelled so."""
    if k < n:
        return {}
    return {"interpolation": f"{k} free parameters on {n} feature numbers: an exact fit is "
                             f"interpolation, not evidence for this effect"}


def chi2(f) -> float:
    """Chi-square of a features fit (its errors are in sigmas)."""
    return float(sum(v**2 for v in f.errors.values()))


def _runner(features):
    from circuitsim.loop.fit import fit_features

    def run(model, free_, params_, bounds_):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return fit_features(model, features, free_, params=params_,
                                bounds={k: v for k, v in bounds_.items() if k in free_} or None)

    return run


def _need_sigmas(features) -> None:
    if any(f.sigma is None for f in features.features):
        raise DiagnosisError(f"{features.path}: every feature needs a sigma for the "
                             f"diagnosis (its chi-square decides)")
