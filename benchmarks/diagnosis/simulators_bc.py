"""Motor BC of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC gearmotor (a 4-pole, 18-slot ferrite motor) driving the winch of a THEATRE'S
MOTORISED FLY-BAR HOIST (a line-shaft winch for one counterweighted line set) on the maker's
test rig: the motor drives a two-stage helical gearbox (48:1, `gear` G, declared rigid and
lossless) to the winch's grooved wire-rope drum; the body ``drum`` is the drum with its
wound rope, the gearbox's output shaft and its brake disc, turning in the drum's two
pillow-block bearings with the ropes bending onto it. The drum winds four 6 mm lift lines up
over the rig's head block and loft blocks (14 m of rope) to a test batten whose weight the
counterweight arbor balances exactly (the line set in trim): the ropes' stretch is a
spring and a damper, `spring_damper` K, between the drum and the body ``batten`` (the batten,
its test load and the arbor with its weights, 520 kg in all, reflected to the drum's pitch
radius of 80 mm: its angle is its travel over 0.08 m). Forward is batten.w > 0 (raising the
batten: the out direction of the line set); the batten moves with the drum on average (1:1).

No circuitsim import, and no other set's simulator: an independent simulator, written from the
physics for netlists/motor_bc_fast.yaml and motor_bc_slow.yaml. It is evaluated at the
record's own sample times (``t_eval``), never on a grid that is then interpolated. Everything
rests at t = 0: no current, no speed, the drum and the batten at 0 and the ropes at their
static stretch (the counterweight balances the batten: no net weight on the ropes' twist).

The gearbox is rigid (``gear`` G, ratio N = 48): the drum stands at th / N and turns at
w / N with the rotor; a torque T on it is T / N on the rotor. The ropes are a spring and a
damper on the stretch th / N - thb between the drum and the batten (``spring_damper`` K),
their pull on the batten

    Tk = Ks (th / N - thb) + Ds (w / N - wb).

The drum's pillow-block bearings and the ropes' bending onto it give the drum a dry friction
(``friction`` Fd, Td tanh(wd / 0.01), w_brk 0.1). The arbor's guide shoes in the T-track and
the loft blocks' and head block's sheaves give the batten a dry friction (``friction`` Fb,
Tb tanh(wb / 0.01), w_brk 0.1) and the sheaves' sealed bearings' grease a viscous drag
(``damper`` Bb).

State y = [i, w, th, wb, thb] (+ the outside effects' states -- the brake coil's current, the
shunt's heating, the ropes' permanent set --, + one Pade stage per delayed probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wb, thb    the batten's speed and travel over the drum's radius [rad/s, rad] (0: start)

Equations (Jr = Jm + Jd / N^2: the armature with the gearbox's input, and the drum):

    L di/dt   = v(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor
                + (X_drum - Td tanh((w / N) / 0.01) - Tk) / N
    Jb dwb/dt = Tk - Tb tanh(wb / 0.01) - Bb wb + X_batten

v(t) the rig's four-quadrant supply's output u(t) (the command, linear between its
breakpoints), Tm tanh(w / 0.01) the brushes' and the motor's bearings' dry friction
(``friction`` Fr, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, drum, batten) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in K (no pull while |stretch| < gap / 2,
              else Ks (stretch -+ gap / 2) + Ds w_rel, the damping never pulling the sides
              together)
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: parameters changed (the record's true values of the declared
              ones the user frees, an inertia's or the inductance's correction)

and outside the catalog:

    layer     (delta [1], th1 [rad], wd [rad]): the lift lines run out of the drum's grooves
              at the drum's angle th1 and climb onto a second layer: the drum's working
              radius is r (1 + delta sig((thd - th1) / wd)), sig(x) = 1 / (1 + exp(-x)), thd
              = th / N; the rope taken up is S(thd) = thd + delta wd (sp((thd - th1) / wd)
              - sp(-th1 / wd)), sp(x) = ln(1 + exp(x)) (in the drum's nominal radius); the
              ropes' stretch is S(thd) - thb, its rate rho w / N - wb, rho = dS/dthd, and the
              drum takes rho Tk (the batten still Tk)
    brake     (Rc [ohm], Lc [H], Ir [A], dI [A], Tb [N m], Ve [V]): the gearmotor's
              spring-applied holding brake, its coil fed from the motor's terminals through a
              bridge rectifier: Lc dic/dt = a(u) - Rc ic, a(u) = sqrt(u^2 + Ve^2) - Ve (ic >= 0,
              0 at rest); the supply's shunt carries i + tanh(u / Ve) ic; the rotor receives
              -Tb (1 - sig((ic - Ir) / dI)) tanh(w / 0.01) (the brake holds until its coil's
              current pulls the armature plate off)
    thermo    (Io [A], I0 [A], tau [s]): the shunt's manganin-to-copper junctions heat
              unevenly with its loss: h follows (i / I0)^2 with dh/dt = ((i / I0)^2 - h) / tau,
              h = 0 at rest, and the current reads i + Io h (a thermoelectric offset); the
              motor itself is not touched
    bedding   (c [rad / N m], tau [s], e [rad]): new lift lines bed in (constructional
              stretch): their permanent set z (in the batten's travel over the drum's radius,
              0 at the start) creeps towards c Tk whenever the pull exceeds what set it,
              dz/dt = e sp((c Tk - z) / e) / tau, never back; the pull is
              Tk = Ks (th / N - thb - z) + Ds (w / N - wb)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor BC [SI] (motor_bc_fast.yaml, motor_bc_slow.yaml): what the
#: diagnosis starts from; a record's true values differ in the parameters it frees
MOTOR_BC: dict[str, float] = {
    "R": 0.2, "L": 5.0e-4, "k": 0.058, "Jm": 2.1e-4, "bm": 5.5e-5, "Tm": 0.045,
    "N": 48.0, "Jd": 0.14, "Td": 1.6, "Ks": 2600.0, "Ds": 7.5, "Jb": 3.3,
    "Tb": 18.0, "Bb": 2.2,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_bc_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.012, 0.0), (0.14, 24.0), (0.20, 24.0), (0.22, 12.0),
               (0.26, 12.0), (0.32, -20.0), (0.41, -20.0), (0.43, 0.0), (0.45, 0.0))
#: the slow regime's logged command [s, V] (motor_bc_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.4, 0.0), (1.6, 12.0), (4.5, 12.0), (5.2, 24.0), (8.0, 24.0),
               (8.6, 0.0), (9.4, 0.0), (10.4, -20.0), (13.8, -20.0), (14.4, 0.0),
               (16.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.45), "slow": (100.0, 16.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "drum", "batten")
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


def softplus(x: float) -> float:
    """ln(1 + exp(x)), without overflow."""
    return max(x, 0.0) + math.log1p(math.exp(-abs(x)))


# ---------------------------------------------------------------------- the model

class FlyHoist:
    """Right-hand side of motor BC with the effects ``fx`` and the parameters ``p`` [SI];
    ``seg`` holds the command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.fx, self.p = fx, p
        self.n = p["N"]
        size = 5
        #: indices of the outside effects' states (None when off)
        self.i_coil = self.i_heat = self.i_set = None
        if "brake" in fx:
            self.i_coil, size = size, size + 1
        if "thermo" in fx:
            self.i_heat, size = size, size + 1
        if "bedding" in fx:
            self.i_set, size = size, size + 1
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
        #: Jr: the rotor with the drum at the rotor's scale
        self.jr = p["Jm"] + p["Jd"] / self.n ** 2
        self.seg = (0.0, 0.0, 0.0)

    def initial(self) -> np.ndarray:
        """The state at rest at t = 0."""
        return np.zeros(self.size)

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

    def taken_up(self, thd: float) -> tuple[float, float]:
        """The rope the drum has taken up at its angle ``thd`` [rad] (in its nominal radius)
        and the working radius's ratio rho = dS/dthd [1] (1, 1 without ``layer``)."""
        if "layer" not in self.fx:
            return thd, 1.0
        delta, th1, wd = self.fx["layer"]
        s = thd + delta * wd * (softplus((thd - th1) / wd) - softplus(-th1 / wd))
        return s, 1.0 + delta * sig((thd - th1) / wd)

    def ropes(self, x: float, v: float) -> float:
        """The lift lines' pull on the batten [N m] at the stretch ``x`` [rad] and the
        stretch rate ``v`` [rad/s] (the drum's minus the batten's), with a play if ``gap``
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

    def brake_torque(self, y: np.ndarray, w: float) -> float:
        """The holding brake's torque on the rotor [N m] (0 without ``brake``)."""
        if self.i_coil is None:
            return 0.0
        _, _, ir, di, tb, _ = self.fx["brake"]
        held = 1.0 - sig((y[self.i_coil] - ir) / di)
        return -tb * held * math.tanh(w / W_SWITCH)

    def __call__(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n, fx = self.p, self.n, self.fx
        i, w, th, wb, thb = y[0], y[1], y[2], y[3], y[4]
        u = self.command(t)
        dy = np.empty(self.size)
        k = p["k"]
        dy[0] = (u - self.loop(t, i, th, w) - k * w) / self.inductance(i)
        motor = (k * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                 + self.body_torque("rotor", w, th) + self.brake_torque(y, w))
        thd, wd = th / n, w / n
        s, rho = self.taken_up(thd)
        x = s - thb
        if self.i_set is not None:
            x -= y[self.i_set]
        tk = self.ropes(x, rho * wd - wb)
        drum = self.body_torque("drum", wd, thd) - p["Td"] * math.tanh(wd / W_SWITCH)
        dy[1] = (motor + (drum - rho * tk) / n) / self.jr
        dy[2] = w
        batten = (tk - p["Tb"] * math.tanh(wb / W_SWITCH) - p["Bb"] * wb
                  + self.body_torque("batten", wb, thb))
        dy[3] = batten / p["Jb"]
        dy[4] = wb
        if self.i_coil is not None:
            rc, lc, _, _, _, ve = fx["brake"]
            dy[self.i_coil] = (math.sqrt(u * u + ve * ve) - ve - rc * y[self.i_coil]) / lc
        if self.i_heat is not None:
            _, i0, tau = fx["thermo"]
            dy[self.i_heat] = ((i / i0) ** 2 - y[self.i_heat]) / tau
        if self.i_set is not None:
            c, tau, e = fx["bedding"]
            dy[self.i_set] = e * softplus((c * tk - y[self.i_set]) / e) / tau
        if self.delays:
            seen = self.seen(y, np.array(u))
            for probe, tau, j in self.delays:
                dy[j] = 2.0 * (seen[probe] - y[j]) / tau
        return dy

    def seen(self, y: np.ndarray, u: np.ndarray) -> dict[str, Any]:
        """What each probe's sensor sees [A, rad/s] before its catalog effects, at the states
        ``y`` and the supply's output ``u`` [V]: the current in the supply's lead (with the
        brake coil's, and the shunt's thermoelectric offset), the rotor's speed and the
        batten's."""
        cur = y[0]
        if self.i_coil is not None:
            cur = cur + np.tanh(u / self.fx["brake"][5]) * y[self.i_coil]
        if self.i_heat is not None:
            cur = cur + self.fx["thermo"][0] * y[self.i_heat]
        return {"current": cur, "speed": y[1], "load_speed": y[3]}


# ---------------------------------------------------------------------- integration

def _span(model: FlyHoist, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor BC, {a:g}-{b:g} s: {why}")


def integrate(model: FlyHoist, t: np.ndarray, bp: np.ndarray, max_step: float) -> np.ndarray:
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
    """Noise-free probes of motor BC at the times ``t`` [s] (default: the nominal grid),
    from rest, with the parameters ``p`` over the declared ones (and ``fx["p"]`` over
    those): current [A] (the rig's shunt in the supply's lead), speed [rad/s] (the rig's DC
    tachogenerator on the motor's rear shaft end, rad/s at the rotor), and in the slow
    regime load_speed [rad/s] (the batten's speed over the drum's pitch radius, from the
    rig's encoder on the head block's sheave, signed), plus the command ``u`` [V].
    ``states``: add the bodies' speeds [rad/s] and angles [rad], the ropes' stretch [rad]
    and pull [N m], and the outside effects' states."""
    fx = dict(fx or {})
    p = {**MOTOR_BC, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = FlyHoist(fx, p)
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
        thd = y[2] / p["N"]
        taken = np.array([model.taken_up(float(a)) for a in thd])
        stretch = taken[:, 0] - y[4]
        if model.i_set is not None:
            stretch = stretch - y[model.i_set]
        rate = taken[:, 1] * y[1] / p["N"] - y[3]
        out.update(rotor_angle=y[2], drum_angle=thd, drum_speed=y[1] / p["N"],
                   batten_travel=y[4], batten_speed=y[3], armature_current=y[0],
                   ropes_stretch=stretch,
                   ropes_pull=np.array([model.ropes(a, b) for a, b in
                                        zip(stretch, rate, strict=True)]))
        for name, j in (("coil_current", model.i_coil), ("shunt_heat", model.i_heat),
                        ("ropes_set", model.i_set)):
            if j is not None:
                out[name] = y[j]
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
