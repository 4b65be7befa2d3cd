"""Small-signal analyses about the operating point: linearisation, AC sweeps, and the
response to an angle-locked harmonic."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from circuitsim.solve.op import N_AVERAGE, OperatingPoint, _angles, operating_point


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


def _refuse_differentiated(model, param: str, input: str) -> str:
    """``param``, unless index reduction differentiated an equation holding it: a source
    across a capacitor (or in a loop of them), or a current source feeding an inductor
    cut-set. Its derivative was taken as zero there, so the perturbation would miss its s*u
    term: a 1 V source across 1 uF answered |H| = 0 A/V for the capacitor's current."""
    if param not in model.meta.get("differentiated_params", ()):
        return param
    from circuitsim.errors import ParameterError
    from circuitsim.solve.sources import _loc

    owner = param.rsplit(".", 2)[0]
    raise ParameterError(
        f"ac: the input '{input}' ({param}) drives a loop of capacitors and voltage sources or "
        f"a cut-set of inductors and current sources, whose equations were differentiated "
        f"with its value held constant: its small-signal response would be wrong. Give that "
        f"source a series resistance (a voltage source) or a parallel one (a current source), "
        f"e.g. 1 mohm or 1 Gohm", _loc(model, owner), owner)


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
    p = model.frozen_vector(params)
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


def _observe_batch(model, lin: Linearization, Y: np.ndarray, YP: np.ndarray, p,
                   out: int) -> np.ndarray:
    """Output number ``out`` at the columns of Y, YP."""
    _, _, _, observe, _ = model.fns
    with np.errstate(all="ignore"):
        (v,) = observe(0.0, Y, YP, p, which=[out])
    return np.broadcast_to(np.asarray(v, float), (Y.shape[1],)).copy()


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
    v = _observe_batch(model, lin, np.hstack(Ys), np.hstack(YPs), lin.p, out_index)
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
    freqs = np.atleast_1d(np.asarray(freqs, float))
    bad = freqs[~(np.isfinite(freqs) & (freqs >= 0))]
    if bad.size:
        from circuitsim.errors import ParameterError

        # a negative frequency gives the conjugate (phase of the wrong sign), inf gives NaN
        raise ParameterError(f"ac: frequency {bad[0]:g} Hz: frequencies are finite and "
                             f">= 0 Hz (0 is DC)")
    residual = model.fns[0]
    lin = lin or linearize(model, params)
    names = model.meta["params"]
    u = names.index(_refuse_differentiated(model, _resolve_input(model, input), input))
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
                                         tuple(pp), out)[0] / (2 * hu * len(lin.samples))
        b += (cols[0] - cols[1]) / (2 * hu * len(lin.samples))
    cy, cyp = _output_rows(model, lin, out)
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
    out_k = _observe_batch(model, lin, Y, YP, lin.p, out) @ w
    speed = lin.op.yp[lin.angles[0]]
    omega = order * speed
    cy, cyp = _output_rows(model, lin, out)
    x = np.linalg.solve(lin.Fy + 1j * omega * lin.Fyp, -ck)
    z = cy @ x + 1j * omega * (cyp @ x) + out_k
    # Re(z e^{i k phi}) = |z| sin(k phi + arg z + pi/2)
    # a frequency whichever way the shaft turns (phi falls on a shaft turning backwards;
    # the phase stays one of the angle)
    return HarmonicResponse(order, abs(omega) / (2 * np.pi), float(abs(z)),
                            float(np.angle(z) + np.pi / 2))
