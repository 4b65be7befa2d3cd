"""Motor W of the diagnosis benchmark: a hand-written scipy model of a 48 V permanent-magnet
brushed DC motor in a small ELECTRIC OUTBOARD pushing a dinghy: the motor, a rigid 2:1 bevel
gear in the lower unit, the propeller shaft, the propeller's rubber cushion hub (a
compliance), the propeller with the water it carries round, and the boat, which the
propeller's thrust drives through the water.

No circuitsim import: an independent simulator (the twentieth of the benchmark), written
from the physics for netlists/motor_w_motor.yaml, motor_w.yaml and motor_w_slow.yaml. It is
evaluated at the record's own sample times (``t_eval``), never on a grid that is then
interpolated. Everything rests at t = 0.

The boat is reflected through the propeller's pitch radius r = 0.04 m/rad (its advance per
radian at zero torque: a 0.25 m pitch): the hull is a body of inertia Jh = m r^2 whose speed
wh = v / r [rad/s] is the boat's speed v [m/s] over r, and on which a force F acts as the
torque F r. The propeller's torque and thrust follow a linear open-water law in the advance
ratio: the propeller takes Q = cq |wp| (wp - wh) (zero when it screws through the water with
no slip), the hull the thrust's torque ct |wp| (lam wp - wh) (zero at a lam = 0.8 of that
advance), both odd in the speeds (astern alike).

State z = [i, w, th, wp, thp, wh, thh] (+ extras, in this order when present: the tender's
speed and angle ``wt``, ``tht`` for ``tender``, one Pade stage per delayed probe):

    i        armature current [A]
    w, th    rotor speed [rad/s] and angle [rad]; the propeller shaft turns at w / N (N = 2)
    wp, thp  the propeller's speed [rad/s] and angle [rad], behind the rubber hub
    wh, thh  the hull's speed and travel in the reflected units [rad/s, rad] (v / r, x / r)

Equations (J1 = Jm + Js / N^2, the rotor with the bevel gear and the shaft seen by the rotor;
a torque T on the shaft is T / N on the rotor, the gear being rigid and lossless):

    L di/dt   = v(t) - R i - k w - (loop extras)
    J1 dw/dt  = k i - bm w + X_rotor + (X_shaft - Ts tanh(ws / 0.01) - Tk) / N,  ws = w / N
    Jp dwp/dt = Tk - cq |wp| (wp - wh) + X_prop
    Jh dwh/dt = ct |wp| (lam wp - wh) - ch wh |wh| - Bh wh + X_hull
    Tk        = c (th / N - thp) + d (w / N - wp)            (the rubber hub ``K``)

Ts tanh(ws / 0.01) is the shaft seals' dry friction (``friction``, w_brk 0.1), ch wh |wh| the
hull's wave and form drag (``btorque``), Bh wh its skin friction (``damper``).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th)),
              voltage only
    cog       {body: [(order, a, b), ...]}: the body (rotor, shaft, prop, hull) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play in the rubber hub (Modelica's ElastoBacklash): no torque while
              |x| < gap / 2, else c (x -+ gap / 2) + d x', never pulling the sides together
              (x = th / N - thp)
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads
              g yd + o, yd the probe through a first-order Pade stage of delay tau
              (yd = 2 q - y, dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    vent      (t0 [s], t1 [s], te [s], depth [1]): the propeller ventilates (draws air down
              from the surface): its torque and its thrust are multiplied by 1 - depth s(t),
              s rising as sin^2 over [t0, t0 + te], 1 to t1, falling as cos^2 over
              [t1, t1 + te], 0 elsewhere
    churn     cw [N m s^2/rad^2]: water in the motor's can: the rotor takes -cw w |w|
    tender    (Jt [kg m^2], kr [N m/rad], L0 [rad], s [rad], cht [N m s^2/rad^2]): a tender
              towed on a slack rope: a body of inertia Jt (its mass times r^2) with its own
              drag -cht wt |wt|, pulled by the rope's tension kr s softplus((thh - tht - L0) / s)
              (slack below a separation L0, a smooth onset of width s), whose reaction the
              hull takes
    wave      (Wo [rad/s], f0 [Hz], kx [1/rad], psi [rad]): a head sea: the propeller's
              inflow is wh + Wo sin(2 pi f0 t + kx thh + psi) (the waves' orbital velocity at
              the propeller, met at a rate that grows with the boat's travel) in the
              propeller's torque and thrust laws
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_w_profile.csv"

#: declared values of motor W [SI] (motor_w_motor.yaml)
MOTOR_W: dict[str, float] = {
    "R": 0.1, "L": 2.5e-4, "k": 0.1, "Jm": 3e-4, "bm": 5e-5, "N": 2.0, "Js": 2e-4,
    "Ts": 0.1, "c": 120.0, "d": 0.04, "Jp": 1.5e-3, "cq": 2.5e-4, "ct": 4.8e-4,
    "lam": 0.8, "Jh": 0.512, "ch": 1.7e-3, "Bh": 0.015,
}
#: [rad/s] the friction's and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_w.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.05, 24.0), (0.15, 24.0), (0.17, 48.0),
               (0.28, 48.0), (0.29, 16.0), (0.38, 16.0), (0.42, -30.0), (0.5, -30.0),
               (0.505, -10.0), (0.55, -10.0), (0.57, 0.0), (0.6, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.6), "slow": (400.0, 12.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "shaft", "prop", "hull")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime (the armature's
#: L/R is 2.5 ms, the rubber hub's mode 65 Hz), a tenth of the mean interval in the slow
#: one (a 14th-order ripple of the rotor's angle, the finest angle-locked term the imprints
#: compare with, has a period of 1 ms at the top rotor speed: the error control resolves it)
H_MAX = {"fast": 4e-5, "slow": 2.5e-4}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    if regime == "fast":
        return np.asarray(FAST_POINTS, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def softplus(z: float) -> float:
    """log(1 + exp(z)), without overflow."""
    return z + math.log1p(math.exp(-z)) if z > 0.0 else math.log1p(math.exp(z))


def vent_window(fx: Mapping[str, Any], t: float) -> float:
    """The ventilation's share s(t) [1] at the time ``t`` [s] (``vent``), 0 without it."""
    if "vent" not in fx:
        return 0.0
    t0, t1, te, _ = fx["vent"]
    if t < t0 or t > t1 + te:
        return 0.0
    if t < t0 + te:
        return math.sin(0.5 * math.pi * (t - t0) / te) ** 2
    if t <= t1:
        return 1.0
    return math.cos(0.5 * math.pi * (t - t1) / te) ** 2


# ---------------------------------------------------------------------- the model

class Outboard:
    """Right-hand side of motor W with one set of effects ``fx`` [SI]."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.j1 = p["Jm"] + p["Js"] / p["N"] ** 2
        n = 7
        self.k_tender = None
        if "tender" in fx:
            self.k_tender, n = n, n + 2
        #: (probe, tau, index of its Pade state)
        self.pade = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.pade.append((probe, float(s["delay"]), n))
                n += 1
        self.n_states = n
        self.seg = (0.0, 0.0, 0.0)
        self.extra = {b: self._body_terms(b) for b in BODIES}

    def _body_terms(self, b: str) -> tuple | None:
        """(viscous, Coulomb, offset, harmonics, Stribeck) the effects put on body ``b``,
        or None when they put nothing there."""
        fx = self.fx
        terms = (fx.get("visc", {}).get(b, 0.0), fx.get("coul", {}).get(b, 0.0),
                 fx.get("offset", {}).get(b, 0.0), tuple(fx.get("cog", {}).get(b, ())),
                 fx.get("stribeck", {}).get(b))
        return terms if any(x for x in terms if x is not None) else None

    def body_torque(self, b: str, w: float, ang: float) -> float:
        """The torque [N m] the catalog's effects put on body ``b`` turning at ``w``
        [rad/s], standing at ``ang`` [rad]."""
        terms = self.extra[b]
        if terms is None:
            return 0.0
        visc, coul, off, harm, strib = terms
        out = off - visc * w
        if coul or strib is not None:
            sg = math.tanh(w / W_SIGN)
            out -= coul * sg
            if strib is not None:
                out -= strib[0] * math.exp(-((w / strib[1]) ** 2)) * sg
        for order, a, b2 in harm:
            out += a * math.sin(order * ang) + b2 * math.cos(order * ang)
        return out

    def resistance(self, t: float) -> float:
        """The loop's resistance [ohm]: the armature's (drifting) and the extras'."""
        p, fx = self.p, self.fx
        r = p["R"]
        if "alpha" in fx:
            r *= 1.0 + fx["alpha"] * t
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        return r + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)

    def inductance(self, i: float) -> float:
        """The differential inductance [H] at the current ``i`` [A]."""
        ell = self.p["L"]
        if "lsat" not in self.fx:
            return ell
        ipar, ratio = self.fx["lsat"]
        return ell * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))

    def drive(self, t: float) -> float:
        """The controller's output [V]: the command, linear within the current segment."""
        t0, u0, slope = self.seg
        return u0 + slope * (t - t0)

    def loop_voltage(self, t: float, i: float, w: float, th: float) -> float:
        """The voltage [V] left for the inductance: the drive less the loop's drops and the
        EMF."""
        fx = self.fx
        v = self.drive(t) - self.resistance(t) * i - self.p["k"] * w
        if "Vb" in fx:
            v -= fx["Vb"] * math.tanh(i / I_SIGN)
        for order, a, b in fx.get("emf", ()):
            v -= w * (a * math.sin(order * th) + b * math.cos(order * th))
        return v

    def hub(self, ths: float, ws: float, thp: float, wp: float) -> float:
        """The rubber hub's torque [N m] from the shaft into the propeller, at the shaft's
        angle ``ths`` [rad] and speed ``ws`` [rad/s] and the propeller's ``thp``, ``wp``."""
        p = self.p
        x, xdot = ths - thp, ws - wp
        gap = self.fx.get("gap")
        if gap is None:
            return p["c"] * x + p["d"] * xdot
        h = 0.5 * gap
        if x > h:
            return max(p["c"] * (x - h) + p["d"] * xdot, 0.0)
        if x < -h:
            return min(p["c"] * (x + h) + p["d"] * xdot, 0.0)
        return 0.0

    def propeller(self, t: float, wp: float, wh: float, thh: float) -> tuple[float, float]:
        """The propeller's torque Q [N m] (which it takes as -Q) and the thrust's torque on
        the hull [N m], at its speed ``wp`` and the hull's ``wh`` [rad/s]."""
        p, fx = self.p, self.fx
        inflow = wh
        if "wave" in fx:
            wo, f0, kx, psi = fx["wave"]
            inflow += wo * math.sin(2.0 * math.pi * f0 * t + kx * thh + psi)
        q = p["cq"] * abs(wp) * (wp - inflow)
        th = p["ct"] * abs(wp) * (p["lam"] * wp - inflow)
        if "vent" in fx:
            f = 1.0 - fx["vent"][3] * vent_window(fx, t)
            q, th = q * f, th * f
        return q, th

    def __call__(self, t: float, z: np.ndarray) -> list[float]:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p, fx = self.p, self.fx
        i, w, th, wp, thp, wh, thh = (float(v) for v in z[:7])
        n = p["N"]
        ws = w / n
        di = self.loop_voltage(t, i, w, th) / self.inductance(i)
        tk = self.hub(th / n, ws, thp, wp)
        rotor = (p["k"] * i - p["bm"] * w + self.body_torque("rotor", w, th)
                 + (self.body_torque("shaft", ws, th / n) - p["Ts"] * math.tanh(ws / W_SIGN)
                    - tk) / n)
        if "churn" in fx:
            rotor -= fx["churn"] * w * abs(w)
        q, thrust = self.propeller(t, wp, wh, thh)
        prop = tk - q + self.body_torque("prop", wp, thp)
        hull = (thrust - p["ch"] * wh * abs(wh) - p["Bh"] * wh
                + self.body_torque("hull", wh, thh))
        extra = []
        if self.k_tender is not None:
            jt, kr, l0, s, cht = fx["tender"]
            wt, tht = float(z[self.k_tender]), float(z[self.k_tender + 1])
            rope = kr * s * softplus((thh - tht - l0) / s)
            hull -= rope
            extra += [(rope - cht * wt * abs(wt)) / jt, wt]
        values = {"current": i, "speed": w, "load_speed": wh}
        for probe, tau, k in self.pade:
            extra.append(2.0 * (values[probe] - float(z[k])) / tau)
        return [di, rotor / self.j1, w, prop / p["Jp"], wp, hull / p["Jh"], wh, *extra]


# ---------------------------------------------------------------------- integration

def _solve(model: Outboard, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor W, {a:g}-{b:g} s: {msg}")


def cuts_of(bp: np.ndarray, fx: Mapping[str, Any], stop: float) -> list[float]:
    """The restarts [s]: 0, the command's corners, the ventilation's corners, ``stop``."""
    inner = {float(c) for c in bp[:, 0] if 0.0 < c < stop}
    if "vent" in fx:
        t0, t1, te, _ = fx["vent"]
        inner.update(float(x) for x in (t0, t0 + te, t1, t1 + te) if 0.0 < x < stop)
    return [0.0, *sorted(inner), stop]


def integrate(model: Outboard, t: np.ndarray, bp: np.ndarray, h_max: float) -> np.ndarray:
    """The states at the increasing times ``t`` [s], from rest at 0, restarted at every
    corner of the command ``bp`` [s, V] (and the ventilation's). Returns (n_states,
    t.size)."""
    cuts = cuts_of(bp, model.fx, float(t[-1]))
    z0 = np.zeros(model.n_states)
    y = np.empty((model.n_states, t.size))
    for j in range(len(cuts) - 1):
        a, b = cuts[j], cuts[j + 1]
        ua, ub = (float(v) for v in np.interp([a, b], bp[:, 0], bp[:, 1]))
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
    """Noise-free probes of motor W at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A], speed [rad/s] (the motor's Hall sensor), and in the slow regime
    load_speed [rad/s] (the boat's speed log, v / r: rad/s of the hull's reflected body),
    plus the logged command ``u`` [V]. ``states``: add the propeller's speed [rad/s] and
    the angles [rad]."""
    fx = dict(fx or {})
    p = {**MOTOR_W, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = Outboard(fx, p)
    y = integrate(model, t, bp, H_MAX[regime])
    full = {"current": y[0], "speed": y[1], "load_speed": y[5]}
    for probe, _, k in model.pade:
        full[probe] = 2.0 * y[k] - full[probe]
    out = {probe: full[probe].copy() for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2], prop_speed=y[3], prop_angle=y[4], hull_speed=y[5],
                   hull_travel=y[6])
        if model.k_tender is not None:
            out.update(tender_speed=y[model.k_tender], tender_travel=y[model.k_tender + 1])
    return out


# ---------------------------------------------------------------------- noise

def gauss_markov(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float
                 ) -> np.ndarray:
    """A stationary Ornstein-Uhlenbeck process [probe unit] of standard deviation
    ``sigma`` and correlation time ``tau`` [s], exact at the times ``t`` [s], even or
    not."""
    a = np.exp(-np.diff(t) / tau)
    e = rng.standard_normal(t.size)
    x = np.empty(t.size)
    x[0] = sigma * e[0]
    scale = sigma * np.sqrt(1.0 - a * a)
    for n in range(1, t.size):
        x[n] = a[n - 1] * x[n - 1] + scale[n - 1] * e[n]
    return x


def one_over_f(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma`` at the times ``t`` [s]: white
    noise on the record's mean grid shaped by 1/sqrt(f) in the frequency domain (the mean
    removed), read at the times ``t`` by linear interpolation, then scaled."""
    n = t.size
    span = float(t[-1] - t[0])
    tg = t[0] + np.arange(n) * span / (n - 1)
    spec = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, span / (n - 1))
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
        out += one_over_f(rng, t, spec["pink"])
    step = spec.get("quant")
    return np.round(out / step) * step if step else out
