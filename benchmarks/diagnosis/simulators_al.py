"""Motor AL of the diagnosis benchmark: a hand-written scipy model of an 18 V permanent-magnet
brushed DC motor (a 5-slot, 2-pole can motor with a brass flywheel on its shaft) in a G-SCALE
GARDEN-RAILWAY LOCOMOTIVE hauling a rake of coaches round an outdoor layout, fed through the
rails by a hobby power pack. The motor's worm drives the driving axles through a worm gear
and its spur gears (a rigid 28:1 reduction, `gear` G, lossless); the body ``hub`` is the
driving axles with their 45 mm wheels and the locomotive's own 4.5 kg reflected to the wheels'
radius r = 22.5 mm (the body's angle is the locomotive's travel over r, 1 rad = 22.5 mm). The
locomotive's sprung drawbar coupler is a compliance (`spring_damper` K) between the hub and
the body ``train``, the rake of five coaches (8 kg) reflected to the same radius. Running
forward is train.w > 0.

No circuitsim import: an independent simulator (the thirty-fifth of the benchmark), written
from the physics for netlists/motor_al_fast.yaml and motor_al_slow.yaml. It is evaluated at
the record's own sample times (``t_eval``), never on a grid that is then interpolated.
Everything rests at t = 0: no current, no speed, the locomotive and the rake at 0 and the
coupler unstrained; the track is level.

The worm gear is rigid (``gear`` G, ratio N = 28): the axles stand at th / N and turn at
w / N with the rotor; a torque T on them is T / N on the rotor. The coupler is a spring and a
damper on the twist th / N - thc between the axles and the rake (``spring_damper`` K), its
torque on the rake

    Tk = Ks (th / N - thc) + Ds (w / N - wc).

The rake meets three declared loads: its axles' plain bushes (a viscous drag Bt wc,
``damper``); the wheels' rolling resistance (a dry friction Tt tanh(wc / 0.01),
``friction``, w_brk 0.1); and the carbon skates of the coaches' lighting pickups sliding on
the rails, a soft dry drag Cp tanh(wc / wp), wp = 2 rad/s (``btorque`` Skates).

State y = [i, w, th, wc, thc] (+ the flywheel's own speed wf for ``slip``, + one Pade stage
per delayed probe, in this order):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wc, thc    the rake's speed and angle [rad/s, rad] (its travel over r; 0: where it starts)

Equations (Jr = Jm + Jh / N^2: the armature with its flywheel, and the axles with the
locomotive):

    L di/dt   = u(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor + (X_hub - Tk) / N
    Jt dwc/dt = Tk - Bt wc - Tt tanh(wc / 0.01) - Cp tanh(wc / wp) + X_train

Tm tanh(w / 0.01) is the brushes', the bearings' and the worm's dry friction (``friction``,
w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, train) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in the coupler K (Modelica's ElastoBacklash):
              no torque while |twist| < gap / 2, else Ks (twist -+ gap / 2) + Ds w_rel, the
              damping never pulling the sides together
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    grade     (Tg [N m], a1 [rad], a2 [rad], d [rad]): the rake climbs the ramp up to a
              level bridge: while it is on the ramp (its angle thc between a1 and a2) it
              receives -Tg s((thc - a1) / d) s((a2 - thc) / d), s(x) = 1 / (1 + exp(-x)),
              gravity along the ramp (the same whichever way it runs), the rake's length
              spreading each end over some d
    dirt      (Rd [ohm], x1 [rad], x2 [rad], dx [rad]): a dirty stretch of rail: while the
              locomotive's pickups run over it (the axles' angle th / N between x1 and x2,
              edges dx) their contact resistance rises, the loop taking
              Rd s((th / N - x1) / dx) s((x2 - th / N) / dx) i
    slip      (Jf [kg m^2], Tc [N m], ws [rad/s]): the brass flywheel (Jf, part of the
              declared Jm) loose on the motor's shaft, held by its set screw's friction only:
              the rotor carries Jm - Jf; the flywheel (its own speed wf) is dragged by
              Tc tanh((w - wf) / ws), the rotor receiving the opposite
    limit     (Ilim [A], Rc [ohm], e [A]): the power pack's current limiter: above Ilim its
              output folds back Rc per ampere, the loop taking
              Rc e softplus((|i|_s - Ilim) / e) tanh(i / 1 mA), |i|_s = sqrt(i^2 + (1 mA)^2),
              softplus(x) = ln(1 + exp(x))
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AL [SI] (motor_al_fast.yaml, motor_al_slow.yaml)
MOTOR_AL: dict[str, float] = {
    "R": 2.6, "L": 2.2e-3, "k": 0.035, "Jm": 4e-5, "bm": 3e-6, "Tm": 5e-3, "N": 28.0,
    "Jh": 2.4e-3, "Ks": 3.0, "Ds": 0.02, "Jt": 4e-3, "Bt": 4e-4, "Tt": 0.015, "Cp": 0.008,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: [rad/s] the skates' speed scale, tanh(wc / wp)
W_SKATES = 2.0
#: [m] the wheels' radius: 1 rad of the hub's or the rake's angle is this much travel
R_WHEEL = 0.0225
#: the fast regime's command [s, V] (motor_al_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.02, 0.0), (0.1, 18.0), (0.3, 18.0), (0.34, 0.0),
               (0.38, 0.0), (0.43, -12.0), (0.54, -12.0), (0.57, 0.0), (0.6, 0.0))
#: the slow regime's logged command [s, V] (motor_al_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.3, 0.0), (1.3, 10.0), (2.6, 10.0), (3.0, 18.0), (4.6, 18.0),
               (5.2, 6.0), (5.6, 6.0), (5.9, 0.0), (6.2, 0.0), (6.8, -9.0), (7.6, -9.0),
               (7.8, 0.0), (8.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.6), "slow": (250.0, 8.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "train")
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


def logistic(x: float) -> float:
    """1 / (1 + exp(-x)), without overflow."""
    if x >= 0.0:
        return 1.0 / (1.0 + math.exp(-x))
    e = math.exp(x)
    return e / (1.0 + e)


def softplus(x: float) -> float:
    """ln(1 + exp(x)), without overflow."""
    return x + math.log1p(math.exp(-x)) if x > 0.0 else math.log1p(math.exp(x))


# ---------------------------------------------------------------------- the model

class Locomotive:
    """Right-hand side of motor AL with one set of effects ``fx`` [SI]; ``ramp`` holds the
    command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.ratio = p["N"]
        j_fly = float(fx["slip"][0]) if "slip" in fx else 0.0
        self.j_rotor = p["Jm"] - j_fly + p["Jh"] / self.ratio ** 2
        #: index of the flywheel's speed (None without ``slip``)
        self.fly = 5 if "slip" in fx else None
        first = 5 + (self.fly is not None)
        #: (probe, tau [s], index of its Pade state)
        self.delays: list[tuple[str, float, int]] = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.delays.append((probe, float(s["delay"]), first + len(self.delays)))
        self.size = first + len(self.delays)
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
        """The power pack's output [V] within the current segment."""
        t0, u0, slope = self.ramp
        return u0 + slope * (t - t0)

    def resistance(self, t: float, th: float) -> float:
        """The loop's resistance [ohm] at the time ``t`` [s] and the rotor's angle ``th``
        [rad]: the armature (drifting or warming), a resistance in series or in the source,
        and the pickups on a dirty stretch of rail."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        if "dirt" in fx:
            rd, x1, x2, dx = fx["dirt"]
            x = th / self.ratio
            r += rd * logistic((x - x1) / dx) * logistic((x2 - x) / dx)
        return r + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)

    def loop_voltage(self, t: float, i: float, w: float, th: float) -> float:
        """The voltage [V] the loop takes at ``t`` [s] besides the inductance's and the
        declared EMF's, at the current ``i`` [A], the rotor's speed ``w`` [rad/s] and angle
        ``th`` [rad]."""
        fx = self.fx
        v = self.resistance(t, th) * i
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SWITCH)
        for order, a, b in fx.get("emf", ()):
            v += w * (a * math.sin(order * th) + b * math.cos(order * th))
        if "limit" in fx:
            ilim, rc, e = fx["limit"]
            mag = math.sqrt(i * i + I_SWITCH ** 2)
            v += rc * e * softplus((mag - ilim) / e) * math.tanh(i / I_SWITCH)
        return v

    def inductance(self, i: float) -> float:
        """The differential inductance [H] at the current ``i`` [A]."""
        ell = self.p["L"]
        if "lsat" in self.fx:
            ipar, ratio = self.fx["lsat"]
            ell *= ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2)
        return ell

    def coupler(self, twist: float, wrel: float) -> float:
        """The coupler's torque [N m] on the rake at the ``twist`` [rad] and the relative
        speed ``wrel`` [rad/s] (the axles' minus the rake's), with a play if ``gap``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        if "gap" not in self.fx:
            return ks * twist + ds * wrel
        half = 0.5 * self.fx["gap"]
        if abs(twist) <= half:
            return 0.0
        edge = half if twist > 0.0 else -half
        push = ks * (twist - edge) + ds * wrel
        return max(push, 0.0) if twist > 0.0 else min(push, 0.0)

    def train_load(self, thc: float) -> float:
        """The torque [N m] the outside effects' laws give the rake at its angle ``thc``
        [rad] (0 when none)."""
        if "grade" not in self.fx:
            return 0.0
        tg, a1, a2, d = self.fx["grade"]
        return -tg * logistic((thc - a1) / d) * logistic((a2 - thc) / d)

    def __call__(self, t: float, y: np.ndarray) -> list[float]:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n = self.p, self.ratio
        i, w, th, wc, thc = (float(v) for v in y[:5])
        di = (self.command(t) - self.loop_voltage(t, i, w, th) - p["k"] * w) \
            / self.inductance(i)
        tk = self.coupler(th / n - thc, w / n - wc)
        torque = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  + self.body_torque("rotor", w, th)
                  + (self.body_torque("hub", w / n, th / n) - tk) / n)
        extra = []
        if self.fly is not None:
            j_fly, tc, ws = self.fx["slip"]
            drag = tc * math.tanh((w - float(y[self.fly])) / ws)
            torque -= drag
            extra.append(drag / j_fly)
        dwc = (tk - p["Bt"] * wc - p["Tt"] * math.tanh(wc / W_SWITCH)
               - p["Cp"] * math.tanh(wc / W_SKATES)
               + self.body_torque("train", wc, thc) + self.train_load(thc)) / p["Jt"]
        seen = {"current": i, "speed": w, "load_speed": wc}
        pade = [2.0 * (seen[probe] - float(y[k])) / tau for probe, tau, k in self.delays]
        return [di, torque / self.j_rotor, w, dwc, wc, *extra, *pade]


# ---------------------------------------------------------------------- integration

def _piece(model: Locomotive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AL, {a:g}-{b:g} s: {why}")


def integrate(model: Locomotive, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor AL at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A], speed [rad/s] (an encoder on the motor's flywheel end), and in
    the slow regime load_speed [rad/s] (the rake, from an axle sensor under the last coach,
    as rad/s of the 45 mm wheels), plus the command ``u`` [V]. ``states``: add the angles
    [rad] and the coupler's torque [N m]."""
    fx = dict(fx or {})
    p = {**MOTOR_AL, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = Locomotive(fx, p)
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
        out.update(rotor_angle=y[2], hub_angle=y[2] / p["N"], train_angle=y[4],
                   train_speed=y[3],
                   coupler_torque=p["Ks"] * twist + p["Ds"] * (y[1] / p["N"] - y[3]))
        if model.fly is not None:
            out["flywheel_speed"] = y[model.fly]
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
