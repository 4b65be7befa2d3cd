"""Motor AM of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC motor (a 2-pole, 9-slot motor with a cast flywheel-fan on its shaft) in an
under-desk WALKING-PAD TREADMILL. The motor's 25 mm pulley drives the front roller's 75 mm
pulley through a poly-V belt (a 3:1 reduction, `gear` G, declared rigid and lossless); the
body ``hub`` is the front roller (48 mm) with its pulley. The walking belt, a 2.7 m loop of
PVC on a polyester carcass, is wrapped round the front and the rear roller; its tight span's
elastic stretch is a compliance (`spring_damper` K) between the hub and the body ``belt``,
the walking belt's 2.8 kg and the rear roller reflected to the rollers' radius r = 24 mm
(the body's angle is the belt's travel over r, 1 rad = 24 mm). Running forward is
belt.w > 0.

No circuitsim import: an independent simulator (the thirty-sixth of the benchmark), written
from the physics for netlists/motor_am_fast.yaml and motor_am_slow.yaml. It is evaluated at
the record's own sample times (``t_eval``), never on a grid that is then interpolated.
Everything rests at t = 0: no current, no speed, the rollers and the belt at 0 and the belt
unstretched; nobody is on the belt.

The poly-V belt is rigid (``gear`` G, ratio N = 3): the front roller stands at th / N and
turns at w / N with the rotor; a torque T on it is T / N on the rotor. The walking belt's
stretch is a spring and a damper on the twist th / N - thb between the front roller and the
belt (``spring_damper`` K), its torque on the belt

    Tk = Ks (th / N - thb) + Ds (w / N - wb).

The belt meets two declared loads: its underside sliding on the deck's silicone film (a
viscous drag Bd wb, ``damper``) and on the deck's board where the film is thin, with the
belt's bending over the rollers (a dry friction Td tanh(wb / 0.01), ``friction``,
w_brk 0.1). The flywheel-fan's windage on the rotor is a quadratic drag
Cw w sqrt(w^2 + (1 rad/s)^2) (``btorque`` Fan).

State y = [i, w, th, wb, thb] (+ the housing's speed and angle ws, ths for ``rock``, + the
wrap's speed and angle wc, thc for ``slip``, + one Pade stage per delayed probe, in this
order):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wb, thb    the walking belt's speed and angle [rad/s, rad] (its travel over r; 0: where
               it starts)

Equations (Jr = Jm + Jh / N^2: the armature with its flywheel-fan, and the front roller):

    L di/dt   = u(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) - Cw w sqrt(w^2 + 1) + X_rotor
                + (X_hub - Tk) / N
    Jt dwb/dt = Tk - Bd wb - Td tanh(wb / 0.01) + X_belt

Tm tanh(w / 0.01) is the brushes' and the bearings' dry friction (``friction``, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, belt) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in K (Modelica's ElastoBacklash): no torque
              while |twist| < gap / 2, else Ks (twist -+ gap / 2) + Ds w_rel, the damping
              never pulling the sides together
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    walker    (Tw [N m], a, f [Hz], t1 [s], t2 [s], d [s]): a person steps onto the belt at
              t1 and off at t2 (each over some d) and walks at a cadence f; their weight
              presses the belt on the deck, the belt receiving
              -Tw (1 + a cos(2 pi f (t - t1))) s((t - t1) / d) s((t2 - t) / d) tanh(wb / 0.01),
              s(x) = 1 / (1 + exp(-x)): the deck's friction under the walker's weight, its
              vertical load swinging at the cadence
    rub       (Tr [N m], Lb [rad], x0 [rad], n): a wavy stretch of the belt's edge rubs the
              side rail's guide once a loop of the belt: the belt receives
              -Tr ((1 + cos(2 pi (thb - x0) / Lb)) / 2)^n tanh(wb / 0.01), Lb the loop's
              length over r (its angle), x0 where the stretch's middle meets the guide
    slip      (Jc [kg m^2], Tc [N m], ws [rad/s]): the walking belt, its tension let down,
              slips on the front roller: the stretch of belt wrapped on the roller (Jc, part
              of the declared Jt; its own speed and angle wc, thc) is dragged by the roller
              with Tc tanh((w / N - wc) / ws), the roller receiving the opposite; the stretch
              K lies between the wrap and the rest of the belt (twist thc - thb), which
              carries Jt - Jc
    rock      (Js [kg m^2], Km [N m/rad], Dm [N m s/rad]): the motor's housing (Js) turns on
              its rubber mounts (Km, Dm) under the reaction of the armature's torque: the
              EMF is k (w - ws); the housing receives -k i - Km ths - Dm ws (the rotor's
              declared frictions stay against the frame, the speed is the rotor's against
              the frame)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AM [SI] (motor_am_fast.yaml, motor_am_slow.yaml)
MOTOR_AM: dict[str, float] = {
    "R": 0.55, "L": 1.4e-3, "k": 0.105, "Jm": 5e-4, "bm": 2e-5, "Tm": 0.015, "Cw": 2e-7,
    "N": 3.0, "Jh": 6e-4, "Ks": 40.0, "Ds": 0.04, "Jt": 2.1e-3, "Bd": 2e-3, "Td": 0.12,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: [rad/s] the fan's windage: w sqrt(w^2 + W_FAN^2)
W_FAN = 1.0
#: [m] the rollers' radius: 1 rad of the hub's or the belt's angle is this much travel
R_ROLLER = 0.024
#: the fast regime's command [s, V] (motor_am_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.015, 0.0), (0.075, 24.0), (0.22, 24.0), (0.24, 12.0),
               (0.31, 12.0), (0.36, -15.0), (0.44, -15.0), (0.47, 0.0), (0.5, 0.0))
#: the slow regime's logged command [s, V] (motor_am_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.5, 0.0), (1.5, 5.0), (3.0, 5.0), (4.0, 14.0), (5.5, 14.0),
               (6.3, 24.0), (7.6, 24.0), (8.4, 8.0), (9.0, 8.0), (9.4, 0.0), (10.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.5), "slow": (200.0, 10.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "belt")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a fifth of the
#: mean interval in the slow one
MAX_STEP = {"fast": 4e-5, "slow": 1e-3}


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

class Treadmill:
    """Right-hand side of motor AM with one set of effects ``fx`` [SI]; ``ramp`` holds the
    command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.ratio = p["N"]
        self.j_rotor = p["Jm"] + p["Jh"] / self.ratio ** 2
        self.j_belt = p["Jt"] - (float(fx["slip"][0]) if "slip" in fx else 0.0)
        size = 5
        #: index of the housing's speed (its angle next; None without ``rock``)
        self.housing = None
        if "rock" in fx:
            self.housing, size = size, size + 2
        #: index of the wrap's speed (its angle next; None without ``slip``)
        self.wrap = None
        if "slip" in fx:
            self.wrap, size = size, size + 2
        #: (probe, tau [s], index of its Pade state)
        self.delays: list[tuple[str, float, int]] = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.delays.append((probe, float(s["delay"]), size))
                size += 1
        self.size = size
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
        """The supply's (or the controller's) output [V] within the current segment."""
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

    def loop_voltage(self, t: float, i: float, w: float, th: float) -> float:
        """The voltage [V] the loop takes at ``t`` [s] besides the inductance's and the
        declared EMF's, at the current ``i`` [A], the rotor's speed ``w`` [rad/s] and angle
        ``th`` [rad]."""
        fx = self.fx
        v = self.resistance(t) * i
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

    def stretch(self, twist: float, wrel: float) -> float:
        """The walking belt's torque [N m] on the belt at the ``twist`` [rad] and the
        relative speed ``wrel`` [rad/s] (the front roller's minus the belt's), with a play
        if ``gap``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        if "gap" not in self.fx:
            return ks * twist + ds * wrel
        half = 0.5 * self.fx["gap"]
        if abs(twist) <= half:
            return 0.0
        edge = half if twist > 0.0 else -half
        push = ks * (twist - edge) + ds * wrel
        return max(push, 0.0) if twist > 0.0 else min(push, 0.0)

    def belt_load(self, t: float, wb: float, thb: float) -> float:
        """The torque [N m] the outside effects' laws give the belt at the time ``t`` [s],
        its speed ``wb`` [rad/s] and angle ``thb`` [rad] (0 when none)."""
        fx, tq = self.fx, 0.0
        if "walker" in fx:
            tw, a, f, t1, t2, d = fx["walker"]
            on = logistic((t - t1) / d) * logistic((t2 - t) / d)
            tq -= tw * (1.0 + a * math.cos(2.0 * math.pi * f * (t - t1))) * on \
                * math.tanh(wb / W_SWITCH)
        if "rub" in fx:
            tr, lb, x0, n = fx["rub"]
            edge = 0.5 * (1.0 + math.cos(2.0 * math.pi * (thb - x0) / lb))
            tq -= tr * edge ** n * math.tanh(wb / W_SWITCH)
        return tq

    def __call__(self, t: float, y: np.ndarray) -> list[float]:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n = self.p, self.ratio
        i, w, th, wb, thb = (float(v) for v in y[:5])
        u = self.command(t)
        emf = p["k"] * w
        extra = []
        if self.housing is not None:
            js, km, dm = self.fx["rock"]
            ws, ths = float(y[self.housing]), float(y[self.housing + 1])
            emf -= p["k"] * ws
            extra += [(-p["k"] * i - km * ths - dm * ws) / js, ws]
        di = (u - self.loop_voltage(t, i, w, th) - emf) / self.inductance(i)
        if self.wrap is None:
            tk = drive = self.stretch(th / n - thb, w / n - wb)
        else:
            jc, tc, ws = self.fx["slip"]
            wc, thc = float(y[self.wrap]), float(y[self.wrap + 1])
            drive = tc * math.tanh((w / n - wc) / ws)
            tk = self.stretch(thc - thb, wc - wb)
            extra += [(drive - tk) / jc, wc]
        torque = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  - p["Cw"] * w * math.sqrt(w * w + W_FAN ** 2)
                  + self.body_torque("rotor", w, th)
                  + (self.body_torque("hub", w / n, th / n) - drive) / n)
        dwb = (tk - p["Bd"] * wb - p["Td"] * math.tanh(wb / W_SWITCH)
               + self.body_torque("belt", wb, thb) + self.belt_load(t, wb, thb)) / self.j_belt
        seen = {"current": i, "speed": w, "load_speed": wb}
        pade = [2.0 * (seen[probe] - float(y[k])) / tau for probe, tau, k in self.delays]
        return [di, torque / self.j_rotor, w, dwb, wb, *extra, *pade]


# ---------------------------------------------------------------------- integration

def _piece(model: Treadmill, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AM, {a:g}-{b:g} s: {why}")


def integrate(model: Treadmill, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor AM at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A] (the supply's shunt), speed [rad/s] (an optical sensor on the
    frame reading the flywheel-fan's stripes), and in the slow regime load_speed [rad/s]
    (the walking belt, from a reed sensor on the rear roller, as rad/s of the 48 mm
    rollers), plus the command ``u`` [V]. ``states``: add the angles [rad] and the walking
    belt's stretch torque [N m]."""
    fx = dict(fx or {})
    p = {**MOTOR_AM, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = Treadmill(fx, p)
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
        out.update(rotor_angle=y[2], hub_angle=y[2] / p["N"], belt_angle=y[4],
                   belt_speed=y[3], armature_current=y[0],
                   stretch_torque=p["Ks"] * twist + p["Ds"] * (y[1] / p["N"] - y[3]))
        if model.housing is not None:
            out.update(housing_speed=y[model.housing], housing_angle=y[model.housing + 1])
        if model.wrap is not None:
            out.update(wrap_speed=y[model.wrap], wrap_angle=y[model.wrap + 1],
                       stretch_torque=p["Ks"] * (y[model.wrap + 1] - y[4])
                       + p["Ds"] * (y[model.wrap] - y[3]))
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
