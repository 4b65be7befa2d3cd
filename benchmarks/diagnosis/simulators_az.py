"""Motor AZ of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC gearmotor (a 2-pole, 9-slot ferrite motor) in the rotation drive of a LIGHTHOUSE's
rotating optic, on the lighthouse service's workshop test stand: the refurbished pedestal of a
third-order four-panel Fresnel lens, the optic (90 kg m^2 about its vertical axis with its lens
table) floating on the pedestal's mercury bath. The motor drives a 40:1 worm gearbox whose
output pinion turns the pedestal's bull wheel through a 20:1 spur stage (`gear` G, 800:1 in
all, declared rigid and lossless); the body ``hub`` is the bull wheel with the foot of the
vertical drive spindle, turning in its bronze bearings. The drive spindle (1.4 m of 40 mm steel
up through the pedestal's column to the lens table's driving dog) is a torsion spring, a
`spring_damper` K between the hub and the body ``lens`` (the optic with its lens table and the
mercury float), the lens's angle its own. Forward is lens.w > 0 (clockwise seen from above);
the lens turns at the hub's speed on average (1:1).

No circuitsim import, and no other set's simulator: an independent simulator, written from the
physics for netlists/motor_az_fast.yaml and motor_az_slow.yaml. It is evaluated at the record's
own sample times (``t_eval``), never on a grid that is then interpolated. Everything rests at
t = 0: no current, no speed, the hub and the lens at 0 and the spindle untwisted.

The drive is rigid (``gear`` G, ratio N = 800): the hub stands at th / N and turns at w / N
with the rotor; a torque T on it is T / N on the rotor. The drive spindle is a spring and a
damper on the twist th / N - thl between the hub and the lens (``spring_damper`` K), its
torque on the lens

    Tk = Ks (th / N - thl) + Ds (w / N - wl).

The bull wheel's bronze bearings give the hub a dry friction (``friction`` Fh,
Th tanh(wh / 0.01), w_brk 0.1). The float's centring rollers give the lens a dry friction
(``friction`` Fl, Tl tanh(wl / 0.01), w_brk 0.1); the roller carriage's grease and the mercury
give a viscous drag (``damper`` Bl).

State y = [i, w, th, wl, thl] (+ one Pade stage per delayed probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wl, thl    the lens's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the armature with the worm, and the hub):

    L di/dt   = v(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor
                + (X_hub - Th tanh((w / N) / 0.01) - Tk) / N
    Jl dwl/dt = Tk - Tl tanh(wl / 0.01) - Bl wl + X_lens

v(t) the stand's supply's output u(t) (the command, linear between its breakpoints),
Tm tanh(w / 0.01) the brushes', the motor's bearings' and the worm's dry friction (``friction``
Fr, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, lens) receives
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

    clamp     (Ilim [A], nVt [V], Is [A]): the freewheel diode of the lantern's old
              one-direction drive panel is still in the motor's terminal box, across the
              terminals (cathode to the positive one): whenever the supply would drive the
              terminals negative past the diode's drop, the diode conducts, the supply runs
              into its current limit Ilim and the terminals sit at the diode's forward drop:
              the motor sees v = max(u, -nVt ln(1 + (Ilim + i) / Is)) (the diode carrying
              Ilim + i), and the current (the supply's, through the shunt) reads
              i - Is (exp(-v / nVt) - 1), -Ilim while clamped
    pickup    M [s] (rad/s per A/s): the tachogenerator's unscreened pair runs beside the
              motor's lead through the stand's trunking: speed reads w + M di/dt, di/dt the
              armature current's rate (the model's own, at each sample); the motor itself is
              not touched
    ratio     rho [1/A]: the lens encoder's analog speed output is ratiometric to its supply
              rail, whose return it shares with the motor's lead: load_speed reads
              wl (1 - rho i); the motor itself is not touched
    limit     (theta_lim [rad], dtheta [rad], Roff [ohm], nVt [V], Is [A]): the stand's
              overtravel switch, its cam on the lens table, is wired into the motor's lead
              with the usual bypass diode: the loop takes
              h (Roff (i + a) / 2 - nVt ln(1 + (a - i) / (2 Is))), a = sqrt(i^2 + (1 uA)^2),
              h = (1 + tanh((thl - theta_lim) / dtheta)) / 2: past theta_lim the contact is
              open, a forward current passes only its suppression resistor Roff, a backward
              one the diode (its forward drop)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AZ [SI] (motor_az_fast.yaml, motor_az_slow.yaml): what the
#: diagnosis starts from; a record's true values differ in the parameters it frees
MOTOR_AZ: dict[str, float] = {
    "R": 0.8, "L": 1.6e-3, "k": 0.08, "Jm": 1.4e-4, "bm": 1.5e-5, "Tm": 0.015,
    "N": 800.0, "Jh": 4.0, "Th": 6.0, "Ks": 40000.0, "Ds": 300.0, "Jl": 90.0,
    "Tl": 14.0, "Bl": 60.0,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_az_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.02, 0.0), (0.14, 22.0), (0.22, 22.0), (0.25, 9.0),
               (0.30, 9.0), (0.37, -14.0), (0.42, -14.0), (0.45, 0.0), (0.50, 0.0))
#: the slow regime's logged command [s, V] (motor_az_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.4, 0.0), (1.6, 12.0), (4.0, 12.0), (4.6, 22.0), (6.4, 22.0),
               (6.8, 0.0), (7.4, 0.0), (8.2, -14.0), (10.4, -14.0), (11.0, 0.0), (12.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.5), "slow": (200.0, 12.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "lens")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a fifth of the
#: mean interval in the slow one
MAX_STEP = {"fast": 1.0 / 20e3, "slow": 1e-3}
#: [A] the smoothing of |i| in the overtravel switch's contact and diode: sqrt(i^2 + eps^2)
I_SMOOTH = 1e-6


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.array(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class LensDrive:
    """Right-hand side of motor AZ with the effects ``fx`` and the parameters ``p`` [SI];
    ``seg`` holds the command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.fx, self.p = fx, p
        self.n = p["N"]
        self.jr = p["Jm"] + p["Jh"] / self.n ** 2
        size = 5
        #: indices of the outside effects' states
        #: (probe, tau [s], index of its Pade state)
        self.delays: list[tuple[str, float, int]] = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.delays.append((probe, float(s["delay"]), size))
                size += 1
        if self.delays and ("pickup" in fx or "ratio" in fx or "clamp" in fx):
            raise ValueError("a probe's delay with an outside reading effect")
        self.size = size
        self.extra = {body: {key: fx[key][body] for key in
                             ("visc", "coul", "offset", "stribeck", "cog")
                             if fx.get(key, {}).get(body)} for body in BODIES}
        self.seg = (0.0, 0.0, 0.0)

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

    def loop(self, t: float, i: float, th: float, w: float, thl: float = 0.0) -> float:
        """The loop's voltage [V] besides the inductance's and the EMF's (``thl`` the lens's
        angle [rad], for the overtravel switch)."""
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
        if "limit" in fx:
            th_lim, dth, roff, nvt, isat = fx["limit"]
            opened = 0.5 * (1.0 + math.tanh((thl - th_lim) / dth))
            mag = math.sqrt(i * i + I_SMOOTH * I_SMOOTH)
            v += opened * (roff * 0.5 * (i + mag) - nvt * math.log1p(0.5 * (mag - i) / isat))
        return v

    def inductance(self, i: float) -> float:
        """The differential inductance [H] at the current ``i`` [A]."""
        if "lsat" not in self.fx:
            return self.p["L"]
        ipar, ratio = self.fx["lsat"]
        return self.p["L"] * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))

    def spindle(self, x: float, v: float) -> float:
        """The drive spindle's torque on the lens [N m] at the twist ``x`` [rad] and the twist
        rate ``v`` [rad/s] (the hub's minus the lens's), with a play if ``gap``: nothing
        inside the play, the damping never pulling the sides together."""
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

    def clamp_voltage(self, i: float) -> float:
        """The freewheel diode's forward drop as the terminals' voltage [V] (negative) while
        the supply, in its current limit Ilim, and the motor's current ``i`` [A] share it
        (``clamp``): the diode carries Ilim + i."""
        ilim, nvt, isat = self.fx["clamp"]
        return -nvt * math.log1p(max(ilim + i, 0.0) / isat)

    def terminal(self, u: float, i: float) -> float:
        """The motor's terminal voltage [V] at the supply's set ``u`` [V] and the current
        ``i`` [A]: u, or the diode's clamp when u would drive the diode past the supply's
        current limit (``clamp``)."""
        if "clamp" not in self.fx:
            return u
        return max(u, self.clamp_voltage(i))

    def supplied(self, u: float, i: float) -> float:
        """The supply's current [A] through the shunt: the motor's ``i`` less the freewheel
        diode's forward current at the terminal voltage (``clamp``)."""
        _, nvt, isat = self.fx["clamp"]
        return i - isat * math.expm1(-self.terminal(u, i) / nvt)

    def di_dt(self, t: float, y: np.ndarray, u: float) -> float:
        """The armature current's rate [A/s] in the state ``y`` at the supply's ``u`` [V]."""
        i, w, th = y[0], y[1], y[2]
        return ((self.terminal(u, i) - self.loop(t, i, th, w, y[4]) - self.p["k"] * w)
                / self.inductance(i))

    def __call__(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n = self.p, self.n
        w, th, wl, thl = y[1], y[2], y[3], y[4]
        u = self.command(t)
        dy = np.empty(self.size)
        dy[0] = self.di_dt(t, y, u)
        tk = self.spindle(th / n - thl, w / n - wl)
        wh = w / n
        hub = self.body_torque("hub", wh, th / n) - p["Th"] * math.tanh(wh / W_SWITCH)
        dy[1] = (p["k"] * y[0] - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                 + self.body_torque("rotor", w, th) + (hub - tk) / n) / self.jr
        dy[2] = w
        lens = (tk - p["Tl"] * math.tanh(wl / W_SWITCH) - p["Bl"] * wl
                + self.body_torque("lens", wl, thl))
        dy[3] = lens / p["Jl"]
        dy[4] = wl
        if self.delays:
            seen = self.seen(y)
            for probe, tau, j in self.delays:
                dy[j] = 2.0 * (seen[probe] - y[j]) / tau
        return dy

    def seen(self, y: np.ndarray) -> dict[str, Any]:
        """What each probe's sensor sees [A, rad/s] before its catalog effects and the
        outside reading effects: the current in the supply's lead, the rotor's speed and the
        lens's."""
        return {"current": y[0], "speed": y[1], "load_speed": y[3]}


# ---------------------------------------------------------------------- integration

def _span(model: LensDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AZ, {a:g}-{b:g} s: {why}")


def integrate(model: LensDrive, t: np.ndarray, bp: np.ndarray, max_step: float
              ) -> np.ndarray:
    """The states (n_states, t.size) at the increasing times ``t`` [s], from rest at 0, the
    integration restarted at every corner of the command ``bp`` [s, V]."""
    end = float(t[-1])
    corners = sorted({0.0, end, *(float(c) for c in bp[:, 0] if 0.0 < c < end)})
    out = np.empty((model.size, t.size))
    y0 = np.zeros(model.size)
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
    """Noise-free probes of motor AZ at the times ``t`` [s] (default: the nominal grid),
    from rest, with the parameters ``p`` over the declared ones (and ``fx["p"]`` over
    those): current [A] (the stand's shunt in the supply's lead), speed [rad/s] (the stand's
    DC tachogenerator on the motor's rear shaft end, rad/s at the rotor), and in the slow
    regime load_speed [rad/s] (the lens, from the stand's encoder under the lens table,
    signed), plus the command ``u`` [V]. ``states``: add the bodies' speeds [rad/s] and
    angles [rad], the spindle's twist [rad] and torque [N m] and the current's rate [A/s]."""
    fx = dict(fx or {})
    p = {**MOTOR_AZ, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = LensDrive(fx, p)
    y = integrate(model, t, bp, MAX_STEP[regime])
    u = np.interp(t, bp[:, 0], bp[:, 1])
    seen = model.seen(y)
    for probe, _, j in model.delays:
        seen[probe] = 2.0 * y[j] - seen[probe]
    out = {probe: np.array(seen[probe], dtype=float) for probe in PROBES[regime]}
    rate = None
    if "pickup" in fx or states:
        rate = np.array([model.di_dt(float(tt), y[:, m], float(uu))
                         for m, (tt, uu) in enumerate(zip(t, u, strict=True))])
    if "pickup" in fx:
        out["speed"] = out["speed"] + fx["pickup"] * rate
    if "ratio" in fx and "load_speed" in out:
        out["load_speed"] = out["load_speed"] * (1.0 - fx["ratio"] * y[0])
    if "clamp" in fx:
        out["current"] = np.array([model.supplied(float(uu), float(ii)) for uu, ii in
                                   zip(u, y[0], strict=True)])
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = u
    if states:
        twist, twist_rate = y[2] / p["N"] - y[4], y[1] / p["N"] - y[3]
        out.update(rotor_angle=y[2], hub_angle=y[2] / p["N"], hub_speed=y[1] / p["N"],
                   lens_angle=y[4], lens_speed=y[3], armature_current=y[0],
                   current_rate=rate, spindle_twist=twist,
                   spindle_torque=np.array([model.spindle(a, b) for a, b in
                                            zip(twist, twist_rate, strict=True)]))
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
