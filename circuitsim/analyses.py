"""Analyses on the compiled model besides transient: the DC operating point.

A machine turning at constant speed is not an equilibrium (its angle grows), so the operating
point of a rotating system is defined as the steady state of its *averaged* model: every
residual is averaged over a full turn of each shaft angle (which removes the harmonic ripple
terms exactly, up to order N-1 for N sample angles), the angle itself is free and its
derivative (the speed) is an unknown. Positions of translational nodes are held at their
initial values; their derivatives are unknowns too. All other derivatives are zero.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from .errors import SolverError

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


def operating_point(model, params: Mapping[str, float] | None = None, t: float = 0.0,
                    tol: float = 1e-12, max_iter: int = 100) -> OperatingPoint:
    """Newton on the averaged residual with y' = 0 except for free integrals (see module)."""
    from .integrate import initial_state

    residual, _, parts, _, _ = model.fns
    names = model.state_names
    n = len(names)
    p = model.param_vector(params)
    free = [k for k, s in enumerate(names) if s in model.meta.get("integrals", {})]
    angles = [k for k in free if model.meta["integrals"][names[k]] == "rotational"]
    y, _ = initial_state(model, t, p)
    yp = np.zeros(n)
    fixed_y = set(free)
    samples = np.arange(N_AVERAGE) * 2 * np.pi / N_AVERAGE if angles else np.zeros(1)
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

    cols_y = [k for k in range(n) if k not in fixed_y]
    f, Fy, Fyp = averaged(y, yp)
    for it in range(max_iter):
        if np.max(np.abs(f)) <= tol * (1 + np.max(np.abs(y))):
            return OperatingPoint(y, yp, names, it)
        A = np.hstack([Fy[:, cols_y], Fyp[:, free]])
        try:
            dz = np.linalg.solve(A, -f)
        except np.linalg.LinAlgError:
            worst = int(np.argmax(np.abs(f)))
            raise SolverError(
                f"operating point: the DC Jacobian is singular (no DC path for the quantity "
                f"of equation {worst}, near {names[worst] if worst < n else '?'}). A node "
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
    worst = int(np.argmax(np.abs(f)))
    raise SolverError(f"operating point: Newton did not converge in {max_iter} iterations; "
                      f"largest residual {f[worst]:.3g} in the equation of {names[worst]}. Try "
                      f"starting from rest (init: rest), or ramp the sources (source stepping)")


@dataclass(frozen=True)
class EnergyAudit:
    """Where the energy of a transient went [J], per component, over [t0, t1].

    ``delivered``: by sources (independent across/through sources); ``dissipated``: turned into
    heat (resistors, dampers, friction, and the losses of lossy storage elements); ``stored``:
    change of stored energy (inductors, capacitors, inertias, masses); ``converted``: per
    multi-domain element (an EMF), the energy absorbed on each side; its sum is what the
    element creates or destroys, zero for an energy-conserving coupling. ``balance`` is
    delivered - dissipated - stored - net converter absorption (zero up to quadrature error).
    """

    t0: float
    t1: float
    delivered: dict[str, float]
    dissipated: dict[str, float]
    stored: dict[str, float]
    converted: dict[str, dict[str, float]]

    @property
    def total_delivered(self) -> float:
        return sum(self.delivered.values())

    @property
    def created(self) -> dict[str, float]:
        """Energy each converter *creates* (minus its net absorption) [J]."""
        return {k: -sum(v.values()) for k, v in self.converted.items()}

    @property
    def balance(self) -> float:
        return (self.total_delivered - sum(self.dissipated.values()) -
                sum(self.stored.values()) + sum(self.created.values()))

    def as_dict(self) -> dict:
        return {"t0": self.t0, "t1": self.t1, "delivered": self.delivered,
                "dissipated": self.dissipated, "stored": self.stored,
                "converted": self.converted, "created": self.created,
                "balance": self.balance}


def energy_audit(res, t0: float | None = None) -> EnergyAudit:
    """Energy audit of a SimResult from ``t0`` (default: start) to its end.

    Powers are integrated with the composite Simpson rule on the output samples, so the
    balance reflects the output step; components are classified by their declared branch
    kinds and by whether they store energy, never by type.
    """
    from scipy.integrate import simpson

    m = res.t >= (res.t[0] if t0 is None else t0)
    t = res.t[m]
    names = set(res.names)
    out: dict[str, dict] = {"delivered": {}, "dissipated": {}, "stored": {}, "converted": {}}
    for comp in res.model.netlist.components:
        n = comp.name
        power = res[f"{n}.power"][m]
        absorbed = float(simpson(power, x=t))
        kinds = {b.kind for b in comp.cls.branches}
        sides = [k for k in names if k.startswith(f"{n}.power_")]
        if kinds & {"V", "I"}:
            out["delivered"][n] = -absorbed
        elif f"{n}.energy" in names:
            e = res[f"{n}.energy"][m]
            out["stored"][n] = float(e[-1] - e[0])
            out["dissipated"][n] = absorbed - out["stored"][n]
        elif sides:
            out["converted"][n] = {k.split("power_", 1)[1]: float(simpson(res[k][m], x=t))
                                   for k in sorted(sides)}
        else:
            out["dissipated"][n] = absorbed
    # A storage element without losses shows a loss at quadrature-error level: drop it.
    scale = max([abs(v) for v in out["delivered"].values()] +
                [abs(v) for v in out["stored"].values()] + [1e-300])
    for n in list(out["dissipated"]):
        if n in out["stored"] and abs(out["dissipated"][n]) < 1e-6 * scale:
            del out["dissipated"][n]
    return EnergyAudit(float(t[0]), float(t[-1]), **out)
