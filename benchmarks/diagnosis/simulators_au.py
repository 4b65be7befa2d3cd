"""Motor AU of the diagnosis benchmark: a hand-written scipy model of a 40 V permanent-magnet
brushed DC motor driving the WATERSTONE of a WET SHARPENING GRINDER (a bench-top wet grinder
for edge tools: a 250 mm natural waterstone turning slowly through a water trough, a leather
honing wheel on the other end of the main shaft), on the service bench with its trough filled
to the mark and no tool on the stone. The armature's 12-tooth pinion drives a 36-tooth gear
and a 10-tooth pinion on the same lay shaft a 90-tooth gear on the main shaft (a 27:1
reduction, `gear` G, declared rigid and lossless); the body ``hub`` is the main shaft with the
90-tooth gear and the honing wheel. The stone sits on the main shaft in its rubber-lined
centre bush between two clamping flanges: the bush's rubber is the compliance, a
`spring_damper` K between the hub and the body ``stone``. The stone turns at the hub's speed
on average (1:1), its angle its own. Forward is stone.w > 0 (the stone's top running away from
the operator); honing the other way round turns it backwards (stone.w < 0).

No circuitsim import, and no other set's simulator: an independent simulator, written from the
physics for netlists/motor_au_fast.yaml and motor_au_slow.yaml. It is evaluated at the record's
own sample times (``t_eval``), never on a grid that is then interpolated. Everything rests at
t = 0: no current, no speed, the hub and the stone at 0 and the bush unloaded; an outside
effect's own state at rest too.

The gear train is rigid (``gear`` G, ratio N = 27): the hub stands at th / N and turns at
w / N with the rotor; a torque T on it is T / N on the rotor. The bush is a spring and a
damper on the twist th / N - ths between the hub and the stone (``spring_damper`` K), its
torque on the stone

    Tk = Ks (th / N - ths) + Ds (w / N - ws).

The main shaft's two bronze bushes give the hub a dry friction (``friction`` Fh,
Th tanh(wh / 0.01), w_brk 0.1). The stone meets the trough's water: a viscous drag (``damper``
Bs) and a churning drag Cq ws sqrt(ws^2 + (0.5 rad/s)^2) (``btorque`` Churn).

State y = [i, w, th, ws, ths] (+ the stone's travelled angle for ``soak``, + the stirred-up
slurry's share for ``slurry``, + one Pade stage per delayed probe, in this order):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    ws, ths    the stone's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the armature with its pinion, and the main shaft):

    L di/dt   = v(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor
                + (X_hub - Th tanh((w / N) / 0.01) - Tk) / N
    Js dws/dt = Tk - Bs ws - Cq ws sqrt(ws^2 + 0.25) + X_stone

v(t) the command u(t) (the supply's output, or the grinder's controller's), Tm tanh(w / 0.01)
the brushes' and the motor's sleeve bearings' dry friction (``friction`` Fr, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, stone) receives
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

    soak      (U0 [N m], phase [rad], x0 [rad]): the stone stood with its lowest segment in
              the trough and is soaked unevenly: the heavy side's gravity torque
              -U0 exp(-x / x0) sin(ths + phase) on the stone, fading as the turning stone
              spreads and flings the excess water, x the angle it has travelled,
              dx/dt = sqrt(ws^2 + (0.01 rad/s)^2), x = 0 at rest
    cpower    (Pmax [W], dP [W]): the bench supply in its constant-power limit: it gives
              v = u Pmax / m, m = (u i + Pmax + sqrt((u i - Pmax)^2 + dP^2)) / 2 (u when
              u i is well below Pmax, Pmax / i above it)
    slurry    (g [1], w1 [rad/s], dw [rad/s], tau [s]): the grit and swarf settled in the
              trough are lifted by the stone's flow above about w1: the viscous drag becomes
              Bs (1 + g z) ws, the suspended share z following dz/dt = (h - z) / tau,
              h = (1 + tanh((a - w1) / dw)) / 2, a = sqrt(ws^2 + (0.01 rad/s)^2), z = 0 at
              rest (all settled)
    headroom  (Vr [V], Ro [ohm], dv [V]): the bench supply's linear pass regulator runs out
              of headroom: its output cannot rise above Vr - Ro i (its unregulated rail
              sagging under the current), nor fall below -Vr - Ro i: v = u - dv sp((u - Vr
              + Ro i) / dv) + dv sp((-u - Vr - Ro i) / dv), sp(x) = ln(1 + exp(x))
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AU [SI] (motor_au_fast.yaml, motor_au_slow.yaml): what the
#: diagnosis starts from; a record's true values differ in the parameters it frees
MOTOR_AU: dict[str, float] = {
    "R": 1.6, "L": 2.2e-3, "k": 0.09, "Jm": 6e-5, "bm": 2e-5, "Tm": 0.015,
    "N": 27.0, "Jh": 4e-3, "Th": 0.18, "Ks": 60.0, "Ds": 0.25, "Js": 0.03, "Bs": 0.015,
    "Cq": 1.2e-3,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: [rad/s] the churning drag: ws sqrt(ws^2 + W_CHURN^2)
W_CHURN = 0.5
#: [rad/s] the smooth |speed| of the outside effects' states
W_EPS = 0.01
#: the fast regime's command [s, V] (motor_au_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.03, 0.0), (0.2, 30.0), (0.38, 30.0), (0.44, 12.0),
               (0.52, 12.0), (0.64, -20.0), (0.72, -20.0), (0.76, 0.0), (0.8, 0.0))
#: the slow regime's logged command [s, V] (motor_au_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.5, 0.0), (1.5, 10.0), (3.0, 10.0), (3.5, 20.0), (5.0, 20.0),
               (5.6, 34.0), (7.2, 34.0), (7.8, 0.0), (8.4, 0.0), (8.9, -16.0),
               (10.6, -16.0), (11.0, 0.0), (12.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (10e3, 0.8), "slow": (200.0, 12.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "stone")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime, a fifth of the
#: mean interval in the slow one
MAX_STEP = {"fast": 1e-4, "slow": 1e-3}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.array(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def _soft_abs(x: float, eps: float) -> float:
    """sqrt(x^2 + eps^2)."""
    return math.sqrt(x * x + eps * eps)


def _softplus(x: float) -> float:
    """ln(1 + exp(x)), without overflow."""
    return max(x, 0.0) + math.log1p(math.exp(-abs(x)))


# ---------------------------------------------------------------------- the model

class StoneDrive:
    """Right-hand side of motor AU with one set of effects ``fx`` and parameters ``p`` [SI];
    ``ramp`` holds the command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.fx, self.p = fx, p
        self.n = p["N"]
        self.j_rotor = p["Jm"] + p["Jh"] / self.n ** 2
        size = 5
        #: index of the stone's travelled angle (``soak``) and of the slurry's share
        self.travel = self.silt = None
        if "soak" in fx:
            self.travel, size = size, size + 1
        if "slurry" in fx:
            self.silt, size = size, size + 1
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
        """The catalog's torque effects on ``body`` (empty when none)."""
        out = {}
        for key in ("visc", "coul", "offset", "stribeck", "cog"):
            value = self.fx.get(key, {}).get(body)
            if value:
                out[key] = value
        return out

    def extra_torque(self, body: str, w: float, angle: float) -> float:
        """The torque [N m] the catalog's effects give ``body`` at its speed ``w`` [rad/s]
        and angle ``angle`` [rad]."""
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

    def supply(self, t: float, i: float) -> float:
        """The voltage [V] across the loop's terminals: the command (linear within its
        segment), or less in the supply's constant-power limit (``cpower``) or out of its
        regulator's headroom (``headroom``)."""
        t0, u0, slope = self.ramp
        u = u0 + slope * (t - t0)
        if "cpower" in self.fx:
            pmax, dp = self.fx["cpower"]
            demand = u * i
            u *= pmax / (0.5 * (demand + pmax + math.sqrt((demand - pmax) ** 2 + dp * dp)))
        if "headroom" in self.fx:
            vr, ro, dv = self.fx["headroom"]
            u += dv * (_softplus((-u - vr - ro * i) / dv) - _softplus((u - vr + ro * i) / dv))
        return u

    def loop_drop(self, t: float, i: float, th: float, w: float) -> float:
        """The voltage [V] the loop takes besides the inductance's and the EMF's."""
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
        ell = self.p["L"]
        if "lsat" in self.fx:
            ipar, ratio = self.fx["lsat"]
            ell *= ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2)
        return ell

    def bush(self, twist: float, wrel: float) -> float:
        """The rubber bush's torque [N m] on the stone at the ``twist`` [rad] and the
        relative speed ``wrel`` [rad/s] (the hub's minus the stone's), with a play if
        ``gap``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        if "gap" not in self.fx:
            return ks * twist + ds * wrel
        half = 0.5 * self.fx["gap"]
        if abs(twist) <= half:
            return 0.0
        edge = half if twist > 0.0 else -half
        push = ks * (twist - edge) + ds * wrel
        return max(push, 0.0) if twist > 0.0 else min(push, 0.0)

    def __call__(self, t: float, y: np.ndarray) -> list[float]:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n, fx = self.p, self.n, self.fx
        i, w, th, ws, ths = (float(v) for v in y[:5])
        di = (self.supply(t, i) - self.loop_drop(t, i, th, w) - p["k"] * w) / \
            self.inductance(i)
        tk = self.bush(th / n - ths, w / n - ws)
        on_hub = self.extra_torque("hub", w / n, th / n) - p["Th"] * math.tanh(
            (w / n) / W_SWITCH)
        torque = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  + self.extra_torque("rotor", w, th) + (on_hub - tk) / n)
        visc = p["Bs"]
        extra: list[float] = []
        if self.travel is not None:
            u0, phase, x0 = fx["soak"]
            heavy = -u0 * math.exp(-float(y[self.travel]) / x0) * math.sin(ths + phase)
            extra.append(_soft_abs(ws, W_EPS))
        else:
            heavy = 0.0
        if self.silt is not None:
            g, w1, dw, tau = fx["slurry"]
            z = float(y[self.silt])
            visc *= 1.0 + g * z
            lift = 0.5 * (1.0 + math.tanh((_soft_abs(ws, W_EPS) - w1) / dw))
            extra.append((lift - z) / tau)
        on_stone = (tk - visc * ws - p["Cq"] * ws * _soft_abs(ws, W_CHURN) + heavy
                    + self.extra_torque("stone", ws, ths))
        seen = {"current": i, "speed": w, "load_speed": ws}
        pade = [2.0 * (seen[probe] - float(y[k])) / tau for probe, tau, k in self.delays]
        return [di, torque / self.j_rotor, w, on_stone / p["Js"], ws, *extra, *pade]


# ---------------------------------------------------------------------- integration

def _piece(model: StoneDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AU, {a:g}-{b:g} s: {why}")


def integrate(model: StoneDrive, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor AU at the times ``t`` [s] (default: the nominal grid),
    from rest, with the parameters ``p`` over the declared ones (and ``fx["p"]`` over
    those): current [A] (the bench's shunt in the supply's lead, or the grinder
    controller's shunt), speed [rad/s]
    (the motor's encoder, rad/s at the rotor), and in the slow regime load_speed [rad/s]
    (the stone, from the controller's optical sensor reading the reflective marks on the
    stone's outer flange, past the bush), plus the command ``u`` [V]. ``states``: add the
    bodies' speeds [rad/s] and angles [rad], the bush's torque [N m], the terminal voltage
    [V] and the outside effects' states."""
    fx = dict(fx or {})
    p = {**MOTOR_AU, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = StoneDrive(fx, p)
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
        twist, wrel = y[2] / p["N"] - y[4], y[1] / p["N"] - y[3]
        torque = np.array([model.bush(a, b) for a, b in zip(twist, wrel, strict=True)])
        volts = []
        for tk, ik in zip(t, y[0], strict=True):
            seg = max(0, min(int(np.searchsorted(bp[:, 0], tk, side="right")) - 1,
                             len(bp) - 2))
            a, b = bp[seg, 0], bp[seg + 1, 0]
            model.ramp = (a, bp[seg, 1], (bp[seg + 1, 1] - bp[seg, 1]) / (b - a))
            volts.append(model.supply(float(tk), float(ik)))
        out.update(rotor_angle=y[2], hub_angle=y[2] / p["N"], hub_speed=y[1] / p["N"],
                   stone_angle=y[4], stone_speed=y[3], armature_current=y[0],
                   bush_twist=twist, bush_torque=torque, terminal_voltage=np.array(volts))
        if model.travel is not None:
            out.update(stone_travel=y[model.travel])
        if model.silt is not None:
            out.update(slurry_share=y[model.silt])
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
