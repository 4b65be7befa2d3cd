"""K parameter sets of one topology in one integration (finite differences, screening).

The K copies of the index-1 system are stacked into one DAE of K n unknowns with a
block-diagonal Jacobian and integrated by one IDA run: one call from the integrator per
residual evaluation for all K members (the per-call wrapper cost, most of a small model's
solve, is paid once), one step-size sequence, one factorisation of a band (small models) or
sparse (large ones) matrix. IDA's error test is a root-mean-square over all K n unknowns, so
the tolerances are divided by sqrt(K): each member's own error norm then stays within what it
would be allowed alone. Members share one step sequence, which also makes differences
between neighbouring parameter sets (finite differences) smooth. A batch that fails (one
member diverges) is re-run member by member, so each failure is reported for its own member.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence

import numpy as np

from circuitsim.solve.fork import fork_map, in_copy
from circuitsim.solve.init import consistent_initial
from circuitsim.solve.integrate import (
    Recorder,
    Settings,
    System,
    _finite,
    break_times,
    consistent_start,
    integrate_system,
    merged,
    settings,
    simulate,
)
from circuitsim.solve.result import SimResult, Status
from circuitsim.solve.route import kernels_requested
from circuitsim.solve.sources import bound_step

#: The largest stacked system [unknowns] solved as one band (the compiled kernels serve it)
BAND_MAX = 400


def simulate_batch(model, params_list: Sequence[Mapping[str, float] | None],
                   stop: float | None = None, *, step: float | None = None,
                   t_eval: np.ndarray | None = None, rtol: float | None = None,
                   atol: float | None = None, max_step: float | None = None,
                   init: str | None = None, nearby: bool = False) -> list[SimResult]:
    """One ``SimResult`` per parameter set, as ``simulate(model, stop, params, ...)`` would
    give (same options; see integrate.simulate), from one stacked integration.

    ``nearby``: the sets are small steps from one point (finite differences). Their errors
    are then alike, IDA's root-mean-square over all members is each member's own, and the
    tolerances are not tightened by sqrt(K) (which costs steps: three times the residual
    calls at K = 25)."""
    run = settings(model, stop, step, t_eval, rtol, atol, max_step, init)
    sets = [dict(q or {}) for q in params_list]
    n = len(model.state_names)
    # a switching model restarts at its own events: its members run one by one. Relations
    # of behavioural expressions are evaluated as written here (no events): a fit's
    # finite differences need one step sequence for all members, and the stacked run is
    # five times faster than one-by-one runs with events (EMPS fit: 46 s against 224 s)
    if len(sets) < 2 or n == 0 or model.meta.get("events"):
        return [simulate(model, run.stop, q, t_eval=run.t_eval, rtol=run.rtol, atol=run.atol,
                         max_step=run.max_step, init=run.init) for q in sets]
    if nearby and kernels_requested() and len(sets) * n > BAND_MAX and 2 * n <= BAND_MAX:
        return _in_chunks(model, run, sets, BAND_MAX // n)
    values = [model.param_values(q) for q in sets]
    run = dataclasses.replace(run, max_step=min(
        (bound_step(model, v, run.stop, run.t_eval, run.max_step) for v in values),
        key=lambda h: h if h > 0 else float("inf")))
    ps = [tuple(v[name] for name in model.meta["params"]) for v in values]
    starts = [consistent_start(model, run, q, p) for q, p in zip(sets, ps, strict=True)]
    if any(isinstance(s, str) for s in starts):  # report each member as it would alone
        return [_solo(model, run, q) for q in sets]
    # every member's corners, merged as one run's
    edges = merged(sorted({b for v in values for b in break_times(model, v, run.stop)}),
                   run.stop)
    rec = Recorder(None, 1)
    start = (np.concatenate([s[0] for s in starts]), np.concatenate([s[1] for s in starts]))
    status, _, nfev, njev = integrate_system(_stacked(model, run, ps, nearby), run,
                                             edges,
                                             start, rec, 50_000)
    if status is not Status.OK:
        return [_solo(model, run, q) for q in sets]
    t, y, yp = rec.arrays(len(sets) * n)
    return [_finite(SimResult(t, y[k * n:(k + 1) * n].copy(), yp[k * n:(k + 1) * n].copy(),
                              model.state_names, Status.OK, "", nfev, njev, model, p))
            for k, p in enumerate(ps)]


def _in_chunks(model, run: Settings, sets: list[dict], size: int) -> list[SimResult]:
    """Steps from one point (``nearby``) too many for one banded block, run as several
    batches of ``size`` members, each led by the first set (the point): a member's
    difference from the point is taken within its own batch, on one step sequence, and
    added to the first batch's run of the point -- the compiled kernels serve banded
    batches, and the sparse block of a larger one runs the Python residual (a blower's
    screen: 35 s a round)."""
    rest = list(range(1, len(sets)))
    groups = [rest[i:i + size - 1] for i in range(0, len(rest), size - 1)]

    def batch(g: list[int]) -> list[SimResult]:
        runs = simulate_batch(model, [sets[0], *(sets[i] for i in g)], run.stop,
                              t_eval=run.t_eval, rtol=run.rtol, atol=run.atol,
                              max_step=run.max_step, init=run.init, nearby=True)
        # the model does not pickle: a forked copy sends its runs without it
        return [dataclasses.replace(r, model=None) for r in runs] if in_copy() else runs

    out: list[SimResult] = []
    # the batches are independent: they share this machine's cores (solve/fork.py)
    for runs in fork_map(batch, groups):
        runs = [r if r.model is not None else dataclasses.replace(r, model=model)
                for r in runs]
        if not out:
            out.append(runs[0])
        out += [moved(out[0], runs[0], r) for r in runs[1:]]
    return out


def moved(point: SimResult, local: SimResult, member: SimResult) -> SimResult:
    """``member``'s difference from ``local`` (its batch's run of the point) added to
    ``point``; the member as it is when either run failed or their grids differ."""
    if not (point.success and local.success and member.success) or \
            member.t.shape != point.t.shape or member.y.shape != point.y.shape:
        return member
    return dataclasses.replace(member, t=point.t, y=point.y + (member.y - local.y),
                               yp=point.yp + (member.yp - local.yp), _obs=None,
                               _index={})


def _solo(model, run: Settings, params: dict) -> SimResult:
    return simulate(model, run.stop, params, t_eval=run.t_eval, rtol=run.rtol, atol=run.atol,
                    max_step=run.max_step, init=run.init)


def _stacked(model, run: Settings, ps: list[tuple], nearby: bool = False) -> System:
    """The block-diagonal system of K members: residual, Jacobian, IDA options, restart."""
    residual = model.fns[0]
    jac = model.jac_flat
    n, nd, K = len(model.state_names), model.meta["n_diff"], len(ps)
    rows, cols = (np.asarray(a, dtype=np.intp) for a in model.meta["jac_pattern"])
    nnz = rows.size
    sl = [slice(k * n, (k + 1) * n) for k in range(K)]

    def res_all(t, y, yp, res):
        for k in range(K):
            residual(t, y[sl[k]], yp[sl[k]], res[sl[k]], ps[k])

    # WRMS over K members <= 1  =>  each member's <= 1 when scaled by 1/sqrt(K)
    shrink = 1.0 if nearby else 1 / np.sqrt(K)
    opts = {"rtol": run.rtol * shrink, "atol": run.atol * shrink, "max_step": run.max_step,
            "max_num_steps": 200_000,
            "algebraic_idx": [k * n + j for k in range(K) for j in range(nd, n)] or None}
    if n * K <= BAND_MAX:  # small blocks: a band solver (bandwidth n - 1) on a dense template
        buf = np.zeros(nnz)
        r_all = np.concatenate([rows + k * n for k in range(K)])
        c_all = np.concatenate([cols + k * n for k in range(K)])

        def jac_all(t, y, yp, res, cj, JJ):
            vals = []
            for k in range(K):
                jac(t, y[sl[k]], yp[sl[k]], res[sl[k]], cj, buf, ps[k])
                vals.append(buf.copy())
            JJ[r_all, c_all] = np.concatenate(vals)

        opts.update(linsolver="band", lband=n - 1, uband=n - 1, jacfn=jac_all)
        if kernels_requested():  # IDA may call compiled kernels
            opts["kernels_of"] = (model, ps)  # (solve/direct.py)
    else:  # block k's nonzeros are the k-th contiguous run of the compressed columns
        import scipy.sparse as sps

        blocks = sps.block_diag([sps.csc_matrix((np.ones(nnz), (rows, cols)), shape=(n, n))]
                                * K, format="csc")
        blocks.sort_indices()

        def jac_all(t, y, yp, res, cj, JJ):
            for k in range(K):
                jac(t, y[sl[k]], yp[sl[k]], res[sl[k]], cj, JJ[k * nnz:(k + 1) * nnz], ps[k])

        opts.update(linsolver="sparse", sparsity=blocks, jacfn=jac_all)

    def restart(t: float, y: np.ndarray, yp: np.ndarray):
        y, yp = y.copy(), yp.copy()
        for k in range(K):
            y[sl[k]], yp[sl[k]] = consistent_initial(model, t, y[sl[k]], ps[k],
                                                     yp_guess=yp[sl[k]])
        return y, yp

    names = tuple(f"[{k}] {s}" for k in range(K) for s in model.state_names)
    return System(res_all, opts, restart, names)

