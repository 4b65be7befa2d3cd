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
        if np.max(np.abs(f), initial=0.0) <= tol * (1 + np.max(np.abs(y), initial=0.0)):
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


def probe_values(model, op: OperatingPoint, params: Mapping[str, float] | None = None
                 ) -> dict[str, float]:
    """Probes at the operating point, averaged over a shaft turn like the residual."""
    _, _, _, observe, _ = model.fns
    p = model.param_vector(params)
    angles, samples = _angles(model)
    Y = np.repeat(op.y[:, None], len(samples), axis=1)
    for k in angles:
        Y[k] += samples
    YP = np.repeat(op.yp[:, None], len(samples), axis=1)
    with np.errstate(all="ignore"):
        vals = observe(0.0, Y, YP, p)
    names = model.meta["observed"][: model.meta["n_probes"]]
    return {n: float(np.mean(np.broadcast_to(np.asarray(v, float), (len(samples),))))
            for n, v in zip(names, vals, strict=False)}


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


def _angles(model) -> tuple[list[int], np.ndarray]:
    """Indices of shaft-angle states and the angles over which the averaged model is taken."""
    integrals = model.meta.get("integrals", {})
    angles = [k for k, s in enumerate(model.state_names) if integrals.get(s) == "rotational"]
    return angles, (np.arange(N_AVERAGE) * 2 * np.pi / N_AVERAGE if angles else np.zeros(1))


def _resolve_input(model, name: str) -> str:
    """A small-signal input: a run-time parameter, or a source component (its value)."""
    params = model.meta["params"]
    if name in params:
        return name
    # the parameter that sets the waveform value at t = 0, where the operating point is
    for suffix in (".value", ".offset", ".v0", ".v1", ".low"):
        cands = [p for p in params if p.startswith(f"{name}.") and p.endswith(suffix) and
                 p.count(".") == 2]
        if cands:
            return cands[0]
    if name in model.netlist.parameters:
        raise ValueError(f"'{name}' is a netlist parameter; name the component parameter it "
                         f"sets (e.g. {next((p for p in params if p.endswith('.value')), '')})")
    raise ValueError(f"no small-signal input '{name}': name a source component or a "
                     f"parameter ({', '.join(params[:8])}, ...)")


@dataclass(frozen=True)
class Linearization:
    """The averaged model linearised at its operating point: Fy dy + Fyp dy' + Fu du = 0."""

    op: OperatingPoint
    p: tuple[float, ...]
    Fy: np.ndarray
    Fyp: np.ndarray
    samples: np.ndarray
    angles: tuple[int, ...]

    def states_at(self, angle: float) -> np.ndarray:
        y = self.op.y.copy()
        y[list(self.angles)] += angle
        return y


def linearize(model, params: Mapping[str, float] | None = None) -> Linearization:
    """Operating point and the analytic Jacobians dF/dy, dF/dy' averaged over a turn."""
    _, _, parts, _, _ = model.fns
    op = operating_point(model, params)
    p = model.param_vector(params)
    angles, samples = _angles(model)
    n = len(op.y)
    Fy, Fyp = np.zeros((n, n)), np.zeros((n, n))
    for a in samples:
        y = op.y.copy()
        y[angles] += a
        jy, jyp, _ = parts(0.0, y, op.yp, p)
        Fy += jy / len(samples)
        Fyp += jyp / len(samples)
    return Linearization(op, p, Fy, Fyp, samples, tuple(angles))


def _observe_batch(model, lin: Linearization, Y: np.ndarray, YP: np.ndarray, p) -> np.ndarray:
    _, _, _, observe, _ = model.fns
    with np.errstate(all="ignore"):
        vals = observe(0.0, Y, YP, p)
    m = Y.shape[1]
    return np.array([np.broadcast_to(np.asarray(v, float), (m,)) for v in vals])


def _output_rows(model, lin: Linearization, out_index: int) -> tuple[np.ndarray, np.ndarray]:
    """d(output)/dy and d(output)/dy', averaged over the turn (central differences)."""
    n = len(lin.op.y)
    # one batch of observer calls for every sample angle and every +-h column: for each
    # angle, 2n columns perturb y (k-th +h, k-th -h, ...) and 2n perturb y'
    hps = 1e-6 * (1 + np.abs(lin.op.yp))
    eye = np.repeat(np.eye(n), 2, axis=1) * np.tile([1.0, -1.0], n)  # (n, 2n)
    Ys, YPs, Hs = [], [], []
    for a in lin.samples:
        y0 = lin.states_at(a)
        hs = 1e-6 * (1 + np.abs(y0))
        Ys += [y0[:, None] + eye * hs[:, None], np.repeat(y0[:, None], 2 * n, axis=1)]
        YPs += [np.repeat(lin.op.yp[:, None], 2 * n, axis=1),
                lin.op.yp[:, None] + eye * hps[:, None]]
        Hs.append(hs)
    v = _observe_batch(model, lin, np.hstack(Ys), np.hstack(YPs), lin.p)[out_index]
    v = v.reshape(len(lin.samples), 4 * n)
    dy = (v[:, 0:2 * n:2] - v[:, 1:2 * n:2]) / (2 * np.array(Hs))
    dyp = (v[:, 2 * n::2] - v[:, 2 * n + 1::2]) / (2 * hps)
    return dy.mean(axis=0), dyp.mean(axis=0)


@dataclass(frozen=True)
class AcResult:
    """Transfer function H(f) = output / input over frequency."""

    frequency: np.ndarray  # [Hz]
    H: np.ndarray  # complex
    input: str
    output: str

    @property
    def magnitude(self) -> np.ndarray:
        return np.abs(self.H)

    @property
    def phase(self) -> np.ndarray:
        """[deg]"""
        return np.degrees(np.angle(self.H))

    def as_dict(self) -> dict:
        return {"input": self.input, "output": self.output,
                "frequency": self.frequency.tolist(), "magnitude": self.magnitude.tolist(),
                "phase_deg": self.phase.tolist()}


def _output_index(model, output: str) -> int:
    observed = model.meta["observed"]
    if output in observed:
        return observed.index(output)
    import difflib

    close = difflib.get_close_matches(output, observed, n=3)
    raise ValueError(f"no probe or variable '{output}'" +
                     (f" (did you mean {', '.join(close)}?)" if close else ""))


def ac(model, input: str, output: str, freqs, params: Mapping[str, float] | None = None,
       lin: Linearization | None = None) -> AcResult:
    """Small-signal transfer function from a source (or any run-time parameter) to a probe,
    around the operating point of the averaged model.

    ``input`` is a source component (its value is perturbed) or a parameter name such as
    ``M.e0`` (an additive back-EMF voltage) or ``Vin.V.value``.
    """
    residual = model.fns[0]
    lin = lin or linearize(model, params)
    names = model.meta["params"]
    u = names.index(_resolve_input(model, input))
    out = _output_index(model, output)
    n = len(lin.op.y)
    res = np.zeros(n)
    hu = 1e-6 * (1 + abs(lin.p[u]))
    b, dout = np.zeros(n), 0.0
    for a in lin.samples:  # dF/du and d(output)/du: central differences, averaged
        y = lin.states_at(a)
        cols = []
        for sgn in (1, -1):
            pp = list(lin.p)
            pp[u] += sgn * hu
            residual(0.0, y, lin.op.yp, res, tuple(pp))
            cols.append(res.copy())
            dout += sgn * _observe_batch(model, lin, y[:, None], lin.op.yp[:, None],
                                         tuple(pp))[out, 0] / (2 * hu * len(lin.samples))
        b += (cols[0] - cols[1]) / (2 * hu * len(lin.samples))
    cy, cyp = _output_rows(model, lin, out)
    freqs = np.atleast_1d(np.asarray(freqs, float))
    H = np.empty(freqs.size, complex)
    for i, f in enumerate(freqs):
        s = 2j * np.pi * f
        x = np.linalg.solve(lin.Fy + s * lin.Fyp, -b)
        H[i] = cy @ x + s * (cyp @ x) + dout
    return AcResult(freqs, H, input, output)


@dataclass(frozen=True)
class HarmonicResponse:
    """Small-signal response of a probe to the order-k harmonic of the shaft angle that the
    circuit's own equations contain (back-EMF ripple, cogging)."""

    order: float
    frequency: float  # [Hz]
    amplitude: float
    phase: float  # [rad], x = amplitude sin(k phi + phase)


def harmonic_response(model, order: int, output: str,
                      params: Mapping[str, float] | None = None,
                      lin: Linearization | None = None) -> HarmonicResponse:
    """Treat the order-``order`` Fourier component (in the shaft angle) of the residual as a
    small-signal source at ``order`` times the shaft frequency and return the probe's
    response. Second-order effects (the speed ripple modulating the ripple) are left out."""
    residual = model.fns[0]
    lin = lin or linearize(model, params)
    if not lin.angles:
        raise ValueError("the circuit has no shaft angle: nothing turns")
    if order >= N_AVERAGE // 2:
        raise ValueError(f"order {order} is above the {N_AVERAGE // 2 - 1} the angle sampling "
                         f"resolves")
    n = len(lin.op.y)
    res = np.zeros(n)
    out = _output_index(model, output)
    ck = np.zeros(n, complex)
    Y = np.column_stack([lin.states_at(a) for a in lin.samples])
    w = np.exp(-1j * order * np.asarray(lin.samples)) * 2 / len(lin.samples)
    for j in range(Y.shape[1]):
        residual(0.0, Y[:, j], lin.op.yp, res, lin.p)
        ck += res * w[j]
    YP = np.repeat(lin.op.yp[:, None], Y.shape[1], axis=1)
    out_k = _observe_batch(model, lin, Y, YP, lin.p)[out] @ w
    speed = lin.op.yp[lin.angles[0]]
    omega = order * speed
    cy, cyp = _output_rows(model, lin, out)
    x = np.linalg.solve(lin.Fy + 1j * omega * lin.Fyp, -ck)
    z = cy @ x + 1j * omega * (cyp @ x) + out_k
    # Re(z e^{i k phi}) = |z| sin(k phi + arg z + pi/2)
    return HarmonicResponse(order, omega / (2 * np.pi), float(abs(z)),
                            float(np.angle(z) + np.pi / 2))


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
    import sksundae as sun

    from .integrate import consistent_initial, initial_state

    residual, jac, _, _, _ = model.fns
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
    opts = {"rtol": rtol, "atol": atol, "userdata": p, "jacfn": jac, "max_num_steps": 500_000,
            "algebraic_idx": list(range(nd, n)) or None}

    def flow(y0: np.ndarray, t_end: float, grid: np.ndarray | None = None):
        y0, yp0 = consistent_initial(model, 0.0, y0, p)
        span = grid if grid is not None else np.array([0.0, 0.5 * t_end, t_end])
        sol = sun.ida.IDA(residual, **opts).solve(span, y0, yp0)
        if not sol.success:
            from .errors import SolverError

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
            from .errors import SolverError

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
