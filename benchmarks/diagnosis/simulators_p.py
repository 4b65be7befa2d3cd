"""Motor P of the diagnosis benchmark: a hand-written scipy model of a 48 V, 300 W class
permanent-magnet brushed DC motor spinning up the steel flywheel of a small flywheel
energy-storage demonstrator through a rigid 1:2 spur-gear STEP-UP and a compliant quill
shaft, the flywheel running in a rough vacuum.

No circuitsim import: an independent simulator (the thirteenth of the benchmark), written
from the physics for netlists/motor_p_motor.yaml, motor_p.yaml and motor_p_slow.yaml. It is
evaluated at the record's own sample times (``t_eval``), never on a grid that is then
interpolated.

State z = [i, w, th, x, wf, thf] (+ the current sensor's delay stage, + the drive's
slew-limited output voltage):

    i        armature current [A]
    w, th    rotor speed [rad/s] and angle [rad]; the pinion turns at w / N (N = 0.5: twice
             as fast as the rotor)
    x        the quill's twist th / N - thf [rad]
    wf, thf  the flywheel's speed [rad/s] and angle [rad]

Equations (J1 = Jm + Jh / N^2, the rotor and the pinion's shaft seen by the rotor; a torque
T on the pinion is T / N on the rotor, power being conserved):

    L(i) di/dt = v(t) - R i - k w - (loop extras)
    J1 dw/dt   = k i - bm w + X_rotor + (X_pinion - Tq) / N
    Jf dwf/dt  = Tq - bf wf - Tf tanh(wf / 0.01) + X_fly
    Tq         = c x + d (w / N - wf)                     (the quill ``K``)

L(i) = L unless the winding saturates; Tf tanh(wf / 0.01) is the bearings' friction
(``friction``, w_brk 0.1), bf wf the windage of the rarefied air.

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): L(i) = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2)), the
              differential inductance of circuitsim's ``Lsat``
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th)),
              voltage only
    cog       {node: [(order, a, b), ...]}: the node (rotor, pinion, fly) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {node: c}: c tanh(speed / 0.01) against the node's motion [N m]
    visc      {node: b}: an extra viscous friction [N m s/rad]
    offset    {node: T}: a constant torque [N m] on the node
    stribeck  {node: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad] a play in the quill (Modelica's ElastoBacklash: no torque within
              +-gap/2, c (x -+ gap/2) + d x' in contact, the damping never pulling)
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g y + o; a
              delay is the first-order Pade stage (1 - s tau/2)/(1 + s tau/2), from rest
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    mica      (Rm [ohm], order, kappa, phase [rad]): high mica between the commutator's bars:
              the brushes ride up at every bar gap; the loop gains the contact resistance
              Rm exp(kappa (cos(order th - phase) - 1)) in series (a pulse per bar gap)
    eddy      (Tp [N m], wc [rad/s]): the flywheel's eddy-current drag by the magnets of a
              passive magnetic bearing: 2 Tp (wf / wc) / (1 + (wf / wc)^2) against its motion
    hold      Th [s]: the current is read as the drive's controller last sampled it, at the
              instants k Th: the reading at t is i(floor(t / Th) Th)
    leak      tau_l [s]: air leaks into the flywheel's housing: the windage grows with the
              pressure, bf (1 + t / tau_l) wf
    slew      (S [V/s], tau [s]): the drive's output voltage v follows the logged command u
              through a slew-rate limiter, dv/dt = S tanh((u - v) / (S tau)) (a lag tau for
              small differences, at most S volts a second), from 0
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_p_profile.csv"

#: declared values of motor P [SI] (motor_p_motor.yaml)
MOTOR_P: dict[str, float] = {
    "R": 0.55, "L": 0.5e-3, "k": 0.11, "Jm": 9e-5, "bm": 8e-6, "N": 0.5, "Jh": 1.5e-5,
    "c": 15.0, "d": 4e-3, "Jf": 3e-4, "bf": 4e-6, "Tf": 6e-3,
}
#: [rad/s] the friction's and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_p.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.16, 36.0), (0.23, 36.0), (0.232, 44.0),
               (0.29, 44.0), (0.37, 16.0), (0.4, 16.0), (0.43, 0.0), (0.46, 0.0),
               (0.485, -10.0), (0.5, -10.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (40e3, 0.5), "slow": (500.0, 10.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
SHAFTS = ("rotor", "pinion", "fly")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime (the command's corners are restarts)
H_MAX = {"fast": 2.5e-5, "slow": 1e-3}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    if regime == "fast":
        return np.asarray(FAST_POINTS, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def mica_pulse(th: float | np.ndarray, order: float, kappa: float, phase: float) -> Any:
    """The high mica's contact-resistance pulse shape [1]: 1 at each bar gap, ~0 between."""
    return np.exp(kappa * (np.cos(order * th - phase) - 1.0))


# ---------------------------------------------------------------------- the model

class Flywheel:
    """Right-hand side of motor P with one set of effects ``fx`` [SI]. Extra states after
    the six base ones: the current sensor's delay stage, then the drive's output voltage."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.delay = fx.get("sensor", {}).get("current", {}).get("delay")
        self.i_delay = 6 if self.delay is not None else None
        self.i_slew = 6 + (self.delay is not None) if "slew" in fx else None
        self.n = 6 + (self.delay is not None) + ("slew" in fx)
        self.seg = (0.0, 0.0, 0.0)
        self.contact = 0  # the play: +1, -1 in contact; 0 apart or the damper clipped
        self.j1 = p["Jm"] + p["Jh"] / p["N"] ** 2
        self.shaft = {s: self._shaft_terms(s) for s in SHAFTS}

    def _shaft_terms(self, s: str) -> tuple | None:
        """(viscous, Coulomb, offset, harmonics, Stribeck) the effects put on shaft ``s``,
        or None when they put nothing there."""
        fx = self.fx
        terms = (fx.get("visc", {}).get(s, 0.0), fx.get("coul", {}).get(s, 0.0),
                 fx.get("offset", {}).get(s, 0.0), tuple(fx.get("cog", {}).get(s, ())),
                 fx.get("stribeck", {}).get(s))
        return terms if any(terms) else None

    def command(self, t: float) -> float:
        """The logged command u [V] in the current linear segment."""
        t0, u0, slope = self.seg
        return u0 + slope * (t - t0)

    def torque(self, s: str, w: float, ang: float) -> float:
        """The torque [N m] the catalog's effects put on shaft ``s`` at ``w`` [rad/s] and
        ``ang`` [rad]."""
        terms = self.shaft[s]
        if terms is None:
            return 0.0
        visc, coul, off, harm, strib = terms
        out = off - visc * w
        if coul or strib is not None:
            sg = math.tanh(w / W_SIGN)
            out -= coul * sg
            if strib is not None:
                out -= strib[0] * math.exp(-(w / strib[1]) ** 2) * sg
        for order, a, b in harm:
            out += a * math.sin(order * ang) + b * math.cos(order * ang)
        return out

    def side(self, x: float, xd: float, sign: int) -> float:
        """The play's contact law against side ``sign`` (+1, -1) at twist ``x`` [rad] and
        twist rate ``xd`` [rad/s], unclipped [N m]."""
        return self.p["c"] * (x - sign * 0.5 * self.fx["gap"]) + self.p["d"] * xd

    def quill(self, x: float, xd: float) -> float:
        """The torque [N m] the quill passes from the pinion to the flywheel."""
        if "gap" not in self.fx:
            return self.p["c"] * x + self.p["d"] * xd
        if self.contact == 0:
            return 0.0
        return self.contact * max(0.0, self.contact * self.side(x, xd, self.contact))

    def resistance(self, t: float, th: float) -> float:
        """The loop's resistance [ohm]: the armature's (drifting), the extras'."""
        p, fx = self.p, self.fx
        r = p["R"]
        if "alpha" in fx:
            r *= 1.0 + fx["alpha"] * t
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        r += fx.get("Rser", 0.0) + fx.get("Rs", 0.0)
        if "mica" in fx:
            rm, order, kappa, phase = fx["mica"]
            r += rm * math.exp(kappa * (math.cos(order * th - phase) - 1.0))
        return r

    def inductance(self, i: float) -> float:
        """The differential inductance [H] at the current ``i`` [A]."""
        ell = self.p["L"]
        if "lsat" not in self.fx:
            return ell
        ipar, ratio = self.fx["lsat"]
        return ell * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))

    def loop_voltage(self, t: float, z: np.ndarray) -> float:
        """The voltage [V] across L: the drive's output less the loop's drops and the EMF."""
        i, w, th = z[0], z[1], z[2]
        fx = self.fx
        v = z[self.i_slew] if self.i_slew is not None else self.command(t)
        v -= self.resistance(t, th) * i + self.p["k"] * w
        if "Vb" in fx:
            v -= fx["Vb"] * math.tanh(i / I_SIGN)
        for order, a, b in fx.get("emf", ()):
            v -= w * (a * math.sin(order * th) + b * math.cos(order * th))
        return v

    def fly_load(self, t: float, wf: float) -> float:
        """The declared losses of the flywheel and the outside ones [N m] (against it)."""
        p, fx = self.p, self.fx
        bf = p["bf"] * (1.0 + t / fx["leak"]) if "leak" in fx else p["bf"]
        load = bf * wf + p["Tf"] * math.tanh(wf / W_SIGN)
        if "eddy" in fx:
            tp, wc = fx["eddy"]
            r = wf / wc
            load += 2.0 * tp * r / (1.0 + r * r)
        return load

    def __call__(self, t: float, z: np.ndarray) -> np.ndarray:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p = self.p
        i, w, th, x, wf, thf = z[:6]
        n = p["N"]
        dz = np.empty_like(z)
        dz[0] = self.loop_voltage(t, z) / self.inductance(i)
        tq = self.quill(x, w / n - wf)
        pin = self.torque("pinion", w / n, th / n) - tq
        dz[1] = (p["k"] * i - p["bm"] * w + self.torque("rotor", w, th) + pin / n) / self.j1
        dz[2] = w
        dz[3] = w / n - wf
        dz[4] = (tq - self.fly_load(t, wf) + self.torque("fly", wf, thf)) / p["Jf"]
        dz[5] = wf
        if self.i_delay is not None:
            dz[self.i_delay] = (i - z[self.i_delay]) / (0.5 * self.delay)
        if self.i_slew is not None:
            s, tau = self.fx["slew"]
            dz[self.i_slew] = s * math.tanh((self.command(t) - z[self.i_slew]) / (s * tau))
        return dz


# ---------------------------------------------------------------------- integration

#: the play's modes and, for each, the boundaries that end it: (boundary, crossing
#: direction, the mode beyond). "in+"/"in-": in contact; "cl+"/"cl-": past a side with the
#: damper clipped (no torque); "free": inside the play.
PLAY: dict[str, tuple[tuple[str, int, str], ...]] = {
    "free": (("edge+", 1, "in+"), ("edge-", -1, "in-")),
    "in+": (("law+", -1, "cl+"),),
    "cl+": (("law+", 1, "in+"), ("edge+", -1, "free")),
    "in-": (("law-", 1, "cl-"),),
    "cl-": (("law-", -1, "in-"), ("edge-", 1, "free")),
}
CONTACT = {"in+": 1, "in-": -1}


def _boundary(model: Flywheel, name: str, direction: int) -> Any:
    """A terminal event of the play: the twist at a side's edge, or a side's contact law
    through zero."""
    h, n = 0.5 * model.fx["gap"], model.p["N"]
    if name == "edge+":
        def f(t: float, z: np.ndarray) -> float:
            return z[3] - h
    elif name == "edge-":
        def f(t: float, z: np.ndarray) -> float:
            return z[3] + h
    else:
        sign = 1 if name == "law+" else -1

        def f(t: float, z: np.ndarray) -> float:
            return model.side(z[3], z[1] / n - z[4], sign)
    f.terminal, f.direction = True, direction
    return f


def _entered(model: Flywheel, mode: str, z: np.ndarray) -> str:
    """The mode reached at a side's edge from inside the play: in contact when its law
    pushes, else clipped."""
    if mode not in ("in+", "in-"):
        return mode
    sign = CONTACT[mode]
    pushes = sign * model.side(z[3], z[1] / model.p["N"] - z[4], sign) > 0.0
    return mode if pushes else "cl" + mode[-1]


def _solve(model: Flywheel, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
           h_max: float, events: list | None = None) -> Any:
    """solve_ivp from ``a`` to ``b`` [s]: LSODA, then Radau if it fails."""
    msg = ""
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), z0, method=method, t_eval=t_out, rtol=RTOL,
                        atol=ATOL, max_step=h_max, events=events)
        if sol.success and np.isfinite(sol.y).all():
            return sol
        msg = sol.message
    raise RuntimeError(f"motor P, {a:g}-{b:g} s: {msg}")


def _piece(model: Flywheel, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
           h_max: float, mode: list[str]) -> tuple[np.ndarray, np.ndarray]:
    """The states at ``t_out`` [s] within [a, b], and at ``b``; with a play, restarted at
    each of its boundaries (``mode[0]`` carried from piece to piece)."""
    if "gap" not in model.fx:
        sol = _solve(model, a, b, z0, t_out, h_max)
        return sol.y, sol.y[:, -1].copy()
    parts, t0, z = [], a, z0
    while True:
        model.contact = CONTACT.get(mode[0], 0)
        table = PLAY[mode[0]]
        events = [_boundary(model, name, d) for name, d, _ in table]
        rest = t_out[t_out > t0] if parts else t_out[t_out >= t0]
        sol = _solve(model, t0, b, z, rest, h_max, events)
        if sol.status == 0:
            parts.append(sol.y)
            return np.concatenate(parts, axis=1), sol.y[:, -1].copy()
        j = next(k for k, te in enumerate(sol.t_events) if te.size)
        t0, z = float(sol.t_events[j][0]), sol.y_events[j][0].copy()
        parts.append(sol.y[:, sol.t <= t0] if sol.t.size else sol.y)
        mode[0] = _entered(model, table[j][2], z)


def integrate(model: Flywheel, t: np.ndarray, bp: np.ndarray, h_max: float) -> np.ndarray:
    """The states at the times ``t`` [s], from rest at t[0], restarted at every corner of
    the command ``bp`` [s, V]. Returns (n_states, t.size)."""
    cuts = [float(t[0]), *(float(c) for c in bp[:, 0] if t[0] < c < t[-1]), float(t[-1])]
    z0 = np.zeros(model.n)
    y = np.empty((model.n, t.size))
    mode = ["free"]
    for j in range(len(cuts) - 1):
        a, b = cuts[j], cuts[j + 1]
        ua, ub = np.interp([a, b], bp[:, 0], bp[:, 1])
        model.seg = (a, float(ua), float((ub - ua) / (b - a)))
        last = j == len(cuts) - 2
        sel = (t >= a) & (t <= b) if last else (t >= a) & (t < b)
        t_out = t[sel] if last else np.append(t[sel], b)
        ys, z0 = _piece(model, a, b, z0, t_out, h_max, mode)
        y[:, sel] = ys[:, :int(sel.sum())]
    return y


def hold_instants(t: np.ndarray, th: float) -> np.ndarray:
    """The instants floor(t / th) th [s] at which a reading at ``t`` was sampled (a
    nanosecond's tolerance, so that a time on the hold grid holds its own sample)."""
    return np.floor(np.asarray(t) / th + 1e-6) * th


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor P at the times ``t`` [s] (default: the nominal grid), from
    rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the flywheel's pickup), plus the command ``u`` [V]. ``states``: add
    the angles [rad] and the quill's twist [rad]."""
    fx = dict(fx or {})
    p = {**MOTOR_P, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = Flywheel(fx, p)
    t_run, at = t, None
    if "hold" in fx:
        t_run, inv = np.unique(np.concatenate([t, hold_instants(t, fx["hold"])]),
                               return_inverse=True)
        at = inv[t.size:]
    y = integrate(model, t_run, bp, H_MAX[regime])
    own = np.searchsorted(t_run, t)
    full = {"current": y[0][own], "speed": y[1][own], "load_speed": y[4][own]}
    if model.i_delay is not None:
        full["current"] = 2.0 * y[model.i_delay][own] - full["current"]
    if at is not None:
        full["current"] = y[0][at]
    out = {probe: full[probe].copy() for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2][own], twist=y[3][own], fly_angle=y[5][own])
    return out


# ---------------------------------------------------------------------- noise

def gauss_markov(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float
                 ) -> np.ndarray:
    """A stationary first-order Gauss-Markov process [probe unit] of standard deviation
    ``sigma`` and correlation time ``tau`` [s], exact at the times ``t`` [s] however uneven:
    x_k = r_k x_(k-1) + sigma sqrt(1 - r_k^2) e_k, r_k = exp(-(t_k - t_(k-1)) / tau)."""
    r = np.exp(-np.diff(np.asarray(t, dtype=float)) / tau)
    e = rng.standard_normal(len(t))
    x = np.empty(len(t))
    x[0] = sigma * e[0]
    kick = sigma * np.sqrt(1.0 - r * r) * e[1:]
    for k in range(1, len(t)):
        x[k] = r[k - 1] * x[k - 1] + kick[k - 1]
    return x


def ar1(rng: np.random.Generator, t: np.ndarray, sigma: float, phi: float) -> np.ndarray:
    """AR(1) noise [probe unit]: correlation ``phi`` over the mean interval, a Gauss-Markov
    process of correlation time -mean(dt) / ln(phi) [s]."""
    return gauss_markov(rng, t, sigma, -float(np.mean(np.diff(t))) / math.log(phi))


def pink(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma`` at the times ``t`` [s]: equal
    variance Gauss-Markov processes whose correlation times are spaced by factors of two
    from the record's length down to the mean interval (their summed Lorentzians make a 1/f
    spectrum between the two), mean removed and scaled."""
    span, dt = float(t[-1] - t[0]), float(np.mean(np.diff(t)))
    taus = span * 0.5 ** np.arange(int(math.log2(span / dt)) + 1)
    x = np.sum([gauss_markov(rng, t, 1.0, tau) for tau in taus], axis=0)
    x -= x.mean()
    return sigma * x / x.std()


def add_noise(rng: np.random.Generator, t: np.ndarray, y: np.ndarray,
              spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` at the times ``t`` [s] with ``white`` sigma, ``ar1`` [sigma, phi] and ``pink``
    sigma noise added [probe unit], then read by an ADC of step ``quant`` [probe unit]."""
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out += rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        out += ar1(rng, t, *spec["ar1"])
    if spec.get("pink"):
        out += pink(rng, t, spec["pink"])
    step = spec.get("quant")
    return np.round(out / step) * step if step else out
