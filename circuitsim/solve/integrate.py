"""Transient integration with SUNDIALS IDA (scikit-sundae) on the index-1 residual.

Consistent initial values include the derivatives of algebraic unknowns (IDA's own
correction does not give those; a wrong y' there makes the first step fail). Waveform corners
are breakpoints where the integrator restarts. Long runs go in chunks whose output can be
decimated, so memory stays bounded. A model with discrete states (ideal switches) integrates
its segments through events.py, which stops at each switching and restarts.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass

import numpy as np

from circuitsim.errors import SolverError, spoken
from circuitsim.netlist.load import analysis_problem
from circuitsim.solve import events
from circuitsim.solve.init import check_initial, consistent_initial, initial_state
from circuitsim.solve.result import SimResult, Status
from circuitsim.solve.sources import bound_step
from circuitsim.solve.watch import HUGE, Runaway, huge_parameters, watch_of, watched


def break_times(model, values: Mapping[str, float], stop: float) -> list[float]:
    """The waveform corners [s] strictly between 0 and ``stop``, sorted, at ``values``."""
    from circuitsim.component import WAVEFORMS
    from circuitsim_components import waveforms  # noqa: F401 - registry

    out: list[float] = []
    for kind, fields in model.meta["breaks"]:
        p = {f: values[name] for f, name in fields}
        out += WAVEFORMS[kind]().breakpoints(p, stop)
    return sorted({b for b in out if 0.0 < b < stop})


def make_ida(residual, opts: dict):
    """An IDA solver; the pattern given with our own Jacobian only sizes the sparse matrix
    (scikit-sundae warns that its finite-difference use is ignored: that is intended).
    ``opts["kernels_of"]`` (set when ``CIRCUITSIM_KERNELS`` is) lets IDA call the model's
    compiled kernels directly when it has them (solve/direct.py)."""
    import warnings

    from circuitsim.solve.sundae import ida_class

    if "kernels_of" in opts:
        from circuitsim.solve.direct import ida_for

        direct = ida_for(opts, watch_of(residual))
        if direct is not None:
            return direct
        # never reached with stops: integrate takes its own step loop for them then
        opts = {k: v for k, v in opts.items() if k not in ("kernels_of", "stops")}
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="Custom sparse Jacobian approximation")
        return ida_class()(residual, **opts)


@dataclass(frozen=True)
class Settings:
    """One run's integration settings, defaults filled from the netlist's analysis."""

    stop: float  # [s]
    t_eval: np.ndarray  # [s] output times
    rtol: float
    atol: float
    max_step: float  # [s] 0: unbounded
    init: str  # 'rest' or 'op'


def settings(model, stop: float | None = None, step: float | None = None,
             t_eval: np.ndarray | None = None, rtol: float | None = None,
             atol: float | None = None, max_step: float | None = None,
             init: str | None = None) -> Settings:
    """Fill the run's settings from the netlist's analysis where not given."""
    an = model.netlist.analysis
    stop = float(stop if stop is not None else an.stop)
    if not 0 < stop < math.inf:
        raise SolverError(f"stop time must be positive and finite, not {stop:g} s")
    init = init or an.init
    if init not in ("rest", "op"):
        raise SolverError(f"init must be 'rest' or 'op', not {init!r}")
    for key, value in (("step", step), ("rtol", rtol)):
        problem = analysis_problem(key, value)
        if problem:
            raise SolverError(problem)
    if t_eval is None:
        h = step or an.step or stop / 20_000
        # at least [0, stop]: a step longer than twice the run rounded to one output, t = 0,
        # and the run reported '0 s simulated' with the values at rest
        t_eval = np.linspace(0.0, stop, max(1, round(stop / h)) + 1)
    run = Settings(stop, np.asarray(t_eval, float), an.rtol if rtol is None else rtol,
                   an.atol if atol is None else atol,
                   an.max_step if max_step is None else max_step, init)
    problem = _settings_problem(run)
    if problem:
        raise SolverError(problem)
    return run


def _settings_problem(run: Settings) -> str:
    """What makes a run's settings meaningless, or '': output times the integration never
    reaches (IDA returned t = 0 alone, with success) and tolerances IDA refuses mid-run."""
    t = run.t_eval
    if t.ndim != 1 or t.size == 0 or not np.all(np.isfinite(t)):
        return "t_eval must be a non-empty list of finite times [s]"
    if t[0] < 0 or t[-1] > run.stop * (1 + 1e-12):
        return (f"t_eval spans {t[0]:g} to {t[-1]:g} s, outside the run from 0 to stop = "
                f"{run.stop:g} s: the model starts at rest at t = 0; raise stop or trim t_eval")
    if t.size > 1 and not np.all(np.diff(t) > 0):
        k = int(np.argmax(np.diff(t) <= 0)) + 1
        return f"t_eval must increase: t_eval[{k}] = {t[k]:g} s after {t[k - 1]:g} s"
    if not 0 < run.atol < math.inf:
        return f"atol = {run.atol:g}: the absolute tolerance must be positive and finite"
    if not 0 <= run.max_step < math.inf:
        return f"max_step = {run.max_step:g} s: must be 0 (unbounded) or a positive time"
    return ""


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
    run = settings(model, stop, step, t_eval, rtol, atol, max_step, init)
    if int(decimate) != decimate or decimate < 1 or int(chunk) != chunk or chunk < 1:
        raise SolverError(f"decimate ({decimate}) and chunk ({chunk}) are whole numbers >= 1")
    values = model.param_values(params)
    # the sources' own step bound (a periodic source's period; a fast one is refused)
    run = dataclasses.replace(run, max_step=bound_step(model, values, run.stop, run.t_eval,
                                                       run.max_step))
    p = tuple(values[n] for n in model.meta["params"])
    n = len(model.state_names)
    if n == 0:  # every unknown was eliminated: the outputs are explicit functions of t
        empty = np.zeros((0, run.t_eval.size))
        return _finite(SimResult(run.t_eval, empty, empty, (), Status.OK, "", 0, 0, model, p))
    # a run that overflows fails with a message naming the time and the variable (or the
    # probe that is not finite): numpy's warnings about it from inside the solver are noise
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        start = consistent_start(model, run, params, p)
        if isinstance(start, str):
            return SimResult(run.t_eval[:0], np.zeros((n, 0)), np.zeros((n, 0)),
                             model.state_names, Status.INIT_FAILED,
                             start + huge_parameters(model, p), 0, 0, model, p)
        rec = Recorder(keep_after, decimate, progress)
        status, detail, nfev, njev = _integrate(model, run, p,
                                                corners(model, values, run.stop), start, rec,
                                                chunk)
    if status is Status.SOLVER_FAILED:
        detail += huge_parameters(model, p)
    t_all, y_all, yp_all = rec.arrays(n)
    return _finite(SimResult(t_all, y_all, yp_all, model.state_names, status, detail, nfev,
                             njev, model, p, np.array(rec.event_times)))


def consistent_start(model, run: Settings, params: Mapping[str, float] | None, p: tuple
           ) -> tuple[np.ndarray, np.ndarray] | str:
    """Consistent (y, y') at t = 0, or why there are none."""
    overridden = frozenset(params or {})
    y0, _ = initial_state(model, 0.0, p, overridden)
    try:
        if run.init == "op":
            from circuitsim.solve.op import operating_point

            y0 = operating_point(model, params).y
        y0, yp0 = consistent_initial(model, 0.0, y0, p)
    except SolverError as exc:
        return exc.bare
    if run.init == "rest":
        ignored = check_initial(model, 0.0, y0, yp0, p, overridden)
        if ignored:
            import warnings

            from circuitsim.errors import CircuitWarning

            warnings.warn("initial values that conflict with the circuit or with each other "
                          "were not met: " + "; ".join(ignored), CircuitWarning, stacklevel=4)
    return y0, yp0


def corners(model, values: Mapping[str, float], stop: float) -> list[float]:
    """0, the waveform corners, stop (``merged``)."""
    return merged(break_times(model, values, stop), stop)


def merged(times: Iterable[float], stop: float) -> list[float]:
    """0, the sorted corner ``times`` [s], ``stop``; corners closer than IDA can resolve
    (|tout - t0| ~ 1e-13 t; merged below 1e-11 t) are merged into one, the latest of them: a
    restart there sees every merged corner behind it, so the consistent y' takes each
    source's slope after its corner (a pwl's corner at 0.6 ms and a pulse's at 0.1 ms + 0.5
    ms, an ulp later: the restart at the earlier took the pulse's flat slope before its rise
    and IDA failed)."""
    edges = [0.0]
    for b in [*times, stop]:
        # relative to the corner's own time, not to stop: a 1 ns rise at t = 0 is two
        # corners IDA resolves however long the run (one 100 s long merged them, and the
        # integrator met the rise as a discontinuity)
        if b - edges[-1] > 1e-11 * b:
            edges.append(b)
        elif len(edges) > 1:
            edges[-1] = b
    edges[-1] = stop
    return edges


class Recorder:
    """Collects output rows, keeping every ``decimate``-th before ``keep_after``."""

    def __init__(self, keep_after: float | None, decimate: int,
                 progress: Callable[[float], None] | None = None):
        self.keep_from = keep_after if keep_after is not None else -np.inf
        self.progress = progress
        self.decimate = decimate
        self.counter = 0
        self.ts: list[np.ndarray] = []
        self.ys: list[np.ndarray] = []
        self.yps: list[np.ndarray] = []
        self.event_times: list[float] = []

    def note_event(self, t: float) -> None:
        """An instant [s] at which events switched something."""
        self.event_times.append(t)

    def __call__(self, times: np.ndarray, yy: np.ndarray, yyp: np.ndarray) -> None:
        idx = self.counter + np.arange(times.size)
        keep = (times >= self.keep_from) | (idx % self.decimate == 0)
        self.counter += times.size
        self.ts.append(times[keep])
        self.ys.append(yy[keep])
        self.yps.append(yyp[keep])
        if self.progress is not None and times.size:
            self.progress(float(times[-1]))

    def arrays(self, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        if not self.ts:
            return np.zeros(0), np.zeros((n, 0)), np.zeros((n, 0))
        return (np.concatenate(self.ts), np.concatenate(self.ys).T,
                np.concatenate(self.yps).T)


@dataclass(frozen=True)
class System:
    """What the corner-to-corner integration needs: the residual, IDA's options, how to
    restart consistently at a waveform corner, and the unknowns' names (for messages)."""

    residual: object
    opts: dict
    restart: object  # (t, y, y') -> consistent (y, y') at t
    names: tuple[str, ...]
    switching: events.Switching | None = None  # discrete states changed at roots
    rows: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0))  # [s] stops
    why_singular: Callable[[float, np.ndarray, np.ndarray], str] | None = None  # on failure


def model_system(model, run: Settings, p: tuple) -> System:
    """The System of one model at parameter vector p."""
    nd, n = model.meta["n_diff"], len(model.state_names)
    opts = {"rtol": run.rtol, "atol": run.atol, "userdata": p, "max_step": run.max_step,
            "max_num_steps": 200_000, "algebraic_idx": list(range(nd, n)) or None,
            **model.ida_options()}

    switching = events.for_model(model, p, run.stop)

    def restart(t: float, y: np.ndarray, yp: np.ndarray):
        if switching is not None:
            return switching.restart(t, y, yp)
        return consistent_initial(model, t, y, p, yp_guess=yp)

    # the Python route's residual, watched for a run that cannot finish (solve/watch.py)
    residual = watched(model.fns[0], run.stop, model.state_names, run.rtol, run.atol)
    return System(residual, opts, restart, model.state_names, switching,
                  table_rows(model, run.stop),
                  lambda t, y, yp: singular_pencil(model, p, t, y, yp, run.stop))


#: [unknowns] the failure diagnosis below factors dense matrices up to this size
PENCIL_MAX = 600


def singular_pencil(model, p: tuple, t: float, y, yp, stop: float) -> str:
    """Why IDA cannot step from (t, y, y'), when the reason is the equations themselves: the
    iteration matrix dF/dy + c dF/dy' is singular for every step size c (tried at two widely
    apart), so the unknowns it leaves undetermined are named. A structurally sound system
    can be singular at its parameter values: a controlled source of gain 1 fed back on its
    own input has the equation (1 - gain) v = 0 for any v. '' when the matrix is regular (the
    failure is then about accuracy) or too large to factor here."""
    n = len(model.state_names)
    if not 0 < n <= PENCIL_MAX:
        return ""
    try:
        Fy, Fyp, _ = model.sparse_parts(t, np.asarray(y, float), np.asarray(yp, float), p)
        Fy, Fyp = Fy.toarray(), Fyp.toarray()
        for c in (1e2 / stop, 1e8 / stop):
            _, sv, vt = np.linalg.svd(Fy + c * Fyp)
            if sv[-1] > 1e-13 * max(sv[0], 1e-300):
                return ""
    except (ValueError, np.linalg.LinAlgError, FloatingPointError):
        return ""
    null = np.abs(vt[-1])
    names = [spoken(model.state_names[k]) for k in np.flatnonzero(null > 0.1 * null.max())][:6]
    return (f". The equations are singular here, whatever the step: they leave "
            f"{', '.join(names)} undetermined (a source or coupling whose value cancels "
            f"another's, such as a gain of 1 fed back on its own input, is the usual cause); "
            f"`circuitsim equations NETLIST` shows the equations of these unknowns")


def table_rows(model, stop: float) -> np.ndarray:
    """Times [s] inside (0, stop) where a table source's interpolant changes slope: its
    rows (and its ends, where it starts to hold), except where the slope is the same on both
    sides. IDA stops exactly at each (SPICE stops at every PWL point) without a restart."""
    out = []
    for comp in model.netlist.components:
        for table in comp.tables:
            x, y = np.asarray(table.x, float), np.asarray(table.y, float)
            slopes = np.concatenate([[0.0], np.diff(y) / np.diff(x), [0.0]])
            kink = np.abs(np.diff(slopes)) > 1e-12 * (np.abs(slopes[1:]) + np.abs(slopes[:-1]))
            out.append(x[kink])
    if not out:
        return np.zeros(0)
    rows = np.unique(np.concatenate(out))
    return rows[(rows > 0.0) & (rows < stop)]


def _integrate(model, run: Settings, p: tuple, edges: list[float],
               start: tuple[np.ndarray, np.ndarray], record: Recorder, chunk: int
               ) -> tuple[Status, str, int, int]:
    return integrate_system(model_system(model, run, p), run, edges, start, record, chunk)


def integrate_system(system: System, run: Settings, edges: list[float],
                     start: tuple[np.ndarray, np.ndarray], record: Recorder, chunk: int
                     ) -> tuple[Status, str, int, int]:
    """IDA from corner to corner, restarting with consistent derivatives at each."""
    eps = 1e-11 * run.stop
    y, yp = start
    if system.switching is not None:  # the modes at t = 0 follow the initial values
        try:
            y, yp = system.switching.start(0.0, y, yp)
        except SolverError as exc:
            return Status.SOLVER_FAILED, exc.bare, 0, 0
    step = _step_of(system)
    first = run.t_eval[run.t_eval <= eps]
    if first.size:
        record(first[:1], y[None, :], yp[None, :])
    state = _Segment(y, yp, 0.0, 0, 0)
    for a, b in itertools.pairwise(edges):
        try:
            detail = step(system, run, a, b, eps, state, record, chunk)
        except Runaway as exc:
            detail = exc.bare
        if detail is None and b < run.stop:  # a waveform corner: consistent derivatives
            try:
                state.y, state.yp = system.restart(b, state.y, state.yp)
            except SolverError as exc:
                detail = exc.bare
        if detail is not None:
            return Status.SOLVER_FAILED, detail, state.nfev, state.njev
    return Status.OK, "", state.nfev, state.njev


@dataclass
class _Segment:
    """Where the integration stands: state, time and counters."""

    y: np.ndarray
    yp: np.ndarray
    t: float
    nfev: int
    njev: int


def _segment(system: System, run: Settings, a: float, b: float, eps: float,
             state: _Segment, record: Recorder, chunk: int) -> str | None:
    """Integrate over (a, b] in chunks of output times; None, or why it failed."""
    # each requested time belongs to one segment; one within eps of the corner b is
    # reported as the state at b
    t_eval = run.t_eval
    mine = t_eval[(t_eval > a + eps) & (t_eval <= b + eps)]
    inner = mine[mine < b - eps]
    targets = np.append(inner, b)
    wanted = np.append(np.ones(inner.size, bool), mine.size > inner.size)
    labels = np.append(inner, mine[-1] if mine.size > inner.size else b)
    for lo in range(0, targets.size, chunk):
        part = targets[lo:lo + chunk]
        opts = {**system.opts, "stops": system.rows} if system.rows.size else system.opts
        try:
            sol = make_ida(system.residual, opts).solve(
                np.concatenate([[state.t], part]), state.y, state.yp)
        except Runaway:
            raise
        except Exception as exc:  # noqa: BLE001 - the wrapper raises assorted types
            return (f"at t = {state.t:.6g} s the integrator stopped ({exc!r}); try "
                    f"smaller tolerances or max_step")
        state.nfev += int(sol.nfev or 0)
        state.njev += int(sol.njev or 0)
        got_t, got_y, got_yp = np.asarray(sol.t), np.asarray(sol.y), np.asarray(sol.yp)
        if part.size == 1 and got_t.size > 1:
            # a two-point span returns the solver's own steps: keep the end only
            ok = bool(np.isclose(got_t[-1], part[0], rtol=0, atol=eps))
            got_t, got_y, got_yp = (np.concatenate([x[:1], x[-1:]]) if ok else x[:1]
                                    for x in (got_t, got_y, got_yp))
        done = max(got_t.size - 1, 0)  # row 0 is the start state
        if done:
            w = wanted[lo:lo + done]
            record(labels[lo:lo + done][w], got_y[1:][w], got_yp[1:][w])
        if not sol.success or done < part.size:
            t_fail = float(got_t[-1]) if got_t.size else state.t
            return _failure(system, sol, t_fail, run.rtol, run.atol)
        state.y, state.yp, state.t = got_y[-1], got_yp[-1], float(got_t[-1])
    return None


def _step_of(system: System):
    """How a segment between corners is integrated: ``_segment`` (no switching) or
    ``events.segment`` (stopping at the guards' roots) over spans of output times, which the
    compiled route also stops at a table's rows within; on the Python route, a model reading
    tables steps from row to row (``_stepped``)."""
    if system.rows.size and not _direct(system):
        return _stepped
    return _segment if system.switching is None else events.segment


def _direct(system: System) -> bool:
    """Whether IDA runs on the model's compiled kernels (they stop at a table's rows in one
    compiled loop, and at the guards' roots of a switching model)."""
    if "kernels_of" not in system.opts:
        return False
    from circuitsim.solve.direct import ida_for

    opts = system.opts
    if system.switching is not None:
        opts = {**opts, **system.switching.ida_options(), "stops": system.rows}
    return ida_for(opts) is not None


def _stop_plan(system: System, run: Settings, a: float, b: float, eps: float):
    """The outputs of (a, b] (times, wanted, labels), every time to step to (outputs, then
    rows that are no output) and the stop times (rows, then b)."""
    targets, wanted, labels = events.output_targets(run.t_eval, a, b, eps)
    rows = system.rows[(system.rows > a + eps) & (system.rows < b - eps)]
    near = np.searchsorted(targets, rows)  # a row on an output time is stopped at as such
    close = np.minimum(np.abs(targets[np.minimum(near, targets.size - 1)] - rows),
                       np.abs(targets[np.maximum(near - 1, 0)] - rows)) <= eps
    times = np.concatenate([targets, rows[~close]])
    return targets, wanted, labels, times, np.append(rows, b)  # rows are sorted


def _stepped(system: System, run: Settings, a: float, b: float, eps: float,
             state: _Segment, record: Recorder, chunk: int) -> str | None:
    """(a, b] with IDA's stop time on each table row in turn: it never steps across a row
    and is not restarted there (a restart per row would cost a new start for each of a long
    record's rows); outputs between rows are interpolated as in ``_segment``. A root of a
    switching guard switches (events.switch_at) and restarts IDA there."""
    targets, wanted, labels, times, stops = _stop_plan(system, run, a, b, eps)
    order = np.argsort(times, kind="stable")
    ida, sol = _stepper(system, state), None
    kept: list[tuple[float, np.ndarray, np.ndarray]] = []
    i = 0
    while i < order.size:
        k, tout = order[i], float(times[order[i]])
        if tout > state.t + eps:
            sol = ida.step(tout, tstop=float(stops[np.searchsorted(stops, tout - eps)]))
            if sol.status == events.ROOT_RETURN:
                _count(state, sol)
                why = events.switch_at(system.switching, sol, sol.t, sol.y, sol.yp, state)
                if why:
                    return why
                record.note_event(state.t)
                ida, sol = _stepper(system, state), None
                continue
            if not sol.success:
                return _failure(system, _Last(sol), float(sol.t), run.rtol, run.atol)
            state.t, state.y, state.yp = tout, np.asarray(sol.y), np.asarray(sol.yp)
        if k < targets.size and wanted[k]:
            kept.append((labels[k], state.y, state.yp))
        if len(kept) >= chunk or (kept and i == order.size - 1):
            record(*(np.array([x[c] for x in kept]) for c in range(3)))
            kept = []
        i += 1
    _count(state, sol)
    return None


def _stepper(system: System, state: _Segment):
    """An IDA started at the state, for step-by-step calls (with the switching's root
    functions and modes when the model switches)."""
    opts = system.opts
    if system.switching is not None:
        opts = {**opts, **system.switching.ida_options()}
    ida = events.plain_ida(system.residual, opts)
    ida.init_step(state.t, state.y, state.yp)
    return ida


def _count(state: _Segment, sol) -> None:
    """Add one IDA's residual and Jacobian calls (its counters run from its start)."""
    if sol is not None:
        state.nfev += int(sol.nfev or 0)
        state.njev += int(sol.njev or 0)


class _Last:
    """One step's result shaped as a solve's (rows of y and y'), for ``_failure``."""

    def __init__(self, sol):
        self.y, self.yp, self.message = np.atleast_2d(sol.y), np.atleast_2d(sol.yp), sol.message


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


def _failure(system: System, sol, t_fail: float, rtol: float, atol: float) -> str:
    y = np.asarray(sol.y)
    yp = np.asarray(sol.yp)
    name, singular = "?", ""
    if y.size:
        with np.errstate(all="ignore"):
            size = np.maximum(np.abs(y[-1]), np.abs(yp[-1]))
        bad = ~(size < HUGE)
        if bad.any():  # IDA's norms overflow: its own words would not say so
            k = int(np.argmax(bad))
            v, r = y[-1][k], yp[-1][k]
            return (f"at t = {t_fail:.6g} s {spoken(system.names[k])} = {v:.4g} (its rate {r:.4g}): "
                    f"values this large (or not a number) overflow the integrator's arithmetic. A parameter "
                    f"far from its physical value does this; check the netlist's parameters "
                    f"and --set")
        with np.errstate(all="ignore"):
            rate = np.abs(yp[-1]) / (rtol * np.abs(y[-1]) + atol)
        name = spoken(system.names[int(np.argmax(rate))])
        if system.why_singular is not None:
            singular = system.why_singular(t_fail, y[-1], yp[-1])
    if singular:
        return f"at t = {t_fail:.6g} s ({str(sol.message).strip()}){singular}"
    return (f"at t = {t_fail:.6g} s ({str(sol.message).strip()}); fastest-changing variable: "
            f"{name}. Try smaller tolerances or max_step, check the parameter values, or run "
            f"`circuitsim check NETLIST`")
