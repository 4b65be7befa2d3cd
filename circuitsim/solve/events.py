"""Switching by events: discrete states that change at roots of their guards.

A component declares discrete states (constant between events: der = 0) and the events that
change them (``Component.events``). IDA watches every guard as a root function, falling
through zero; at a root the integration stops, the event's discrete states take their new
values, every further event whose guard the new values leave at or below zero is applied at
the same instant (event iteration), and IDA restarts from values made consistent by
``init.consistent_initial`` (the differential states, discrete ones included, are kept; the
algebraic unknowns and all derivatives are solved again).

A switching that cannot settle -- the same modes coming back within one instant, or a long
run of switchings with no time between them -- stops the run with the elements named: it
is a switch without hysteresis whose control sits on its threshold, or a circuit that has no
consistent mode (an ideal diode driving an ideal current source backwards).

Kept apart from integrate.py, which only hands a segment to ``segment`` when the model has
events.
"""

from __future__ import annotations

import collections
import warnings

import numpy as np

from circuitsim.errors import SolverError, spoken
from circuitsim.solve.init import consistent_initial
from circuitsim.solve.kernel_lib import BAND_ABS, BAND_REL, ROOT_RETURN
from circuitsim.solve.watch import Runaway, watch_of

#: Rounds of event iteration at one instant before the switching is declared chattering
#: (a half-bridge commutation takes three: gate off, diode on, dead time over).
MAX_ROUNDS = 20
#: This many switchings within ZENO_SPAN * stop of each other is chatter, not switching.
ZENO_COUNT = 64
ZENO_SPAN = 1e-10
#: Residual tolerance of the restart, relative to 1 + max |y|. consistent_initial's default
#: (1e-10) is loose when some state is large: at 600 rad/s it left a current 2.5e-8 A off,
#: and IDA's first step then failed its error test at atol 1e-9 down to h = 1e-17.
RESTART_TOL = 1e-12
#: A relation exactly on its threshold at the start takes its truth this fraction of the run
#: later (``t > 0`` at t = 0 starts true, as its root would otherwise be missed).
LOOKAHEAD = 1e-9


class Switching:
    """The events of one model at one parameter vector: IDA's root functions, the jumps of
    the discrete states, the modes of the held relations (run-time parameters, flipped at
    their roots) and the event iteration."""

    def __init__(self, model, p: tuple, stop: float):
        self.model, self.p = model, list(p)
        self.state_guards, self.jumps = model.event_fns or (None, None)
        self.crossings = model.crossing_fn
        self.info = list(model.meta.get("events", []))
        self.modes = [c["mode"] for c in model.meta.get("crossings", [])]
        self.n_ev = len(self.info)
        self.info += [{"owner": c["owner"], "targets": []}
                      for c in model.meta.get("crossings", [])]
        self.g = np.zeros(len(self.info))
        self.discrete = sorted({i for e in self.info for i in e["targets"]})
        self.recent: collections.deque = collections.deque(maxlen=ZENO_COUNT)
        self.span = ZENO_SPAN * stop
        self.lookahead = LOOKAHEAD * stop
        self.guards = self._root_functions()

    def _root_functions(self):
        """IDA's root functions: the components' guards, then one per held relation (its
        distance, signed for the mode held, plus the hysteresis band); every one matters
        when it falls through zero."""
        n_ev, modes = self.n_ev, np.array(self.modes, int)

        def guards(t, y, yp, g, p):
            if n_ev:
                self.state_guards(t, y, yp, g[:n_ev], p)
            if modes.size:
                g[n_ev:] = self._held(t, y, yp, p, modes)

        guards.terminal = [True] * len(self.info)
        guards.direction = [-1] * len(self.info)
        return guards

    def _held(self, t, y, yp, p, modes: np.ndarray) -> np.ndarray:
        """Guards of the held relations: positive while each holds its mode."""
        out = self.crossings(t, y, yp, p)
        k = modes.size
        held = np.asarray(p, float)[modes] > 0.5
        return np.where(held, out[:k], -out[:k]) + BAND_REL * out[k:] + BAND_ABS

    def start(self, t: float, y: np.ndarray, yp: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray]:
        """Set every held relation to its truth at t (on its threshold: a moment later, so
        ``t > 0`` starts true), then consistent values and event iteration."""
        if self.modes:
            k = len(self.modes)
            out = self.crossings(t, y, yp, tuple(self.p))
            later = self.crossings(t + self.lookahead, y + self.lookahead * yp, yp,
                                   tuple(self.p))
            on = np.abs(out[:k]) <= BAND_REL * out[k:] + BAND_ABS
            for j, m in enumerate(self.modes):
                self.p[m] = float((later[j] if on[j] else out[j]) > 0)
            y, yp = self.consistent(t, y, yp)
        return self.settle(t, y, yp)

    def ida_options(self) -> dict:
        return {"eventsfn": self.guards, "num_events": len(self.info),
                "userdata": tuple(self.p)}

    def owners(self, fired: np.ndarray) -> list[str]:
        return sorted({self.info[k]["owner"] for k in np.flatnonzero(fired)})

    def apply(self, t: float, y: np.ndarray, yp: np.ndarray, fired: np.ndarray) -> np.ndarray:
        """y with the discrete states of the fired events set (all new values computed from
        the old states first: the events of one instant happen together); the fired held
        relations flip their modes."""
        out = np.array(y, float)
        if fired[:self.n_ev].any():
            vals = self.jumps(t, y, yp, tuple(self.p))
            for k in np.flatnonzero(fired[:self.n_ev]):
                e = self.info[k]
                for j, idx in enumerate(e["targets"]):
                    out[idx] = vals[e["start"] + j]
        for k in np.flatnonzero(fired[self.n_ev:]):
            m = self.modes[k]
            self.p[m] = 1.0 - self.p[m]
        return out

    def settle(self, t: float, y: np.ndarray, yp: np.ndarray,
               fired: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Apply ``fired`` (None: whatever guards are not positive), then event iteration
        until every guard is positive; consistent (y, y') at t. Raises SolverError when the
        modes do not settle."""
        seen: set[tuple] = set()
        who: set[str] = set()
        for _ in range(MAX_ROUNDS):
            if fired is None:
                self.guards(t, y, yp, self.g, tuple(self.p))
                fired = self.g <= 0
            if not fired.any():
                return y, yp
            who.update(self.owners(fired))
            y = self.apply(t, y, yp, fired)
            key = (*np.round(y[self.discrete], 12), *(self.p[m] for m in self.modes))
            if key in seen:
                break
            seen.add(key)
            y, yp = self.consistent(t, y, yp)
            fired = None
        raise SolverError(f"at t = {t:.9g} s the switching of {', '.join(sorted(who))} does "
                          f"not settle: its modes keep changing at one instant. Give a switch "
                          f"a hysteresis (Vh) or check what drives it")

    def consistent(self, t: float, y: np.ndarray, yp: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray]:
        """Consistent (y, y') at t to RESTART_TOL, or to consistent_initial's own tolerance
        where rounding stops Newton short of it."""
        try:
            return consistent_initial(self.model, t, y, tuple(self.p), yp_guess=yp,
                                      tol=RESTART_TOL, max_iter=12)
        except SolverError:
            return consistent_initial(self.model, t, y, tuple(self.p), yp_guess=yp)

    def restart(self, t: float, y: np.ndarray, yp: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray]:
        """Restart at a waveform corner: consistent values, then whatever switches there."""
        y, yp = self.consistent(t, y, yp)
        return self.settle(t, y, yp)

    def note(self, t: float, fired: np.ndarray) -> str | None:
        """Record a root; a message if the roots pile up with no time between them."""
        self.recent.append((t, tuple(self.owners(fired)), bool(fired[self.n_ev:].any())))
        if len(self.recent) == ZENO_COUNT and t - self.recent[0][0] <= self.span:
            who = sorted({o for _, names, _ in self.recent for o in names})
            fix = ("give the switch a hysteresis (Vh) or a control that does not sit on its "
                   "threshold")
            if any(rel for *_, rel in self.recent):
                fix = (f"{fix}; a relation in an expression (if, sign, abs, min, max) that "
                       f"switches back at once has no consistent side there (sign(w) "
                       f"friction at rest is one): write it with smooth_sign or smooth_abs, "
                       f"or use a stick-slip element (stick_clutch)")
            return (f"at t = {t:.9g} s {', '.join(who)} switched {ZENO_COUNT} times within "
                    f"{t - self.recent[0][0]:.3g} s (chatter): {fix}")
        return None


def for_model(model, p: tuple, stop: float) -> Switching | None:
    """The model's switching at parameters p, or None when it has no events and no held
    relations."""
    if model.meta.get("events") or model.meta.get("crossings"):
        return Switching(model, p, stop)
    return None


def refuse(model, what: str) -> None:
    """Raise SolverError if the model switches by events, which ``what`` cannot follow."""
    owners = sorted({e["owner"] for e in model.meta.get("events", [])})
    if owners:
        raise SolverError(f"{what} does not follow switching events ({', '.join(owners)} "
                          f"switch by events); use a transient run, or the smooth models "
                          f"(model: smooth, pwm_leg)")


def watching_ida(residual, opts: dict):
    """IDA watching the guards over a span: on the model's compiled kernels and root function
    when a fit or a sweep asks for kernels and the model has them (``solve/direct.py``: the
    same steps and roots, to the bit), else ``plain_ida``. Stops at a table's rows are
    served by the compiled route only (``integrate._step_of`` sends such a model here then)."""
    if "kernels_of" in opts:
        from circuitsim.solve.direct import ida_for

        direct = ida_for(opts, watch_of(residual))
        if direct is not None:
            return direct
    if opts.get("stops") is not None:
        raise SolverError("a table's rows as stops need the compiled route")
    return plain_ida(residual, opts)


def plain_ida(residual, opts: dict):
    """scikit-sundae's IDA (the lean import) on the Python residual and guards; it also steps
    one output at a time (``init_step``, ``step``), which the compiled route does not."""
    from circuitsim.solve.sundae import ida_class

    opts = {k: v for k, v in opts.items() if k != "kernels_of"}
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="Custom sparse Jacobian approximation")
        return ida_class()(residual, **opts)


def output_targets(t_eval: np.ndarray, a: float, b: float, eps: float):
    """Output times of (a, b]: the times to stop at, whether each is wanted, their labels
    (one within eps of the corner b is reported as the state at b)."""
    mine = t_eval[(t_eval > a + eps) & (t_eval <= b + eps)]
    inner = mine[mine < b - eps]
    targets = np.append(inner, b)
    wanted = np.append(np.ones(inner.size, bool), mine.size > inner.size)
    labels = np.append(inner, mine[-1] if mine.size > inner.size else b)
    return targets, wanted, labels


def segment(system, run, a: float, b: float, eps: float, state, record, chunk: int
            ) -> str | None:
    """Integrate over (a, b] as integrate's segments do, stopping at every root of a guard
    to switch and restart; None, or why it failed."""
    sw: Switching = system.switching
    targets, wanted, labels = output_targets(run.t_eval, a, b, eps)
    lo = 0
    while lo < targets.size:
        part = targets[lo:lo + chunk]
        opts = {**system.opts, **sw.ida_options()}  # the modes held since the last switch
        if system.rows.size:  # a table's rows: stops of the compiled route (integrate._step_of)
            opts["stops"] = system.rows
        try:
            sol = watching_ida(system.residual, opts).solve(
                np.concatenate([[state.t], part]), state.y, state.yp)
        except Runaway:
            raise
        except Exception as exc:  # noqa: BLE001 - the wrapper raises assorted types
            return (f"at t = {state.t:.6g} s the integrator stopped ({exc!r}); try "
                    f"smaller tolerances or max_step")
        state.nfev += int(sol.nfev or 0)
        state.njev += int(sol.njev or 0)
        root = sol.status == ROOT_RETURN
        got_t, got_y, got_yp = np.asarray(sol.t), np.asarray(sol.y), np.asarray(sol.yp)
        if part.size == 1 and got_t.size > 1:  # one-step mode: keep the start and the end
            got_t, got_y, got_yp = (np.concatenate([x[:1], x[-1:]])
                                    for x in (got_t, got_y, got_yp))
        done = max(got_t.size - 1 - int(root), 0)
        if done:
            w = wanted[lo:lo + done]
            record(labels[lo:lo + done][w], got_y[1:done + 1][w], got_yp[1:done + 1][w])
        lo += done
        if root:
            why = switch_at(sw, sol, got_t[-1], got_y[-1], got_yp[-1], state)
            if why:
                return why
            record.note_event(state.t)
            while lo < targets.size and targets[lo] <= state.t + eps:  # outputs at the
                if wanted[lo]:                                        # switching instant
                    record(labels[lo:lo + 1], state.y[None, :], state.yp[None, :])
                lo += 1
            continue
        if not sol.success or done < part.size:
            return _failure(system.names, sol, float(got_t[-1]) if got_t.size else state.t)
        state.y, state.yp, state.t = got_y[-1], got_yp[-1], float(got_t[-1])
    return None


def switch_at(sw: Switching, sol, t: float, y: np.ndarray, yp: np.ndarray, state
            ) -> str | None:
    """Apply the events IDA found at t and settle; the state moves to t."""
    fired = np.asarray(sol.i_events)[-1] != 0
    why = sw.note(float(t), fired)
    if why:
        return why
    try:
        state.y, state.yp = sw.settle(float(t), y, yp, fired)
    except SolverError as exc:
        return exc.bare
    state.t = float(t)
    return None


def _failure(names: tuple[str, ...], sol, t_fail: float) -> str:
    y, yp = np.asarray(sol.y), np.asarray(sol.yp)
    name = spoken(names[int(np.argmax(np.abs(yp[-1])))]) if y.size else "?"
    return (f"at t = {t_fail:.6g} s ({str(sol.message).strip()}); fastest-changing variable: "
            f"{name}. Try smaller tolerances or max_step, or run `circuitsim check NETLIST`")
