"""Motor J of the diagnosis benchmark: a hand-written scipy model of a 30 V, 150 W class
permanent-magnet brushed DC servo motor driving one horizontal joint of a robot arm through a
100:1 harmonic drive. The harmonic drive is a rigid reduction followed by the flexspline's
torsional compliance; the arm turns in a horizontal plane (no gravity torque is declared).

No circuitsim import: an independent simulator (the sixth of the benchmark), written from the
physics for netlists/motor_j_motor.yaml, motor_j.yaml and motor_j_slow.yaml.

Base state (6 numbers) z = [i, w, th, q, wa, tha]:

    i    armature current [A]
    w    rotor speed [rad/s],  th  rotor angle [rad]; the flexspline's cup (node ``hd``)
         turns rigidly with it at w / N, angle th / N
    q    twist of the flexspline: the spring's input angle minus the arm angle [rad]
    wa   arm speed [rad/s],    tha arm angle [rad]

Equations (positive rotation is the arm swinging out):

    L(i) di/dt   = v - R(t) i - e,                 e = kf k w (+ an EMF harmonic)
    Jr dw/dt     = kf k i - bm w - Tc tanh(w / 0.01) - T_K g'(th) + X_rotor + X_hd / N
    dq/dt        = w g'(th) - wa,                  T_K = c q + d dq/dt
    Ja dwa/dt    = T_K - ba wa + X_arm

with Jr = Jm + Jh / N^2 (the cup is geared rigidly to the rotor), g(th) the spring's input
angle as a function of the rotor angle (th / N for the declared, perfect gear), kf = 1
unless the magnets lose flux, and X_node the torques an effect adds on a node.

Effects (``fx`` keys, SI, all off by default) -- the catalog's laws, as its patches write them:

    Rs        [ohm]   an internal resistance of the supply
    Rser      [ohm]   a resistance in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   R(t) = R (1 + alpha t)
    warmup    (rise, tau [s]): R(t) = R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): L(i) = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2)), the
              differential inductance of Modelica's SaturatingInductor at Lzer = L,
              Linf = ratio L
    emf_h     (order, a, b): e gains w (a sin(order th) + b cos(order th)), voltage only
    cog       {node: [(order, a, b), ...]}: the node (rotor, hd or arm) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {node: c}: a Coulomb friction c tanh(speed / 0.01) against the node's motion
    visc      {node: b}: an extra viscous friction on the node
    offset    {node: F}: a constant torque F the node receives
    stribeck  {node: (s, ws)}: a breakaway peak s exp(-(speed / ws)^2) tanh(speed / 0.01)
              against the motion, over the declared friction
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g y + o, y
              the probe through the first-order Pade stage of a delay tau (reads 2 s - x,
              tau/2 ds/dt = x - s, s(0) = 0)
    (a declared value off: pass motor parameters ``p`` with another value)

and outside the catalog:

    kinerr    (eps [rad], phase): the harmonic drive's transmission error: the flexspline's
              output leads the perfect gear by eps sin(2 th + phase) (twice per turn of the
              wave generator): g(th) = th / N + eps sin(2 th + phase)
    hyst      h [A]: the Hall current sensor's core has magnetic hysteresis: it reads the
              current through a play (backlash) operator of half-width h: the reading lags
              the current by h in the direction the current last moved
    harness   (kc [N m/rad], th0 [rad]): the cable harness along the arm twists like a
              torsion spring: the arm receives -kc (tha - th0)
    brake     (Tb [N m], phase): the motor's spring-applied holding brake does not release
              fully: a warped friction disc rubs once per rotor turn, a friction
              Tb (1 + cos(th + phase)) / 2 tanh(w / 0.01) against the rotor's motion
    demag     (delta, I1 [A], Iw [A], G [1/s]): the magnets lose flux irreversibly when the
              current's magnitude exceeds I1: kf = 1 - delta (1 - exp(-(max(m - I1, 0)/Iw)^2))
              of the peak current m so far (a state following |i| upwards at rate G, never
              downwards), in the EMF and the torque alike
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_j_profile.csv"

#: declared values of motor J [SI] (motor_j_motor.yaml)
MOTOR_J: dict[str, float] = {
    "R": 0.75, "L": 0.18e-3, "k": 0.05, "Jm": 1.6e-5, "bm": 5e-6, "Tc": 6e-3, "N": 100.0,
    "Jh": 1e-3, "c": 6000.0, "d": 2.5, "Ja": 0.45, "ba": 0.2,
}
#: [rad/s] circuitsim's friction (w_brk 0.1) and the catalog's friction switch as tanh(w/0.01)
W_SIGN = 0.01
#: [A] the catalog's brush drop switches sign as tanh(i / 1 mA)
I_SIGN = 1e-3
#: the fast regime's command [s, V] (motor_j.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.002, 0.0), (0.004, 24.0), (0.12, 24.0), (0.122, 8.0),
               (0.2, 8.0), (0.202, -20.0), (0.33, -20.0), (0.332, 0.0), (0.4, 0.0),
               (0.41, 12.0), (0.5, 12.0))
REGIMES: dict[str, tuple[float, float]] = {"fast": (25e3, 0.5), "slow": (1e3, 5.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
NODES = ("rotor", "hd", "arm")
RTOL, ATOL = 1e-10, 1e-12


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t, u]: the command, linear between points, held after the last."""
    if regime == "fast":
        return np.asarray(FAST_POINTS, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def _relu(x: float, eps: float) -> float:
    """max(x, 0), smoothed over eps."""
    return 0.5 * (x + math.sqrt(x * x + eps * eps))


class MotorJ:
    """Right-hand side of motor J with one set of effects; states the effects need are
    appended after the six base ones."""

    def __init__(self, bp: np.ndarray, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.t_cmd, self.u_cmd = bp[:, 0].copy(), bp[:, 1].copy()
        self.fx, self.p = fx, p
        self.n = 6
        self.idx: dict[str, int] = {}
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.idx["delay:" + probe] = self._grow()
        if "demag" in fx:
            self.idx["demag"] = self._grow()
        self.j_rotor = p["Jm"] + p["Jh"] / p["N"] ** 2
        # the extras per node: (offset, viscous, Coulomb, [(order, a, b)], (s, ws) or None)
        self.extra = {}
        for node in NODES:
            self.extra[node] = (fx.get("offset", {}).get(node, 0.0),
                                fx.get("visc", {}).get(node, 0.0),
                                fx.get("coul", {}).get(node, 0.0),
                                list(fx.get("cog", {}).get(node, ())),
                                fx.get("stribeck", {}).get(node))

    def _grow(self) -> int:
        self.n += 1
        return self.n - 1

    def x0(self) -> np.ndarray:
        return np.zeros(self.n)

    def u(self, t: float) -> float:
        return float(np.interp(t, self.t_cmd, self.u_cmd))

    def node_torque(self, node: str, w: float, angle: float) -> float:
        off, visc, coul, harm, strib = self.extra[node]
        tq = off - visc * w
        sgn = math.tanh(w / W_SIGN) if (coul or strib) else 0.0
        tq -= coul * sgn
        if strib is not None:
            s, ws = strib
            tq -= s * math.exp(-(w / ws) ** 2) * sgn
        for order, a, b in harm:
            tq += a * math.sin(order * angle) + b * math.cos(order * angle)
        return tq

    def resistance(self, t: float) -> float:
        r0 = self.p["R"]
        r = r0 * (1.0 + self.fx.get("alpha", 0.0) * t)
        if "warmup" in self.fx:
            rise, tau = self.fx["warmup"]
            r += r0 * rise * (1.0 - math.exp(-t / tau))
        return r + self.fx.get("Rser", 0.0)

    def inductance(self, i: float) -> float:
        if "lsat" not in self.fx:
            return self.p["L"]
        ipar, ratio = self.fx["lsat"]
        return self.p["L"] * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))

    def flux(self, z: np.ndarray) -> float:
        """kf: the magnets' flux relative to the declared."""
        if "demag" not in self.fx:
            return 1.0
        delta, i1, iw, _ = self.fx["demag"]
        x = max(z[self.idx["demag"]] - i1, 0.0) / iw
        return 1.0 - delta * (1.0 - math.exp(-x * x))

    def gear_slope(self, th: float) -> tuple[float, float]:
        """(g(th) - th/N, g'(th)): the transmission error and the gear's local ratio."""
        n = self.p["N"]
        if "kinerr" not in self.fx:
            return 0.0, 1.0 / n
        eps, ph = self.fx["kinerr"]
        return eps * math.sin(2.0 * th + ph), 1.0 / n + 2.0 * eps * math.cos(2.0 * th + ph)

    def __call__(self, t: float, z: np.ndarray) -> np.ndarray:
        p, fx = self.p, self.fx
        i, w, th, q, wa, tha = z[:6]
        n = p["N"]
        dz = np.zeros_like(z)
        kf = self.flux(z)
        k = p["k"] * kf

        # armature loop
        v = self.u(t) - fx.get("Rs", 0.0) * i - fx.get("Vb", 0.0) * math.tanh(i / I_SIGN)
        e = k * w
        if "emf_h" in fx:
            order, a, b = fx["emf_h"]
            e += w * (a * math.sin(order * th) + b * math.cos(order * th))
        dz[0] = (v - self.resistance(t) * i - e) / self.inductance(i)

        # rotor (with the cup), flexspline, arm
        _, slope = self.gear_slope(th)
        dq = w * slope - wa
        t_k = p["c"] * q + p["d"] * dq
        t_rotor = k * i - p["bm"] * w - p["Tc"] * math.tanh(w / W_SIGN) - t_k * slope
        t_rotor += self.node_torque("rotor", w, th) + self.node_torque("hd", w / n, th / n) / n
        if "brake" in fx:
            tb, ph = fx["brake"]
            t_rotor -= tb * 0.5 * (1.0 + math.cos(th + ph)) * math.tanh(w / W_SIGN)
        dz[1] = t_rotor / self.j_rotor
        dz[2] = w
        dz[3] = dq
        t_arm = t_k - p["ba"] * wa + self.node_torque("arm", wa, tha)
        if "harness" in fx:
            kc, th0 = fx["harness"]
            t_arm -= kc * (tha - th0)
        dz[4] = t_arm / p["Ja"]
        dz[5] = wa

        # the sensors' delay stages and the peak current
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                j = self.idx["delay:" + probe]
                dz[j] = (self.quantity(probe, z) - z[j]) / (0.5 * s["delay"])
        if "demag" in fx:
            j = self.idx["demag"]
            gain = fx["demag"][3]
            dz[j] = gain * _relu(math.sqrt(i * i + 1e-6) - z[j], 1e-3)
        return dz

    @staticmethod
    def quantity(probe: str, z: np.ndarray) -> Any:
        """The physical quantity a probe measures, from a state (or an array of states)."""
        return {"current": z[0], "speed": z[1], "load_speed": z[4]}[probe]


def play(x: np.ndarray, h: float) -> np.ndarray:
    """The play (backlash) operator of half-width h on a sampled signal, from y(0) = x(0)."""
    y = np.empty_like(x)
    cur = float(x[0])
    for j, v in enumerate(x):
        if v - cur > h:
            cur = v - h
        elif cur - v > h:
            cur = v + h
        y[j] = cur
    return y


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor J on ``t`` (default: the record grid), from rest, plus the
    command ``u``: current, speed (and load_speed in the slow regime). ``states``: add the
    arm angle ``arm_angle`` and the rotor angle ``rotor_angle`` (for reports)."""
    fx = dict(fx or {})
    p = dict(MOTOR_J if p is None else p)
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = MotorJ(bp, fx, p)
    # the command has kinks at its breakpoints: integrate piecewise, restarting at each
    cuts = [float(t[0])] + [float(b) for b in bp[:, 0] if t[0] < b < t[-1]] + [float(t[-1])]
    z0 = model.x0()
    y = np.empty((model.n, t.size))
    h_max = 1.0 / REGIMES[regime][0]
    for j in range(len(cuts) - 1):
        a, b = cuts[j], cuts[j + 1]
        last = j == len(cuts) - 2
        sel = (t >= a) & (t <= b) if last else (t >= a) & (t < b)
        t_out = t[sel] if last else np.append(t[sel], b)
        sol = None
        for method in ("LSODA", "Radau"):
            sol = solve_ivp(model, (a, b), z0, method=method, t_eval=t_out, rtol=RTOL,
                            atol=ATOL, max_step=h_max)
            if sol.success and np.isfinite(sol.y).all():
                break
        if sol is None or not (sol.success and np.isfinite(sol.y).all()):
            raise RuntimeError(f"motor J, {regime}, {a:g}-{b:g} s: "
                               f"{sol.message if sol else 'no solution'}")
        y[:, sel] = sol.y[:, :sel.sum()]
        z0 = sol.y[:, -1].copy()

    out: dict[str, np.ndarray] = {}
    for probe in PROBES[regime]:
        x = np.asarray(model.quantity(probe, y), dtype=float)
        s = fx.get("sensor", {}).get(probe, {})
        if s.get("delay"):
            x = 2.0 * y[model.idx["delay:" + probe]] - x
        out[probe] = x
    if "hyst" in fx:
        out["current"] = play(out["current"], fx["hyst"])
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out["rotor_angle"] = y[2].copy()
        out["arm_angle"] = y[5].copy()
        if "demag" in fx:
            out["flux"] = np.array([model.flux(y[:, j]) for j in range(t.size)])
    return out


# ---------------------------------------------------------------------- noise

def ar1(rng: np.random.Generator, n: int, sigma: float, phi: float) -> np.ndarray:
    """A stationary AR(1) sequence with marginal standard deviation ``sigma``."""
    e = rng.normal(0.0, sigma * math.sqrt(1.0 - phi * phi), n)
    e[0] = rng.normal(0.0, sigma)
    out = np.empty(n)
    acc = 0.0
    for j in range(n):
        acc = e[j] if j == 0 else phi * acc + e[j]
        out[j] = acc
    return out


def pink(rng: np.random.Generator, n: int, sigma: float) -> np.ndarray:
    """1/f noise: white noise shaped by f^-1/2 in the frequency domain, mean removed,
    standard deviation ``sigma``."""
    spec = np.fft.rfft(rng.normal(size=n))
    f = np.fft.rfftfreq(n)
    spec[0] = 0.0
    spec[1:] = spec[1:] / np.sqrt(f[1:])
    x = np.fft.irfft(spec, n)
    return sigma * x / np.std(x)


def add_noise(rng: np.random.Generator, y: np.ndarray, spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` plus ``white`` sigma, ``ar1`` [sigma, phi] and ``pink`` sigma noise, then
    rounded to the ADC step ``quant``."""
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out = out + rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        out = out + ar1(rng, out.size, *spec["ar1"])
    if spec.get("pink"):
        out = out + pink(rng, out.size, spec["pink"])
    if spec.get("quant"):
        out = np.round(out / spec["quant"]) * spec["quant"]
    return out
