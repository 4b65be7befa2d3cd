"""Motor U of the diagnosis benchmark: a hand-written scipy model of a 36 V permanent-magnet
brushed DC motor driving the DISC BRUSH of a walk-behind FLOOR SCRUBBER: a rigid 20:1
two-stage spur gearbox turns a hub whose rubber-bonded drive plate (a compliant coupling)
carries a 430 mm scrubbing brush pressed onto a wet floor.

No circuitsim import: an independent simulator (the eighteenth of the benchmark), written
from the physics for netlists/motor_u_motor.yaml, motor_u.yaml and motor_u_slow.yaml. It is
evaluated at the record's own sample times (``t_eval``), never on a grid that is then
interpolated; a probe read through a transport delay is evaluated at the shifted times too
(at rest before the record starts).

State z = [i, w, th, x, wb, thb] (+ the bristles' presliding torque F, for ``dahl``):

    i        armature current [A]
    w, th    rotor speed [rad/s] and angle [rad]; the hub turns at w / N (N = 20)
    x        the drive plate's twist, the hub's angle less the brush's, th / N - thb [rad]
    wb, thb  the brush's speed [rad/s] and angle [rad]

Equations (J1 = Jm + Jg / N^2, the rotor with the gearbox's output and the hub seen by the
rotor; a torque T on the hub is T / N on the rotor, the gear being rigid and lossless):

    L di/dt   = v(t) - R i - k w - (loop extras)
    J1 dw/dt  = k i - bm w + T6 sin(6 th + ph6) + X_rotor + (X_hub - Tk) / N
    Jb dwb/dt = Tk - Bb wb - Tf tanh(wb / 0.01) + X_brush
    Tk        = c x + d (w / N - wb)                       (the drive plate ``K``)

T6 sin(6 th + ph6) is the motor's cogging (6 slots under 2 magnets; ``cogging``, declared),
Bb wb the detergent film's and the bristles' viscous drag (``damper``), Tf tanh(wb / 0.01)
the floor's friction under the brush's pressure (``friction``, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {shaft: [(order, a, b), ...]}: the shaft (rotor, hub, brush) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {shaft: c}: c tanh(speed / 0.01) against the shaft's motion [N m]
    visc      {shaft: b}: an extra viscous friction [N m s/rad]
    offset    {shaft: T}: a constant torque [N m] the shaft receives
    stribeck  {shaft: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play in the drive plate (Modelica's ElastoBacklash): no torque while
              |x| < gap / 2, else c (x -+ gap / 2) + d x', never pulling the sides together
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads
              g y(t - tau) + o, a pure transport delay (y at rest before the record)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    leak      Rp [ohm]: a conducting path (detergent water and brush dust) across the motor's
              terminals; the drive's current shunt sits in the supply lead, so the current
              reads i + v / Rp, v the bridge's output (the armature's own current unchanged)
    clock     eps [1]: the logger's clock runs fast by eps: a sample stamped t was taken at
              the true time t / (1 + eps)
    absread   probe: the probe is a single-channel pickup (no direction): it reads |y|
    dahl      (sigma [N m/rad], eps [rad/s]): the floor's friction on the brush is the
              bristles' presliding (Dahl) friction instead of Tf tanh(wb / 0.01): the brush
              takes -F, dF/dt = sigma (wb - sqrt(wb^2 + eps^2) F / Tf)
    vac       (t0 [s], dV [V], dVin [V], tau_in [s], Vbus [V]): the squeegee's vacuum motor
              starts at t0 on the same battery and pulls its bus down by
              dV + dVin exp(-(t - t0) / tau_in); the bridge's output is u (1 - drop / Vbus)
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_u_profile.csv"

#: declared values of motor U [SI] (motor_u_motor.yaml)
MOTOR_U: dict[str, float] = {
    "R": 0.45, "L": 7e-4, "k": 0.075, "Jm": 1.2e-4, "bm": 1.5e-5, "T6": 0.02, "ph6": 0.4,
    "N": 20.0, "Jg": 8e-4, "c": 400.0, "d": 0.8, "Jb": 0.05, "Bb": 0.08, "Tf": 6.0,
}
#: the declared cogging's order [1 / turn of the rotor]
COG_ORDER = 6
#: [rad/s] the friction's and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_u.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.16, 30.0), (0.3, 30.0), (0.301, 20.0),
               (0.4, 20.0), (0.401, 34.0), (0.48, 34.0), (0.52, 0.0), (0.56, 0.0),
               (0.62, -26.0), (0.72, -26.0), (0.721, 0.0), (0.8, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.8), "slow": (250.0, 12.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
SHAFTS = ("rotor", "hub", "brush")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the cogging's period at the rotor's top speed is 2.4 ms
#: fast (428 rad/s) and 2.8 ms slow (370 rad/s); the fast step is the sample interval (1/60
#: of it), the slow one 1/11 of it (a quarter of it moves the slow probes by < 3e-9 of their
#: range: the error control at rtol 1e-10 resolves the ripple)
H_MAX = {"fast": 4e-5, "slow": 2.5e-4}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    if regime == "fast":
        return np.asarray(FAST_POINTS, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def bus_drop(fx: Mapping[str, Any], t: float) -> float:
    """The battery bus's drop [V] at the time ``t`` [s] once the vacuum motor runs
    (``vac``), 0 before it or without it."""
    if "vac" not in fx:
        return 0.0
    t0, dv, dvin, tau, _ = fx["vac"]
    return dv + dvin * math.exp(-(t - t0) / tau) if t >= t0 else 0.0


# ---------------------------------------------------------------------- the model

class Scrubber:
    """Right-hand side of motor U with one set of effects ``fx`` [SI]."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.n_states = 7 if "dahl" in fx else 6
        self.j1 = p["Jm"] + p["Jg"] / p["N"] ** 2
        self.seg = (0.0, 0.0, 0.0)
        self.extra = {s: self._shaft_terms(s) for s in SHAFTS}

    def _shaft_terms(self, s: str) -> tuple | None:
        """(viscous, Coulomb, offset, harmonics, Stribeck) the effects put on shaft ``s``,
        or None when they put nothing there."""
        fx = self.fx
        terms = (fx.get("visc", {}).get(s, 0.0), fx.get("coul", {}).get(s, 0.0),
                 fx.get("offset", {}).get(s, 0.0), tuple(fx.get("cog", {}).get(s, ())),
                 fx.get("stribeck", {}).get(s))
        return terms if any(x for x in terms if x is not None) else None

    def shaft_torque(self, s: str, w: float, ang: float) -> float:
        """The torque [N m] the catalog's effects put on shaft ``s`` turning at ``w``
        [rad/s], standing at ``ang`` [rad]."""
        terms = self.extra[s]
        if terms is None:
            return 0.0
        visc, coul, off, harm, strib = terms
        out = off - visc * w
        if coul or strib is not None:
            sg = math.tanh(w / W_SIGN)
            out -= coul * sg
            if strib is not None:
                out -= strib[0] * math.exp(-((w / strib[1]) ** 2)) * sg
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

    def inductance(self, i: float) -> float:
        """The differential inductance [H] at the current ``i`` [A]."""
        ell = self.p["L"]
        if "lsat" not in self.fx:
            return ell
        ipar, ratio = self.fx["lsat"]
        return ell * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))

    def drive(self, t: float) -> float:
        """The bridge's output [V]: the command, less its share of the bus's drop."""
        t0, u0, slope = self.seg
        u = u0 + slope * (t - t0)
        if "vac" in self.fx:
            u *= 1.0 - bus_drop(self.fx, t) / self.fx["vac"][4]
        return u

    def loop_voltage(self, t: float, i: float, w: float, th: float) -> float:
        """The voltage [V] left for the inductance: the drive less the loop's drops and the
        EMF."""
        fx = self.fx
        v = self.drive(t) - self.resistance(t) * i - self.p["k"] * w
        if "Vb" in fx:
            v -= fx["Vb"] * math.tanh(i / I_SIGN)
        for order, a, b in fx.get("emf", ()):
            v -= w * (a * math.sin(order * th) + b * math.cos(order * th))
        return v

    def plate(self, x: float, xdot: float) -> float:
        """The drive plate's torque [N m] from the hub into the brush at the twist ``x``
        [rad] and its rate ``xdot`` [rad/s]: a spring-damper, or with a play ElastoBacklash's
        law."""
        p = self.p
        gap = self.fx.get("gap")
        if gap is None:
            return p["c"] * x + p["d"] * xdot
        h = 0.5 * gap
        if x > h:
            return max(p["c"] * (x - h) + p["d"] * xdot, 0.0)
        if x < -h:
            return min(p["c"] * (x + h) + p["d"] * xdot, 0.0)
        return 0.0

    def floor(self, wb: float, z: np.ndarray) -> float:
        """The floor's friction on the brush [N m] (against it): the declared one, or the
        bristles' presliding torque F (``dahl``)."""
        if "dahl" in self.fx:
            return float(z[6])
        return self.p["Tf"] * math.tanh(wb / W_SIGN)

    def __call__(self, t: float, z: np.ndarray) -> list[float]:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p = self.p
        i, w, th, x, wb, thb = (float(v) for v in z[:6])
        n = p["N"]
        di = self.loop_voltage(t, i, w, th) / self.inductance(i)
        tk = self.plate(x, w / n - wb)
        rotor = (p["k"] * i - p["bm"] * w + p["T6"] * math.sin(COG_ORDER * th + p["ph6"])
                 + self.shaft_torque("rotor", w, th)
                 + (self.shaft_torque("hub", w / n, th / n) - tk) / n)
        brush = (tk - p["Bb"] * wb - self.floor(wb, z)
                 + self.shaft_torque("brush", wb, thb))
        out = [di, rotor / self.j1, w, w / n - wb, brush / p["Jb"], wb]
        if "dahl" in self.fx:
            sigma, eps = self.fx["dahl"]
            out.append(sigma * (wb - math.sqrt(wb * wb + eps * eps) * float(z[6]) / p["Tf"]))
        return out


# ---------------------------------------------------------------------- integration

def _solve(model: Scrubber, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor U, {a:g}-{b:g} s: {msg}")


def cuts_of(bp: np.ndarray, fx: Mapping[str, Any], stop: float) -> list[float]:
    """The restarts [s]: 0, the command's corners, the vacuum motor's start, ``stop``."""
    inner = {float(c) for c in bp[:, 0] if 0.0 < c < stop}
    if "vac" in fx and 0.0 < fx["vac"][0] < stop:
        inner.add(float(fx["vac"][0]))
    return [0.0, *sorted(inner), stop]


def integrate(model: Scrubber, t: np.ndarray, bp: np.ndarray, h_max: float) -> np.ndarray:
    """The states at the increasing times ``t`` [s], from rest at 0, restarted at every
    corner of the command ``bp`` [s, V] (and the bus's step). Returns (n_states, t.size)."""
    cuts = cuts_of(bp, model.fx, float(t[-1]))
    z0 = np.zeros(model.n_states)
    y = np.empty((model.n_states, t.size))
    for j in range(len(cuts) - 1):
        a, b = cuts[j], cuts[j + 1]
        ua, ub = (float(v) for v in np.interp([a, b], bp[:, 0], bp[:, 1]))
        model.seg = (a, ua, (ub - ua) / (b - a))
        last = j == len(cuts) - 2
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


def applied(regime: str, t: np.ndarray, fx: Mapping[str, Any]) -> np.ndarray:
    """The bridge's output [V] at the true times ``t`` [s]: the command less its share of
    the bus's drop (``vac``)."""
    bp = breakpoints(regime)
    u = np.interp(t, bp[:, 0], bp[:, 1])
    if "vac" in fx:
        u = u * (1.0 - np.array([bus_drop(fx, float(x)) for x in t]) / fx["vac"][4])
    return u


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor U at the (stamped) times ``t`` [s] (default: the nominal
    grid), from rest: current [A], speed [rad/s] (the motor's encoder), and in the slow
    regime load_speed [rad/s] (the brush's tachometer, rad/s of the brush shaft), plus the
    logged command ``u`` [V]. ``states``: add the rotor's and the brush's angles [rad] and
    the drive plate's twist [rad]."""
    fx = dict(fx or {})
    p = {**MOTOR_U, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    true = t / (1.0 + fx["clock"]) if "clock" in fx else t
    bp = breakpoints(regime)
    delays = _delays(fx)
    # one pass at the record's times and every delayed reading's (rounded to 1 ps, so that
    # a shifted time that is a sample time is that very time)
    every = np.concatenate([true, *(np.round(true - d, 12) for _, d in delays)])
    union, inv = np.unique(every[every >= 0.0], return_inverse=True)
    model = Scrubber(fx, p)
    y = integrate(model, union, bp, H_MAX[regime])
    pos = np.full(every.size, -1)
    pos[every >= 0.0] = inv
    pos = pos.reshape(-1, t.size)
    cur = y[0] + applied(regime, union, fx) / fx["leak"] if "leak" in fx else y[0]
    full = {"current": cur, "speed": y[1], "load_speed": y[4]}
    out = {probe: full[probe][pos[0]].copy() for probe in PROBES[regime]}
    for k, (probe, _) in enumerate(delays, start=1):
        out[probe] = np.where(pos[k] >= 0, full[probe][pos[k]], 0.0)
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    if "absread" in fx:
        out[fx["absread"]] = np.abs(out[fx["absread"]])
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2][pos[0]], twist=y[3][pos[0]], brush_angle=y[5][pos[0]])
    return out


# ---------------------------------------------------------------------- noise

def gauss_markov(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float
                 ) -> np.ndarray:
    """A stationary Ornstein-Uhlenbeck process [probe unit] of standard deviation
    ``sigma`` and correlation time ``tau`` [s], exact at the times ``t`` [s], even or
    not."""
    a = np.exp(-np.diff(t) / tau)
    e = rng.standard_normal(t.size)
    x = np.empty(t.size)
    x[0] = sigma * e[0]
    scale = sigma * np.sqrt(1.0 - a * a)
    for n in range(1, t.size):
        x[n] = a[n - 1] * x[n - 1] + scale[n - 1] * e[n]
    return x


def one_over_f(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma`` at the times ``t`` [s]: a
    sum of equal-variance Ornstein-Uhlenbeck processes whose corner frequencies lie an
    octave apart, from the record's length down to twice the mean interval (a spectrum
    that falls as 1/f between them), mean removed and scaled."""
    span = float(t[-1] - t[0])
    dt = span / (t.size - 1)
    taus = []
    tau = span
    while tau > 2.0 * dt:
        taus.append(tau)
        tau *= 0.5
    x = sum(gauss_markov(rng, t, 1.0, tc) for tc in taus)
    x = x - x.mean()
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
        out += gauss_markov(rng, t, sig, -float(np.mean(np.diff(t))) / math.log(phi))
    if spec.get("pink"):
        out += one_over_f(rng, t, spec["pink"])
    step = spec.get("quant")
    return np.round(out / step) * step if step else out
