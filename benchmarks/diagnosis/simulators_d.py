"""Motor D of the diagnosis benchmark: a hand-written scipy model of a 24 V brushed DC
gearmotor with a current-sense shunt, with switchable effects and noise generators.

No circuitsim import: this is the second, independent simulator of the benchmark (the
netlists it mirrors are netlists/motor_d_motor.yaml, motor_d.yaml and motor_d_slow.yaml).

The ideal gear (ratio N, lossless, no play) ties the output to the rotor, w_load = w / N, so
the mechanics are one body at the rotor with the output's inertia and torques reflected:

    L di/dt          = u(t) - (Rsh + Ra) i - k w                    [V]
    (Jm + Jl/N^2) dw/dt = k i - bm w - (bl w/N + T_out) / N          [N*m]
    dtheta/dt        = w                                             [rad/s]

T_out [N*m] is the torque the output shaft's own additions take (friction, a load torque).
The effects (``fx`` keys, SI, all off by default):

    Rser               [ohm]  a resistance in series with the loop (a connector, a cable)
    Rs                 [ohm]  an internal resistance of the supply
    Ls                 [H]    an inductance between the supply and the drive (a cable's)
    Vb, Vb_eps         [V], [A]  brush drop Vb tanh(i/Vb_eps)
    Fc_load, wc_load   [N*m], [rad/s]  Coulomb friction on the output Fc tanh(w_load/wc)
    T_load             [N*m]  a constant load torque on the output, opposing positive rotation
    Bx_load            [N*m*s/rad]  extra viscous friction on the output
    warmup             (rise [1], tau [s]): Ra (1 + rise (1 - exp(-t/tau))), copper warming
    sensor             {probe: {gain [1], offset [probe unit], delay [s]}}
    -- outside the catalog --
    current_limit      (I_lim [A], G [V/A], width [A]): the supply's voltage folds back by
                       G times the excess of |i| over I_lim (a bipolar supply's current limit,
                       a regulator of finite gain), smoothed over ``width``
    dc_link            (E [V], R0 [ohm], R1 [ohm], C1 [F]): the bridge is fed by a battery
                       of EMF E with an internal resistance R0 and a polarisation branch
                       R1 || C1: duty d = u/E, the battery delivers d i, the armature sees
                       d (E - R0 d i - v1), C1 dv1/dt = d i - v1/R1 (a duty-dependent sag)
    windage            c_f [N*m*s^2/rad^2]: a cooling fan on the rotor, drag c_f w |w|
    armature_reaction  I_ar [A]: the field weakens with current, k(i) = k / (1 + (i/I_ar)^2),
                       in the EMF and the torque alike (energy-consistent)
    gear_runout        (order [1], T [N*m], phase [rad]): an eccentric intermediate gear: the
                       rotor receives T sin(order theta + phase), order non-integer
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
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_d_profile.csv"

#: declared values of motor D [SI]: shunt, armature, coupling, rotor, gear, output
MOTOR_D: dict[str, float] = {
    "Rsh": 0.02, "R": 1.1, "L": 0.9e-3, "k": 0.055, "Jm": 1.1e-5, "bm": 1e-5, "N": 15.0,
    "Jl": 0.012, "bl": 2e-3,
}
#: the fast regime's drive [s, V] (motor_d.yaml's pwl)
PWL_FAST: tuple[tuple[float, float], ...] = (
    (0.0, 0.0), (0.005, 0.0), (0.065, 24.0), (0.16, 24.0), (0.161, 12.0), (0.26, 12.0),
    (0.3, -12.0), (0.4, -12.0))
#: regime -> (sample rate [Hz], duration [s])
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.4), "slow": (1e3, 6.0)}
#: regime -> probes (current [A], speed [rad/s] at the rotor, load_speed [rad/s] at the output)
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


def _softplus(x: float, width: float) -> float:
    """width log(1 + exp(x/width)) [same unit as x]: a smooth max(0, x)."""
    z = x / width
    return width * (z + math.log1p(math.exp(-z))) if z > 0 else width * math.log1p(math.exp(z))


def _supply_drop(u: float, i: float, v1: float, fx: Mapping[str, Any]) -> float:
    """What the supply loses below its command ``u`` [V] at current ``i`` [A] [V]: internal
    resistance, a current limit's fold-back, a battery-fed bridge's sag (``v1`` [V], the
    polarisation branch's voltage)."""
    drop = fx.get("Rs", 0.0) * i
    if "dc_link" in fx:
        e, r0, _, _ = fx["dc_link"]
        d = u / e
        drop += d * (r0 * d * i + v1)
    if "current_limit" in fx:
        ilim, gain, width = fx["current_limit"]
        drop += gain * (_softplus(i - ilim, width) - _softplus(-i - ilim, width))
    return drop


def _k_of(i: float, p: Mapping[str, float], fx: Mapping[str, Any]) -> float:
    """The motor constant at current ``i`` [A] [N*m/A = V*s/rad]."""
    if "armature_reaction" in fx:
        return p["k"] / (1.0 + (i / fx["armature_reaction"]) ** 2)
    return p["k"]


def _r_loop(t: float, p: Mapping[str, float], fx: Mapping[str, Any]) -> float:
    """The loop's resistance without the supply's [ohm] at time ``t`` [s]: shunt,
    armature (warming up), a series resistance."""
    ra = p["R"]
    if "warmup" in fx:
        rise, tau = fx["warmup"]
        ra = ra * (1.0 + rise * (1.0 - math.exp(-t / tau)))
    return p["Rsh"] + ra + fx.get("Rser", 0.0)


def _output_torque(w: float, p: Mapping[str, float], fx: Mapping[str, Any]) -> float:
    """The torque the output shaft's load and friction take [N*m] at rotor speed ``w``
    [rad/s] (declared viscous bl included)."""
    wl = w / p["N"]
    tq = (p["bl"] + fx.get("Bx_load", 0.0)) * wl + fx.get("T_load", 0.0)
    if fx.get("Fc_load"):
        tq += fx["Fc_load"] * math.tanh(wl / fx.get("wc_load", 0.01))
    return tq


def _rotor_torque(w: float, theta: float, p: Mapping[str, float],
                  fx: Mapping[str, Any]) -> float:
    """Torque the rotor's own additions take [N*m] (declared viscous bm included)."""
    tq = p["bm"] * w
    if fx.get("windage"):
        tq += fx["windage"] * w * abs(w)
    if "gear_runout" in fx:
        order, amp, ph = fx["gear_runout"]
        tq -= amp * math.sin(order * theta + ph)
    return tq


def make_rhs(pts: np.ndarray, fx: Mapping[str, Any],
             p: Mapping[str, float] = MOTOR_D) -> Callable[[float, np.ndarray], list[float]]:
    """The ODE's right-hand side for the drive ``pts`` [s, V]; state [i [A], w [rad/s],
    theta [rad], v1 [V] (the battery's polarisation voltage, 0 without it)]."""
    j_tot = p["Jm"] + p["Jl"] / p["N"] ** 2
    l_tot = p["L"] + fx.get("Ls", 0.0)
    vb, vb_eps = fx.get("Vb", 0.0), fx.get("Vb_eps", 0.01)
    e_dc, _, r1, c1 = fx.get("dc_link", (1.0, 0.0, 1.0, 1.0))
    tp, vp = pts[:, 0], pts[:, 1]

    def rhs(t: float, y: np.ndarray) -> list[float]:
        """d/dt of [i [A], w [rad/s], theta [rad], v1 [V]] at time t [s]."""
        i, w, theta, v1 = y
        k = _k_of(i, p, fx)
        cmd = float(np.interp(t, tp, vp))
        u = cmd - _supply_drop(cmd, i, v1, fx)
        v = u - _r_loop(t, p, fx) * i - vb * math.tanh(i / vb_eps) - k * w
        tq = k * i - _rotor_torque(w, theta, p, fx) - _output_torque(w, p, fx) / p["N"]
        dv1 = (cmd / e_dc * i - v1 / r1) / c1 if "dc_link" in fx else 0.0
        return [v / l_tot, tq / j_tot, w, dv1]
    return rhs


def _max_step(fx: Mapping[str, Any], regime: str) -> float:
    """The integrator's largest step [s]: 1/40 of the fastest angle-locked excitation at
    500 rad/s, at most 0.2 ms (fast) or 1 ms (slow)."""
    step = 2e-4 if regime == "fast" else 1e-3
    if "gear_runout" in fx:
        order = fx["gear_runout"][0]
        step = min(step, 2 * math.pi / (order * 500.0) / 40)
    return step


class Solution:
    """The state on [0, t_end] as pieces of dense output, split at the drive's breakpoints;
    before t = 0 the motor is at rest (the state at 0)."""

    def __init__(self, pieces: list[tuple[float, float, Any]], y0: np.ndarray) -> None:
        self.pieces, self.y0 = pieces, y0

    def __call__(self, t: np.ndarray) -> np.ndarray:
        """State at times ``t`` [s]: an array (4, len(t))."""
        t = np.asarray(t, dtype=float)
        out = np.repeat(self.y0[:, None], t.size, axis=1)
        for j, (a, b, sol) in enumerate(self.pieces):
            last = j == len(self.pieces) - 1
            sel = (t >= a) & ((t <= b) if last else (t < b))
            if sel.any():
                out[:, sel] = sol(t[sel])
        return out


def integrate(regime: str, fx: Mapping[str, Any] | None = None,
              p: Mapping[str, float] = MOTOR_D, t_end: float | None = None) -> Solution:
    """Integrate from rest over the regime's duration (or ``t_end`` [s]), LSODA with
    rtol 1e-10, atol 1e-12, split at every breakpoint of the drive."""
    fx = dict(fx or {})
    pts = drive_points(regime)
    t_end = REGIMES[regime][1] if t_end is None else t_end
    edges = sorted({0.0, t_end, *(float(x) for x in pts[:, 0] if 0.0 < x < t_end)})
    rhs = make_rhs(pts, fx, p)
    y = np.zeros(4)
    pieces = []
    for a, b in itertools.pairwise(edges):
        sol = solve_ivp(rhs, (a, b), y, method="LSODA", rtol=RTOL, atol=ATOL,
                        dense_output=True, max_step=_max_step(fx, regime))
        if not sol.success:
            raise RuntimeError(f"motor D {regime}: {sol.message} at t = {sol.t[-1]:.6g} s")
        pieces.append((a, b, sol.sol))
        y = sol.y[:, -1].copy()
    return Solution(pieces, np.zeros(4))


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] = MOTOR_D) -> dict[str, np.ndarray]:
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
    """AR(1) noise of marginal standard deviation ``sigma`` and coefficient ``phi`` [1],
    started in its stationary distribution."""
    e = rng.normal(0.0, sigma * math.sqrt(1.0 - phi * phi), n)
    out = np.empty(n)
    out[0] = rng.normal(0.0, sigma)
    for j in range(1, n):
        out[j] = phi * out[j - 1] + e[j]
    return out


def pink(rng: np.random.Generator, n: int, sigma: float) -> np.ndarray:
    """1/f noise: white noise shaped by 1/sqrt(f) in the frequency domain (no DC), scaled to
    standard deviation ``sigma``."""
    spec = np.fft.rfft(rng.normal(size=n))
    f = np.fft.rfftfreq(n)
    spec[0] = 0.0
    spec[1:] /= np.sqrt(f[1:])
    x = np.fft.irfft(spec, n)
    return sigma * x / np.std(x)


def add_noise(rng: np.random.Generator, y: np.ndarray, spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` plus noise: ``white`` sigma, ``ar1`` [sigma, phi], ``pink`` sigma (1/f), in that
    order, then ``quant``: rounding to an ADC step (same unit as ``y``)."""
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
