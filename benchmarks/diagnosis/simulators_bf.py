"""Motor BF of the diagnosis benchmark: a hand-written scipy model of a 24 V permanent-magnet
brushed DC gearmotor (a 2-pole, 14-slot ferrite motor) driving the lower drive roll of a bench
THREE-ROLL SECTION BENDER (a ring roller for tubes and profiles) on the maker's test stand.
The motor drives a rigid 40:1 two-stage spur gearhead (`gear` G, declared rigid and lossless)
whose output shaft, with its gear wheel and the cardan shaft's flange yoke, is the body
``hub`` (turning in the gearhead's output bearings and their lip seal). A 0.6 m cardan shaft
with a rubber-bushed flange at its roll end runs under the machine's table to the drive roll:
its twist (and the bushes') is a spring and a damper, `spring_damper` K, between the hub and
the body ``roll`` (the hardened drive roll on its 40 mm shaft, 1:1, with a clamped test
section of 30 mm tube between it and the top roll). The roll's plain bronze bushes and the
tube's bending give it a dry friction, the bushes' heavy grease a viscous drag. Forward is
roll.w > 0 (the tube fed in).

No circuitsim import, and no other set's simulator: written from the physics for
netlists/motor_bf_fast.yaml and motor_bf_slow.yaml. Evaluated at the record's own sample
times (``t_eval``), never on a grid that is then interpolated. Everything rests at t = 0.

The gearhead is rigid (ratio N = 40): the hub stands at th / N and turns at w / N with the
rotor; a torque T on it is T / N on the rotor. The cardan shaft's torque on the roll is

    Tk = Ks (th / N - thl) + Ds (w / N - wl).

Dry frictions are Tx tanh(speed / 0.01) (circuitsim's `friction` with w_brk 0.1 and no
breakaway): the motor's brushes and bearings Tm on the rotor, the gearhead's output bearings
and seal Th on the hub, the roll's bushes and the tube Tl on the roll; viscous bm on the rotor
(`damper` Br), Bl on the roll (`damper` Bl).

State y = [i, w, th, wl, thl] (+ the outside effects' states: the roll encoder's own
angle, the speed module's output; + one Pade stage per delayed probe):

    L di/dt   = v(t) - R i - k w - (the loop's extras)
    Jr dw/dt  = k i - bm w - Tm tanh(w / 0.01) + X_rotor
                + (X_hub - Th tanh((w / N) / 0.01) - Tk) / N,      Jr = Jm + Jh / N^2
    Jl dwl/dt = Tk - Tl tanh(wl / 0.01) - Bl wl + X_roll

v(t) the stand's four-quadrant supply's output u(t) (linear between its breakpoints).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body receives a sin(order angle)
              + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body [N m]
    visc      {body: b}: b speed against the body [N m s/rad]
    offset    {body: T}: a constant torque the body receives [N m]
    stribeck  {body: (s, ws)}: s exp(-(speed / ws)^2) tanh(speed / 0.01) against it [N m]
    gap       [rad]   a play of total width gap in K (no torque while |twist| < gap / 2, else
              Ks (twist -+ gap / 2) + Ds w_rel, the damping never pulling the sides together)
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o, yd
              the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: parameters changed

and outside the catalog:

    pitted    (Rp [ohm], u0 [V]): the motor is fed through the bender's reversing contactor,
              whose reverse contacts are pitted: the loop takes Rp i (1 - tanh(v / u0)) / 2
              more, v(t) the supply's output (the contactor's reverse side closed while the
              command is negative)
    hold      Th [s]: the stand's PC updates the programmable supply's set voltage only every
              Th over its slow link: the supply's output is v(t) = u(Th floor(t / Th)), the
              logged command u held between updates (the record's ``u`` stays the command)
    play      (b [rad], tau [s], eps [rad]): the roll's encoder is driven through a worn tongue
              coupling with a play b: its angle phi follows dphi/dt = dz(thl - phi) / tau,
              dz(x) = eps (ln(1 + e^((x - b/2)/eps)) - ln(1 + e^((-x - b/2)/eps))), phi(0) = 0;
              load_speed reads dphi/dt
    slew      (S [rad/s^2], tau [s]): the motor's speed is read through a frequency-to-speed
              module whose output stage slews at most S: it reads r, dr/dt = S tanh((w - r) /
              (S tau)), r(0) = 0 (a lag tau for small changes)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: the declared values of motor BF [SI] (motor_bf_fast.yaml, motor_bf_slow.yaml)
MOTOR_BF: dict[str, float] = {
    "R": 0.32, "L": 9e-4, "k": 0.062, "Jm": 1.8e-4, "bm": 6e-5, "Tm": 0.025,
    "N": 40.0, "Jh": 0.02, "Th": 0.3, "Ks": 90.0, "Ds": 0.05, "Jl": 0.15,
    "Tl": 1.2, "Bl": 0.08,
}
WSW, ISW = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_bf_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.01, 0.0), (0.10, 24.0), (0.20, 24.0), (0.23, 10.0),
               (0.30, 10.0), (0.36, -18.0), (0.44, -18.0), (0.46, 0.0), (0.50, 0.0))
#: the slow regime's logged command [s, V] (motor_bf_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.4, 0.0), (1.6, 8.0), (4.5, 8.0), (5.5, 24.0), (8.5, 24.0),
               (9.2, 0.0), (10.0, 0.0), (10.8, -16.0), (13.5, -16.0), (14.2, 0.0),
               (16.0, 0.0))
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.5), "slow": (125.0, 16.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "hub", "roll")
RTOL, ATOL = 1e-10, 1e-12
MAX_STEP = {"fast": 1.0 / 20e3, "slow": 2e-3}


def breakpoints(regime: str) -> np.ndarray:
    """The command's corners [[t s, u V], ...]."""
    return np.asarray(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's even sample times k / fs [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


def _softplus(x: float) -> float:
    """ln(1 + e^x) without overflow."""
    return x + math.log1p(math.exp(-x)) if x > 0.0 else math.log1p(math.exp(x))


class RingRoller:
    """dy/dt of motor BF with the effects ``fx`` and the values ``p``; ``seg`` = (t0, u0,
    slope) of the command's current piece."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        self.fx, self.p = fx, p
        n = 5
        self.j_enc = self.j_slew = None
        if "play" in fx:
            self.j_enc, n = n, n + 1
        if "slew" in fx:
            self.j_slew, n = n, n + 1
        self.pade: list[tuple[str, float, int]] = []
        for probe, d in fx.get("sensor", {}).items():
            if d.get("delay"):
                self.pade.append((probe, float(d["delay"]), n))
                n += 1
        self.size = n
        self.tq = {b: {key: fx[key][b] for key in ("visc", "coul", "offset", "stribeck", "cog")
                       if fx.get(key, {}).get(b)} for b in BODIES}
        self.jr = p["Jm"] + p["Jh"] / p["N"] ** 2
        self.seg = (0.0, 0.0, 0.0)
        r = p["R"] + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)
        self.r_fixed = r

    def v(self, t: float) -> float:
        """The supply's output [V]."""
        t0, u0, s = self.seg
        return u0 + s * (t - t0)

    def extra(self, body: str, w: float, ang: float) -> float:
        """The catalog's torques on ``body`` [N m]."""
        e = self.tq[body]
        if not e:
            return 0.0
        th = math.tanh(w / WSW)
        out = e.get("offset", 0.0) - e.get("visc", 0.0) * w - e.get("coul", 0.0) * th
        if "stribeck" in e:
            s, ws = e["stribeck"]
            out -= s * math.exp(-(w / ws) ** 2) * th
        for order, a, b in e.get("cog", ()):
            out += a * math.sin(order * ang) + b * math.cos(order * ang)
        return out

    def resistance_drop(self, t: float, i: float, th: float, w: float) -> float:
        """The loop's voltage besides L di/dt and k w [V]."""
        fx, p = self.fx, self.p
        r = self.r_fixed
        if "alpha" in fx:
            r += p["R"] * fx["alpha"] * t
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        out = r * i
        if "pitted" in fx:
            rp, u0 = fx["pitted"]
            out += rp * i * 0.5 * (1.0 - math.tanh(self.v(t) / u0))
        if "Vb" in fx:
            out += fx["Vb"] * math.tanh(i / ISW)
        for order, a, b in fx.get("emf", ()):
            out += w * (a * math.sin(order * th) + b * math.cos(order * th))
        return out

    def ldiff(self, i: float) -> float:
        """The differential inductance [H]."""
        if "lsat" not in self.fx:
            return self.p["L"]
        ipar, ratio = self.fx["lsat"]
        return self.p["L"] * (ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2))

    def coupling(self, x: float, v: float) -> float:
        """The cardan shaft's torque on the roll [N m] at twist ``x`` and twist rate ``v``."""
        ks, ds = self.p["Ks"], self.p["Ds"]
        gap = self.fx.get("gap")
        if gap:
            h = 0.5 * gap
            if x > h:
                out = max(ks * (x - h) + ds * v, 0.0)
            elif x < -h:
                out = min(ks * (x + h) + ds * v, 0.0)
            else:
                out = 0.0
        else:
            out = ks * x + ds * v
        return out

    def encoder_rate(self, x: float) -> float:
        """The roll encoder's speed [rad/s] with its play at the lag ``x`` = thl - phi."""
        b, tau, eps = self.fx["play"]
        h = 0.5 * b
        return eps * (_softplus((x - h) / eps) - _softplus((-x - h) / eps)) / tau

    def __call__(self, t: float, y: np.ndarray) -> np.ndarray:
        p, fx = self.p, self.fx
        i, w, th, wl, thl = y[0], y[1], y[2], y[3], y[4]
        n = p["N"]
        d = np.empty(self.size)
        d[0] = (self.v(t) - self.resistance_drop(t, i, th, w) - p["k"] * w) / self.ldiff(i)
        wh, thh = w / n, th / n
        tk = self.coupling(thh - thl, wh - wl)
        rotor = p["k"] * i - p["bm"] * w - p["Tm"] * math.tanh(w / WSW) + \
            self.extra("rotor", w, th)
        hub = self.extra("hub", wh, thh) - p["Th"] * math.tanh(wh / WSW)
        d[1] = (rotor + (hub - tk) / n) / self.jr
        d[2] = w
        sl = math.tanh(wl / WSW)
        roll = tk - p["Tl"] * sl - p["Bl"] * wl + self.extra("roll", wl, thl)
        if self.j_enc is not None:
            d[self.j_enc] = self.encoder_rate(thl - y[self.j_enc])
        if self.j_slew is not None:
            sr, tau = fx["slew"]
            d[self.j_slew] = sr * math.tanh((w - y[self.j_slew]) / (sr * tau))
        d[3] = roll / p["Jl"]
        d[4] = wl
        if self.pade:
            look = self.sees(t, y)
            for probe, tau, j in self.pade:
                d[j] = 2.0 * (look[probe] - y[j]) / tau
        return d

    def sees(self, t: Any, y: np.ndarray) -> dict[str, Any]:
        """What each probe's sensor sees before its catalog effects (scalar or arrays)."""
        speed = y[1] if self.j_slew is None else y[self.j_slew]
        if self.j_enc is not None:
            x = y[4] - y[self.j_enc]
            load = np.vectorize(self.encoder_rate)(x) if np.ndim(x) else self.encoder_rate(x)
        else:
            load = y[3]
        return {"current": y[0], "speed": speed, "load_speed": load}


def _solve(model: RingRoller, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
           max_step: float) -> np.ndarray:
    """States at ``t_out`` from ``y0`` at ``a`` to ``b``: LSODA, else Radau."""
    msg = ""
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), y0, method=method, t_eval=t_out, rtol=RTOL, atol=ATOL,
                        max_step=max_step)
        if sol.success and np.isfinite(sol.y).all() and sol.y.shape[1] == t_out.size:
            return sol.y
        msg = sol.message
    raise RuntimeError(f"motor BF {a:g}-{b:g} s: {msg}")


def integrate(model: RingRoller, t: np.ndarray, bp: np.ndarray, max_step: float) -> np.ndarray:
    """States (size, len(t)) at the increasing times ``t``, from rest, restarted at every
    corner of the command."""
    end = float(t[-1])
    cuts = {0.0, end, *(float(c) for c in bp[:, 0] if 0.0 < c < end)}
    hold = model.fx.get("hold")
    if hold:
        cuts |= {round(float(x), 9) for x in np.arange(1, int(end / hold) + 1) * hold
                 if round(float(x), 9) < end}
    cuts = sorted(cuts)
    out = np.empty((model.size, t.size))
    y0 = np.zeros(model.size)
    for a, b in itertools.pairwise(cuts):
        k = int(np.searchsorted(bp[:, 0], 0.5 * (a + b))) - 1
        slope = (bp[k + 1, 1] - bp[k, 1]) / (bp[k + 1, 0] - bp[k, 0])
        if hold:
            at = math.floor(a / hold + 1e-9) * hold
            model.seg = (a, float(np.interp(at, bp[:, 0], bp[:, 1])), 0.0)
        else:
            model.seg = (a, float(np.interp(a, bp[:, 0], bp[:, 1])), float(slope))
        final = b == end
        mask = (t >= a) & (t <= b if final else t < b)
        idx = np.flatnonzero(mask)
        t_out = t[idx] if final else np.append(t[idx], b)
        ys = _solve(model, a, b, y0, t_out, max_step)
        out[:, idx] = ys[:, :idx.size]
        y0 = ys[:, -1].copy()
    return out


def simulate(regime: str, t: np.ndarray | None = None, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor BF at the times ``t`` [s] (default the regime's grid), from
    rest, with ``p`` over the declared values and ``fx["p"]`` over those: current [A] (the
    stand's shunt in the armature lead), speed [rad/s] (the motor's rear-shaft encoder), in
    the slow regime load_speed [rad/s] (the encoder on the roll's shaft end), and the command
    ``u`` [V]; ``states`` adds the bodies' angles and speeds, the twist and the outside
    effects' states."""
    fx = dict(fx or {})
    par = {**MOTOR_BF, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = RingRoller(fx, par)
    y = integrate(model, t, bp, MAX_STEP[regime])
    look = model.sees(t, y)
    for probe, _, j in model.pade:
        look[probe] = 2.0 * y[j] - look[probe]
    out = {pr: np.array(look[pr], dtype=float) for pr in PROBES[regime]}
    for probe, d in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = d.get("gain", 1.0) * out[probe] + d.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        n = par["N"]
        out.update(armature_current=y[0], rotor_angle=y[2], hub_speed=y[1] / n,
                   hub_angle=y[2] / n, roll_speed=y[3], roll_angle=y[4],
                   twist=y[2] / n - y[4])
        if model.j_enc is not None:
            out["encoder_angle"] = y[model.j_enc]
        if model.j_slew is not None:
            out["speed_module"] = y[model.j_slew]
    return out


# ---------------------------------------------------------------------- noise

def ar1(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float) -> np.ndarray:
    """A stationary Gauss-Markov sequence of deviation ``sigma``, correlation time ``tau``
    [s], exact at the (uneven) times ``t``."""
    a = np.exp(-np.diff(t) / tau)
    z = rng.standard_normal(t.size)
    x = np.empty(t.size)
    x[0] = sigma * z[0]
    for j in range(1, t.size):
        x[j] = a[j - 1] * x[j - 1] + sigma * math.sqrt(1.0 - a[j - 1] ** 2) * z[j]
    return x


def pink(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise of deviation ``sigma`` at ``t``: white noise on an even grid over the
    record shaped by 1/sqrt(f) in amplitude (no mean), read at ``t`` linearly."""
    m = t.size
    tg = np.linspace(t[0], t[-1], m)
    f = np.fft.rfftfreq(m, tg[1] - tg[0])
    z = np.fft.rfft(rng.standard_normal(m))
    z[0] = 0.0
    z[1:] /= np.sqrt(f[1:] / f[1])
    x = np.interp(t, tg, np.fft.irfft(z, m))
    x = x - x.mean()
    return sigma * x / x.std()


def add_noise(rng: np.random.Generator, t: np.ndarray, y: np.ndarray,
              spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` with white (``white`` sigma), AR(1) (``ar1`` [sigma, phi], phi the correlation
    over the mean interval) and 1/f (``pink`` sigma) noise, read by an ADC of step
    ``quant``."""
    out = np.asarray(y, dtype=float).copy()
    if spec.get("white"):
        out = out + rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        s, phi = spec["ar1"]
        out = out + ar1(rng, t, s, -float(np.mean(np.diff(t))) / math.log(phi))
    if spec.get("pink"):
        out = out + pink(rng, t, spec["pink"])
    q = spec.get("quant")
    return np.round(out / q) * q if q else out
