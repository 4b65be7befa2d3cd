"""Motor BG of the diagnosis benchmark: a hand-written scipy model of a 12 V permanent-magnet
brushed DC gearmotor (a 2-pole, 5-slot motor with a 10-bar commutator) driving the roller
head of a LABORATORY PERISTALTIC PUMP on the maker's test stand. The motor drives a rigid
50:1 spur gearhead (`gear` G, declared rigid and lossless) whose output shaft, with its final
wheel, the stand's adaptor flange and the Oldham coupling's drive-side hub, is the body
``hub`` (turning in the gearhead's output bearings: a dry friction Th). The Oldham coupling's
polymer centre disc is the train's torsional compliance, `spring_damper` K, between the hub
and the body ``head`` (the pump's three-roller head, 1:1). The silicone tubing squeezed by
the rollers drags the head viscously (Bl), the rollers' and the head's bearings give it a
dry friction (Tl). Forward is head.w > 0 (pumping).

No circuitsim import, and no other set's simulator: written from the physics for
netlists/motor_bg_fast.yaml and motor_bg_slow.yaml. Evaluated at the record's own sample
times (``t_eval``), never on a grid that is then interpolated. Everything rests at t = 0.

With the rotor's angle th and speed w, the hub's are th / N and w / N (rigid gearhead); the
head's thl and wl. The Oldham disc's torque on the head is

    Tk = Ks (th / N - thl) + Ds (w / N - wl),

a torque T on the hub is T / N on the rotor. Dry frictions follow circuitsim's `friction`
with w_brk 0.1 (no breakaway): T tanh(speed / 0.01). The equations (Jr = Jm + Jh / N^2):

    L di/dt   = v(t) - R i - k w - (loop extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor
                + (X_hub - Th tanh(w / N / 0.01) - Tk) / N
    Jl dwl/dt = Tk - Tl tanh(wl / 0.01) - Bl wl + X_head

v(t) is the stand's supply output, linear between the command's corners.

Effects (``fx``; SI; catalog laws as the catalog's patches state them):

    Rser, Rs  [ohm]  a resistance in series with the armature / inside the source
    Vb        [V]    brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]  R (1 + alpha t);  warmup (rise, tau): R (1 + rise (1 - exp(-t/tau)))
    lsat      (Ipar, ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i/Ipar)^2))
    emf       [(order, a, b)]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b)]}: the body receives a sin(order ang) + b cos(order ang)
    coul      {body: c}: c tanh(speed / 0.01) against it
    visc      {body: b}: b speed against it
    offset    {body: T}: a constant torque it receives
    stribeck  {body: (s, ws)}: s exp(-(speed/ws)^2) tanh(speed/0.01) against it
    gap       [rad]  a play of total width gap in K (no torque inside, Ks (x -+ gap/2)
              + Ds v in contact, the damper never pulling)
    sensor    {probe: {"gain", "offset", "delay"}}: g * (probe through a first-order Pade
              delay: yd = 2 q - y, dq/dt = 2 (y - q) / tau) + offset
    p         {name: value}: parameters changed

Outside the catalog:

    seized    (Tp [N m], half_width [rad], theta0 [rad], delta): one of the head's three
              rollers has a seized bearing and skids on the tube while it is in the occlusion
              bed: the head takes Tp g(thl) tanh(wl / 0.01) more against it, g the smooth gate
              of ``tacho`` over +-half_width about theta0 of the head's angle
    tacho     (m, half_width [rad], theta0 [rad], delta): the rear-shaft tachogenerator has a
              burnt commutator bar: its reading is w (1 - m g(th)), g a smooth gate once a
              rotor turn, g = 1 / (1 + exp(-(cos(th - theta0) - cos(half_width)) / delta))
    slip      (Ts [N m], Tc [N m], vs [rad/s], Jo [kg m^2]): the Oldham coupling's drive-side
              hub (inertia Jo, a part of the declared Jh) is held on the gearhead's shaft by a
              set screw that slips: its slip angle phi (shaft minus hub piece, from rest) and
              slip speed s obey Jo (dw/dt / N - ds/dt) = F(s) - Tk, the shaft (the rest of the
              hub, Jh - Jo) taking -F(s) instead of -Tk; the screw's friction
              F(s) = (Tc + (Ts - Tc) exp(-(s/vs)^2)) tanh(s / 0.01): it holds up to Ts and
              slides at Tc; the twist x = th / N - phi - thl, Tk = Ks x + Ds (w/N - s - wl)
    climit    (I0 [A], I1 [A], tau [s], Rf [V/A], eps [A]): the bench supply's current limit
              sags as it warms, Ilim(t) = I1 + (I0 - I1) exp(-t / tau); beyond it the output
              folds back: v = u - Rf dz(i), dz a smooth dead zone of half width Ilim
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: the declared values of motor BG [SI] (motor_bg_fast.yaml, motor_bg_slow.yaml)
MOTOR_BG: dict[str, float] = {
    "R": 1.8, "L": 1.2e-3, "k": 0.022, "Jm": 6e-6, "bm": 2e-7, "Tm": 2e-3,
    "N": 50.0, "Jh": 1e-3, "Th": 0.08, "Ks": 12.0, "Ds": 0.01, "Jl": 2.5e-3,
    "Tl": 0.12, "Bl": 0.025,
}
#: the friction's and the brush drop's smoothing [rad/s, A]
W_SMOOTH, I_SMOOTH = 0.01, 1e-3
#: the fast regime's supply output [s, V] (motor_bg_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.008, 0.0), (0.068, 12.0), (0.19, 12.0), (0.21, 5.0),
               (0.29, 5.0), (0.335, -9.0), (0.425, -9.0), (0.445, 0.0), (0.5, 0.0))
#: the slow regime's logged command [s, V] (motor_bg_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.5, 0.0), (1.5, 6.0), (5.0, 6.0), (6.0, 12.0), (10.0, 12.0),
               (10.6, 0.0), (11.5, 0.0), (12.3, -8.0), (15.5, -8.0), (16.1, 0.0),
               (18.0, 0.0))
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.5), "slow": (100.0, 18.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "head")
TOL = {"rtol": 1e-10, "atol": 1e-12}
MAX_STEP = {"fast": 5e-5, "slow": 2e-3}


def corners(regime: str) -> np.ndarray:
    """The command's corners, rows [t s, u V]."""
    return np.array(FAST_POINTS if regime == "fast" else SLOW_POINTS)


def grid(regime: str) -> np.ndarray:
    """The regime's even sample times k / fs [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def soft_dead_zone(x: float, half: float, eps: float) -> float:
    """eps (ln(1 + e^((x - half)/eps)) - ln(1 + e^((-x - half)/eps))): zero inside +-half,
    x -+ half beyond, smooth over eps."""
    return eps * (np.logaddexp(0.0, (x - half) / eps) - np.logaddexp(0.0, (-x - half) / eps))


def tacho_gate(th: Any, half: float, theta0: float, delta: float) -> Any:
    """The burnt bar's gate: about 1 within +-half of theta0 (mod 2 pi), else about 0."""
    z = (np.cos(th - theta0) - math.cos(half)) / delta
    return 0.5 * (1.0 + np.tanh(0.5 * z))


class PumpDrive:
    """The right-hand side of motor BG for the effects ``fx`` and the values ``p``."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.fx, self.p = fx, p
        self.idx: dict[str, int] = {"i": 0, "w": 1, "th": 2, "wl": 3, "thl": 4}
        if "slip" in fx:
            self.idx["phi"] = len(self.idx)
            self.idx["s"] = len(self.idx)
        self.delays = [(pr, float(d["delay"])) for pr, d in fx.get("sensor", {}).items()
                       if d.get("delay")]
        for pr, _ in self.delays:
            self.idx["q_" + pr] = len(self.idx)
        self.n = len(self.idx)
        jh = p["Jh"] - (fx["slip"][3] if "slip" in fx else 0.0)
        self.jr = p["Jm"] + jh / p["N"] ** 2
        self.body = {b: {kind: fx[kind][b] for kind in
                         ("coul", "visc", "offset", "stribeck", "cog")
                         if kind in fx and b in fx[kind]} for b in BODIES}
        self.r0 = p["R"] + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)
        self.piece = (0.0, 0.0, 0.0)

    # the supply
    def command(self, t: float) -> float:
        """The command on the current piece [V]."""
        t0, u0, slope = self.piece
        return u0 + slope * (t - t0)

    def supply(self, t: float, i: float) -> float:
        """The supply's output [V]."""
        u = self.command(t)
        if "climit" in self.fx:
            i0, i1, tau, rf, eps = self.fx["climit"]
            ilim = i1 + (i0 - i1) * math.exp(-t / tau)
            u -= rf * soft_dead_zone(i, ilim, eps)
        return u

    # the armature loop
    def loop_drop(self, t: float, i: float, w: float, th: float) -> float:
        """Everything the loop takes besides L di/dt and k w [V]."""
        fx, r = self.fx, self.r0
        if "alpha" in fx:
            r += self.p["R"] * fx["alpha"] * t
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += self.p["R"] * rise * -math.expm1(-t / tau)
        v = r * i
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SMOOTH)
        for order, a, b in fx.get("emf", ()):
            v += w * (a * math.sin(order * th) + b * math.cos(order * th))
        return v

    def inductance(self, i: float) -> float:
        """The incremental inductance [H]."""
        if "lsat" in self.fx:
            ipar, ratio = self.fx["lsat"]
            return self.p["L"] * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))
        return self.p["L"]

    # the mechanics
    def torque_on(self, body: str, speed: float, angle: float) -> float:
        """The catalog torques the body receives [N m]."""
        e = self.body[body]
        if not e:
            return 0.0
        sg = math.tanh(speed / W_SMOOTH)
        tq = e.get("offset", 0.0) - e.get("visc", 0.0) * speed - e.get("coul", 0.0) * sg
        if "stribeck" in e:
            s, ws = e["stribeck"]
            tq -= s * math.exp(-((speed / ws) ** 2)) * sg
        for order, a, b in e.get("cog", ()):
            tq += a * math.sin(order * angle) + b * math.cos(order * angle)
        return tq

    def disc(self, twist: float, rate: float) -> float:
        """The Oldham disc's torque on the head [N m]."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        gap = self.fx.get("gap")
        if not gap:
            return ks * twist + ds * rate
        h = 0.5 * gap
        if twist > h:
            return max(ks * (twist - h) + ds * rate, 0.0)
        if twist < -h:
            return min(ks * (twist + h) + ds * rate, 0.0)
        return 0.0

    def __call__(self, t: float, y: np.ndarray) -> np.ndarray:
        p, fx, ix = self.p, self.fx, self.idx
        i, w, th, wl, thl = y[0], y[1], y[2], y[3], y[4]
        n = p["N"]
        dy = np.zeros(self.n)
        dy[0] = (self.supply(t, i) - self.loop_drop(t, i, w, th) - p["k"] * w) \
            / self.inductance(i)
        if "slip" in fx:
            ts, tc, vs, jo = fx["slip"]
            phi, slip = y[ix["phi"]], y[ix["s"]]
            grip = (tc + (ts - tc) * math.exp(-((slip / vs) ** 2))) * math.tanh(slip / W_SMOOTH)
        else:
            phi = slip = 0.0
        tk = self.disc(th / n - phi - thl, w / n - slip - wl)
        t_rotor = p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / W_SMOOTH) \
            + self.torque_on("rotor", w, th)
        t_hub = self.torque_on("hub", w / n, th / n) - p["Th"] * math.tanh(w / n / W_SMOOTH)
        if "slip" in fx:
            dy[1] = (t_rotor + (t_hub - grip) / n) / self.jr
            dy[ix["phi"]] = slip
            dy[ix["s"]] = dy[1] / n - (grip - tk) / jo
        else:
            dy[1] = (t_rotor + (t_hub - tk) / n) / self.jr
        dy[2] = w
        dry = p["Tl"]
        if "seized" in fx:
            tp, half, theta0, delta = fx["seized"]
            dry += tp * float(tacho_gate(thl, half, theta0, delta))
        t_head = tk - dry * math.tanh(wl / W_SMOOTH) - p["Bl"] * wl \
            + self.torque_on("head", wl, thl)
        dy[3] = t_head / p["Jl"]
        dy[4] = wl
        if self.delays:
            seen = self.readings(y)
            for pr, tau in self.delays:
                j = ix["q_" + pr]
                dy[j] = 2.0 * (seen[pr] - y[j]) / tau
        return dy

    def readings(self, y: np.ndarray) -> dict[str, Any]:
        """What each probe's sensor sees (before the catalog's sensor effects)."""
        speed = y[1]
        if "tacho" in self.fx:
            m, half, theta0, delta = self.fx["tacho"]
            speed = y[1] * (1.0 - m * tacho_gate(y[2], half, theta0, delta))
        return {"current": y[0], "speed": speed, "load_speed": y[3]}


def _piece(model: PumpDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
           max_step: float) -> np.ndarray:
    """The states at ``t_out`` (in [a, b]) from ``y0`` at ``a``: LSODA, else BDF, else
    Radau."""
    why = ""
    for method in ("LSODA", "BDF", "Radau"):
        sol = solve_ivp(model, (a, b), y0, method=method, t_eval=t_out, max_step=max_step,
                        **TOL)
        if sol.success and sol.y.shape[1] == t_out.size and np.all(np.isfinite(sol.y)):
            return sol.y
        why = sol.message
    raise RuntimeError(f"motor BG, {a:g}-{b:g} s: {why}")


def run_states(model: PumpDrive, t: np.ndarray, regime: str) -> np.ndarray:
    """The states (n, len(t)) at the increasing times ``t``, from rest, the solver restarted
    at each of the command's corners."""
    bp = corners(regime)
    end = float(t[-1])
    edges = np.unique(np.concatenate([[0.0, end], bp[(bp[:, 0] > 0.0) & (bp[:, 0] < end), 0]]))
    y = np.zeros((model.n, t.size))
    y0 = np.zeros(model.n)
    for a, b in itertools.pairwise(edges):
        k = min(int(np.searchsorted(bp[:, 0], a, side="right")) - 1, len(bp) - 2)
        slope = (bp[k + 1, 1] - bp[k, 1]) / (bp[k + 1, 0] - bp[k, 0])
        model.piece = (float(a), float(bp[k, 1] + slope * (a - bp[k, 0])), float(slope))
        last = b == end
        sel = np.flatnonzero((t >= a) & ((t <= b) if last else (t < b)))
        t_out = t[sel] if last else np.concatenate([t[sel], [b]])
        ys = _piece(model, float(a), float(b), y0, t_out, MAX_STEP[regime])
        y[:, sel] = ys[:, :sel.size]
        y0 = ys[:, -1].copy()
    return y


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor BG at the times ``t`` [s] (default: the regime's grid),
    from rest, with the values ``p`` over the declared ones and ``fx["p"]`` over those:
    current [A] (the stand's shunt in the armature lead), speed [rad/s] (the motor's
    rear-shaft tachogenerator), in the slow regime load_speed [rad/s] (the encoder on the
    head's shaft), and the command ``u`` [V]; ``states`` adds the bodies' angles and speeds,
    the disc's twist and the outside effects' states."""
    fx = dict(fx or {})
    par = {**MOTOR_BG, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    model = PumpDrive(fx, par)
    y = run_states(model, t, regime)
    seen = model.readings(y)
    for pr, _ in model.delays:
        seen[pr] = 2.0 * y[model.idx["q_" + pr]] - seen[pr]
    out = {pr: np.asarray(seen[pr], dtype=float).copy() for pr in PROBES[regime]}
    for pr, d in fx.get("sensor", {}).items():
        if pr in out:
            out[pr] = d.get("gain", 1.0) * out[pr] + d.get("offset", 0.0)
    bp = corners(regime)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        n = par["N"]
        phi = y[model.idx["phi"]] if "phi" in model.idx else 0.0
        out.update(armature_current=y[0], rotor_speed=y[1], rotor_angle=y[2],
                   hub_speed=y[1] / n, hub_angle=y[2] / n, head_speed=y[3],
                   head_angle=y[4], twist=y[2] / n - phi - y[4])
        if "phi" in model.idx:
            out["slip_angle"] = y[model.idx["phi"]]
    return out


# ---------------------------------------------------------------------- noise

def gauss_markov(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float
                 ) -> np.ndarray:
    """Stationary first-order Gauss-Markov noise (deviation ``sigma``, correlation time
    ``tau`` [s]) sampled exactly at the (possibly uneven) times ``t``."""
    rho = np.exp(-np.diff(t) / tau)
    z = rng.standard_normal(t.size)
    out = np.empty(t.size)
    out[0] = sigma * z[0]
    for j in range(1, t.size):
        out[j] = rho[j - 1] * out[j - 1] + sigma * math.sqrt(1.0 - rho[j - 1] ** 2) * z[j]
    return out


def flicker(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise of deviation ``sigma``: white noise on an even grid spanning ``t``, its
    spectrum's amplitude shaped by 1/sqrt(f) (no mean), read linearly at ``t``."""
    m = t.size
    even = np.linspace(t[0], t[-1], m)
    f = np.fft.rfftfreq(m, even[1] - even[0])
    spec = np.fft.rfft(rng.standard_normal(m))
    spec[0] = 0.0
    spec[1:] = spec[1:] * np.sqrt(f[1] / f[1:])
    x = np.interp(t, even, np.fft.irfft(spec, m))
    x -= x.mean()
    return sigma * x / x.std()


def add_noise(rng: np.random.Generator, t: np.ndarray, y: np.ndarray,
              spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` with white (``white`` sigma), Gauss-Markov (``ar1`` [sigma, phi], phi the
    correlation over the mean interval) and 1/f (``pink`` sigma) noise, then quantised to the
    ADC step ``quant``."""
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out += rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        sigma, phi = spec["ar1"]
        out += gauss_markov(rng, t, sigma, -float(np.mean(np.diff(t))) / math.log(phi))
    if spec.get("pink"):
        out += flicker(rng, t, spec["pink"])
    q = spec.get("quant")
    return np.round(out / q) * q if q else out
