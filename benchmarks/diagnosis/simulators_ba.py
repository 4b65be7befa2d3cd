"""Motor BA of the diagnosis benchmark: a hand-written scipy model of a 12 V permanent-magnet
brushed DC motor (a 4-pole, 14-slot ferrite motor) driving the drum of a small (140 L)
ELECTRIC SITE CEMENT MIXER on the service bench: the mixer's drum charged with a test batch of
wet concrete, 1.9 kg m^2 of steel drum and 5.6 kg m^2 of concrete about the drum's axis
(7.5 kg m^2 in all). The motor drives a 9:1 spur gearbox whose output pinion (15 teeth) meshes
with the drum's girth ring (225 teeth, 15:1; `gear` G, 135:1 in all, declared rigid and
lossless); the body ``ring`` is the girth ring with the pinion and the gearbox's output shaft,
turning in the gearbox's output bearings and the pinion's open mesh. The girth ring is bolted
to the drum's shell in six cast segments, and the drum is carried in its tilting yoke: the
segments' bolted joints and the yoke's arms are a torsion spring from the ring to the drum, a
`spring_damper` K between the ring and the body ``drum`` (the drum with its wet concrete), the
drum's angle its own. Forward is drum.w > 0 (mixing; backwards the blades' spiral throws the
batch out of the mouth); the drum turns at the ring's speed on average (1:1).

No circuitsim import, and no other set's simulator: an independent simulator, written from the
physics for netlists/motor_ba_fast.yaml and motor_ba_slow.yaml. It is evaluated at the record's
own sample times (``t_eval``), never on a grid that is then interpolated. Everything rests at
t = 0: no current, no speed, the ring and the drum at 0 and the segments untwisted.

The drive is rigid (``gear`` G, ratio N = 135): the ring stands at th / N and turns at w / N
with the rotor; a torque T on it is T / N on the rotor. The ring's segments and the yoke are a
spring and a damper on the twist th / N - thl between the ring and the drum (``spring_damper``
K), its torque on the drum

    Tk = Ks (th / N - thl) + Ds (w / N - wl).

The gearbox's output bearings and the pinion's open mesh give the ring a dry friction
(``friction`` Fh, Th tanh(wh / 0.01), w_brk 0.1). The drum rolls on its two trunnion bearings
in the yoke: a dry friction (``friction`` Fl, Tl tanh(wl / 0.01), w_brk 0.1, with the lift of
the tumbling batch); the wet concrete churned by the blades gives a viscous drag (``damper``
Bl).

State y = [i, w, th, wl, thl] (+ the outside effects' states -- the batch's heel angle, the
batch's fill --, + one Pade stage per delayed probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wl, thl    the drum's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the armature with the gearbox's input, and the ring):

    L di/dt   = v(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor
                + (X_ring - Th tanh((w / N) / 0.01) - Tk) / N
    Jl dwl/dt = Tk - Tl tanh(wl / 0.01) - Bl wl + X_drum

v(t) the bench supply's output u(t) (the command, linear between its breakpoints), Tm tanh(w /
0.01) the brushes' and the motor's bearings' dry friction (``friction`` Fr, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, ring, drum) receives
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

    heel      (U [N m], amax [rad], wc [rad/s], tau [s]): the wet batch heels over: the drum
              receives -U sin(a), a the angle by which the batch's centre of mass is carried
              up the drum's rising side, lagging the drum's speed:
              da/dt = (amax tanh(wl / wc) - a) / tau, a = 0 at rest (state)
    discharge (sJ, sT, sB [1], Th [rad]): turning backwards, the blades throw the batch out of
              the mouth: its fill f (1 at the start, state) falls as
              df/dt = -f max(-wl, 0) / Th, and the drum's inertia, trunnion friction and
              churning drag are Jl (1 - sJ (1 - f)), Tl (1 - sT (1 - f)) and
              Bl (1 - sB (1 - f)) (sJ, sT, sB: the batch's shares of them); the concrete
              leaves at the drum's speed, taking its own angular momentum with it
    compound  c [1/A]: a series winding on the motor's poles adds to the magnets' flux with
              the current: the EMF and the torque take k (1 + c i) in place of k (signed:
              a reverse current weakens the flux)
    arc       (Vs [V], X0 [A rad/s]): the brushes spark at their trailing edges once the
              commutating coils' reactance voltage (in proportion to |i w|) outruns their
              contact: the loop takes Vs max(|i w| / X0 - 1, 0) tanh(i / 1 mA) more
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor BA [SI] (motor_ba_fast.yaml, motor_ba_slow.yaml): what the
#: diagnosis starts from; a record's true values differ in the parameters it frees
MOTOR_BA: dict[str, float] = {
    "R": 0.11, "L": 3.0e-4, "k": 0.034, "Jm": 1.6e-4, "bm": 4.0e-5, "Tm": 0.035,
    "N": 135.0, "Jh": 0.9, "Th": 1.8, "Ks": 5200.0, "Ds": 9.0, "Jl": 7.5,
    "Tl": 12.0, "Bl": 18.0,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_ba_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.14, 12.0), (0.22, 12.0), (0.24, 7.0),
               (0.29, 7.0), (0.35, -9.0), (0.41, -9.0), (0.43, 0.0), (0.45, 0.0))
#: the slow regime's logged command [s, V] (motor_ba_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.5, 0.0), (2.0, 6.0), (5.0, 6.0), (5.8, 12.0), (8.5, 12.0),
               (9.0, 0.0), (9.6, 0.0), (10.6, -10.0), (14.2, -10.0), (14.8, 0.0),
               (16.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.45), "slow": (100.0, 16.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "ring", "drum")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a fifth of the
#: mean interval in the slow one
MAX_STEP = {"fast": 1.0 / 20e3, "slow": 2e-3}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.array(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class MixerDrive:
    """Right-hand side of motor BA with the effects ``fx`` and the parameters ``p`` [SI];
    ``seg`` holds the command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.fx, self.p = fx, p
        self.n = p["N"]
        size = 5
        #: indices of the outside effects' states
        self.i_heel = self.i_fill = None
        if "heel" in fx:
            self.i_heel, size = size, size + 1
        if "discharge" in fx:
            self.i_fill, size = size, size + 1
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
        #: Jr: the rotor with the ring at the rotor's scale
        self.jr = p["Jm"] + p["Jh"] / self.n ** 2
        self.seg = (0.0, 0.0, 0.0)

    def initial(self) -> np.ndarray:
        """The state at rest at t = 0 (the batch's fill 1 if ``discharge``)."""
        y0 = np.zeros(self.size)
        if self.i_fill is not None:
            y0[self.i_fill] = 1.0
        return y0

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

    def flux(self, i: float) -> float:
        """The motor's constant [N m/A = V s/rad] at the current ``i`` [A]."""
        if "compound" not in self.fx:
            return self.p["k"]
        return self.p["k"] * (1.0 + self.fx["compound"] * i)

    def loop(self, t: float, i: float, th: float, w: float) -> float:
        """The loop's voltage [V] besides the inductance's and the EMF's."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        r += fx.get("Rser", 0.0) + fx.get("Rs", 0.0)
        v = r * i
        if "arc" in fx:
            vs, x0 = fx["arc"]
            v += vs * max(abs(i * w) / x0 - 1.0, 0.0) * math.tanh(i / I_SWITCH)
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
        """The segments' and the yoke's torque on the drum [N m] at the twist ``x`` [rad] and
        the twist rate ``v`` [rad/s] (the ring's minus the drum's), with a play if ``gap``
        (nothing inside the play, the damping never pulling the sides together)."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        gap = self.fx.get("gap")
        if not gap:
            return ks * x + ds * v
        half = 0.5 * gap
        if -half <= x <= half:
            return 0.0
        if x > 0.0:
            return max(ks * (x - half) + ds * v, 0.0)
        return min(ks * (x + half) + ds * v, 0.0)

    def __call__(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n, fx = self.p, self.n, self.fx
        i, w, th, wl, thl = y[0], y[1], y[2], y[3], y[4]
        u = self.command(t)
        dy = np.empty(self.size)
        kf = self.flux(i)
        dy[0] = (u - self.loop(t, i, th, w) - kf * w) / self.inductance(i)
        motor = (kf * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                 + self.body_torque("rotor", w, th))
        tk = self.shaft(th / n - thl, w / n - wl)
        wh = w / n
        ring = self.body_torque("ring", wh, th / n) - p["Th"] * math.tanh(wh / W_SWITCH)
        dy[1] = (motor + (ring - tk) / n) / self.jr
        dy[2] = w
        jl, tl, bl = p["Jl"], p["Tl"], p["Bl"]
        if self.i_fill is not None:
            sj, st, sb, theta = fx["discharge"]
            gone = 1.0 - y[self.i_fill]
            jl, tl, bl = jl * (1.0 - sj * gone), tl * (1.0 - st * gone), bl * (1.0 - sb * gone)
            dy[self.i_fill] = -y[self.i_fill] * max(-wl, 0.0) / theta
        drum = tk - tl * math.tanh(wl / W_SWITCH) - bl * wl + self.body_torque("drum", wl, thl)
        if self.i_heel is not None:
            u0, amax, wc, tau = fx["heel"]
            a = y[self.i_heel]
            drum -= u0 * math.sin(a)
            dy[self.i_heel] = (amax * math.tanh(wl / wc) - a) / tau
        dy[3] = drum / jl
        dy[4] = wl
        if self.delays:
            seen = self.seen(y)
            for probe, tau, j in self.delays:
                dy[j] = 2.0 * (seen[probe] - y[j]) / tau
        return dy

    @staticmethod
    def seen(y: np.ndarray) -> dict[str, Any]:
        """What each probe's sensor sees [A, rad/s] before its catalog effects: the current
        in the supply's lead, the rotor's speed and the drum's."""
        return {"current": y[0], "speed": y[1], "load_speed": y[3]}


# ---------------------------------------------------------------------- integration

def _span(model: MixerDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor BA, {a:g}-{b:g} s: {why}")


def integrate(model: MixerDrive, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor BA at the times ``t`` [s] (default: the nominal grid),
    from rest, with the parameters ``p`` over the declared ones (and ``fx["p"]`` over
    those): current [A] (the bench's shunt in the supply's lead), speed [rad/s] (the bench's
    DC tachogenerator on the motor's rear shaft end, rad/s at the rotor), and in the slow
    regime load_speed [rad/s] (the drum, from the bench's magnetic encoder on the drum's
    drive-side trunnion, signed), plus the command ``u`` [V]. ``states``: add the bodies'
    speeds [rad/s] and angles [rad], the segments' twist [rad] and torque [N m], and the
    outside effects' states."""
    fx = dict(fx or {})
    p = {**MOTOR_BA, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = MixerDrive(fx, p)
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
        twist, rate = y[2] / p["N"] - y[4], y[1] / p["N"] - y[3]
        out.update(rotor_angle=y[2], ring_angle=y[2] / p["N"], ring_speed=y[1] / p["N"],
                   drum_angle=y[4], drum_speed=y[3], armature_current=y[0],
                   segments_twist=twist,
                   segments_torque=np.array([model.shaft(a, b) for a, b in
                                             zip(twist, rate, strict=True)]))
        if model.i_heel is not None:
            out["heel_angle"] = y[model.i_heel]
        if model.i_fill is not None:
            out["fill"] = y[model.i_fill]
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
