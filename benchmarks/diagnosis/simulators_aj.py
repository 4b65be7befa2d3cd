"""Motor AJ of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC motor in the ROTATION DRIVE OF AN OBSERVATORY DOME (a 3 m steel-framed dome of an
amateur observatory, about 500 kg, turning on a ring of support rollers). The motor drives a
rigid, lossless 60:1 worm gearbox (`gear` G), whose output shaft carries a polyurethane-tyred
friction drive wheel (the body ``hub``, 80 mm across, r = 0.04 m); the wheel is pressed by a
spring bracket against the inside face of the dome's base ring. The tyre's tangential
(shear) compliance and the bracket's spring are a compliance (`spring_damper` K) between the
wheel and the dome. The dome is reflected to the wheel through the ratio of the ring's radius
to the wheel's, 1.5 m / 0.04 m = 37.5: the body ``dome``'s angle is the ring's travel over r
(1 rad = 40 mm of the ring, 1.53 degrees of the dome), its speed the ring's speed over r, its
inertia the dome's over 37.5^2, a torque T on it T / 37.5 on the dome. Turning clockwise
(seen from below) is dome.w > 0.

No circuitsim import: an independent simulator (the thirty-third of the benchmark), written
from the physics for netlists/motor_aj_fast.yaml and motor_aj_slow.yaml. It is evaluated at
the record's own sample times (``t_eval``), never on a grid that is then interpolated.
Everything rests at t = 0: no current, no speed, the dome at 0 and the tyre unstrained.

The gearbox is rigid (``gear`` G, ratio N = 60): the wheel stands at th / N and turns at w / N
with the rotor; a torque T on it is T / N on the rotor. The tyre and the bracket are a spring
and a damper on the twist th / N - thd between the wheel and the dome (``spring_damper`` K),
their torque on the dome

    Tk = Ks (th / N - thd) + Ds (w / N - wd).

The dome meets three declared loads: the support rollers' bearings and the side guide
rollers' grease (a viscous drag Bd wd, ``damper``); the rollers' rolling resistance (a dry
friction Td tanh(wd / 0.01), ``friction``, w_brk 0.1); and the weather skirt's brush seal
round the dome's base, whose bristles bend over before they slide: a soft dry drag
Cs tanh(wd / ws), ws = 2 rad/s (``btorque`` Skirt).

State y = [i, w, th, wd, thd] (+ one Pade stage per delayed probe, + the battery's
polarisation voltage):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wd, thd    the dome's speed and angle, reflected to the wheel [rad/s, rad] (0: where it
               starts)

Equations (Jr = Jm + Jh / N^2: the rotor with the worm, and the wheel):

    L di/dt   = u(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor + (X_hub - Tk) / N
    Jd dwd/dt = Tk - Bd wd - Td tanh(wd / 0.01) - Cs tanh(wd / ws) + X_dome

Tm tanh(w / 0.01) is the brushes' and the bearings' dry friction (``friction``, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, dome) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in the tyre K (Modelica's ElastoBacklash): no
              torque while |twist| < gap / 2, else Ks (twist -+ gap / 2) + Ds w_rel, the
              damping never pulling the sides together
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    ice       (F [N m], a [rad], b [rad], d [rad]): a patch of ice on the base ring between
              the dome's angles a and b: the rollers and the wheel's contact drag more
              there, the dome receiving -F s((thd - a) / d) s((b - thd) / d) tanh(wd / 0.01),
              s(x) = 1 / (1 + exp(-x))
    detent    (Kh [N m/rad], wh [rad]): the shutter's charging contacts at the home position
              (where the dome starts) hold it there: the dome receives
              -Kh thd exp(-(thd / wh)^2)
    battery   (Rp [ohm], Cp [F]): the off-grid 24 V lead-acid bank's polarisation, an R-C
              pair in series with the source: the loop takes vp, dvp/dt = i / Cp - vp / (Rp Cp)
              (from 0)
    splice    (E [J], a [rad], wd [rad]): the base ring's splice plate, where two rolled
              segments are bolted together, stands proud at the dome's angle a; the sprung
              drive wheel climbs over it and drops off it (the bracket's spring storing and
              giving back the energy E): the dome receives -dU/dthd, U = E exp(-((thd - a)
              / wd)^2), that is 2 E (thd - a) / wd^2 exp(-((thd - a) / wd)^2)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AJ [SI] (motor_aj_fast.yaml, motor_aj_slow.yaml)
MOTOR_AJ: dict[str, float] = {
    "R": 0.55, "L": 9e-4, "k": 0.055, "Jm": 1.1e-4, "bm": 8e-6, "Tm": 0.02, "N": 60.0,
    "Jh": 2e-3, "Ks": 800.0, "Ds": 4.0, "Jd": 0.8, "Bd": 0.3, "Td": 2.5, "Cs": 1.0,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: [rad/s] the skirt's bristles' speed scale, tanh(wd / ws)
W_SKIRT = 2.0
#: the fast regime's command [s, V] (motor_aj_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.02, 0.0), (0.12, 24.0), (0.3, 24.0), (0.4, 0.0),
               (0.43, 0.0), (0.5, -16.0), (0.56, -16.0), (0.59, 0.0), (0.6, 0.0))
#: the slow regime's logged command [s, V] (motor_aj_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.3, 0.0), (0.8, 24.0), (2.4, 24.0), (2.6, 10.0), (3.0, 10.0),
               (3.05, 0.0), (3.4, 0.0), (3.9, -24.0), (5.25, -24.0), (5.45, -10.0),
               (5.8, -10.0), (5.85, 0.0), (6.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.6), "slow": (200.0, 6.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "dome")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a fifth of the
#: mean interval in the slow one
MAX_STEP = {"fast": 5e-5, "slow": 1e-3}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.array(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def logistic(x: float) -> float:
    """1 / (1 + exp(-x)), without overflow."""
    if x >= 0.0:
        return 1.0 / (1.0 + math.exp(-x))
    e = math.exp(x)
    return e / (1.0 + e)


# ---------------------------------------------------------------------- the model

class DomeDrive:
    """Right-hand side of motor AJ with one set of effects ``fx`` [SI]; ``ramp`` holds the
    command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.ratio = p["N"]
        self.j_rotor = p["Jm"] + p["Jh"] / self.ratio ** 2
        #: (probe, tau [s], index of its Pade state)
        self.delays: list[tuple[str, float, int]] = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.delays.append((probe, float(s["delay"]), 5 + len(self.delays)))
        #: the index of the battery's polarisation voltage (None: no battery effect)
        self.i_batt = 5 + len(self.delays) if "battery" in fx else None
        self.size = 5 + len(self.delays) + (1 if self.i_batt is not None else 0)
        self.extras = {body: self._collect(body) for body in BODIES}
        self.ramp = (0.0, 0.0, 0.0)

    def _collect(self, body: str) -> dict[str, Any]:
        """The catalog's effects on ``body`` (empty when none)."""
        out = {}
        for key in ("visc", "coul", "offset", "stribeck", "cog"):
            value = self.fx.get(key, {}).get(body)
            if value:
                out[key] = value
        return out

    def body_torque(self, body: str, w: float, angle: float) -> float:
        """The torque [N m] the catalog's effects give ``body`` at the speed ``w`` [rad/s]
        and the angle ``angle`` [rad]."""
        ex = self.extras[body]
        if not ex:
            return 0.0
        sw = math.tanh(w / W_SWITCH)
        tq = ex.get("offset", 0.0) - ex.get("visc", 0.0) * w - ex.get("coul", 0.0) * sw
        if "stribeck" in ex:
            peak, ws = ex["stribeck"]
            tq -= peak * math.exp(-(w / ws) ** 2) * sw
        for order, a, b in ex.get("cog", ()):
            tq += a * math.sin(order * angle) + b * math.cos(order * angle)
        return tq

    def command(self, t: float) -> float:
        """The controller's mean output [V] within the current segment."""
        t0, u0, slope = self.ramp
        return u0 + slope * (t - t0)

    def resistance(self, t: float) -> float:
        """The loop's resistance [ohm] at the time ``t`` [s]: the armature (drifting or
        warming), and a resistance in series or in the source."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        return r + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)

    def loop_voltage(self, t: float, i: float, w: float, th: float, vp: float) -> float:
        """The voltage [V] the loop takes at ``t`` [s] besides the inductance's and the
        declared EMF's, at the current ``i`` [A], the rotor's speed ``w`` [rad/s] and angle
        ``th`` [rad], the battery's polarisation ``vp`` [V]."""
        fx = self.fx
        v = self.resistance(t) * i + vp
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SWITCH)
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

    def tyre(self, twist: float, wrel: float) -> float:
        """The tyre's torque [N m] on the dome at the ``twist`` [rad] and the relative speed
        ``wrel`` [rad/s] (the wheel's minus the dome's), with a play if ``gap``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        if "gap" not in self.fx:
            return ks * twist + ds * wrel
        half = 0.5 * self.fx["gap"]
        if abs(twist) <= half:
            return 0.0
        edge = half if twist > 0.0 else -half
        push = ks * (twist - edge) + ds * wrel
        return max(push, 0.0) if twist > 0.0 else min(push, 0.0)

    def dome_load(self, wd: float, thd: float) -> float:
        """The torque [N m] the outside effects' laws give the dome at its speed ``wd``
        [rad/s] and angle ``thd`` [rad] (0 when none)."""
        fx, tq = self.fx, 0.0
        if "ice" in fx:
            f, a, b, d = fx["ice"]
            tq -= f * logistic((thd - a) / d) * logistic((b - thd) / d) \
                * math.tanh(wd / W_SWITCH)
        if "detent" in fx:
            kh, wh = fx["detent"]
            tq -= kh * thd * math.exp(-(thd / wh) ** 2)
        if "splice" in fx:
            e, a, wdt = fx["splice"]
            x = (thd - a) / wdt
            tq += 2.0 * e * x / wdt * math.exp(-x * x)
        return tq

    def __call__(self, t: float, y: np.ndarray) -> list[float]:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n = self.p, self.ratio
        i, w, th, wd, thd = (float(v) for v in y[:5])
        vp = 0.0 if self.i_batt is None else float(y[self.i_batt])
        di = (self.command(t) - self.loop_voltage(t, i, w, th, vp) - p["k"] * w) \
            / self.inductance(i)
        tk = self.tyre(th / n - thd, w / n - wd)
        torque = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  + self.body_torque("rotor", w, th)
                  + (self.body_torque("hub", w / n, th / n) - tk) / n)
        dwd = (tk - p["Bd"] * wd - p["Td"] * math.tanh(wd / W_SWITCH)
               - p["Cs"] * math.tanh(wd / W_SKIRT)
               + self.body_torque("dome", wd, thd) + self.dome_load(wd, thd)) / p["Jd"]
        seen = {"current": i, "speed": w, "load_speed": wd}
        pade = [2.0 * (seen[probe] - float(y[k])) / tau for probe, tau, k in self.delays]
        out = [di, torque / self.j_rotor, w, dwd, wd, *pade]
        if self.i_batt is not None:
            rp, cp = self.fx["battery"]
            out.append(i / cp - vp / (rp * cp))
        return out


# ---------------------------------------------------------------------- integration

def _piece(model: DomeDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
           max_step: float) -> np.ndarray:
    """The states at ``t_out`` [s] from ``y0`` at ``a`` to ``b`` [s]: LSODA, Radau if LSODA
    fails."""
    why = ""
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), y0, method=method, t_eval=t_out, rtol=RTOL,
                        atol=ATOL, max_step=max_step)
        if sol.success and sol.y.shape[1] == t_out.size and np.isfinite(sol.y).all():
            return sol.y
        why = sol.message
    raise RuntimeError(f"motor AJ, {a:g}-{b:g} s: {why}")


def integrate(model: DomeDrive, t: np.ndarray, bp: np.ndarray, max_step: float
              ) -> np.ndarray:
    """The states (n_states, t.size) at the increasing times ``t`` [s], from rest at 0, the
    integration restarted at every corner of the command ``bp`` [s, V]."""
    end = float(t[-1])
    corners = sorted({0.0, end, *(float(c) for c in bp[:, 0] if 0.0 < c < end)})
    out = np.empty((model.size, t.size))
    y0 = np.zeros(model.size)
    for a, b in itertools.pairwise(corners):
        ua, ub = np.interp([a, b], bp[:, 0], bp[:, 1])
        model.ramp = (a, float(ua), float(ub - ua) / (b - a))
        inside = (t >= a) & ((t <= b) if b == end else (t < b))
        t_out = t[inside] if b == end else np.append(t[inside], b)
        ys = _piece(model, a, b, y0, t_out, max_step)
        out[:, inside] = ys[:, :int(inside.sum())]
        y0 = ys[:, -1].copy()
    return out


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor AJ at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the dome, from an encoder wheel running on the base ring, reflected
    to the drive wheel), plus the command ``u`` [V]. ``states``: add the angles [rad] and
    the tyre's torque [N m]."""
    fx = dict(fx or {})
    p = {**MOTOR_AJ, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = DomeDrive(fx, p)
    y = integrate(model, t, bp, MAX_STEP[regime])
    u = np.interp(t, bp[:, 0], bp[:, 1])
    true = {"current": y[0], "speed": y[1], "load_speed": y[3]}
    for probe, _, k in model.delays:
        true[probe] = 2.0 * y[k] - true[probe]
    out = {probe: np.array(true[probe]) for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = u
    if states:
        twist = y[2] / p["N"] - y[4]
        out.update(rotor_angle=y[2], dome_angle=y[4], dome_speed=y[3],
                   tyre_torque=p["Ks"] * twist + p["Ds"] * (y[1] / p["N"] - y[3]))
    return out


# ---------------------------------------------------------------------- noise

def ar1(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float) -> np.ndarray:
    """A stationary first-order Gauss-Markov process [probe unit], standard deviation
    ``sigma``, correlation time ``tau`` [s], sampled exactly at the (uneven) times ``t``."""
    rho = np.exp(-np.diff(t) / tau)
    kick = rng.standard_normal(t.size) * sigma
    kick[1:] *= np.sqrt(1.0 - rho ** 2)
    x = np.empty(t.size)
    x[0] = kick[0]
    for j, r in enumerate(rho, start=1):
        x[j] = r * x[j - 1] + kick[j]
    return x


def pink(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma`` at the times ``t`` [s]: white
    noise on an even grid over the record, its amplitude spectrum divided by sqrt(f) (no
    mean), read at ``t`` linearly."""
    n = t.size
    even = np.linspace(float(t[0]), float(t[-1]), n)
    f = np.fft.rfftfreq(n, float(even[1] - even[0]))
    spectrum = np.fft.rfft(rng.standard_normal(n))
    spectrum[0] = 0.0
    spectrum[1:] *= np.sqrt(f[1] / f[1:])
    x = np.interp(t, even, np.fft.irfft(spectrum, n))
    x -= x.mean()
    return x * (sigma / x.std())


def add_noise(rng: np.random.Generator, t: np.ndarray, y: np.ndarray,
              spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` at the times ``t`` [s] with ``white`` sigma, ``ar1`` [sigma, phi] (a
    Gauss-Markov process correlated by phi over the mean interval) and ``pink`` (1/f) sigma
    noise added [probe unit], then read by an ADC of step ``quant`` [probe unit]."""
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out += rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        sigma, phi = spec["ar1"]
        out += ar1(rng, t, sigma, -float(np.mean(np.diff(t))) / math.log(phi))
    if spec.get("pink"):
        out += pink(rng, t, spec["pink"])
    step = spec.get("quant")
    return np.round(out / step) * step if step else out
