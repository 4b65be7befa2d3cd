"""Motor AX of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC gearmotor (a 2-pole, 9-slot ferrite motor) in the canopy drive of an automatic
three-wing REVOLVING DOOR, on the door maker's test rig: a full-size 2.2 m drum with a
lightweight test wing set (three aluminium-framed wings on the central column, 16 kg m^2 about
the column) under a dummy canopy. The motor drives a 40:1 worm gearbox whose 10-tooth output
pinion meshes the column's 100-tooth crown gear (`gear` G, 400:1 in all, declared rigid and
lossless); the body ``hub`` is the crown gear with the column's head, turning in the canopy's
top pivot bush. The central column (a 2.3 m steel tube with the wings' frames bolted to it
through rubber-bushed brackets) is a torsion spring from the crown to the wing set, a
`spring_damper` K between the hub and the body ``door`` (the wing set with the column's foot),
the door's angle its own. Forward is door.w > 0 (anticlockwise seen from above); the door
turns at the hub's speed on average (1:1).

No circuitsim import, and no other set's simulator: an independent simulator, written from the
physics for netlists/motor_ax_fast.yaml and motor_ax_slow.yaml. It is evaluated at the record's
own sample times (``t_eval``), never on a grid that is then interpolated. Everything rests at
t = 0: no current, no speed, the hub and the door at 0 and the column untwisted.

The drive is rigid (``gear`` G, ratio N = 400): the hub stands at th / N and turns at w / N
with the rotor; a torque T on it is T / N on the rotor. The column is a spring and a damper on
the twist th / N - thl between the hub and the door (``spring_damper`` K), its torque on the
door

    Tk = Ks (th / N - thl) + Ds (w / N - wl).

The top pivot bush gives the hub a dry friction (``friction`` Fh, Th tanh(wh / 0.01), w_brk
0.1). The door stands on the floor pivot's thrust bearing and sweeps the drum walls and the
floor with its wings' brush seals: a dry friction (``friction`` Fl, Tl tanh(wl / 0.01), w_brk
0.1) and the air's and the brushes' viscous drag (``damper`` Bl).

State y = [i, w, th, wl, thl] (+ the outside effects' states -- the castor's q, the charge
int i dt for the auto-zero's mean --, + one Pade stage per delayed probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wl, thl    the door's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the armature with the worm, and the hub):

    L di/dt   = v(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor
                + (X_hub - Th tanh((w / N) / 0.01) - Tk) / N
    Jl dwl/dt = Tk - Tl tanh(wl / 0.01) - Bl wl + X_door

v(t) the rig supply's output u(t) (the command, linear between its breakpoints), Tm tanh(w /
0.01) the brushes' and the motor's bearings' dry friction (``friction`` Fr, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, door) receives
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

    castor    (rc [m], a [m], Fs [N], q0 [1]): a support castor under one wing's outer end,
              at the radius rc, its trail a: q (the cosine of its swivel angle from trailing
              behind in forward motion; q0 at the start) relaxes towards the door's direction
              over a travel of about a, dq/dt = (rc |wl| / a) (tanh(wl / 0.01) - q); while it
              stands across its path it scrubs: the door receives -rc Fs (1 - q^2)
              tanh(wl / 0.01)
    air       (Bp [N m s/rad], m [1]): the air forced out of the compartments the wings close
              off against the drum walls, through the brush seals' gaps: the door receives
              -Bp sin(m thl)^2 wl (m = 3: six times a turn, least with a wing in the middle
              of each opening, at thl = 0)
    autozero  Tw [s]: the logger's current channel re-zeroes itself whenever the command
              reaches 0 V after a nonzero stretch (its auto-zero at idle): it takes the mean
              of the current over the Tw that follows as its new zero, from the window's end
              on (zeroed at the start, at rest); the current reads i - that zero; the motor
              itself is not touched
    autorange (w_up [rad/s], w_dn [rad/s], g [1]): the acquisition's speed input switches
              from its low range to its high one when |w| rises through w_up and back when |w|
              falls through w_dn (the low range at the start); the low range reads g times
              the speed (its calibration lost), the high one the speed; the motor itself is
              not touched
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AX [SI] (motor_ax_fast.yaml, motor_ax_slow.yaml): what the
#: diagnosis starts from; a record's true values differ in the parameters it frees
MOTOR_AX: dict[str, float] = {
    "R": 0.85, "L": 1.3e-3, "k": 0.055, "Jm": 6.0e-5, "bm": 1.5e-5, "Tm": 0.012,
    "N": 400.0, "Jh": 0.35, "Th": 3.0, "Ks": 3000.0, "Ds": 40.0, "Jl": 16.0,
    "Tl": 10.0, "Bl": 12.0,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_ax_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.015, 0.0), (0.165, 22.0), (0.24, 22.0), (0.27, 9.0),
               (0.32, 9.0), (0.40, -15.0), (0.45, -15.0), (0.48, 0.0), (0.50, 0.0))
#: the slow regime's logged command [s, V] (motor_ax_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.4, 0.0), (1.6, 7.0), (4.2, 7.0), (4.8, 22.0), (6.6, 22.0),
               (7.1, 0.0), (7.7, 0.0), (8.5, -12.0), (10.8, -12.0), (11.3, 0.0), (12.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.5), "slow": (200.0, 12.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "door")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a fifth of the
#: mean interval in the slow one
MAX_STEP = {"fast": 1.0 / 20e3, "slow": 1e-3}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.array(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class DoorDrive:
    """Right-hand side of motor AX with the effects ``fx`` and the parameters ``p`` [SI];
    ``seg`` holds the command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.fx, self.p = fx, p
        self.n = p["N"]
        self.jr = p["Jm"] + p["Jh"] / self.n ** 2
        size = 5
        #: indices of the outside effects' states
        self.i_castor = self.i_charge = None
        if "castor" in fx:
            self.i_castor, size = size, size + 1
        if "autozero" in fx:
            self.i_charge, size = size, size + 1
        #: (probe, tau [s], index of its Pade state)
        self.delays: list[tuple[str, float, int]] = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                if probe == "speed" and "autorange" in fx:
                    raise ValueError("a delay on the autoranging input is not modelled")
                self.delays.append((probe, float(s["delay"]), size))
                size += 1
        self.size = size
        self.extra = {body: {key: fx[key][body] for key in
                             ("visc", "coul", "offset", "stribeck", "cog")
                             if fx.get(key, {}).get(body)} for body in BODIES}
        self.seg = (0.0, 0.0, 0.0)

    def initial(self) -> np.ndarray:
        """The state at rest at t = 0 (the castor at q0)."""
        y0 = np.zeros(self.size)
        if self.i_castor is not None:
            y0[self.i_castor] = self.fx["castor"][3]
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

    def column(self, x: float, v: float) -> float:
        """The column's torque on the door [N m] at the twist ``x`` [rad] and the twist rate
        ``v`` [rad/s] (the hub's minus the door's), with a play if ``gap``."""
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
        tk = self.column(th / n - thl, w / n - wl)
        wh = w / n
        hub = self.body_torque("hub", wh, th / n) - p["Th"] * math.tanh(wh / W_SWITCH)
        dy[1] = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                 + self.body_torque("rotor", w, th) + (hub - tk) / n) / self.jr
        dy[2] = w
        door = (tk - p["Tl"] * math.tanh(wl / W_SWITCH) - p["Bl"] * wl
                + self.body_torque("door", wl, thl))
        sw = math.tanh(wl / W_SWITCH)
        if self.i_castor is not None:
            rc, a, fs, _ = fx["castor"]
            q = y[self.i_castor]
            door -= rc * fs * (1.0 - q * q) * sw
            dy[self.i_castor] = rc * abs(wl) / a * (sw - q)
        if "air" in fx:
            bp, m = fx["air"]
            door -= bp * math.sin(m * thl) ** 2 * wl
        dy[3] = door / p["Jl"]
        dy[4] = wl
        if self.i_charge is not None:
            dy[self.i_charge] = i
        if self.delays:
            seen = self.seen(y)
            for probe, tau, j in self.delays:
                dy[j] = 2.0 * (seen[probe] - y[j]) / tau
        return dy

    @staticmethod
    def seen(y: np.ndarray) -> dict[str, Any]:
        """What each probe's sensor sees [A, rad/s] before its catalog effects (and the
        autoranging input's reading, which ``simulate`` makes from the events): the current
        in the supply's lead, the rotor's speed and the door's."""
        return {"current": y[0], "speed": y[1], "load_speed": y[3]}

    def events(self) -> list:
        """The event functions of the outside effects that need them: the autoranging
        input's switching up (|w| rising through w_up) and down (|w| falling through
        w_dn)."""
        if "autorange" not in self.fx:
            return []
        w_up, w_dn, _ = self.fx["autorange"]

        def up(t: float, y: np.ndarray) -> float:
            return abs(y[1]) - w_up

        def down(t: float, y: np.ndarray) -> float:
            return abs(y[1]) - w_dn

        up.direction, down.direction = 1.0, -1.0
        return [up, down]


# ---------------------------------------------------------------------- integration

def _span(model: DoorDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AX, {a:g}-{b:g} s: {why}")


def integrate(model: DoorDrive, t: np.ndarray, bp: np.ndarray, max_step: float
              ) -> tuple[np.ndarray, list[np.ndarray]]:
    """The states (n_states, t.size) at the increasing times ``t`` [s], from rest at 0, the
    integration restarted at every corner of the command ``bp`` [s, V]; and the times [s]
    of each of the model's events (``DoorDrive.events``), located by the integrator."""
    end = float(t[-1])
    corners = sorted({0.0, end, *(float(c) for c in bp[:, 0] if 0.0 < c < end)})
    out = np.empty((model.size, t.size))
    y0 = model.initial()
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


def range_gain(t: np.ndarray, ups: np.ndarray, downs: np.ndarray, g: float) -> np.ndarray:
    """The autoranging input's gain at the times ``t`` [s]: ``g`` in the low range (from the
    start, and from each switch down), 1 in the high one (from each switch up)."""
    gain = np.full(t.size, g)
    for x, high in sorted([(x, True) for x in ups] + [(x, False) for x in downs]):
        gain[t >= x] = 1.0 if high else g
    return gain


def idle_starts(bp: np.ndarray, end: float) -> np.ndarray:
    """The times [s] before ``end`` at which the command ``bp`` [s, V] reaches 0 V after a
    nonzero stretch (the auto-zero's triggers)."""
    hits = [float(bp[j, 0]) for j in range(1, len(bp))
            if bp[j, 1] == 0.0 and bp[j - 1, 1] != 0.0 and bp[j, 0] < end]
    return np.array(hits)


def auto_zero(t: np.ndarray, t_all: np.ndarray, charge: np.ndarray, zeros: np.ndarray,
              window: float) -> np.ndarray:
    """The current channel's zero [A] at the times ``t`` [s]: 0 from the start; from each
    trigger's window's end on, the mean current over the window (``charge``: int i dt at the
    times ``t_all`` [A s], which hold every trigger and window end)."""
    zero = np.zeros(t.size)
    for tz in zeros:
        if tz + window > t_all[-1]:
            continue
        qa, qb = np.interp([tz, tz + window], t_all, charge)
        zero[t >= tz + window] = (qb - qa) / window
    return zero


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor AX at the times ``t`` [s] (default: the nominal grid),
    from rest, with the parameters ``p`` over the declared ones (and ``fx["p"]`` over
    those): current [A] (the rig's shunt in the supply's lead), speed [rad/s] (the rig's DC
    tachogenerator on the motor's rear shaft end, rad/s at the rotor), and in the slow regime
    load_speed [rad/s] (the door, from the rig's incremental encoder on the column's foot,
    signed), plus the command ``u`` [V]. ``states``: add the bodies' speeds [rad/s] and
    angles [rad], the column's twist [rad] and torque [N m], the castor's q, the auto-zero's
    zero [A] and the autoranging input's switching times [s]."""
    fx = dict(fx or {})
    p = {**MOTOR_AX, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = DoorDrive(fx, p)
    zeros = idle_starts(bp, float(t[-1])) if "autozero" in fx else np.empty(0)
    if zeros.size:
        edges = np.concatenate([zeros, zeros + fx["autozero"]])
        t_all = np.union1d(t, edges[edges <= t[-1]])
        y_all, found = integrate(model, t_all, bp, MAX_STEP[regime])
        y = y_all[:, np.searchsorted(t_all, t)]
    else:
        y, found = integrate(model, t, bp, MAX_STEP[regime])
    u = np.interp(t, bp[:, 0], bp[:, 1])
    seen = model.seen(y)
    if zeros.size:
        seen["current"] = seen["current"] - auto_zero(t, t_all, y_all[model.i_charge], zeros,
                                                      fx["autozero"])
    for probe, _, j in model.delays:
        seen[probe] = 2.0 * y[j] - seen[probe]
    if "autorange" in fx:
        seen["speed"] = range_gain(t, found[0], found[1], fx["autorange"][2]) * seen["speed"]
    out = {probe: np.array(seen[probe], dtype=float) for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = u
    if states:
        twist, rate = y[2] / p["N"] - y[4], y[1] / p["N"] - y[3]
        out.update(rotor_angle=y[2], hub_angle=y[2] / p["N"], hub_speed=y[1] / p["N"],
                   door_angle=y[4], door_speed=y[3], armature_current=y[0],
                   column_twist=twist,
                   column_torque=np.array([model.column(a, b) for a, b in zip(twist, rate,
                                                                              strict=True)]))
        if model.i_castor is not None:
            out["castor_q"] = y[model.i_castor]
        if zeros.size:
            out["current_zero"] = auto_zero(t, t_all, y_all[model.i_charge], zeros,
                                            fx["autozero"])
        if "autorange" in fx:
            out.update(range_up=found[0], range_down=found[1])
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
