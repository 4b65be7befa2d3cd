"""Motor AS of the diagnosis benchmark: a hand-written scipy model of a 48 V permanent-magnet
brushed DC motor (a 4-pole, 16-slot armature in a ferrite-magnet can, about 150 W) turning the
OPEN-ARRAY ANTENNA of a MARINE RADAR SCANNER (a 4 ft slotted-waveguide array on its pedestal)
on a service workshop's bench. The motor's pinion drives a two-stage spur train lumped as one
rigid 60:1 reduction (`gear` G, declared rigid and lossless); the body ``hub`` is the
pedestal's output shaft with the final gear, the rotary joint's rotor and the turntable
flange. The array's mounting bracket and its long fibreglass radiator, bending in its plane
of rotation, are the compliance, a `spring_damper` K between the hub and the body ``array``
(the array: its radiator, the waveguide and the end caps). The array turns at the hub's speed
on average (1:1), its angle its own. Clockwise (seen from above, the scanner's normal
direction) is array.w > 0; the bench's test program also runs it backwards.

No circuitsim import: an independent simulator (the forty-second of the benchmark), written
from the physics for netlists/motor_as_fast.yaml and motor_as_slow.yaml. It is evaluated at
the record's own sample times (``t_eval``), never on a grid that is then interpolated.
Everything rests at t = 0: no current, no speed, the hub and the array at 0 and the bracket
unloaded; an outside effect's own state at rest too.

The spur train is rigid (``gear`` G, ratio N = 60): the hub stands at th / N and turns at
w / N with the rotor; a torque T on it is T / N on the rotor. The bracket is a spring and a
damper on the twist th / N - tha between the hub and the array (``spring_damper`` K), its
torque on the array

    Tk = Ks (th / N - tha) + Ds (w / N - wa).

The array meets three declared loads: the pedestal's main bearing grease (a viscous drag
Ba wa, ``damper``), the pedestal's lip seal with the rotary joint's choke (a dry friction
Ta tanh(wa / 0.01), ``friction``, w_brk 0.1) and the radiator's air drag, a quadratic drag
Cw wa sqrt(wa^2 + (1 rad/s)^2) (``btorque`` Wind).

State y = [i, w, th, wa, tha] (+ the seal's run-in distance s for ``runin``, + the coupling
capacitor's lag q for ``accouple``, + one Pade stage per delayed probe, in this order):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wa, tha    the array's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the armature with its pinion and the first stage, and the
hub):

    L di/dt   = u(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor + (X_hub - Tk) / N
    Ja dwa/dt = Tk - Ba wa - Ta tanh(wa / 0.01) - Cw wa sqrt(wa^2 + 1) + X_array

Tm tanh(w / 0.01) is the brushes', the motor's ball bearings' and the spur train's dry
friction (``friction``, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, array) receives
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

    runin     (T1 [N m], s0 [rad]): the pedestal's new lip seal, not yet run in: the array
              takes an extra dry friction T1 exp(-s / s0) tanh(wa / 0.01), s the angle the
              array has travelled since the start (ds/dt = sqrt(wa^2 + (0.01 rad/s)^2),
              s = 0 at rest): it fades with the turns the seal has made, not with the time
    pickup    (Ip [A], phase [rad]): the open-loop Hall current sensor sits next to the
              rotor's diametric encoder magnet and reads its field: the current reads
              i + Ip sin(th + phase), th the rotor's angle, at any speed and current; the
              motor itself is not touched
    accouple  (tau [s],): the logger's current input is AC-coupled (a series capacitor):
              it reads i - q, dq/dt = (i - q) / tau, q = 0 at rest; the motor itself is not
              touched
    governor  (w0 [rad/s], Kg [V s/rad], eps [rad/s]): the driver board's speed limiter
              ('harbour mode'): its output falls by Kg p(w - w0) below the set value,
              p(x) = (x + sqrt(x^2 + eps^2)) / 2 (a smooth ramp from 0 above w0), forward
              only
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AS [SI] (motor_as_fast.yaml, motor_as_slow.yaml)
MOTOR_AS: dict[str, float] = {
    "R": 1.6, "L": 2.4e-3, "k": 0.14, "Jm": 1.5e-4, "bm": 2e-5, "Tm": 0.012,
    "N": 60.0, "Jh": 0.03, "Ks": 500.0, "Ds": 1.0, "Ja": 0.6, "Ba": 0.02, "Ta": 0.3,
    "Cw": 0.04,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: [rad/s] the air drag: w sqrt(w^2 + W_WIND^2)
W_WIND = 1.0
#: the fast regime's command [s, V] (motor_as_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.02, 0.0), (0.2, 36.0), (0.3, 36.0), (0.32, 20.0),
               (0.38, 20.0), (0.46, -30.0), (0.53, -30.0), (0.55, 0.0), (0.6, 0.0))
#: the slow regime's logged command [s, V] (motor_as_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.3, 0.0), (1.3, 16.0), (3.0, 16.0), (3.4, 32.0), (5.0, 32.0),
               (5.4, 44.0), (7.0, 44.0), (7.5, 0.0), (7.9, 0.0), (8.3, -30.0), (9.3, -30.0),
               (9.6, 0.0), (10.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.6), "slow": (250.0, 10.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "array")
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

class ScannerDrive:
    """Right-hand side of motor AS with one set of effects ``fx`` [SI]; ``ramp`` holds the
    command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.ratio = p["N"]
        self.j_rotor = p["Jm"] + p["Jh"] / self.ratio ** 2
        size = 5
        #: index of the seal's run-in distance s (None without ``runin``)
        self.runin = None
        if "runin" in fx:
            self.runin, size = size, size + 1
        #: index of the coupling capacitor's lag q (None without ``accouple``)
        self.accouple = None
        if "accouple" in fx:
            self.accouple, size = size, size + 1
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
        """The supply's (or the driver's) set output [V] within the current segment."""
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
        EMF's, at the current ``i`` [A], the rotor's speed ``w`` [rad/s] and angle ``th``
        [rad]."""
        fx = self.fx
        v = self.resistance(t) * i
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SWITCH)
        if "governor" in fx:
            w0, kg, eps = fx["governor"]
            x = w - w0
            v += kg * 0.5 * (x + _smooth_abs(x, eps))
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
        """The bracket's elastic and damping torque [N m] on the array at the ``twist``
        [rad] and the relative speed ``wrel`` [rad/s] (the hub's minus the array's), with a
        play if ``gap``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        if "gap" not in self.fx:
            return ks * twist + ds * wrel
        half = 0.5 * self.fx["gap"]
        if abs(twist) <= half:
            return 0.0
        edge = half if twist > 0.0 else -half
        push = ks * (twist - edge) + ds * wrel
        return max(push, 0.0) if twist > 0.0 else min(push, 0.0)

    def array_load(self, wa: float, travelled: float) -> float:
        """The array's declared air drag [N m] (against its motion), with the unworn seal's
        friction if ``runin`` (``travelled``: the angle s [rad])."""
        drag = self.p["Cw"] * wa * _smooth_abs(wa, W_WIND)
        if "runin" in self.fx:
            t1, s0 = self.fx["runin"]
            drag += t1 * math.exp(-travelled / s0) * math.tanh(wa / W_SWITCH)
        return drag

    def __call__(self, t: float, y: np.ndarray) -> list[float]:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n, fx = self.p, self.ratio, self.fx
        i, w, th, wa, tha = (float(v) for v in y[:5])
        u = self.command(t)
        extra: list[float] = []
        travelled = 0.0
        if self.runin is not None:
            travelled = float(y[self.runin])
            extra.append(_smooth_abs(wa, W_SWITCH))
        if self.accouple is not None:
            tau, = fx["accouple"]
            extra.append((i - float(y[self.accouple])) / tau)
        di = (u - self.loop_voltage(t, i, w, th) - p["k"] * w) / self.inductance(i)
        wrel = w / n - wa
        tk = self.band(th / n - tha, wrel)
        on_hub = self.body_torque("hub", w / n, th / n)
        torque = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  + self.body_torque("rotor", w, th) + (on_hub - tk) / n)
        on_array = (tk - p["Ba"] * wa - p["Ta"] * math.tanh(wa / W_SWITCH)
                    - self.array_load(wa, travelled) + self.body_torque("array", wa, tha))
        seen = {"current": i, "speed": w, "load_speed": wa}
        pade = [2.0 * (seen[probe] - float(y[k])) / tau for probe, tau, k in self.delays]
        return [di, torque / self.j_rotor, w, on_array / p["Ja"], wa, *extra, *pade]


# ---------------------------------------------------------------------- integration

def _piece(model: ScannerDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AS, {a:g}-{b:g} s: {why}")


def integrate(model: ScannerDrive, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor AS at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A] (the bench's shunt in the supply's lead, or the scanner driver's
    current sensor; with ``pickup`` the sensor reads the encoder magnet's field too, with
    ``accouple`` through a coupling capacitor), speed [rad/s] (the motor's magnetic encoder,
    rad/s at the rotor), and in the slow regime load_speed [rad/s] (the array, from the
    pedestal's bearing encoder), plus the command ``u`` [V]. ``states``: add the bodies'
    speeds [rad/s] and angles [rad], the bracket's torque [N m] and the outside effects'
    states."""
    fx = dict(fx or {})
    p = {**MOTOR_AS, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = ScannerDrive(fx, p)
    y = integrate(model, t, bp, MAX_STEP[regime])
    u = np.interp(t, bp[:, 0], bp[:, 1])
    true = {"current": y[0], "speed": y[1], "load_speed": y[3]}
    for probe, _, k in model.delays:
        true[probe] = 2.0 * y[k] - true[probe]
    if "pickup" in fx:
        ip, phase = fx["pickup"]
        true["current"] = y[0] + float(ip) * np.sin(y[2] + float(phase))
    if model.accouple is not None:
        true["current"] = y[0] - y[model.accouple]
    out = {probe: np.array(true[probe]) for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = u
    if states:
        twist, wrel = y[2] / p["N"] - y[4], y[1] / p["N"] - y[3]
        torque = np.array([model.band(a, b) for a, b in zip(twist, wrel, strict=True)])
        out.update(rotor_angle=y[2], hub_angle=y[2] / p["N"], hub_speed=y[1] / p["N"],
                   array_angle=y[4], array_speed=y[3], armature_current=y[0],
                   bracket_twist=twist, bracket_torque=torque)
        if model.runin is not None:
            out.update(seal_travel=y[model.runin])
        if model.accouple is not None:
            out.update(coupling_lag=y[model.accouple])
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
