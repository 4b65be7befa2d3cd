"""Motor AT of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC motor driving the evaporating FLASK of a laboratory ROTARY EVAPORATOR (a
bench-top rotavap's rotation drive, the motor in the drive head above the water bath) on the
service bench (a 1 L round-bottom flask with 0.4 L of water in it, half immersed in the bath,
no vacuum). The armature's 10-tooth pinion drives a 120-tooth spur gear (a 12:1 reduction,
`gear` G, declared rigid and lossless); the body ``hub`` is the drive head's hollow shaft
with the gear and the duct's clamp nut. The glass vapour duct is held in the hollow shaft by
a rubber collet and carries the flask on its ground joint and a clip: the collet's rubber
with the duct is the compliance, a `spring_damper` K between the hub and the body ``flask``
(the flask with its water, the duct and the clip). The flask turns at the hub's speed on
average (1:1), its angle its own. Forward is flask.w > 0; the drive's interval mode turns it
backwards (flask.w < 0) to mix.

No circuitsim import: an independent simulator, written from the physics for
netlists/motor_at_fast.yaml and motor_at_slow.yaml. It is evaluated at the record's own
sample times (``t_eval``), never on a grid that is then interpolated. Everything rests at
t = 0: no current, no speed, the hub and the flask at 0 and the collet unloaded; an outside
effect's own state at rest too.

The spur gear is rigid (``gear`` G, ratio N = 12): the hub stands at th / N and turns at w / N
with the rotor; a torque T on it is T / N on the rotor. The collet is a spring and a damper on
the twist th / N - thf between the hub and the flask (``spring_damper`` K), its torque on the
flask

    Tk = Ks (th / N - thf) + Ds (w / N - wf).

The flask meets three declared loads: the bath water's viscous drag on the flask (``damper``
Bf), the PTFE vapour seal's dry friction on the duct (``friction`` Fs, Tf tanh(wf / 0.01),
w_brk 0.1), and the bath's wave drag, a quadratic drag Cw wf sqrt(wf^2 + (1 rad/s)^2)
(``btorque`` Wave).

State y = [i, w, th, wf, thf] (+ the water's speed wl for ``spinup``, + one Pade stage
per delayed probe, in this order):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wf, thf    the flask's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the armature with its pinion, and the hub):

    L di/dt   = u(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor + (X_hub - Tk) / N
    Jf dwf/dt = Tk - Bf wf - Tf tanh(wf / 0.01) - Cw wf sqrt(wf^2 + 1) + X_flask

Tm tanh(w / 0.01) is the brushes', the motor's sleeve bearings' and the gear's dry friction
(``friction`` Fr, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, flask) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in K (no torque while |twist| < gap / 2,
              else Ks (twist -+ gap / 2) + Ds w_rel, the damping never pulling the sides
              together)
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: parameters changed (the record's true values of the declared
              ones the user frees, an inertia's or the inductance's correction)

and outside the catalog:

    spinup    (Jl [kg m^2], c [N m s/rad]): the water in the flask does not turn with the
              glass at once: its share Jl of Jf is a body of its own (the flask's rigid
              inertia Jf - Jl), dragged by the wall's boundary layer, a viscous coupling
              c (wf - wl) on the flask (and the opposite on the water), Jl dwl/dt =
              c (wf - wl), wl = 0 at rest
    vacuum    (Tv [N m], t0 [s], tr [s]): the vacuum, let in during the record, pulls the duct
              into the PTFE seal: the seal's dry friction grows by Tv s(t) tanh(wf / 0.01),
              s(t) = (1 + tanh((t - t0) / tr)) / 2 as the pressure falls
    varistor  (I0 [A], V0 [V], n [1, an odd whole number]): a suppression varistor across
              the motor's terminals, after the current's shunt in the supply's lead: the
              current reads i + I0 (u / V0)^n, u the (stiff) supply's output; the motor
              itself is not touched
    governor  (Rg [ohm], wg [rad/s], dw [rad/s]): the motor's centrifugal speed governor
              opens its contacts above wg and puts its resistor Rg in the armature's loop:
              Rg i s, s = (1 + tanh((a - wg) / dw)) / 2, a = sqrt(w^2 + (1 rad/s)^2)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AT [SI] (motor_at_fast.yaml, motor_at_slow.yaml): what the
#: diagnosis starts from; a record's true values differ in the parameters it frees
MOTOR_AT: dict[str, float] = {
    "R": 1.2, "L": 1.5e-3, "k": 0.055, "Jm": 4e-5, "bm": 1.5e-5, "Tm": 0.012,
    "N": 12.0, "Jh": 1.5e-3, "Ks": 10.0, "Ds": 0.03, "Jf": 4e-3, "Bf": 2.5e-3, "Tf": 0.05,
    "Cw": 4e-5,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: [rad/s] the wave drag: w sqrt(w^2 + W_WAVE^2); the governor's smooth |w| likewise
W_WAVE = 1.0
#: the fast regime's command [s, V] (motor_at_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.02, 0.0), (0.18, 16.0), (0.3, 16.0), (0.33, 6.0),
               (0.4, 6.0), (0.46, -10.0), (0.53, -10.0), (0.55, 0.0), (0.6, 0.0))
#: the slow regime's logged command [s, V] (motor_at_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.5, 0.0), (1.5, 6.0), (3.0, 6.0), (3.5, 12.0), (5.0, 12.0),
               (5.5, 20.0), (6.8, 20.0), (7.4, 0.0), (7.8, 0.0), (8.2, -12.0), (9.2, -12.0),
               (9.5, 0.0), (10.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.6), "slow": (250.0, 10.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "flask")
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
    """sqrt(x^2 + eps^2)."""
    return math.sqrt(x * x + eps * eps)


# ---------------------------------------------------------------------- the model

class FlaskDrive:
    """Right-hand side of motor AT with one set of effects ``fx`` and parameters ``p`` [SI];
    ``ramp`` holds the command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.fx, self.p = fx, p
        self.ratio = p["N"]
        self.j_rotor = p["Jm"] + p["Jh"] / self.ratio ** 2
        #: the flask's rigid inertia: Jf, less the water's share with ``spinup``
        self.j_flask = p["Jf"] - (float(fx["spinup"][0]) if "spinup" in fx else 0.0)
        size = 5
        #: index of the water's speed wl (``spinup``)
        self.spin = None
        if "spinup" in fx:
            self.spin, size = size, size + 1
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
        """The torque [N m] the catalog's effects give ``body`` at its speed ``w`` [rad/s]
        and angle ``angle`` [rad]."""
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

    def resistance(self, t: float, w: float) -> float:
        """The loop's resistance [ohm] at ``t`` [s] and the rotor speed ``w`` [rad/s]: the
        armature (drifting or warming), a resistance in series or in the source, and the
        governor's resistor as its contacts open."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        if "governor" in fx:
            rg, wg, dw = fx["governor"]
            r += rg * 0.5 * (1.0 + math.tanh((_smooth_abs(w, W_WAVE) - wg) / dw))
        return r + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)

    def loop_voltage(self, t: float, i: float, w: float, th: float) -> float:
        """The voltage [V] the loop takes besides the inductance's and the EMF's."""
        fx = self.fx
        v = self.resistance(t, w) * i
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

    def collet(self, twist: float, wrel: float) -> float:
        """The collet's elastic and damping torque [N m] on the flask at the ``twist`` [rad]
        and the relative speed ``wrel`` [rad/s] (the hub's minus the flask's), with a play
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

    def flask_load(self, t: float, wf: float) -> float:
        """The flask's declared wave drag [N m] against its motion, with the vacuum's extra
        seal friction if ``vacuum``."""
        drag = self.p["Cw"] * wf * _smooth_abs(wf, W_WAVE)
        if "vacuum" in self.fx:
            tv, t0, tr = self.fx["vacuum"]
            drag += tv * 0.5 * (1.0 + math.tanh((t - t0) / tr)) * math.tanh(wf / W_SWITCH)
        return drag

    def __call__(self, t: float, y: np.ndarray) -> list[float]:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n, fx = self.p, self.ratio, self.fx
        i, w, th, wf, thf = (float(v) for v in y[:5])
        u = self.command(t)
        di = (u - self.loop_voltage(t, i, w, th) - p["k"] * w) / self.inductance(i)
        tk = self.collet(th / n - thf, w / n - wf)
        on_hub = self.body_torque("hub", w / n, th / n)
        torque = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  + self.body_torque("rotor", w, th) + (on_hub - tk) / n)
        on_flask = (tk - p["Bf"] * wf - p["Tf"] * math.tanh(wf / W_SWITCH)
                    - self.flask_load(t, wf) + self.body_torque("flask", wf, thf))
        extra: list[float] = []
        if self.spin is not None:
            jl, c = fx["spinup"]
            drag = c * (wf - float(y[self.spin]))
            on_flask -= drag
            extra.append(drag / jl)
        seen = {"current": i, "speed": w, "load_speed": wf}
        pade = [2.0 * (seen[probe] - float(y[k])) / tau for probe, tau, k in self.delays]
        return [di, torque / self.j_rotor, w, on_flask / self.j_flask, wf, *extra, *pade]


# ---------------------------------------------------------------------- integration

def _piece(model: FlaskDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AT, {a:g}-{b:g} s: {why}")


def integrate(model: FlaskDrive, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor AT at the times ``t`` [s] (default: the nominal grid),
    from rest, with the parameters ``p`` over the declared ones (and ``fx["p"]`` over
    those): current [A] (the bench's shunt in the supply's lead, or the rotavap
    controller's shunt; with a varistor's current with ``varistor``), speed [rad/s]
    (the motor's encoder, rad/s at the rotor), and in the slow regime load_speed [rad/s]
    (the flask, from the drive head's optical sensor on the hollow shaft's far end, past
    the collet: the duct's slotted ring), plus the command ``u`` [V]. ``states``: add the
    bodies' speeds [rad/s] and angles [rad], the collet's torque [N m] and the outside
    effects' states."""
    fx = dict(fx or {})
    p = {**MOTOR_AT, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = FlaskDrive(fx, p)
    y = integrate(model, t, bp, MAX_STEP[regime])
    u = np.interp(t, bp[:, 0], bp[:, 1])
    true = {"current": y[0], "speed": y[1], "load_speed": y[3]}
    for probe, _, k in model.delays:
        true[probe] = 2.0 * y[k] - true[probe]
    if "varistor" in fx:
        i0, v0, power = fx["varistor"]
        true["current"] = y[0] + float(i0) * (u / float(v0)) ** int(power)
    out = {probe: np.array(true[probe]) for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = u
    if states:
        twist, wrel = y[2] / p["N"] - y[4], y[1] / p["N"] - y[3]
        torque = np.array([model.collet(a, b) for a, b in zip(twist, wrel, strict=True)])
        out.update(rotor_angle=y[2], hub_angle=y[2] / p["N"], hub_speed=y[1] / p["N"],
                   flask_angle=y[4], flask_speed=y[3], armature_current=y[0],
                   collet_twist=twist, collet_torque=torque)
        if model.spin is not None:
            out.update(water_speed=y[model.spin])
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
