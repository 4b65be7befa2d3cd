"""Independent reference implementations used by tests and benchmarks to cross-check circuitsim.

Nothing in here imports circuitsim: the models are written out by hand so that a bug in the
simulator cannot hide in the reference.

Contents
--------
* ``KIM_BASE`` -- parameters of the Kim & Kim 2024 brushed-DC-motor model (no filter).
* ``kim_base_ode`` / ``simulate_kim_lsoda`` -- the model as an explicit ODE, optionally with a
  series filter inductor ``Lf`` (resistance ``Rf``) between the source and the varistor node,
  integrated with scipy ``solve_ivp(method="LSODA")``.
* ``kim_dc_steady_state`` / ``small_signal_i8`` -- DC operating point and the linear
  small-signal amplitude of the 8th-order current ripple.
* ``fit_ripple`` -- offset + trend + sine fit (FFT peak, then variable projection);
  ``resample`` -- cubic-spline resampling onto a uniform grid.
* Closed forms: ``rc_step``, ``rl_step``, ``rlc_series_step``, ``dc_motor_step``,
  ``dc_motor_steady_speed``, ``dc_motor_sine`` (from rest under an offset sine).
* ``errnorm`` -- tolerance-normalised maximum error.

Model (Kim & Kim 2024, see shared/REFERENCE.md section 1)
---------------------------------------------------------
Ideal source ``Vin`` -> [``Rf`` + ``Lf`` filter, optional] -> node a. Varistor ``Rv`` + ``Cv``
from a to ground. Connector inductor ``Lc`` a->b, armature ``Ra``, ``La`` and back-EMF ``e``
b->c, second ``Lc`` c->ground. Loop current ``i``, series inductance ``Lm = La + 2 Lc``::

    e  = k_e*w + e0 + A8*sin(8*theta),   A8 = a8_slope*w + a8_offset
    Lm*i' = v_a - Ra*i - e
    J*w'  = k_t*i - B*w                  (the ripple produces no torque)
    theta' = w

Units are SI throughout: V, A, ohm, H, F, s, rad, rad/s, kg*m^2, N*m.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_ivp
from scipy.interpolate import CubicSpline
from scipy.optimize import minimize_scalar

__all__ = [
    "KIM_BASE",
    "dc_motor_sine",
    "dc_motor_steady_speed",
    "dc_motor_step",
    "errnorm",
    "fit_ripple",
    "kim_base_ode",
    "kim_dc_steady_state",
    "kim_initial_state",
    "rc_step",
    "resample",
    "rl_step",
    "rlc_series_step",
    "simulate_kim_lsoda",
    "small_signal_i8",
]

FloatArray = NDArray[np.float64]

#: Kim & Kim 2024 base model (no filter). Keys and units:
#: Vin [V], Rv [ohm], Cv [F], L_conn [H] (each of the two connector inductors), Ra [ohm],
#: La [H], J [kg*m^2], B [N*m*s/rad], k_t [N*m/A], k_e [V*s/rad], e0 [V] (DC offset of the
#: back-EMF), a8_slope [V*s/rad] and a8_offset [V] (8th-order amplitude A8 = a8_slope*w +
#: a8_offset). The paper's per-Hz coefficients are converted with 1 rev/s = 2*pi rad/s.
KIM_BASE: dict[str, float] = {
    "Vin": 12.0,
    "Rv": 500e6,
    "Cv": 1.6e-6,
    "L_conn": 0.22e-6,
    "Ra": 1.1,
    "La": 0.87e-3,
    "J": 4.57e-6,
    "B": 2.95e-4,
    "k_t": 0.14,
    "k_e": 0.1017 / (2.0 * math.pi),
    "e0": 1.151e-4,
    "a8_slope": 0.0021 * 8.0 / (2.0 * math.pi),
    "a8_offset": 2.504e-5,
}


def _params(params: Mapping[str, float] | None) -> dict[str, float]:
    """Return ``KIM_BASE`` updated with ``params`` (unknown keys raise ``KeyError``)."""
    p = dict(KIM_BASE)
    if params:
        unknown = set(params) - set(p)
        if unknown:
            raise KeyError(f"unknown Kim parameter(s): {sorted(unknown)}")
        p.update(params)
    return p


# ---------------------------------------------------------------------------------------------
# Kim & Kim 2024 model as an ODE
# ---------------------------------------------------------------------------------------------


def kim_base_ode(
    params: Mapping[str, float] | None = None, lf: float = 0.0, rf: float = 0.0
) -> Callable[[float, FloatArray], FloatArray]:
    """Right-hand side ``f(t, y)`` of the Kim & Kim model, optionally with a series filter.

    Parameters
    ----------
    params : overrides of ``KIM_BASE`` entries (same keys and units).
    lf : series filter inductance [H] between the source and node a (0 = no inductor).
    rf : series filter resistance [ohm] (in series with ``lf``; may be used with ``lf == 0``).

    State vector ``y``
    ------------------
    * ``lf == 0``: ``[v_cap [V], i [A], w [rad/s], theta [rad]]``.
      With ``rf == 0`` node a is tied to the ideal source and the varistor branch does not
      affect the motor; ``v_cap`` is still integrated. With ``rf > 0`` the node voltage follows
      from KCL at a: ``(Vin - v_a)/Rf = i + (v_a - v_cap)/Rv`` (algebraic, solved exactly).
    * ``lf > 0``: ``[i_f [A], v_cap [V], i [A], w [rad/s], theta [rad]]`` where ``i_f`` is the
      filter current. Node a is then set by the varistor: ``v_a = v_cap + Rv*(i_f - i)``, and
      ``Lf*i_f' = Vin - Rf*i_f - v_a``, ``Cv*v_cap' = i_f - i``. This is honest but very stiff
      (fast eigenvalue about ``-Rv*(1/Lf + 1/Lm)``), hence the analytic Jacobian.

    Returns
    -------
    The callable ``f(t, y) -> dy/dt``. It carries attributes ``jac`` (analytic Jacobian
    ``jac(t, y) -> (n, n) array``), ``state_names`` (tuple of str) and ``n_states`` (int).
    """
    p = _params(params)
    vin, rv, cv = p["Vin"], p["Rv"], p["Cv"]
    ra, lm = p["Ra"], p["La"] + 2.0 * p["L_conn"]
    jm, bm, kt, ke = p["J"], p["B"], p["k_t"], p["k_e"]
    e0, a8s, a8o = p["e0"], p["a8_slope"], p["a8_offset"]
    lf = float(lf)
    rf = float(rf)
    if lf < 0.0 or rf < 0.0:
        raise ValueError("lf and rf must be >= 0")

    def emf(w: float, th: float) -> tuple[float, float, float]:
        """Back-EMF e [V] and its partial derivatives de/dw [V*s/rad], de/dtheta [V/rad]."""
        s8 = math.sin(8.0 * th)
        c8 = math.cos(8.0 * th)
        a8 = a8s * w + a8o
        return ke * w + e0 + a8 * s8, ke + a8s * s8, 8.0 * a8 * c8

    if lf > 0.0:

        def rhs(t: float, y: FloatArray) -> FloatArray:
            i_f, vc, i, w, th = y
            e = emf(w, th)[0]
            va = vc + rv * (i_f - i)
            return np.array(
                [
                    (vin - rf * i_f - va) / lf,
                    (i_f - i) / cv,
                    (va - ra * i - e) / lm,
                    (kt * i - bm * w) / jm,
                    w,
                ]
            )

        def jac(t: float, y: FloatArray) -> FloatArray:
            _, _, _, w, th = y
            _, de_dw, de_dth = emf(w, th)
            return np.array(
                [
                    [-(rf + rv) / lf, -1.0 / lf, rv / lf, 0.0, 0.0],
                    [1.0 / cv, 0.0, -1.0 / cv, 0.0, 0.0],
                    [rv / lm, 1.0 / lm, -(rv + ra) / lm, -de_dw / lm, -de_dth / lm],
                    [0.0, 0.0, kt / jm, -bm / jm, 0.0],
                    [0.0, 0.0, 0.0, 1.0, 0.0],
                ]
            )

        names: tuple[str, ...] = ("i_f", "v_cap", "i", "omega", "theta")
    else:
        if rf > 0.0:
            # v_a = g_s*Vin + g_v*v_cap - r_par*i  (KCL at node a, exact)
            r_par = 1.0 / (1.0 / rf + 1.0 / rv)
            g_s, g_v = r_par / rf, r_par / rv
        else:
            r_par, g_s, g_v = 0.0, 1.0, 0.0

        def rhs(t: float, y: FloatArray) -> FloatArray:
            vc, i, w, th = y
            e = emf(w, th)[0]
            va = g_s * vin + g_v * vc - r_par * i
            return np.array(
                [(va - vc) / (rv * cv), (va - ra * i - e) / lm, (kt * i - bm * w) / jm, w]
            )

        def jac(t: float, y: FloatArray) -> FloatArray:
            _, _, w, th = y
            _, de_dw, de_dth = emf(w, th)
            return np.array(
                [
                    [(g_v - 1.0) / (rv * cv), -r_par / (rv * cv), 0.0, 0.0],
                    [g_v / lm, -(r_par + ra) / lm, -de_dw / lm, -de_dth / lm],
                    [0.0, kt / jm, -bm / jm, 0.0],
                    [0.0, 0.0, 1.0, 0.0],
                ]
            )

        names = ("v_cap", "i", "omega", "theta")

    f: Any = rhs
    f.jac = jac
    f.state_names = names
    f.n_states = len(names)
    return f


def kim_initial_state(lf: float = 0.0) -> FloatArray:
    """Initial state from rest (all currents [A], v_cap [V], w [rad/s], theta [rad] zero).

    Length 4 for ``lf == 0`` and 5 for ``lf > 0`` (see ``kim_base_ode``).
    """
    return np.zeros(5 if lf > 0.0 else 4)


def simulate_kim_lsoda(
    t_stop: float = 0.3,
    t_eval: ArrayLike | None = None,
    params: Mapping[str, float] | None = None,
    lf: float = 0.0,
    rf: float = 0.0,
    rtol: float = 1e-10,
    atol: float = 1e-12,
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """Integrate the Kim & Kim model from rest with scipy ``solve_ivp(method="LSODA")``.

    Parameters
    ----------
    t_stop : end time [s].
    t_eval : output times [s] (e.g. a uniform grid for ripple analysis); ``None`` returns the
        solver's own steps.
    params, lf, rf : model parameters, filter inductance [H], filter resistance [ohm]
        (see ``kim_base_ode``).
    rtol, atol : solver tolerances (``atol`` [A / V / rad/s / rad], applied to all states).

    Returns
    -------
    ``(t [s], i [A], omega [rad/s], theta [rad], v_cap [V])``; ``i`` is the motor loop current.

    Raises
    ------
    RuntimeError if the integration fails.
    """
    f = kim_base_ode(params, lf, rf)
    y0 = kim_initial_state(lf)
    te = None if t_eval is None else np.asarray(t_eval, dtype=float)
    sol = solve_ivp(
        f,
        (0.0, float(t_stop)),
        y0,
        method="LSODA",
        t_eval=te,
        rtol=rtol,
        atol=atol,
        jac=f.jac,  # type: ignore[attr-defined]
    )
    if not sol.success:
        raise RuntimeError(f"LSODA failed: {sol.message}")
    y = sol.y
    k = 1 if lf > 0.0 else 0  # offset of v_cap in the state vector
    vcap = y[k]
    return sol.t, y[k + 1], y[k + 2], y[k + 3], vcap


def kim_dc_steady_state(
    params: Mapping[str, float] | None = None, rf: float = 0.0
) -> tuple[float, float, float]:
    """DC operating point of the Kim & Kim model, ripple neglected.

    Derivation: at DC the inductors are shorts and the varistor capacitor blocks, so
    ``Vin - e0 - k_e*w = (Ra + Rf)*i`` and ``k_t*i = B*w``. Eliminating ``i``::

        w    = k_t*(Vin - e0) / (k_t*k_e + B*(Ra + Rf))      [rad/s]
        i_dc = B*w / k_t                                     [A]
        e_dc = k_e*w + e0                                    [V]

    The 8th-order ripple adds second-order DC terms (products of ripples), so a simulation
    differs from these by about 1e-6 relative (648.5052 vs 648.505195 rad/s).

    Returns ``(omega [rad/s], i_dc [A], e_dc [V])``.
    """
    p = _params(params)
    kt, ke, bm = p["k_t"], p["k_e"], p["B"]
    w = kt * (p["Vin"] - p["e0"]) / (kt * ke + bm * (p["Ra"] + rf))
    return w, bm * w / kt, ke * w + p["e0"]


def small_signal_i8(
    params: Mapping[str, float] | None = None,
    lf: float = 0.0,
    rf: float = 0.0,
    f: float | None = None,
    varistor: bool = True,
) -> float:
    """Linear small-signal amplitude [A] of the 8th-order current ripple.

    ``I8 = |A8 / Z|`` with the loop impedance at ``Omega = 8*w`` [rad/s]::

        Z = Ra + j*Omega*(La + 2*Lc) + k_t*k_e/(j*Omega*J + B) + Z_src
        Z_src = Rf + j*Omega*Lf                  (varistor=False; the textbook formula)
        Z_src = (Rf + j*Omega*Lf) || (Rv + 1/(j*Omega*Cv))   (varistor=True, default)

    The varistor shunt changes the result by < 1e-8 relative for the paper's values.
    ``k_t*k_e/(j*Omega*J + B)`` is the mechanical feedback (inertia seen through the EMF).

    Parameters
    ----------
    params : overrides of ``KIM_BASE``.
    lf, rf : series filter inductance [H] and resistance [ohm].
    f : ripple frequency [Hz]. ``None`` uses ``8*w/(2*pi)`` with ``w`` from
        ``kim_dc_steady_state(params, rf)``. If given, ``w = 2*pi*f/8`` is used both for
        ``Omega`` and for ``A8 = a8_slope*w + a8_offset``.
    varistor : include the varistor shunt in the source impedance (only matters if lf or rf).
    """
    p = _params(params)
    if f is None:
        w = kim_dc_steady_state(p, rf)[0]
    else:
        w = 2.0 * math.pi * float(f) / 8.0
    om = 8.0 * w
    a8 = p["a8_slope"] * w + p["a8_offset"]
    z_src: complex = complex(rf, om * lf)
    if varistor and z_src != 0:
        z_v = complex(p["Rv"], -1.0 / (om * p["Cv"]))
        z_src = z_src * z_v / (z_src + z_v)
    z = (
        p["Ra"]
        + 1j * om * (p["La"] + 2.0 * p["L_conn"])
        + p["k_t"] * p["k_e"] / (1j * om * p["J"] + p["B"])
        + z_src
    )
    return abs(a8 / z)


# ---------------------------------------------------------------------------------------------
# Ripple extraction
# ---------------------------------------------------------------------------------------------


def resample(t: ArrayLike, y: ArrayLike, t_new: ArrayLike) -> FloatArray:
    """Resample samples ``y(t)`` onto ``t_new`` with a not-a-knot cubic spline.

    ``t`` [s] strictly increasing (duplicate time points, as some solvers emit at
    breakpoints, are dropped keeping the last value). Use this rather than ``np.interp`` before
    measuring ripple amplitudes: linear interpolation of a sine sampled every ``dt`` shrinks
    its amplitude by about ``(2*pi*f*dt)^2/12`` (2e-4 at 826 Hz and dt = 10 us).
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    keep = np.append(np.diff(t) > 0.0, True)
    return CubicSpline(t[keep], y[keep])(np.asarray(t_new, dtype=float))


def fit_ripple(
    t: ArrayLike, y: ArrayLike, f_guess: float | None = None, f_band: float | None = None
) -> dict[str, float]:
    """Fit ``y ~ c0 + c1*(t - t_mid) + a*cos(2*pi*f*t) + b*sin(2*pi*f*t)`` on a steady window.

    ``t`` [s] should be a uniform grid; a non-uniform ``t`` (e.g. raw ngspice time points) is
    first resampled onto ``len(t)`` uniform points with ``resample`` (cubic spline; linear
    interpolation would bias the amplitude by about ``-(2*pi*f*dt)^2/12``). The frequency is
    started at the peak of a Hann-windowed FFT (parabolic interpolation of the
    log-magnitude), restricted to ``f_guess +- f_band`` if
    ``f_guess`` [Hz] is given (default band: 10 % of ``f_guess``), then refined by minimising
    the residual of the linear least-squares fit over ``f`` (variable projection, bounded
    Brent search within +- 2 FFT bins). No whole number of periods is needed.

    Returns a dict with ``freq`` [Hz], ``amp`` [units of y] (sine amplitude ``hypot(a, b)``),
    ``phase`` [rad] (of ``amp*sin(2*pi*f*t + phase)``), ``offset`` (mean level ``c0`` at the
    window centre), ``trend`` [units of y per s] and ``rms_resid``.
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    n = t.size
    if n < 16 or y.shape != t.shape:
        raise ValueError("need t and y of equal length >= 16")
    dt = (t[-1] - t[0]) / (n - 1)
    if not np.allclose(np.diff(t), dt, rtol=1e-6, atol=0.0):
        t_u = np.linspace(t[0], t[-1], n)
        y = resample(t, y, t_u)
        t = t_u
    tm = t - 0.5 * (t[0] + t[-1])
    yd = y - np.polyval(np.polyfit(tm, y, 1), tm)
    spec = np.abs(np.fft.rfft(yd * np.hanning(n)))
    freqs = np.fft.rfftfreq(n, dt)
    df = freqs[1]
    mask = np.ones_like(freqs, dtype=bool)
    mask[0] = False
    if f_guess is not None:
        band = 0.1 * f_guess if f_band is None else f_band
        mask &= np.abs(freqs - f_guess) <= max(band, 2.0 * df)
    k = int(np.flatnonzero(mask)[np.argmax(spec[mask])])
    f0 = freqs[k]
    if 0 < k < spec.size - 1:
        la, lb, lc = np.log(spec[k - 1 : k + 2] + 1e-300)
        den = la - 2.0 * lb + lc
        if den != 0.0:
            f0 += 0.5 * (la - lc) / den * df

    def solve(fr: float) -> tuple[FloatArray, float]:
        ph = 2.0 * math.pi * fr * t
        a = np.column_stack([np.ones(n), tm, np.cos(ph), np.sin(ph)])
        c, *_ = np.linalg.lstsq(a, y, rcond=None)
        r = y - a @ c
        return c, float(r @ r)

    res = minimize_scalar(
        lambda fr: solve(fr)[1],
        bounds=(f0 - 2.0 * df, f0 + 2.0 * df),
        method="bounded",
        options={"xatol": 1e-10 * max(f0, 1.0)},
    )
    fr = float(res.x)
    c, rss = solve(fr)
    return {
        "freq": fr,
        "amp": float(math.hypot(c[2], c[3])),
        "phase": float(math.atan2(c[2], c[3])),
        "offset": float(c[0]),
        "trend": float(c[1]),
        "rms_resid": math.sqrt(rss / n),
    }


# ---------------------------------------------------------------------------------------------
# Closed forms
# ---------------------------------------------------------------------------------------------


def rc_step(t: ArrayLike, R: float, C: float, V: float) -> FloatArray:
    """Capacitor voltage [V] of a series RC driven by a step ``V`` [V] at t = 0 from rest.

    ``v_C(t) = V*(1 - exp(-t/(R*C)))``; ``t`` [s], ``R`` [ohm], ``C`` [F].
    """
    t = np.asarray(t, dtype=float)
    return V * -np.expm1(-t / (R * C))


def rl_step(t: ArrayLike, R: float, L: float, V: float) -> FloatArray:
    """Current [A] of a series RL driven by a step ``V`` [V] at t = 0 from rest.

    ``i(t) = V/R*(1 - exp(-R*t/L))``; ``t`` [s], ``R`` [ohm], ``L`` [H].
    """
    t = np.asarray(t, dtype=float)
    return V / R * -np.expm1(-R * t / L)


def _exp_cos_sin(sig: float, disc: float, t: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``(e^(sig t)*c(t), e^(sig t)*s(t))`` for a 2nd-order mode with roots ``sig +- sqrt(disc)``.

    ``disc < 0``: ``c = cos(nu t)``, ``s = sin(nu t)/nu`` with ``nu = sqrt(-disc)``;
    ``disc > 0``: ``c = cosh(r t)``, ``s = sinh(r t)/r`` with ``r = sqrt(disc)``;
    ``disc == 0``: ``c = 1``, ``s = t``. Continuous through critical damping; the real case is
    evaluated as ``e^((sig + r) t)*(1 +- e^(-2 r t))/2`` so it neither overflows nor cancels.
    ``sig`` [1/s], ``disc`` [1/s^2], ``t`` [s].
    """
    if disc < 0.0:
        nu = math.sqrt(-disc)
        es = np.exp(sig * t)
        return es * np.cos(nu * t), es * np.sin(nu * t) / nu
    if disc > 0.0:
        r = math.sqrt(disc)
        g = np.exp((sig + r) * t)
        return 0.5 * g * (1.0 + np.exp(-2.0 * r * t)), g * -np.expm1(-2.0 * r * t) / (2.0 * r)
    es = np.exp(sig * t)
    return es, es * t


def rlc_series_step(
    t: ArrayLike, R: float, L: float, C: float, V: float
) -> tuple[FloatArray, FloatArray]:
    """Capacitor voltage [V] and loop current [A] of a series RLC, step ``V`` [V], from rest.

    With ``alpha = R/(2L)`` [1/s], ``w0 = 1/sqrt(L*C)`` [rad/s]; underdamped
    (``alpha < w0``), ``wd = sqrt(w0^2 - alpha^2)`` [rad/s]::

        v_C(t) = V*(1 - exp(-alpha*t)*(cos(wd*t) + alpha/wd*sin(wd*t)))
        i(t)   = C*v_C'(t) = V/(L*wd)*exp(-alpha*t)*sin(wd*t)

    The same expressions with ``cos -> cosh``, ``sin(wd t)/wd -> sinh(r t)/r``,
    ``r = sqrt(alpha^2 - w0^2)`` give the overdamped case, and ``cos -> 1``,
    ``sin(wd t)/wd -> t`` the critically damped one; all three are returned, accurately
    (no cancellation near critical damping).

    ``t`` [s], ``R`` [ohm], ``L`` [H], ``C`` [F]. Returns ``(v_C, i)``.
    """
    t = np.asarray(t, dtype=float)
    alpha = R / (2.0 * L)
    w0 = 1.0 / math.sqrt(L * C)
    c, s = _exp_cos_sin(-alpha, (alpha - w0) * (alpha + w0), t)
    return V * (1.0 - (c + alpha * s)), V / L * s


def dc_motor_sine(t: ArrayLike, R: float = 1.0, L: float = 1e-3, k: float = 0.05,
                  J: float = 1e-5, b: float = 1e-5, V0: float = 6.0, Va: float = 6.0,
                  f: float = 5.0) -> FloatArray:
    """Current [A] and speed [rad/s] (rows of a (2, n) array) of a DC motor (``k_e = k_t =
    k``) from rest under ``V0 + Va sin(2 pi f t)`` [V, Hz]: x' = A x + B V with x = (i, w)
    is linear, so the response is a constant, a sinusoid and the matrix exponential that
    starts it from rest. ``R`` [ohm], ``L`` [H], ``J`` [kg*m^2], ``b`` [N*m*s/rad]."""
    t = np.asarray(t, dtype=float)
    A = np.array([[-R / L, -k / L], [k / J, -b / J]])
    B = np.array([1 / L, 0.0])
    omega = 2 * np.pi * f
    steady = -np.linalg.solve(A, B) * V0
    g = np.linalg.solve(1j * omega * np.eye(2) - A, B) * Va  # response to Va e^{j omega t}
    lam, vec = np.linalg.eig(A)
    c = np.linalg.solve(vec, -(steady + g.imag))  # the transient that starts it from rest
    out = steady[:, None] + (g[:, None] * np.exp(1j * omega * t)[None]).imag
    for m in range(2):
        out += (vec[:, m:m + 1] * (c[m] * np.exp(lam[m] * t))[None]).real
    return out


def dc_motor_steady_speed(V: float, R: float, k: float, b: float) -> float:
    """Steady speed [rad/s] of a DC motor with ``k_e = k_t = k`` [V*s/rad = N*m/A]:
    ``w = k*V/(k^2 + b*R)``; ``V`` [V], ``R`` [ohm], ``b`` [N*m*s/rad]. The steady current is
    ``b*w/k`` [A].
    """
    return k * V / (k * k + b * R)


def dc_motor_step(
    t: ArrayLike, V: float, R: float, L: float, k: float, J: float, b: float
) -> tuple[FloatArray, FloatArray]:
    """Speed [rad/s] and current [A] of a DC motor from rest after a voltage step ``V`` [V].

    Model (``k_e = k_t = k`` [V*s/rad]; ``R`` [ohm], ``L`` [H], ``J`` [kg*m^2],
    ``b`` [N*m*s/rad])::

        L*i' = V - R*i - k*w,   J*w' = k*i - b*w,   i(0) = w(0) = 0

    i.e. ``x' = A x + u`` with ``x = (i, w)``, ``A = [[-R/L, -k/L], [k/J, -b/J]]``. Then
    ``x(t) = x_ss - exp(A t) x_ss`` with ``x_ss = (b, k)*V/(k^2 + b*R)``. The eigenvalues are
    ``sigma +- sqrt(disc)``, ``sigma = tr/2 = -(R/L + b/J)/2``,
    ``disc = sigma^2 - det``, ``det = (R*b + k^2)/(L*J)``, and by Cayley-Hamilton::

        exp(A t) = e^(sigma t)*(c(t)*I + s(t)*(A - sigma*I))

    complex roots (``disc < 0``, ``nu = sqrt(-disc)``): ``c = cos(nu t)``, ``s = sin(nu t)/nu``;
    real distinct (``r = sqrt(disc)``): ``c = cosh(r t)``, ``s = sinh(r t)/r`` (equivalent to
    ``(e^(l1 t)(A - l2 I) - e^(l2 t)(A - l1 I))/(l1 - l2)``); repeated: ``c = 1``, ``s = t``.

    Returns ``(omega, i)``.
    """
    t = np.asarray(t, dtype=float)
    den = k * k + b * R
    i_ss, w_ss = b * V / den, k * V / den
    sig = -0.5 * (R / L + b / J)
    # disc = sigma^2 - det, written without cancellation: ((R/L - b/J)/2)^2 - k^2/(L*J)
    disc = 0.25 * (R / L - b / J) ** 2 - k * k / (L * J)
    c, s = _exp_cos_sin(sig, disc, t)
    # (A - sigma I) x_ss
    m_i = (-R / L - sig) * i_ss - k / L * w_ss
    m_w = k / J * i_ss + (-b / J - sig) * w_ss
    return w_ss - (c * w_ss + s * m_w), i_ss - (c * i_ss + s * m_i)


# ---------------------------------------------------------------------------------------------
# Error measure
# ---------------------------------------------------------------------------------------------


def errnorm(a: ArrayLike, b: ArrayLike, rtol: float, atol: float) -> float:
    """Tolerance-normalised maximum error ``max |a - b| / (atol + rtol*|b|)``.

    ``b`` is the reference. A value <= 1 means ``a`` is within tolerance everywhere
    (the same weighting as ``numpy.isclose``). ``atol`` is in the units of ``a``; ``rtol``
    is dimensionless. Arrays are broadcast; NaN anywhere gives ``inf``.
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    if atol <= 0.0 and rtol <= 0.0:
        raise ValueError("need atol > 0 or rtol > 0")
    e = np.abs(a - b) / (atol + rtol * np.abs(b))
    if e.size == 0:
        return 0.0
    if np.isnan(e).any():
        return math.inf
    return float(np.max(e))
