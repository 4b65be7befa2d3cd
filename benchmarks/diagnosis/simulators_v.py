"""Motor V of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC motor in an AUTO-STEER kit retrofitted to a small utility vehicle: the motor and
a rigid 18:1 gearhead turn the steering column (with the steering wheel), which turns the
intermediate shaft (two universal joints and a rubber flex coupling, a compliance) down to
the pinion of the rack-and-pinion steering gear; the rack, the tie rods and the road wheels
are reflected to the pinion, and the tyres' aligning moment pulls them back to straight
ahead like a torsional spring to the frame.

No circuitsim import: an independent simulator (the nineteenth of the benchmark), written
from the physics for netlists/motor_v_motor.yaml, motor_v.yaml and motor_v_slow.yaml. It is
evaluated at the record's own sample times (``t_eval``), never on a grid that is then
interpolated. Angles are counted from straight ahead, where everything rests at t = 0.

State z = [i, w, th, wp, thp] (+ extras, in this order when present: the encoder hub's
speed ``wc`` for ``slip``, the aligning moment ``Mz`` for ``relax``, one Pade stage per
delayed probe):

    i        armature current [A]
    w, th    rotor speed [rad/s] and angle [rad]; the column turns at w / N (N = 18)
    wp, thp  the pinion's speed [rad/s] and angle [rad] (the rack and the wheels with it)

Equations (J1 = Jm + Jc / N^2, the rotor with the column and the steering wheel seen by the
rotor; a torque T on the column is T / N on the rotor, the gearhead being rigid and
lossless):

    L di/dt   = v(t) - R i - k w - (loop extras)
    J1 dw/dt  = k i - bm w + X_rotor + (X_column - Tk) / N
    Jp dwp/dt = Tk - Bp wp - Tf tanh(wp / 0.01) - Ka thp + X_pinion
    Tk        = c (th / N - thp) + d (w / N - wp)            (the intermediate shaft ``K``)

Bp wp is the tie-rod joints' and the tyres' viscous loss (``damper``), Tf tanh(wp / 0.01)
the rack's and the kingpins' dry friction (``friction``, w_brk 0.1), Ka thp the tyres'
aligning moment at the pinion (``spring`` to ``fixed``).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th)),
              voltage only
    cog       {shaft: [(order, a, b), ...]}: the shaft (rotor, column, pinion) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {shaft: c}: c tanh(speed / 0.01) against the shaft's motion [N m]
    visc      {shaft: b}: an extra viscous friction [N m s/rad]
    offset    {shaft: T}: a constant torque [N m] the shaft receives
    stribeck  {shaft: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play in the intermediate shaft (Modelica's ElastoBacklash): no torque
              while |x| < gap / 2, else c (x -+ gap / 2) + d x', never pulling the sides
              together (x = th / N - thp)
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads
              g yd + o, yd the probe through a first-order Pade stage of delay tau
              (yd = 2 q - y, dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    cardan    (e [rad], psi [rad]): the intermediate shaft's two universal joints are
              assembled out of phase, so that their speed fluctuations add: the shaft's
              lower end stands at phi = thc + e (sin(2 thc + psi) - sin(psi)), thc = th / N
              the column's angle; Tk = c (phi - thp) + d (phi' - wp), phi' = g wc,
              g = 1 + 2 e cos(2 thc + psi); the column takes -g Tk (virtual work)
    slip      (Jenc [kg m^2], Tc [N m], eps [rad/s]): the motor encoder's hub slips on the
              shaft: the hub (Jenc, a part of the declared Jm) is dragged by
              Tc tanh((w - wc) / eps) and the speed probe reads its speed wc; the rotor
              keeps J1 - Jenc and takes the drag's reaction
    kerb      (t0 [s], A [N m], Tw [s]): a front wheel strikes a kerb stone: the pinion
              receives A sin(pi (t - t0) / Tw)^2 for t0 <= t <= t0 + Tw
    relax     tau [s]: the tyres' aligning moment builds up over their relaxation length:
              the pinion takes -Mz, dMz/dt = (Ka thp - Mz) / tau, instead of -Ka thp
    alsat     theta0 [rad]: the aligning moment saturates: the pinion takes
              -Ka theta0 tanh(thp / theta0) instead of -Ka thp
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_v_profile.csv"

#: declared values of motor V [SI] (motor_v_motor.yaml)
MOTOR_V: dict[str, float] = {
    "R": 0.4, "L": 3.5e-4, "k": 0.043, "Jm": 2.5e-5, "bm": 1e-5, "N": 18.0, "Jc": 0.016,
    "c": 150.0, "d": 0.25, "Jp": 6e-3, "Bp": 0.4, "Tf": 0.4, "Ka": 30.0,
}
#: [rad/s] the friction's and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_v.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.02, 0.0), (0.04, 6.0), (0.2, 6.0), (0.201, 2.5), (0.3, 2.5),
               (0.301, 8.0), (0.4, 8.0), (0.45, -7.0), (0.62, -7.0), (0.621, -2.0),
               (0.7, -2.0), (0.72, 0.0), (0.8, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.8), "slow": (500.0, 10.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
SHAFTS = ("rotor", "column", "pinion")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime (the armature's
#: L/R is 0.875 ms, the intermediate shaft's mode 28 Hz), a tenth of the mean interval in
#: the slow one (a 10th-order ripple of the rotor's angle, the finest angle-locked term the
#: imprints compare with, has a period of 6 ms at the slow regime's top rotor speed)
H_MAX = {"fast": 5e-5, "slow": 2e-4}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    if regime == "fast":
        return np.asarray(FAST_POINTS, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class Steering:
    """Right-hand side of motor V with one set of effects ``fx`` [SI]."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.j1 = p["Jm"] + p["Jc"] / p["N"] ** 2
        n = 5
        self.k_slip = self.k_relax = None
        if "slip" in fx:
            self.k_slip, n = n, n + 1
            self.j1 -= fx["slip"][0]
        if "relax" in fx:
            self.k_relax, n = n, n + 1
        #: (probe, tau, index of its Pade state)
        self.pade = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.pade.append((probe, float(s["delay"]), n))
                n += 1
        self.n_states = n
        self.seg = (0.0, 0.0, 0.0)
        self.extra = {s: self._shaft_terms(s) for s in SHAFTS}

    def _shaft_terms(self, s: str) -> tuple | None:
        """(viscous, Coulomb, offset, harmonics, Stribeck) the effects put on shaft ``s``,
        or None when they put nothing there."""
        fx = self.fx
        terms = (fx.get("visc", {}).get(s, 0.0), fx.get("coul", {}).get(s, 0.0),
                 fx.get("offset", {}).get(s, 0.0), tuple(fx.get("cog", {}).get(s, ())),
                 fx.get("stribeck", {}).get(s))
        return terms if any(x for x in terms if x is not None) else None

    def shaft_torque(self, s: str, w: float, ang: float) -> float:
        """The torque [N m] the catalog's effects put on shaft ``s`` turning at ``w``
        [rad/s], standing at ``ang`` [rad]."""
        terms = self.extra[s]
        if terms is None:
            return 0.0
        visc, coul, off, harm, strib = terms
        out = off - visc * w
        if coul or strib is not None:
            sg = math.tanh(w / W_SIGN)
            out -= coul * sg
            if strib is not None:
                out -= strib[0] * math.exp(-((w / strib[1]) ** 2)) * sg
        for order, a, b in harm:
            out += a * math.sin(order * ang) + b * math.cos(order * ang)
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
        """The bridge's output [V]: the command, linear within the current segment."""
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

    def shaft_k(self, thc: float, wc: float, thp: float, wp: float) -> tuple[float, float]:
        """The intermediate shaft's torque [N m] from the column into the pinion, and the
        factor [1] by which the column takes it (1 but with ``cardan``), at the column's
        angle ``thc`` [rad] and speed ``wc`` [rad/s] and the pinion's ``thp``, ``wp``."""
        p, fx = self.p, self.fx
        g = 1.0
        phi, dphi = thc, wc
        if "cardan" in fx:
            e, psi = fx["cardan"]
            phi = thc + e * (math.sin(2.0 * thc + psi) - math.sin(psi))
            g = 1.0 + 2.0 * e * math.cos(2.0 * thc + psi)
            dphi = g * wc
        x, xdot = phi - thp, dphi - wp
        gap = fx.get("gap")
        if gap is None:
            return p["c"] * x + p["d"] * xdot, g
        h = 0.5 * gap
        if x > h:
            return max(p["c"] * (x - h) + p["d"] * xdot, 0.0), g
        if x < -h:
            return min(p["c"] * (x + h) + p["d"] * xdot, 0.0), g
        return 0.0, g

    def aligning(self, thp: float, z: np.ndarray) -> float:
        """The tyres' aligning moment [N m] against the pinion's angle: the declared spring,
        its lagged value (``relax``) or its saturated law (``alsat``)."""
        ka = self.p["Ka"]
        if self.k_relax is not None:
            return float(z[self.k_relax])
        if "alsat" in self.fx:
            th0 = self.fx["alsat"]
            return ka * th0 * math.tanh(thp / th0)
        return ka * thp

    def kerb(self, t: float) -> float:
        """The kerb stone's torque [N m] on the pinion at the time ``t`` [s]."""
        if "kerb" not in self.fx:
            return 0.0
        t0, amp, tw = self.fx["kerb"]
        if t0 <= t <= t0 + tw:
            return amp * math.sin(math.pi * (t - t0) / tw) ** 2
        return 0.0

    def __call__(self, t: float, z: np.ndarray) -> list[float]:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p, fx = self.p, self.fx
        i, w, th, wp, thp = (float(v) for v in z[:5])
        n = p["N"]
        di = self.loop_voltage(t, i, w, th) / self.inductance(i)
        tk, g = self.shaft_k(th / n, w / n, thp, wp)
        rotor = (p["k"] * i - p["bm"] * w + self.shaft_torque("rotor", w, th)
                 + (self.shaft_torque("column", w / n, th / n) - g * tk) / n)
        pinion = (tk - p["Bp"] * wp - p["Tf"] * math.tanh(wp / W_SIGN)
                  - self.aligning(thp, z) + self.shaft_torque("pinion", wp, thp)
                  + self.kerb(t))
        extra = []
        if self.k_slip is not None:
            jenc, tc, eps = fx["slip"]
            drag = tc * math.tanh((w - float(z[self.k_slip])) / eps)
            rotor -= drag
            extra.append(drag / jenc)
        if self.k_relax is not None:
            extra.append((p["Ka"] * thp - float(z[self.k_relax])) / fx["relax"])
        values = {"current": i, "speed": w, "load_speed": wp}
        if self.k_slip is not None:
            values["speed"] = float(z[self.k_slip])
        for probe, tau, k in self.pade:
            extra.append(2.0 * (values[probe] - float(z[k])) / tau)
        return [di, rotor / self.j1, w, pinion / p["Jp"], wp, *extra]


# ---------------------------------------------------------------------- integration

def _solve(model: Steering, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor V, {a:g}-{b:g} s: {msg}")


def cuts_of(bp: np.ndarray, fx: Mapping[str, Any], stop: float) -> list[float]:
    """The restarts [s]: 0, the command's corners, the kerb's start and end, ``stop``."""
    inner = {float(c) for c in bp[:, 0] if 0.0 < c < stop}
    if "kerb" in fx:
        t0, _, tw = fx["kerb"]
        inner.update(x for x in (float(t0), float(t0 + tw)) if 0.0 < x < stop)
    return [0.0, *sorted(inner), stop]


def integrate(model: Steering, t: np.ndarray, bp: np.ndarray, h_max: float) -> np.ndarray:
    """The states at the increasing times ``t`` [s], from rest at 0, restarted at every
    corner of the command ``bp`` [s, V] (and the kerb's). Returns (n_states, t.size)."""
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
    """Noise-free probes of motor V at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the pinion's steering-angle sensor, differentiated: rad/s of the
    pinion shaft), plus the logged command ``u`` [V]. ``states``: add the rotor's and the
    pinion's angles [rad]."""
    fx = dict(fx or {})
    p = {**MOTOR_V, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = Steering(fx, p)
    y = integrate(model, t, bp, H_MAX[regime])
    full = {"current": y[0], "speed": y[1], "load_speed": y[3]}
    if model.k_slip is not None:
        full["speed"] = y[model.k_slip]
    for probe, _, k in model.pade:
        full[probe] = 2.0 * y[k] - full[probe]
    out = {probe: full[probe].copy() for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2], pinion_angle=y[4])
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
    """1/f noise [probe unit] of standard deviation ``sigma`` at the times ``t`` [s]: equal
    variance Ornstein-Uhlenbeck processes with corner frequencies an octave apart, from the
    record's length down to twice the mean interval, mean removed and scaled."""
    span = float(t[-1] - t[0])
    dt = span / (t.size - 1)
    x = np.zeros(t.size)
    tau = span
    while tau > 2.0 * dt:
        x += gauss_markov(rng, t, 1.0, tau)
        tau *= 0.5
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
