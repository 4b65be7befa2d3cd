"""Hand-written reference simulators for the diagnosis benchmark (scipy only: no circuitsim).

Three brushed DC drives, each with a set of optional physical effects written out by hand, so
that the records the benchmark feeds to ``circuitsim diagnose`` come from an independent
implementation of the physics, not from circuitsim's own patched netlists.

Motor A -- Kim & Kim 2024 base model (netlists/kim2024/base.yaml + motor.yaml):
    12 V ideal source across nodes a-gnd; varistor (Rv = 500 Mohm in series with Cv = 1.6 uF)
    across the same nodes; connector inductors 2 x 0.22 uH, Ra = 1.1 ohm, La = 0.87 mH in
    series with the back-EMF
        e = k_e w + e0 + (A8_slope w + A8_offset) sin(8 theta),
    k_e = 0.1017/(2 pi) V s/rad, e0 = 1.151e-4 V, A8_slope = 0.0168/(2 pi) V s/rad,
    A8_offset = 2.504e-5 V; torque k_t i with k_t = 0.14 N m/A (the paper's model: the
    harmonic makes no torque, ripple_torque: false); J = 4.57e-6 kg m^2, B = 2.95e-4 N m s/rad.
    Probes: i_total = supply current (loop current + varistor current), speed = w.
    The varistor branch carries 12 V / 500 Mohm = 24 nA decaying with Rv Cv = 800 s: it is
    included (it is in the netlist) but invisible at the noise levels used.

Motor B -- a small 6 V permanent-magnet motor of this benchmark's own design
(netlists/motor_b*.yaml): R = 2.5 ohm, L = 1.2 mH, k_e = k_t = k = 0.02, J = 4e-6 kg m^2,
b = 2e-6 N m s/rad, no declared ripple. Two drives: ``fast`` (a 6 V source from rest) and
``slow`` (a measured voltage command u(t) read from inputs/motor_b_aprbs.csv, linearly
interpolated as circuitsim's table source does, plus a declared 1 mN m load torque switched on
at 2.5 s). Probes: current (armature current) and speed.

Motor C -- a two-mass drive of this benchmark's own design (netlists/motor_c.yaml): motor B's
armature (R = 2.5 ohm, L = 1.2 mH, k = 0.02) and a rotor J1 = 4e-6 kg m^2 (viscous b1 = 2e-6
N m s/rad) drive a load inertia J2 = 12e-6 kg m^2 (viscous b2 = 1e-5 N m s/rad) through a
compliant coupling K (c = 0.75 N m/rad, d = 1.5e-4 N m s/rad): resonance 500 rad/s = 79.6 Hz,
damping ratio 0.05. Drive: the voltage command PWL_C with reversals, 0.6 s from rest.
Probes: current, speed (rotor) and load_speed (an encoder on the load). Its own ODE
(``simulate_c``), state [i, w1, w2, phi_rel, th2]; effects (``fx`` keys):
    backlash        total play [rad] of the coupling (Modelica's ElastoBacklash, as
                    circuitsim's ``backlash``): no torque while |phi_rel| < gap/2; in contact
                    c (phi_rel -+ gap/2) + d w_rel, clipped so the damping never pulls the sides
                    together. The contact events are located (solve_ivp events, the torque law
                    fixed per piece between events), max_step MAX_STEP_C
    Rser, Rs        series / source resistance [ohm]
    Fc_load, wc_load  Coulomb friction Fc tanh(w2/wc) on the load [N m], [rad/s]
    T_load          constant load torque against the load's positive direction [N m]
    hardening       kh [1/rad^2]: coupling torque c phi_rel (1 + kh phi_rel^2) + d w_rel
                                                                                   [outside]
    load_ripple_c   (order, T [N m], phase): the load receives T sin(order th2 + phase), a
                    non-integer order is outside the catalog                       [outside]

Effects of motors A and B (``fx`` dict, all optional; names are physical, SI units):
    Rser            series resistance added to the armature [ohm]
    Rs              internal (source) resistance of the supply [ohm]
    Vb, Vb_eps      brush drop Vb*tanh(i/Vb_eps) opposing the current [V], [A]
    Fc, wc          Coulomb friction Fc*tanh(w/wc) [N m], [rad/s]
    Bx              extra viscous friction [N m s/rad]
    cogging         list of (order, T [N m], phase): the shaft receives T sin(order th + phase)
    emf             list of (order, slope [V s/rad], phase): extra EMF slope*w*sin(order th +
                    phase) in series with the armature (voltage only, like the catalog patch)
    sat             (Ipar [A], ratio): La(i) = La*(ratio + (1-ratio)/(1+(i/Ipar)^2)) (the
                    differential inductance of circuitsim's Lsat / Modelica SaturatingInductor)
    drift           ("linear", alpha [1/s]): Ra(t) = Ra (1 + alpha t), or
                    ("heating", rise [1], tau [s]): Ra(t) = Ra (1 + rise (1 - exp(-t/tau)))
    stribeck        (Fs, Fc, ws, wc): (Fc + (Fs-Fc) exp(-(w/ws)^2)) tanh(w/wc) against w
    unbalance       (T [N m] = m g r, phase): the shaft receives T sin(th + phase)
    load_ripple     list of (order, T, phase): a load torque locked to the angle (the shaft
                    receives -T sin(order th + phase))
    belt            (order, T, phase): a non-integer shaft order (belt / pulley ratio) load
                    torque; the shaft receives T sin(order th + phase)            [outside]
    supply_ripple   (amplitude [V], frequency [Hz], shape "sine"|"rectified"): added to the
                    supply voltage, locked to time, not to the angle             [outside]
    chopper         (amplitude [V], frequency [Hz], sharpness): a smoothed square ripple
                    amplitude*tanh(sin(2 pi f t)/sharpness) on the supply          [outside]
    torsion         (J2, ks, cs): a second inertia J2 on a compliant shaft (spring ks
                    [N m/rad], damping cs [N m s/rad]); the probe measures the motor side
                                                                                   [outside]
    Ls              supply inductance [H] between the source and the rest of the circuit
                    (motors A, B, C): the source's terminals see u - Ls di_supply/dt. On
                    motor A the varistor branch sits behind it; its current (tens of nA)
                    changes by under a nA through it and is taken as part of the loop's
    params          dict of declared parameters to override (declared-parameter error)
Sensor effects (applied to the simulated probes, before noise; per probe):
    sensor          {probe: {"gain": g, "offset": c [SI], "delay": d [s]}}
"""

from __future__ import annotations

import math
from itertools import pairwise
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
TWO_PI = 2 * math.pi

MOTOR_A = {
    "Vin": 12.0, "Ra": 1.1, "La": 0.87e-3, "L_conn": 0.22e-6, "Rv": 500e6, "Cv": 1.6e-6,
    "J": 4.57e-6, "B": 2.95e-4, "k_t": 0.14, "k_e": 0.1017 / TWO_PI, "e0": 1.151e-4,
    "A8_slope": 0.0168 / TWO_PI, "A8_offset": 2.504e-5,
}
MOTOR_B = {
    "Vs": 6.0, "R": 2.5, "L": 1.2e-3, "k": 0.02, "J": 4e-6, "b": 2e-6, "T_load": 1e-3,
    "t_load": 2.5,
}
PROBES = {"A": ("i_total", "speed"), "B": ("current", "speed"),
          "C": ("current", "speed", "load_speed")}
APRBS_FILE = HERE / "netlists" / "inputs" / "motor_b_aprbs.csv"


# ------------------------------------------------------------------------------ inputs

def aprbs_levels(seed: int = 7, stop: float = 5.0, ramp: float = 2e-3):
    """The slow drive of motor B: an amplitude-modulated pseudo-random sequence of voltage
    levels in [0.8, 6] V held 0.15-0.45 s, linear 2 ms ramps between them, then 0 V for the
    last 0.4 s (the motor coasts and the declared load drives it slowly backwards).
    Returns breakpoints (t, u) for a piecewise-linear table."""
    rng = np.random.default_rng(seed)
    t, pts = 0.0, [(0.0, 0.0)]
    level = 0.0
    while t < stop - 0.4:
        new = float(np.round(rng.uniform(0.8, 6.0), 3))
        hold = float(np.round(rng.uniform(0.15, 0.45), 3))
        pts.append((t + ramp, new))
        t = min(t + hold, stop - 0.4)
        pts.append((t, new))
        level = new
    pts.append((t + ramp, 0.0))
    pts.append((stop, 0.0))
    del level
    tt = np.array([p[0] for p in pts])
    uu = np.array([p[1] for p in pts])
    return tt, uu


def write_aprbs(path: Path = APRBS_FILE) -> None:
    tt, uu = aprbs_levels()
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("time,u\n")
        fh.writelines(f"{a:.6f},{b:.6f}\n" for a, b in zip(tt, uu, strict=True))


def read_aprbs(path: Path = APRBS_FILE):
    arr = np.loadtxt(path, delimiter=",", skiprows=1)
    return arr[:, 0], arr[:, 1]


# ------------------------------------------------------------------------------ models

def _emf_harm(fx, w, th):
    out = 0.0
    for order, slope, ph in fx.get("emf", ()):
        out += slope * w * math.sin(order * th + ph)
    return out


def _mech_extra(fx, t, w, th):
    """Torque the effects put on the rotor shaft [N m] (positive accelerates)."""
    tq = 0.0
    if "Fc" in fx:
        tq -= fx["Fc"] * math.tanh(w / fx.get("wc", 0.05))
    if "Bx" in fx:
        tq -= fx["Bx"] * w
    for order, amp, ph in fx.get("cogging", ()):
        tq += amp * math.sin(order * th + ph)
    if "stribeck" in fx:
        fs, fc, ws, wc = fx["stribeck"]
        tq -= (fc + (fs - fc) * math.exp(-(w / ws) ** 2)) * math.tanh(w / wc)
    if "unbalance" in fx:
        amp, ph = fx["unbalance"]
        tq += amp * math.sin(th + ph)
    for order, amp, ph in fx.get("load_ripple", ()):
        tq -= amp * math.sin(order * th + ph)
    if "belt" in fx:
        order, amp, ph = fx["belt"]
        tq += amp * math.sin(order * th + ph)
    return tq


def _supply_extra(fx, t):
    v = 0.0
    if "supply_ripple" in fx:
        amp, f, shape = fx["supply_ripple"]
        if shape == "rectified":  # |sin| of the 50 Hz mains, mean removed: a 100 Hz ripple
            v += amp * (abs(math.sin(math.pi * f * t)) - 2 / math.pi)
        else:
            v += amp * math.sin(TWO_PI * f * t)
    if "chopper" in fx:
        amp, f, sharp = fx["chopper"]
        v += amp * math.tanh(math.sin(TWO_PI * f * t) / sharp)
    return v


def _resistance(r0, fx, t):
    d = fx.get("drift")
    if d is None:
        return r0
    if d[0] == "linear":
        return r0 * (1 + d[1] * t)
    return r0 * (1 + d[1] * (1 - math.exp(-t / d[2])))


def _inductance(l0, fx, i):
    s = fx.get("sat")
    if s is None:
        return l0
    ipar, ratio = s
    return l0 * (ratio + (1 - ratio) / (1 + (i / ipar) ** 2))


def _rhs_factory(motor: str, fx: dict, u_fn):
    """State x = [i, w, th, vc, w2, delta]: armature current, rotor speed and angle,
    varistor capacitor voltage (motor A), second-inertia speed and shaft twist (torsion)."""
    if motor == "A":
        p = {**MOTOR_A, **fx.get("params", {})}
        ra, la, lc = p["Ra"], p["La"], p["L_conn"]
        kt, ke, e0 = p["k_t"], p["k_e"], p["e0"]
        a8s, a8o = p["A8_slope"], p["A8_offset"]
        J, B = p["J"], p["B"]
        rv, cv = p["Rv"], p["Cv"]
    else:
        p = {**MOTOR_B, **fx.get("params", {})}
        ra, la, lc = p["R"], p["L"], 0.0
        kt = ke = p["k"]
        e0 = a8s = a8o = 0.0
        J, B = p["J"], p["b"]
        rv = cv = None
    rs, rser, ls = fx.get("Rs", 0.0), fx.get("Rser", 0.0), fx.get("Ls", 0.0)
    vb, vb_eps = fx.get("Vb", 0.0), fx.get("Vb_eps", 5e-3)
    tors = fx.get("torsion")
    load = (lambda t: p["T_load"] if t >= p["t_load"] else 0.0) if motor == "B" and \
        fx.get("load", False) else (lambda t: 0.0)

    def rhs(t, x):
        i, w, th, vc, w2, dl = x
        v = u_fn(t) + _supply_extra(fx, t)
        e = ke * w + e0 + (a8s * w + a8o) * math.sin(8 * th) + _emf_harm(fx, w, th)
        drop = (rs + _resistance(ra, fx, t) + rser) * i + vb * math.tanh(i / vb_eps)
        di = (v - drop - e) / (_inductance(la, fx, i) + 2 * lc + ls)
        tq = kt * i - B * w + _mech_extra(fx, t, w, th) - load(t)
        dw2 = ddl = 0.0
        if tors is not None:
            j2, ks, cs = tors
            tshaft = ks * dl + cs * (w - w2)
            tq -= tshaft
            dw2 = tshaft / j2
            ddl = w - w2
        dvc = 0.0 if rv is None else (v - ls * di - vc) / (rv * cv)
        return [di, tq / J, w, dvc, dw2, ddl]

    def probes(t, x):
        i, w = x[0], x[1]
        if motor == "A":
            v = np.array([u_fn(tt) + _supply_extra(fx, tt) for tt in t])
            if ls:  # the varistor sees the source less the supply inductance's drop
                v = v - ls * np.array([rhs(tt, x[:, k])[0] for k, tt in enumerate(t)])
            i_var = (v - x[3]) / rv
            return {"i_total": i + i_var, "speed": w}
        return {"current": i, "speed": w}

    return rhs, probes


def simulate(motor: str, regime: str, t: np.ndarray, fx: dict | None = None,
             rtol: float = 1e-10, atol: float = 1e-12, method: str = "LSODA") -> dict:
    """Noise-free probes of ``motor`` ('A', 'B' or 'C') at the sample times ``t`` (from rest at
    t = 0), with the effects ``fx`` (see the module docstring). Returns {probe: array}; for
    motor B slow also the input column 'u'."""
    if motor == "C":
        return simulate_c(t, fx, rtol=rtol, atol=atol)
    fx = dict(fx or {})
    if motor == "B" and regime == "slow":
        tb, ub = read_aprbs()
        fx.setdefault("load", True)

        def u_fn(tt):
            return float(np.interp(tt, tb, ub))
        breaks = [float(b) for b in tb if 0 < b < t[-1]]
    else:
        v0 = MOTOR_A["Vin"] if motor == "A" else MOTOR_B["Vs"]
        v0 = fx.get("params", {}).get("Vin" if motor == "A" else "Vs", v0)

        def u_fn(tt):
            return v0
        breaks = []
    if motor == "B" and fx.get("load"):
        breaks.append(MOTOR_B["t_load"])
    # a delayed probe is evaluated at t - d as well
    sensor = fx.get("sensor", {})
    extra = [t - s["delay"] for s in sensor.values() if s.get("delay")]
    times = np.unique(np.concatenate([t, *[np.clip(e, 0, None) for e in extra]]))
    rhs, probe_fn = _rhs_factory(motor, fx, u_fn)
    # the fastest time scale: ripple, chopper, torsion
    fmax = 200.0
    if motor == "A":
        fmax = max(fmax, 8 * 110.0)
    if "chopper" in fx:
        fmax = max(fmax, 8 * fx["chopper"][1])
    if "supply_ripple" in fx:
        fmax = max(fmax, 4 * fx["supply_ripple"][1])
    for order, *_ in [*fx.get("cogging", ()), *fx.get("emf", ()), *fx.get("load_ripple", ())]:
        fmax = max(fmax, order * (110.0 if motor == "A" else 50.0))
    if "torsion" in fx:
        j2, ks, _ = fx["torsion"]
        jm = MOTOR_A["J"] if motor == "A" else MOTOR_B["J"]
        fmax = max(fmax, math.sqrt(ks * (1 / jm + 1 / j2)) / TWO_PI)
    max_step = 1 / (40 * fmax)
    edges = [0.0, *sorted(b for b in set(breaks) if 0 < b < times[-1]), float(times[-1])]
    x0 = np.zeros(6)
    if motor == "A":
        x0[3] = 0.0  # capacitor uncharged, as circuitsim starts from rest
    out = np.empty((6, times.size))
    for a, b in pairwise(edges):
        sel = (times >= a) & ((times < b) | (b == edges[-1]))
        sol = solve_ivp(rhs, (a, b), x0, method=method, rtol=rtol, atol=atol,
                        max_step=max_step, dense_output=True)
        if not sol.success:
            raise RuntimeError(f"solve_ivp failed on [{a}, {b}]: {sol.message}")
        if sel.any():
            out[:, sel] = sol.sol(times[sel])
        x0 = sol.y[:, -1]
    # the varistor branch is a linear first-order circuit fed by the source: with the source
    # voltage known, its current is (v - vc)/Rv
    full = probe_fn(times, out)
    res = {}
    for name, y in full.items():
        s = sensor.get(name, {})
        d = s.get("delay", 0.0)
        if d:
            y = np.interp(np.clip(t - d, 0, None), times, y)
        else:
            y = np.interp(t, times, y)
        res[name] = s.get("gain", 1.0) * y + s.get("offset", 0.0)
    if motor == "B" and regime == "slow":
        res["u"] = np.array([u_fn(tt) for tt in t])
    return res


# ------------------------------------------------------------------------------- noise

def white(rng, n, sigma):
    return rng.normal(0.0, sigma, n)


def ar1(rng, n, sigma, phi):
    """AR(1) noise with marginal standard deviation ``sigma``."""
    e = rng.normal(0.0, sigma * math.sqrt(1 - phi**2), n)
    out = np.empty(n)
    out[0] = rng.normal(0.0, sigma)
    for k in range(1, n):
        out[k] = phi * out[k - 1] + e[k]
    return out


def pink(rng, n, sigma):
    """1/f ('pink') noise: white noise shaped by 1/sqrt(f) in the frequency domain, zero
    mean, scaled to standard deviation ``sigma``."""
    spec = np.fft.rfft(rng.normal(0.0, 1.0, n))
    f = np.arange(spec.size, dtype=float)
    f[0] = 1.0
    spec /= np.sqrt(f)
    spec[0] = 0.0
    x = np.fft.irfft(spec, n)
    return sigma * x / np.std(x)


def quantise(y, step):
    return np.round(y / step) * step


def add_noise(rng, y: np.ndarray, spec: dict) -> np.ndarray:
    """spec: {"white": sigma, "ar1": [sigma, phi], "pink": sigma, "quant": step}."""
    out = y.copy()
    if spec.get("white"):
        out = out + white(rng, y.size, spec["white"])
    if spec.get("ar1"):
        out = out + ar1(rng, y.size, *spec["ar1"])
    if spec.get("pink"):
        out = out + pink(rng, y.size, spec["pink"])
    if spec.get("quant"):
        out = quantise(out, spec["quant"])
    return out


# ------------------------------------------------------------------- motor C (two-mass)

MOTOR_C = {
    "R": 2.5, "L": 1.2e-3, "k": 0.02, "J1": 4e-6, "b1": 2e-6, "c": 0.75, "d": 1.5e-4,
    "J2": 12e-6, "b2": 1e-5,
}
# the voltage command of netlists/motor_c.yaml: (t [s], V [V]) breakpoints, linear between
PWL_C = ((0.0, 0.0), (0.001, 4.0), (0.12, 4.0), (0.121, -4.0), (0.24, -4.0), (0.241, 2.0),
         (0.33, 2.0), (0.331, 0.0), (0.4, 0.0), (0.401, -3.0), (0.5, -3.0), (0.501, 3.0),
         (0.6, 3.0))
MAX_STEP_C = 5e-5  # [s] half a sample at 10 kHz; 1/250 of the 79.6 Hz coupling period


def _coupling_c(p, fx):
    """The coupling's torque law tau(phi_rel [rad], w_rel [rad/s], mode) [N m] and its half
    play h [rad]. mode 0: in the gap (or no play), +1 / -1: in contact on that side. The
    torque decelerates the rotor and drives the load."""
    c, d = p["c"], p["d"]
    h = fx.get("backlash", 0.0) / 2
    kh = fx.get("hardening", 0.0)

    def tau(phi, w, mode):
        if h == 0.0:
            return c * phi * (1 + kh * phi * phi) + d * w
        if mode == 0:
            return 0.0
        push = c * (phi - mode * h) + d * w
        # in contact the damper may slow the approach but never glue the sides together
        return max(push, 0.0) if mode > 0 else min(push, 0.0)
    return tau, h


def _rhs_c(fx, u_fn):
    """Right-hand side of motor C for a fixed contact mode. State x = [i, w1, w2, phi_rel,
    th2]: armature current [A], rotor and load speeds [rad/s], coupling twist th1 - th2 [rad],
    load angle [rad]."""
    p = {**MOTOR_C, **fx.get("params", {})}
    tau, h = _coupling_c(p, fx)
    rloop = p["R"] + fx.get("Rser", 0.0) + fx.get("Rs", 0.0)
    fc2, wc2 = fx.get("Fc_load", 0.0), fx.get("wc_load", 0.05)
    t_load = fx.get("T_load", 0.0)
    ripple = fx.get("load_ripple_c")  # (order [1], T [N m], phase [rad]) of the load angle

    def rhs(t, x, mode):
        i, w1, w2, phi, th2 = x
        ts = tau(phi, w1 - w2, mode)
        di = (u_fn(t) - rloop * i - p["k"] * w1) / (p["L"] + fx.get("Ls", 0.0))
        dw1 = (p["k"] * i - p["b1"] * w1 - ts) / p["J1"]
        tl = ts - p["b2"] * w2 - fc2 * math.tanh(w2 / wc2) - t_load
        if ripple is not None:
            tl += ripple[1] * math.sin(ripple[0] * th2 + ripple[2])
        return [di, dw1, tl / p["J2"], w1 - w2, w2]
    return rhs, h


def _segment_c(rhs, h, a, b, x0, mode, rtol, atol):
    """Integrate motor C over [a, b] from x0, switching the contact mode at the located
    events (the twist reaching +-h). Returns the list of (t0, t1, dense solution), the final
    state and mode."""
    pieces = []
    while True:
        if h == 0.0:
            events = []
        elif mode == 0:  # in the gap: reaching either side
            events = [lambda t, x, m: x[3] - h, lambda t, x, m: x[3] + h]
            events[0].direction, events[1].direction = 1, -1
        else:  # in contact on side `mode`: leaving it
            events = [lambda t, x, m: x[3] - m * h]
            events[0].direction = -mode
        for ev in events:
            ev.terminal = True
        sol = solve_ivp(rhs, (a, b), x0, method="LSODA", rtol=rtol, atol=atol, args=(mode,),
                        max_step=MAX_STEP_C, dense_output=True, events=events or None)
        if not sol.success:
            raise RuntimeError(f"solve_ivp failed on [{a}, {b}]: {sol.message}")
        pieces.append((a, sol.t[-1], sol.sol))
        x0 = sol.y[:, -1].copy()
        if sol.status != 1:
            return pieces, x0, mode
        a = sol.t[-1]
        if mode == 0:  # at a side: contact if still closing, else it grazes the side
            side = 1 if x0[3] > 0 else -1
            x0[3] = side * h
            mode = side if side * (x0[1] - x0[2]) > 0 else 0
        else:
            x0[3] = mode * h
            mode = 0


def simulate_c(t: np.ndarray, fx: dict | None = None, rtol: float = 1e-10,
               atol: float = 1e-12) -> dict:
    """Noise-free probes of motor C (netlists/motor_c.yaml) at the sample times ``t`` [s],
    from rest, with the effects ``fx`` (module docstring). The integration is split at the
    command's breakpoints and, with a backlash, at every contact event (located by
    solve_ivp's event search, the torque law fixed per piece). Returns {probe: array}."""
    fx = dict(fx or {})
    tb = np.array([q[0] for q in PWL_C])
    ub = np.array([q[1] for q in PWL_C])

    def u_fn(tt):
        return float(np.interp(tt, tb, ub))
    rhs, h = _rhs_c(fx, u_fn)
    edges = [0.0, *[float(b) for b in tb if 0 < b < t[-1]], float(t[-1])]
    x0, mode = np.zeros(5), 0
    pieces = []
    for a, b in pairwise(edges):
        got, x0, mode = _segment_c(rhs, h, a, b, x0, mode, rtol, atol)
        pieces.extend(got)
    out = np.empty((5, t.size))
    for a, b, sol in pieces:
        sel = (t >= a) & (t <= b)
        if sel.any():
            out[:, sel] = sol(t[sel])
    res = {"current": out[0], "speed": out[1], "load_speed": out[2]}
    for name, s in fx.get("sensor", {}).items():
        res[name] = s.get("gain", 1.0) * res[name] + s.get("offset", 0.0)
    return res
