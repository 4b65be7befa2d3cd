"""Motor AC of the diagnosis benchmark: a hand-written scipy model of a 12 V permanent-magnet
brushed DC motor moving a car seat fore and aft: the motor drives a rigid, lossless 5:1 spur
gear, whose output hub turns the seat track's lead screw through a flexible drive shaft (a
torsional compliance, the steel core of the shaft that runs from the motor across to the
track). The screw, with the nut, the seat and its occupant reflected to it through its 1 mm
lead, takes the nut's dry friction and a viscous drag of its grease.

No circuitsim import: an independent simulator (the twenty-sixth of the benchmark), written
from the physics for netlists/motor_ac_fast.yaml and motor_ac_slow.yaml. It is evaluated at
the record's own sample times (``t_eval``), never on a grid that is then interpolated.
Everything rests at t = 0 (no current, no speed, the flexible shaft untwisted).

The spur gear is rigid and lossless (``gear`` G, ratio N = 5): its output hub stands at th / N
and turns at w / N with the rotor; a torque T on the hub is T / N on the rotor. The flexible
shaft is a spring and damper on the twist th / N - ths between the hub and the screw
(``spring_damper`` K).

State z = [i, w, th, ws, ths] (+ one Pade stage per delayed probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    ws, ths    the screw's speed and angle [rad/s, rad]

Equations (J1 = Jm + Jg / N^2: the rotor with the gear's output hub):

    L di/dt   = v(t) - R i - k w - (the loop's extras)
    J1 dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor + (X_hub - Tk) / N
    Js dws/dt = Tk - Bs ws - Tl tanh(ws / 0.01) + X_screw
    Tk        = Kc (th / N - ths) + Dc (w / N - ws)          (the flexible shaft)

Tm tanh(w / 0.01) is the brushes' dry friction (``friction``, w_brk 0.1), Bs ws the grease's
drag, Tl tanh(ws / 0.01) the nut's and the track's dry friction (``friction``, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, screw) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in the flexible shaft (Modelica's
              ElastoBacklash): no torque while |twist| < gap / 2, else Kc (twist -+ gap / 2)
              + Dc w_rel, the damping never pulling the sides together
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    nutload   mu [1]: the nut's friction grows with the thrust it carries: the screw takes
              -mu |Tk| tanh(ws / 0.01) more (Tk the flexible shaft's torque, the thrust's
              measure through the screw's lead)
    grease    (b1 [N m s/rad], tau [s]): cold grease thinning as it warms: the screw takes
              -b1 exp(-t / tau) ws more
    heater    (Rh [ohm], Ih [A], t1 [s], tr [s]): the seat heater switched on at t1 on a
              harness shared with the motor: the motor's terminal sees v - Rh (i + Ih h(t)),
              h(t) = (1 + tanh((t - t1) / tr)) / 2
    tight     (Tb [N m], th0 [rad], wd [rad]): a bent track, tight over a stretch: the screw
              takes -Tb exp(-((ths - th0) / wd)^2) tanh(ws / 0.01) more
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AC [SI] (motor_ac_fast.yaml, motor_ac_slow.yaml)
MOTOR_AC: dict[str, float] = {
    "R": 1.6, "L": 0.9e-3, "k": 0.02, "Jm": 1.2e-5, "bm": 4e-6, "Tm": 0.003, "N": 5.0,
    "Jg": 2e-5, "Kc": 1.5, "Dc": 1.5e-3, "Js": 2e-5, "Bs": 2e-4, "Tl": 0.03,
}
#: [rad/s] the frictions' and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_ac_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.005, 0.0), (0.015, 12.0), (0.12, 12.0), (0.122, 8.0),
               (0.18, 8.0), (0.182, 0.0), (0.22, 0.0), (0.224, -12.0), (0.3, -12.0),
               (0.302, 0.0), (0.35, 0.0))
#: the slow regime's logged command [s, V] (motor_ac_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.2, 0.0), (0.4, 12.0), (1.8, 12.0), (1.85, 0.0), (2.3, 0.0),
               (2.5, -12.0), (3.9, -12.0), (3.95, 0.0), (4.2, 0.0), (4.3, 8.0), (4.8, 8.0),
               (4.85, 0.0), (5.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.35), "slow": (250.0, 5.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "screw")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime (L/R is 0.56 ms),
#: a fifth of the mean interval in the slow one
H_MAX = {"fast": 5e-5, "slow": 8e-4}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.asarray(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class SeatDrive:
    """Right-hand side of motor AC with one set of effects ``fx`` [SI]."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.n = p["N"]
        self.j1 = p["Jm"] + p["Jg"] / self.n ** 2
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
        """What the catalog's effects put on ``body``: (viscous, Coulomb, offset,
        harmonics, Stribeck), or None when nothing."""
        fx = self.fx
        t = (fx.get("visc", {}).get(body, 0.0), fx.get("coul", {}).get(body, 0.0),
             fx.get("offset", {}).get(body, 0.0), tuple(fx.get("cog", {}).get(body, ())),
             fx.get("stribeck", {}).get(body))
        return t if any(t) else None

    def extra_torque(self, body: str, w: float, angle: float) -> float:
        """The torque [N m] the catalog's effects give ``body`` at its speed ``w`` [rad/s]
        and angle ``angle`` [rad]."""
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
        """The driver's output [V] as commanded, linear within the segment."""
        t0, u0, slope = self.seg
        return u0 + slope * (t - t0)

    def loop_drop(self, t: float, i: float, w: float, th: float) -> float:
        """Every voltage [V] the loop takes but the inductance's and the declared EMF's:
        the (drifting) resistances, the brushes, the shared harness and the EMF's
        harmonics, at the time ``t`` [s], the current ``i`` [A], the rotor's speed ``w``
        [rad/s] and angle ``th`` [rad]."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t) + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        v = r * i
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SIGN)
        if "heater" in fx:
            rh, ih, t1, tr = fx["heater"]
            v += rh * (i + ih * 0.5 * (1.0 + math.tanh((t - t1) / tr)))
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

    def shaft_torque(self, twist: float, wrel: float) -> float:
        """The flexible shaft's torque [N m] from the hub on the screw at the ``twist``
        [rad] and the relative speed ``wrel`` [rad/s] (hub minus screw), with a play if
        ``gap``."""
        p = self.p
        gap = self.fx.get("gap")
        if gap is None:
            return p["Kc"] * twist + p["Dc"] * wrel
        h = 0.5 * gap
        if twist > h:
            return max(p["Kc"] * (twist - h) + p["Dc"] * wrel, 0.0)
        if twist < -h:
            return min(p["Kc"] * (twist + h) + p["Dc"] * wrel, 0.0)
        return 0.0

    def screw_outside(self, t: float, ws: float, ths: float, tk: float) -> float:
        """The torque [N m] the outside effects give the screw at the time ``t`` [s], its
        speed ``ws`` [rad/s] and angle ``ths`` [rad], the shaft's torque ``tk`` [N m]."""
        fx = self.fx
        out = 0.0
        sgn = math.tanh(ws / W_SIGN)
        if "nutload" in fx:
            out -= fx["nutload"] * abs(tk) * sgn
        if "grease" in fx:
            b1, tau = fx["grease"]
            out -= b1 * math.exp(-t / tau) * ws
        if "tight" in fx:
            tb, th0, wd = fx["tight"]
            out -= tb * math.exp(-((ths - th0) / wd) ** 2) * sgn
        return out

    def __call__(self, t: float, z: np.ndarray) -> list[float]:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p, n = self.p, self.n
        i, w, th, ws, ths = (float(v) for v in z[:5])
        di = (self.command(t) - self.loop_drop(t, i, w, th) - p["k"] * w) / self.inductance(i)
        tk = self.shaft_torque(th / n - ths, w / n - ws)
        tau = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SIGN)
               + self.extra_torque("rotor", w, th)
               + (self.extra_torque("hub", w / n, th / n) - tk) / n)
        dws = (tk - p["Bs"] * ws - p["Tl"] * math.tanh(ws / W_SIGN)
               + self.extra_torque("screw", ws, ths)
               + self.screw_outside(t, ws, ths, tk)) / p["Js"]
        out = [di, tau / self.j1, w, dws, ws]
        values = {"current": i, "speed": w, "load_speed": ws}
        out += [2.0 * (values[probe] - float(z[k])) / tau_d for probe, tau_d, k in self.pade]
        return out


# ---------------------------------------------------------------------- integration

def _solve(model: SeatDrive, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AC, {a:g}-{b:g} s: {msg}")


def integrate(model: SeatDrive, t: np.ndarray, bp: np.ndarray, h_max: float
              ) -> np.ndarray:
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
    """Noise-free probes of motor AC at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the screw, from the Hall sensor on its end), plus the command
    ``u`` [V]. ``states``: add the angles [rad]."""
    fx = dict(fx or {})
    p = {**MOTOR_AC, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = SeatDrive(fx, p)
    y = integrate(model, t, bp, H_MAX[regime])
    full = {"current": y[0], "speed": y[1], "load_speed": y[3]}
    for probe, _, k in model.pade:
        full[probe] = 2.0 * y[k] - full[probe]
    out = {probe: full[probe].copy() for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2], screw_angle=y[4], screw_speed=y[3],
                   twist=y[2] / p["N"] - y[4])
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
    noise on an even grid spanning the record, its power spectrum shaped by 1/f (amplitude
    by 1/sqrt(f), mean removed), read at ``t`` by linear interpolation."""
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
