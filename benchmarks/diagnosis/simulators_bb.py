"""Motor BB of the diagnosis benchmark: a hand-written scipy model of Kim & Kim 2024's small
brushed DC motor (Machines 12(3):148: Ra = 1.1 ohm, La = 0.87 mH, J = 4.57e-6 kg m^2,
B = 2.95e-4 N m s/rad, k_t = 0.14 N m/A, the back-EMF 0.1017 V per rev/s + 1.151e-4 V with
its 8th-order ripple (0.0168 V per rev/s + 2.504e-5 V) sin(8 phi)) behind the paper's
connector (a varistor, Rv = 500 Mohm in series with Cv = 1.6 uF, across the motor's input; a
0.22 uH rod-core inductor on each pole) and one of three of the paper's SUPPLY FILTERS between
the bench supply (node s) and the connector's input (node a):

    case 3  series Rf = 0.5 ohm, shunt Cf = 1000 uF at a          (netlists/motor_bb_case3.yaml)
    case 5  series Lf = 1 mH with Rf = 0.05 ohm, shunt Cf = 1000 uF (motor_bb_case5.yaml)
    case 6  series Lf = 1 mH, an RC snubber Rs = 1 ohm + Cs = 470 uF across a
                                                                   (motor_bb_case6.yaml)

No circuitsim import, and no other set's simulator: an independent simulator, written from the
physics for those netlists (the MNA equations eliminated by hand into ODEs). It is evaluated at
the record's own sample times (``t_eval``), never on a grid that is then interpolated.
Everything rests at t = 0 (no current, no charge, no speed, the rotor at angle 0).

The stimulus (every netlist's): the bench supply's output u(t) (``pwl``: 0 V, 12 V from 0.5 ms,
a dip to 8 V from 80 to 120 ms (2 ms ramps), 12 V again, a reversal to -12 V over 220-230 ms,
held to 0.3 s) and a brake on the rotor (``torque`` Tl, ``step``): the rotor receives
TL(t) = -0.05 N m from 160 ms (a 1 ms ramp), always.

State y = [i, w, phi, vcv, (filter states), (outside effects' states), (Pade stages)]:

    i       the armature current [A] (through Lc1, Ra, La, M and Lc2 in series)
    w, phi  the rotor's speed [rad/s] and angle [rad]
    vcv     the varistor's capacitor voltage [V] (Rv in series with Cv, from a to gnd)
    case 3  va   [V]  Cf's voltage (node a)
    case 5  iLf  [A]  the filter inductor's current, va [V] Cf's voltage
    case 6  iLf  [A], vcs [V] the snubber capacitor's voltage; va algebraic:
            va = (iLf - i + vcv/Rv + vcs/Rs) / (1/Rv + 1/Rs)

Equations (ke, s8 in V s/rad: the netlist's V s/rev over 2 pi):

    (La + 2 L_conn) di/dt = va - Ra i - e - (the loop's extras),
        e = ke w + e0 + (s8 w + o8) sin(8 phi)
    J dw/dt = k_t i - B w + TL(t) + (the rotor's extras)
    Cv dvcv/dt = iv = (va - vcv) / Rv
    case 3:  Cf dva/dt = (u - va) / Rf - i - iv;   i_total = (u - va) / Rf
    case 5:  Lf diLf/dt = u - Rf iLf - va;  Cf dva/dt = iLf - i - iv;   i_total = iLf
    case 6:  Lf diLf/dt = u - va;  Cs dvcs/dt = (va - vcs) / Rs;   i_total = iLf
    speed = w

Effects (``fx`` keys, SI, all off by default), the catalog's laws as its patches write them:

    Rs, Rser  [ohm]   a resistance inside the source (in series with the supply, before the
              filter) / in series with the armature
    Vb        [V]     brush drop Vb tanh(i / 1 mA)
    alpha     [1/s]   the armature's resistance Ra (1 + alpha t)
    warmup    (rise, tau [s]): the armature's resistance Ra (1 + rise (1 - exp(-t / tau)))
    lsat      (Ipar [A], ratio): La's dpsi/di = La (ratio + (1 - ratio) / (1 + (i / Ipar)^2))
    lsat_f    (Ipar [A], ratio): the same for the filter inductor Lf (cases 5, 6)
    emf       [(order, a, b), ...]: the EMF gains w (a sin(order phi) + b cos(order phi))
    cog       {"rotor": [(order, a, b), ...]}: the rotor receives a sin(order phi)
              + b cos(order phi) [N m]
    coul      {"rotor": c}: c tanh(w / 0.01) against the rotor's motion [N m]
    visc      {"rotor": b}: an extra viscous friction [N m s/rad]
    offset    {"rotor": T}: a constant torque [N m] the rotor receives
    stribeck  {"rotor": (s, ws)}: s exp(-(w / ws)^2) tanh(w / 0.01) against it [N m]
    sensor    {probe: {"gain": g, "offset": o, "delay": tau}}: the probe reads g yd + o,
              yd the probe through a first-order Pade stage of delay tau (yd = 2 q - y,
              dq/dt = 2 (y - q) / tau, from rest)
    p         {name: value}: parameters changed (the record's true values of the declared
              ones the user frees, an inertia's or an inductance's correction)

and outside the catalog:

    capbias   (r [1], V0 [V]): Cf (cases 3, 5) is a bank of class-II ceramic capacitors whose
              capacitance falls with the DC bias: its differential capacitance dq/dv =
              Cf (r + (1 - r) / (1 + (va / V0)^2))
    revcap    (Ir [A], Vr [V]): Cf (case 5) is a polarised aluminium electrolytic that conducts
              like a diode when reverse-biased: it carries, besides Cf dva/dt, the current
              -Ir (exp(-va / Vr) - 1) from a to gnd (+Ir of leakage when forward-biased, an
              exponentially growing reverse current when va < 0)
    fritt     (R0 [ohm], r1 [ohm], Vf [V], n [1], tau [s]): a tarnished contact of the
              connector's + pole whose oxide film breaks down (A-fritting) under the voltage
              across it: the armature loop takes Rc i, Rc = r1 + (R0 - r1) h, h the intact
              fraction of the film (1 at the start), dh/dt = -h (|Rc i| / Vf)^n / tau; it
              never heals
    ktrip     (m [1], psi [rad]): the torque constant ripples with the slots: the rotor
              receives k_t i (1 + m sin(8 phi + psi)) (the EMF unchanged)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

TWO_PI = 2.0 * math.pi
#: the declared motor and connector [SI] (every netlist's; k_e and A8_slope are the netlist's
#: V s/rev over 2 pi)
MOTOR: dict[str, float] = {
    "Ra": 1.1, "La": 0.87e-3, "L_conn": 0.22e-6, "Rv": 500e6, "Cv": 1.6e-6,
    "J": 4.57e-6, "B": 2.95e-4, "k_t": 0.14, "k_e": 0.1017 / TWO_PI, "e0": 1.151e-4,
    "A8_slope": 0.0168 / TWO_PI, "A8_offset": 2.504e-5,
}
#: each case's declared filter [SI]
FILTERS: dict[int, dict[str, float]] = {
    3: {"Rf": 0.5, "Cf": 1000e-6},
    5: {"Lf": 1e-3, "Rf": 0.05, "Cf": 1000e-6},
    6: {"Lf": 1e-3, "Rs": 1.0, "Cs": 470e-6},
}
CASES = tuple(FILTERS)
#: [rad/s] the dry frictions' switch tanh(w / 0.01); [A] the brush drop's tanh(i / 1 mA)
W_SWITCH, I_SWITCH = 0.01, 1e-3
#: the supply's output [s, V] (every netlist's pwl)
POINTS = ((0.0, 0.0), (0.0005, 12.0), (0.080, 12.0), (0.082, 8.0), (0.120, 8.0),
          (0.122, 12.0), (0.220, 12.0), (0.230, -12.0), (0.300, -12.0))
#: the brake: (t0 [s], rise [s], the torque the rotor receives after it [N m])
BRAKE = (0.160, 0.001, -0.05)
DURATION = 0.3
REGIMES: dict[str, tuple[float, float]] = {"fast": (20e3, DURATION)}
PROBES: dict[str, tuple[str, ...]] = {"fast": ("i_total", "speed")}
RTOL, ATOL = 1e-10, 1e-12


def params(case: int) -> dict[str, float]:
    """The declared parameters of a case's netlist [SI]."""
    return {**MOTOR, **FILTERS[case]}


def breakpoints() -> np.ndarray:
    """(n, 2) array of [t [s], u [V]]: the supply's output, linear between points."""
    return np.array(POINTS, dtype=float)


def corners(end: float) -> list[float]:
    """Every time [s] in (0, end) where the supply's or the brake's slope changes."""
    ts = {float(c) for c, _ in POINTS} | {BRAKE[0], BRAKE[0] + BRAKE[1]}
    return sorted({0.0, end, *(c for c in ts if 0.0 < c < end)})


def grid(fs: float, duration: float = DURATION) -> np.ndarray:
    """An even grid k/fs [s]."""
    return np.arange(round(fs * duration) + 1) / fs


def brake(t: float) -> float:
    """The torque the rotor receives from the brake [N m] (the netlist's ``step``)."""
    t0, rise, v1 = BRAKE
    u = (t - t0) / rise
    if u < 0.0:
        return 0.0
    return v1 * u if u < 1.0 else v1


# ---------------------------------------------------------------------- the model

class KimDrive:
    """Right-hand side of motor BB (``case``) with the effects ``fx`` and the parameters
    ``p`` [SI]; ``seg`` holds the supply's current segment (t0 [s], u0 [V], slope [V/s])."""

    def __init__(self, case: int, fx: Mapping[str, Any], p: Mapping[str, float]):
        if case not in FILTERS:
            raise ValueError(f"no filter case {case}")
        self.case, self.fx, self.p = case, fx, p
        size = 6
        #: the index of the contact film's state (``fritt``)
        self.i_film = None
        if "fritt" in fx:
            self.i_film, size = size, size + 1
        self.delays: list[tuple[str, float, int]] = []
        for probe, s in fx.get("sensor", {}).items():
            if s.get("delay"):
                self.delays.append((probe, float(s["delay"]), size))
                size += 1
        self.size = size
        rot = {key: fx[key]["rotor"] for key in ("visc", "coul", "offset", "stribeck", "cog")
               if fx.get(key, {}).get("rotor")}
        self.rot = rot
        self.seg = (0.0, 0.0, 0.0)
        self.lc2 = 2.0 * p["L_conn"]
        self.rsrc = fx.get("Rs", 0.0)
        if "revcap" in fx and case != 5:
            raise ValueError("revcap: case 5's electrolytic Cf only")
        if "capbias" in fx and case not in (3, 5):
            raise ValueError("capbias: the shunt Cf of cases 3 and 5 only")
        if "lsat_f" in fx and case == 3:
            raise ValueError("lsat_f: no Lf in case 3")

    def initial(self) -> np.ndarray:
        """The state at rest at t = 0 (the contact's film intact)."""
        y0 = np.zeros(self.size)
        if self.i_film is not None:
            y0[self.i_film] = 1.0
        return y0

    def supply(self, t: float) -> float:
        """The supply's output [V] within the current segment."""
        t0, u0, slope = self.seg
        return u0 + slope * (t - t0)

    def rotor_torque(self, w: float, phi: float) -> float:
        """The catalog's torque effects on the rotor [N m]."""
        e = self.rot
        if not e:
            return 0.0
        sw = math.tanh(w / W_SWITCH)
        tq = e.get("offset", 0.0) - e.get("visc", 0.0) * w - e.get("coul", 0.0) * sw
        if "stribeck" in e:
            s, ws = e["stribeck"]
            tq -= s * math.exp(-(w / ws) ** 2) * sw
        for order, a, b in e.get("cog", ()):
            tq += a * math.sin(order * phi) + b * math.cos(order * phi)
        return tq

    def loop(self, t: float, i: float, phi: float, w: float) -> float:
        """The armature loop's voltage [V] besides its inductances' and the declared EMF."""
        p, fx = self.p, self.fx
        r = p["Ra"] * (1.0 + fx.get("alpha", 0.0) * t)
        if "warmup" in fx:
            rise, tau = fx["warmup"]
            r += p["Ra"] * rise * (1.0 - math.exp(-t / tau))
        r += fx.get("Rser", 0.0)
        v = r * i
        if "Vb" in fx:
            v += fx["Vb"] * math.tanh(i / I_SWITCH)
        for order, a, b in fx.get("emf", ()):
            v += w * (a * math.sin(order * phi) + b * math.cos(order * phi))
        return v

    def l_arm(self, i: float) -> float:
        """The armature loop's differential inductance [H] (La, saturating if ``lsat``, and
        the connector's two rod-core inductors)."""
        la = self.p["La"]
        if "lsat" in self.fx:
            ipar, ratio = self.fx["lsat"]
            la *= ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2)
        return la + self.lc2

    def l_filter(self, i: float) -> float:
        """The filter inductor's differential inductance [H] (``lsat_f``)."""
        lf = self.p["Lf"]
        if "lsat_f" in self.fx:
            ipar, ratio = self.fx["lsat_f"]
            lf *= ratio + (1.0 - ratio) / (1.0 + (i / ipar) ** 2)
        return lf

    def c_filter(self, v: float) -> float:
        """Cf's differential capacitance [F] at its voltage ``v`` [V] (``capbias``)."""
        cf = self.p["Cf"]
        if "capbias" in self.fx:
            r, v0 = self.fx["capbias"]
            cf *= r + (1.0 - r) / (1.0 + (v / v0) ** 2)
        return cf

    def node(self, y: np.ndarray) -> float:
        """The connector's input voltage va [V]."""
        if self.case == 6:
            p = self.p
            return (y[4] - y[0] + y[3] / p["Rv"] + y[5] / p["Rs"]) / (1.0 / p["Rv"]
                                                                      + 1.0 / p["Rs"])
        return y[4] if self.case == 3 else y[5]

    def __call__(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt [SI/s] at the time ``t`` [s] in the state ``y`` [SI]."""
        p, fx, case = self.p, self.fx, self.case
        i, w, phi, vcv = y[0], y[1], y[2], y[3]
        u = self.supply(t)
        va = self.node(y)
        s8 = math.sin(8.0 * phi)
        emf = p["k_e"] * w + p["e0"] + (p["A8_slope"] * w + p["A8_offset"]) * s8
        varm = va - self.loop(t, i, phi, w) - emf
        if self.i_film is not None:
            r0, r1, vf, n, tau = fx["fritt"]
            h = y[self.i_film]
            vc = (r1 + (r0 - r1) * h) * i
            varm -= vc
            dh = -h * (abs(vc) / vf) ** n / tau
        iv = (va - vcv) / p["Rv"]
        dy = np.empty(self.size)
        if case == 3:
            rf = p["Rf"] + self.rsrc
            dy[4] = ((u - va) / rf - i - iv) / self.c_filter(va)
            dy[5] = 0.0
            dy[0] = varm / self.l_arm(i)
        else:
            ilf = y[4]
            if case == 5:
                vf = u - (p["Rf"] + self.rsrc) * ilf - va
                ic = ilf - i - iv
                if "revcap" in fx:
                    ir, vr = fx["revcap"]
                    ic += ir * math.expm1(-va / vr)
                dy[5] = ic / self.c_filter(va)
            else:
                vf = u - self.rsrc * ilf - va
                dy[5] = (va - y[5]) / (p["Rs"] * p["Cs"])
            dy[0] = varm / self.l_arm(i)
            dy[4] = vf / self.l_filter(ilf)
        torque = p["k_t"] * i
        if "ktrip" in fx:
            m_, psi = fx["ktrip"]
            torque *= 1.0 + m_ * math.sin(8.0 * phi + psi)
        dy[1] = (torque - p["B"] * w + brake(t) + self.rotor_torque(w, phi)) / p["J"]
        dy[2] = w
        dy[3] = iv / p["Cv"]
        if self.i_film is not None:
            dy[self.i_film] = dh
        if self.delays:
            seen = self.seen(t, y)
            for probe, tau, j in self.delays:
                dy[j] = 2.0 * (seen[probe] - y[j]) / tau
        return dy

    def seen(self, t: Any, y: np.ndarray) -> dict[str, Any]:
        """What each probe's sensor sees [A, rad/s] before its catalog effects: the supply's
        current and the rotor's speed (``t`` a time or an array of them, with ``seg``
        covering them in a scalar call)."""
        if self.case == 3:
            u = self.supply(t) if np.ndim(t) == 0 else np.interp(t, *breakpoints().T)
            cur = (u - y[4]) / (self.p["Rf"] + self.rsrc)
        else:
            cur = y[4]
        return {"i_total": cur, "speed": y[1]}


# ---------------------------------------------------------------------- integration

def _span(model: KimDrive, a: float, b: float, y0: np.ndarray, t_out: np.ndarray,
          max_step: float) -> np.ndarray:
    """The states at ``t_out`` [s] from ``y0`` at ``a`` to ``b`` [s]: LSODA, Radau if LSODA
    fails."""
    why = ""
    for method in ("LSODA", "Radau"):
        sol = solve_ivp(model, (a, b), y0, method=method, t_eval=t_out, rtol=RTOL,
                        atol=ATOL, max_step=max_step)
        if sol.success and np.isfinite(sol.y).all() and sol.y.shape[1] == t_out.size:
            return sol.y
        why = sol.message
    raise RuntimeError(f"motor BB, {a:g}-{b:g} s: {why}")


def integrate(model: KimDrive, t: np.ndarray, max_step: float) -> np.ndarray:
    """The states (n_states, t.size) at the increasing times ``t`` [s], from rest at 0, the
    integration restarted at every corner of the supply and the brake."""
    end = float(t[-1])
    cs = corners(end)
    bp = breakpoints()
    out = np.empty((model.size, t.size))
    y0 = model.initial()
    for a, b in itertools.pairwise(cs):
        mid = 0.5 * (a + b)
        j = min(int(np.searchsorted(bp[:, 0], mid)) - 1, len(bp) - 2)
        slope = float(bp[j + 1, 1] - bp[j, 1]) / float(bp[j + 1, 0] - bp[j, 0])
        if mid > bp[-1, 0]:
            slope = 0.0
        model.seg = (a, float(np.interp(a, bp[:, 0], bp[:, 1])), slope)
        last = b == end
        inside = (t >= a) & ((t <= b) if last else (t < b))
        t_out = t[inside] if last else np.append(t[inside], b)
        ys = _span(model, a, b, y0, t_out, max_step)
        idx = np.flatnonzero(inside)
        out[:, idx] = ys[:, :idx.size]
        y0 = ys[:, -1].copy()
    return out


def simulate(case: int, t: np.ndarray, fx: Mapping[str, Any] | None = None,
             p: Mapping[str, float] | None = None, states: bool = False
             ) -> dict[str, np.ndarray]:
    """Noise-free probes of motor BB's ``case`` at the times ``t`` [s], from rest, with the
    parameters ``p`` over the declared ones (and ``fx["p"]`` over those): i_total [A] (the
    supply's current, a current probe on the supply's lead) and speed [rad/s] (the rotor's),
    and the supply's output ``u`` [V]. ``states``: add the armature current, the connector's
    input voltage and the rotor's angle. The largest step is the mean sample interval."""
    fx = dict(fx or {})
    p = {**params(case), **(p or {}), **fx.pop("p", {})}
    t = np.asarray(t, dtype=float)
    model = KimDrive(case, fx, p)
    max_step = float(t[-1] - t[0]) / (t.size - 1)
    y = integrate(model, t, max_step)
    seen = model.seen(t, y)
    for probe, _, j in model.delays:
        seen[probe] = 2.0 * y[j] - seen[probe]
    out = {probe: np.array(seen[probe], dtype=float) for probe in PROBES["fast"]}
    for probe, s in fx.get("sensor", {}).items():
        if probe in out:
            out[probe] = s.get("gain", 1.0) * out[probe] + s.get("offset", 0.0)
    out["u"] = np.interp(t, *breakpoints().T)
    if states:
        out.update(armature_current=y[0], rotor_angle=y[2],
                   va=np.array([model.node(y[:, k]) for k in range(t.size)]))
    return out


# ---------------------------------------------------------------------- noise

def gauss_markov(rng: np.random.Generator, t: np.ndarray, sigma: float, tau: float
                 ) -> np.ndarray:
    """A stationary first-order Gauss-Markov process [probe unit] of standard deviation
    ``sigma`` and correlation time ``tau`` [s], exact at the (uneven) times ``t``."""
    rho = np.exp(-np.diff(t) / tau)
    e = rng.standard_normal(t.size) * sigma
    e[1:] *= np.sqrt(1.0 - rho ** 2)
    x = np.empty(t.size)
    x[0] = e[0]
    for j in range(1, t.size):
        x[j] = rho[j - 1] * x[j - 1] + e[j]
    return x


def flicker(rng: np.random.Generator, t: np.ndarray, sigma: float) -> np.ndarray:
    """1/f noise [probe unit] of standard deviation ``sigma`` at the times ``t`` [s]: white
    noise on an even grid spanning the record, its amplitude spectrum shaped by 1/sqrt(f)
    (no mean), read at ``t`` linearly."""
    n = t.size
    even = np.linspace(float(t[0]), float(t[-1]), n)
    f = np.fft.rfftfreq(n, float(even[1] - even[0]))
    spec = np.fft.rfft(rng.standard_normal(n))
    spec[0] = 0.0
    spec[1:] *= np.sqrt(f[1] / f[1:])
    x = np.interp(t, even, np.fft.irfft(spec, n))
    x -= x.mean()
    return x * (sigma / x.std())


def add_noise(rng: np.random.Generator, t: np.ndarray, y: np.ndarray,
              spec: Mapping[str, Any]) -> np.ndarray:
    """``y`` at the times ``t`` [s] with ``white`` sigma, ``ar1`` [sigma, phi] (a
    Gauss-Markov process correlated by phi over the mean interval) and ``pink`` (1/f) sigma
    noise added [probe unit], then read by an ADC of step ``quant`` [probe unit]."""
    out = np.array(y, dtype=float)
    if spec.get("white"):
        out += rng.normal(0.0, spec["white"], out.size)
    if spec.get("ar1"):
        sigma, phi = spec["ar1"]
        out += gauss_markov(rng, t, sigma, -float(np.mean(np.diff(t))) / math.log(phi))
    if spec.get("pink"):
        out += flicker(rng, t, spec["pink"])
    step = spec.get("quant")
    return np.round(out / step) * step if step else out
