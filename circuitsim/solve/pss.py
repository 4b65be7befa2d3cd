"""Periodic steady state by shooting: one period (or one turn) integrated and corrected."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from circuitsim.errors import spoken
from circuitsim.solve.ac import _observe_batch, _output_index
from circuitsim.solve.op import _angles, operating_point


@dataclass(frozen=True)
class PeriodicSteadyState:
    """One period of the periodic orbit: ``t`` [s] from 0 to ``period`` (excluded) on a
    uniform grid, states ``y`` (n, m) and ``yp``; ``res[name]`` as for transient results."""

    period: float
    t: np.ndarray
    y: np.ndarray
    yp: np.ndarray
    iterations: int
    residual: float
    model: object
    p: tuple[float, ...]
    order: float | None

    def __getitem__(self, name: str) -> np.ndarray:
        out = _output_index(self.model, name)
        return _observe_batch(self.model, None, self.y, self.yp, self.p, out)

    def harmonic(self, name: str, k: int = 1) -> tuple[float, float, float]:
        """(frequency [Hz], amplitude, phase [rad]) of the k-th harmonic of the period, from
        the exact DFT over one period (x = amplitude sin(2 pi f t + phase) + ...)."""
        x = self[name]
        m = x.size
        c = 2 / m * np.sum(x * np.exp(-2j * np.pi * k * np.arange(m) / m))
        return k / self.period, float(abs(c)), float(np.angle(c) + np.pi / 2)


class _Shooting:
    """The period map of one circuit: integrate from a state over a time, and the gap
    between where the orbit ends and where it started."""

    def __init__(self, model, p: tuple, opts: dict, free: list[int], angles: list[int],
                 order: float, base: np.ndarray, period: float | None, sense: float = 1.0):
        self.model, self.p, self.opts = model, p, opts
        self.free, self.angles, self.order = free, angles, order
        self.base, self.period = base, period
        self.autonomous = period is None
        self.sense = sense  # +1 when the first shaft turns forwards, -1 backwards

    def flow(self, y0: np.ndarray, t_end: float, grid: np.ndarray | None = None):
        from circuitsim.solve.init import consistent_initial
        from circuitsim.solve.integrate import make_ida

        y0, yp0 = consistent_initial(self.model, 0.0, y0, self.p)
        span = grid if grid is not None else np.array([0.0, 0.5 * t_end, t_end])
        sol = make_ida(self.model.fns[0], self.opts).solve(span, y0, yp0)
        if not sol.success:
            from circuitsim.errors import SolverError

            raise SolverError(f"periodic steady state: the integration over one period failed "
                              f"({sol.message})")
        return np.asarray(sol.y), np.asarray(sol.yp)

    def unpack(self, z: np.ndarray) -> tuple[np.ndarray, float]:
        yy = self.base.copy()
        yy[self.free] = z[: len(self.free)]
        return yy, (z[-1] if self.autonomous else self.period)

    def gap(self, z: np.ndarray) -> np.ndarray:
        y0, t_end = self.unpack(z)
        ys, _ = self.flow(y0, t_end)
        r = ys[-1][self.free] - y0[self.free]
        if self.autonomous:
            a = self.angles[0]
            # the angle a turning shaft travels: backwards when it turns backwards
            r = np.append(r, ys[-1][a] - y0[a] - self.sense * 2 * np.pi / self.order)
        return r

    def scale(self, z: np.ndarray) -> np.ndarray:
        """Each unknown's size, for its finite-difference step: a state's and the period's."""
        if self.autonomous:
            return np.append(1 + np.abs(z[: len(self.free)]), z[-1])
        return 1 + np.abs(z)

    def gap_scale(self, z: np.ndarray) -> np.ndarray:
        """Each gap's size, for the tolerance: a state's, and the angle the shaft turns over
        the period (the angle's gap over it is the period's relative error) [rad]."""
        if self.autonomous:
            return np.append(1 + np.abs(z[: len(self.free)]), 2 * np.pi / self.order)
        return 1 + np.abs(z)


def periodic_steady_state(model, params: Mapping[str, float] | None = None, *,
                          order: float = 1, period: float | None = None,
                          samples: int = 256, tol: float = 1e-9, max_iter: int = 20,
                          rtol: float = 1e-10, atol: float = 1e-12) -> PeriodicSteadyState:
    """Periodic steady state by shooting (Newton on the period map).

    Rotating, autonomous circuits (DC sources, a shaft): the period is unknown and set by the
    speed, so the map runs from the Poincaré section phi = 0 until the shaft has turned
    1/``order`` of a revolution; unknowns are the other differential states and the period.
    Circuits driven by a periodic source: give ``period`` [s]; unknowns are the differential
    states. The Jacobian of the map is built by finite differences of short integrations.
    """
    from circuitsim.solve.events import refuse

    refuse(model, "the periodic steady state")
    shoot, z = _setup(model, params, order, period, rtol, atol)
    asked = dict(shoot.opts)
    for k, factor in enumerate(TIGHTER):
        shoot.opts = {**asked, "rtol": rtol * factor, "atol": atol * factor}
        try:
            z, r, it = _newton(shoot, z, tol, max_iter)
            break
        except _Stalled as stall:
            if k == len(TIGHTER) - 1:
                from circuitsim.errors import SolverError

                raise SolverError(
                    f"periodic steady state: shooting did not converge in {max_iter} Newton "
                    f"steps (residual {stall.residual:.3g}, integrated down to rtol "
                    f"{rtol * factor:.3g}); try a transient closer to steady state first"
                ) from None
            z = stall.z  # the best start so far, integrated more finely
    y0, T = shoot.unpack(z)
    grid = np.arange(samples + 1) * T / samples
    ys, yps = shoot.flow(y0, T, grid)
    return PeriodicSteadyState(float(T), grid[:-1], ys[:-1].T, yps[:-1].T, it,
                               float(np.max(np.abs(r))), model, shoot.p,
                               order if shoot.autonomous else None)


def _setup(model, params, order: float, period: float | None, rtol: float, atol: float
           ) -> tuple[_Shooting, np.ndarray]:
    """The shooting problem and its first guess: the operating point on the section phi = 0
    with the period of its speed (autonomous), or the state from rest."""
    from circuitsim.solve.init import initial_state
    from circuitsim.solve.sources import check_period

    p = model.param_vector(params)
    nd = model.meta["n_diff"]
    n = len(model.state_names)
    angles, _ = _angles(model)
    opts = {"rtol": rtol, "atol": atol, "userdata": p, "max_num_steps": 500_000,
            "algebraic_idx": list(range(nd, n)) or None, **model.ida_options()}
    if period is None:
        if not angles:
            raise ValueError("no shaft angle: give the period of the driving source")
        op = operating_point(model, params)
        y = op.y.copy()
        y[angles] = 0.0
        speed = float(op.yp[angles[0]])
        if not abs(speed) > 0:  # a period 2 pi / (order w) would be infinite
            raise ValueError(
                f"the shaft stands still at the operating point (speed {speed:g} rad/s with the "
                f"sources at their values at t = 0, as `circuitsim op` shows): a turning "
                f"machine's periodic state needs a drive that turns it at t = 0 (a step "
                f"source that starts at 0 does not), or give --period for a driven circuit")
        _check_symmetric(model, p, op.y, op.yp, angles, order)
        # the period is a time, whichever way the shaft turns: integrating a turning-backwards
        # machine over a negative period ran its stable orbit backwards in time, which IDA
        # cannot follow (the Kim & Kim case 6 at Vin = -5 V ran out of steps)
        T = 2 * np.pi / order / abs(speed)
        free = [k for k in range(nd) if k not in angles]
        return (_Shooting(model, p, opts, free, angles, order, y, None, float(np.sign(speed))),
                np.append(y[free], T))
    check_period(model, model.param_values(params), float(period))
    y, _ = initial_state(model, 0.0, p)
    free = list(range(nd))
    return _Shooting(model, p, opts, free, angles, order, y, float(period)), y[free].copy()


def _check_symmetric(model, p: tuple, y: np.ndarray, yp: np.ndarray, angles: list[int],
                     order: float) -> None:
    """Refuse an ``order`` whose 1/order of a turn does not leave the circuit as it was.

    Shooting over 1/order of a turn closes the orbit on that section; if the circuit's
    angle-locked terms (an EMF harmonic, a cogging, a behavioural law of the angle) are not
    the same there -- an order 8 ripple seen every third of a turn -- Newton still finds a
    state that returns to itself once, which is no steady state (the Kim & Kim motor at
    order 1.5 gave a mean speed 0.6 % off). The residual is compared at states whose angles
    differ by 1/order of a turn of the first shaft (the other shafts by their share of it, in
    the ratio of their speeds at the operating point)."""
    residual = model.fns[0]
    shift = 2 * np.pi / order * yp[angles] / yp[angles[0]]
    rng = np.random.default_rng(0)
    for _ in range(3):
        a = y.copy()
        a[angles] = rng.uniform(0.0, 2 * np.pi, len(angles))
        b = a.copy()
        b[angles] += shift
        ra, rb = np.zeros(len(y)), np.zeros(len(y))
        residual(0.0, a, yp, ra, p)
        residual(0.0, b, yp, rb, p)
        scale = np.maximum(np.abs(ra), np.abs(rb)) + 1e-12 * (1.0 + np.max(np.abs(ra)))
        if np.any(np.abs(ra - rb) > 1e-7 * scale):
            k = int(np.argmax(np.abs(ra - rb) / scale))
            raise ValueError(
                f"the circuit is not the same after 1/{order:g} of a turn: the equation of "
                f"{spoken(model.state_names[k])} changes when the shaft angle moves by 2 pi/{order:g} "
                f"(an angle-locked term whose order {order:g} does not divide), so no steady "
                f"state repeats every 1/{order:g} turn; give an --order that divides every "
                f"angle-locked order of the circuit (1, a whole turn, always does)")


#: the integration's tolerances tried in turn, as factors of those asked: the period map is
#: only as smooth as its integration, and Newton stalls at that noise (the Kim & Kim case 4
#: over a whole turn at rtol 1e-10 wanders at 1e-9 of the speed, at 1e-11 it converges)
TIGHTER = (1.0, 0.1, 0.01)
#: Newton steps without halving the best gap: the map's noise is reached
STALL = 4


class _Stalled(Exception):
    """Newton stopped short of the tolerance: ``z`` the best unknowns found, ``residual``
    the largest gap there."""

    def __init__(self, z: np.ndarray, residual: float):
        super().__init__()
        self.z, self.residual = z, residual


def _newton(shoot: _Shooting, z: np.ndarray, tol: float, max_iter: int):
    """Newton on the gap with a finite-difference Jacobian of the period map; ``_Stalled``
    after ``max_iter`` steps, or ``STALL`` steps that do not halve the best gap."""
    r = first = shoot.gap(z)
    it = since = 0
    best = (np.max(np.abs(r) / shoot.gap_scale(z)), z, r)
    while True:
        size = np.max(np.abs(r) / shoot.gap_scale(z))
        if size < tol:
            _closes(shoot, r, first, it)
            return z, r, it
        if size < 0.5 * best[0]:
            best, since = (size, z, r), 0
        it, since = it + 1, since + 1
        if it > max_iter or since > STALL:
            raise _Stalled(best[1], float(np.max(np.abs(best[2]))))
        scale = shoot.scale(z)
        J = np.empty((r.size, z.size))
        for c in range(z.size):
            h = 1e-6 * scale[c]
            zz = z.copy()
            zz[c] += h
            J[:, c] = (shoot.gap(zz) - r) / h
        z = z + np.linalg.lstsq(J, -r, rcond=None)[0]
        r = shoot.gap(z)


def _closes(shoot: _Shooting, r: np.ndarray, first: np.ndarray, it: int) -> None:
    """Refuse a 'converged' orbit whose gap never shrank: the tolerance is relative to the
    state, so a map with no fixed point (a state that grows by the same step every period,
    as a capacitor fed a current with a nonzero mean) passes it once Newton's step, divided by
    a zero derivative, has thrown the state to 1e9. Newton on a real orbit cuts the gap by
    orders of magnitude; here it stays as it was."""
    if it == 0 or np.max(np.abs(r)) < 0.5 * np.max(np.abs(first)):
        return
    from circuitsim.errors import SolverError

    names = [spoken(shoot.model.state_names[k]) for k in shoot.free] + ["the shaft angle"]
    k = int(np.argmax(np.abs(r)))
    raise SolverError(f"periodic steady state: there is none: {names[k]} ends each period "
                      f"{r[k]:+.4g} from where it started, whatever the start. A source with "
                      f"a nonzero mean into a capacitor or an inductor, or a torque into an "
                      f"undamped shaft, grows every period: add a bleed resistor or a damper, "
                      f"or a drive whose mean is zero")
