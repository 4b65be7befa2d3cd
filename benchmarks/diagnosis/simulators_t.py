"""Motor T of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC motor driving a PERISTALTIC HOSE PUMP: a rigid 16:1 two-stage spur gearhead turns
the pump head's rotor, whose three rollers squeeze a reinforced hose against a curved track
and push a water-based liquid up a delivery line.

No circuitsim import: an independent simulator (the seventeenth of the benchmark), written
from the physics for netlists/motor_t_motor.yaml, motor_t.yaml and motor_t_slow.yaml. It is
evaluated at the record's own sample times (``t_eval``), never on a grid that is then
interpolated; a probe read through a transport delay is evaluated at the shifted times too
(at rest before the record starts).

The drive is rigid, so the state is small, z = [i, w, th]:

    i      armature current [A]
    w, th  rotor speed [rad/s] and angle [rad]; the pump rotor turns at wp = w / N and
           stands at thp = th / N (N = 16)

Equations (J = Jm + Jp / N^2, the rotor and the pump head seen by the rotor; a torque Tp on
the pump shaft is Tp / N on the rotor, the gear being lossless):

    L di/dt = v(t) - R i - k w - (loop extras)
    J dw/dt = k i - bm w + X_rotor + Tp / N
    Tp      = -Bp wp - Tocc tanh(wp / 0.01) - Th + T3 sin(3 thp + ph3) + X_pump

Bp wp is the delivery line's laminar loss (``damper``), Tocc tanh(wp / 0.01) the hose's
rolling (hysteresis) loss under the rollers (``friction``, w_brk 0.1), Th the static
delivery pressure on the pump's displacement (``btorque``, -Th: pumping is wp > 0) and
T3 sin(3 thp + ph3) the three rollers' occlusion ripple (``cogging``, order 3 on the pump:
a declared term).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th)),
              voltage only
    cog       {shaft: [(order, a, b), ...]}: the shaft (rotor, pump) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {shaft: c}: c tanh(speed / 0.01) against the shaft's motion [N m]
    visc      {shaft: b}: an extra viscous friction [N m s/rad]
    offset    {shaft: T}: a constant torque [N m] the shaft receives
    stribeck  {shaft: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads
              g y(t - tau) + o, a pure transport delay (y at rest before the record)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    lrip      (eps [1], order, phase [rad]): the armature's inductance is modulated by the
              rotor's slots, L0 (1 + eps cos(order th + phase)): the loop takes
              d(L(th) i)/dt, the rotor the reluctance torque i^2 / 2 dL/dth
    busread   Vbus [V]: the current is read on the bridge's DC-link shunt, averaged over the
              PWM period: the reading is the bus current i u / Vbus (a lossless bridge)
    seized    (Ts [N m], centre [rad], half [rad], width [1]): one roller's bearing has
              seized; while that roller presses the hose (its window of the pump's angle,
              0.5 (1 + tanh((cos(thp - centre) - cos(half)) / width))) it drags the pump
              with Ts tanh(wp / 0.01) more
    duty_q    q [V]: the bridge's duty register is coarse: the armature gets the command
              rounded to the nearest multiple of q (a staircase), the log keeps the command
    vessel    (D [m^3/rad], p0 [Pa], V0 [m^3]): the receiving bottle's vent is blocked:
              its headspace V0 of air at p0 is compressed isothermally by the pumped volume
              D thp, and the pump takes D p0 D thp / (V0 - D thp) more
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_t_profile.csv"

#: declared values of motor T [SI] (motor_t_motor.yaml)
MOTOR_T: dict[str, float] = {
    "R": 0.9, "L": 1.1e-3, "k": 0.055, "Jm": 4.5e-5, "bm": 6e-6, "N": 16.0,
    "Jp": 2.2e-3, "Bp": 0.012, "Tocc": 1.1, "Th": 0.55, "T3": 0.3, "ph3": 0.6,
}
#: [rad/s] the friction's and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_t.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.005, 0.0), (0.065, 24.0), (0.17, 24.0), (0.171, 12.0),
               (0.26, 12.0), (0.28, 0.0), (0.31, 0.0), (0.34, -16.0), (0.44, -16.0),
               (0.441, 0.0), (0.5, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (40e3, 0.5), "slow": (250.0, 10.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
SHAFTS = ("rotor", "pump")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime (the command's corners are restarts)
H_MAX = {"fast": 2e-5, "slow": 5e-4}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    if regime == "fast":
        return np.asarray(FAST_POINTS, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def pieces(bp: np.ndarray, q: float | None, stop: float) -> list[tuple[float, float, float]]:
    """The armature's drive as pieces (start [s], value at start [V], slope [V/s]) up to
    ``stop`` [s]: the command's linear segments, or, with a duty step ``q`` [V], the
    staircase q round(u / q), a new constant piece wherever u crosses (m + 1/2) q."""
    corners = [0.0, *sorted(float(c) for c in set(bp[:, 0]) if 0.0 < c < stop), stop]
    out: list[tuple[float, float, float]] = []
    for a, b in itertools.pairwise(corners):
        ua, ub = (float(v) for v in np.interp([a, b], bp[:, 0], bp[:, 1]))
        slope = (ub - ua) / (b - a)
        if q is None:
            out.append((a, ua, slope))
            continue
        cuts = [a]
        if slope != 0.0:
            lo, hi = sorted((ua, ub))
            m = np.arange(math.ceil(lo / q - 0.5), math.floor(hi / q - 0.5) + 1)
            cross = sorted(a + ((k + 0.5) * q - ua) / slope for k in m)
            cuts += [c for c in cross if a < c < b]
        for j, c in enumerate(cuts):
            end = cuts[j + 1] if j + 1 < len(cuts) else b
            mid = ua + slope * (0.5 * (c + end) - a)
            out.append((c, q * math.floor(mid / q + 0.5), 0.0))
    return out


def drive_at(t: np.ndarray, segs: list[tuple[float, float, float]]) -> np.ndarray:
    """The armature's drive [V] at the times ``t`` [s] from its ``pieces``."""
    starts = np.array([s[0] for s in segs])
    k = np.clip(np.searchsorted(starts, t, side="right") - 1, 0, len(segs) - 1)
    base = np.array([s[1] for s in segs])[k]
    slope = np.array([s[2] for s in segs])[k]
    return base + slope * (t - starts[k])


# ---------------------------------------------------------------------- the model

class HosePump:
    """Right-hand side of motor T with one set of effects ``fx`` [SI]."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.n = p["N"]
        self.j = p["Jm"] + p["Jp"] / p["N"] ** 2
        self.seg = (0.0, 0.0, 0.0)
        self.terms = {s: self._shaft_terms(s) for s in SHAFTS}

    def _shaft_terms(self, s: str) -> tuple | None:
        """(viscous, Coulomb, offset, harmonics, Stribeck) the effects put on shaft ``s``,
        or None when they put nothing there."""
        fx = self.fx
        terms = (fx.get("visc", {}).get(s, 0.0), fx.get("coul", {}).get(s, 0.0),
                 fx.get("offset", {}).get(s, 0.0), tuple(fx.get("cog", {}).get(s, ())),
                 fx.get("stribeck", {}).get(s))
        return terms if any(x for x in terms if x is not None) else None

    def extra_torque(self, s: str, w: float, ang: float) -> float:
        """The torque [N m] the catalog's effects put on shaft ``s`` turning at ``w``
        [rad/s], standing at ``ang`` [rad]."""
        terms = self.terms[s]
        if terms is None:
            return 0.0
        visc, coul, off, harm, strib = terms
        out = off - visc * w
        if coul or strib is not None:
            sg = math.tanh(w / W_SIGN)
            out -= coul * sg
            if strib is not None:
                out -= strib[0] * math.exp(-(w / strib[1]) ** 2) * sg
        for order, a, b in harm:
            out += a * math.sin(order * ang) + b * math.cos(order * ang)
        return out

    def resistance(self, t: float) -> float:
        """The loop's resistance [ohm]: the armature's (drifting) and the extras'."""
        p, fx = self.p, self.fx
        r = p["R"]
        if "alpha" in fx:
            r *= 1.0 + fx["alpha"] * t
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        return r + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)

    def inductance(self, i: float, th: float) -> tuple[float, float]:
        """The differential inductance [H] at the current ``i`` [A] and the rotor angle
        ``th`` [rad], and its slope with the angle dL/dth [H/rad]."""
        ell, fx = self.p["L"], self.fx
        if "lsat" in fx:
            ipar, ratio = fx["lsat"]
            ell = ell * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))
        if "lrip" not in fx:
            return ell, 0.0
        eps, order, ph = fx["lrip"]
        l0 = self.p["L"]
        return (ell + eps * l0 * math.cos(order * th + ph),
                -eps * l0 * order * math.sin(order * th + ph))

    def loop_voltage(self, t: float, i: float, w: float, th: float, dldth: float) -> float:
        """The voltage [V] left for the inductance: the drive less the loop's drops, the EMF
        and the slot-modulated flux's motional term i w dL/dth."""
        t0, u0, slope = self.seg
        fx = self.fx
        v = u0 + slope * (t - t0) - self.resistance(t) * i - self.p["k"] * w
        if "Vb" in fx:
            v -= fx["Vb"] * math.tanh(i / I_SIGN)
        for order, a, b in fx.get("emf", ()):
            v -= w * (a * math.sin(order * th) + b * math.cos(order * th))
        return v - i * w * dldth

    def pump_torque(self, wp: float, thp: float) -> float:
        """The torque [N m] the pump shaft receives at ``wp`` [rad/s] and ``thp`` [rad]: the
        declared hose and delivery line, and the effects on the pump."""
        p, fx = self.p, self.fx
        sg = math.tanh(wp / W_SIGN)
        out = (-p["Bp"] * wp - p["Tocc"] * sg - p["Th"]
               + p["T3"] * math.sin(3.0 * thp + p["ph3"]) + self.extra_torque("pump", wp, thp))
        if "seized" in fx:
            ts, centre, half, width = fx["seized"]
            win = 0.5 * (1.0 + math.tanh((math.cos(thp - centre) - math.cos(half)) / width))
            out -= ts * win * sg
        if "vessel" in fx:
            disp, p0, v0 = fx["vessel"]
            out -= disp * p0 * disp * thp / (v0 - disp * thp)
        return out

    def __call__(self, t: float, z: np.ndarray) -> list[float]:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p = self.p
        i, w, th = float(z[0]), float(z[1]), float(z[2])
        ell, dldth = self.inductance(i, th)
        di = self.loop_voltage(t, i, w, th, dldth) / ell
        torque = (p["k"] * i + 0.5 * i * i * dldth - p["bm"] * w
                  + self.extra_torque("rotor", w, th)
                  + self.pump_torque(w / self.n, th / self.n) / self.n)
        return [di, torque / self.j, w]


# ---------------------------------------------------------------------- integration

def _solve(model: HosePump, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
           h_max: float) -> np.ndarray:
    """solve_ivp from ``a`` to ``b`` [s] at the times ``t_out`` [s]: LSODA, then Radau if
    it fails."""
    msg = ""
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), z0, method=method, t_eval=t_out, rtol=RTOL,
                        atol=ATOL, max_step=h_max)
        if sol.success and np.isfinite(sol.y).all() and sol.y.shape[1] == t_out.size:
            return sol.y
        msg = sol.message
    raise RuntimeError(f"motor T, {a:g}-{b:g} s: {msg}")


def integrate(model: HosePump, t: np.ndarray, segs: list[tuple[float, float, float]],
              h_max: float) -> np.ndarray:
    """The states at the increasing times ``t`` [s], from rest at 0, restarted at every
    piece of the drive ``segs`` (``pieces``). Returns (3, t.size)."""
    cuts = [s[0] for s in segs] + [float(t[-1])]
    z0 = np.zeros(3)
    y = np.empty((3, t.size))
    for j, seg in enumerate(segs):
        a, b = cuts[j], cuts[j + 1]
        if b <= a:
            continue
        model.seg = seg
        last = j == len(segs) - 1
        sel = (t >= a) & (t <= b) if last else (t >= a) & (t < b)
        t_out = t[sel] if last else np.append(t[sel], b)
        ys = _solve(model, a, b, z0, t_out, h_max)
        y[:, sel] = ys[:, :int(sel.sum())]
        z0 = ys[:, -1].copy()
    return y


def _delays(fx: Mapping[str, Any]) -> list[tuple[str, float]]:
    """(probe, delay [s]) of each probe read through a transport delay."""
    return [(pr, float(s["delay"])) for pr, s in fx.get("sensor", {}).items()
            if s.get("delay")]


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor T at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the pump head's tachometer), plus the logged command ``u`` [V].
    ``states``: add the rotor's angle [rad] and the armature's drive [V]."""
    fx = dict(fx or {})
    p = {**MOTOR_T, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    segs = pieces(bp, fx.get("duty_q"), float(t[-1]))
    delays = _delays(fx)
    # one pass at the record's times and every delayed reading's (rounded to 1 ps, so that
    # a shifted time that is a sample time is that very time)
    every = np.concatenate([t, *(np.round(t - d, 12) for _, d in delays)])
    union, inv = np.unique(every[every >= 0.0], return_inverse=True)
    y = integrate(HosePump(fx, p), union, segs, H_MAX[regime])
    pos = np.full(every.size, -1)
    pos[every >= 0.0] = inv
    pos = pos.reshape(-1, t.size)
    cur = y[0] * drive_at(union, segs) / fx["busread"] if "busread" in fx else y[0]
    full = {"current": cur, "speed": y[1], "load_speed": y[1] / p["N"]}
    out = {probe: full[probe][pos[0]].copy() for probe in PROBES[regime]}
    for k, (probe, _) in enumerate(delays, start=1):
        out[probe] = np.where(pos[k] >= 0, full[probe][pos[k]], 0.0)
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2][pos[0]], drive=drive_at(t, segs))
    return out


# ---------------------------------------------------------------------- noise

def markov(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float) -> np.ndarray:
    """A stationary Gauss-Markov (Ornstein-Uhlenbeck) process [probe unit] of standard
    deviation ``sigma`` and correlation time ``tau`` [s], sampled exactly at the times
    ``t`` [s], even or not."""
    rho = np.exp(-np.diff(t) / tau)
    kick = rng.standard_normal(t.size)
    kick[1:] *= sigma * np.sqrt(1.0 - rho * rho)
    kick[0] *= sigma
    x = np.empty(t.size)
    x[0] = kick[0]
    for n in range(1, t.size):
        x[n] = rho[n - 1] * x[n - 1] + kick[n]
    return x


def flicker(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma``: white noise on an even grid
    of half the mean interval, its spectrum shaped by 1/sqrt(f) (the mean left out), read
    at the times ``t`` [s] by linear interpolation, mean removed and scaled."""
    span = float(t[-1] - t[0])
    h = 0.5 * span / (t.size - 1)
    m = math.ceil(span / h) + 1
    spec = np.fft.rfft(rng.standard_normal(m))
    f = np.fft.rfftfreq(m, h)
    spec[0] = 0.0
    spec[1:] /= np.sqrt(f[1:])
    x = np.interp(t - t[0], np.arange(m) * h, np.fft.irfft(spec, m))
    x -= x.mean()
    return sigma * x / x.std()


def add_noise(rng: np.random.Generator, t: np.ndarray, y: np.ndarray,
              spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` at the times ``t`` [s] with ``white`` sigma, ``ar1`` [sigma, phi] (a
    Gauss-Markov process correlated by phi over the mean interval) and ``pink`` (1/f) sigma
    noise added [probe unit], then read by an ADC of step ``quant`` [probe unit]."""
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out += rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        sig, phi = spec["ar1"]
        out += markov(rng, t, sig, -float(np.mean(np.diff(t))) / math.log(phi))
    if spec.get("pink"):
        out += flicker(rng, t, spec["pink"])
    step = spec.get("quant")
    return np.round(out / step) * step if step else out
