"""Motor BD of the diagnosis benchmark: a hand-written scipy model of a 48 V permanent-magnet
brushed DC motor (a 4-pole, 10-slot ferrite motor) driving a GLASSBLOWER'S LATHE (a bench
glass-working lathe for scientific glassware, whose headstock and tailstock chucks turn in
step from one line shaft under the bed) on the maker's test stand: the motor drives a rigid
two-stage helical gearbox (16:1, `gear` G, declared rigid and lossless) to the headstock's
hollow spindle; the body ``head`` is the headstock's spindle with its (empty) scroll chuck and
the line shaft's driving gear pair, turning in the spindle's preloaded taper-roller bearings.
The 14 mm steel line shaft runs 1.1 m under the bed to the tailstock, whose spindle it drives
through a sliding gear keyed to the shaft: the shaft's twist is a spring and a damper,
`spring_damper` K, between the head and the body ``tail`` (the tailstock's spindle, its
scroll chuck and the glass tube it holds, the tailstock gear reflected 1:1). Forward is
tail.w > 0 (the glassworker's "towards"); the tail turns with the head on average (1:1).

No circuitsim import, and no other set's simulator: an independent simulator, written from the
physics for netlists/motor_bd_fast.yaml and motor_bd_slow.yaml. It is evaluated at the
record's own sample times (``t_eval``), never on a grid that is then interpolated. Everything
rests at t = 0: no current, no speed, the head and the tail at 0 and the shaft untwisted.

The gearbox is rigid (``gear`` G, ratio N = 16): the head stands at th / N and turns at w / N
with the rotor; a torque T on it is T / N on the rotor. The line shaft is a spring and a
damper on the twist th / N - tht between the head and the tail (``spring_damper`` K), its
torque on the tail

    Tk = Ks (th / N - tht) + Ds (w / N - wt).

The headstock spindle's preloaded bearings and their seals give the head a dry friction
(``friction`` Fh, Th tanh(wh / 0.01), w_brk 0.1). The tailstock spindle's bearings and the
tailstock gear's sliding key give the tail a dry friction (``friction`` Ft, Tt tanh(wt / 0.01),
w_brk 0.1) and the grease of its bearings and of its gear a viscous drag (``damper`` Bt).

State y = [i, w, th, wt, tht] (+ the outside effects' states -- the shear pin's intact
fraction, the tachogenerator's speed and its coupling's twist --, + one Pade stage per delayed
probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wt, tht    the tail's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the armature with the gearbox's input, and the head):

    L di/dt   = v(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor
                + (X_head - Th tanh((w / N) / 0.01) - Tk) / N
    Jt dwt/dt = Tk - Tt tanh(wt / 0.01) - Bt wt + X_tail

v(t) the stand's four-quadrant supply's output u(t) (the command, linear between its
breakpoints), Tm tanh(w / 0.01) the brushes' and the motor's bearings' dry friction
(``friction`` Fr, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, head, tail) receives
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

    bridge    (c0 [N m s/rad], cinf [N m s/rad], tau [s]): a glass tube held in BOTH chucks,
              its middle softening in the burner's flame from t = 0: the hot zone is a
              viscous bridge across the chucks, in parallel with the line shaft, passing
              c(t) (wh - wt) from the head to the tail, its coefficient (the glass's
              viscosity) falling as the zone heats, log c(t) = log cinf + (log c0 - log cinf)
              exp(-t / tau)
    tacho     (Jg [kg m^2], Kc [N m/rad], Dc [N m s/rad]): the tachogenerator's armature
              (Jg, counted in the declared Jm) is coupled to the rotor's rear shaft end by a
              split elastomer spider, a spring and a damper: Jg dwg/dt = Kc q + Dc (w - wg),
              dq/dt = w - wg (q the spider's twist, 0 at rest), the rotor (Jm - Jg) taking
              -(Kc q + Dc (w - wg)); the speed reads the tachogenerator's wg
    slide     (L0 [m], dL [m], tm [s], ws [s]): the tailstock is cranked along the bed while
              the lathe runs, its sliding gear carried along the line shaft: the shaft's
              twisting span (from the headstock's driving gear to the tailstock's gear) is
              L(t) = L0 + dL sig((t - tm) / ws), sig(x) = 1 / (1 + exp(-x)), and the shaft's
              stiffness and damping both scale with L0 / L(t) (the twist stays with the span
              it is in)
    pin       (Ts [N m], dT [N m], tau [s]): the tailstock gear is driven off its sliding key
              through a soft shear pin: the line shaft's torque reaches the tail as s Tk, s
              the pin's intact fraction (1 at the start), which shears away once |Tk|
              exceeds Ts, ds/dt = -s sig((|Tk| - Ts) / dT) / tau, and never comes back (Tk
              the shaft's torque from its twist th / N - tht, which the head takes as well)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor BD [SI] (motor_bd_fast.yaml, motor_bd_slow.yaml): what the
#: diagnosis starts from; a record's true values differ in the parameters it frees
MOTOR_BD: dict[str, float] = {
    "R": 0.85, "L": 2.4e-3, "k": 0.145, "Jm": 6.5e-4, "bm": 1.2e-4, "Tm": 0.06,
    "N": 16.0, "Jh": 0.09, "Th": 0.9, "Ks": 190.0, "Ds": 0.22, "Jt": 0.16,
    "Tt": 0.7, "Bt": 0.08,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_bd_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.13, 48.0), (0.22, 48.0), (0.25, 24.0),
               (0.30, 24.0), (0.38, -36.0), (0.45, -36.0), (0.47, 0.0), (0.50, 0.0))
#: the slow regime's logged command [s, V] (motor_bd_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.5, 0.0), (2.0, 24.0), (5.0, 24.0), (6.0, 48.0), (9.0, 48.0),
               (9.8, 0.0), (10.6, 0.0), (11.5, -36.0), (15.2, -36.0), (16.0, 0.0),
               (18.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.5), "slow": (80.0, 18.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "head", "tail")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a fifth of the
#: mean interval in the slow one
MAX_STEP = {"fast": 1.0 / 20e3, "slow": 2.5e-3}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.array(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def sig(x: float) -> float:
    """The logistic 1 / (1 + exp(-x)), without overflow."""
    if x >= 0.0:
        return 1.0 / (1.0 + math.exp(-x))
    e = math.exp(x)
    return e / (1.0 + e)


# ---------------------------------------------------------------------- the model

class GlassLathe:
    """Right-hand side of motor BD with the effects ``fx`` and the parameters ``p`` [SI];
    ``seg`` holds the command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.fx, self.p = fx, p
        self.n = p["N"]
        size = 5
        #: indices of the shear pin's intact fraction and of the tachogenerator's speed and
        #: its coupling's twist (None when off)
        self.i_pin = self.i_tacho = None
        if "pin" in fx:
            self.i_pin, size = size, size + 1
        if "tacho" in fx:
            self.i_tacho, size = size, size + 2
        #: (probe, tau [s], index of its Pade state)
        self.delays: list[tuple[str, float, int]] = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.delays.append((probe, float(s["delay"]), size))
                size += 1
        self.size = size
        self.extra = {body: {key: fx[key][body] for key in
                             ("visc", "coul", "offset", "stribeck", "cog")
                             if fx.get(key, {}).get(body)} for body in BODIES}
        #: Jr: the rotor with the head at the rotor's scale (without the tachogenerator's
        #: armature when ``tacho`` couples it softly: Jm declares it with the rotor)
        self.jr = p["Jm"] + p["Jh"] / self.n ** 2 - (fx["tacho"][0] if "tacho" in fx else 0.0)
        self.seg = (0.0, 0.0, 0.0)

    def initial(self) -> np.ndarray:
        """The state at rest at t = 0 (the shear pin intact)."""
        y = np.zeros(self.size)
        if self.i_pin is not None:
            y[self.i_pin] = 1.0
        return y

    def command(self, t: float) -> float:
        """The supply's output [V] within the current segment of the command."""
        t0, u0, slope = self.seg
        return u0 + slope * (t - t0)

    def body_torque(self, body: str, w: float, angle: float) -> float:
        """The catalog's torque effects on ``body`` [N m] at its speed ``w`` [rad/s] and its
        angle [rad]."""
        e = self.extra[body]
        if not e:
            return 0.0
        sw = math.tanh(w / W_SWITCH)
        tq = e.get("offset", 0.0) - e.get("visc", 0.0) * w - e.get("coul", 0.0) * sw
        if "stribeck" in e:
            s, ws = e["stribeck"]
            tq -= s * math.exp(-(w / ws) ** 2) * sw
        for order, a, b in e.get("cog", ()):
            tq += a * math.sin(order * angle) + b * math.cos(order * angle)
        return tq

    def loop(self, t: float, i: float, th: float, w: float) -> float:
        """The loop's voltage [V] besides the inductance's and the EMF's."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        r += fx.get("Rser", 0.0) + fx.get("Rs", 0.0)
        v = r * i
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SWITCH)
        for order, a, b in fx.get("emf", ()):
            v += w * (a * math.sin(order * th) + b * math.cos(order * th))
        return v

    def inductance(self, i: float) -> float:
        """The differential inductance [H] at the current ``i`` [A]."""
        if "lsat" not in self.fx:
            return self.p["L"]
        ipar, ratio = self.fx["lsat"]
        return self.p["L"] * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))

    def span(self, t: float) -> float:
        """The line shaft's stiffness (and damping) over its declared one [1] at the time
        ``t`` [s]: L0 / L(t) with ``slide``, else 1."""
        if "slide" not in self.fx:
            return 1.0
        l0, dl, tm, ws = self.fx["slide"]
        return l0 / (l0 + dl * sig((t - tm) / ws))

    def bridge(self, t: float) -> float:
        """The softening glass bridge's viscous coefficient [N m s/rad] at the time ``t``
        [s] (0 without ``bridge``)."""
        if "bridge" not in self.fx:
            return 0.0
        c0, cinf, tau = self.fx["bridge"]
        return cinf * (c0 / cinf) ** math.exp(-t / tau)

    def shaft(self, t: float, x: float, v: float) -> float:
        """The line shaft's torque on the tail [N m] at the twist ``x`` [rad] and the twist
        rate ``v`` [rad/s] (the head's minus the tail's), with a play if ``gap`` (nothing
        inside the play, the damping never pulling the sides together), and the glass
        bridge's torque beside it."""
        f = self.span(t)
        ks, ds = self.p["Ks"] * f, self.p["Ds"] * f
        gap = self.fx.get("gap")
        if not gap:
            tq = ks * x + ds * v
        else:
            half = 0.5 * gap
            if -half <= x <= half:
                tq = 0.0
            elif x > 0.0:
                tq = max(ks * (x - half) + ds * v, 0.0)
            else:
                tq = min(ks * (x + half) + ds * v, 0.0)
        return tq + self.bridge(t) * v

    def __call__(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n, fx = self.p, self.n, self.fx
        i, w, th, wt, tht = y[0], y[1], y[2], y[3], y[4]
        u = self.command(t)
        dy = np.empty(self.size)
        k = p["k"]
        dy[0] = (u - self.loop(t, i, th, w) - k * w) / self.inductance(i)
        motor = (k * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                 + self.body_torque("rotor", w, th))
        tc = 0.0
        if self.i_tacho is not None:
            _, kc, dc = fx["tacho"]
            tc = kc * y[self.i_tacho + 1] + dc * (w - y[self.i_tacho])
            motor -= tc
        thh, wh = th / n, w / n
        tk = self.shaft(t, thh - tht, wh - wt)
        if self.i_pin is not None:
            ts, dt, tau = fx["pin"]
            dy[self.i_pin] = -y[self.i_pin] * sig((abs(tk) - ts) / dt) / tau
            tk *= y[self.i_pin]
        head = self.body_torque("head", wh, thh) - p["Th"] * math.tanh(wh / W_SWITCH)
        dy[1] = (motor + (head - tk) / n) / self.jr
        dy[2] = w
        tail = (tk - p["Tt"] * math.tanh(wt / W_SWITCH) - p["Bt"] * wt
                + self.body_torque("tail", wt, tht))
        dy[3] = tail / p["Jt"]
        dy[4] = wt
        if self.i_tacho is not None:
            dy[self.i_tacho] = tc / fx["tacho"][0]
            dy[self.i_tacho + 1] = w - y[self.i_tacho]
        if self.delays:
            seen = self.seen(y, np.array(u))
            for probe, tau, j in self.delays:
                dy[j] = 2.0 * (seen[probe] - y[j]) / tau
        return dy

    def seen(self, y: np.ndarray, u: np.ndarray) -> dict[str, Any]:
        """What each probe's sensor sees [A, rad/s] before its catalog effects, at the states
        ``y`` and the supply's output ``u`` [V]: the armature current, the rotor's speed (the
        tachogenerator's, with ``tacho``) and the tail's."""
        cur = y[0]
        speed = y[1] if self.i_tacho is None else y[self.i_tacho]
        return {"current": cur, "speed": speed, "load_speed": y[3]}


# ---------------------------------------------------------------------- integration

def _span(model: GlassLathe, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
          max_step: float) -> np.ndarray:
    """The states at ``t_out`` [s] from ``y0`` at ``a`` to ``b`` [s]: LSODA, Radau if LSODA
    fails."""
    why = ""
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), y0, method=method, t_eval=t_out, rtol=RTOL,
                        atol=ATOL, max_step=max_step)
        if not sol.success or not np.isfinite(sol.y).all():
            why = sol.message
            continue
        if sol.y.shape[1] == t_out.size:
            return sol.y
        why = "missing outputs"
    raise RuntimeError(f"motor BD, {a:g}-{b:g} s: {why}")


def integrate(model: GlassLathe, t: np.ndarray, bp: np.ndarray, max_step: float
              ) -> np.ndarray:
    """The states (n_states, t.size) at the increasing times ``t`` [s], from rest at 0, the
    integration restarted at every corner of the command ``bp`` [s, V]."""
    end = float(t[-1])
    corners = sorted({0.0, end, *(float(c) for c in bp[:, 0] if 0.0 < c < end)})
    out = np.empty((model.size, t.size))
    y0 = model.initial()
    for a, b in itertools.pairwise(corners):
        mid = 0.5 * (a + b)
        j = int(np.searchsorted(bp[:, 0], mid)) - 1
        slope = float(bp[j + 1, 1] - bp[j, 1]) / float(bp[j + 1, 0] - bp[j, 0])
        model.seg = (a, float(np.interp(a, bp[:, 0], bp[:, 1])), slope)
        last = b == end
        inside = (t >= a) & ((t <= b) if last else (t < b))
        t_out = t[inside] if last else np.append(t[inside], b)
        ys = _span(model, a, b, y0, t_out, max_step)
        idx = np.flatnonzero(inside)
        out[:, idx] = ys[:, :idx.size]
        y0 = ys[:, -1].copy()
    return out


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor BD at the times ``t`` [s] (default: the nominal grid),
    from rest, with the parameters ``p`` over the declared ones (and ``fx["p"]`` over
    those): current [A] (the stand's shunt in the armature's lead), speed [rad/s] (the
    stand's DC tachogenerator on the motor's rear shaft end, rad/s at the rotor), and in the
    slow regime load_speed [rad/s] (the tail's speed, from the stand's encoder on the
    tailstock spindle's rear end, signed), plus the command ``u`` [V]. ``states``: add the
    bodies' speeds [rad/s] and angles [rad], the line shaft's twist [rad] and torque [N m],
    and the outside effects' states."""
    fx = dict(fx or {})
    p = {**MOTOR_BD, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = GlassLathe(fx, p)
    y = integrate(model, t, bp, MAX_STEP[regime])
    u = np.interp(t, bp[:, 0], bp[:, 1])
    seen = model.seen(y, u)
    for probe, _, j in model.delays:
        seen[probe] = 2.0 * y[j] - seen[probe]
    out = {probe: np.array(seen[probe], dtype=float) for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = u
    if states:
        thh = y[2] / p["N"]
        twist = thh - y[4]
        rate = y[1] / p["N"] - y[3]
        out.update(rotor_angle=y[2], head_angle=thh, head_speed=y[1] / p["N"],
                   tail_angle=y[4], tail_speed=y[3], armature_current=y[0],
                   shaft_twist=twist,
                   shaft_torque=np.array([model.shaft(float(a), float(b), float(c)) for
                                          a, b, c in zip(t, twist, rate, strict=True)]))
        if model.i_pin is not None:
            out["pin_intact"] = y[model.i_pin]
            out["shaft_torque"] = out["shaft_torque"] * y[model.i_pin]
        if model.i_tacho is not None:
            out.update(tacho_speed=y[model.i_tacho], coupling_twist=y[model.i_tacho + 1])
    return out


# ---------------------------------------------------------------------- noise

def gauss_markov(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float
                 ) -> np.ndarray:
    """A stationary first-order Gauss-Markov process [probe unit] of standard deviation
    ``sigma`` and correlation time ``tau`` [s], exact at the (uneven) times ``t``."""
    rho = np.exp(-np.diff(t) / tau)
    e = rng.standard_normal(t.size) * sigma
    e[1:] *= np.sqrt(1.0 - rho ** 2)
    x = np.empty(t.size)
    x[0] = e[0]
    for j in range(1, t.size):
        x[j] = rho[j - 1] * x[j - 1] + e[j]
    return x


def flicker(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma`` at the times ``t`` [s]: white
    noise on an even grid spanning the record, its amplitude spectrum shaped by 1/sqrt(f)
    (no mean), read at ``t`` linearly."""
    n = t.size
    even = np.linspace(float(t[0]), float(t[-1]), n)
    f = np.fft.rfftfreq(n, float(even[1] - even[0]))
    spec = np.fft.rfft(rng.standard_normal(n))
    spec[0] = 0.0
    spec[1:] *= np.sqrt(f[1] / f[1:])
    x = np.interp(t, even, np.fft.irfft(spec, n))
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
        out += gauss_markov(rng, t, sigma, -float(np.mean(np.diff(t))) / math.log(phi))
    if spec.get("pink"):
        out += flicker(rng, t, spec["pink"])
    step = spec.get("quant")
    return np.round(out / step) * step if step else out
