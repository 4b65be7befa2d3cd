"""Motor K of the diagnosis benchmark: a hand-written scipy model of a 24 V, 100 W class
permanent-magnet brushed DC motor driving the sealless gear pump of a coolant loop through a
4:1 planetary gearhead and a permanent-magnet drive coupling (an outer magnet ring on the
gearhead's output hub turns the pump's inner magnet rotor through a sealed can).

No circuitsim import: an independent simulator (the eighth of the benchmark), written from
the physics for netlists/motor_k_motor.yaml, motor_k.yaml and motor_k_slow.yaml.

Base state (5 numbers) z = [i, w, th, wp, thp]:

    i    armature current [A]
    w    rotor speed [rad/s],  th  rotor angle [rad]; the hub (outer magnet ring, node
         ``hub``) turns rigidly with it at w / N, angle th / N
    wp   pump speed [rad/s],   thp pump angle [rad] (the inner magnet rotor, node ``pump``)

Equations (positive rotation pumps forward):

    L(i) di/dt = v - R(t) i - e,                     e = k w (+ an EMF harmonic)
    Jr dw/dt   = k i - bm w - Tc tanh(w / 0.01) - (T_M + D) / N + X_rotor + X_hub / N
    Jp dwp/dt  = T_M + D - bp wp - Tp tanh(wp / 0.01) + X_pump

with Jr = Jm + Jh / N^2, the magnetic coupling's torque T_M = Tm sin(np (th / N - thp)) and
the can's eddy drag D = dc (w / N - wp) (both what the pump receives from the hub), and
X_node the torques an effect adds on a node.

Effects (``fx`` keys, SI, all off by default) -- the catalog's laws, as its patches write them:

    Rs        [ohm]   an internal resistance of the supply
    Rser      [ohm]   a resistance in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   R(t) = R (1 + alpha t)
    warmup    (rise, tau [s]): R(t) = R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): L(i) = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf_h     (order, a, b): e gains w (a sin(order th) + b cos(order th)), voltage only
    cog       {node: [(order, a, b), ...]}: the node (rotor, hub or pump) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {node: c}: a Coulomb friction c tanh(speed / 0.01) against the node's motion
    visc      {node: b}: an extra viscous friction on the node
    offset    {node: F}: a constant torque F the node receives
    stribeck  {node: (s, ws)}: a breakaway peak s exp(-(speed / ws)^2) tanh(speed / 0.01)
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g y + o, y
              the probe through the first-order Pade stage of a delay tau (reads 2 s - x,
              tau/2 ds/dt = x - s, s(0) = 0)
    (a declared value off: pass motor parameters ``p`` with another value)

and outside the catalog:

    hose      tau [s]: the loop's hose (or an air pocket in it) is compliant: the pressure,
              and with it the pump's load torque, lags the flow: the declared bp wp becomes
              bp x with tau dx/dt = wp - x (a hydraulic RC: the hose's capacitance charged
              by the pump's flow and discharged through the laminar restriction)
    ecc       (eps, phase): the magnetic coupling's hubs are eccentric: the air gap, and with
              it the coupling's torque, goes round once per hub turn:
              T_M = Tm (1 + eps cos(th / N + phase)) sin(np (th / N - thp))
    odrift    (o1 [A], tau [s]): the current sensor's offset drifts as it warms up:
              it reads i + o1 (1 - exp(-t / tau))
    asym      b2 [N m s/rad]: the reverse flow goes through the relief valve's narrower
              bypass: running backwards the pump sees an extra laminar load; the pump
              receives -b2 min(wp, 0) (smoothed: -b2 (wp - sqrt(wp^2 + 0.01^2)) / 2)
    cavit     wc [rad/s]: the pump's inlet starves (cavitation): the laminar load saturates,
              bp wp becomes bp wc tanh(wp / wc)
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_k_profile.csv"

#: declared values of motor K [SI] (motor_k_motor.yaml)
MOTOR_K: dict[str, float] = {
    "R": 0.9, "L": 0.45e-3, "k": 0.045, "Jm": 2.5e-5, "bm": 3e-6, "Tc": 5e-3, "N": 4.0,
    "Jh": 3e-4, "Tm": 3.0, "np": 4.0, "dc": 4e-3, "Jp": 5e-4, "bp": 5e-3, "Tp": 0.06,
}
#: [rad/s] circuitsim's friction (w_brk 0.1) and the catalog's friction switch as tanh(w/0.01)
W_SIGN = 0.01
#: [A] the catalog's brush drop switches sign as tanh(i / 1 mA)
I_SIGN = 1e-3
#: [rad/s] the smoothing of the asymmetric load's min(wp, 0)
W_ASYM = 0.01
#: the fast regime's command [s, V] (motor_k.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.005, 0.0), (0.025, 24.0), (0.15, 24.0), (0.152, 10.0),
               (0.23, 10.0), (0.234, -16.0), (0.36, -16.0), (0.362, 0.0), (0.42, 0.0),
               (0.44, 14.0), (0.5, 14.0))
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.5), "slow": (500.0, 8.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
NODES = ("rotor", "hub", "pump")
RTOL, ATOL = 1e-10, 1e-12


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t, u]: the command, linear between points, held after the last."""
    if regime == "fast":
        return np.asarray(FAST_POINTS, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


class MotorK:
    """Right-hand side of motor K with one set of effects; the states the effects need are
    appended after the five base ones."""

    def __init__(self, bp: np.ndarray, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.t_cmd, self.u_cmd = bp[:, 0].copy(), bp[:, 1].copy()
        self.fx, self.p = fx, p
        self.n = 5
        self.idx: dict[str, int] = {}
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.idx["delay:" + probe] = self._grow()
        if "hose" in fx:
            self.idx["hose"] = self._grow()
        self.j_rotor = p["Jm"] + p["Jh"] / p["N"] ** 2
        self.extra = {node: (fx.get("offset", {}).get(node, 0.0),
                             fx.get("visc", {}).get(node, 0.0),
                             fx.get("coul", {}).get(node, 0.0),
                             list(fx.get("cog", {}).get(node, ())),
                             fx.get("stribeck", {}).get(node))
                      for node in NODES}

    def _grow(self) -> int:
        self.n += 1
        return self.n - 1

    def x0(self) -> np.ndarray:
        return np.zeros(self.n)

    def u(self, t: float) -> float:
        return float(np.interp(t, self.t_cmd, self.u_cmd))

    def added(self, node: str, w: float, angle: float) -> float:
        """The torque the catalog's effects add on a node."""
        off, visc, coul, harm, strib = self.extra[node]
        tq = off - visc * w
        if coul or strib is not None:
            sgn = math.tanh(w / W_SIGN)
            tq -= coul * sgn
            if strib is not None:
                tq -= strib[0] * math.exp(-(w / strib[1]) ** 2) * sgn
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

    def coupling(self, th: float, w: float, thp: float, wp: float) -> float:
        """What the pump receives from the hub: the magnets' torque and the can's drag."""
        p = self.p
        n = p["N"]
        tm = p["Tm"]
        if "ecc" in self.fx:
            eps, ph = self.fx["ecc"]
            tm *= 1.0 + eps * math.cos(th / n + ph)
        return tm * math.sin(p["np"] * (th / n - thp)) + p["dc"] * (w / n - wp)

    def load(self, z: np.ndarray) -> float:
        """The loop's laminar load on the pump (the declared bp wp, or its outside forms)."""
        bp, wp = self.p["bp"], z[3]
        if "hose" in self.fx:
            return bp * z[self.idx["hose"]]
        if "cavit" in self.fx:
            wc = self.fx["cavit"]
            return bp * wc * math.tanh(wp / wc)
        return bp * wp

    def __call__(self, t: float, z: np.ndarray) -> np.ndarray:
        p, fx = self.p, self.fx
        i, w, th, wp, thp = z[:5]
        n = p["N"]
        dz = np.zeros_like(z)

        # armature loop
        v = self.u(t) - fx.get("Rs", 0.0) * i - fx.get("Vb", 0.0) * math.tanh(i / I_SIGN)
        e = p["k"] * w
        if "emf_h" in fx:
            order, a, b = fx["emf_h"]
            e += w * (a * math.sin(order * th) + b * math.cos(order * th))
        dz[0] = (v - self.resistance(t) * i - e) / self.inductance(i)

        # rotor with the hub, the coupling, the pump
        tcp = self.coupling(th, w, thp, wp)
        t_rotor = (p["k"] * i - p["bm"] * w - p["Tc"] * math.tanh(w / W_SIGN) - tcp / n
                   + self.added("rotor", w, th) + self.added("hub", w / n, th / n) / n)
        dz[1] = t_rotor / self.j_rotor
        dz[2] = w
        t_pump = tcp - self.load(z) - p["Tp"] * math.tanh(wp / W_SIGN) \
            + self.added("pump", wp, thp)
        if "asym" in fx:
            t_pump -= fx["asym"] * 0.5 * (wp - math.sqrt(wp * wp + W_ASYM * W_ASYM))
        dz[3] = t_pump / p["Jp"]
        dz[4] = wp

        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                j = self.idx["delay:" + probe]
                dz[j] = (self.quantity(probe, z) - z[j]) / (0.5 * s["delay"])
        if "hose" in fx:
            j = self.idx["hose"]
            dz[j] = (wp - z[j]) / fx["hose"]
        return dz

    @staticmethod
    def quantity(probe: str, z: np.ndarray) -> Any:
        """The physical quantity a probe measures, from a state (or an array of states)."""
        return {"current": z[0], "speed": z[1], "load_speed": z[3]}[probe]


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor K on ``t`` (default: the record grid), from rest, plus the
    command ``u``: current, speed (and load_speed in the slow regime). ``states``: add the
    rotor and pump angles and the coupling's twist (for reports)."""
    fx = dict(fx or {})
    p = dict(MOTOR_K if p is None else p)
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = MotorK(bp, fx, p)
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
            raise RuntimeError(f"motor K, {regime}, {a:g}-{b:g} s: "
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
    if "odrift" in fx:
        o1, tau = fx["odrift"]
        out["current"] = out["current"] + o1 * (1.0 - np.exp(-t / tau))
    for probe, s in fx.get("sensor", {}).items():
        out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out["rotor_angle"] = y[2].copy()
        out["pump_angle"] = y[4].copy()
        out["pump_speed"] = y[3].copy()
        out["twist"] = y[2] / p["N"] - y[4]
    return out


# ---------------------------------------------------------------------- noise

def ar1(rng: np.random.Generator, n: int, sigma: float, phi: float) -> np.ndarray:
    """A stationary AR(1) sequence of marginal standard deviation ``sigma``."""
    e = rng.normal(0.0, sigma * math.sqrt(1.0 - phi * phi), n)
    out = np.empty(n)
    acc = rng.normal(0.0, sigma)
    out[0] = acc
    for j in range(1, n):
        acc = phi * acc + e[j]
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
