"""Motor E of the diagnosis benchmark: a hand-written scipy model of a 12 V permanent-magnet
brushed DC motor with brush friction, driving a turntable through a toothed belt (a rigid
3:1 reduction), with switchable effects and noise generators.

No circuitsim import: this is an independent simulator of the benchmark (the netlists it
mirrors are netlists/motor_e_motor.yaml, motor_e.yaml and motor_e_slow.yaml).

The belt is rigid and lossless (declared): w_load = w / N. The mechanics are one body at the
rotor with the turntable's inertia and torques reflected:

    L di/dt             = u(t) - R i - k w                                     [V]
    (Jm + Jl/N^2) dw/dt = k i - bm w - Tc tanh(w/0.01) - (bl w/N + T_out)/N     [N*m]
    dtheta/dt           = w                                                    [rad/s]

Tc tanh(w / 0.01 rad/s) is the declared brush friction on the rotor. T_out [N*m] is the torque
the turntable's own additions take. The effects (``fx`` keys, SI, all off by default):

    Rser               [ohm]  a resistance in series with the loop (a connector)
    Rs                 [ohm]  an internal resistance of the supply
    Vb, Vb_eps         [V], [A]  brush drop Vb tanh(i/Vb_eps)
    lsat               (Ipar [A], ratio [1]): the armature inductance falls with current,
                       dpsi/di = L (ratio + (1 - ratio)/(1 + (i/Ipar)^2))
    alpha              [1/s]  Ra drifts straight: R (1 + alpha t)
    warmup             (rise [1], tau [s]): Ra warms up, R (1 + rise (1 - exp(-t/tau)))
    stribeck           (s [N*m], ws [rad/s]): a breakaway peak over the brush friction, the
                       rotor takes s exp(-(w/ws)^2) tanh(w/0.01) more
    Bx_load            [N*m*s/rad]  extra viscous friction on the turntable
    Fc_load            [N*m]  Coulomb friction on the turntable, Fc tanh(w_load/0.01)
    T_load             [N*m]  a constant load torque on the turntable against positive rotation
    sensor             {probe: {gain [1], offset [probe unit], delay [s]}}
    (the turntable's inertia off: pass ``p`` with another Jl)
    -- outside the catalog --
    magnet_heating     (delta [1], tau [s]): the magnets warm up and the motor constant falls,
                       k(t) = k (1 - delta (1 - exp(-t/tau))), in the EMF and the torque
    belt_eta           [1]  the belt's efficiency: the torque it passes loses a fraction
                       1 - eta (a friction proportional to the transmitted torque); while the
                       motor drives the turntable the motor supplies Q/(eta N), while the
                       turntable drives the motor (braking) it receives eta Q/N, Q the
                       turntable's demand Jl dw_load/dt + its torques
    inertia_step       (t1 [s], dJ [kg*m^2]): a part is set on the turntable at t1 (while it
                       stands still): its inertia grows by dJ from then on
    iron_loss          (c [N*m/(rad/s)^1.5]): eddy-current and hysteresis drag in the rotor
                       iron, c |w|^1.5 sign(w)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_e_profile.csv"

#: declared values of motor E [SI]: armature, coupling, rotor, brush friction, belt, turntable
MOTOR_E: dict[str, float] = {
    "R": 1.6, "L": 0.5e-3, "k": 0.028, "Jm": 2.2e-6, "bm": 3e-6, "Tc": 2e-3, "N": 3.0,
    "Jl": 1.8e-4, "bl": 4e-5,
}
#: [rad/s] the speed over which the declared friction (and any Coulomb law) changes sign:
#: circuitsim's ``friction`` with w_brk 0.1 rad/s smooths its sign as tanh(w/0.01)
W_SIGN = 0.01
#: the fast regime's drive [s, V] (motor_e.yaml's pwl)
PWL_FAST: tuple[tuple[float, float], ...] = (
    (0.0, 0.0), (0.002, 0.0), (0.003, 12.0), (0.15, 12.0), (0.151, 5.0), (0.23, 5.0),
    (0.27, -9.0), (0.4, -9.0))
#: regime -> (sample rate [Hz], duration [s])
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.4), "slow": (1e3, 6.0)}
#: regime -> probes (current [A], speed [rad/s] of the rotor, load_speed [rad/s] of the
#: turntable)
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
RTOL, ATOL = 1e-10, 1e-12


def drive_points(regime: str) -> np.ndarray:
    """The drive's breakpoints, an (n, 2) array of [time [s], voltage [V]], linear between
    them and held at the ends (pwl and table alike)."""
    if regime == "fast":
        return np.array(PWL_FAST, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    """The record's sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(dur * fs) + 1) / fs


def _k_of(t: float, p: Mapping[str, float], fx: Mapping[str, Any]) -> float:
    """The motor constant at time ``t`` [s] [N*m/A = V*s/rad]."""
    if "magnet_heating" in fx:
        delta, tau = fx["magnet_heating"]
        return p["k"] * (1.0 - delta * (1.0 - math.exp(-t / tau)))
    return p["k"]


def _inductance(i: float, p: Mapping[str, float], fx: Mapping[str, Any]) -> float:
    """The armature's differential inductance dpsi/di at current ``i`` [A] [H]."""
    if "lsat" in fx:
        ipar, ratio = fx["lsat"]
        return p["L"] * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))
    return p["L"]


def _rotor_torque(w: float, p: Mapping[str, float], fx: Mapping[str, Any]) -> float:
    """Torque the rotor's own losses take [N*m] at speed ``w`` [rad/s]: declared viscous
    and brush friction, a breakaway peak, iron loss."""
    sgn = math.tanh(w / W_SIGN)
    tq = p["bm"] * w + p["Tc"] * sgn
    if "stribeck" in fx:
        s, ws = fx["stribeck"]
        tq += s * math.exp(-((w / ws) ** 2)) * sgn
    if fx.get("iron_loss"):
        tq += fx["iron_loss"] * abs(w) ** 1.5 * math.copysign(1.0, w)
    return tq


def _load_torque(wl: float, p: Mapping[str, float], fx: Mapping[str, Any]) -> float:
    """Torque the turntable's bearing and additions take [N*m] at its speed ``wl`` [rad/s]
    (declared viscous bl included)."""
    tq = (p["bl"] + fx.get("Bx_load", 0.0)) * wl + fx.get("T_load", 0.0)
    if fx.get("Fc_load"):
        tq += fx["Fc_load"] * math.tanh(wl / W_SIGN)
    return tq


def _load_inertia(t: float, p: Mapping[str, float], fx: Mapping[str, Any]) -> float:
    """The turntable's inertia at time ``t`` [s] [kg*m^2]."""
    if "inertia_step" in fx and t >= fx["inertia_step"][0]:
        return p["Jl"] + fx["inertia_step"][1]
    return p["Jl"]


def make_rhs(pts: np.ndarray, fx: Mapping[str, Any],
             p: Mapping[str, float] = MOTOR_E) -> Callable[[float, np.ndarray], list[float]]:
    """The ODE's right-hand side for the drive ``pts`` [s, V]; state [i [A], w [rad/s],
    theta [rad]]."""
    n, jm = p["N"], p["Jm"]
    vb, vb_eps = fx.get("Vb", 0.0), fx.get("Vb_eps", 1e-3)
    r_ext = fx.get("Rser", 0.0) + fx.get("Rs", 0.0)
    alpha = fx.get("alpha", 0.0)
    rise, tau_w = fx.get("warmup", (0.0, 1.0))
    eta = fx.get("belt_eta", 1.0)
    tp, vp = pts[:, 0], pts[:, 1]

    def rhs(t: float, y: np.ndarray) -> list[float]:
        """d/dt of [i [A], w [rad/s], theta [rad]] at time t [s]."""
        i, w, _ = y
        k = _k_of(t, p, fx)
        u = float(np.interp(t, tp, vp))
        r = p["R"] * (1.0 + alpha * t + rise * (1.0 - math.exp(-t / tau_w))) + r_ext
        v = u - r * i - vb * math.tanh(i / vb_eps) - k * w
        f_m = k * i - _rotor_torque(w, p, fx)  # what the rotor has left for the belt
        jl = _load_inertia(t, p, fx)
        t_ld = _load_torque(w / n, p, fx)
        # the belt passes the turntable's demand Q = jl dw_l/dt + t_ld: the motor supplies
        # c Q / N with c = 1/eta while it drives the turntable, eta while it is driven; the
        # sign of Q w (the power's direction) is that of (jl f_m / N + jm t_ld) w, whichever c
        c = 1.0
        if eta != 1.0:
            c = 1.0 / eta if (jl * f_m / n + jm * t_ld) * w >= 0.0 else eta
        dw = (f_m - c * t_ld / n) / (jm + c * jl / n**2)
        return [v / _inductance(i, p, fx), dw, w]
    return rhs


def _edges(regime: str, fx: Mapping[str, Any], t_end: float) -> list[float]:
    """Where the integration is split [s]: the drive's breakpoints, an inertia step."""
    pts = drive_points(regime)
    cuts = {0.0, t_end, *(float(x) for x in pts[:, 0] if 0.0 < x < t_end)}
    if "inertia_step" in fx and 0.0 < fx["inertia_step"][0] < t_end:
        cuts.add(float(fx["inertia_step"][0]))
    return sorted(cuts)


class Solution:
    """The state on [0, t_end] as pieces of dense output; before t = 0 the motor is at rest
    (the state at 0)."""

    def __init__(self, pieces: list[tuple[float, float, Any]], y0: np.ndarray) -> None:
        self.pieces, self.y0 = pieces, y0

    def __call__(self, t: np.ndarray) -> np.ndarray:
        """State at times ``t`` [s]: an array (3, len(t))."""
        t = np.asarray(t, dtype=float)
        out = np.repeat(self.y0[:, None], t.size, axis=1)
        for j, (a, b, sol) in enumerate(self.pieces):
            last = j == len(self.pieces) - 1
            sel = (t >= a) & ((t <= b) if last else (t < b))
            if sel.any():
                out[:, sel] = sol(t[sel])
        return out


def integrate(regime: str, fx: Mapping[str, Any] | None = None,
              p: Mapping[str, float] = MOTOR_E, t_end: float | None = None) -> Solution:
    """Integrate from rest over the regime's duration (or ``t_end`` [s]), LSODA with
    rtol 1e-10, atol 1e-12 (Radau for a piece where LSODA fails), split at every breakpoint
    of the drive and at an inertia step; the largest step is 0.1 ms (fast) or 0.5 ms
    (slow)."""
    fx = dict(fx or {})
    t_end = REGIMES[regime][1] if t_end is None else t_end
    rhs = make_rhs(drive_points(regime), fx, p)
    max_step = 1e-4 if regime == "fast" else 5e-4
    y = np.zeros(3)
    pieces = []
    for a, b in itertools.pairwise(_edges(regime, fx, t_end)):
        sol = solve_ivp(rhs, (a, b), y, method="LSODA", rtol=RTOL, atol=ATOL,
                        dense_output=True, max_step=max_step)
        if not (sol.success and np.all(np.isfinite(sol.y))):
            # LSODA breaks down (NaN) on a state decaying into denormals (the rotor braked
            # to rest by the friction's steep sign): Radau takes such a piece
            sol = solve_ivp(rhs, (a, b), y, method="Radau", rtol=RTOL, atol=ATOL,
                            dense_output=True, max_step=max_step)
        if not sol.success:
            raise RuntimeError(f"motor E {regime}: {sol.message} at t = {sol.t[-1]:.6g} s")
        pieces.append((a, b, sol.sol))
        y = sol.y[:, -1].copy()
    return Solution(pieces, np.zeros(3))


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] = MOTOR_E) -> dict[str, np.ndarray]:
    """Noise-free probes at times ``t`` [s] (default: the record's grid): current [A],
    speed [rad/s], and for the slow regime load_speed [rad/s] and the command ``u`` [V].
    Sensor effects (gain, offset, delay) are applied to the probes they name."""
    fx = dict(fx or {})
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    sol = integrate(regime, fx, p, float(t[-1]))
    sensors = fx.get("sensor", {})
    out: dict[str, np.ndarray] = {}
    for probe in PROBES[regime]:
        spec = sensors.get(probe, {})
        y = sol(t - spec.get("delay", 0.0))
        val = {"current": y[0], "speed": y[1], "load_speed": y[1] / p["N"]}[probe]
        out[probe] = spec.get("gain", 1.0) * val + spec.get("offset", 0.0)
    if regime == "slow":
        pts = drive_points(regime)
        out["u"] = np.interp(t, pts[:, 0], pts[:, 1])
    return out


# ---------------------------------------------------------------------- noise

def ar1(rng: np.random.Generator, n: int, sigma: float, phi: float) -> np.ndarray:
    """AR(1) noise of marginal standard deviation ``sigma`` [probe unit] and coefficient
    ``phi`` [1], started in its stationary distribution."""
    e = rng.normal(0.0, sigma * math.sqrt(1.0 - phi * phi), n)
    out = np.empty(n)
    out[0] = rng.normal(0.0, sigma)
    for j in range(1, n):
        out[j] = phi * out[j - 1] + e[j]
    return out


def pink(rng: np.random.Generator, n: int, sigma: float) -> np.ndarray:
    """1/f noise: white noise shaped by 1/sqrt(f) in the frequency domain (no DC), scaled to
    standard deviation ``sigma`` [probe unit]."""
    spec = np.fft.rfft(rng.normal(size=n))
    f = np.fft.rfftfreq(n)
    spec[0] = 0.0
    spec[1:] /= np.sqrt(f[1:])
    x = np.fft.irfft(spec, n)
    return sigma * x / np.std(x)


def add_noise(rng: np.random.Generator, y: np.ndarray, spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` plus noise: ``white`` sigma, ``ar1`` [sigma, phi], ``pink`` sigma (1/f), in that
    order, then ``quant``: rounding to an ADC step (all in the probe's unit)."""
    n = y.size
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out += rng.normal(0.0, spec["white"], n)
    if spec.get("ar1"):
        out += ar1(rng, n, *spec["ar1"])
    if spec.get("pink"):
        out += pink(rng, n, spec["pink"])
    if spec.get("quant"):
        out = np.round(out / spec["quant"]) * spec["quant"]
    return out
