"""Fit free netlist parameters to measured data by nonlinear least squares.

Two kinds of measurement (``circuitsim.data``):

- **features** (a steady value, a harmonic's amplitude or frequency) are compared with the
  analyses of the compiled model: a steady mean with the operating point of the averaged model
  (a turning machine's steady state), a harmonic with the small-signal response to the
  circuit's own shaft-angle harmonic (``analyses.harmonic_response``). The small-signal
  response is the default because it is a smooth, noise-free function of the parameters (a
  Newton solve and a linear solve, ~10 ms), so the finite-difference Jacobian of the fit is
  clean; the exact periodic steady state (``harmonic='pss'``, shooting) differs from it by
  second-order terms only (4e-6 relative for the Kim & Kim ripple) and costs ~30x more.
- a **record** (time series) is compared sample by sample with a transient simulated on the
  record's time grid (output error), each probe normalised by its measured spread.

A ripple locked to the rotor angle slides out of phase as soon as the modelled speed is off by
a fraction of a percent, so the raw time-domain residual of a rotating machine is dominated by
phase misalignment and its least-squares cost has a local minimum every time the accumulated
phase error passes a multiple of 2 pi. The record fit is therefore **staged**: stage 1 fits
phase-insensitive slow features -- Hann-weighted means and ripple RMS over overlapping windows
at least ten ripple periods long (the window's side lobes suppress a misaligned ripple by
~60 dB) -- and stage 2 refines on the full waveform starting from there, inside the basin of
the true minimum.

Parameters move in a scaled space: a parameter with a non-zero start value moves as
``start * exp(z)`` (its sign is kept, positive parameters stay positive, and z is a relative
change), a zero one as ``z * scale``. Standard errors and correlations come from the Jacobian
at the optimum, scaled by the residual variance (per probe for a record); when the
information is near-singular (condition number, or |correlation| > 0.99) the parameters
involved are flagged and no standard error is given for them.

Top-level imports stay light (numpy only): the CLI imports this module on every call.
"""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import math
import warnings
from collections import OrderedDict
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from circuitsim.errors import CircuitsimError, ParameterError, SolverError
from circuitsim.loop import slip
from circuitsim.loop.record import DataError, FeatureSet, Record
from circuitsim.solve.route import serial_blas

# |correlation| above which two estimates are reported as not told apart
CORRELATION_LIMIT = 0.99
# condition number of the column-normalised information matrix above which the fit is
# reported as near-singular (a pair at |corr| = 0.99 gives ~200, so this catches groups of
# three or more parameters whose pairwise correlations all look harmless)
CONDITION_LIMIT = 1e6
# default box for a log-scaled parameter: a factor 1e4 either way of its start value
LOG_SPAN = math.log(1e4)
# RMS change of the normalised residual that a unit step of a zero-start parameter's scaled
# coordinate should cause (see ``_calibrate``)
CALIBRATION_TARGET = 0.1
# penalty per residual when a simulation fails inside the fit (a normalised residual of a
# sensible model is O(1)): the trust region shrinks away from the failing parameters
FAILED_PENALTY = 1e2
#: Relative change of cost and parameters that ends the slow-feature stage of a record fit:
#: that stage only brings the waveform stage into its basin, a few digits are enough there.
SLOW_STAGE_TOL = 1e-3
#: Runs a record fit keeps for revisited points: the Jacobian's neighbours of the last point
#: and the point itself (a few parameters, central differences).
MEMO_RUNS = 16
# smoothing windows of stage 1 are at least this many ripple periods long
WINDOW_PERIODS = 10


class FitError(CircuitsimError):
    """The fit is ill-posed as asked (no data for it, bad bounds, nothing to compare)."""


class FitWarning(UserWarning):
    """Parameters that the data cannot tell apart; a fit that did not converge."""


# ----------------------------------------------------------------------------- results

@dataclass(frozen=True)
class Stage:
    """One least-squares stage: what it compared, where it ended, its cost ½Σr²."""

    name: str
    estimate: dict[str, float]
    cost: float
    nfev: int
    message: str


@dataclass(frozen=True)
class FitResult:
    """Estimates of the free parameters [SI] and what the data say about them.

    Attributes
    ----------
    free : the free parameters, in order.
    start, estimate : their start values and estimates [SI].
    stderr : standard errors [SI]; NaN where the data cannot tell a parameter apart from
        others, or where the fit is exact and the features give no sigma.
    correlation : (n, n) correlation matrix of the estimates.
    condition : condition number of the column-normalised information matrix JᵀJ.
    identifiable : False when near-singular (see ``warnings``).
    kind : 'record' or 'features'.
    residuals : measured - model; per probe on the record's time grid (record), or per
        feature label (features).
    errors : per probe, NRMSE = RMS(residual) / RMS(measured - its mean) (record; NaN for a
        flat column, which has no spread); per feature, the residual in sigmas (or relative
        to the value when no sigma is given).
    params : every override of the fitted model (fixed ones and the estimates) [SI]:
        ``model.simulate(params=fit.params)`` reproduces the fit.
    sim : the fitted transient on the record's grid (record), else None.
    reduction : what ``loop.reduce.reduce_record`` did to the record (record), else None;
        residuals, errors and ``sim`` are on the working record it produced.
    predicted : model values of the features at the estimate (features), else empty.
    stages : the least-squares stages run, in order.
    """

    free: tuple[str, ...]
    start: dict[str, float]
    estimate: dict[str, float]
    stderr: dict[str, float]
    correlation: np.ndarray
    condition: float
    identifiable: bool
    warnings: tuple[str, ...]
    kind: str
    residuals: dict[str, Any]
    errors: dict[str, float]
    params: dict[str, float]
    success: bool
    message: str
    nfev: int
    stages: tuple[Stage, ...] = ()
    sim: Any = field(default=None, repr=False)
    predicted: dict[str, float] = field(default_factory=dict)
    measured: dict[str, float] = field(default_factory=dict)
    sigma: dict[str, float | None] = field(default_factory=dict)
    units: dict[str, str] = field(default_factory=dict)
    reduction: Any = None

    @property
    def error(self) -> float:
        """Root-mean-square over probes of each probe's NRMSE (record), or over features of
        the normalised residuals (features); a flat probe's (NaN) left out, NaN if all are."""
        v = np.array(list(self.errors.values()), float)
        if v.size and not np.any(np.isfinite(v)):
            return math.nan
        v = v[np.isfinite(v)]
        return float(np.sqrt(np.mean(v**2))) if v.size else 0.0

    def as_dict(self) -> dict:
        """JSON-ready report (NaN becomes null)."""

        def num(x: float) -> float | None:
            return float(x) if x is not None and math.isfinite(x) else None

        out: dict[str, Any] = {
            "kind": self.kind, "success": self.success, "message": self.message,
            "free": list(self.free),
            "parameters": {n: {"start": num(self.start[n]), "estimate": num(self.estimate[n]),
                               "stderr": num(self.stderr[n]), "unit": self.units.get(n, "")}
                           for n in self.free},
            "correlation": [[num(c) for c in row] for row in self.correlation.tolist()],
            "condition_number": num(self.condition),
            "identifiable": self.identifiable,
            "warnings": list(self.warnings),
            "error": num(self.error),
            "errors": {k: num(v) for k, v in self.errors.items()},
            "nfev": self.nfev,
            "stages": [{"name": s.name, "estimate": s.estimate, "cost": num(s.cost),
                        "nfev": s.nfev, "message": s.message} for s in self.stages],
            "params": self.params,
        }
        if self.kind == "features":
            out["features"] = [{"feature": k, "measured": self.measured[k],
                                "model": self.predicted[k], "sigma": self.sigma[k],
                                "residual": num(self.residuals[k])} for k in self.predicted]
        else:
            out["rms_residual"] = {k: float(np.sqrt(np.mean(np.asarray(v) ** 2)))
                                   for k, v in self.residuals.items()}
            if self.reduction is not None:
                out["record"] = self.reduction.as_dict()
        return out


# ----------------------------------------------------------------- parameter space

@dataclass(frozen=True)
class _Space:
    """Free parameters in the scaled coordinates z (see the module docstring)."""

    names: tuple[str, ...]
    start: np.ndarray
    log: np.ndarray
    scale: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    # the bounds in the parameters' own units (-inf, inf where none): z at its bound maps
    # back a rounding beyond it, which a later fit from these values would refuse
    floor: np.ndarray | None = None
    ceil: np.ndarray | None = None

    def theta(self, z: np.ndarray) -> np.ndarray:
        th = np.where(self.log, self.start * np.exp(np.where(self.log, z, 0.0)),
                      self.start + self.scale * z)
        return th if self.floor is None else np.clip(th, self.floor, self.ceil)

    def dtheta(self, z: np.ndarray) -> np.ndarray:
        return np.where(self.log, self.theta(z), self.scale)

    def z_of(self, theta: np.ndarray) -> np.ndarray:
        with np.errstate(all="ignore"):
            return np.where(self.log, np.log(np.where(self.log, theta / self.start, 1.0)),
                            (theta - self.start) / self.scale)


def _space(model, free: Sequence[str], params: Mapping[str, float],
           bounds: Mapping[str, tuple[float, float]] | None) -> _Space:
    from circuitsim.compiler.model import _near

    net = model.netlist
    comp = model.meta["params"]
    for name in free:
        if name not in net.parameters and name not in comp:
            raise ParameterError(f"--free {name}: no such parameter"
                                 f"{_near(name, [*net.parameters, *comp])}; free a netlist "
                                 f"parameter (La) or a component parameter (La.L); "
                                 f"`circuitsim check NETLIST` lists them")
    if len(set(free)) != len(free):
        raise FitError("a parameter is listed twice in --free")
    bounds = dict(bounds or {})
    for b in bounds:
        if b not in free:
            raise FitError(f"bounds given for '{b}', which is not free")
    glob = net.global_values({k: v for k, v in params.items() if k in net.parameters})
    comp_vals = model.param_values(params)
    start = np.array([glob[n] if n in net.parameters else comp_vals[n] for n in free], float)
    log = start != 0.0
    scale = np.ones(len(free))
    lo = np.where(log, -LOG_SPAN, -np.inf)
    hi = np.where(log, LOG_SPAN, np.inf)
    floor, ceil = np.full(len(free), -np.inf), np.full(len(free), np.inf)
    for k, n in enumerate(free):
        if n not in bounds:
            continue
        a, b = sorted(float(v) for v in bounds[n])
        floor[k], ceil[k] = a, b
        # a start placed on a bound may arrive a rounding off it (aa04's inertia correction,
        # screened to its floor of -0.9, was refused as outside [-0.9, 10])
        edge = 1e-9 * max((abs(v) for v in (a, b) if math.isfinite(v)), default=0.0)
        if a - edge <= start[k] <= b + edge:
            start[k] = min(max(start[k], a), b)
            log[k] = start[k] != 0.0  # a start clipped to a zero bound has no magnitude
        else:
            raise FitError(f"the start value of {n} ({start[k]:g}) is outside its bounds "
                           f"[{a:g}, {b:g}]; --set {n}=... inside them")
        if log[k]:
            if a * start[k] <= 0 or b * start[k] <= 0:
                # a bound across zero: the sign may change, so move linearly
                log[k] = False
                scale[k] = abs(start[k])
                lo[k], hi[k] = (a - start[k]) / scale[k], (b - start[k]) / scale[k]
            else:
                zs = sorted((math.log(a / start[k]), math.log(b / start[k])))
                lo[k], hi[k] = zs
        else:
            scale[k] = (b - a) / 10 if math.isfinite(b - a) and b > a else 1.0
            lo[k], hi[k] = (a - start[k]) / scale[k], (b - start[k]) / scale[k]
    # least_squares needs a strictly feasible start
    lo = np.minimum(lo, -1e-12)
    hi = np.maximum(hi, 1e-12)
    return _Space(tuple(free), start, log, scale, lo, hi, floor, ceil)


def _calibrate(space: _Space, fun: Callable[[np.ndarray], np.ndarray], z0: np.ndarray,
               r0: np.ndarray, bounds: Mapping[str, tuple[float, float]] | None) -> _Space:
    """Rescale the parameters that start at zero so that a unit step in z moves the
    normalised residual by CALIBRATION_TARGET (RMS).

    A zero start has no magnitude to scale by, and a fixed SI unit is meaningless across
    domains: 1 N is a large step for a friction force and a tiny one for a 1e4 N bound's
    tenth. With a poor scale the finite-difference step of the fit (1e-5 in z) either drowns
    in the simulation's own error -- the parameter then never moves -- or jumps out of the
    linear range. One or two extra evaluations per such parameter fix it.
    """
    scale, lo, hi = space.scale.copy(), space.lo.copy(), space.hi.copy()
    n = max(r0.size, 1)
    for k in np.flatnonzero(~space.log & (space.start == 0.0)):
        for _ in range(3):
            # ``fun`` works in the caller's coordinates (the old scale): a unit step in the
            # new ones is scale/old-scale there; it stays inside the bounds
            d = _inside(space, z0, k, float(scale[k] / space.scale[k]))
            if d == 0.0:
                break
            step = np.zeros_like(z0)
            step[k] = d
            r = fun(z0 + step)
            if _failed(r):
                break  # the model fails there: keep the scale we have
            # RMS change per unit of the new coordinate
            change = float(np.linalg.norm(r - r0)) / math.sqrt(n) / \
                (abs(d) * space.scale[k] / scale[k])
            if not math.isfinite(change) or change <= 0.0:
                break  # no effect: leave it (the uncertainty report says so)
            ratio = CALIBRATION_TARGET / change
            if 0.3 < ratio < 3.0:
                break
            # the response may be nonlinear: do not jump by more than 1e3 per try
            scale[k] *= min(max(ratio, 1e-3), 1e3)
        name = space.names[k]
        if bounds and name in bounds:
            a, b = sorted(float(v) for v in bounds[name])
            lo[k], hi[k] = (a - space.start[k]) / scale[k], (b - space.start[k]) / scale[k]
    return dataclasses.replace(space, scale=scale, lo=np.minimum(lo, -1e-12),
                               hi=np.maximum(hi, 1e-12))


# ------------------------------------------------------------------- least squares core

def _least_squares(fun: Callable[[np.ndarray], np.ndarray], space: _Space, z0: np.ndarray,
                   diff_step: float | np.ndarray, max_nfev: int,
                   many: Callable[[list[np.ndarray]], list[np.ndarray]] | None = None,
                   tol: float = 1e-8):
    """scipy's trust-region least squares in z, with forward differences of *absolute* step
    ``diff_step`` in z (a relative change of a log-scaled parameter).

    scipy's own ``diff_step`` is relative to |z|, which near the start (z = 0) shrinks the
    step to round-off size: the simulation's own error (~1e-7 of a normalised residual at
    rtol 1e-8) then swamps the difference and the trust region collapses.
    """
    from scipy.optimize import least_squares

    last: dict[str, np.ndarray] = {}
    steps = np.broadcast_to(np.asarray(diff_step, float), z0.shape)

    def f(z: np.ndarray) -> np.ndarray:
        r = fun(z)
        last["z"], last["r"] = z.copy(), r
        return r

    def jac(z: np.ndarray) -> np.ndarray:
        hs = [_inside(space, z, k, float(steps[k])) or float(steps[k]) for k in range(z.size)]
        shifted = []
        for k, h in enumerate(hs):
            zz = z.copy()
            zz[k] += h
            shifted.append(zz)
        if many is not None:
            # the point and its neighbours in one batched run: one step sequence for all,
            # so the differences carry no integration noise of their own
            r0, *rs = many([z, *shifted])
        else:
            r0 = last["r"] if "z" in last and np.array_equal(last["z"], z) else fun(z)
            rs = [fun(zz) for zz in shifted]
        return np.column_stack([(r - r0) / h for r, h in zip(rs, hs, strict=True)])

    # a start on a bound (a friction force starting at 0 >= 0) is feasible but freezes the
    # trust region: its affine scaling shrinks every step to the distance to the bound
    margin = np.minimum(1e-2, 1e-2 * (space.hi - space.lo))
    z0 = np.clip(z0, space.lo + margin, space.hi - margin)
    return least_squares(f, z0, jac=jac, bounds=(space.lo, space.hi), method="trf",
                         x_scale=1.0, xtol=tol, ftol=tol, gtol=1e-10, max_nfev=max_nfev)


def _difference_steps(fun: Callable[[np.ndarray], np.ndarray], z: np.ndarray, r0: np.ndarray,
                      space: _Space, noise: float) -> np.ndarray:
    """Forward-difference step per parameter in z, sized to the simulation's own noise.

    A simulated output carries the integrator's error, which jumps with its step pattern
    whenever a parameter moves; how large it is depends on the model (a stiff position loop
    turns a 1e-9 m position error into a millinewton of force). ``noise`` is its norm (the
    caller measures it: the same run at another tolerance); the signal comes from a 1e-3 step,
    and each step is set so that the noise is at most a tenth of the difference, within
    [1e-5, 1e-2]. A smooth model keeps 1e-5: a ripple locked to the rotor angle turns
    nonlinear when the speed moves by much more.
    """
    n = z.size
    steps = np.full(n, 1e-5)
    for k in range(n):
        h = _inside(space, z, k, 1e-3)
        if h == 0.0:
            continue
        zz = z.copy()
        zz[k] += h
        r = fun(zz)
        if _failed(r):
            continue
        slope = float(np.linalg.norm(r - r0)) / abs(h)
        if slope > 0:
            steps[k] = min(max(10 * noise / slope, 1e-5), 1e-2)
    return steps


def _failed(r: np.ndarray) -> bool:
    """A residual vector that stands for a failed simulation (see FAILED_PENALTY)."""
    return bool(r.size) and bool(np.all(r == FAILED_PENALTY))


def _inside(space: _Space, z: np.ndarray, k: int, h: float) -> float:
    """A step of size up to |h| along z_k that stays inside the box: forward if there is
    room, else backward, shortened to the room there is (0.0: no room at all)."""
    up, down = space.hi[k] - z[k], z[k] - space.lo[k]
    if up >= h:
        return h
    if down >= h:
        return -h
    return max(up, -down, key=abs) * 0.5


def _jacobian(fun: Callable[[np.ndarray], np.ndarray], z: np.ndarray,
              h: float | np.ndarray, space: _Space | None = None
              ) -> tuple[np.ndarray, list[int]]:
    """Central differences in z (z is a relative change for log-scaled parameters); one-sided
    where a bound is closer than the step, and never outside the box: a parameter fitted onto
    its bound (a friction of 0 >= 0) must not be evaluated at a forbidden value. Returns the
    Jacobian and the columns whose every evaluation failed (those are zero)."""
    hs = np.broadcast_to(np.asarray(h, float), z.shape)
    r0: np.ndarray | None = None
    cols, bad = [], []
    for k in range(z.size):
        hk = float(hs[k])
        up = space.hi[k] - z[k] if space is not None else np.inf
        down = z[k] - space.lo[k] if space is not None else np.inf
        col = None
        if up >= hk and down >= hk:
            zp, zm = z.copy(), z.copy()
            zp[k] += hk
            zm[k] -= hk
            rp, rm = fun(zp), fun(zm)
            if not (_failed(rp) or _failed(rm)):
                col = (rp - rm) / (2 * hk)
        if col is None:
            if r0 is None:
                r0 = fun(z)
            short = _inside(space, z, k, hk) if space is not None else 0.0
            for d in (hk, -hk, short):
                if d == 0.0 or (d > 0 and up < d) or (d < 0 and down < -d):
                    continue
                zz = z.copy()
                zz[k] += d
                r = fun(zz)
                if not _failed(r):
                    col = (r - r0) / d
                    break
        if col is None:
            bad.append(k)
            col = np.zeros(r0.size if r0 is not None else fun(z).size)
        cols.append(col)
    if not cols:
        return np.zeros((fun(z).size, 0)), []
    return np.column_stack(cols), bad


def _central_points(z: np.ndarray, h: np.ndarray, space: _Space) -> list[np.ndarray]:
    """The points ``_jacobian`` evaluates where both sides are inside the box."""
    out = []
    for k in range(z.size):
        if space.hi[k] - z[k] >= h[k] and z[k] - space.lo[k] >= h[k]:
            e = np.eye(z.size)[k] * h[k]
            out += [z + e, z - e]
    return out


def _unevaluated(unc: _Uncertainty, bad: list[int], space: _Space) -> _Uncertainty:
    """No standard error where the model failed on both sides of the estimate."""
    if not bad:
        return unc
    import dataclasses

    stderr = unc.stderr.copy()
    stderr[bad] = np.nan
    msgs = tuple(f"{space.names[k]}: the model fails on both sides of its estimate, so its "
                 f"sensitivity (and standard error) could not be evaluated; check the "
                 f"fitted values with `circuitsim run --set`" for k in bad)
    return dataclasses.replace(unc, stderr=stderr, flagged=tuple(sorted({*unc.flagged, *bad})),
                               warnings=unc.warnings + msgs)


@dataclass(frozen=True)
class _Uncertainty:
    stderr: np.ndarray
    correlation: np.ndarray
    condition: float
    flagged: tuple[int, ...]
    warnings: tuple[str, ...]


def _long_run_information(J: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Jᵀ R J for a residual r with stationary autocorrelation R (unit variance) [-].

    A record's residual is rarely white: an effect the model lacks leaves a slow, correlated
    error, and treating its samples as independent makes the standard errors too small by
    the square root of its correlation time. The autocorrelation is estimated from r and
    weighted with a Bartlett window (so the result stays positive semi-definite) out to the
    lag of Andrews' (1991) AR(1) rule; for white noise the window is one or two samples and
    this is JᵀJ. Like every Bartlett estimate it runs low for very long correlation times
    (measured on AR(1) residuals: -3 % at phi = 0.9 over 2e5 samples, -15..-25 % at
    phi = 0.99 over 5e3).
    """
    m = r.size
    rr = float(r @ r)
    if m < 8 or rr == 0.0:
        return J.T @ J
    rho1 = float(np.clip(r[1:] @ r[:-1] / rr, -0.99, 0.99))
    alpha = 4 * rho1**2 / ((1 - rho1) ** 2 * (1 + rho1) ** 2)
    lags = int(min(1.1447 * (alpha * m) ** (1 / 3), m // 4))
    if lags < 1:
        return J.T @ J
    size = 1 << int(2 * m - 1).bit_length()
    fr = np.fft.rfft(r, size)
    rho = np.fft.irfft(fr * np.conj(fr), size)[: lags + 1] / rr
    w = (1 - np.arange(lags + 1) / (lags + 1)) * rho
    fj = np.fft.rfft(J, size, axis=0)
    n = J.shape[1]
    out = np.empty((n, n))
    for a in range(n):
        # cross-correlations of column a with every column, lags 0..L
        cc = np.fft.irfft(np.conj(fj[:, a:a + 1]) * fj, size, axis=0)[: lags + 1]
        out[a] = w @ cc
    # out[a, b] = sum_l w_l sum_t J[t, a] J[t + l, b]; add the negative lags
    return out + out.T - w[0] * (J.T @ J)


def _uncertainty(J: np.ndarray, r: np.ndarray, space: _Space, z: np.ndarray,
                 groups: list[np.ndarray] | None, absolute: bool) -> _Uncertainty:
    """Covariance of the estimates from the Jacobian J = dr/dz at the optimum.

    ``groups`` (record fits): index sets of the residual, one per probe, each with its own
    noise variance estimated from its residual; the covariance is the sandwich
    A⁻¹ (Σ_p σ_p² J_pᵀJ_p) A⁻¹ with A = JᵀJ, which is right whatever weights the fit used.
    ``absolute``: r is already in units of its standard deviation (features with sigma).
    Otherwise the residual variance SSR / (m - n) scales A⁻¹.
    """
    m, n = J.shape
    names = space.names
    if n == 0:
        return _Uncertainty(np.zeros(0), np.zeros((0, 0)), 1.0, (), ())
    norms = np.linalg.norm(J, axis=0)
    dead = norms == 0
    cn = np.where(dead, 1.0, norms)
    Jn = J / cn
    A = Jn.T @ Jn
    lam, V = np.linalg.eigh(A)
    lam_max = max(float(lam.max()), 1e-300)
    cond = lam_max / max(float(lam.min()), 1e-300 * lam_max, 1e-308)
    # a floored inverse keeps the near-null direction huge but finite, so the correlation
    # of two interchangeable parameters comes out as the trade-off it is (about -1)
    Ainv = (V / np.maximum(lam, 1e-14 * lam_max)) @ V.T
    msgs: list[str] = []
    dof = m - n
    if groups is not None:
        cov_n = _sandwich(Jn, r, groups, A, Ainv, lam, lam_max, n, m)
    elif absolute:
        cov_n = Ainv
    elif dof > 0:
        cov_n = Ainv * float(r @ r) / dof
    else:
        cov_n = Ainv * np.nan
        msgs.append(f"{m} measured values for {n} free parameters and no sigma given: the "
                    f"fit is exact and the data say nothing about its uncertainty. Give each "
                    f"feature a 'sigma', or measure more")
    cov_z = cov_n / np.outer(cn, cn)
    d = space.dtheta(z)
    cov = cov_z * np.outer(d, d)
    sd = np.sqrt(np.abs(np.diag(cov_n)))
    with np.errstate(all="ignore"):
        corr = cov_n / np.outer(sd, sd) if np.all(np.isfinite(sd)) else \
            Ainv / np.sqrt(np.outer(np.diag(Ainv), np.diag(Ainv)))
    corr = np.clip(np.nan_to_num(corr), -1.0, 1.0)
    np.fill_diagonal(corr, 1.0)
    stderr = np.sqrt(np.abs(np.diag(cov)))
    flagged, more = _unidentifiable(names, dead, corr, lam, V, cond)
    msgs += more
    stderr = np.where(np.isin(np.arange(n), sorted(flagged)), np.nan, stderr)
    return _Uncertainty(stderr, corr, float(cond), tuple(sorted(flagged)), tuple(msgs))


def _sandwich(Jn, r, groups, A, Ainv, lam, lam_max, n: int, m: int) -> np.ndarray:
    """A⁻¹ (Σ_p σ_p² J_pᵀJ_p) A⁻¹, with long-run (HAC) information per probe."""
    B = np.zeros((n, n))
    for g in groups:
        mg = g.size
        s2 = float(r[g] @ r[g]) / max(mg - n * mg / m, 1.0)
        B += s2 * _long_run_information(Jn[g], r[g])
    # the sandwich squares the floored inverse and would wipe out a null direction;
    # there a scalar noise level keeps the trade-off visible
    if lam.min() > 1e-12 * lam_max:
        return Ainv @ B @ Ainv
    return Ainv * float(np.trace(B) / np.trace(A))


def _unidentifiable(names, dead, corr, lam, V, cond) -> tuple[set[int], list[str]]:
    """Parameters the data cannot determine: without effect (a dead column), or only as a
    combination with others (a strong correlation, a near-null direction); with the message
    that says what to do about each."""
    n = len(names)
    lam_max = max(float(lam.max()), 1e-300)
    flagged: set[int] = set()
    msgs: list[str] = []
    for k in np.flatnonzero(dead):
        flagged.add(int(k))
        msgs.append(f"{names[k]} has no effect on the measured values: it cannot be "
                    f"estimated from these data. Fix it (do not free it), or measure a probe "
                    f"it acts on")
    pairs = [(a, b) for a in range(n) for b in range(a + 1, n)
             if abs(corr[a, b]) > CORRELATION_LIMIT and not (dead[a] or dead[b])]
    weak = [V[:, k] for k in range(n) if lam[k] < lam_max / CONDITION_LIMIT]
    groups_bad: list[set[int]] = [{a, b} for a, b in pairs]
    for v in weak:
        g = {int(j) for j in np.flatnonzero(np.abs(v) > 0.1) if not dead[j]}
        if len(g) > 1:
            groups_bad.append(g)
    merged: list[set[int]] = []
    for g in groups_bad:
        for h in [h for h in merged if h & g]:
            merged.remove(h)
            g = g | h
        merged.append(g)
    for g in merged:
        flagged |= g
        members = sorted(g)
        worst = max(((a, b) for a in members for b in members if a < b),
                    key=lambda ab: abs(corr[ab]))
        msgs.append(f"{', '.join(names[j] for j in members)} cannot be told apart from these "
                    f"data: only a combination of them is determined (correlation "
                    f"{names[worst[0]]}-{names[worst[1]]} = {corr[worst]:+.4f}, information "
                    f"condition number {cond:.3g}); their standard errors would be "
                    f"meaningless. Fix all but one of them (--set), or measure a probe that "
                    f"separates them")
    return flagged, msgs


# ------------------------------------------------------------------------- features

def predict_features(model, features: FeatureSet, params: Mapping[str, float] | None = None,
                     harmonic: str = "small-signal") -> np.ndarray:
    """Model values of ``features`` [SI] with parameter overrides ``params``.

    A ``mean`` is the probe at the operating point of the averaged model (a turning machine's
    steady state); a harmonic ``amplitude``/``frequency`` is the small-signal response to the
    circuit's own shaft-angle harmonic of that order (``harmonic='small-signal'``) or the
    order-th harmonic of the exact periodic steady state (``harmonic='pss'``).
    """
    from circuitsim.solve.ac import harmonic_response, linearize
    from circuitsim.solve.op import probe_values
    from circuitsim.solve.pss import periodic_steady_state

    if harmonic not in ("small-signal", "pss"):
        raise FitError(f"harmonic must be 'small-signal' or 'pss', not {harmonic!r}")
    params = dict(params or {})
    wants_harmonic = any(f.quantity != "mean" for f in features.features)
    if wants_harmonic and not model.shafts:
        raise DataError("a harmonic feature needs a turning shaft in the netlist (its order "
                        "counts per revolution)", features.features[0].loc)
    lin = linearize(model, params)
    means: dict[str, float] | None = None
    pss: dict[float, Any] = {}
    out = []
    for f in features.features:
        if f.quantity == "mean":
            if means is None:
                means = probe_values(model, lin.op, params)
            out.append(means[f.probe])
            continue
        if harmonic == "small-signal":
            try:
                h = harmonic_response(model, f.order, f.probe, params, lin=lin)
            except ValueError as exc:
                raise DataError(f"feature {f.label}: {exc}", f.loc) from None
            out.append(h.amplitude if f.quantity == "amplitude" else h.frequency)
        else:
            if f.order not in pss:
                pss[f.order] = periodic_steady_state(model, params, order=f.order)
            freq, amp, _ = pss[f.order].harmonic(f.probe, 1)
            out.append(amp if f.quantity == "amplitude" else freq)
    return np.array(out, float)


def fit_features(model, features: FeatureSet, free: Sequence[str], *,
                 params: Mapping[str, float] | None = None,
                 bounds: Mapping[str, tuple[float, float]] | None = None,
                 harmonic: str = "small-signal", max_nfev: int = 200,
                 progress: Callable[[str], None] | None = None) -> FitResult:
    """Fit ``free`` parameters of a compiled model to measured features.

    Parameters
    ----------
    model : a CompiledModel.
    features : measured features (``data.load_features``).
    free : parameter names to estimate: netlist parameters (``La``) or component parameters
        (``La.L``).
    params : other overrides [SI]; a value for a free parameter is its start value.
    bounds : ``{name: (low, high)}`` [SI]; default: a factor 1e4 either way of the start,
        sign kept.
    harmonic : 'small-signal' (default) or 'pss' (see ``predict_features``).
    max_nfev : largest number of model evaluations (Jacobian evaluations not counted).
    progress : called with a line of text after each evaluation of the model.

    Returns
    -------
    FitResult
        With ``kind='features'``; each feature's residual in ``residuals`` [SI] and in sigmas
        (or relative to its value when no sigma is given) in ``errors``.
    """
    features.check(model)
    params = dict(params or {})
    space = _space(model, free, params, bounds)
    vals = np.array([f.value for f in features.features])
    absolute = all(f.sigma is not None for f in features.features)
    w = np.array([f.sigma if f.sigma is not None else max(abs(f.value), 1e-300)
                  for f in features.features])
    failures = [0]

    def overrides(z: np.ndarray) -> dict[str, float]:
        return {**params, **dict(zip(space.names, space.theta(z).tolist(), strict=True))}

    fun = _feature_residual(model, features, overrides, harmonic, vals, w, failures,
                            progress)
    z0 = np.zeros(len(free))
    r0 = fun(z0)
    if failures[0]:
        raise SolverError("the model's analyses fail at the start values; check them with "
                          "`circuitsim op NETLIST`")
    space = _calibrate(space, fun, z0, r0, bounds)
    stages: list[Stage] = []
    if free:
        diff = 1e-6 if harmonic == "small-signal" else 1e-4
        sol = _least_squares(fun, space, z0, diff, max_nfev)
        z, nfev, ok, msg = sol.x, int(sol.nfev), bool(sol.status > 0), str(sol.message)
        stages.append(Stage("features", _named(space, z), float(sol.cost), nfev, msg))
    else:
        z, nfev, ok, msg = z0, 1, True, "nothing free: the residuals of the start values"
    r = fun(z) if free else r0
    h = 1e-5 if harmonic == "small-signal" else 1e-3
    J, bad = _jacobian(fun, z, h, space) if free else (np.zeros((vals.size, 0)), [])
    unc = _unevaluated(_uncertainty(J, r, space, z, None, absolute), bad, space)
    return _features_result(model, features, space, z, unc, overrides(z), harmonic, vals, w,
                            ok, msg, nfev, stages)


def _feature_residual(model, features: FeatureSet, overrides, harmonic: str,
                      vals: np.ndarray, w: np.ndarray, failures: list[int],
                      progress: Callable[[str], None] | None = None):
    """The features' residual in sigmas at a parameter vector z (a failed evaluation counts
    in ``failures`` and returns the penalty)."""
    calls = [0]

    def fun(z: np.ndarray) -> np.ndarray:
        calls[0] += 1
        try:
            pred = predict_features(model, features, overrides(z), harmonic)
        except (SolverError, ParameterError, np.linalg.LinAlgError):
            failures[0] += 1
            return np.full(vals.size, FAILED_PENALTY)
        r = (pred - vals) / w
        if progress is not None:
            progress(f"features: {calls[0]} evaluations, cost {0.5 * float(r @ r):.6g}")
        return r

    return fun


def _features_result(model, features: FeatureSet, space: _Space, z: np.ndarray, unc, fitted,
                     harmonic: str, vals: np.ndarray, w: np.ndarray, ok: bool, msg: str,
                     nfev: int, stages: list[Stage]) -> FitResult:
    pred = predict_features(model, features, fitted, harmonic)
    labels = _labels(features)
    return _result(model, space, z, unc, "features", ok, msg, nfev, stages,
                   residuals={k: float(v - p) for k, v, p in zip(labels, vals, pred,
                                                                 strict=True)},
                   errors={k: float((v - p) / s) for k, v, p, s in zip(labels, vals, pred, w,
                                                                       strict=True)},
                   params=fitted, predicted=dict(zip(labels, pred.tolist(), strict=True)),
                   measured=dict(zip(labels, vals.tolist(), strict=True)),
                   sigma={k: f.sigma for k, f in zip(labels, features.features, strict=True)})


def _labels(features: FeatureSet) -> list[str]:
    out: list[str] = []
    for f in features.features:
        label, k = f.label, 2
        while label in out:
            label, k = f"{f.label} #{k}", k + 1
        out.append(label)
    return out


# ---------------------------------------------------------------------------- records

def _probes_of(model, record: Record, probes: Sequence[str] | None) -> list[str]:
    names = list(probes) if probes else [p for p in model.probe_names if p in record.columns]
    for p in names:
        if p not in model.probe_names:
            raise FitError(f"'{p}' is not a probe of the netlist (probes: "
                           f"{', '.join(model.probe_names)})")
        if p not in record.columns:
            raise DataError(f"the record has no column '{p}' (columns: "
                            f"{', '.join(record.names)}). Measure it, or leave it out of "
                            f"--probes", None)
    if not names:
        raise DataError(f"record '{record.path}' has no column for any probe of the netlist "
                        f"({', '.join(model.probe_names)})")
    return names


def _spread(x: np.ndarray) -> float:
    """Measured spread of a probe: its standard deviation (its mean's size if it is flat)."""
    s = float(np.std(x))
    return s if s > 1e-12 * (1 + float(np.max(np.abs(x)))) else max(float(np.mean(np.abs(x))),
                                                                      1.0)


#: the windows of the last few records: a diagnosis refits one record some thirty times, and
#: finding its strongest ripple (``_window_length``) costs more than a small model's fit
_WINDOWS: OrderedDict[bytes, Any] = OrderedDict()
_WINDOWS_KEPT = 4


def smoothing_windows(t: np.ndarray, columns: Sequence[np.ndarray]):
    """``_smoothing_windows`` of a record, kept for the record's next fit (``_WINDOWS``):
    keyed by a digest of its times and columns, so a changed record is never served stale
    windows. The matrix returned is shared: callers only multiply with it."""
    digest = hashlib.blake2b(digest_size=20)
    for x in (t, *columns):
        a = np.ascontiguousarray(x, dtype=float)
        digest.update(np.int64(a.size).tobytes())
        digest.update(a.tobytes())
    key = digest.digest()
    W = _WINDOWS.get(key)
    if W is None:
        W = _WINDOWS[key] = _smoothing_windows(np.asarray(t, float), columns)
    with contextlib.suppress(KeyError):  # another thread's fit may have dropped it meanwhile
        _WINDOWS.move_to_end(key)
        while len(_WINDOWS) > _WINDOWS_KEPT:
            _WINDOWS.popitem(last=False)
    return W


def _smoothing_windows(t: np.ndarray, columns: Sequence[np.ndarray]):
    """Row-normalised Hann weights for the slow features of stage 1, as a sparse
    (n_windows, n_samples) matrix (scipy ``csr_array``: each sample lies in about two
    windows, so a long record costs two weights a sample, not one per window).

    Windows are at least ``WINDOW_PERIODS`` periods of the strongest ripple found in the
    second half of the record, and at least 1/20 of it; they overlap by half. Trapezoidal
    sample weights make the average right on a non-uniform grid.
    """
    from scipy.sparse import csr_array

    duration = float(t[-1] - t[0])
    length = _window_length(t, columns, duration)
    hop = length / 2
    centers = t[0] + length / 2 + hop * np.arange(int((duration - length) / hop + 1e-9) + 1)
    dt = np.empty_like(t)
    dt[1:-1] = (t[2:] - t[:-2]) / 2
    dt[0], dt[-1] = (t[1] - t[0]) / 2, (t[-1] - t[-2]) / 2
    rows, cols, vals = [], [], []
    for k, c in enumerate(centers):
        # the samples with |t - c| < length / 2, where the Hann weight is not zero
        a = int(np.searchsorted(t, c - length / 2, side="right"))
        b = int(np.searchsorted(t, c + length / 2, side="left"))
        u = (t[a:b] - c) / length
        w = 0.5 * (1 + np.cos(2 * np.pi * u)) * dt[a:b]
        rows.append(np.full(b - a, k))
        cols.append(np.arange(a, b))
        vals.append(w / w.sum())
    return csr_array((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                     shape=(centers.size, t.size))


def _window_length(t: np.ndarray, columns: Sequence[np.ndarray], duration: float) -> float:
    """Length of the slow-feature windows [s]: WINDOW_PERIODS periods of the strongest
    ripple of the record's second half, within [duration / 20, duration / 2]."""
    from circuitsim.signal import dominant_ripple

    period = 0.0
    best = 0.0
    half = t >= t[0] + 0.5 * duration
    for x in columns:
        try:
            h = dominant_ripple(t[half], x[half])
        except ValueError:
            continue
        rel = h.amplitude / _spread(x)
        if h.frequency > 0 and rel > best:
            best, period = rel, 1.0 / h.frequency
    return min(max(WINDOW_PERIODS * period, duration / 20), duration / 2)


def slow_features(W, x: np.ndarray) -> np.ndarray:
    """Windowed means and ripple RMS of ``x`` (phase-insensitive summaries)."""
    m = W @ x
    rms = np.sqrt(np.maximum(W @ (x * x) - m * m, 0.0))
    return np.concatenate([m, rms])


@serial_blas
def fit_record(model, record: Record, free: Sequence[str], *,
               params: Mapping[str, float] | None = None,
               bounds: Mapping[str, tuple[float, float]] | None = None,
               probes: Sequence[str] | None = None, staged: bool = True,
               rtol: float = 1e-8, atol: float | None = None,
               max_nfev: int = 100, weights: Mapping[str, float] | None = None,
               tol: float = 1e-8, reduce: bool = True,
               progress: Callable[[str], None] | None = None,
               refuse_slip: bool = True) -> FitResult:
    """Fit ``free`` parameters of a compiled model to a measured record (output error).

    The model is simulated from rest on the record's time grid and compared with each probe
    column, normalised by the column's spread. With ``staged=True`` (default) a first stage
    fits the phase-insensitive slow features (``smoothing_windows``, ``slow_features``) and
    the second refines on the full waveform from there; ``staged=False`` is the naive
    single-stage waveform fit (it falls into a local minimum when a ripple locked to the
    rotor angle is misaligned, see the module docstring). A model without a shaft angle has
    no such ripple and is always fitted in one stage.

    Parameters
    ----------
    model : a CompiledModel.
    record : measured time series (``data.load_record``); simulation starts at t = 0.
    free : parameter names to estimate (``La`` or ``La.L``).
    params : other overrides [SI]; a value for a free parameter is its start value.
    bounds : ``{name: (low, high)}`` [SI]; default: a factor 1e4 either way, sign kept.
    probes : probe columns to compare (default: every probe the record has).
    staged : slow features first, then the waveform (default), or the waveform only.
    rtol, atol : integrator tolerances for the fit's simulations; tighter than a plain run
        because finite differences of the parameters must see the model, not the solver.
    max_nfev, tol : largest number of simulations per stage (Jacobian evaluations not
        counted); relative change of the cost and of the parameters that ends a stage [-].
    weights : per probe, the scale its residual is divided by [probe unit] (its noise level,
        when known; on a reduced record, the working record's); default: the probe's spread.
    reduce : first bring a long, oversampled record to the resolution its content needs
        (``loop.reduce.reduce_record``). progress : called with a line at each simulation.
    refuse_slip : raise DataError when the record matches the fitted model only after a
        unit's factor or a sign (``loop.slip``), and warn of what ``slip.hints`` asks to check.

    Returns
    -------
    FitResult
        With ``kind='record'``, ``sim`` the fitted transient, ``residuals[probe]`` = measured -
        model on the (working) record's grid, ``errors[probe]`` the NRMSE, ``reduction``.
    """
    record, reduction = _working_record(model, record, probes, reduce, progress)
    prob = _RecordProblem(model, record, free, dict(params or {}), bounds, probes, weights,
                          rtol, atol, progress)
    z = np.zeros(len(free))
    r0 = _started(prob, z, bounds)
    step = prob.difference_steps(z, r0) if free else np.zeros(0)
    z, ok, msg, nfev, stages = _run_stages(prob, z, step, staged if free else None, max_nfev,
                                           tol)
    prob.stage = "uncertainty"
    result = prob.result(z, step, ok, msg, nfev, stages)
    if refuse_slip:
        result = _slips_said(model, record, result)
    return dataclasses.replace(result, reduction=reduction)


def _slips_said(model, record: Record, result: FitResult) -> FitResult:
    """A unit's slip refused (DataError); a clock or a scale, the user's or the model's,
    said in the result's warnings (``loop.slip``), judged against the fitted run itself."""
    runs = {p: result.sim[p] for p in result.residuals}
    slip.refuse(model, record, result.residuals, runs)
    notes = slip.hints(model, record, result.residuals, result.error, runs)
    return dataclasses.replace(result, warnings=(*result.warnings, *notes))


def _started(prob: _RecordProblem, z: np.ndarray, bounds) -> np.ndarray:
    """The residual at the start values ``z``; a parameter that starts at 0 has its scale
    calibrated from there (``_calibrate``)."""
    r0 = prob.full(z)
    if prob.failures:
        raise SolverError(f"the simulation fails at the start values of the fit, on the "
                          f"record's times at the fit's rtol {prob.rtol:g} (by default "
                          f"tighter than a plain run's): {prob.why or 'no reason given'}. "
                          f"Fix what it names, or the start values; a looser rtol may pass "
                          f"where the model sits on a threshold")
    if np.any(~prob.space.log & (prob.space.start == 0.0)):
        prob.space = _calibrate(prob.space, prob.full, z, r0, bounds)
        prob.failures = 0
    return r0


def _working_record(model, record: Record, probes, reduce: bool, progress):
    """The record a fit works on (``loop.reduce``), and what its reduction did."""
    from circuitsim.loop.reduce import reduce_record
    from circuitsim.solve.route import many_solves

    many_solves()  # a fit solves one topology many times
    if not reduce:
        return record, None
    return reduce_record(record, _probes_of(model, record, probes), progress=progress)


def _run_stages(prob: _RecordProblem, z: np.ndarray, step: np.ndarray, staged: bool | None,
                max_nfev: int, tol: float) -> tuple[np.ndarray, bool, str, int, list[Stage]]:
    """The least-squares stages of a record fit in turn (none when ``staged`` is None:
    nothing is free); returns where they end, how, and what each did."""
    stages: list[Stage] = []
    nfev = 0
    ok, msg = True, "nothing free: the residuals of the start values"
    for name, fun in prob.plan(staged) if staged is not None else []:
        prob.stage = name
        stage_tol = tol if fun == prob.full else max(tol, SLOW_STAGE_TOL)
        sol = _least_squares(fun, prob.space, z, step, max_nfev, prob.batched(fun), stage_tol)
        z = sol.x
        nfev += int(sol.nfev)
        ok, msg = bool(sol.status > 0), str(sol.message)
        stages.append(Stage(name, _named(prob.space, z), float(sol.cost), int(sol.nfev), msg))
    return z, ok, msg, nfev, stages


class _RecordProblem:
    """The output-error problem of one record: simulations at a parameter vector ``z`` and
    the residual vectors the least-squares stages minimise."""

    def __init__(self, model, record: Record, free: Sequence[str], params: dict[str, float],
                 bounds, probes, weights, rtol: float, atol: float | None,
                 say: Callable[[str], None] | None = None):
        self.model, self.params, self.rtol = model, params, rtol
        self.names = _probes_of(model, record, probes)
        self.space = _space(model, free, params, bounds)
        self.data = [np.asarray(record[p], float) for p in self.names]
        # each probe's residual is divided by its scale: its noise level when the caller
        # knows it (then a probe counts by its signal-to-noise ratio), else its spread
        self.spread = np.array([weights[p] if weights and p in weights else _spread(x)
                                for p, x in zip(self.names, self.data, strict=True)])
        self.t = np.asarray(record.t, float)
        self.atol = atol if atol is not None else model.netlist.analysis.atol
        self.failures = 0
        self.why = ""  # the last failed run's message
        self.say = say
        self.stage, self.runs = "start", 0
        self.W = smoothing_windows(self.t, self.data)
        self.memo: dict[bytes, Any] = {}
        self.slow_data = [slow_features(self.W, x) for x in self.data]

    def overrides(self, z: np.ndarray) -> dict[str, float]:
        return {**self.params,
                **dict(zip(self.space.names, self.space.theta(z).tolist(), strict=True))}

    def tell(self, r: np.ndarray) -> np.ndarray:
        """Report the simulations so far and the cost of the residual ``r`` (returned)."""
        if self.say is not None:
            self.say(f"{self.stage}: {self.runs} simulations, cost {0.5 * float(r @ r):.6g}")
        return r

    def simulate(self, z: np.ndarray, rtol: float | None = None):
        key = z.tobytes()
        if rtol is None and key in self.memo:
            return self.memo[key]
        self.runs += 1
        try:
            res = self.model.simulate(stop=float(self.t[-1]), params=self.overrides(z),
                                      t_eval=self.t, rtol=rtol or self.rtol, atol=self.atol)
        except ParameterError:
            return None
        if not res.success or res.t.size != self.t.size:
            self.why = (res.message if not res.success else
                        f"it gave {res.t.size} of {self.t.size} output times")
            res = None
        if rtol is None:
            self.remember(key, res)
        return res

    def remember(self, key: bytes, res) -> None:
        """Keep a run for the points the least squares revisits (its accepted point is the
        next Jacobian's base; the result re-reads the optimum), a few at a time: a run of a
        long record is large."""
        self.memo[key] = res
        while len(self.memo) > MEMO_RUNS:
            self.memo.pop(next(iter(self.memo)))

    def prefetch(self, zs: Sequence[np.ndarray], again: bool = False) -> None:
        """Simulate the points not yet known (``again``: all of them) in one batched
        integration: one step sequence for all, so differences between them carry no
        integration noise of their own."""
        from circuitsim.solve.batch import simulate_batch

        todo = list({z.tobytes(): z for z in zs if again or z.tobytes() not in self.memo
                     }.values())
        if len(todo) < 2:
            return
        self.runs += len(todo)
        try:
            runs = simulate_batch(self.model, [self.overrides(z) for z in todo],
                                  stop=float(self.t[-1]), t_eval=self.t, rtol=self.rtol,
                                  atol=self.atol, nearby=True)
        except ParameterError:
            return
        for z, res in zip(todo, runs, strict=True):
            ok = res.success and res.t.size == self.t.size
            self.remember(z.tobytes(), res if ok else None)

    def batched(self, fun: Callable[[np.ndarray], np.ndarray]
                ) -> Callable[[list[np.ndarray]], list[np.ndarray]]:
        """``fun`` at several points, their runs made in one batched integration."""
        def many(zs: list[np.ndarray]) -> list[np.ndarray]:
            self.prefetch(zs, again=True)
            return [fun(z) for z in zs]
        return many

    def waveforms(self, z: np.ndarray) -> list[np.ndarray] | None:
        res = self.simulate(z)
        return None if res is None else [res[p] for p in self.names]

    def full(self, z: np.ndarray) -> np.ndarray:
        ys = self.waveforms(z)
        if ys is None:
            self.failures += 1
            return np.full(self.t.size * len(self.names), FAILED_PENALTY)
        return self.tell(np.concatenate([(y - x) / s for y, x, s in
                                         zip(ys, self.data, self.spread, strict=True)]))

    def slow(self, z: np.ndarray) -> np.ndarray:
        ys = self.waveforms(z)
        if ys is None:
            self.failures += 1
            return np.full(sum(d.size for d in self.slow_data), FAILED_PENALTY)
        return self.tell(np.concatenate([(slow_features(self.W, y) - d) / s for y, d, s in
                                         zip(ys, self.slow_data, self.spread, strict=True)]))

    def difference_steps(self, z: np.ndarray, r0: np.ndarray) -> np.ndarray:
        """Finite-difference steps sized to the simulation's own noise: the same run at
        another tolerance."""
        alt = self.simulate(z, self.rtol * 1.5)
        noise = float(np.linalg.norm(np.concatenate(
            [(alt[p] - x) / s for p, x, s in zip(self.names, self.data, self.spread,
                                                 strict=True)]) - r0)) if alt is not None else 0.0
        self.prefetch([z, *(z + h * np.eye(z.size)[k] for k in range(z.size)
                            if (h := _inside(self.space, z, k, 1e-3)) != 0.0)], again=True)
        return _difference_steps(self.full, z, self.full(z), self.space, noise)

    def plan(self, staged: bool) -> list[tuple[str, Any]]:
        # without a shaft angle there is no ripple to slide out of phase: the waveform's own
        # cost has no spurious minima from it, and the slow stage would only cost runs
        rotating = "rotational" in self.model.meta.get("integrals", {}).values()
        return [("slow features", self.slow), ("waveform", self.full)] \
            if staged and rotating else [("waveform", self.full)]

    def result(self, z: np.ndarray, step: np.ndarray, ok: bool, msg: str, nfev: int,
               stages: list[Stage]) -> FitResult:
        r = self.full(z)
        if self.failures and self.simulate(z) is None:
            raise SolverError("the simulation fails at the fitted values; bound the "
                              "parameters (bounds=...) or start closer")
        n = len(self.space.names)
        self.prefetch([z, *_central_points(z, 10 * step, self.space)], again=True)
        J, bad = _jacobian(self.full, z, 10 * step, self.space) if n else \
            (np.zeros((r.size, 0)), [])
        groups = [np.arange(k * self.t.size, (k + 1) * self.t.size)
                  for k in range(len(self.names))]
        unc = _unevaluated(_uncertainty(J, r, self.space, z, groups, False), bad, self.space)
        sim = self.simulate(z)
        residuals = {p: x - sim[p] for p, x in zip(self.names, self.data, strict=True)}
        # a flat column (a locked rotor's speed) has no spread to normalise by: NaN, not 1e300
        errors = {p: float(np.sqrt(np.mean(residuals[p] ** 2)) / np.std(x)) if np.std(x) > 0
                  else math.nan for p, x in zip(self.names, self.data, strict=True)}
        return _result(self.model, self.space, z, unc, "record", ok, msg, nfev, stages,
                       residuals=residuals, errors=errors, params=self.overrides(z), sim=sim)


# -------------------------------------------------------------------------- dispatch

def fit(model, data: Record | FeatureSet, free: Sequence[str], **kw) -> FitResult:
    """Fit ``free`` parameters to a record (``fit_record``) or features (``fit_features``)."""
    if isinstance(data, FeatureSet):
        return fit_features(model, data, free, **kw)
    if isinstance(data, Record):
        return fit_record(model, data, free, **kw)
    raise TypeError(f"data must be a Record or a FeatureSet, not {type(data).__name__}")


def _named(space: _Space, z: np.ndarray) -> dict[str, float]:
    return dict(zip(space.names, space.theta(z).tolist(), strict=True))


def param_unit(model, name: str) -> str:
    """Unit of a netlist or component parameter, for display."""
    for comp in model.netlist.components:
        for key, val in comp.values.items():
            if key == name:
                return val.unit
    for comp in model.netlist.components:
        for val in comp.values.values():
            if val.node.kind == "name" and val.node.value == name:
                return val.unit
    return ""


def _result(model, space: _Space, z: np.ndarray, unc: _Uncertainty, kind: str, ok: bool,
            msg: str, nfev: int, stages: list[Stage], **kw) -> FitResult:
    theta = space.theta(z)
    names = space.names
    msgs = list(unc.warnings)
    at_bound = [n for k, n in enumerate(names)
                if min(z[k] - space.lo[k], space.hi[k] - z[k]) < 1e-6]
    if at_bound:
        msgs.append(f"{', '.join(at_bound)} ended at a bound: the optimum may lie beyond it "
                    f"and the standard error assumes it does not; widen the bounds")
    if not ok:
        msgs.append(f"the least-squares fit did not converge: {msg}")
    for m in msgs:
        warnings.warn(m, FitWarning, stacklevel=3)
    return FitResult(
        free=names, start=dict(zip(names, space.start.tolist(), strict=True)),
        estimate=dict(zip(names, theta.tolist(), strict=True)),
        stderr=dict(zip(names, unc.stderr.tolist(), strict=True)),
        correlation=unc.correlation, condition=unc.condition,
        identifiable=not unc.flagged,
        warnings=tuple(msgs), kind=kind, success=ok, message=msg, nfev=nfev,
        stages=tuple(stages), units={n: param_unit(model, n) for n in names}, **kw)


# ------------------------------------------------------------------------------- CLI


def format_result(result: FitResult, title: str = "") -> str:
    """Human-readable summary: estimates ± standard errors, correlations, residuals."""
    lines = [title] if title else []
    if result.reduction is not None and result.reduction.reduced:
        lines.append(result.reduction.note())
    lines.append(f"fit of {len(result.free)} parameter(s) to {result.kind}: "
                 f"{'converged' if result.success else 'NOT converged'} ({result.nfev} "
                 f"evaluations; stages: {', '.join(s.name for s in result.stages) or '-'})")
    if result.free:
        lines.append(f"{'parameter':<16}{'start':>14}{'estimate':>16}{'std. error':>14}"
                     f"{'rel.':>9}  unit")
        for n in result.free:
            est, se = result.estimate[n], result.stderr[n]
            ratio = abs(se / est) if math.isfinite(se) and est else math.nan
            # a standard error of ten times the estimate or more determines nothing
            rel = ("-" if not math.isfinite(ratio) else
                   f"{ratio:.2%}" if ratio < 10 else ">1000%")
            se_s = f"{se:14.5g}" if math.isfinite(se) else f"{'(see warning)':>14}"
            lines.append(f"{n:<16}{result.start[n]:>14.6g}{est:>16.8g}{se_s}{rel:>9}  "
                         f"{result.units.get(n, '')}")
        if len(result.free) > 1:
            lines.append("correlation:")
            w = max(max(len(n) for n in result.free) + 2, 9)
            lines.append(" " * w + "".join(f"{n:>{w}}" for n in result.free))
            for i, n in enumerate(result.free):
                lines.append(f"{n:<{w}}" + "".join(f"{c:>{w}.4f}"
                                                   for c in result.correlation[i]))
        lines.append(f"information condition number: {result.condition:.3g}")
    if result.kind == "features":
        lines.append(f"{'feature':<34}{'measured':>14}{'model':>14}{'residual':>14}")
        for k in result.predicted:
            lines.append(f"{k:<34}{result.measured[k]:>14.6g}{result.predicted[k]:>14.6g}"
                         f"{result.residuals[k]:>14.4g}")
    else:
        lines.append(f"{'probe':<16}{'NRMSE':>10}{'RMS residual':>16}")
        for k, v in result.errors.items():
            rms = float(np.sqrt(np.mean(np.asarray(result.residuals[k]) ** 2)))
            nrmse = f"{v:>10.4g}" if math.isfinite(v) else f"{'flat':>10}"
            lines.append(f"{k:<16}{nrmse}{rms:>16.5g}")
    for m in result.warnings:
        lines.append(f"WARNING: {m}")
    return "\n".join(lines)


