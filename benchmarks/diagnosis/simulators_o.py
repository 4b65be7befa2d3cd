"""Motor O of the diagnosis benchmark: a hand-written scipy model of a 36 V, 500 W class
permanent-magnet brushed DC motor whose winding warms from its own loss, driving a triplex
plunger pump (a crop sprayer's pump, spraying through its nozzles) through a rigid 3:1
gearhead and a compliant tyre coupling.

No circuitsim import: an independent simulator (the twelfth of the benchmark), written from
the physics for netlists/motor_o_motor.yaml, motor_o.yaml and motor_o_slow.yaml. It is
evaluated at the record's own sample times (``t_eval``), never on a grid that is then
interpolated.

State z = [i, w, th, x, wp, thp, Tw, Th] (+ the sensor delay's stage, + the battery's
drawn charge):

    i       armature current [A]
    w, th   rotor speed [rad/s] and angle [rad]; the gearhead's output turns at w / N
    x       the coupling's twist th / N - thp [rad]
    wp, thp the pump crank's speed [rad/s] and angle [rad]
    Tw, Th  winding and housing temperatures [K]

Equations (J1 = Jm + Jo / N^2, the rotor and the gearhead's output seen by the rotor):

    L di/dt   = v(t) - R(Tw) i - k w - (loop extras),   R(Tw) = R0 (1 + a_cu (Tw - Tref))
    J1 dw/dt  = k i - bm w + X_rotor + (X_out - Tk) / N
    Jp dwp/dt = Tk - bp wp - Tf tanh(wp / 0.01) - cq wp |wp| + X_crank
    Tk        = c x + d (w / N - wp)                       (the tyre coupling ``K``)
    Cw dTw/dt = R(Tw) i^2 - Gwh (Tw - Th)
    Ch dTh/dt = Gwh (Tw - Th) - Gha (Th - Ta)

cq wp |wp| is the nozzles' pressure load (the pressure grows with the square of the mean
flow), Tf tanh(wp / 0.01) the plungers' packing friction (``friction``, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    emf       (order, a, b): the EMF gains w (a sin(order th) + b cos(order th)), voltage only
    cog       {node: [(order, a, b), ...]}: the node (rotor, out, crank) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {node: c}: c tanh(speed / 0.01) against the node's motion [N m]
    visc      {node: b}: an extra viscous friction [N m s/rad]
    stribeck  {node: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad] a play in the coupling (Modelica's ElastoBacklash: no torque within
              +-gap/2, c (x -+ gap/2) + d x' in contact, the damping never pulling)
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g y + o; a
              delay is the first-order Pade stage (1 - s tau/2)/(1 + s tau/2), from rest

and outside the catalog:

    pulse     kappa: the plungers' discharge pulsates: the pressure load becomes
              cq wp |wp| (1 + kappa (S(thp)^3 / <S^3> - 1)), S(thp) = sum over the three
              plungers of max(0, sin(thp - 2 pi j / 3))
    relief    (Tc [N m], s, delta [N m]): the pressure-relief valve opens: the load q =
              cq wp |wp| becomes q - (1 - s) (sp(q - Tc) - sp(-q - Tc)), sp(y) = delta
              log(1 + exp(y / delta))
    battery   (V0 [V], kq [V/C], Vnom [V]): the drive's duty u / Vnom chops a battery whose
              voltage V0 - kq q falls with the charge q [C] it delivers, dq/dt = u i / Vnom
    prime     (a0, th1 [rad], dth [rad]): the pump starts air-bound: its pressure load is
              scaled by a0 + (1 - a0) (1 + tanh((thp - th1) / dth)) / 2
    tooth     (thc [rad], width [rad], kappa): the speed is read from a toothed wheel with a
              missing tooth: w (1 - G / 2), G = (1 + tanh(kappa (cos(th - thc) -
              cos(width / 2)))) / 2, the reading halving for one pitch per turn
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_o_profile.csv"

#: declared values of motor O [SI] (motor_o_motor.yaml)
MOTOR_O: dict[str, float] = {
    "R": 0.3, "a_cu": 3.93e-3, "Tref": 293.15, "L": 0.45e-3, "k": 0.075,
    "Jm": 1.6e-4, "bm": 1e-5, "N": 3.0, "Jo": 4e-4, "c": 180.0, "d": 0.06,
    "Jp": 2.5e-3, "bp": 2e-3, "Tf": 0.4, "cq": 9e-5,
    "Cw": 180.0, "Gwh": 2.5, "Ch": 900.0, "Gha": 3.0, "Ta": 293.15,
}
#: [rad/s] the friction's and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_o.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.005, 0.0), (0.105, 36.0), (0.2, 36.0), (0.203, 24.0),
               (0.26, 24.0), (0.262, 0.0), (0.31, 0.0), (0.325, -24.0), (0.4, -24.0),
               (0.43, 20.0), (0.5, 20.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (50e3, 0.5), "slow": (1000.0, 8.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
NODES = ("rotor", "out", "crank")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime (the command's corners are restarts)
H_MAX = {"fast": 5e-5, "slow": 1e-3}
#: the mean of S^3 over a turn, S the three plungers' summed discharge rate (see ``pulse``)
_TH = np.linspace(0.0, 2.0 * np.pi, 720001)[:-1]
_S = sum(np.maximum(0.0, np.sin(_TH - 2.0 * np.pi * j / 3.0)) for j in range(3))
S3_MEAN = float(np.mean(_S ** 3))


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    if regime == "fast":
        return np.asarray(FAST_POINTS, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def plunger_rate(th: float) -> float:
    """S(th) [1]: the three plungers' summed discharge rate per unit stroke speed."""
    return sum(max(0.0, math.sin(th - 2.0 * math.pi * j / 3.0)) for j in range(3))


def softplus(y: float, delta: float) -> float:
    """delta log(1 + exp(y / delta)) [N m], overflow-safe."""
    return delta * float(np.logaddexp(0.0, y / delta))


# ---------------------------------------------------------------------- the model

class MotorO:
    """Right-hand side of motor O with one set of effects ``fx`` [SI]. Extra states after
    the eight base ones: the current sensor's delay stage, then the battery's charge."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.delay = fx.get("sensor", {}).get("current", {}).get("delay")
        self.n = 8 + (self.delay is not None) + ("battery" in fx)
        self.seg = (0.0, 0.0, 0.0)
        self.mode = 0  # the play's contact: +1, -1, or 0 (apart, or the damper clipped)
        self.j1 = p["Jm"] + p["Jo"] / p["N"] ** 2
        self.torq = {node: (fx.get("visc", {}).get(node, 0.0),
                            fx.get("coul", {}).get(node, 0.0),
                            tuple(fx.get("cog", {}).get(node, ())),
                            fx.get("stribeck", {}).get(node)) for node in NODES}

    def command(self, t: float) -> float:
        """The command u [V] in the current linear segment."""
        ta, ua, slope = self.seg
        return ua + slope * (t - ta)

    def extra(self, node: str, w: float, angle: float) -> float:
        """The torque [N m] the catalog's effects add on ``node`` at ``w`` [rad/s] and
        ``angle`` [rad]."""
        visc, coul, harm, strib = self.torq[node]
        tq = -visc * w
        if coul or strib is not None:
            sgn = math.tanh(w / W_SIGN)
            tq -= coul * sgn
            if strib is not None:
                tq -= strib[0] * math.exp(-(w / strib[1]) ** 2) * sgn
        for order, a, b in harm:
            tq += a * math.sin(order * angle) + b * math.cos(order * angle)
        return tq

    def push(self, x: float, xd: float, side: int) -> float:
        """The play's contact law on ``side`` (+1, -1) at twist ``x`` [rad] and twist rate
        ``xd`` [rad/s], before clipping [N m]."""
        return self.p["c"] * (x - side * 0.5 * self.fx["gap"]) + self.p["d"] * xd

    def coupling(self, x: float, xd: float) -> float:
        """The torque [N m] the coupling passes from the gearhead's output to the crank."""
        if "gap" not in self.fx:
            return self.p["c"] * x + self.p["d"] * xd
        if self.mode == 0:
            return 0.0
        return self.mode * max(0.0, self.mode * self.push(x, xd, self.mode))

    def pump_load(self, wp: float, thp: float) -> float:
        """The nozzles' pressure load on the crank [N m] (against its motion)."""
        fx = self.fx
        q = self.p["cq"] * wp * abs(wp)
        if "relief" in fx:
            tc, s, delta = fx["relief"]
            q -= (1.0 - s) * (softplus(q - tc, delta) - softplus(-q - tc, delta))
        if "pulse" in fx:
            q *= 1.0 + fx["pulse"] * (plunger_rate(thp) ** 3 / S3_MEAN - 1.0)
        if "prime" in fx:
            a0, th1, dth = fx["prime"]
            q *= a0 + (1.0 - a0) * 0.5 * (1.0 + math.tanh((thp - th1) / dth))
        return q

    def voltage(self, t: float, z: np.ndarray) -> float:
        """The armature's terminal voltage [V] the drive applies."""
        u = self.command(t)
        if "battery" in self.fx:
            v0, kq, vnom = self.fx["battery"]
            return u * (v0 - kq * z[-1]) / vnom
        return u

    def loop(self, i: float, w: float, th: float, tw: float) -> float:
        """The loop's voltage [V] besides L di/dt and k w, at ``i`` [A]."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + p["a_cu"] * (tw - p["Tref"])) + fx.get("Rser", 0.0) \
            + fx.get("Rs", 0.0)
        v = r * i + fx.get("Vb", 0.0) * math.tanh(i / I_SIGN)
        for order, a, b in fx.get("emf", ()):
            v += w * (a * math.sin(order * th) + b * math.cos(order * th))
        return v

    def __call__(self, t: float, z: np.ndarray) -> np.ndarray:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p = self.p
        i, w, th, x, wp, thp, tw, th_h = z[:8]
        n = p["N"]
        dz = np.empty_like(z)
        r_cu = p["R"] * (1.0 + p["a_cu"] * (tw - p["Tref"]))
        dz[0] = (self.voltage(t, z) - self.loop(i, w, th, tw) - p["k"] * w) / p["L"]
        tk = self.coupling(x, w / n - wp)
        out = self.extra("out", w / n, th / n) - tk
        dz[1] = (p["k"] * i - p["bm"] * w + self.extra("rotor", w, th) + out / n) / self.j1
        dz[2] = w
        dz[3] = w / n - wp
        dz[4] = (tk - p["bp"] * wp - p["Tf"] * math.tanh(wp / W_SIGN)
                 - self.pump_load(wp, thp) + self.extra("crank", wp, thp)) / p["Jp"]
        dz[5] = wp
        dz[6] = (r_cu * i * i - p["Gwh"] * (tw - th_h)) / p["Cw"]
        dz[7] = (p["Gwh"] * (tw - th_h) - p["Gha"] * (th_h - p["Ta"])) / p["Ch"]
        if self.delay is not None:
            dz[8] = (i - z[8]) / (0.5 * self.delay)
        if "battery" in self.fx:
            dz[-1] = self.command(t) * i / self.fx["battery"][2]
        return dz


# ---------------------------------------------------------------------- integration

#: the play's states, each with its events: (function name, direction, next state)
PLAY_EVENTS: dict[str, tuple[tuple[str, int, str], ...]] = {
    "apart": (("x-h", 1, "+?"), ("x+h", -1, "-?")),
    "+": (("push+", -1, "+c"),), "+c": (("push+", 1, "+"), ("x-h", -1, "apart")),
    "-": (("push-", 1, "-c"),), "-c": (("push-", -1, "-"), ("x+h", 1, "apart")),
}


def _play_function(model: MotorO, name: str) -> Any:
    """An event function of the play: the twist against a side, or a side's contact law."""
    h, n = 0.5 * model.fx["gap"], model.p["N"]
    if name == "x-h":
        return lambda t, z: z[3] - h
    if name == "x+h":
        return lambda t, z: z[3] + h
    side = 1 if name == "push+" else -1
    return lambda t, z: model.push(z[3], z[1] / n - z[4], side)


def _resolve(model: MotorO, state: str, z: np.ndarray) -> str:
    """A state reached at a side: touching it if the contact law pushes, else clipped."""
    if state not in ("+?", "-?"):
        return state
    side = 1 if state == "+?" else -1
    pushes = side * model.push(z[3], z[1] / model.p["N"] - z[4], side) > 0.0
    return state[0] if pushes else state[0] + "c"


def _ivp(model: MotorO, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
         h_max: float, events: list | None = None) -> Any:
    """solve_ivp from ``a`` to ``b`` [s]: LSODA, Radau if it fails."""
    sol = None
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), z0, method=method, t_eval=t_out, rtol=RTOL,
                        atol=ATOL, max_step=h_max, events=events)
        if sol.success and np.isfinite(sol.y).all():
            return sol
    raise RuntimeError(f"motor O, {a:g}-{b:g} s: {sol.message if sol else 'none'}")


def _segment(model: MotorO, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
             h_max: float, play: list[str]) -> tuple[np.ndarray, np.ndarray]:
    """The states at ``t_out`` [s] within [a, b] and at ``b``; with a play, restarted at
    each of its events (the state ``play[0]`` carried across segments)."""
    if "gap" not in model.fx:
        sol = _ivp(model, a, b, z0, t_out, h_max)
        return sol.y, sol.y[:, -1].copy()
    ys, t0, z = [], a, z0
    while True:
        state = play[0]
        model.mode = {"+": 1, "-": -1}.get(state, 0)
        evs = []
        for name, direction, _ in PLAY_EVENTS[state]:
            f = _play_function(model, name)
            f.terminal, f.direction = True, direction
            evs.append(f)
        rest = t_out[t_out > t0] if ys else t_out[t_out >= t0]
        sol = _ivp(model, t0, b, z, rest, h_max, evs)
        if sol.status == 0:
            ys.append(sol.y)
            return np.concatenate(ys, axis=1), sol.y[:, -1].copy()
        k = next(j for j, te in enumerate(sol.t_events) if te.size)
        t0, z = float(sol.t_events[k][0]), sol.y_events[k][0].copy()
        ys.append(sol.y[:, sol.t <= t0] if sol.t.size else sol.y)
        play[0] = _resolve(model, PLAY_EVENTS[state][k][2], z)


def integrate(model: MotorO, t: np.ndarray, bp: np.ndarray, h_max: float) -> np.ndarray:
    """The states at the times ``t`` [s], from rest (cold, at the ambient) at t[0],
    restarted at every corner of the command ``bp`` [s, V]. Returns (n_states, t.size)."""
    cuts = [float(t[0]), *(float(x) for x in bp[:, 0] if t[0] < x < t[-1]), float(t[-1])]
    z0 = np.zeros(model.n)
    z0[6] = z0[7] = model.p["Ta"]
    y = np.empty((model.n, t.size))
    play = ["apart"]
    for j in range(len(cuts) - 1):
        a, b = cuts[j], cuts[j + 1]
        ua, ub = np.interp([a, b], bp[:, 0], bp[:, 1])
        model.seg = (a, float(ua), float((ub - ua) / (b - a)))
        last = j == len(cuts) - 2
        sel = (t >= a) & (t <= b) if last else (t >= a) & (t < b)
        t_out = t[sel] if last else np.append(t[sel], b)
        ys, z0 = _segment(model, a, b, z0, t_out, h_max, play)
        y[:, sel] = ys[:, :int(sel.sum())]
    return y


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor O at the times ``t`` [s] (default: the nominal grid), from
    rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the crank's), plus the command ``u`` [V]. ``states``: add the
    angles [rad], the twist [rad] and the temperatures [K]."""
    fx = dict(fx or {})
    p = dict(MOTOR_O if p is None else p)
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = MotorO(fx, p)
    y = integrate(model, t, bp, H_MAX[regime])
    full = {"current": y[0].copy(), "speed": y[1].copy(), "load_speed": y[4].copy()}
    if model.delay is not None:
        full["current"] = 2.0 * y[8] - y[0]
    if "tooth" in fx:
        thc, width, kappa = fx["tooth"]
        g = 0.5 * (1.0 + np.tanh(kappa * (np.cos(y[2] - thc) - math.cos(0.5 * width))))
        full["speed"] = y[1] * (1.0 - 0.5 * g)
    out = {probe: full[probe] for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2], twist=y[3], crank_angle=y[5], T_winding=y[6],
                   T_housing=y[7])
    return out


# ---------------------------------------------------------------------- noise

def markov(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float) -> np.ndarray:
    """A stationary first-order Gauss-Markov process [probe unit] of standard deviation
    ``sigma`` and correlation time ``tau`` [s], exact at the times ``t`` [s] however
    uneven: x_k = r_k x_(k-1) + sigma sqrt(1 - r_k^2) e_k, r_k = exp(-(t_k - t_(k-1)) / tau)."""
    r = np.exp(-np.diff(t) / tau)
    kick = sigma * rng.standard_normal(t.size)
    kick[1:] *= np.sqrt(1.0 - r * r)
    x = np.empty(t.size)
    acc = 0.0
    for j, (rk, e) in enumerate(zip(np.concatenate([[0.0], r]), kick, strict=True)):
        acc = rk * acc + e
        x[j] = acc
    return x


def ar1(rng: np.random.Generator, t: np.ndarray, sigma: float, phi: float) -> np.ndarray:
    """AR(1) noise [probe unit]: correlation ``phi`` over the mean interval, i.e. a
    Gauss-Markov process of correlation time -mean(dt) / ln(phi) [s]."""
    return markov(rng, t, sigma, -float(np.mean(np.diff(t))) / math.log(phi))


def pink(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma`` at the times ``t`` [s]: the
    sum of equal-variance Gauss-Markov processes whose corner frequencies are spaced by
    factors of two from the record's length to the mean sample rate (a 1/f spectrum between
    them), mean removed and scaled."""
    span, dt = float(t[-1] - t[0]), float(np.mean(np.diff(t)))
    taus = span / 2.0 ** np.arange(int(math.log2(span / dt)) + 1)
    x = sum(markov(rng, t, 1.0, tau) for tau in taus)
    x -= x.mean()
    return sigma * x / x.std()


def add_noise(rng: np.random.Generator, t: np.ndarray, y: np.ndarray,
              spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` at the times ``t`` [s] with ``white`` sigma, ``ar1`` [sigma, phi] and ``pink``
    sigma noise added [probe unit], then read by an ADC of step ``quant`` [probe unit]."""
    out = np.asarray(y, dtype=float) + (rng.normal(0.0, spec["white"], len(y))
                                        if spec.get("white") else 0.0)
    if spec.get("ar1"):
        out = out + ar1(rng, t, *spec["ar1"])
    if spec.get("pink"):
        out = out + pink(rng, t, spec["pink"])
    step = spec.get("quant")
    return np.round(out / step) * step if step else out
