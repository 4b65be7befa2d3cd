"""Motor AE of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC motor driving a car park's BARRIER GATE: the motor's worm and a spur stage (a
rigid, lossless 300:1 gearbox) turn the gearbox's output hub, which swings the boom's pivot
shaft through a short crank-and-rod drive held at 1:1; the drive's rubber-bushed rods and the
long aluminium boom's bending are one torsional compliance between the hub and the boom. The
boom (3.5 m, 3.2 kg, its centre of mass 1.75 m out) swings up from horizontal (0 rad) to
vertical (pi/2) against its weight, -Tg cos(angle), and is helped by a balance spring on its
pivot, Kb (th0 - angle); the two cancel exactly with the boom down, the spring leaving the
boom a little heavy through the stroke. The pivot's bearings and the spring's guide rod rub
(a dry friction on the boom), and the boom drags air (a viscous friction).

No circuitsim import: an independent simulator (the twenty-eighth of the benchmark), written
from the physics for netlists/motor_ae_fast.yaml and motor_ae_slow.yaml. It is evaluated at
the record's own sample times (``t_eval``), never on a grid that is then interpolated.
Everything rests at t = 0 (no current, no speed, the boom down and the drive untwisted: the
boom's weight and the spring cancel there, so nothing creeps).

The gearbox is rigid and lossless (``gear`` G, ratio N = 300): its output hub stands at
th / N and turns at w / N with the rotor; a torque T on the hub is T / N on the rotor. The
drive is a spring and damper on the twist th / N - thb between the hub and the boom
(``spring_damper`` K).

State z = [i, w, th, wb, thb] (+ one Pade stage per delayed probe, in this order):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wb, thb    the boom's speed and angle [rad/s, rad] (0: down, pi/2: up)

Equations (J1 = Jm + Jh / N^2: the rotor with the gearbox's output hub):

    L di/dt   = v(t) - R i - k w - (the loop's extras)
    J1 dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor + (X_hub - Tk) / N
    Jb dwb/dt = Tk + Kb (th0 - thb) - Tg cos(thb) - Bb wb - Tb tanh(wb / 0.01) + X_boom
    Tk        = Kc (th / N - thb) + Dc (w / N - wb)          (the drive)

Tm tanh(w / 0.01) is the worm's and the brushes' dry friction (``friction``, w_brk 0.1),
Kb (th0 - thb) the balance spring and -Tg cos(thb) the boom's weight (``btorque`` each),
Bb wb the boom's air drag (``damper``), Tb tanh(wb / 0.01) the pivot's and the spring
guide's dry friction (``friction``, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, boom) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in the drive K (Modelica's ElastoBacklash):
              no torque while |twist| < gap / 2, else Kc (twist -+ gap / 2) + Dc w_rel,
              the damping never pulling the sides together
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    wind      Tw [N m]: a steady wind along the road presses on the boom's face as it rises:
              the boom receives -Tw sin(thb) |sin(thb)| (the face's projection, squared)
    brake_r   (Rb [ohm], u0 [V]): the controller's braking relay: while the bridge's command
              is near 0 V it drops the motor onto a braking resistor instead of shorting it:
              the loop takes Rb exp(-(u / u0)^2) i more
    clip      ws [rad/s]: the boom's gyroscope left at its +-ws full scale: load_speed reads
              clip(wb, -ws, ws)
    crack     dk [1]: a fatigue crack at the boom's root opens under tension: the drive's
              stiffness is Kc (1 - dk) while the hub leads the boom (twist > 0), Kc else:
              Tk takes -dk Kc max(twist, 0) more
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AE [SI] (motor_ae_fast.yaml, motor_ae_slow.yaml)
MOTOR_AE: dict[str, float] = {
    "R": 0.8, "L": 1.6e-3, "k": 0.07, "Jm": 1e-4, "bm": 2e-5, "Tm": 0.03, "N": 300.0,
    "Jh": 0.05, "Kc": 3500.0, "Dc": 20.0, "Jb": 14.0, "Bb": 1.5, "Tb": 3.0,
    "Tg": 55.1, "Kb": 38.0, "th0": 1.45,
}
#: [rad/s] the frictions' and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_ae_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.09, 24.0), (0.24, 24.0), (0.25, 12.0),
               (0.31, 12.0), (0.315, 0.0), (0.37, 0.0), (0.39, -16.0), (0.45, -16.0),
               (0.455, 0.0), (0.5, 0.0))
#: the slow regime's logged command [s, V] (motor_ae_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.2, 0.0), (0.5, 24.0), (1.3, 24.0), (1.45, 8.0), (2.4, 8.0),
               (2.5, 0.0), (4.0, 0.0), (4.3, -20.0), (5.0, -20.0), (5.15, -7.0),
               (6.85, -7.0), (6.95, 0.0), (8.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.5), "slow": (200.0, 8.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "boom")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime (L/R is 2 ms),
#: a fifth of the mean interval in the slow one
H_MAX = {"fast": 4e-5, "slow": 1e-3}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.asarray(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class Barrier:
    """Right-hand side of motor AE with one set of effects ``fx`` [SI]."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.n = p["N"]
        self.j1 = p["Jm"] + p["Jh"] / self.n ** 2
        k = 5
        #: (probe, tau [s], index of its Pade state)
        self.pade: list[tuple[str, float, int]] = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.pade.append((probe, float(s["delay"]), k))
                k += 1
        self.n_states = k
        self.terms = {b: self._terms_of(b) for b in BODIES}
        self.seg = (0.0, 0.0, 0.0)

    def _terms_of(self, body: str) -> tuple | None:
        """The catalog's effects on ``body``: (viscous, Coulomb, offset, harmonics,
        Stribeck), or None when there are none."""
        fx = self.fx
        t = (fx.get("visc", {}).get(body, 0.0), fx.get("coul", {}).get(body, 0.0),
             fx.get("offset", {}).get(body, 0.0), tuple(fx.get("cog", {}).get(body, ())),
             fx.get("stribeck", {}).get(body))
        return t if any(t) else None

    def extra_torque(self, body: str, w: float, angle: float) -> float:
        """The torque [N m] the catalog's effects give ``body`` turning at ``w`` [rad/s],
        standing at ``angle`` [rad]."""
        t = self.terms[body]
        if t is None:
            return 0.0
        visc, coul, off, harm, strib = t
        sgn = math.tanh(w / W_SIGN)
        out = off - visc * w - coul * sgn
        if strib:
            s, ws = strib
            out -= s * math.exp(-(w / ws) ** 2) * sgn
        for order, a, b in harm:
            out += a * math.sin(order * angle) + b * math.cos(order * angle)
        return out

    def command(self, t: float) -> float:
        """The bridge's mean output [V], linear within the current segment."""
        t0, u0, slope = self.seg
        return u0 + slope * (t - t0)

    def loop_drop(self, t: float, i: float, w: float, th: float, u: float) -> float:
        """Every voltage [V] the loop takes but the inductance's and the declared EMF's, at
        the time ``t`` [s], the current ``i`` [A], the rotor's speed ``w`` [rad/s] and
        angle ``th`` [rad], the command ``u`` [V]."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t) + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        if "brake_r" in fx:
            rb, u0 = fx["brake_r"]
            r += rb * math.exp(-(u / u0) ** 2)
        v = r * i
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SIGN)
        for order, a, b in fx.get("emf", ()):
            v += w * (a * math.sin(order * th) + b * math.cos(order * th))
        return v

    def inductance(self, i: float) -> float:
        """The differential inductance [H] at the current ``i`` [A]."""
        ell = self.p["L"]
        if "lsat" in self.fx:
            ipar, ratio = self.fx["lsat"]
            ell *= ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2)
        return ell

    def drive_torque(self, twist: float, wrel: float) -> float:
        """The drive's torque [N m] on the boom at the ``twist`` [rad] and the relative
        speed ``wrel`` [rad/s] (the hub minus the boom), with a play if ``gap``, softer
        under tension if ``crack``."""
        p, fx = self.p, self.fx
        gap = fx.get("gap")
        if gap is None:
            out = p["Kc"] * twist + p["Dc"] * wrel
            if "crack" in fx:
                out -= fx["crack"] * p["Kc"] * max(twist, 0.0)
            return out
        h = 0.5 * gap
        if twist > h:
            return max(p["Kc"] * (twist - h) + p["Dc"] * wrel, 0.0)
        if twist < -h:
            return min(p["Kc"] * (twist + h) + p["Dc"] * wrel, 0.0)
        return 0.0

    def boom_load(self, wb: float, thb: float) -> float:
        """The balance spring's, the weight's, the air's and the pivot's torque [N m] on the
        boom turning at ``wb`` [rad/s], standing at ``thb`` [rad]."""
        p, fx = self.p, self.fx
        out = (p["Kb"] * (p["th0"] - thb) - p["Tg"] * math.cos(thb) - p["Bb"] * wb
               - p["Tb"] * math.tanh(wb / W_SIGN))
        if "wind" in fx:
            s = math.sin(thb)
            out -= fx["wind"] * s * abs(s)
        return out

    def __call__(self, t: float, z: np.ndarray) -> list[float]:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p, n = self.p, self.n
        i, w, th, wb, thb = (float(v) for v in z[:5])
        u = self.command(t)
        di = (u - self.loop_drop(t, i, w, th, u) - p["k"] * w) / self.inductance(i)
        tk = self.drive_torque(th / n - thb, w / n - wb)
        tau = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SIGN)
               + self.extra_torque("rotor", w, th)
               + (self.extra_torque("hub", w / n, th / n) - tk) / n)
        dwb = (tk + self.boom_load(wb, thb) + self.extra_torque("boom", wb, thb)) / p["Jb"]
        values = {"current": i, "speed": w, "load_speed": wb}
        pade = [2.0 * (values[probe] - float(z[k])) / tau_d for probe, tau_d, k in self.pade]
        return [di, tau / self.j1, w, dwb, wb, *pade]


# ---------------------------------------------------------------------- integration

def _solve(model: Barrier, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AE, {a:g}-{b:g} s: {msg}")


def integrate(model: Barrier, t: np.ndarray, bp: np.ndarray, h_max: float) -> np.ndarray:
    """The states at the increasing times ``t`` [s], from rest at 0, restarted at every
    corner of the command ``bp`` [s, V]. Returns (n_states, t.size)."""
    stop = float(t[-1])
    cuts = [0.0, *sorted({float(c) for c in bp[:, 0] if 0.0 < c < stop}), stop]
    z0 = np.zeros(model.n_states)
    y = np.empty((model.n_states, t.size))
    for j in range(len(cuts) - 1):
        a, b = cuts[j], cuts[j + 1]
        ua, ub = (float(x) for x in np.interp([a, b], bp[:, 0], bp[:, 1]))
        model.seg = (a, ua, (ub - ua) / (b - a))
        last = j == len(cuts) - 2
        sel = (t >= a) & (t <= b) if last else (t >= a) & (t < b)
        t_out = t[sel] if last else np.append(t[sel], b)
        ys = _solve(model, a, b, z0, t_out, h_max)
        y[:, sel] = ys[:, :int(sel.sum())]
        z0 = ys[:, -1].copy()
    return y


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor AE at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the boom, from a gyroscope on it), plus the command ``u`` [V].
    ``states``: add the angles [rad]."""
    fx = dict(fx or {})
    p = {**MOTOR_AE, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = Barrier(fx, p)
    y = integrate(model, t, bp, H_MAX[regime])
    full = {"current": y[0], "speed": y[1], "load_speed": y[3]}
    for probe, _, k in model.pade:
        full[probe] = 2.0 * y[k] - full[probe]
    if "clip" in fx:
        full["load_speed"] = np.clip(full["load_speed"], -fx["clip"], fx["clip"])
    out = {probe: full[probe].copy() for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2], boom_angle=y[4], boom_speed=y[3])
    return out


# ---------------------------------------------------------------------- noise

def gauss_markov(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float
                 ) -> np.ndarray:
    """A stationary Gauss-Markov process [probe unit] of standard deviation ``sigma`` and
    correlation time ``tau`` [s], sampled exactly at the (uneven) times ``t`` [s]."""
    rho = np.exp(-np.diff(t) / tau)
    shocks = sigma * np.sqrt(1.0 - rho ** 2) * rng.standard_normal(t.size - 1)
    x = np.empty(t.size)
    x[0] = sigma * rng.standard_normal()
    for j in range(1, t.size):
        x[j] = rho[j - 1] * x[j - 1] + shocks[j - 1]
    return x


def flicker(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma`` at the times ``t`` [s]: white
    noise on an even grid spanning the record, its amplitude spectrum shaped by 1/sqrt(f)
    (mean removed), read at ``t`` by linear interpolation."""
    n = t.size
    tg = np.linspace(float(t[0]), float(t[-1]), n)
    spec = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, float(tg[1] - tg[0]))
    spec[0] = 0.0
    spec[1:] /= np.sqrt(f[1:] / f[1])
    x = np.interp(t, tg, np.fft.irfft(spec, n))
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
        out += gauss_markov(rng, t, sig, -float(np.mean(np.diff(t))) / math.log(phi))
    if spec.get("pink"):
        out += flicker(rng, t, spec["pink"])
    step = spec.get("quant")
    return np.round(out / step) * step if step else out
