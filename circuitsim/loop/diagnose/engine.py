"""Close the loop: trace a model's residual against a measured record to a physical effect.

1. Fit the declared free parameters (``fit.fit_record``, staged so that a ripple locked to the
   rotor angle cannot trap it) and compute the residual of every probe.
2. Analyse it: RMS and NRMSE per probe; spectrum with peaks labelled as orders of the shaft
   frequency; whiteness (Ljung-Box); correlation with candidate regressors; the noise floor
   (from first differences, which white noise inflates and smooth structure does not).
3. Score every effect of the catalog (``effects``: netlist patches exact at their null
   value), with harmonic orders taken from the residual spectrum: a score test projects the
   residual on each candidate's sensitivity at its null value (one short simulation per free
   parameter); effects a linearisation cannot see (saturation) are screened on a small grid.
   The best few are refitted with full simulation.
4. Accept an effect only when the Bayesian information criterion falls by more than
   ``BIC_MARGIN`` *and* it explains at least ``EXCESS_FRACTION`` of the residual above the
   noise floor (so a slice of an effect outside the catalog is no confident attribution).
   Repeat greedily; stop when nothing significant remains.
5. Report the error before and after, the effects in order with parameters, standard errors
   and evidence, what could not be told apart, and what structure remains.

Top-level imports stay light (numpy only): the CLI imports this module on every call.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, MutableMapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from circuitsim.errors import CircuitsimError
from circuitsim.loop.diagnose.residual import _orders, analyse
from circuitsim.loop.diagnose.result import Accepted, Diagnosis, DiagnosisError

BIC_MARGIN = 10.0  # "very strong" evidence on the Kass-Raftery scale
EXCESS_FRACTION = 0.3  # share of the above-noise residual an accepted effect must explain
SCREEN_TOP = 4  # candidates refitted with full simulation per round
MAX_EFFECTS = 4


# ------------------------------------------------------------------ residual analysis


# --------------------------------------------------------------------- the engine

@dataclass
class _State:
    """The model as it stands in the greedy loop."""

    raw: Any
    model: Any
    free: list[str]
    params: dict[str, float]
    fit: Any
    bounds: dict[str, tuple[float, float]]


def _compile(raw):
    from circuitsim.compiler.model import compile as compile_model
    from circuitsim.netlist.load import build

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return compile_model(build(raw))


def _normalised(record, probes, sims_or_residuals, spread) -> np.ndarray:
    return np.concatenate([np.asarray(sims_or_residuals[p]) / s
                           for p, s in zip(probes, spread, strict=True)])


def _sse(fit_res, probes, spread) -> float:
    e = _normalised(None, probes, fit_res.residuals, spread)
    return float(e @ e)


def _simulate(model, record, params, rtol):
    res = model.simulate(stop=float(record.t[-1]), params=params, t_eval=record.t,
                         rtol=rtol, atol=model.netlist.analysis.atol)
    if not res.success or res.t.size != record.t.size:
        return None
    return res


def _screen(cand, state: _State, record, probes, spread, e0: np.ndarray, rtol: float,
            project, noise: float = 0.0) -> dict[str, Any] | None:
    """Score test of one candidate: how much of the residual its sensitivity explains.

    ``noise``: the norm of the simulation's own error in the projected space; a candidate
    whose sensitivity stays within a few times it, however large the step, acts on nothing
    that is measured (a resistance in series with an ideal source's shunt) and is dropped --
    its "gain" would be solver noise fitted to the residual."""
    model = _compile(cand.apply(state.raw))
    base = {**state.params, **{k: v[0] for k, v in cand.free.items()}}
    y0 = _simulate(model, record, base, rtol)
    if y0 is None:
        return None
    if cand.grid:  # invisible to a linearisation at null: try a few values instead
        first = next(iter(cand.free))
        scale = max(float(np.max(np.abs(y0[f"{cand.target}.i"]))), 1e-9) \
            if f"{cand.target}.i" in y0.names else 1.0
        best = None
        for g in cand.grid:
            trial = {**base, first: g * scale}
            y = _simulate(model, record, trial, rtol)
            if y is None:
                continue
            e = e0 - (project(y) - project(y0))
            gain = float(e0 @ e0 - e @ e)
            if best is None or gain > best["gain"]:
                best = {"gain": gain, "start": {first: g * scale}, "S": None}
        return best and {**best, "model": model}
    cols = []
    for name in cand.free:
        h = cand.steps.get(name, 1e-3)
        for _ in range(3):
            y = _simulate(model, record, {**base, name: base[name] + h}, rtol)
            if y is None:
                return None
            col = (project(y) - project(y0)) / h
            size = float(np.linalg.norm(col * h))
            if size < max(1e-4 * math.sqrt(col.size) * 1e-3, 10 * noise):
                h *= 100  # invisible above the solver's noise: a bigger step
            elif size > 0.3 * math.sqrt(col.size):
                h /= 30  # far from linear: a smaller one
            else:
                break
        else:
            if size < 10 * noise:
                return None
        cols.append(col)
    S = np.column_stack(cols)
    coef, *_ = np.linalg.lstsq(S, e0, rcond=None)
    gain = float(e0 @ (S @ coef))
    start = {n: base[n] + float(c) for n, c in zip(cand.free, coef, strict=True)}
    return {"gain": gain, "start": start, "S": S, "model": model}


def diagnose(netlist, record, free: Sequence[str] = (), *, probes: Sequence[str] | None = None,
             max_effects: int = MAX_EFFECTS, screen_top: int = SCREEN_TOP,
             rtol: float = 1e-8, params: Mapping[str, float] | None = None,
             progress=None) -> Diagnosis:
    """Find what the netlist lacks to explain ``record`` (see the module docstring).

    Parameters
    ----------
    netlist : a Netlist (``circuitsim.load``) or a path.
    record : a ``data.Record`` (time series).
    free : declared free parameters, fitted first and kept free throughout.
    probes : probe columns to use (default: every probe the record has).
    """
    import time

    from circuitsim.compiler.model import compile as compile_model
    from circuitsim.loop import effects
    from circuitsim.loop.fit import fit_record, slow_features, smoothing_windows
    from circuitsim.netlist.load import Netlist, load

    say = progress or (lambda msg: None)
    clock = {"start": time.perf_counter()}
    net = netlist if isinstance(netlist, Netlist) else load(netlist)
    if net.raw is None:
        raise DiagnosisError("this netlist has no raw form to patch; load it from a file")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = compile_model(net)
    probes = list(probes or [p for p in model.probe_names if p in record.names])
    if not probes:
        raise DiagnosisError(f"the record {record.path} has no column named like a probe of "
                             f"the netlist ({', '.join(model.probe_names)})")
    spread = np.array([max(float(np.std(record[p])), 1e-300) for p in probes])
    n_samples = record.t.size * len(probes)

    def refit(model_, free_, params_, bounds_, staged=False, nfev=12):
        # a candidate starts from its score-test estimate, inside the right basin: one
        # waveform stage with a few iterations is enough (the declared fit is staged)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            bounds_ = {k: v for k, v in (bounds_ or {}).items() if k in free_}
            return fit_record(model_, record, free_, params=params_, bounds=bounds_ or None,
                              probes=probes, rtol=rtol, staged=staged,
                              max_nfev=100 if staged else nfev)

    fit0 = refit(model, list(free), dict(params or {}), {}, staged=True)
    clock["fit"] = time.perf_counter() - clock["start"]
    state = _State(net.raw, model, list(free), dict(fit0.params), fit0, {})
    analysis0 = analyse(model, record, fit0, probes)
    sigma2 = sum(analysis0["probes"][p]["noise_sigma"] ** 2 / s**2 * record.t.size
                 for p, s in zip(probes, spread, strict=True))
    accepted: list[Accepted] = []
    chosen: list[Any] = []  # the accepted candidates, in order
    alternatives: list[list[tuple[Any, dict[str, float]]]] = []  # near-equals per round
    rejected: list[dict[str, Any]] = []
    indistinct: list[str] = []
    tried: set[str] = set()
    analysis = analysis0
    screen_time = refit_time = 0.0
    # Screening compares phase-insensitive slow features (windowed means and ripple RMS,
    # as the fit's first stage): a ripple locked to the rotor angle slides out of phase as
    # soon as an effect changes the speed, and a linearisation of the raw waveform then
    # points anywhere. The BIC that decides is computed on the refitted waveform.
    W = smoothing_windows(record.t, [np.asarray(record[p]) for p in probes])

    def project(y) -> np.ndarray:
        return np.concatenate([slow_features(W, np.asarray(y[p])) / sp_
                               for p, sp_ in zip(probes, spread, strict=True)])

    def wave(y) -> np.ndarray:
        return np.concatenate([np.asarray(y[p]) / sp_ for p, sp_ in zip(probes, spread,
                                                                          strict=True)])

    rotating = bool(model.meta.get("integrals")) and any(
        d == "rotational" for d in model.meta.get("integrals", {}).values())
    measured_features = project(record)
    measured_wave = wave(record)
    while len(accepted) < max_effects:
        sse0 = _sse(state.fit, probes, spread)
        excess = max(sse0 - sigma2, 0.0)
        # A harmonic of the shaft angle leaves the speed alone to first order, so its score
        # test can use the waveform itself, where the phase tells cogging (a torque) from
        # an EMF harmonic (a voltage); everything else is screened on the slow features.
        spaces = {False: (measured_features - project(state.fit.sim), project),
                  True: (measured_wave - wave(state.fit.sim), wave)}
        if not rotating:  # no shaft angle: no phase to slide, the waveform is best
            spaces[False] = spaces[True]
        t0 = time.perf_counter()
        # the simulation's own error: the same model at a slightly different tolerance
        alt = _simulate(state.model, record, state.params, rtol * 1.5)
        noise = {False: 0.0, True: 0.0} if alt is None else {
            k: float(np.linalg.norm(fn(alt) - fn(state.fit.sim)))
            for k, fn in ((False, spaces[False][1]), (True, spaces[True][1]))}
        cands = [c for c in effects.candidates(load_raw_netlist(state.raw),
                                               _orders(analysis))
                 if c.key not in tried and c.key not in {x.key for x in chosen}]
        scored = []
        for c in cands:
            say(f"screening {c.key}")
            e0, space = spaces["order" in c.fixed]
            s = _screen(c, state, record, probes, spread, e0, rtol, space,
                        noise["order" in c.fixed])
            if s is not None and s["gain"] > 0:
                # gains in the two spaces are compared as shares of their own residual
                s["share"] = s["gain"] / float(e0 @ e0)
                s["n"] = e0.size
                scored.append((c, s))
        scored.sort(key=lambda cs: -cs[1]["share"])
        # A candidate whose best linear gain cannot pay its BIC penalty will not pass after
        # a refit either (the score test is exact for effects linear in their parameters):
        # refitting it would only cost simulations.
        # ... nor one that explains less than a tenth of what the best one does
        top = scored[0][1]["share"] if scored else 0.0
        scored = [(c, s) for c, s in scored if s["share"] >= 0.1 * top]
        scored = [(c, s) for c, s in scored
                  if s["share"] > 0.5 * (1 - math.exp(-(BIC_MARGIN + len(c.free) *
                                                        math.log(s["n"])) / s["n"]))]
        screen_time += time.perf_counter() - t0
        if not scored:
            break
        t0 = time.perf_counter()
        best = None
        results = []
        top_set = scored[:screen_top]
        # neighbouring orders of one harmonic effect score alike when the speed changes
        # through the record (order 35 fits a drifting order-36 ripple almost as well): the
        # linear screen cannot rank such near-ties, so the refit gets all of them
        for c, s in scored[screen_top:]:
            if "order" in c.fixed and any(
                    c2.effect == c.effect and c2.target == c.target and "order" in c2.fixed
                    and abs(c2.fixed["order"] - c.fixed["order"]) <= 1
                    and s["share"] >= 0.8 * s2["share"] for c2, s2 in top_set):
                top_set.append((c, s))
        for c, s in top_set:
            say(f"refitting {c.key}")
            free_c = [*state.free, *c.free]
            params_c = {**state.params, **s["start"]}
            bounds_c = dict(state.bounds)
            for n, (_, lo, hi) in c.free.items():
                # the score test's linear estimate may fall outside the physical range
                # (a negative viscous coefficient): start on the edge instead
                params_c[n] = min(max(params_c[n], lo), hi)
                bounds_c[n] = (lo, hi)
            try:
                f = refit(s["model"], free_c, params_c, bounds_c)
            except CircuitsimError as exc:
                rejected.append({"effect": c.effect, "target": c.target,
                                 "reason": f"refit failed: {exc.bare}"})
                continue
            sse = _sse(f, probes, spread)
            say(f"  {c.key}: SSE {sse0:.5g} -> {sse:.5g}")
            k = len(c.free)
            dbic = n_samples * math.log(max(sse, 1e-300) / sse0) + k * math.log(n_samples)
            entry = (dbic, c, s, f, sse)
            results.append(entry)
            if best is None or dbic < best[0]:
                best = entry
        refit_time += time.perf_counter() - t0
        if best is None:
            break
        dbic, c, s, f, sse = best
        explained = (sse0 - sse) / excess if excess > 0 else 0.0
        tried.add(c.key)
        if not (dbic < -BIC_MARGIN and explained >= EXCESS_FRACTION):
            rejected.append({"effect": c.effect, "target": c.target, "delta_bic": dbic,
                             "explained_fraction": explained,
                             "reason": "not significant" if dbic >= -BIC_MARGIN else
                             "explains too little of the residual above the noise"})
            break
        # which other candidates explain the same thing: a refit nearly as good, or a
        # sensitivity of the same shape
        for dbic2, c2, _, _, _ in results:
            if c2 is not c and dbic2 - dbic < BIC_MARGIN:
                indistinct.append(f"{c.effect} on {c.target} and {c2.effect} on {c2.target} "
                                  f"explain this record almost equally well (BIC "
                                  f"{dbic:.1f} vs {dbic2:.1f}): the data cannot tell them "
                                  f"apart")
        # the short refit decided; polish the accepted model with a full fit, from there
        polish_bounds = {**state.bounds, **{n: (min(lo, f.params[n]), max(hi, f.params[n]))
                                            for n, (_, lo, hi) in c.free.items()}}
        try:
            f = refit(s["model"], [*state.free, *c.free], dict(f.params), polish_bounds,
                      nfev=40)
            sse = _sse(f, probes, spread)
        except CircuitsimError:
            pass
        raw = c.apply(state.raw)
        chosen.append(c)
        alternatives.append([(c2, {n: f2.params[n] for n in c2.free})
                             for _, c2, _, f2, sse2 in results
                             if c2 is not c and sse2 < 1.1 * sse])
        state = _State(raw, s["model"], [*state.free, *c.free], dict(f.params), f,
                       {**state.bounds, **{n: (lo, hi) for n, (_, lo, hi) in c.free.items()}})
        analysis = analyse(state.model, record, f, probes)
        peak = next((pk for pr in analysis0["probes"].values() for pk in pr["peaks"]
                     if c.fixed.get("order") in pk["orders"].values()), None)
        accepted.append(Accepted(
            c.effect, c.target,
            {**{n: f.estimate[n] for n in c.free}, **({"order": c.fixed["order"]}
                                                      if "order" in c.fixed else {})},
            {n: (f.stderr[n] if math.isfinite(f.stderr[n]) else None) for n in c.free},
            f.error,
            {"what": c.what, "delta_bic": dbic, "explained_fraction": explained,
             "screen_gain": s["gain"], "spectral_peak": peak,
             "sse_before": sse0, "sse_after": sse}))
        say(f"accepted {c.key}: error {f.error:.4g}")
        # Forward selection is greedy: an effect chosen while another was still missing may
        # have been a stand-in for a near-equal alternative (viscous friction for Coulomb
        # friction while a cogging ripple blurred the record). Revisit earlier choices.
        state = _revisit(state, chosen, alternatives, accepted, net.raw, list(free), refit,
                         probes, spread, n_samples, say)
    final = state.fit
    analysis_after = analysis
    sse_end = _sse(final, probes, spread)
    left = max(sse_end - sigma2, 0.0) / sse_end if sse_end > 0 else 0.0
    white = all(pr["whiteness"]["white"] for pr in analysis_after["probes"].values())
    peaks = [pk for pr in analysis_after["probes"].values() for pk in pr["peaks"]]
    remaining = {"structure": bool(left > 0.2 or not white),
                 "above_noise_fraction": left, "white": white,
                 "peaks": peaks[:6],
                 "note": (f"{left:.0%} of the residual is above the noise floor" +
                          ("" if white else ", the residual is not white") +
                          ("; peaks at " + ", ".join(f"{pk['frequency']:.4g} Hz"
                                                     for pk in peaks[:3]) if peaks else ""))}
    clock_total = time.perf_counter() - clock["start"]
    raw = _with_values(state.raw, final.params)
    return Diagnosis(fit0.error, final.error, dict(fit0.errors), dict(final.errors), accepted,
                     indistinct, remaining, analysis0, analysis_after, raw, fit0, final, record,
                     {"fit_declared": clock["fit"], "screen": screen_time, "refit": refit_time,
                      "total": clock_total}, rejected)


def _revisit(state: _State, chosen, alternatives, accepted, base_raw, declared, refit,
             probes, spread, n_samples, say) -> _State:
    """Swap an earlier accepted effect for one of its near-equal alternatives when, with the
    later effects in place, the swap lowers the BIC by more than ``BIC_MARGIN``."""
    sse_now = _sse(state.fit, probes, spread)
    for i in range(len(chosen) - 1):
        for alt, alt_start in alternatives[i]:
            trial = [*chosen[:i], alt, *chosen[i + 1:]]
            raw = base_raw
            for c in trial:
                raw = c.apply(raw)
            params = {k: v for k, v in state.params.items() if k not in chosen[i].free}
            params.update(alt_start)
            free = [*declared, *(n for c in trial for n in c.free)]
            bounds = {n: (min(lo, params.get(n, st)), max(hi, params.get(n, st)))
                      for c in trial for n, (st, lo, hi) in c.free.items()}
            try:
                f = refit(_compile(raw), free, params, bounds)
            except CircuitsimError:
                continue
            sse = _sse(f, probes, spread)
            if n_samples * math.log(max(sse, 1e-300) / sse_now) < -BIC_MARGIN:
                say(f"revised: {alt.key} replaces {chosen[i].key}")
                old = chosen[i]
                chosen[i] = alt
                alternatives[i] = [(old, {n: state.params[n] for n in old.free})]
                a = accepted[i]
                a.effect, a.target = alt.effect, alt.target
                a.parameters = {**{n: f.estimate[n] for n in alt.free},
                                **({"order": alt.fixed["order"]} if "order" in alt.fixed
                                   else {})}
                a.stderr = {n: (f.stderr[n] if math.isfinite(f.stderr[n]) else None)
                            for n in alt.free}
                a.evidence = {**a.evidence, "what": alt.what,
                              "revised": f"replaced {old.effect} on {old.target} once "
                                         f"later effects were in place"}
                for b in accepted:
                    for n in list(b.parameters):
                        if n in f.estimate:
                            b.parameters[n] = f.estimate[n]
                accepted[-1].error_after = f.error
                state = _State(raw, _compile(raw), free, dict(f.params), f,
                               {**state.bounds, **bounds})
                sse_now = sse
                break
    return state


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
    from circuitsim.loop.fit import fit_features
    from circuitsim.netlist.load import Netlist, load

    say = progress or (lambda msg: None)
    start = time.perf_counter()
    net = netlist if isinstance(netlist, Netlist) else load(netlist)
    if any(f.sigma is None for f in features.features):
        raise DiagnosisError(f"{features.path}: every feature needs a sigma for the "
                             f"diagnosis (its chi-square decides)")
    n = len(features.features)

    def chi2(f) -> float:
        return float(sum(v**2 for v in f.errors.values()))

    def run(model, free_, params_, bounds_):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return fit_features(model, features, free_, params=params_,
                                bounds={k: v for k, v in bounds_.items() if k in free_} or None)

    model = _compile(net.raw)
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
        best = None
        round_results: list[tuple[Any, float]] = []
        for cand in effects.candidates(build_raw(raw)):
            if cand.key in tried:
                continue
            m = _compile(cand.apply(raw))
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
                round_results.append((cand, chi2(f)))
                if best is None or chi2(f) < chi2(best[1]):
                    best = (cand, f, b)
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
        for other, x2 in round_results:
            if other.key != cand.key and x2 - chi2(f) < BIC_MARGIN and \
                    not any(other.effect in t and other.target in t for t in indistinct):
                indistinct.append(f"{cand.effect} on {cand.target} and {other.effect} on "
                                  f"{other.target} explain these features almost equally "
                                  f"well (chi-square {chi2(f):.3g} vs {x2:.3g}): the data "
                                  f"cannot tell them apart")
        raw = cand.apply(raw)
        cur_free += list(cand.free)
        params, bounds, fit = dict(f.params), b, f
        accepted.append(Accepted(
            cand.effect, cand.target, {nm: f.estimate[nm] for nm in cand.free},
            {nm: (f.stderr[nm] if math.isfinite(f.stderr[nm]) else None)
             for nm in cand.free}, f.error,
            {"what": cand.what, "chi2_before": c0, "chi2_after": chi2(f),
             "predicted": dict(f.predicted)}))
        say(f"accepted {cand.key}: chi2 {chi2(f):.4g}")
    out = _with_values(raw, fit.params)
    left = chi2(fit)
    remaining = {"structure": bool(left > n + 3 * math.sqrt(2 * n)), "chi2": left,
                 "note": f"chi-square {left:.3g} for {n} features"}
    return Diagnosis(fit0.error, fit.error, dict(fit0.errors), dict(fit.errors), accepted,
                     indistinct, remaining, {"predicted": dict(fit0.predicted)},
                     {"predicted": dict(fit.predicted)}, out, fit0, fit, None,
                     {"total": time.perf_counter() - start}, rejected)


def _with_values(raw, params: Mapping[str, float]):
    """A copy of the raw netlist with the fitted (and overridden) values written in:
    netlist parameters by name, component parameters (``La.L``) in their component."""
    out = raw.copy()
    for name, v in params.items():
        if name in out.params:
            out.params[name] = (repr(float(v)), out.params[name][1])
        elif "." in name:
            comp, *path = name.split(".")
            node = out.component_entry(comp)
            # a waveform field ('V1.V.v1') sits one level down, under the waveform's kind:
            # V: {step: {v1: ...}}
            for key in path[:-1]:
                node = node[key]
                if isinstance(node, Mapping) and key not in ("table",) and len(node) == 1 \
                        and isinstance(next(iter(node.values())), Mapping):
                    node = next(iter(node.values()))
            if not isinstance(node, MutableMapping):
                raise DiagnosisError(f"cannot write the value of {name} into the netlist "
                                     f"(its entry is not a mapping); give it as a netlist "
                                     f"parameter instead")
            node[path[-1]] = float(v)
    return out


def build_raw(raw):
    from circuitsim.netlist.load import build

    return build(raw)


def load_raw_netlist(raw):
    """Type a raw netlist (for candidate generation on the current, patched netlist)."""
    from circuitsim.netlist.load import build

    return build(raw)


# ---------------------------------------------------------------------------- output


