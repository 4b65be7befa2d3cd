"""Transient integration with SUNDIALS IDA (scikit-sundae) on the index-1 residual.

Consistent initial values include the derivatives of algebraic unknowns (IDA's own
correction does not give those; a wrong y' there makes the first step fail). Waveform corners
are breakpoints where the integrator restarts. Long runs go in chunks whose output can be
decimated, so memory stays bounded.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping

import numpy as np

from circuitsim.errors import SolverError
from circuitsim.solve.init import check_initial, consistent_initial, initial_state
from circuitsim.solve.result import SimResult, Status
from circuitsim.solve.sources import bound_step


def _break_times(model, values: Mapping[str, float], stop: float) -> list[float]:
    from circuitsim.component import WAVEFORMS
    from circuitsim_components import waveforms  # noqa: F401 - registry

    out: list[float] = []
    for kind, fields in model.meta["breaks"]:
        p = {f: values[name] for f, name in fields}
        out += WAVEFORMS[kind]().breakpoints(p, stop)
    return sorted({b for b in out if 0.0 < b < stop})


def simulate(model, stop: float | None = None, params: Mapping[str, float] | None = None, *,
             step: float | None = None, t_eval: np.ndarray | None = None,
             rtol: float | None = None, atol: float | None = None,
             max_step: float | None = None, init: str | None = None,
             chunk: int = 50_000, keep_after: float | None = None, decimate: int = 1
             ) -> SimResult:
    """Integrate from t = 0 to ``stop`` [s].

    Parameters
    ----------
    params : overrides by name [SI] (netlist or component parameters); no recompilation.
    step : output step [s] (default: the netlist's, else stop / 20000).
    t_eval : explicit output times [s] (overrides step).
    rtol, atol, max_step : IDA tolerances and largest step [s] (0: unbounded).
    init : 'rest' (states at their initial values, default) or 'op' (DC operating point).
    chunk : output points per integrator call; memory is bounded by chunk when decimating.
    keep_after : [s] keep every output point after this time, and only every ``decimate``-th
        before it (for long runs whose end is analysed).
    """
    import sksundae as sun

    an = model.netlist.analysis
    stop = float(stop if stop is not None else an.stop)
    if not stop > 0:
        raise SolverError("stop time must be positive")
    rtol = an.rtol if rtol is None else rtol
    atol = an.atol if atol is None else atol
    max_step = an.max_step if max_step is None else max_step
    init = init or an.init
    values = model.param_values(params)
    p = tuple(values[n] for n in model.meta["params"])
    if t_eval is None:
        h = step or an.step or stop / 20_000
        n_out = round(stop / h)
        t_eval = np.linspace(0.0, stop, n_out + 1)
    t_eval = np.asarray(t_eval, float)
    max_step = bound_step(model, values, stop, t_eval, max_step)  # the sources' step bound
    residual, jac, _, _, _ = model.fns
    nd = model.meta["n_diff"]
    n = len(model.state_names)
    if n == 0:  # every unknown was eliminated: the outputs are explicit functions of t
        empty = np.zeros((0, t_eval.size))
        return _finite(SimResult(t_eval, empty, empty, (), Status.OK, "", 0, 0, model, p))
    overridden = frozenset(params or {})
    y0, _ = initial_state(model, 0.0, p, overridden)
    if init == "op":
        from circuitsim.solve.op import operating_point

        try:
            y0 = operating_point(model, params).y
        except SolverError as exc:
            return SimResult(t_eval[:0], np.zeros((n, 0)), np.zeros((n, 0)),
                             model.state_names, Status.INIT_FAILED, exc.bare, 0, 0, model, p)
    elif init != "rest":
        raise SolverError(f"init must be 'rest' or 'op', not {init!r}")
    try:
        y0, yp0 = consistent_initial(model, 0.0, y0, p)
    except SolverError as exc:
        return SimResult(t_eval[:0], np.zeros((n, 0)), np.zeros((n, 0)), model.state_names,
                         Status.INIT_FAILED, exc.bare, 0, 0, model, p)
    if init == "rest":
        ignored = check_initial(model, 0.0, y0, yp0, p, overridden)
        if ignored:
            import warnings

            from circuitsim.errors import CircuitWarning

            warnings.warn("initial values that conflict with the circuit or with each other "
                          "were not met: " + "; ".join(ignored), CircuitWarning, stacklevel=3)
    # Corners closer than IDA can resolve (|tout - t0| ~ 1e-13 t) are merged into one.
    eps = 1e-11 * stop
    edges = [0.0]
    for b in [*_break_times(model, values, stop), stop]:
        if b - edges[-1] > eps:
            edges.append(b)
    edges[-1] = stop
    ts, ys, yps = [], [], []
    nfev = njev = 0
    y, yp, t_now = y0, yp0, 0.0
    opts = {"rtol": rtol, "atol": atol, "userdata": p, "jacfn": jac, "max_step": max_step,
            "max_num_steps": 200_000, "algebraic_idx": list(range(nd, n)) or None}
    status, detail = Status.OK, ""
    keep_from = keep_after if keep_after is not None else -np.inf
    counter = 0

    def record(times: np.ndarray, yy: np.ndarray, yyp: np.ndarray) -> None:
        nonlocal counter
        idx = counter + np.arange(times.size)
        keep = (times >= keep_from) | (idx % decimate == 0)
        counter += times.size
        ts.append(times[keep])
        ys.append(yy[keep])
        yps.append(yyp[keep])

    first = t_eval[t_eval <= eps]
    if first.size:
        record(first[:1], y0[None, :], yp0[None, :])
    for a, b in itertools.pairwise(edges):
        # each requested time belongs to one segment; one within eps of the corner b is
        # reported as the state at b
        mine = t_eval[(t_eval > a + eps) & (t_eval <= b + eps)]
        inner = mine[mine < b - eps]
        targets = np.append(inner, b)
        wanted = np.append(np.ones(inner.size, bool), mine.size > inner.size)
        labels = np.append(inner, mine[-1] if mine.size > inner.size else b)
        for lo in range(0, targets.size, chunk):
            part = targets[lo:lo + chunk]
            solver = sun.ida.IDA(residual, **opts)
            try:
                sol = solver.solve(np.concatenate([[t_now], part]), y, yp)
            except Exception as exc:  # noqa: BLE001 - the wrapper raises assorted types
                status = Status.SOLVER_FAILED
                detail = (f"at t = {t_now:.6g} s the integrator stopped ({exc!r}); try "
                          f"smaller tolerances or max_step")
                break
            nfev += int(sol.nfev or 0)
            njev += int(sol.njev or 0)
            got_t, got_y, got_yp = np.asarray(sol.t), np.asarray(sol.y), np.asarray(sol.yp)
            if part.size == 1 and got_t.size > 1:
                # a two-point span returns the solver's own steps: keep the end only
                ok = bool(np.isclose(got_t[-1], part[0], rtol=0, atol=eps))
                got_t, got_y, got_yp = (np.concatenate([a[:1], a[-1:]]) if ok else a[:1]
                                        for a in (got_t, got_y, got_yp))
            done = max(got_t.size - 1, 0)  # row 0 is the start state
            if done:
                w = wanted[lo:lo + done]
                record(labels[lo:lo + done][w], got_y[1:][w], got_yp[1:][w])
            if not sol.success or done < part.size:
                t_fail = float(got_t[-1]) if got_t.size else t_now
                status = Status.SOLVER_FAILED
                detail = _failure(model, sol, t_fail, rtol, atol)
                break
            y, yp, t_now = got_y[-1], got_yp[-1], float(got_t[-1])
        if status is not Status.OK:
            break
        if b < stop:  # a waveform corner: restart with consistent derivatives
            try:
                y, yp = consistent_initial(model, b, y, p, yp_guess=yp)
            except SolverError as exc:
                status, detail = Status.SOLVER_FAILED, exc.bare
                break
    t_all = np.concatenate(ts) if ts else np.zeros(0)
    y_all = np.concatenate(ys).T if ys else np.zeros((n, 0))
    yp_all = np.concatenate(yps).T if yps else np.zeros((n, 0))
    return _finite(SimResult(t_all, y_all, yp_all, model.state_names, status, detail, nfev,
                             njev, model, p))


def _finite(res: SimResult) -> SimResult:
    """A run whose probes are NaN or infinite has not succeeded, whatever the integrator says
    (a probe dividing by a quantity that is zero, a negative number to a fractional power in
    a probe that no equation uses): mark it, naming the probe and when it went bad."""
    if not res.success or not res.t.size:
        return res
    for name in res.model.probe_names:
        x = res[name]
        bad = ~np.isfinite(x)
        if bad.any():
            k = int(np.argmax(bad))
            res.status = Status.NOT_FINITE
            res.detail = (f"probe '{name}' is {x[k]} from t = {res.t[k]:.6g} s: its expression "
                          f"has no real value there (a division by zero, a negative number to "
                          f"a fractional power, the log or square root of a negative number); "
                          f"guard it, e.g. with max(..., small)")
            break
    return res


def _failure(model, sol, t_fail: float, rtol: float, atol: float) -> str:
    y = np.asarray(sol.y)
    yp = np.asarray(sol.yp)
    name = "?"
    if y.size:
        rate = np.abs(yp[-1]) / (rtol * np.abs(y[-1]) + atol)
        name = model.state_names[int(np.argmax(rate))]
    return (f"at t = {t_fail:.6g} s ({str(sol.message).strip()}); fastest-changing variable: "
            f"{name}. Try smaller tolerances or max_step, check the parameter values, or run "
            f"`circuitsim check NETLIST`")
