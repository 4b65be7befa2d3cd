"""Periodic steady state by shooting: one period (or one turn) integrated and corrected."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

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
        return _observe_batch(self.model, None, self.y, self.yp, self.p)[out]

    def harmonic(self, name: str, k: int = 1) -> tuple[float, float, float]:
        """(frequency [Hz], amplitude, phase [rad]) of the k-th harmonic of the period, from
        the exact DFT over one period (x = amplitude sin(2 pi f t + phase) + ...)."""
        x = self[name]
        m = x.size
        c = 2 / m * np.sum(x * np.exp(-2j * np.pi * k * np.arange(m) / m))
        return k / self.period, float(abs(c)), float(np.angle(c) + np.pi / 2)


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
    from circuitsim.solve.init import consistent_initial, initial_state
    from circuitsim.solve.integrate import make_ida

    residual, _, _, _, _ = model.fns
    p = model.param_vector(params)
    nd = model.meta["n_diff"]
    n = len(model.state_names)
    angles, _ = _angles(model)
    autonomous = period is None
    if autonomous:
        if not angles:
            raise ValueError("no shaft angle: give the period of the driving source")
        op = operating_point(model, params)
        y = op.y.copy()
        y[angles] = 0.0
        T = 2 * np.pi / order / op.yp[angles[0]]
        free = [k for k in range(nd) if k not in angles]
    else:
        y, _ = initial_state(model, 0.0, p)
        T = float(period)
        free = list(range(nd))
    opts = {"rtol": rtol, "atol": atol, "userdata": p, "max_num_steps": 500_000,
            "algebraic_idx": list(range(nd, n)) or None, **model.ida_options()}

    def flow(y0: np.ndarray, t_end: float, grid: np.ndarray | None = None):
        y0, yp0 = consistent_initial(model, 0.0, y0, p)
        span = grid if grid is not None else np.array([0.0, 0.5 * t_end, t_end])
        sol = make_ida(residual, opts).solve(span, y0, yp0)
        if not sol.success:
            from circuitsim.errors import SolverError

            raise SolverError(f"periodic steady state: the integration over one period failed "
                              f"({sol.message})")
        return np.asarray(sol.y), np.asarray(sol.yp)

    def gap(y0: np.ndarray, t_end: float) -> np.ndarray:
        ys, _ = flow(y0, t_end)
        r = ys[-1][free] - y0[free]
        if autonomous:
            r = np.append(r, ys[-1][angles[0]] - y0[angles[0]] - 2 * np.pi / order)
        return r

    def unpack(z: np.ndarray) -> tuple[np.ndarray, float]:
        yy = y.copy()
        yy[free] = z[: len(free)]
        return yy, (z[-1] if autonomous else T)

    z = np.append(y[free], T) if autonomous else y[free].copy()
    r = gap(*unpack(z))
    it = 0
    while True:
        scale = np.append(1 + np.abs(z[: len(free)]), z[-1]) if autonomous else 1 + np.abs(z)
        if np.max(np.abs(r) / scale) < tol:
            break
        it += 1
        if it > max_iter:
            from circuitsim.errors import SolverError

            raise SolverError(f"periodic steady state: shooting did not converge in "
                              f"{max_iter} Newton steps (residual {np.max(np.abs(r)):.3g}); "
                              f"try a transient closer to steady state first")
        J = np.empty((r.size, z.size))
        for c in range(z.size):
            h = 1e-6 * scale[c]
            zz = z.copy()
            zz[c] += h
            J[:, c] = (gap(*unpack(zz)) - r) / h
        z = z + np.linalg.lstsq(J, -r, rcond=None)[0]
        r = gap(*unpack(z))
    y0, T = unpack(z)
    grid = np.arange(samples + 1) * T / samples
    ys, yps = flow(y0, T, grid)
    return PeriodicSteadyState(float(T), grid[:-1], ys[:-1].T, yps[:-1].T, it,
                               float(np.max(np.abs(r))), model, p,
                               order if autonomous else None)
