"""Motor AY of the diagnosis benchmark: a hand-written scipy model of a 36 V permanent-magnet
brushed DC gearmotor (a 2-pole, 7-slot ferrite motor) in the prism drive of a TRI-VISION
(rotating-prism) BILLBOARD, on the sign maker's test rig: a full-size test frame with a row of
twelve 3 m aluminium prisms (three sign faces each) lying horizontally one above another,
0.6 kg m^2 about their axes together. The motor drives a 24:1 worm gearbox whose output
sprocket turns the row's drive shaft through a 4:1 chain stage (`gear` G, 96:1 in all, declared
rigid and lossless); the body ``hub`` is the chain stage's big sprocket with the drive shaft's
driven end, turning in the gearbox's output bearing and its lip seal. The drive shaft (a 3 m,
20 mm steel line shaft standing upright beside the prisms' ends, driving each prism through a
1:1 bevel pair) is a torsion spring from the sprocket to the row, a `spring_damper` K between
the hub and the body ``row`` (the twelve prisms with their bevel gears), the row's angle its
own. Forward is row.w > 0 (the prisms' front faces turning upwards); the row turns at the hub's
speed on average (1:1).

No circuitsim import, and no other set's simulator: an independent simulator, written from the
physics for netlists/motor_ay_fast.yaml and motor_ay_slow.yaml. It is evaluated at the record's
own sample times (``t_eval``), never on a grid that is then interpolated. Everything rests at
t = 0: no current, no speed, the hub and the row at 0 and the shaft untwisted.

The drive is rigid (``gear`` G, ratio N = 96): the hub stands at th / N and turns at w / N with
the rotor; a torque T on it is T / N on the rotor. The line shaft is a spring and a damper on
the twist th / N - thl between the hub and the row (``spring_damper`` K), its torque on the row

    Tk = Ks (th / N - thl) + Ds (w / N - wl).

The gearbox's output bearing and lip seal give the hub a dry friction (``friction`` Fh,
Th tanh(wh / 0.01), w_brk 0.1). The prisms turn in their nylon top and bottom bushes: a dry
friction (``friction`` Fl, Tl tanh(wl / 0.01), w_brk 0.1); the air the prisms' edges sweep
round, and the bevel pairs' grease, give a viscous drag (``damper`` Bl).

State y = [i, w, th, wl, thl] (+ the outside effects' states -- the loose prism's speed and
angle, the notch filter's two states --, + one Pade stage per delayed probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wl, thl    the row's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the armature with the worm, and the hub):

    L di/dt   = v(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor
                + (X_hub - Th tanh((w / N) / 0.01) - Tk) / N
    Jl dwl/dt = Tk - Tl tanh(wl / 0.01) - Bl wl + X_row

v(t) the rig supply's output u(t) (the command, linear between its breakpoints), Tm tanh(w /
0.01) the brushes' and the motor's bearings' dry friction (``friction`` Fr, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, row) receives
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

    loose     (share [1], delta [rad], Kc [N m/rad], Dc [N m s/rad], x0 [rad]): one prism
              of the row, the fraction ``share`` of the declared Jl, Tl and Bl, is driven
              through a lost motion: its drive dog rides free in a slot of +-delta of the
              row's angle. The prism is a body of its own (speed wp, angle thp, from rest,
              x = thl - thp = x0 at the start); the row keeps (1 - share) of Jl, Tl and Bl
              and receives -Tc, the prism receives Tc - share (Tl tanh(wp / 0.01) + Bl wp),
              Tc = Kc (x -+ delta) + Dc (wl - wp) while |x| > delta (the dog against the
              slot's end, the damping never pulling them apart), 0 inside the slot
    notch     (f0 [Hz], Q [1]): the acquisition's current channel has its mains-hum notch
              filter switched on: the current reads i - z, z the band-pass
              (w0 / Q) s / (s^2 + (w0 / Q) s + w0^2) of i, w0 = 2 pi f0, from rest; the motor
              itself is not touched
    wrap      W [rad/s]: the encoder interface's speed word wraps: load_speed reads
              ((y + W) mod 2 W) - W, y the row's speed; the motor itself is not touched
    trip      (It [A], Tr [s], Rq [ohm]): the rig's electronic fuse in the motor's positive
              lead (a MOSFET switch with its own current sense) opens whenever the forward
              current i rises through It (the armature's current then flows through the
              fuse's bleed resistor Rq, in series; a reverse current would pass its body
              diode, so it never trips backwards) and retries, closing again Tr after it
              opened (closed at the start): hiccup mode; exact switching times (events)
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AY [SI] (motor_ay_fast.yaml, motor_ay_slow.yaml): what the
#: diagnosis starts from; a record's true values differ in the parameters it frees
MOTOR_AY: dict[str, float] = {
    "R": 1.6, "L": 3.2e-3, "k": 0.095, "Jm": 1.1e-4, "bm": 2.5e-5, "Tm": 0.02,
    "N": 96.0, "Jh": 0.05, "Th": 0.5, "Ks": 450.0, "Ds": 2.5, "Jl": 0.6,
    "Tl": 2.4, "Bl": 0.8,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_ay_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.13, 30.0), (0.21, 30.0), (0.235, 12.0),
               (0.29, 12.0), (0.36, -20.0), (0.42, -20.0), (0.45, 0.0), (0.50, 0.0))
#: the slow regime's logged command [s, V] (motor_ay_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.5, 0.0), (1.5, 10.0), (3.8, 10.0), (4.4, 30.0), (6.2, 30.0),
               (6.6, 0.0), (7.2, 0.0), (8.0, -16.0), (10.6, -16.0), (11.1, 0.0), (12.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.5), "slow": (200.0, 12.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "row")
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

class PrismDrive:
    """Right-hand side of motor AY with the effects ``fx`` and the parameters ``p`` [SI];
    ``seg`` holds the command's current segment (t0 [s], u0 [V], slope [V/s]) and ``closed``
    the electronic fuse's state (``trip``)."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.fx, self.p = fx, p
        self.n = p["N"]
        self.jr = p["Jm"] + p["Jh"] / self.n ** 2
        size = 5
        #: indices of the outside effects' states
        self.i_loose = self.i_notch = None
        if "loose" in fx:
            self.i_loose, size = size, size + 2
        if "notch" in fx:
            self.i_notch, size = size, size + 2
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
        #: the row's own share of Jl, Tl and Bl (the loose prism takes the rest)
        self.keep = 1.0 - fx["loose"][0] if "loose" in fx else 1.0
        self.seg = (0.0, 0.0, 0.0)
        self.closed = True

    def initial(self) -> np.ndarray:
        """The state at rest at t = 0 (the loose prism x0 behind the row)."""
        y0 = np.zeros(self.size)
        if self.i_loose is not None:
            y0[self.i_loose + 1] = -self.fx["loose"][4]
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
        r += fx.get("Rser", 0.0) + fx.get("Rs", 0.0)
        if not self.closed:
            r += fx["trip"][2]
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

    @staticmethod
    def play(x: float, v: float, half: float, ks: float, ds: float) -> float:
        """A spring ``ks`` and damper ``ds`` across a play of +-``half`` [rad] at the twist
        ``x`` [rad] and its rate ``v`` [rad/s]: nothing inside the play, the damping never
        pulling the sides together."""
        if -half <= x <= half:
            return 0.0
        if x > 0.0:
            return max(ks * (x - half) + ds * v, 0.0)
        return min(ks * (x + half) + ds * v, 0.0)

    def shaft(self, x: float, v: float) -> float:
        """The line shaft's torque on the row [N m] at the twist ``x`` [rad] and the twist
        rate ``v`` [rad/s] (the hub's minus the row's), with a play if ``gap``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        gap = self.fx.get("gap")
        if not gap:
            return ks * x + ds * v
        return self.play(x, v, 0.5 * gap, ks, ds)

    def __call__(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n, fx = self.p, self.n, self.fx
        i, w, th, wl, thl = y[0], y[1], y[2], y[3], y[4]
        u = self.command(t)
        dy = np.empty(self.size)
        dy[0] = (u - self.loop(t, i, th, w) - p["k"] * w) / self.inductance(i)
        tk = self.shaft(th / n - thl, w / n - wl)
        wh = w / n
        hub = self.body_torque("hub", wh, th / n) - p["Th"] * math.tanh(wh / W_SWITCH)
        dy[1] = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                 + self.body_torque("rotor", w, th) + (hub - tk) / n) / self.jr
        dy[2] = w
        keep = self.keep
        row = (tk - keep * (p["Tl"] * math.tanh(wl / W_SWITCH) + p["Bl"] * wl)
               + self.body_torque("row", wl, thl))
        if self.i_loose is not None:
            share, delta, kc, dc, _ = fx["loose"]
            j = self.i_loose
            wp, thp = y[j], y[j + 1]
            tc = self.play(thl - thp, wl - wp, delta, kc, dc)
            row -= tc
            dy[j] = (tc - share * (p["Tl"] * math.tanh(wp / W_SWITCH) + p["Bl"] * wp)) \
                / (share * p["Jl"])
            dy[j + 1] = wp
        dy[3] = row / (keep * p["Jl"])
        dy[4] = wl
        if self.i_notch is not None:
            f0, q = fx["notch"]
            w0 = 2.0 * math.pi * f0
            j = self.i_notch
            dy[j] = y[j + 1]
            dy[j + 1] = i - w0 * w0 * y[j] - (w0 / q) * y[j + 1]
        if self.delays:
            seen = self.seen(y)
            for probe, tau, j in self.delays:
                dy[j] = 2.0 * (seen[probe] - y[j]) / tau
        return dy

    def seen(self, y: np.ndarray) -> dict[str, Any]:
        """What each probe's sensor sees [A, rad/s] before its catalog effects: the current
        in the supply's lead (through the notch if ``notch``), the rotor's speed and the
        row's (the drive-end prism's, from the encoder under it)."""
        cur = y[0]
        if self.i_notch is not None:
            f0, q = self.fx["notch"]
            cur = cur - (2.0 * math.pi * f0 / q) * y[self.i_notch + 1]
        return {"current": cur, "speed": y[1], "load_speed": y[3]}

    def trip_event(self):
        """The electronic fuse's opening: the forward current i rising through It (None
        without ``trip``)."""
        if "trip" not in self.fx:
            return None
        limit = self.fx["trip"][0]

        def opens(t: float, y: np.ndarray) -> float:
            return y[0] - limit

        opens.terminal, opens.direction = True, 1.0
        return opens


# ---------------------------------------------------------------------- integration

def _span(model: PrismDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
          max_step: float, event) -> tuple[np.ndarray, float | None, np.ndarray | None]:
    """The states at ``t_out`` [s] from ``y0`` at ``a`` to ``b`` [s]: LSODA, Radau if LSODA
    fails; with a terminal ``event``, stopped there: (the states at the times of ``t_out``
    before it, its time [s], the state then), else (states, None, None)."""
    why = ""
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), y0, method=method, t_eval=t_out, rtol=RTOL,
                        atol=ATOL, max_step=max_step,
                        events=[event] if event is not None else None)
        if not sol.success or not np.isfinite(sol.y).all():
            why = sol.message
            continue
        if sol.status == 1:
            te = float(sol.t_events[0][0])
            ys = sol.y[:, sol.t < te]
            return ys, te, np.array(sol.y_events[0][0], dtype=float)
        if sol.y.shape[1] == t_out.size:
            return sol.y, None, None
        why = "missing outputs"
    raise RuntimeError(f"motor AY, {a:g}-{b:g} s: {why}")


def integrate(model: PrismDrive, t: np.ndarray, bp: np.ndarray, max_step: float
              ) -> tuple[np.ndarray, list[tuple[float, str]]]:
    """The states (n_states, t.size) at the increasing times ``t`` [s], from rest at 0, the
    integration restarted at every corner of the command ``bp`` [s, V] and at every switch
    of the electronic fuse (``trip``: opened at the event i = It, closed Tr later); and the
    fuse's switching times [s] with what it did."""
    end = float(t[-1])
    corners = sorted({0.0, end, *(float(c) for c in bp[:, 0] if 0.0 < c < end)})
    out = np.empty((model.size, t.size))
    y0 = model.initial()
    event = model.trip_event()
    switches: list[tuple[float, str]] = []
    a, reclose = 0.0, math.inf
    while a < end:
        b = min(next(c for c in corners if c > a), reclose)
        mid = 0.5 * (a + b)
        j = int(np.searchsorted(bp[:, 0], mid)) - 1
        slope = float(bp[j + 1, 1] - bp[j, 1]) / float(bp[j + 1, 0] - bp[j, 0])
        model.seg = (a, float(np.interp(a, bp[:, 0], bp[:, 1])), slope)
        last = b == end
        inside = (t >= a) & ((t <= b) if last else (t < b))
        t_out = t[inside] if last else np.append(t[inside], b)
        ys, te, ye = _span(model, a, b, y0, t_out, max_step,
                           event if model.closed else None)
        idx = np.flatnonzero(inside)
        if te is None:
            out[:, idx] = ys[:, :idx.size]
            y0 = ys[:, -1].copy()
            if b == reclose:
                model.closed, reclose = True, math.inf
                switches.append((b, "closes"))
            a = b
        else:
            k = ys.shape[1]
            out[:, idx[:k]] = ys
            model.closed, reclose = False, te + model.fx["trip"][1]
            switches.append((te, "opens"))
            y0, a = ye.copy(), te
    return out, switches


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor AY at the times ``t`` [s] (default: the nominal grid),
    from rest, with the parameters ``p`` over the declared ones (and ``fx["p"]`` over
    those): current [A] (the rig's shunt in the supply's lead), speed [rad/s] (the rig's DC
    tachogenerator on the motor's rear shaft end, rad/s at the rotor), and in the slow regime
    load_speed [rad/s] (the row, from the rig's incremental encoder on the drive-end
    prism's shaft end, signed), plus the command ``u`` [V]. ``states``: add the bodies'
    speeds [rad/s] and angles [rad], the shaft's twist [rad] and torque [N m], the loose
    prism's speed and angle, and the electronic fuse's switching times [s]."""
    fx = dict(fx or {})
    p = {**MOTOR_AY, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = PrismDrive(fx, p)
    y, switches = integrate(model, t, bp, MAX_STEP[regime])
    u = np.interp(t, bp[:, 0], bp[:, 1])
    seen = model.seen(y)
    for probe, _, j in model.delays:
        seen[probe] = 2.0 * y[j] - seen[probe]
    out = {probe: np.array(seen[probe], dtype=float) for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    if "wrap" in fx and "load_speed" in out:
        big = fx["wrap"]
        out["load_speed"] = np.mod(out["load_speed"] + big, 2.0 * big) - big
    out["u"] = u
    if states:
        twist, rate = y[2] / p["N"] - y[4], y[1] / p["N"] - y[3]
        out.update(rotor_angle=y[2], hub_angle=y[2] / p["N"], hub_speed=y[1] / p["N"],
                   row_angle=y[4], row_speed=y[3], armature_current=y[0],
                   shaft_twist=twist,
                   shaft_torque=np.array([model.shaft(a, b) for a, b in zip(twist, rate,
                                                                            strict=True)]))
        if model.i_loose is not None:
            out.update(prism_speed=y[model.i_loose], prism_angle=y[model.i_loose + 1])
        if "trip" in fx:
            out["fuse_opens"] = np.array([x for x, what in switches if what == "opens"])
            out["fuse_closes"] = np.array([x for x, what in switches if what == "closes"])
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
