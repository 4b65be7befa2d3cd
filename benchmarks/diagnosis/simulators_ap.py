"""Motor AP of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC motor (a 2-pole, 12-slot armature in a ferrite-magnet can) driving the FLYER of an
ELECTRIC SPINNING WHEEL (a bench-top "e-spinner" for hand-spinning yarn) on the maker's
test bench (no fibre, no yarn: the flyer spins empty). The armature's 12-tooth pinion drives a
48-tooth spur gear (a 4:1 reduction, `gear` G, declared rigid and lossless); the body ``hub``
is the gear's shaft with the gear and the drive whorl (a V-grooved pulley, 50 mm across). An
elastic polyurethane round drive band (5 mm) runs from the hub's whorl to the flyer's whorl of
the same size (1:1); the band's two spans' stretch is a `spring_damper` K between the hub and
the body ``flyer`` (the U-shaped flyer with its hooks, its shaft (the orifice) and whorl, and
the empty bobbin pinned to it). The flyer turns at the hub's speed on average (1:1), its
angle the flyer's own. Running forward (Z twist) is flyer.w > 0; backwards (S twist, for
plying) is flyer.w < 0.

No circuitsim import: an independent simulator (the thirty-ninth of the benchmark), written
from the physics for netlists/motor_ap_fast.yaml and motor_ap_slow.yaml. It is evaluated at
the record's own sample times (``t_eval``), never on a grid that is then interpolated.
Everything rests at t = 0: no current, no speed, the hub and the flyer at 0 and the band at its
even pretension (unstretched); an outside effect's own state at rest too.

The spur gear is rigid (``gear`` G, ratio N = 4): the hub stands at th / N and turns at
w / N with the rotor; a torque T on it is T / N on the rotor. The band is a spring and a
damper on the twist th / N - thc between the hub and the flyer (``spring_damper`` K), its
torque on the flyer

    Tk = Ks (th / N - thc) + Ds (w / N - wc).

The flyer meets three declared loads: its two ball bearings at the orifice and the back
(a viscous drag Bc wc, ``damper``), the Scotch-tension brake cord resting on the flyer's
whorl at its bench setting (a dry friction Tb tanh(wc / 0.01), ``friction``, w_brk 0.1) and
the arms' and hooks' windage, a quadratic drag Cw wc sqrt(wc^2 + (1 rad/s)^2) (``btorque``
Wind).

State y = [i, w, th, wc, thc] (+ the bobbin's speed wb for ``bobbin``, + the band's
relaxing torque z for ``zener``, + one Pade stage per delayed probe, in this order):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wc, thc    the flyer's speed and angle [rad/s, rad] (0: where it starts)

Equations (Jr = Jm + Jh / N^2: the armature with its pinion, and the hub):

    L di/dt   = u(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor + (X_hub - Tk) / N
    Jc dwc/dt = Tk - Bc wc - Tb tanh(wc / 0.01) - Cw wc sqrt(wc^2 + 1) + X_flyer

Tm tanh(w / 0.01) is the brushes', the motor's sleeve bearings' and the gear's dry friction
(``friction``, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, flyer) receives
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

    bobbin    (Jb [kg m^2], Bv [N m s/rad], Tbb [N m]): a second, undeclared body: the
              bobbin rides loose on the flyer's shaft (not pinned), dragged round by the oil
              film in its bore, Bv (wc - wb), and held back by its own Scotch-tension brake
              cord, Tbb tanh(wb / 0.01): Jb dwb/dt = Bv (wc - wb) - Tbb tanh(wb / 0.01), the
              flyer receiving -Bv (wc - wb) (wb = 0 at rest)
    armre     (Ik [A],): armature reaction: the field the armature's current cross-magnetises
              weakens the magnets' flux at high current: the EMF and the torque take
              k / (1 + (i / Ik)^2) in place of k
    mesh      (mu [1],): the spur gear's sliding losses: the hub receives a dry friction
              proportional to the torque the mesh carries (taken as the band's),
              -mu sqrt(Tk^2 + E_MESH^2) tanh((w / N) / 0.01)
    zener     (K2 [N m/rad], tau2 [s]): the drive band viscoelastic (a standard linear solid):
              besides Ks and Ds a Maxwell branch z, dz/dt = K2 (w / N - wc) - z / tau2
              (z = 0 at rest), the band's torque Tk + z: stiffer and lossier at the band's
              resonance, as declared when slow
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AP [SI] (motor_ap_fast.yaml, motor_ap_slow.yaml)
MOTOR_AP: dict[str, float] = {
    "R": 0.9, "L": 4e-4, "k": 0.028, "Jm": 1.5e-5, "bm": 3e-6, "Tm": 0.006,
    "N": 4.0, "Jh": 8e-5, "Ks": 5.0, "Ds": 0.006, "Jc": 6e-4, "Bc": 2e-5, "Tb": 0.02,
    "Cw": 2e-7,
}
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: [rad/s] the windage: w sqrt(w^2 + W_WIND^2)
W_WIND = 1.0
#: [N m] the gear mesh's losses: mu sqrt(Tk^2 + E_MESH^2)
E_MESH = 1e-4
#: the fast regime's command [s, V] (motor_ao_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.25, 16.0), (0.33, 16.0), (0.35, 8.0),
               (0.41, 8.0), (0.52, -6.0), (0.555, -6.0), (0.58, 0.0), (0.6, 0.0))
#: the slow regime's logged command [s, V] (motor_ao_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.4, 0.0), (1.4, 8.0), (2.6, 8.0), (3.4, 14.0), (4.8, 14.0),
               (5.4, 20.0), (6.8, 20.0), (7.6, 0.0), (8.0, 0.0), (8.6, -10.0), (9.5, -10.0),
               (9.8, 0.0), (10.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.6), "slow": (250.0, 10.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "flyer")
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


def _smooth_abs(x: float, eps: float) -> float:
    """sqrt(x^2 + eps^2), as circuitsim's smooth_abs."""
    return math.sqrt(x * x + eps * eps)


# ---------------------------------------------------------------------- the model

class FlyerDrive:
    """Right-hand side of motor AP with one set of effects ``fx`` [SI]; ``ramp`` holds the
    command's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.ratio = p["N"]
        self.j_rotor = p["Jm"] + p["Jh"] / self.ratio ** 2
        size = 5
        #: index of the loose bobbin's speed (None without ``bobbin``)
        self.bobbin = None
        if "bobbin" in fx:
            self.bobbin, size = size, size + 1
        #: index of the band's Maxwell branch torque (None without ``zener``)
        self.zener = None
        if "zener" in fx:
            self.zener, size = size, size + 1
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
        EMF's, at the current ``i`` [A], the rotor's speed ``w`` [rad/s] and angle ``th``
        [rad]."""
        fx = self.fx
        v = self.resistance(t) * i
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SWITCH)
        for order, a, b in fx.get("emf", ()):
            v += w * (a * math.sin(order * th) + b * math.cos(order * th))
        return v

    def coupling(self, i: float) -> float:
        """The EMF's and the torque's constant [V s/rad = N m/A] at the current ``i`` [A]:
        k, or k / (1 + (i / Ik)^2) with the armature's reaction (``armre``)."""
        if "armre" in self.fx:
            ik = float(self.fx["armre"][0])
            return self.p["k"] / (1.0 + (i / ik) ** 2)
        return self.p["k"]

    def inductance(self, i: float) -> float:
        """The differential inductance [H] at the current ``i`` [A]."""
        ell = self.p["L"]
        if "lsat" in self.fx:
            ipar, ratio = self.fx["lsat"]
            ell *= ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2)
        return ell

    def band(self, twist: float, wrel: float) -> float:
        """The band's elastic and damping torque [N m] on the flyer at the ``twist`` [rad]
        and the relative speed ``wrel`` [rad/s] (the hub's minus the flyer's), with a play
        if ``gap`` (the Maxwell branch of ``zener`` is added by the caller)."""
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
        p, n, fx = self.p, self.ratio, self.fx
        i, w, th, wc, thc = (float(v) for v in y[:5])
        u = self.command(t)
        kk = self.coupling(i)
        di = (u - self.loop_voltage(t, i, w, th) - kk * w) / self.inductance(i)
        wrel = w / n - wc
        tk = self.band(th / n - thc, wrel)
        extra: list[float] = []
        if self.bobbin is not None:
            jb, bv, tbb = fx["bobbin"]
            wb = float(y[self.bobbin])
            drag = bv * (wc - wb)
            extra.append((drag - tbb * math.tanh(wb / W_SWITCH)) / jb)
        else:
            drag = 0.0
        if self.zener is not None:
            k2, tau2 = fx["zener"]
            z = float(y[self.zener])
            extra.append(k2 * wrel - z / tau2)
            tk += z
        on_hub = self.body_torque("hub", w / n, th / n)
        if "mesh" in fx:
            on_hub -= (float(fx["mesh"][0]) * _smooth_abs(tk, E_MESH)
                       * math.tanh(w / n / W_SWITCH))
        torque = (kk * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SWITCH)
                  + self.body_torque("rotor", w, th) + (on_hub - tk) / n)
        on_flyer = (tk - p["Bc"] * wc - p["Tb"] * math.tanh(wc / W_SWITCH)
                    - p["Cw"] * wc * _smooth_abs(wc, W_WIND)
                    + self.body_torque("flyer", wc, thc) - drag)
        seen = {"current": i, "speed": w, "load_speed": wc}
        pade = [2.0 * (seen[probe] - float(y[k])) / tau for probe, tau, k in self.delays]
        return [di, torque / self.j_rotor, w, on_flyer / p["Jc"], wc, *extra, *pade]


# ---------------------------------------------------------------------- integration

def _piece(model: FlyerDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AP, {a:g}-{b:g} s: {why}")


def integrate(model: FlyerDrive, t: np.ndarray, bp: np.ndarray, max_step: float
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
    """Noise-free probes of motor AP at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A] (the bench's shunt in the supply's lead, or the wheel
    controller's shunt), speed [rad/s] (the motor's Hall encoder, rad/s at the rotor), and in
    the slow regime load_speed [rad/s] (the flyer, from the controller's optical sensor
    counting the flyer's arms), plus the command ``u`` [V]. ``states``: add the bodies'
    speeds [rad/s] and angles [rad], the band's torque [N m] and the outside effects'
    states."""
    fx = dict(fx or {})
    p = {**MOTOR_AP, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = FlyerDrive(fx, p)
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
        torque = np.array([model.band(a, b) for a, b in zip(twist, wrel, strict=True)])
        if model.zener is not None:
            torque = torque + y[model.zener]
            out.update(band_relaxing=y[model.zener])
        out.update(rotor_angle=y[2], hub_angle=y[2] / p["N"], hub_speed=y[1] / p["N"],
                   flyer_angle=y[4], flyer_speed=y[3], armature_current=y[0],
                   band_twist=twist, band_torque=torque)
        if model.bobbin is not None:
            out.update(bobbin_speed=y[model.bobbin])
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
