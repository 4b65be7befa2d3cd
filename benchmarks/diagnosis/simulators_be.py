"""Motor BE of the diagnosis benchmark: a hand-written scipy model of a 36 V permanent-magnet
brushed DC motor (a 2-pole, 12-slot ferrite motor) driving the GRAVURE ROLL of a pilot
roll-to-roll coater (a lab-scale reverse-gravure coater laying battery-electrode slurry on
foil) on the maker's test stand: the motor drives a rigid 18:1 reduction (a 3:1 HTD timing
belt and a 6:1 spur pair on the drive-side frame, `gear` G, declared rigid and lossless) to
the body ``hub`` (the reduction's output shaft with its spur wheel and the drive shaft's
coupling hub, turning in the drive-side frame's bearings and their seals). A 12 mm steel drive
shaft 0.8 m long runs across the coater's frame to the operator side, through a double
disc-pack coupling to the gravure roll's journal: the shaft's twist (and the disc packs') is a
spring and a damper, `spring_damper` K, between the hub and the body ``roll`` (the chromed
100 mm gravure roll and its journals, 1:1). The roll dips into the slurry pan and is wiped
by the doctor blade: its journals' bearings and the blade give it a dry friction, the
slurry's shear in the pan a viscous drag. Forward is roll.w > 0 (the coating direction).

No circuitsim import, and no other set's simulator: an independent simulator, written from the
physics for netlists/motor_be_fast.yaml and motor_be_slow.yaml. It is evaluated at the
record's own sample times (``t_eval``), never on a grid that is then interpolated. Everything
rests at t = 0: no current, no speed, the hub and the roll at 0 and the shaft untwisted.

The reduction is rigid (``gear`` G, ratio N = 18): the hub stands at th / N and turns at
w / N with the rotor; a torque T on it is T / N on the rotor. The drive shaft is a spring and
a damper on the twist th / N - thg between the hub and the roll (``spring_damper`` K), its
torque on the roll

    Tk = Ks (th / N - thg) + Ds (w / N - wg).

The drive-side bearings and seals give the hub a dry friction (``friction`` Fh, Th tanh(wh /
0.01), w_brk 0.1). The roll's journal bearings and the doctor blade give the roll a dry
friction (``friction`` Fg, Tg tanh(wg / 0.01), w_brk 0.1), the slurry in the pan a viscous
drag (``damper`` Bg).

State y = [i, w, th, wg, thg] (+ the outside effects' states -- the nip's engagement and the
nip roller's speed, the slurry's structure, the current converter's mean square --, + one Pade
stage per delayed probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wg, thg    the roll's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the armature with the reduction's input, and the hub):

    L di/dt   = v(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor
                + (X_hub - Th tanh((w / N) / 0.01) - Tk) / N
    Jg dwg/dt = Tk - Tg tanh(wg / 0.01) - Bg wg + X_roll

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
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, roll) receives
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

    nip       (w_on [rad/s], dw [rad/s], tau [s], Tmax [N m], v0 [rad/s], Ji [kg m^2],
              bi [N m s/rad], Tr [N m]): the coater's rubber nip roller, pressed onto the
              roll by pneumatic cylinders that the coater's controller opens once the roll
              runs faster than w_on: the engagement s (0 at the start) follows
              ds/dt = (sig((|wg| - w_on) / dw) - s) / tau, sig(x) = 1 / (1 + exp(-x)); the nip
              roller (Ji, its speed wi at the roll's surface over the roll's radius, at rest
              at the start, its bearings' drag bi wi) is driven by traction
              Tc = s Tmax tanh((wg - wi) / v0), which the roll gives up; the pressed rubber's
              rolling resistance s Tr tanh(wg / 0.01) acts against the roll
    fret      (Tf [N m], v0 [rad/s]): the coupling's disc packs, their bolts loosened, fret on
              each other: a dry friction Tf tanh(v / v0) on the twist rate v = w / N - wg,
              in parallel with the shaft's spring and damper (passed from the hub to the roll)
    thix      (db [N m s/rad], t_rec [s], theta_b [rad]): the slurry is thixotropic: its
              structure lam (1 at the start: the slurry stood overnight) breaks down with the
              roll's turning and rebuilds at rest, dlam/dt = (1 - lam) / t_rec -
              lam |wg| / theta_b; the slurry's drag is (Bg + db lam) wg (Bg: the sheared
              slurry's, declared)
    rms       tau [s]: the current channel reads a true-RMS converter's output:
              sqrt(m), dm/dt = (i^2 - m) / tau (m the mean square, 0 at the start): never
              negative
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor BE [SI] (motor_be_fast.yaml, motor_be_slow.yaml): what the
#: diagnosis starts from; a record's true values differ in the parameters it frees
MOTOR_BE: dict[str, float] = {
    "R": 0.48, "L": 1.5e-3, "k": 0.098, "Jm": 3.6e-4, "bm": 9e-5, "Tm": 0.04,
    "N": 18.0, "Jh": 0.011, "Th": 0.25, "Ks": 150.0, "Ds": 0.08, "Jg": 0.06,
    "Tg": 0.6, "Bg": 0.035,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_be_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.12, 36.0), (0.20, 36.0), (0.23, 15.0),
               (0.29, 15.0), (0.36, -24.0), (0.42, -24.0), (0.44, 0.0), (0.45, 0.0))
#: the slow regime's logged command [s, V] (motor_be_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.5, 0.0), (2.0, 12.0), (5.0, 12.0), (6.0, 36.0), (9.5, 36.0),
               (10.3, 0.0), (11.0, 0.0), (11.8, -18.0), (14.5, -18.0), (15.2, 0.0),
               (17.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.45), "slow": (100.0, 17.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "roll")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a fifth of the
#: mean interval in the slow one
MAX_STEP = {"fast": 1.0 / 25e3, "slow": 2e-3}


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

class GravureCoater:
    """Right-hand side of motor BE with the effects ``fx`` and the parameters ``p`` [SI];
    ``seg`` holds the command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.fx, self.p = fx, p
        self.n = p["N"]
        size = 5
        #: indices of the nip's engagement (its roller's speed next), of the slurry's
        #: structure and of the current converter's mean square (None when off)
        self.i_nip = self.i_thix = self.i_rms = None
        if "nip" in fx:
            self.i_nip, size = size, size + 2
        if "thix" in fx:
            self.i_thix, size = size, size + 1
        if "rms" in fx:
            self.i_rms, size = size, size + 1
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
        #: Jr: the rotor with the hub at the rotor's scale
        self.jr = p["Jm"] + p["Jh"] / self.n ** 2
        self.seg = (0.0, 0.0, 0.0)

    def initial(self) -> np.ndarray:
        """The state at rest at t = 0 (the slurry's structure whole)."""
        y = np.zeros(self.size)
        if self.i_thix is not None:
            y[self.i_thix] = 1.0
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

    def shaft(self, x: float, v: float) -> float:
        """The drive shaft's torque on the roll [N m] at the twist ``x`` [rad] and the twist
        rate ``v`` [rad/s] (the hub's minus the roll's), with a play if ``gap`` (nothing
        inside the play, the damping never pulling the sides together), and the fretting
        disc packs' dry friction beside it if ``fret``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
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
        if "fret" in self.fx:
            tf, v0 = self.fx["fret"]
            tq += tf * math.tanh(v / v0)
        return tq

    def __call__(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n, fx = self.p, self.n, self.fx
        i, w, th, wg, thg = y[0], y[1], y[2], y[3], y[4]
        u = self.command(t)
        dy = np.empty(self.size)
        k = p["k"]
        dy[0] = (u - self.loop(t, i, th, w) - k * w) / self.inductance(i)
        motor = (k * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                 + self.body_torque("rotor", w, th))
        thh, wh = th / n, w / n
        tk = self.shaft(thh - thg, wh - wg)
        hub = self.body_torque("hub", wh, thh) - p["Th"] * math.tanh(wh / W_SWITCH)
        dy[1] = (motor + (hub - tk) / n) / self.jr
        dy[2] = w
        sw = math.tanh(wg / W_SWITCH)
        roll = tk - p["Tg"] * sw - p["Bg"] * wg + self.body_torque("roll", wg, thg)
        if self.i_nip is not None:
            w_on, dw, tau, tmax, v0, ji, bi, tr = fx["nip"]
            s, wi = y[self.i_nip], y[self.i_nip + 1]
            tc = s * tmax * math.tanh((wg - wi) / v0)
            roll -= tc + s * tr * sw
            dy[self.i_nip] = (sig((abs(wg) - w_on) / dw) - s) / tau
            dy[self.i_nip + 1] = (tc - bi * wi) / ji
        if self.i_thix is not None:
            db, t_rec, theta_b = fx["thix"]
            lam = y[self.i_thix]
            roll -= db * lam * wg
            dy[self.i_thix] = (1.0 - lam) / t_rec - lam * abs(wg) / theta_b
        if self.i_rms is not None:
            dy[self.i_rms] = (i * i - y[self.i_rms]) / fx["rms"]
        dy[3] = roll / p["Jg"]
        dy[4] = wg
        if self.delays:
            seen = self.seen(y)
            for probe, tau, j in self.delays:
                dy[j] = 2.0 * (seen[probe] - y[j]) / tau
        return dy

    def seen(self, y: np.ndarray) -> dict[str, Any]:
        """What each probe's sensor sees [A, rad/s] before its catalog effects, at the states
        ``y``: the armature current (the true-RMS converter's output with ``rms``), the
        rotor's speed and the roll's."""
        cur = y[0] if self.i_rms is None else np.sqrt(np.maximum(y[self.i_rms], 0.0))
        return {"current": cur, "speed": y[1], "load_speed": y[3]}


# ---------------------------------------------------------------------- integration

def _span(model: GravureCoater, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor BE, {a:g}-{b:g} s: {why}")


def integrate(model: GravureCoater, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor BE at the times ``t`` [s] (default: the nominal grid),
    from rest, with the parameters ``p`` over the declared ones (and ``fx["p"]`` over
    those): current [A] (the stand's shunt in the armature's lead), speed [rad/s] (the
    motor's rear-shaft encoder, rad/s at the rotor), and in the slow regime load_speed
    [rad/s] (the roll's speed, from the encoder on the roll's operator-side journal,
    signed), plus the command ``u`` [V]. ``states``: add the bodies' speeds [rad/s] and
    angles [rad], the drive shaft's twist [rad] and torque [N m], and the outside effects'
    states."""
    fx = dict(fx or {})
    p = {**MOTOR_BE, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = GravureCoater(fx, p)
    y = integrate(model, t, bp, MAX_STEP[regime])
    u = np.interp(t, bp[:, 0], bp[:, 1])
    seen = model.seen(y)
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
        out.update(rotor_angle=y[2], hub_angle=thh, hub_speed=y[1] / p["N"],
                   roll_angle=y[4], roll_speed=y[3], armature_current=y[0],
                   shaft_twist=twist,
                   shaft_torque=np.array([model.shaft(float(b), float(c)) for
                                          b, c in zip(twist, rate, strict=True)]))
        if model.i_nip is not None:
            out.update(nip_engaged=y[model.i_nip], nip_roller_speed=y[model.i_nip + 1])
        if model.i_thix is not None:
            out["slurry_structure"] = y[model.i_thix]
        if model.i_rms is not None:
            out["mean_square_current"] = y[model.i_rms]
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
