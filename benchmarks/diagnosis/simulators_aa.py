"""Motor AA of the diagnosis benchmark: a hand-written scipy model of a 36 V permanent-magnet
brushed DC motor driving an INDUSTRIAL LOCKSTITCH SEWING MACHINE's head: the motor, mounted
under the table, turns the head's main (arm) shaft through a toothed (timing) belt, a 24-tooth
motor pulley to a 36-tooth head pulley (1.5:1). The belt's tension members stretch: a
compliance between the belt's teeth and the head's shaft, which carries the handwheel, the
head pulley and, through the crank and the hook drive, the needle bar, the take-up lever and
the rotary hook.

No circuitsim import: an independent simulator (the twenty-fourth of the benchmark), written
from the physics for netlists/motor_aa_fast.yaml and motor_aa_slow.yaml. It is evaluated at
the record's own sample times (``t_eval``), never on a grid that is then interpolated.
Everything rests at t = 0 (no current, no speed, the belt unstretched).

The belt's tooth engagement is rigid (``gear`` G, ratio N = 1.5): the belt, reflected to the
head pulley's pitch radius, stands at thb = th / N and turns at wb = w / N with the rotor; a
torque T on it is T / N on the rotor. Its stretch is a spring and damper on the twist
thb - thh between the belt and the head (``spring_damper`` K).

State z = [i, w, th, wh, thh] (+ one state per outside effect that needs one, + one Pade
stage per delayed probe):

    i          armature current [A]
    w, th      rotor speed [rad/s] and angle [rad]
    wh, thh    the head's (main shaft's) speed and angle [rad/s, rad]

Equations (J1 = Jm + Jbt / N^2: the rotor with its pulley and the belt's own mass):

    L di/dt   = v(t) - R i - k w - (the loop's extras)
    J1 dw/dt  = k i - bm w - Tb tanh(w / 0.01) + X_rotor + (X_belt - Tk) / N
    Jh dwh/dt = Tk - Bh wh - Th tanh(wh / 0.01) + X_head
    Tk        = Kb (th / N - thh) + Db (w / N - wh)          (the belt's stretch)

Tb tanh(w / 0.01) is the brushes' dry friction (``friction``, w_brk 0.1), Bh wh the head's oil
drag, Th tanh(wh / 0.01) the mechanisms' dry friction (``friction``, w_brk 0.1).

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance R (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance R (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): dpsi/di = L (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order th) + b cos(order th))
    cog       {body: [(order, a, b), ...]}: the body (rotor, belt, head) receives
              a sin(order angle) + b cos(order angle) [N m]
    coul      {body: c}: c tanh(speed / 0.01) against the body's motion [N m]
    visc      {body: b}: an extra viscous friction [N m s/rad]
    offset    {body: T}: a constant torque [N m] the body receives
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: declared parameters changed (an inertia, the inductance)

and outside the catalog:

    lag       (probe, tau [s]): the probe is read through a first-order RC low-pass,
              dyf/dt = (y - yf) / tau from 0 (a frequency-to-voltage converter's filter)
    film      (a [V/A^0.5], eps [A]): a tarnished connector's film in the loop, a drop
              a i (i^2 + eps^2)^(-1/4) (about a sqrt(|i|) sign(i))
    ecc       (e [1], phase [rad]): a bent rotor shaft, the air gap eccentric: the EMF and
              the torque constant are k (1 + e sin(th + phase))
    bushing   (T0 [N m], beta [1/K], C [J/K], G [W/K]): a needle-bar bushing running dry,
              its friction growing with its temperature rise dT: the head takes
              -T0 (1 + beta dT) tanh(wh / 0.01); C ddT/dt = T0 (1 + beta dT) tanh(wh / 0.01)
              wh - G dT (from 0)
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

#: declared values of motor AA [SI] (motor_aa_fast.yaml, motor_aa_slow.yaml)
MOTOR_AA: dict[str, float] = {
    "R": 1.0, "L": 1.8e-3, "k": 0.075, "Jm": 8e-5, "bm": 2e-5, "Tb": 0.01, "N": 1.5,
    "Jbt": 3.3e-5, "Kb": 25.0, "Db": 0.01, "Jh": 8e-4, "Bh": 6e-4, "Th": 0.06,
}
#: [rad/s] the frictions' and the catalog's switch tanh(w / 0.01); [A] the brush drop's
W_SIGN, I_SIGN = 0.01, 1e-3
#: the fast regime's command [s, V] (motor_aa_fast.yaml's pwl)
FAST_POINTS = ((0.0, 0.0), (0.005, 0.0), (0.02, 24.0), (0.1, 24.0), (0.102, 36.0),
               (0.16, 36.0), (0.162, 10.0), (0.22, 10.0), (0.222, 0.0), (0.26, 0.0),
               (0.262, -14.0), (0.31, -14.0), (0.312, 0.0), (0.35, 0.0))
#: the slow regime's logged command [s, V] (motor_aa_slow.yaml's pwl; the record's ``u``)
SLOW_POINTS = ((0.0, 0.0), (0.3, 0.0), (0.5, 20.0), (1.0, 20.0), (1.1, 36.0), (2.6, 36.0),
               (2.7, 14.0), (3.4, 14.0), (3.5, 0.0), (4.0, 0.0), (4.05, -6.0), (4.3, -6.0),
               (4.35, 0.0), (4.7, 0.0), (4.9, 28.0), (5.6, 28.0), (5.7, 0.0), (6.0, 0.0))
#: nominal (mean) sample rate [Hz] and duration [s] of each regime
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, 0.35), "slow": (500.0, 6.0)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("current", "speed"),
                                      "slow": ("current", "speed", "load_speed")}
BODIES = ("rotor", "belt", "head")
RTOL, ATOL = 1e-10, 1e-12
#: [s] the largest step per regime: the sample interval in the fast regime (L/R is 1.8 ms),
#: a fifth of the mean interval in the slow one
H_MAX = {"fast": 5e-5, "slow": 4e-4}


def breakpoints(regime: str) -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the command, linear between points, held after."""
    return np.asarray(FAST_POINTS if regime == "fast" else SLOW_POINTS, dtype=float)


def grid(regime: str) -> np.ndarray:
    """The regime's nominal, evenly spaced sample times [s]."""
    fs, dur = REGIMES[regime]
    return np.arange(round(fs * dur) + 1) / fs


# ---------------------------------------------------------------------- the model

class SewingDrive:
    """Right-hand side of motor AA with one set of effects ``fx`` [SI]."""

    def __init__(self, fx: Mapping[str, Any], p: Mapping[str, float]):
        """The effects ``fx`` and the motor's parameters ``p`` [SI]."""
        self.fx, self.p = fx, p
        self.n = p["N"]
        self.j1 = p["Jm"] + p["Jbt"] / self.n ** 2
        k = 5
        #: indices of the outside effects' states (bushing temperature, lagged probe)
        self.k_bush = self.k_lag = None
        if "bushing" in fx:
            self.k_bush, k = k, k + 1
        if "lag" in fx:
            self.k_lag, k = k, k + 1
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
        """What the catalog's effects put on ``body``: (viscous, Coulomb, offset,
        harmonics), or None when nothing."""
        fx = self.fx
        t = (fx.get("visc", {}).get(body, 0.0), fx.get("coul", {}).get(body, 0.0),
             fx.get("offset", {}).get(body, 0.0), tuple(fx.get("cog", {}).get(body, ())))
        return t if any(t) else None

    def extra_torque(self, body: str, w: float, angle: float) -> float:
        """The torque [N m] the catalog's effects give ``body`` at its speed ``w`` [rad/s]
        and angle ``angle`` [rad]."""
        t = self.terms[body]
        if t is None:
            return 0.0
        visc, coul, off, harm = t
        out = off - visc * w - coul * math.tanh(w / W_SIGN)
        for order, a, b in harm:
            out += a * math.sin(order * angle) + b * math.cos(order * angle)
        return out

    def command(self, t: float) -> float:
        """The driver's mean output [V] as commanded, linear within the segment."""
        t0, u0, slope = self.seg
        return u0 + slope * (t - t0)

    def loop_drop(self, t: float, i: float, w: float, th: float) -> float:
        """Every voltage [V] the loop takes but the inductance's and the declared EMF's:
        the (drifting) resistances, the brushes, the film and the EMF's harmonics, at the
        time ``t`` [s], the current ``i`` [A], the rotor's speed ``w`` [rad/s] and angle
        ``th`` [rad]."""
        p, fx = self.p, self.fx
        r = p["R"] * (1.0 + fx.get("alpha", 0.0) * t) + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["R"] * rise * (1.0 - math.exp(-t / tau))
        v = r * i
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SIGN)
        if "film" in fx:
            a, eps = fx["film"]
            v += a * i * (i * i + eps * eps) ** -0.25
        for order, a, b in fx.get("emf", ()):
            v += w * (a * math.sin(order * th) + b * math.cos(order * th))
        return v

    def k_of(self, th: float) -> float:
        """The EMF and torque constant [V s/rad = N m/A] at the rotor's angle ``th``
        [rad] (modulated by an eccentric air gap)."""
        if "ecc" in self.fx:
            e, ph = self.fx["ecc"]
            return self.p["k"] * (1.0 + e * math.sin(th + ph))
        return self.p["k"]

    def inductance(self, i: float) -> float:
        """The differential inductance [H] at the current ``i`` [A]."""
        ell = self.p["L"]
        if "lsat" in self.fx:
            ipar, ratio = self.fx["lsat"]
            ell *= ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2)
        return ell

    def bushing(self, wh: float, dtb: float) -> float:
        """The dry bushing's friction torque [N m] against the head's motion at its speed
        ``wh`` [rad/s] and temperature rise ``dtb`` [K] (0 without it)."""
        if "bushing" not in self.fx:
            return 0.0
        t0, beta, _, _ = self.fx["bushing"]
        return t0 * (1.0 + beta * dtb) * math.tanh(wh / W_SIGN)

    def __call__(self, t: float, z: np.ndarray) -> list[float]:
        """dz/dt [SI/s] at the time ``t`` [s] in the state ``z`` [SI]."""
        p, n = self.p, self.n
        i, w, th, wh, thh = (float(v) for v in z[:5])
        kth = self.k_of(th)
        di = (self.command(t) - self.loop_drop(t, i, w, th) - kth * w) / self.inductance(i)
        tk = p["Kb"] * (th / n - thh) + p["Db"] * (w / n - wh)
        tau = (kth * i - p["bm"] * w - p["Tb"] * math.tanh(w / W_SIGN)
               + self.extra_torque("rotor", w, th)
               + (self.extra_torque("belt", w / n, th / n) - tk) / n)
        dtb = float(z[self.k_bush]) if self.k_bush is not None else 0.0
        fb = self.bushing(wh, dtb)
        dwh = (tk - p["Bh"] * wh - p["Th"] * math.tanh(wh / W_SIGN) - fb
               + self.extra_torque("head", wh, thh)) / p["Jh"]
        out = [di, tau / self.j1, w, dwh, wh]
        values = {"current": i, "speed": w, "load_speed": wh}
        if self.k_bush is not None:
            _, _, cap, g = self.fx["bushing"]
            out.append((fb * wh - g * dtb) / cap)
        if self.k_lag is not None:
            probe, tau_f = self.fx["lag"]
            out.append((values[probe] - float(z[self.k_lag])) / tau_f)
        out += [2.0 * (values[probe] - float(z[k])) / tau_d for probe, tau_d, k in self.pade]
        return out


# ---------------------------------------------------------------------- integration

def _solve(model: SewingDrive, a: float, b: float, z0: np.ndarray, t_out: np.ndarray,
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
    raise RuntimeError(f"motor AA, {a:g}-{b:g} s: {msg}")


def integrate(model: SewingDrive, t: np.ndarray, bp: np.ndarray, h_max: float
              ) -> np.ndarray:
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
    """Noise-free probes of motor AA at the times ``t`` [s] (default: the nominal grid),
    from rest: current [A], speed [rad/s] (the motor's encoder), and in the slow regime
    load_speed [rad/s] (the head's main shaft, from the handwheel's synchroniser), plus the
    command ``u`` [V]. ``states``: add the angles [rad]."""
    fx = dict(fx or {})
    p = {**MOTOR_AA, **(p or {}), **fx.pop("p", {})}
    t = grid(regime) if t is None else np.asarray(t, dtype=float)
    bp = breakpoints(regime)
    model = SewingDrive(fx, p)
    y = integrate(model, t, bp, H_MAX[regime])
    full = {"current": y[0], "speed": y[1], "load_speed": y[3]}
    if model.k_lag is not None:
        full[fx["lag"][0]] = y[model.k_lag]
    for probe, _, k in model.pade:
        full[probe] = 2.0 * y[k] - full[probe]
    out = {probe: full[probe].copy() for probe in PROBES[regime]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, bp[:, 0], bp[:, 1])
    if states:
        out.update(rotor_angle=y[2], head_angle=y[4], head_speed=y[3])
        if model.k_bush is not None:
            out["bushing_rise"] = y[model.k_bush]
    return out


# ---------------------------------------------------------------------- noise

def gauss_markov(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float
                 ) -> np.ndarray:
    """A stationary Gauss-Markov process [probe unit] of standard deviation ``sigma`` and
    correlation time ``tau`` [s], sampled exactly at the times ``t`` [s]."""
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
