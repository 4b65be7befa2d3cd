"""Motor AQ of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC motor (a 2-pole, 12-slot armature in a ferrite-magnet can) driving the BURR of an
ELECTRIC FLAT-BURR COFFEE GRINDER (a bench-top grinder for a cafe's filter coffee) on the
maker's test bench (no beans: the burr spins empty). The armature's 10-tooth pinion drives a
50-tooth spur gear (a 5:1 reduction, `gear` G, declared rigid and lossless); the body ``hub``
is the gear's output shaft with the gear and one hub of a jaw coupling. The coupling's
polyurethane spider (a six-lobed elastomer star) between the two jaw hubs is the compliance, a
`spring_damper` K between the hub and the body ``burr`` (the lower burr carrier: the burr
shaft, the other jaw hub, the steel carrier with the 64 mm rotating flat burr and the grounds
sweeper). The burr turns at the hub's speed on average (1:1), its angle its own. Grinding is
burr.w > 0; backwards (the controller's "reverse to clear" run) is burr.w < 0.

No circuitsim import: an independent simulator (the fortieth of the benchmark), written from
the physics for netlists/motor_aq_fast.yaml and motor_aq_slow.yaml. It is evaluated at the
record's own sample times (``t_eval``), never on a grid that is then interpolated. Everything
rests at t = 0: no current, no speed, the hub and the burr at 0 and the spider unloaded; an
outside effect's own state at rest too.

The spur gear is rigid (``gear`` G, ratio N = 5): the hub stands at th / N and turns at w / N
with the rotor; a torque T on it is T / N on the rotor. The spider is a spring and a damper on
the twist th / N - thc between the hub and the burr (``spring_damper`` K), its torque on the
burr

    Tk = Ks (th / N - thc) + Ds (w / N - wc).

The burr meets three declared loads: the burr shaft's two ball bearings (a viscous drag
Bc wc, ``damper``), the felt dust seal under the burr carrier (a dry friction
Tb tanh(wc / 0.01), ``friction``, w_brk 0.1) and the sweeper's and the burr's teeth's air
drag, a quadratic drag Cw wc sqrt(wc^2 + (1 rad/s)^2) (``btorque`` Wind).

State y = [i, w, th, wc, thc] (+ the polyfuse's heating h for ``pptc``, + one Pade stage per
delayed probe, in this order):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wc, thc    the burr's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the armature with its pinion, and the hub):

    L di/dt   = u(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor + (X_hub - Tk) / N
    Jc dwc/dt = Tk - Bc wc - Tb tanh(wc / 0.01) - Cw wc sqrt(wc^2 + 1) + X_burr

Tm tanh(w / 0.01) is the brushes', the motor's sleeve bearings' and the gear's dry friction
(``friction``, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, burr) receives
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

    pptc      (Rh [ohm], I0 [A], tau [s]): a resettable polyfuse (PPTC) in the motor's lead,
              its resistance rising with its own temperature: Rh h in the loop, the heating
              h following the current's square, dh/dt = ((i / I0)^2 - h) / tau (h = 0 at
              rest): a resistance that grows with the recent I^2, not with time
    ring      (e [1], phase [rad]): the speed probe's magnet ring glued off-centre on the
              rotor's shaft: the speed reads w (1 + e sin(th + phase)) (a measurement error
              once a turn of the rotor, in proportion to the speed; the motor is not touched)
    ripple    (r [1], f [Hz]): the controller's unsmoothed rectified rail: the PWM output is
              u(t) (1 + r sin(2 pi f t)) while the logged command is u(t): a ripple locked to
              the mains, in proportion to the command, not to any angle
    harden    (x0 [rad],): the spider hardening as its lobes are squeezed: besides Ks and Ds
              the coupling's torque takes Ks x (x / x0)^2, x = th / N - thc (stiffer at large
              twist: the coupling's resonance rises with the torque it carries)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AQ [SI] (motor_aq_fast.yaml, motor_aq_slow.yaml)
MOTOR_AQ: dict[str, float] = {
    "R": 1.2, "L": 6e-4, "k": 0.035, "Jm": 2e-5, "bm": 4e-6, "Tm": 0.008,
    "N": 5.0, "Jh": 1.2e-4, "Ks": 8.0, "Ds": 0.008, "Jc": 4e-4, "Bc": 3e-5, "Tb": 0.03,
    "Cw": 1e-6,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: [rad/s] the windage: w sqrt(w^2 + W_WIND^2)
W_WIND = 1.0
#: the fast regime's command [s, V] (motor_aq_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.2, 16.0), (0.3, 16.0), (0.32, 6.0),
               (0.4, 6.0), (0.48, -8.0), (0.54, -8.0), (0.56, 0.0), (0.6, 0.0))
#: the slow regime's logged command [s, V] (motor_aq_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.5, 0.0), (1.5, 10.0), (3.0, 10.0), (3.5, 18.0), (5.0, 18.0),
               (5.5, 22.0), (7.0, 22.0), (7.8, 0.0), (8.2, 0.0), (8.7, -12.0), (9.4, -12.0),
               (9.7, 0.0), (10.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.6), "slow": (250.0, 10.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "burr")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a fifth of the
#: mean interval in the slow one
MAX_STEP = {"fast": 5e-5, "slow": 8e-4}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.array(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def _smooth_abs(x: float, eps: float) -> float:
    """sqrt(x^2 + eps^2), as circuitsim's smooth_abs."""
    return math.sqrt(x * x + eps * eps)


# ---------------------------------------------------------------------- the model

class BurrDrive:
    """Right-hand side of motor AQ with one set of effects ``fx`` [SI]; ``ramp`` holds the
    command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.ratio = p["N"]
        self.j_rotor = p["Jm"] + p["Jh"] / self.ratio ** 2
        size = 5
        #: index of the polyfuse's heating (None without ``pptc``)
        self.pptc = None
        if "pptc" in fx:
            self.pptc, size = size, size + 1
        #: (probe, tau [s], index of its Pade state)
        self.delays: list[tuple[str, float, int]] = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.delays.append((probe, float(s["delay"]), size))
                size += 1
        self.size = size
        self.extras = {body: self._collect(body) for body in BODIES}
        self.ramp = (0.0, 0.0, 0.0)
        #: the polyfuse's heating h [1] at the current evaluation (``pptc``)
        self.heat = 0.0

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
        u = u0 + slope * (t - t0)
        if "ripple" in self.fx:
            r, f = self.fx["ripple"]
            u *= 1.0 + r * math.sin(2.0 * math.pi * f * t)
        return u

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
        EMF's, at the current ``i`` [A], the rotor's speed ``w`` [rad/s] and angle ``th``
        [rad]."""
        fx = self.fx
        v = self.resistance(t) * i
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SWITCH)
        if self.pptc is not None:
            v += fx["pptc"][0] * float(self.heat) * i
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

    def band(self, twist: float, wrel: float) -> float:
        """The spider's elastic and damping torque [N m] on the burr at the ``twist`` [rad]
        and the relative speed ``wrel`` [rad/s] (the hub's minus the burr's), with a play
        if ``gap``, hardening if ``harden``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        if "gap" not in self.fx:
            tk = ks * twist + ds * wrel
            if "harden" in self.fx:
                tk += ks * twist * (twist / float(self.fx["harden"][0])) ** 2
            return tk
        half = 0.5 * self.fx["gap"]
        if abs(twist) <= half:
            return 0.0
        edge = half if twist > 0.0 else -half
        push = ks * (twist - edge) + ds * wrel
        return max(push, 0.0) if twist > 0.0 else min(push, 0.0)

    def __call__(self, t: float, y: np.ndarray) -> list[float]:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n, fx = self.p, self.ratio, self.fx
        i, w, th, wc, thc = (float(v) for v in y[:5])
        u = self.command(t)
        extra: list[float] = []
        if self.pptc is not None:
            _, i0, tau = fx["pptc"]
            self.heat = float(y[self.pptc])
            extra.append(((i / i0) ** 2 - self.heat) / tau)
        di = (u - self.loop_voltage(t, i, w, th) - p["k"] * w) / self.inductance(i)
        wrel = w / n - wc
        tk = self.band(th / n - thc, wrel)
        on_hub = self.body_torque("hub", w / n, th / n)
        torque = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  + self.body_torque("rotor", w, th) + (on_hub - tk) / n)
        on_burr = (tk - p["Bc"] * wc - p["Tb"] * math.tanh(wc / W_SWITCH)
                   - p["Cw"] * wc * _smooth_abs(wc, W_WIND)
                   + self.body_torque("burr", wc, thc))
        seen = {"current": i, "speed": w, "load_speed": wc}
        pade = [2.0 * (seen[probe] - float(y[k])) / tau for probe, tau, k in self.delays]
        return [di, torque / self.j_rotor, w, on_burr / p["Jc"], wc, *extra, *pade]


# ---------------------------------------------------------------------- integration

def _piece(model: BurrDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AQ, {a:g}-{b:g} s: {why}")


def integrate(model: BurrDrive, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor AQ at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A] (the bench's shunt in the supply's lead, or the grinder
    controller's shunt), speed [rad/s] (the motor's Hall encoder, rad/s at the rotor, read
    through an off-centre magnet ring with ``ring``), and in the slow regime load_speed
    [rad/s] (the burr, from the controller's Hall switch under the burr carrier's magnets),
    plus the command ``u`` [V]. ``states``: add the bodies' speeds [rad/s] and angles [rad],
    the spider's torque [N m] and the outside effects' states."""
    fx = dict(fx or {})
    p = {**MOTOR_AQ, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = BurrDrive(fx, p)
    y = integrate(model, t, bp, MAX_STEP[regime])
    u = np.interp(t, bp[:, 0], bp[:, 1])
    true = {"current": y[0], "speed": y[1], "load_speed": y[3]}
    for probe, _, k in model.delays:
        true[probe] = 2.0 * y[k] - true[probe]
    if "ring" in fx:
        e, phase = fx["ring"]
        true["speed"] = y[1] * (1.0 + e * np.sin(y[2] + phase))
    out = {probe: np.array(true[probe]) for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = u
    if states:
        twist, wrel = y[2] / p["N"] - y[4], y[1] / p["N"] - y[3]
        torque = np.array([model.band(a, b) for a, b in zip(twist, wrel, strict=True)])
        out.update(rotor_angle=y[2], hub_angle=y[2] / p["N"], hub_speed=y[1] / p["N"],
                   burr_angle=y[4], burr_speed=y[3], armature_current=y[0],
                   spider_twist=twist, spider_torque=torque)
        if model.pptc is not None:
            out.update(pptc_heating=y[model.pptc])
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
