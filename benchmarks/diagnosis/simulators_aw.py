"""Motor AW of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC gearmotor (a 2-pole, 7-slot ferrite motor) turning the SPIT of a caterer's HOG-ROAST
SPIT ROASTER (a trailer-mounted charcoal roaster with a 1.6 m stainless spit) on the maker's
end-of-line test stand, a 38 kg dummy roast (a steel tube ballasted with sand bags, its mass
spread along the spit like a hog's) clamped in the spit's two forks. The motor's 10-tooth
pinion drives a three-stage spur gearhead (`gear` G, 120:1, declared rigid and lossless); the
body ``hub`` is the gearhead's output shaft with its square drive socket and the drive-end
fork, turning in the gearhead's output bush and the drive-end upright's bush. The spit is a
20 mm square bar: from the drive socket to the roast it is a long torsion spring (with the
forks' grip on the roast), a `spring_damper` K between the hub and the body ``roast`` (the
dummy roast with the far-end fork and the spit's far end), the roast's angle its own. Forward
is roast.w > 0; the roast turns at the hub's speed on average (1:1).

No circuitsim import, and no other set's simulator: an independent simulator, written from the
physics for netlists/motor_aw_fast.yaml and motor_aw_slow.yaml. It is evaluated at the record's
own sample times (``t_eval``), never on a grid that is then interpolated. Everything rests at
t = 0: no current, no speed, the hub and the roast at 0 and the spit untwisted.

The gearhead is rigid (``gear`` G, ratio N = 120): the hub stands at th / N and turns at w / N
with the rotor; a torque T on it is T / N on the rotor. The spit is a spring and a damper on
the twist th / N - thl between the hub and the roast (``spring_damper`` K), its torque on the
roast

    Tk = Ks (th / N - thl) + Ds (w / N - wl).

The hub's bushes give it a dry friction (``friction`` Fh, Th tanh(wh / 0.01), w_brk 0.1). The
roast's far end turns in the far upright's grease-packed sleeve bearing: a dry friction
(``friction`` Fl, Tl tanh(wl / 0.01), w_brk 0.1) and the grease's viscous drag (``damper`` Bl).

State y = [i, w, th, wl, thl] (+ the outside effects' states, + one Pade stage per delayed
probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wl, thl    the roast's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the armature with its pinion, and the hub):

    L di/dt   = v(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor
                + (X_hub - Th tanh((w / N) / 0.01) - Tk) / N
    Jl dwl/dt = Tk - Tl tanh(wl / 0.01) - Bl wl + X_roast

v(t) the supply's output u(t) (the command, linear between its breakpoints), Tm tanh(w /
0.01) the brushes' and the motor's bushes' dry friction (``friction`` Fr, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, roast) receives
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

    weight    (U [N m], Tc [N m], Jc [kg m^2]): a counterweight clamped loosely on the spit
              beside the far fork, hanging straight down at the start: a body of its own
              (angle thc from hanging, speed wc), Jc dwc/dt = Tc tanh((wl - wc) / 0.01) -
              U sin(thc); the roast receives -Tc tanh((wl - wc) / 0.01) (the clamp's
              friction); U = m g r its gravity torque a quarter turn from hanging
    reed      (n, delta [rad], T0 [s], theta0 [rad]): the load_speed is the spit controller's
              speed from a reed switch and n magnets on the far fork: a pulse whenever the
              roast's angle enters a window of +-delta about theta0 + m 2 pi / n; the reading
              is (2 pi / n) / (t_k - t_k-1) from the last pulse t_k on, signed as the
              command's direction at t_k (its last nonzero sign), 0 when t - t_k > T0 or
              t_k - t_k-1 > T0
    dirbit    h [rad/s]: the speed is the stand's speed module's: the tachogenerator's
              magnitude |w| with the sign of a direction comparator of hysteresis h (it turns
              forward when w rises through +h, backward when w falls through -h; forward at
              the start)
    bus       (C [F], r [ohm], Vd [V], Rb [ohm]): the roaster's control box left connected
              to the motor's terminals, its own supply off: its H-bridge's body diodes (Vd for
              the two in the path) rectify the terminal voltage u into its bus capacitor C
              (vc, 0 at rest; its bleeder Rb): the charging current ic = (0.01 V / r)
              ln(1 + exp((|u| - Vd - vc) / 0.01 V)), C dvc/dt = ic - vc / Rb; the current (the
              shunt in the supply's lead) reads i + sign(u) ic; the motor itself is not
              touched
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AW [SI] (motor_aw_fast.yaml, motor_aw_slow.yaml): what the
#: diagnosis starts from; a record's true values differ in the parameters it frees
MOTOR_AW: dict[str, float] = {
    "R": 1.1, "L": 1.6e-3, "k": 0.052, "Jm": 4.5e-5, "bm": 1.2e-5, "Tm": 0.01,
    "N": 120.0, "Jh": 0.06, "Th": 0.9, "Ks": 160.0, "Ds": 2.2, "Jl": 0.9,
    "Tl": 0.7, "Bl": 0.35,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: [V] the width of the body diodes' knee (``bus``)
V_KNEE = 0.01
#: the fast regime's command [s, V] (motor_aw_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.02, 0.0), (0.14, 20.0), (0.27, 20.0), (0.30, 8.0),
               (0.38, 8.0), (0.46, -14.0), (0.55, -14.0), (0.57, 0.0), (0.60, 0.0))
#: the slow regime's logged command [s, V] (motor_aw_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.5, 0.0), (1.5, 6.0), (3.5, 6.0), (4.0, 20.0), (5.8, 20.0),
               (6.2, 0.0), (6.8, 0.0), (7.4, -10.0), (9.0, -10.0), (9.4, 0.0), (10.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.6), "slow": (250.0, 10.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "roast")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a quarter of the
#: mean interval in the slow one
MAX_STEP = {"fast": 1.0 / 25e3, "slow": 1e-3}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.array(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class SpitDrive:
    """Right-hand side of motor AW with the effects ``fx`` and the parameters ``p`` [SI];
    ``seg`` holds the command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.fx, self.p = fx, p
        self.n = p["N"]
        self.jr = p["Jm"] + p["Jh"] / self.n ** 2
        size = 5
        #: indices of the outside effects' states
        self.i_weight = self.i_bus = None
        if "weight" in fx:
            self.i_weight, size = size, size + 2
        if "bus" in fx:
            self.i_bus, size = size, size + 1
        #: (probe, tau [s], index of its Pade state)
        self.delays: list[tuple[str, float, int]] = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                if probe == "load_speed" and "reed" in fx:
                    raise ValueError("a delay on the reed switch's reading is not modelled")
                self.delays.append((probe, float(s["delay"]), size))
                size += 1
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

    def loop(self, t: float, i: float, th: float, w: float) -> float:
        """The loop's voltage [V] besides the inductance's and the EMF's."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        v = (r + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)) * i
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

    def spit(self, x: float, v: float) -> float:
        """The spit's torque on the roast [N m] at the twist ``x`` [rad] and the twist rate
        ``v`` [rad/s] (the hub's minus the roast's), with a play if ``gap``."""
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
        dy[0] = (u - self.loop(t, i, th, w) - p["k"] * w) / self.inductance(i)
        tk = self.spit(th / n - thl, w / n - wl)
        wh = w / n
        hub = self.body_torque("hub", wh, th / n) - p["Th"] * math.tanh(wh / W_SWITCH)
        dy[1] = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                 + self.body_torque("rotor", w, th) + (hub - tk) / n) / self.jr
        dy[2] = w
        roast = (tk - p["Tl"] * math.tanh(wl / W_SWITCH) - p["Bl"] * wl
                 + self.body_torque("roast", wl, thl))
        if self.i_weight is not None:
            u_w, tc, jc = fx["weight"]
            wc, thc = y[self.i_weight], y[self.i_weight + 1]
            clamp = tc * math.tanh((wl - wc) / W_SWITCH)
            roast -= clamp
            dy[self.i_weight] = (clamp - u_w * math.sin(thc)) / jc
            dy[self.i_weight + 1] = wc
        dy[3] = roast / p["Jl"]
        dy[4] = wl
        if self.i_bus is not None:
            c, _, _, rb = fx["bus"]
            vc = y[self.i_bus]
            dy[self.i_bus] = (self.charging(u, vc) - vc / rb) / c
        if self.delays:
            seen = self.seen(u, y)
            for probe, tau, j in self.delays:
                dy[j] = 2.0 * (seen[probe] - y[j]) / tau
        return dy

    def charging(self, u: Any, vc: Any) -> Any:
        """The control box's bus capacitor's charging current [A] through its bridge's
        body diodes at the terminal voltage ``u`` and the capacitor's ``vc`` [V]."""
        _, r, vd, _ = self.fx["bus"]
        return V_KNEE / r * np.logaddexp(0.0, (np.abs(u) - vd - vc) / V_KNEE)

    def seen(self, u: Any, y: np.ndarray) -> dict[str, Any]:
        """What each probe's sensor sees [A, rad/s] before its catalog effects (and the reed
        switch's and the direction module's readings, which ``simulate`` makes from the
        events): the current in the supply's lead, the rotor's speed and the roast's."""
        i, w, wl = y[0], y[1], y[3]
        current = i
        if self.i_bus is not None:
            current = i + np.sign(u) * self.charging(u, y[self.i_bus])
        return {"current": current, "speed": w, "load_speed": wl}

    def events(self) -> list:
        """The event functions of the outside effects that need them: the reed switch's
        closing; the direction bit's rising and falling thresholds."""
        out = []
        if "reed" in self.fx:
            out.append(self.reed_event())
        if "dirbit" in self.fx:
            h = self.fx["dirbit"]

            def up(t: float, y: np.ndarray) -> float:
                return y[1] - h

            def down(t: float, y: np.ndarray) -> float:
                return y[1] + h

            up.direction, down.direction = 1.0, -1.0
            out += [up, down]
        return out

    def reed_event(self):
        """The reed switch's closing: the roast's angle entering a magnet's window (an event
        function of (t, y), rising through 0)."""
        nmag, delta, _, theta0 = self.fx["reed"]
        pitch = 2.0 * math.pi / nmag
        edge = math.cos(2.0 * math.pi * delta / pitch)

        def closing(t: float, y: np.ndarray) -> float:
            return math.cos(2.0 * math.pi * (y[4] - theta0) / pitch) - edge

        closing.direction = 1.0
        return closing


# ---------------------------------------------------------------------- integration

def _span(model: SpitDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
          max_step: float, events: list) -> tuple[np.ndarray, list[np.ndarray]]:
    """The states at ``t_out`` [s] from ``y0`` at ``a`` to ``b`` [s] and the events' times
    [s]: LSODA, Radau if LSODA fails."""
    why = ""
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), y0, method=method, t_eval=t_out, rtol=RTOL,
                        atol=ATOL, max_step=max_step, events=events or None)
        if sol.success and sol.y.shape[1] == t_out.size and np.isfinite(sol.y).all():
            hits = [np.asarray(h, dtype=float) for h in sol.t_events] if events else []
            return sol.y, hits
        why = sol.message
    raise RuntimeError(f"motor AW, {a:g}-{b:g} s: {why}")


def integrate(model: SpitDrive, t: np.ndarray, bp: np.ndarray, max_step: float
              ) -> tuple[np.ndarray, list[np.ndarray]]:
    """The states (n_states, t.size) at the increasing times ``t`` [s], from rest at 0, the
    integration restarted at every corner of the command ``bp`` [s, V]; and the times [s]
    of each of the model's events (``SpitDrive.events``), located by the integrator."""
    end = float(t[-1])
    corners = sorted({0.0, end, *(float(c) for c in bp[:, 0] if 0.0 < c < end)})
    out = np.empty((model.size, t.size))
    y0 = np.zeros(model.size)
    events = model.events()
    found = [[] for _ in events]
    for a, b in itertools.pairwise(corners):
        ua, ub = np.interp([a, b], bp[:, 0], bp[:, 1])
        model.seg = (a, float(ua), float(ub - ua) / (b - a))
        last = b == end
        inside = (t >= a) & ((t <= b) if last else (t < b))
        t_out = t[inside] if last else np.append(t[inside], b)
        ys, hits = _span(model, a, b, y0, t_out, max_step, events)
        out[:, inside] = ys[:, :int(inside.sum())]
        for j, h in enumerate(hits):
            found[j].extend(float(x) for x in h if a < x <= b)
        y0 = ys[:, -1].copy()
    return out, [np.array(sorted(set(f))) for f in found]


def reed_reading(t: np.ndarray, pulses: np.ndarray, bp: np.ndarray,
                 reed: tuple[float, float, float, float]) -> np.ndarray:
    """The spit controller's speed [rad/s] at the times ``t`` [s] from the reed switch's
    ``pulses`` [s] (see ``reed`` in the module's docstring)."""
    nmag, _, t0_out, _ = reed
    pitch = 2.0 * math.pi / nmag
    out = np.zeros(t.size)
    for j, tk in enumerate(pulses):
        if j == 0 or tk - pulses[j - 1] > t0_out:
            continue
        nxt = pulses[j + 1] if j + 1 < pulses.size else math.inf
        hold = (t >= tk) & (t < nxt) & (t - tk <= t0_out)
        out[hold] = direction(tk, bp) * pitch / (tk - pulses[j - 1])
    return out


def direction(t: float, bp: np.ndarray) -> float:
    """The command's direction at ``t`` [s]: the sign of the command, or of its last nonzero
    value before ``t`` (0 before any)."""
    u = float(np.interp(t, bp[:, 0], bp[:, 1]))
    if u != 0.0:
        return math.copysign(1.0, u)
    before = bp[bp[:, 0] <= t, 1]
    nonzero = before[before != 0.0]
    return math.copysign(1.0, nonzero[-1]) if nonzero.size else 0.0


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor AW at the times ``t`` [s] (default: the nominal grid),
    from rest, with the parameters ``p`` over the declared ones (and ``fx["p"]`` over
    those): current [A] (the test stand's shunt in the supply's lead), speed [rad/s] (the
    test stand's DC tachogenerator on the motor's rear shaft end, rad/s at the rotor), and
    in the slow regime load_speed [rad/s] (the roast, from the test stand's incremental
    encoder on the spit's far end, signed), plus the command ``u`` [V]. ``states``: add the
    bodies' speeds [rad/s] and angles [rad], the spit's twist [rad] and torque [N m], the
    reed switch's pulses [s] and the counterweight's speed and angle."""
    fx = dict(fx or {})
    p = {**MOTOR_AW, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = SpitDrive(fx, p)
    y, found = integrate(model, t, bp, MAX_STEP[regime])
    pulses = found[0] if "reed" in fx else np.empty(0)
    u = np.interp(t, bp[:, 0], bp[:, 1])
    seen = model.seen(u, y)
    for probe, _, j in model.delays:
        seen[probe] = 2.0 * y[j] - seen[probe]
    if "reed" in fx:
        seen["load_speed"] = reed_reading(t, pulses, bp, fx["reed"])
    if "dirbit" in fx:
        ups, downs = found[-2], found[-1]
        sign = np.ones(t.size)
        for x, turn in sorted([(x, 1.0) for x in ups] + [(x, -1.0) for x in downs]):
            sign[t >= x] = turn
        seen["speed"] = sign * np.abs(seen["speed"])
    out = {probe: np.array(seen[probe], dtype=float) for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = u
    if states:
        twist, rate = y[2] / p["N"] - y[4], y[1] / p["N"] - y[3]
        out.update(rotor_angle=y[2], hub_angle=y[2] / p["N"], hub_speed=y[1] / p["N"],
                   roast_angle=y[4], roast_speed=y[3], armature_current=y[0],
                   spit_twist=twist,
                   spit_torque=np.array([model.spit(a, b) for a, b in zip(twist, rate,
                                                                          strict=True)]),
                   pulses=pulses)
        if model.i_weight is not None:
            out.update(weight_speed=y[model.i_weight], weight_angle=y[model.i_weight + 1])
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
