"""Motor H of the diagnosis benchmark: a hand-written scipy model of a 36 V, 250 W class
permanent-magnet brushed DC servo motor driving the ball screw of a horizontal linear axis
(a 60 kg carriage, 10 mm lead) through a rigid 2.5:1 spur gear pair. The screw's nut and
the carriage's guides are declared as a Coulomb friction and a viscous drag on the screw.

No circuitsim import: an independent simulator (the sixth of the benchmark), written from the
physics for netlists/motor_h_motor.yaml, motor_h.yaml and motor_h_slow.yaml. Only the noise
recipes and the record format follow the earlier sets.

Base state z = [i, w, th]: armature current [A], rotor speed [rad/s], rotor angle [rad];
then whatever states the effects add. The gear is rigid: the screw turns at w_s = w / N and
its angle is th_s = th / N (both start at 0). Written at the rotor (lead-screw axis moving
out is positive rotation):

    dpsi/di di/dt = v_arm - R(t) i - e,           e = k w (+ an EMF harmonic)
    J dw/dt       = k i - bm w + T_rotor + T_screw / N,      J = Jm + Js / N^2
    T_screw       = -bs w_s - Fs tanh(w_s / 0.01) + (screw-side extras)

The declared screw friction is circuitsim's ``friction`` with tau_brk = tau_c and w_brk
0.1 rad/s: Fs tanh(w_s / 0.01), no breakaway bump.

Effects (``fx`` keys, SI, all off by default) -- the catalog's, each in its patch's law:

    Rs        [ohm]   an internal resistance of the supply
    Rser      [ohm]   a resistance in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   R(t) = R (1 + alpha t)
    warmup    (rise, tau [s]): R(t) = R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf_h     (order, a, b): e gains w (a sin(order th) + b cos(order th))
    cog       {node: [(order, a, b), ...]}: the node (rotor or screw) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {node: c}: Coulomb friction c tanh(w_node / 0.01) against the node's motion
    stribeck  {node: (s, ws)}: a breakaway peak s exp(-(w/ws)^2) tanh(w / 0.01) against
              the motion (the catalog offers it where a friction is declared: the screw)
    visc      {node: b}: extra viscous friction on the node
    offset    {node: F}: a constant torque F the node receives
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g y + o, y the
              probe seen through the first-order Pade stage of a delay tau (2 s - x with
              tau/2 ds/dt = x - s, s(0) = 0); gain is the factor
    (an inertia off: pass motor parameters ``p`` with another Js or Jm)

and outside the catalog:

    clutch    (fn [N m], mu, mu_s, Jw [kg m^2]): a torque-limiting friction clutch between
              the gear wheel (inertia Jw, part of the declared Js) and the screw, exact
              stick-slip: stuck, the two turn together and the clutch passes whatever torque
              that takes while it stays below mu_s fn; slipping, it passes mu fn sign(w_rel);
              it breaks away at mu_s fn and sticks again where w_rel crosses zero (events)
    xtalk     kappa [rad/s per A]: the speed signal (a DC tachogenerator on an analogue input)
              shares its ground return with the armature current: speed reads w + kappa i
    nut       (order, T [N m], phase): a spalled ball in the ball nut: a torque on the screw
              T sin(order th_s + phase) at a NON-integer order of the screw's angle (the
              defect's pass rate per screw turn)
    spring    (T0 [N m], Ks [N m/rad]): a preloaded return spring pulling the carriage home:
              the screw receives -(T0 + Ks th_s)
    shorted   (ks [V s/rad], Rs [ohm], Ls [H], phase [rad]): a shorted group of turns in the
              armature (2 poles): the magnets link ks sin(th + phase) with it, so it carries
              Ls dis/dt = ks w cos(th + phase) - Rs is and brakes the rotor with
              -ks cos(th + phase) is: a drag that grows with the speed, rippling twice per
              turn (its coupling with the armature's own field is left out)
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
PROFILE_CSV = HERE / "netlists" / "inputs" / "motor_h_profile.csv"

#: declared values of motor H [SI] (motor_h_motor.yaml)
MOTOR_H: dict[str, float] = {
    "R": 0.45, "L": 0.35e-3, "k": 0.065, "Jm": 4.5e-5, "bm": 1.5e-5, "N": 2.5,
    "Js": 2.6e-4, "bs": 2e-4, "Fs": 0.08,
}
LEAD = 0.010  # [m] the ball screw's lead (carriage travel per screw turn)
#: [rad/s] circuitsim's friction (w_brk 0.1) switches sign as tanh(w / 0.01)
W_SIGN = 0.01
#: [A] the catalog's brush drop switches sign as tanh(i / 1 mA)
I_SIGN = 1e-3
#: the fast regime's command [s, V] (motor_h.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.003, 0.0), (0.018, 30.0), (0.12, 30.0), (0.122, 36.0),
               (0.2, 36.0), (0.202, 10.0), (0.26, 10.0), (0.29, -24.0), (0.38, -24.0),
               (0.382, -6.0), (0.43, -6.0), (0.432, 0.0), (0.46, 0.0), (0.465, 5.0),
               (0.5, 5.0))
REGIMES: dict[str, tuple[float, float]] = {"fast": (40e3, 0.5), "slow": (1e3, 5.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
RTOL, ATOL = 1e-10, 1e-12


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t, u]: the command, linear between points, held after the last."""
    if regime == "fast":
        return np.asarray(FAST_POINTS, dtype=float)
    return np.loadtxt(PROFILE_CSV, delimiter=",", skiprows=1)


def grid(regime: str) -> np.ndarray:
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


class _Model:
    """Motor H's right-hand side for one set of effects (and, with a clutch, one mode)."""

    def __init__(self, bp: np.ndarray, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.tb, self.ub = bp[:, 0].copy(), bp[:, 1].copy()
        self.fx, self.p = fx, p
        self.n = 3
        self.slots: dict[str, int] = {}
        if "clutch" in fx:
            self.slots["clutch"] = self._slot(2)  # screw speed and angle
        if "shorted" in fx:
            self.slots["shorted"] = self._slot(1)
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.slots["delay:" + probe] = self._slot(1)
        self.mode = 0  # the clutch: 0 stuck, +1 / -1 slipping forward / backward
        self.cog = {n: list(v) for n, v in fx.get("cog", {}).items()}

    def _slot(self, size: int) -> int:
        first = self.n
        self.n += size
        return first

    def x0(self) -> np.ndarray:
        return np.zeros(self.n)

    def command(self, t: float) -> float:
        return float(np.interp(t, self.tb, self.ub))

    # ---- the parts
    def extras(self, node: str, w: float, angle: float) -> float:
        """The torque the catalog's mechanical effects give a node (rotor or screw)."""
        fx = self.fx
        tq = fx.get("offset", {}).get(node, 0.0) - fx.get("visc", {}).get(node, 0.0) * w
        c = fx.get("coul", {}).get(node)
        if c:
            tq -= c * math.tanh(w / W_SIGN)
        st = fx.get("stribeck", {}).get(node)
        if st:
            s, ws = st
            tq -= s * math.exp(-(w / ws) ** 2) * math.tanh(w / W_SIGN)
        for order, a, b in self.cog.get(node, ()):
            tq += a * math.sin(order * angle) + b * math.cos(order * angle)
        return tq

    def screw_torque(self, ws: float, ths: float) -> float:
        """Everything the screw (with the carriage) receives besides the drive."""
        p, fx = self.p, self.fx
        tq = -p["bs"] * ws - p["Fs"] * math.tanh(ws / W_SIGN) + self.extras("screw", ws, ths)
        if "nut" in fx:
            order, amp, ph = fx["nut"]
            tq += amp * math.sin(order * ths + ph)
        if "spring" in fx:
            t0, ks = fx["spring"]
            tq -= t0 + ks * ths
        return tq

    def resistance(self, t: float) -> float:
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        return r + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)

    def inductance(self, i: float) -> float:
        if "lsat" not in self.fx:
            return self.p["L"]
        ipar, ratio = self.fx["lsat"]
        return self.p["L"] * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))

    def clutch_stuck_torque(self, i: float, w: float, th: float, ws: float, ths: float) -> float:
        """The torque the stuck clutch passes to the screw: what keeps w_s = w / N."""
        p = self.p
        n_g = p["N"]
        jw = self.fx["clutch"][3]
        j1 = p["Jm"] + jw / n_g**2
        j2 = p["Js"] - jw
        drive = p["k"] * i - p["bm"] * w + self.extras("rotor", w, th)
        ts = self.screw_torque(ws, ths)
        return (drive / (j1 * n_g) - ts / j2) / (1.0 / j2 + 1.0 / (j1 * n_g**2))

    # ---- the right-hand side
    def __call__(self, t: float, z: np.ndarray) -> np.ndarray:
        p, fx = self.p, self.fx
        i, w, th = z[0], z[1], z[2]
        n_g = p["N"]
        dz = np.zeros_like(z)

        # the armature loop
        v = self.command(t)
        v -= fx.get("Vb", 0.0) * math.tanh(i / I_SIGN)
        emf = p["k"] * w
        if "emf_h" in fx:
            order, a, b = fx["emf_h"]
            emf += w * (a * math.sin(order * th) + b * math.cos(order * th))
        dz[0] = (v - self.resistance(t) * i - emf) / self.inductance(i)

        # the mechanics
        drive = p["k"] * i - p["bm"] * w + self.extras("rotor", w, th)
        if "shorted" in fx:
            ks, rs, ls, ph = fx["shorted"]
            k_t = self.slots["shorted"]
            c = ks * math.cos(th + ph)
            dz[k_t] = (c * w - rs * z[k_t]) / ls
            drive -= c * z[k_t]
        if "clutch" in fx:
            k_c = self.slots["clutch"]
            ws, ths = z[k_c], z[k_c + 1]
            fn, mu, _, jw = fx["clutch"]
            j1 = p["Jm"] + jw / n_g**2
            j2 = p["Js"] - jw
            if self.mode == 0:
                tc = self.clutch_stuck_torque(i, w, th, ws, ths)
            else:
                tc = self.mode * mu * fn
            dz[1] = (drive - tc / n_g) / j1
            dz[k_c] = (tc + self.screw_torque(ws, ths)) / j2 if self.mode else dz[1] / n_g
            dz[k_c + 1] = ws
        else:
            jeq = p["Jm"] + p["Js"] / n_g**2
            dz[1] = (drive + self.screw_torque(w / n_g, th / n_g) / n_g) / jeq
        dz[2] = w

        # sensor states
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                k_s = self.slots["delay:" + probe]
                dz[k_s] = (self.raw_probe(probe, z) - z[k_s]) / (0.5 * s["delay"])
        return dz

    def raw_probe(self, probe: str, z: np.ndarray) -> Any:
        """The probe's physical quantity (before any sensor law) from a state (or states)."""
        if probe == "current":
            return z[0]
        if probe == "speed":
            return z[1]
        if "clutch" in self.fx:
            return z[self.slots["clutch"]]
        return z[1] / self.p["N"]

    # ---- the clutch's switchings
    def events(self) -> list:
        if "clutch" not in self.fx:
            return []
        fn, _, mu_s, _ = self.fx["clutch"]
        k_c = self.slots["clutch"]

        def args(z):
            return z[0], z[1], z[2], z[k_c], z[k_c + 1]

        def brk_fwd(t, z):
            return mu_s * fn - self.clutch_stuck_torque(*args(z)) if self.mode == 0 else 1.0

        def brk_bwd(t, z):
            return mu_s * fn + self.clutch_stuck_torque(*args(z)) if self.mode == 0 else 1.0

        def stick(t, z):
            return self.mode * (z[1] / self.p["N"] - z[k_c]) if self.mode else 1.0

        for ev in (brk_fwd, brk_bwd, stick):
            ev.terminal, ev.direction = True, -1
        return [brk_fwd, brk_bwd, stick]

    def switch(self, k_event: int, z: np.ndarray) -> np.ndarray:
        """The clutch's new mode after event ``k_event``; a clutch that sticks has its screw
        speed set to the rotor's / N exactly."""
        z = z.copy()
        k_c = self.slots["clutch"]
        fn, _, mu_s, _ = self.fx["clutch"]
        if k_event == 0:
            self.mode = 1
        elif k_event == 1:
            self.mode = -1
        else:
            self.mode = 0
            z[k_c] = z[1] / self.p["N"]
            tc = self.clutch_stuck_torque(z[0], z[1], z[2], z[k_c], z[k_c + 1])
            if abs(tc) > mu_s * fn:
                self.mode = 1 if tc > 0 else -1
        return z


def _integrate(model: _Model, a: float, b: float, z0: np.ndarray, h_max: float):
    """One piece [a, b]: a list of (t0, t1, dense solution) and the state at b, the clutch's
    switchings located by the event search and restarted from."""
    pieces = []
    t0 = a
    events = model.events()
    n_switch = 0
    while True:
        sol = None
        for method in ("LSODA", "Radau"):
            sol = solve_ivp(model, (t0, b), z0, method=method, rtol=RTOL, atol=ATOL,
                            max_step=h_max, dense_output=True, events=events or None)
            if sol.status >= 0 and np.isfinite(sol.y).all():
                break
        if sol is None or sol.status < 0 or not np.isfinite(sol.y).all():
            raise RuntimeError(f"motor H, {t0:g}-{b:g} s: {sol.message if sol else '?'}")
        t1 = float(sol.t[-1])
        pieces.append((t0, t1, sol.sol))
        z0 = sol.y[:, -1].copy()
        if sol.status == 0 or t1 >= b:
            return pieces, z0
        k_event = next(j for j, te in enumerate(sol.t_events) if te.size)
        z0 = model.switch(k_event, z0)
        n_switch += 1
        if n_switch > 10000:
            raise RuntimeError("motor H: the clutch chatters")
        t0 = t1


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False) -> dict[str, np.ndarray]:
    """Noise-free probes of motor H on ``t`` (default: the record grid), from rest, plus the
    command ``u``: current, speed (and load_speed, the screw's speed, in the slow regime).
    ``states``: also return the state matrix as ``"_z"``."""
    fx = dict(fx or {})
    p = dict(MOTOR_H if p is None else p)
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = _Model(bp, fx, p)
    # the command has kinks at its breakpoints: integrate between them, restarting there
    cuts = [float(t[0])] + [float(b) for b in bp[:, 0] if t[0] < b < t[-1]] + [float(t[-1])]
    z0 = model.x0()
    z = np.full((model.n, t.size), np.nan)
    h_max = 1.0 / REGIMES[regime][0]
    for k in range(len(cuts) - 1):
        a, b = cuts[k], cuts[k + 1]
        pieces, z0 = _integrate(model, a, b, z0, h_max)
        for j, (t0, t1, dense) in enumerate(pieces):
            last = j == len(pieces) - 1 and k == len(cuts) - 2
            mask = (t >= t0) & ((t <= t1) if last else (t < t1))
            if mask.any():
                z[:, mask] = dense(t[mask])
    if not np.isfinite(z).all():
        raise RuntimeError(f"motor H, {regime}: samples left unset")

    out: dict[str, np.ndarray] = {}
    for probe in PROBES[regime]:
        y = np.asarray(model.raw_probe(probe, z), dtype=float)
        s = fx.get("sensor", {}).get(probe, {})
        if s.get("delay"):
            y = 2.0 * z[model.slots["delay:" + probe]] - y
        out[probe] = y
    if "xtalk" in fx:
        out["speed"] = out["speed"] + fx["xtalk"] * z[0]
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out["_z"] = z
    return out


# ---------------------------------------------------------------------- noise

def ar1(rng: np.random.Generator, n: int, sigma: float, phi: float) -> np.ndarray:
    """A stationary AR(1) sequence of marginal standard deviation ``sigma``."""
    e = rng.normal(0.0, sigma * math.sqrt(1.0 - phi * phi), n)
    out = np.empty(n)
    out[0] = rng.normal(0.0, sigma)
    for j in range(1, n):
        out[j] = phi * out[j - 1] + e[j]
    return out


def pink(rng: np.random.Generator, n: int, sigma: float) -> np.ndarray:
    """1/f noise: white noise whose amplitude spectrum is shaped by f^-1/2 (no mean), std
    sigma."""
    spec = np.fft.rfft(rng.normal(size=n))
    f = np.fft.rfftfreq(n)
    spec[0] = 0.0
    spec[1:] /= np.sqrt(f[1:])
    x = np.fft.irfft(spec, n)
    return sigma * x / np.std(x)


def add_noise(rng: np.random.Generator, y: np.ndarray, spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` plus ``white`` sigma, ``ar1`` [sigma, phi] and ``pink`` sigma noise, then rounded
    to the ADC step ``quant`` (applied last)."""
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out += rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        out += ar1(rng, out.size, *spec["ar1"])
    if spec.get("pink"):
        out += pink(rng, out.size, spec["pink"])
    if spec.get("quant"):
        out = np.round(out / spec["quant"]) * spec["quant"]
    return out
