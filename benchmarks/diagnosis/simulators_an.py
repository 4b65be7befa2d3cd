"""Motor AN of the diagnosis benchmark: a hand-written scipy model of a 48 V permanent-magnet
brushed DC motor (a 4-pole, 18-slot armature inside a ferrite-magnet can) in a REAR GEARED
E-BIKE HUB on the workshop's end-of-line TEST RIG, the bike's rear wheel clamped on a fluid
turbo trainer. The armature drives the hub shell through a single-stage planetary gear (a
5:1 reduction, `gear` G, declared rigid and lossless: a clutchless "regen" hub, which turns
the wheel both ways); the body ``hub`` is the whole wheel (the shell, the spokes, the rim and
the tyre, 26 inch, r = 0.33 m). The tyre presses on the trainer's 57 mm steel roller; the
tyre's tangential (shear and tread) compliance at the contact is a `spring_damper` K
between the hub and the body ``roller``, the roller with the trainer's flywheel reflected to
the wheel's radius (the body's angle is the tyre's travel over r, 1 rad = 0.33 m). Running
forward is roller.w > 0.

No circuitsim import: an independent simulator (the thirty-seventh of the benchmark),
written from the physics for netlists/motor_an_fast.yaml and motor_an_slow.yaml. It is
evaluated at the record's own sample times (``t_eval``), never on a grid that is then
interpolated. Everything rests at t = 0: no current, no speed, the wheel and the roller at 0
and the tyre untwisted; an outside effect's own bodies at rest too (the pedal hanging).

The planetary gear is rigid (``gear`` G, ratio N = 5): the wheel stands at th / N and turns
at w / N with the rotor; a torque T on it is T / N on the rotor. The tyre's contact is a
spring and a damper on the twist th / N - thr between the wheel and the roller
(``spring_damper`` K), its torque on the roller

    Tk = Ks (th / N - thr) + Ds (w / N - wr).

The roller meets three declared loads (all reflected to the wheel's radius): its bearings (a
viscous drag Bf wr, ``damper``), the tyre's rolling resistance on the small roller (a dry
friction Tf tanh(wr / 0.01), ``friction``, w_brk 0.1) and the trainer's fluid resistance
unit, a quadratic drag Cf wr sqrt(wr^2 + (1 rad/s)^2) (``btorque`` Fluid).

State y = [i, w, th, wr, thr] (+ the hub shell's own speed and angle wh, thh for ``clutch``,
+ the rim's speed and angle wm, thm for ``windup``, + the impeller's speed and angle wi, thi
for ``magdrive``, + the cranks' speed and angle wc, thc for ``pedal``, + one Pade stage per
delayed probe, in this order):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wr, thr    the roller's speed and angle [rad/s, rad] (the tyre's travel over r; 0: where
               it starts)

Equations (Jr = Jm + Jw / N^2: the armature with the planetary's sun, and the wheel):

    L di/dt   = u(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor + (X_hub - Tk) / N
    Jf dwr/dt = Tk - Bf wr - Tf tanh(wr / 0.01) - Cf wr sqrt(wr^2 + 1) + X_roller

Tm tanh(w / 0.01) is the brushes' and the bearings' dry friction with the planetary's
(``friction``, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, roller) receives
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

    clutch    (Jk [kg m^2], Dl [N m s/rad], e [rad/s]): a clutched hub: a one-way roller
              clutch between the planetary's carrier (Jk, part of the declared Jw, turning
              with the rotor at w / N) and the hub shell (the rest of the wheel, its own speed
              and angle wh, thh): the shell receives Dl (x + sqrt(x^2 + e^2)) / 2, x = w / N
              - wh, the carrier the opposite: the carrier drives the wheel forward, and the
              wheel overruns it freely (it cannot be driven backwards); K lies between the
              wheel and the roller
    windup    (Jsh [kg m^2], Kw [N m/rad], Dw [N m s/rad]): a radially laced wheel: the
              spokes are a torsional spring and damper (Kw, Dw) between the hub shell (Jsh,
              part of the declared Jw, turning with the rotor) and the rim with the tyre (Jw -
              Jsh, its own speed and angle wm, thm): the rim receives Kw (th / N - thm) + Dw
              (w / N - wm); K lies between the rim and the roller
    magdrive  (Ji [kg m^2], Tmax [N m], P): the fluid unit's impeller (Ji, part of the
              declared Jf, its own speed and angle wi, thi) is driven through the sealed
              unit's magnetic coupling: it receives Tmax sin(P (thr - thi)), the roller the
              opposite (Tmax and P at the wheel's radius: the physical coupling's pull-out
              torque and pole pairs times r / r_roller), and the fluid's drag
              -Cf wi sqrt(wi^2 + 1) acts on the impeller instead of the roller
    pedal     (Jc [kg m^2], Df [N m s/rad], Tp [N m], Dl [N m s/rad], e [rad/s], Tb [N m],
              G [N m], rho): the gummed freewheel of the cassette drags the cranks
              round (ghost pedalling): the cranks, chainring, chain and sprockets (Jc, at the
              sprocket's speed wc, angle thc) receive from the wheel
              Tg = Df x + Tp tanh(x / 0.01) + Dl (x - sqrt(x^2 + e^2)) / 2, x = wh - wc (wh
              the wheel's speed: the freewheel drags while the wheel overruns, and locks when
              the cranks overrun the wheel), the wheel the opposite; the bottom bracket's and
              the chain's friction -Tb tanh(wc / 0.01) and the one pedal's weight
              -G sin(rho thc) (rho the cranks' turns per sprocket turn, the pedal hanging at
              thc = 0), both as torques at the sprocket
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AN [SI] (motor_an_fast.yaml, motor_an_slow.yaml)
MOTOR_AN: dict[str, float] = {
    "R": 0.45, "L": 9e-4, "k": 0.24, "Jm": 8e-4, "bm": 5e-5, "Tm": 0.04,
    "N": 5.0, "Jw": 0.11, "Ks": 6000.0, "Ds": 2.0, "Jf": 0.05, "Bf": 0.01, "Tf": 0.8,
    "Cf": 0.011,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: [rad/s] the fluid unit's drag: w sqrt(w^2 + W_FLUID^2)
W_FLUID = 1.0
#: [m] the wheel's radius: 1 rad of the hub's or the roller's angle is this much travel
R_WHEEL = 0.33
#: [m] the trainer's roller's radius (57 mm): the roller turns R_WHEEL / R_ROLLER times as
#: fast as the body ``roller``
R_ROLLER = 0.0285
#: the fast regime's command [s, V] (motor_an_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.19, 30.0), (0.32, 30.0), (0.34, 15.0),
               (0.41, 15.0), (0.48, -10.0), (0.54, -10.0), (0.57, 0.0), (0.6, 0.0))
#: the slow regime's logged command [s, V] (motor_an_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.4, 0.0), (1.4, 12.0), (2.8, 12.0), (3.8, 30.0), (5.4, 30.0),
               (6.4, 48.0), (7.8, 48.0), (8.5, 20.0), (9.1, 20.0), (9.5, 0.0), (10.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.6), "slow": (250.0, 10.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "roller")
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


# ---------------------------------------------------------------------- the model

class EbikeRig:
    """Right-hand side of motor AN with one set of effects ``fx`` [SI]; ``ramp`` holds the
    command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.ratio = p["N"]
        size = 5
        #: the inertias [kg m^2] of the hub shell (with the carrier unless ``clutch``) and of
        #: the rim (0 unless ``windup``: the rim is part of the shell)
        shell = float(fx["windup"][0]) if "windup" in fx else p["Jw"]
        self.j_rim = p["Jw"] - shell
        #: index of the hub shell's own speed (its angle next; None without ``clutch``)
        self.shell = None
        if "clutch" in fx:
            jk = float(fx["clutch"][0])
            self.j_rotor = p["Jm"] + jk / self.ratio ** 2
            self.j_shell = shell - jk
            self.shell, size = size, size + 2
        else:
            self.j_rotor = p["Jm"] + shell / self.ratio ** 2
        #: index of the rim's speed (its angle next; None without ``windup``)
        self.rim = None
        if "windup" in fx:
            self.rim, size = size, size + 2
        #: index of the impeller's speed (its angle next; None without ``magdrive``)
        self.impeller = None
        self.j_roller = p["Jf"]
        if "magdrive" in fx:
            self.j_roller -= float(fx["magdrive"][0])
            self.impeller, size = size, size + 2
        #: index of the cranks' speed (their angle next; None without ``pedal``)
        self.cranks = None
        if "pedal" in fx:
            self.cranks, size = size, size + 2
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
        """The supply's (or the controller's) output [V] within the current segment."""
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
        declared EMF's, at the current ``i`` [A], the rotor's speed ``w`` [rad/s] and angle
        ``th`` [rad]."""
        fx = self.fx
        v = self.resistance(t) * i
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

    def tyre(self, twist: float, wrel: float) -> float:
        """The tyre's torque [N m] on the roller at the ``twist`` [rad] and the relative
        speed ``wrel`` [rad/s] (the wheel's minus the roller's), with a play if ``gap``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        if "gap" not in self.fx:
            return ks * twist + ds * wrel
        half = 0.5 * self.fx["gap"]
        if abs(twist) <= half:
            return 0.0
        edge = half if twist > 0.0 else -half
        push = ks * (twist - edge) + ds * wrel
        return max(push, 0.0) if twist > 0.0 else min(push, 0.0)

    def crank_drag(self, y: np.ndarray, wh: float) -> tuple[float, list[float]]:
        """With ``pedal``: the torque [N m] the freewheel gives the cranks at the wheel's
        speed ``wh`` [rad/s] (the wheel takes the opposite) and the cranks' rates
        [rad/s^2, rad/s]; else (0, [])."""
        if self.cranks is None:
            return 0.0, []
        jc, df, tp, dl, e, tb, g, rho = self.fx["pedal"]
        wc, thc = float(y[self.cranks]), float(y[self.cranks + 1])
        x = wh - wc
        tg = df * x + tp * math.tanh(x / W_SWITCH) + dl * (x - math.sqrt(x * x + e * e)) / 2.0
        return tg, [(tg - tb * math.tanh(wc / W_SWITCH) - g * math.sin(rho * thc)) / jc, wc]

    def __call__(self, t: float, y: np.ndarray) -> list[float]:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, n, fx = self.p, self.ratio, self.fx
        i, w, th, wr, thr = (float(v) for v in y[:5])
        di = (self.command(t) - self.loop_voltage(t, i, w, th) - p["k"] * w) \
            / self.inductance(i)
        torque = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  + self.body_torque("rotor", w, th))
        extra: list[float] = []
        # the hub shell: rigid with the rotor, or behind the clutch
        if self.shell is None:
            wh, thh = w / n, th / n
        else:
            wh, thh = float(y[self.shell]), float(y[self.shell + 1])
        # the rim (the tyre's side of the wheel): the shell, or behind the spokes
        if self.rim is None:
            wm, thm = wh, thh
        else:
            wm, thm = float(y[self.rim]), float(y[self.rim + 1])
        tk = self.tyre(thm - thr, wm - wr)
        tg, crank_rates = self.crank_drag(y, wh)
        on_shell = self.body_torque("hub", wh, thh) - tg
        if self.rim is None:
            on_shell -= tk
        else:
            _, kw, dw = fx["windup"]
            tw = kw * (thh - thm) + dw * (wh - wm)
            on_shell -= tw
            rim_rates = [(tw - tk) / self.j_rim, wm]
        if self.shell is None:
            torque += on_shell / n
        else:
            _, dl, e = fx["clutch"]
            x = w / n - wh
            tc = dl * (x + math.sqrt(x * x + e * e)) / 2.0
            torque -= tc / n
            extra += [(tc + on_shell) / self.j_shell, wh]
        if self.rim is not None:
            extra += rim_rates
        on_roller = (tk - p["Bf"] * wr - p["Tf"] * math.tanh(wr / W_SWITCH)
                     + self.body_torque("roller", wr, thr))
        if self.impeller is None:
            on_roller -= p["Cf"] * wr * math.sqrt(wr * wr + W_FLUID ** 2)
        else:
            _, tmax, pp = fx["magdrive"]
            wi, thi = float(y[self.impeller]), float(y[self.impeller + 1])
            tm = tmax * math.sin(pp * (thr - thi))
            on_roller -= tm
            extra += [(tm - p["Cf"] * wi * math.sqrt(wi * wi + W_FLUID ** 2))
                      / float(fx["magdrive"][0]), wi]
        extra += crank_rates
        seen = {"current": i, "speed": w, "load_speed": wr}
        pade = [2.0 * (seen[probe] - float(y[k])) / tau for probe, tau, k in self.delays]
        return [di, torque / self.j_rotor, w, on_roller / self.j_roller, wr, *extra, *pade]


# ---------------------------------------------------------------------- integration

def _piece(model: EbikeRig, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AN, {a:g}-{b:g} s: {why}")


def integrate(model: EbikeRig, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor AN at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A] (the rig's shunt in the supply's lead), speed [rad/s] (the hub's
    Hall speed sensor on the armature's magnet ring, rad/s at the rotor), and in the slow
    regime load_speed [rad/s] (the trainer's roller, from its own speed sensor, as rad/s of
    the 0.33 m wheel), plus the command ``u`` [V]. ``states``: add the bodies' speeds [rad/s]
    and angles [rad], the tyre's torque [N m] and the outside effects' states."""
    fx = dict(fx or {})
    p = {**MOTOR_AN, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = EbikeRig(fx, p)
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
        if model.shell is None:
            wh, thh = y[1] / p["N"], y[2] / p["N"]
        else:
            wh, thh = y[model.shell], y[model.shell + 1]
        wm, thm = (wh, thh) if model.rim is None else (y[model.rim], y[model.rim + 1])
        out.update(rotor_angle=y[2], hub_angle=thh, hub_speed=wh, rim_angle=thm,
                   rim_speed=wm, roller_angle=y[4], roller_speed=y[3],
                   armature_current=y[0],
                   tyre_torque=p["Ks"] * (thm - y[4]) + p["Ds"] * (wm - y[3]))
        if model.impeller is not None:
            out.update(impeller_speed=y[model.impeller],
                       impeller_angle=y[model.impeller + 1])
        if model.cranks is not None:
            out.update(crank_speed=y[model.cranks], crank_angle=y[model.cranks + 1])
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
