"""Motor AD of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC motor (2 poles, 6 slots, a 12-bar commutator) driving a top-entry TANK AGITATOR
(a mixing tank of a small dairy or brewery, stirring a water-thin liquid): the motor drives a
rigid, lossless 10:1 planetary gearhead, whose output hub turns a slender stainless shaft,
12 mm across and 1 m long (a torsional compliance), that carries a 180 mm pitched-blade
impeller near the tank's bottom. The impeller stirs turbulently (its drag is quadratic in its
speed) and runs in a PTFE steady bush at the bottom of the tank (a dry friction).

No circuitsim import: an independent simulator (the twenty-seventh of the benchmark),
written from the physics for netlists/motor_ad_fast.yaml and motor_ad_slow.yaml. It is
evaluated at the record's own sample times (``t_eval``), never on a grid that is then
interpolated. Everything rests at t = 0 (no current, no speed, the shaft untwisted).

The gearhead is rigid and lossless (``gear`` G, ratio N = 10): its output hub stands at
th / N and turns at w / N with the rotor; a torque T on the hub is T / N on the rotor. The
shaft is a spring and damper on the twist th / N - thi between the hub and the impeller
(``spring_damper`` K).

State z = [i, w, th, wi, thi] (+ the liquid's swirl wf for ``swirl``, + the clutch plate's
speed and angle wp, thp for ``clutch``, + one Pade stage per delayed probe, in this order):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wi, thi    the impeller's speed and angle [rad/s, rad]

Equations (J1 = Jm + Jg / N^2: the rotor with the gearhead's output hub):

    L di/dt   = v(t) - R i - k w - (the loop's extras)
    J1 dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor + (X_hub - Tk) / N
    Ji dwi/dt = Tk - Bi wi - Tl tanh(wi / 0.01) - cq wi |wi| + X_impeller
    Tk        = Kc (th / N - thi) + Dc (w / N - wi)          (the shaft)

Tm tanh(w / 0.01) is the brushes' dry friction (``friction``, w_brk 0.1), Bi wi the bush's
grease and the liquid's laminar part (``damper``), Tl tanh(wi / 0.01) the steady bush's dry
friction (``friction``, w_brk 0.1), cq wi |wi| the impeller's turbulent drag (``btorque``).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, hub, impeller) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in the shaft K (Modelica's ElastoBacklash):
              no torque while |twist| < gap / 2, else Kc (twist -+ gap / 2) + Dc w_rel,
              the damping never pulling the sides together
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    swirl     (Jf [kg m^2], cw [N m s^2/rad^2]): the tank's baffles left out: the liquid's
              bulk spins up as a body of inertia Jf (its speed wf a state, from 0); the
              impeller's turbulent drag acts on its speed relative to the liquid,
              cq (wi - wf) |wi - wf| instead of cq wi |wi|, and the wall drags the liquid,
              Jf dwf/dt = cq (wi - wf) |wi - wf| - cw wf |wf|
    bar       (dR [ohm], kappa [1], phase [rad]): an open armature coil: one of the two
              parallel paths is broken, so the armature's resistance is dR higher but for
              the moments the brushes bridge the open coil's two bars (twice a turn): the
              loop takes dR (1 - exp(kappa (cos(2 (th - phase)) - 1))) i more
    vortex    (dv [1], wv [rad/s], dw [rad/s]): the tank drawn down to a low level: above a
              critical speed the surface vortex reaches the impeller, which draws air and
              loses a fraction dv of its drag: the impeller receives
              dv cq wi |wi| (1 + tanh((|wi| - wv) / dw)) / 2
    clutch    (Ts [N m], ws [rad/s], Jp [kg m^2]): a worn overload slip clutch between the
              hub and the shaft: its driven plate (inertia Jp, speed and angle wp, thp from
              rest) takes Tc = Ts tanh((w / N - wp) / ws) from the hub, the shaft K twists
              by thp - thi (the rotor takes -Tc / N instead of -Tk / N)
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AD [SI] (motor_ad_fast.yaml, motor_ad_slow.yaml)
MOTOR_AD: dict[str, float] = {
    "R": 0.8, "L": 1.2e-3, "k": 0.06, "Jm": 6e-5, "bm": 1e-5, "Tm": 0.01, "N": 10.0,
    "Jg": 4e-4, "Kc": 160.0, "Dc": 0.02, "Ji": 4e-3, "Bi": 2e-3, "Tl": 0.1, "cq": 1e-3,
}
#: [rad/s] the frictions' and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_ad_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.005, 0.0), (0.035, 24.0), (0.16, 24.0), (0.162, 14.0),
               (0.23, 14.0), (0.232, 0.0), (0.27, 0.0), (0.28, -18.0), (0.36, -18.0),
               (0.362, 0.0), (0.4, 0.0))
#: the slow regime's logged command [s, V] (motor_ad_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.2, 0.0), (0.5, 24.0), (2.0, 24.0), (2.1, 12.0), (3.2, 12.0),
               (3.25, 0.0), (3.6, 0.0), (3.9, -20.0), (5.2, -20.0), (5.25, 0.0), (6.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.4), "slow": (200.0, 6.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "impeller")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime (L/R is 1.5 ms),
#: a fifth of the mean interval in the slow one
H_MAX = {"fast": 5e-5, "slow": 1e-3}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.asarray(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class Agitator:
    """Right-hand side of motor AD with one set of effects ``fx`` [SI]."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.n = p["N"]
        self.j1 = p["Jm"] + p["Jg"] / self.n ** 2
        k = 5
        #: index of the liquid's swirl speed, of the clutch plate's speed (angle next)
        self.k_swirl = self.k_plate = -1
        if "swirl" in fx:
            self.k_swirl, k = k, k + 1
        if "clutch" in fx:
            self.k_plate, k = k, k + 2
        #: (probe, tau [s], index of its Pade state)
        self.pade: list[tuple[str, float, int]] = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.pade.append((probe, float(s["delay"]), k))
                k += 1
        self.n_states = k
        self.terms = {b: self._terms_of(b) for b in BODIES}
        self.seg = (0.0, 0.0, 0.0)

    def _terms_of(self, body: str) -> tuple | None:
        """The catalog's effects on ``body``: (viscous, Coulomb, offset, harmonics,
        Stribeck), or None when there are none."""
        fx = self.fx
        t = (fx.get("visc", {}).get(body, 0.0), fx.get("coul", {}).get(body, 0.0),
             fx.get("offset", {}).get(body, 0.0), tuple(fx.get("cog", {}).get(body, ())),
             fx.get("stribeck", {}).get(body))
        return t if any(t) else None

    def extra_torque(self, body: str, w: float, angle: float) -> float:
        """The torque [N m] the catalog's effects give ``body`` turning at ``w`` [rad/s],
        standing at ``angle`` [rad]."""
        t = self.terms[body]
        if t is None:
            return 0.0
        visc, coul, off, harm, strib = t
        sgn = math.tanh(w / W_SIGN)
        out = off - visc * w - coul * sgn
        if strib:
            s, ws = strib
            out -= s * math.exp(-(w / ws) ** 2) * sgn
        for order, a, b in harm:
            out += a * math.sin(order * angle) + b * math.cos(order * angle)
        return out

    def command(self, t: float) -> float:
        """The bridge's mean output [V], linear within the current segment."""
        t0, u0, slope = self.seg
        return u0 + slope * (t - t0)

    def loop_drop(self, t: float, i: float, w: float, th: float) -> float:
        """Every voltage [V] the loop takes but the inductance's and the declared EMF's, at
        the time ``t`` [s], the current ``i`` [A], the rotor's speed ``w`` [rad/s] and
        angle ``th`` [rad]."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t) + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        if "bar" in fx:
            dr, kappa, phase = fx["bar"]
            r += dr * (1.0 - math.exp(kappa * (math.cos(2.0 * (th - phase)) - 1.0)))
        v = r * i
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SIGN)
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

    def shaft_torque(self, twist: float, wrel: float) -> float:
        """The shaft's torque [N m] on the impeller at the ``twist`` [rad] and the relative
        speed ``wrel`` [rad/s] (its top minus the impeller), with a play if ``gap``."""
        p = self.p
        gap = self.fx.get("gap")
        if gap is None:
            return p["Kc"] * twist + p["Dc"] * wrel
        h = 0.5 * gap
        if twist > h:
            return max(p["Kc"] * (twist - h) + p["Dc"] * wrel, 0.0)
        if twist < -h:
            return min(p["Kc"] * (twist + h) + p["Dc"] * wrel, 0.0)
        return 0.0

    def impeller_load(self, wi: float, wf: float) -> float:
        """The liquid's and the bush's torque [N m] on the impeller turning at ``wi``
        [rad/s], the liquid's bulk at ``wf`` [rad/s] (0 but with ``swirl``)."""
        p, fx = self.p, self.fx
        cq = p["cq"]
        out = -p["Bi"] * wi - p["Tl"] * math.tanh(wi / W_SIGN)
        rel = wi - wf if "swirl" in fx else wi
        out -= cq * rel * abs(rel)
        if "vortex" in fx:
            dv, wv, dw = fx["vortex"]
            out += dv * cq * wi * abs(wi) * 0.5 * (1.0 + math.tanh((abs(wi) - wv) / dw))
        return out

    def __call__(self, t: float, z: np.ndarray) -> list[float]:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p, n, fx = self.p, self.n, self.fx
        i, w, th, wi, thi = (float(v) for v in z[:5])
        di = (self.command(t) - self.loop_drop(t, i, w, th) - p["k"] * w) / self.inductance(i)
        extra: list[float] = []
        wf = float(z[self.k_swirl]) if self.k_swirl >= 0 else 0.0
        ts, ws, jp = fx.get("clutch", (0.0, 1.0, 1.0))
        if self.k_plate >= 0:
            wp, thp = float(z[self.k_plate]), float(z[self.k_plate + 1])
            tk = self.shaft_torque(thp - thi, wp - wi)
            t_hub = ts * math.tanh((w / n - wp) / ws)
        else:
            tk = self.shaft_torque(th / n - thi, w / n - wi)
            t_hub = tk
        tau = (p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SIGN)
               + self.extra_torque("rotor", w, th)
               + (self.extra_torque("hub", w / n, th / n) - t_hub) / n)
        dwi = (tk + self.impeller_load(wi, wf)
               + self.extra_torque("impeller", wi, thi)) / p["Ji"]
        if self.k_swirl >= 0:
            jf, cw = fx["swirl"]
            rel = wi - wf
            extra.append((p["cq"] * rel * abs(rel) - cw * wf * abs(wf)) / jf)
        if self.k_plate >= 0:
            extra += [(t_hub - tk) / jp, wp]
        values = {"current": i, "speed": w, "load_speed": wi}
        pade = [2.0 * (values[probe] - float(z[k])) / tau_d for probe, tau_d, k in self.pade]
        return [di, tau / self.j1, w, dwi, wi, *extra, *pade]


# ---------------------------------------------------------------------- integration

def _solve(model: Agitator, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
           h_max: float) -> np.ndarray:
    """solve_ivp from ``a`` to ``b`` [s] at the times ``t_out`` [s]: LSODA, then Radau if
    it fails."""
    msg = ""
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), z0, method=method, t_eval=t_out, rtol=RTOL,
                        atol=ATOL, max_step=h_max)
        if sol.success and np.isfinite(sol.y).all() and sol.y.shape[1] == t_out.size:
            return sol.y
        msg = sol.message
    raise RuntimeError(f"motor AD, {a:g}-{b:g} s: {msg}")


def integrate(model: Agitator, t: np.ndarray, bp: np.ndarray, h_max: float) -> np.ndarray:
    """The states at the increasing times ``t`` [s], from rest at 0, restarted at every
    corner of the command ``bp`` [s, V]. Returns (n_states, t.size)."""
    stop = float(t[-1])
    cuts = [0.0, *sorted({float(c) for c in bp[:, 0] if 0.0 < c < stop}), stop]
    z0 = np.zeros(model.n_states)
    y = np.empty((model.n_states, t.size))
    for j in range(len(cuts) - 1):
        a, b = cuts[j], cuts[j + 1]
        ua, ub = (float(x) for x in np.interp([a, b], bp[:, 0], bp[:, 1]))
        model.seg = (a, ua, (ub - ua) / (b - a))
        last = j == len(cuts) - 2
        sel = (t >= a) & (t <= b) if last else (t >= a) & (t < b)
        t_out = t[sel] if last else np.append(t[sel], b)
        ys = _solve(model, a, b, z0, t_out, h_max)
        y[:, sel] = ys[:, :int(sel.sum())]
        z0 = ys[:, -1].copy()
    return y


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor AD at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the impeller, from a blade-pass pickup), plus the command ``u``
    [V]. ``states``: add the angles [rad] (and the extra states)."""
    fx = dict(fx or {})
    p = {**MOTOR_AD, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = Agitator(fx, p)
    y = integrate(model, t, bp, H_MAX[regime])
    full = {"current": y[0], "speed": y[1], "load_speed": y[3]}
    for probe, _, k in model.pade:
        full[probe] = 2.0 * y[k] - full[probe]
    out = {probe: full[probe].copy() for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2], impeller_angle=y[4], impeller_speed=y[3])
        if model.k_swirl >= 0:
            out["swirl_speed"] = y[model.k_swirl]
        if model.k_plate >= 0:
            out["plate_speed"] = y[model.k_plate]
    return out


# ---------------------------------------------------------------------- noise

def gauss_markov(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float
                 ) -> np.ndarray:
    """A stationary Gauss-Markov process [probe unit] of standard deviation ``sigma`` and
    correlation time ``tau`` [s], sampled exactly at the (uneven) times ``t`` [s]."""
    rho = np.exp(-np.diff(t) / tau)
    shocks = sigma * np.sqrt(1.0 - rho ** 2) * rng.standard_normal(t.size - 1)
    x = np.empty(t.size)
    x[0] = sigma * rng.standard_normal()
    for j in range(1, t.size):
        x[j] = rho[j - 1] * x[j - 1] + shocks[j - 1]
    return x


def flicker(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma`` at the times ``t`` [s]: white
    noise on an even grid spanning the record, its amplitude spectrum shaped by 1/sqrt(f)
    (mean removed), read at ``t`` by linear interpolation."""
    n = t.size
    tg = np.linspace(float(t[0]), float(t[-1]), n)
    spec = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, float(tg[1] - tg[0]))
    spec[0] = 0.0
    spec[1:] /= np.sqrt(f[1:] / f[1])
    x = np.interp(t, tg, np.fft.irfft(spec, n))
    x -= x.mean()
    return sigma * x / x.std()


def add_noise(rng: np.random.Generator, t: np.ndarray, y: np.ndarray,
              spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` at the times ``t`` [s] with ``white`` sigma, ``ar1`` [sigma, phi] (a
    Gauss-Markov process correlated by phi over the mean interval) and ``pink`` (1/f) sigma
    noise added [probe unit], then read by an ADC of step ``quant`` [probe unit]."""
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out += rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        sig, phi = spec["ar1"]
        out += gauss_markov(rng, t, sig, -float(np.mean(np.diff(t))) / math.log(phi))
    if spec.get("pink"):
        out += flicker(rng, t, spec["pink"])
    step = spec.get("quant")
    return np.round(out / step) * step if step else out
