"""Transient integration with SUNDIALS IDA (scikit-sundae) on the index-1 residual.

Consistent initial values include the derivatives of algebraic unknowns (IDA's own
correction does not give those; a wrong y' there makes the first step fail). Waveform corners
are breakpoints where the integrator restarts. Long runs go in chunks whose output can be
decimated, so memory stays bounded.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Mapping

import numpy as np

from circuitsim.errors import SolverError
from circuitsim.solve.init import check_initial, consistent_initial, initial_state
from circuitsim.solve.result import SimResult, Status


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
             chunk: int = 50_000, keep_after: float | None = None, decimate: int = 1,
             progress: Callable[[float], None] | None = None) -> SimResult:
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
    progress : called with the simulated time [s] after each integrator call (at every
        waveform corner and every ``chunk`` output points); for a progress bar.
    """
    an = model.netlist.analysis
    stop = float(stop if stop is not None else an.stop)
    if not stop > 0:
        raise SolverError("stop time must be positive")
    rtol = an.rtol if rtol is None else rtol
    atol = an.atol if atol is None else atol
    max_step = an.max_step if max_step is None else max_step
    values = model.param_values(params)
    p = tuple(values[n] for n in model.meta["params"])
    if t_eval is None:
        h = step or an.step or stop / 20_000
        n_out = round(stop / h)
        t_eval = np.linspace(0.0, stop, n_out + 1)
    t_eval = np.asarray(t_eval, float)
    n = len(model.state_names)
    if n == 0:  # every unknown was eliminated: the outputs are explicit functions of t
        empty = np.zeros((0, t_eval.size))
        return _finite(SimResult(t_eval, empty, empty, (), Status.OK, "", 0, 0, model, p))
    start = _start(model, params, p, init or an.init, t_eval)
    if isinstance(start, SimResult):
        return start
    # Corners closer than IDA can resolve (|tout - t0| ~ 1e-13 t) are merged into one.
    eps = 1e-11 * stop
    edges = [0.0]
    for b in [*_break_times(model, values, stop), stop]:
        if b - edges[-1] > eps:
            edges.append(b)
    edges[-1] = stop
    rec = _Recorder(keep_after, decimate)
    run = _Run(model, p, rtol, atol, max_step, chunk, eps, progress)
    status, detail = run.integrate(edges, t_eval, *start, rec)
    t_all, y_all, yp_all = rec.arrays(n)
    return _finite(SimResult(t_all, y_all, yp_all, model.state_names, status, detail,
                             run.nfev, run.njev, model, p))


def _start(model, params: Mapping[str, float] | None, p: tuple, init: str,
           t_eval: np.ndarray) -> tuple[np.ndarray, np.ndarray] | SimResult:
    """Stage 1: consistent initial values (y, y') at t = 0, from rest or the operating point;
    a failed start is returned as its SimResult."""
    n = len(model.state_names)

    def failed(message: str) -> SimResult:
        return SimResult(t_eval[:0], np.zeros((n, 0)), np.zeros((n, 0)), model.state_names,
                         Status.INIT_FAILED, message, 0, 0, model, p)

    overridden = frozenset(params or {})
    y0, _ = initial_state(model, 0.0, p, overridden)
    if init == "op":
        from circuitsim.solve.op import operating_point

        try:
            y0 = operating_point(model, params).y
        except SolverError as exc:
            return failed(exc.bare)
    elif init != "rest":
        raise SolverError(f"init must be 'rest' or 'op', not {init!r}")
    try:
        y0, yp0 = consistent_initial(model, 0.0, y0, p)
    except SolverError as exc:
        return failed(exc.bare)
    if init == "rest":
        ignored = check_initial(model, 0.0, y0, yp0, p, overridden)
        if ignored:
            import warnings

            from circuitsim.errors import CircuitWarning

            warnings.warn("initial values that conflict with the circuit or with each other "
                          "were not met: " + "; ".join(ignored), CircuitWarning, stacklevel=4)
    return y0, yp0


class _Recorder:
    """Collects output points: all of them after ``keep_after`` [s], every ``decimate``-th
    before it (memory stays bounded for long runs whose end is analysed)."""

    def __init__(self, keep_after: float | None, decimate: int):
        self.keep_from = keep_after if keep_after is not None else -np.inf
        self.decimate = decimate
        self.counter = 0
        self.ts: list[np.ndarray] = []
        self.ys: list[np.ndarray] = []
        self.yps: list[np.ndarray] = []

    def __call__(self, times: np.ndarray, yy: np.ndarray, yyp: np.ndarray) -> None:
        idx = self.counter + np.arange(times.size)
        keep = (times >= self.keep_from) | (idx % self.decimate == 0)
        self.counter += times.size
        self.ts.append(times[keep])
        self.ys.append(yy[keep])
        self.yps.append(yyp[keep])

    def arrays(self, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        t_all = np.concatenate(self.ts) if self.ts else np.zeros(0)
        y_all = np.concatenate(self.ys).T if self.ys else np.zeros((n, 0))
        yp_all = np.concatenate(self.yps).T if self.yps else np.zeros((n, 0))
        return t_all, y_all, yp_all


class _Run:
    """Stage 2: IDA from corner to corner, in chunks of output points."""

    def __init__(self, model, p: tuple, rtol: float, atol: float, max_step: float,
                 chunk: int, eps: float, progress: Callable[[float], None] | None):
        residual, jac, _, _, _ = model.fns
        nd, n = model.meta["n_diff"], len(model.state_names)
        self.model, self.rtol, self.atol, self.chunk, self.eps = model, rtol, atol, chunk, eps
        self.p, self.residual, self.progress = p, residual, progress
        self.opts = {"rtol": rtol, "atol": atol, "userdata": p, "jacfn": jac,
                     "max_step": max_step, "max_num_steps": 200_000,
                     "algebraic_idx": list(range(nd, n)) or None}
        self.nfev = self.njev = 0

    def integrate(self, edges: list[float], t_eval: np.ndarray, y0: np.ndarray,
                  yp0: np.ndarray, record: _Recorder) -> tuple[Status, str]:
        eps, stop = self.eps, edges[-1]
        first = t_eval[t_eval <= eps]
        if first.size:
            record(first[:1], y0[None, :], yp0[None, :])
        state = (y0, yp0, 0.0)
        for a, b in itertools.pairwise(edges):
            # each requested time belongs to one segment; one within eps of the corner b is
            # reported as the state at b
            mine = t_eval[(t_eval > a + eps) & (t_eval <= b + eps)]
            inner = mine[mine < b - eps]
            targets = np.append(inner, b)
            wanted = np.append(np.ones(inner.size, bool), mine.size > inner.size)
            labels = np.append(inner, mine[-1] if mine.size > inner.size else b)
            status, detail, state = self.segment(targets, wanted, labels, state, record)
            if status is not Status.OK:
                return status, detail
            if b < stop:  # a waveform corner: restart with consistent derivatives
                y, yp, t_now = state
                try:
                    y, yp = consistent_initial(self.model, b, y, self.p, yp_guess=yp)
                except SolverError as exc:
                    return Status.SOLVER_FAILED, exc.bare
                state = (y, yp, t_now)
        return Status.OK, ""

    def segment(self, targets: np.ndarray, wanted: np.ndarray, labels: np.ndarray,
                state: tuple, record: _Recorder) -> tuple[Status, str, tuple]:
        import sksundae as sun

        y, yp, t_now = state
        for lo in range(0, targets.size, self.chunk):
            part = targets[lo:lo + self.chunk]
            solver = sun.ida.IDA(self.residual, **self.opts)
            try:
                sol = solver.solve(np.concatenate([[t_now], part]), y, yp)
            except Exception as exc:  # noqa: BLE001 - the wrapper raises assorted types
                why = (f"at t = {t_now:.6g} s the integrator stopped ({exc!r}); try smaller "
                       f"tolerances or max_step")
                return Status.SOLVER_FAILED, why, (y, yp, t_now)
            self.nfev += int(sol.nfev or 0)
            self.njev += int(sol.njev or 0)
            got_t, got_y, got_yp = np.asarray(sol.t), np.asarray(sol.y), np.asarray(sol.yp)
            if part.size == 1 and got_t.size > 1:
                # a two-point span returns the solver's own steps: keep the end only
                ok = bool(np.isclose(got_t[-1], part[0], rtol=0, atol=self.eps))
                got_t, got_y, got_yp = (np.concatenate([a[:1], a[-1:]]) if ok else a[:1]
                                        for a in (got_t, got_y, got_yp))
            done = max(got_t.size - 1, 0)  # row 0 is the start state
            if done:
                w = wanted[lo:lo + done]
                record(labels[lo:lo + done][w], got_y[1:][w], got_yp[1:][w])
            if not sol.success or done < part.size:
                t_fail = float(got_t[-1]) if got_t.size else t_now
                return (Status.SOLVER_FAILED, _failure(self.model, sol, t_fail, self.rtol,
                                                       self.atol), (y, yp, t_now))
            y, yp, t_now = got_y[-1], got_yp[-1], float(got_t[-1])
            if self.progress is not None:
                self.progress(t_now)
        return Status.OK, "", (y, yp, t_now)


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
