"""Analyses on the compiled model besides transient: the DC operating point.

A machine turning at constant speed is not an equilibrium (its angle grows), so the operating
point of a rotating system is defined as the steady state of its *averaged* model: every
residual is averaged over a full turn of each shaft angle (which removes the harmonic ripple
terms exactly, up to order N-1 for N sample angles), the angle itself is free and its
derivative (the speed) is an unknown. Positions of translational nodes are held at their
initial values; their derivatives are unknowns too. All other derivatives are zero, and so
is every source's rate of change: the sources hold their values at the instant asked for.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from circuitsim.errors import SolverError, spoken
from circuitsim.solve.watch import huge_parameters

N_AVERAGE = 64  # sample angles per turn: exact for ripple harmonics up to order 63


@dataclass(frozen=True)
class OperatingPoint:
    """DC operating point: states ``y`` and derivatives ``yp`` (non-zero only for free
    integrals such as shaft angles, whose derivative is the speed)."""

    y: np.ndarray
    yp: np.ndarray
    names: tuple[str, ...]
    iterations: int

    def __getitem__(self, name: str) -> float:
        return float(self.y[self.names.index(name)])


def _averaged(model, t: float, p: tuple, angles: list[int], samples: np.ndarray):
    """The residual and its Jacobian parts averaged over the sample shaft angles."""
    residual, _, parts, _, _ = model.fns
    n = len(model.state_names)
    res = np.zeros(n)

    def averaged(y_, yp_):
        f = np.zeros(n)
        Fy = np.zeros((n, n))
        Fyp = np.zeros((n, n))
        for a in samples:
            ys = y_.copy()
            ys[angles] = y_[angles] + a
            residual(t, ys, yp_, res, p)
            f += res
            jy, jyp, _ = parts(t, ys, yp_, p)
            Fy += jy
            Fyp += jyp
        m = len(samples)
        return f / m, Fy / m, Fyp / m

    return averaged


def operating_point(model, params: Mapping[str, float] | None = None, t: float = 0.0,
                    tol: float = 1e-12, max_iter: int = 100) -> OperatingPoint:
    """Newton on the averaged residual with y' = 0 except for free integrals (see module)."""
    from circuitsim.solve.events import refuse
    from circuitsim.solve.init import initial_state

    refuse(model, "the operating point")
    names = model.state_names
    n = len(names)
    p = model.frozen_vector(params)
    free = [k for k, s in enumerate(names) if s in model.meta.get("integrals", {})]
    angles = [k for k in free if model.meta["integrals"][names[k]] == "rotational"]
    y, _ = initial_state(model, t, p)
    samples = np.arange(N_AVERAGE) * 2 * np.pi / N_AVERAGE if angles else np.zeros(1)
    averaged = _averaged(model, t, p, angles, samples)
    cols_y = [k for k in range(n) if k not in set(free)]
    # a Newton that overflows fails with its own message: numpy's warnings would be noise
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        try:
            y, yp, f, it = _dc_newton(averaged, y, np.zeros(n), cols_y, free, tol, max_iter,
                                      names)
        except SolverError as exc:
            raise SolverError(exc.bare + huge_parameters(model, p)) from None
    if it is not None:
        return OperatingPoint(y, yp, names, it)
    worst = int(np.argmax(np.abs(f)))
    raise SolverError(f"operating point: Newton did not converge in {max_iter} iterations; "
                      f"largest residual {f[worst]:.3g} in the equation of {spoken(names[worst])}. Try "
                      f"starting from rest (init: rest), or ramp the sources (source "
                      f"stepping){huge_parameters(model, p)}")


def _dc_newton(averaged, y: np.ndarray, yp: np.ndarray, cols_y: list[int], free: list[int],
               tol: float, max_iter: int, names: tuple[str, ...]):
    """Damped Newton for y (but the free integrals) and y' of the free integrals; returns
    (y, y', residual, iterations or None if it did not converge)."""
    n = len(names)
    f, Fy, Fyp = averaged(y, yp)
    for it in range(max_iter):
        if np.max(np.abs(f), initial=0.0) <= tol * (1 + np.max(np.abs(y), initial=0.0)):
            return y, yp, f, it
        A = np.hstack([Fy[:, cols_y], Fyp[:, free]])
        try:
            dz = np.linalg.solve(A, -f)
        except np.linalg.LinAlgError:
            worst = int(np.argmax(np.abs(f)))
            raise SolverError(
                f"operating point: the DC Jacobian is singular (no DC path for the quantity "
                f"of equation {worst}, near {spoken(names[worst]) if worst < n else '?'}). A node "
                f"reached only through capacitors, or a shaft with no damping, has no DC "
                f"solution: add a bleed resistor or damper, or start from rest") from None
        step, norm0 = 1.0, np.linalg.norm(f)
        for _ in range(40):
            y_t, yp_t = y.copy(), yp.copy()
            y_t[cols_y] += step * dz[: len(cols_y)]
            yp_t[free] += step * dz[len(cols_y):]
            f_t, Fy_t, Fyp_t = averaged(y_t, yp_t)
            if np.all(np.isfinite(f_t)) and np.linalg.norm(f_t) < (1 - 1e-4 * step) * norm0:
                break
            step *= 0.5
        y, yp, f, Fy, Fyp = y_t, yp_t, f_t, Fy_t, Fyp_t
    return y, yp, f, None


def probe_values(model, op: OperatingPoint, params: Mapping[str, float] | None = None,
                 t: float = 0.0) -> dict[str, float]:
    """Probes at the operating point (sources at time ``t`` [s]), averaged over a shaft turn
    like the residual."""
    _, _, _, observe, _ = model.fns
    p = model.frozen_vector(params)
    angles, samples = _angles(model)
    Y = np.repeat(op.y[:, None], len(samples), axis=1)
    for k in angles:
        Y[k] += samples
    YP = np.repeat(op.yp[:, None], len(samples), axis=1)
    with np.errstate(all="ignore"):
        vals = observe(t, Y, YP, p, which=range(model.meta["n_probes"]))
    names = model.meta["observed"][: model.meta["n_probes"]]
    return {n: float(np.mean(np.broadcast_to(np.asarray(v, float), (len(samples),))))
            for n, v in zip(names, vals, strict=False)}


def _angles(model) -> tuple[list[int], np.ndarray]:
    """Indices of shaft-angle states and the angles over which the averaged model is taken."""
    integrals = model.meta.get("integrals", {})
    angles = [k for k, s in enumerate(model.state_names) if integrals.get(s) == "rotational"]
    return angles, (np.arange(N_AVERAGE) * 2 * np.pi / N_AVERAGE if angles else np.zeros(1))
