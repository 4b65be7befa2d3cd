"""The order scan (loop/diagnose/scan.py): harmonic orders proposed by their fit gain.

The motor: a DC motor on viscous friction (a linear circuit; a variant adds Coulomb friction),
driven forward for 0.15 s and then reversed, so that a ripple locked to its angle wanders in
phase and smears in any spectrum. Its "measured" records come from a hand-written scipy model
(not from circuitsim), checked against the netlist first.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.signal import lfilter

import circuitsim as cs
from circuitsim.loop import effects
from circuitsim.loop.diagnose import scan
from circuitsim.loop.diagnose.context import compile_raw, simulate_many
from circuitsim.loop.diagnose.decide import BIC_MARGIN
from circuitsim.loop.diagnose.engine import fit_declared
from circuitsim.loop.record import Record
from circuitsim.netlist import build

R, L, K, J, B = 1.0, 1e-3, 0.05, 2e-5, 2e-5  # [ohm, H, N*m/A, kg*m^2, N*m*s/rad]
W_COUL = 0.01  # [rad/s] the friction component's Coulomb smoothing: w_brk / 10
T = np.arange(3001) / 10e3  # [s] 10 kHz
NOISE = {"speed": 0.1, "i": 2e-3, "vL": 0.05}  # [rad/s, A, V]
ORDER = 7


def _drive(volts: float) -> list[tuple[float, float]]:
    return [(0.0, 0.0), (0.002, 0.0), (0.004, volts), (0.15, volts), (0.16, -volts),
            (0.3, -volts)]


def _netlist(volts: float = 12.0, tau_c: float = 0.0) -> str:
    friction = (f"  - {{name: Fr, type: friction, shaft: rotor, tau_c: {tau_c}, "
                f"tau_brk: {tau_c}, w_brk: {10 * W_COUL}}}\n") if tau_c else ""
    return f"""
title: a DC motor driven forward and reversed
parameters: {{R: {R} ohm, L: {L} H, k: {K} N*m/A, J: {J} kg*m^2, b: {B} N*m*s/rad}}
components:
  - {{name: V1, type: V, p: a, n: gnd, V: {{pwl: {[list(p) for p in _drive(volts)]}}}}}
  - {{name: Rw, type: R, p: a, n: b, R: R}}
  - {{name: Lw, type: L, p: b, n: c, L: L}}
  - {{name: M, type: emf, p: c, n: gnd, shaft: rotor, k_t: k}}
  - {{name: Jr, type: inertia, shaft: rotor, J: J}}
  - {{name: Bv, type: damper, shaft: rotor, b: b}}
{friction}probes:
  speed: rotor.w
  i: Lw.i
  vL: Lw.v
analysis: {{stop: 0.3, step: 50 us, rtol: 1e-9, atol: 1e-12}}
"""


def _reference(cogging: float, volts: float = 12.0, tau_c: float = 0.0, load: float = 0.0,
               phase: float = 0.4, times: np.ndarray = T) -> dict[str, np.ndarray]:
    """The motor in scipy at ``times`` [s]: a cogging torque ``cogging`` sin(7 phi + phase),
    Coulomb friction ``tau_c`` tanh(w / W_COUL) and a constant load ``load`` [N*m]."""
    tv, vv = np.array(_drive(volts)).T

    def rhs(t, y):
        i, w, phi = y
        v = np.interp(t, tv, vv)
        torque = K * i - B * w - tau_c * math.tanh(w / W_COUL) - load \
            + cogging * math.sin(ORDER * phi + phase)
        return [(v - R * i - K * w) / L, torque / J, w]

    sol = solve_ivp(rhs, (0.0, times[-1]), [0.0, 0.0, 0.0], method="LSODA", t_eval=times,
                    rtol=1e-11, atol=1e-12, max_step=2e-5)
    assert sol.success, sol.message
    i, w, _ = sol.y
    return {"i": i, "speed": w, "vL": np.interp(times, tv, vv) - R * i - K * w}


def _record(cogging: float, seed: int, ar: float = 0.0, probes=("speed", "i"),
            times: np.ndarray = T, **kw) -> Record:
    clean = _reference(cogging, times=times, **kw)
    rng = np.random.default_rng(seed)
    cols = {}
    for p in probes:
        e = rng.normal(0.0, NOISE[p], times.size)
        if ar:  # AR(1) noise of the same variance
            e = lfilter([math.sqrt(1 - ar * ar)], [1.0, -ar], e)
        cols[p] = clean[p] + e
    return Record(times.copy(), cols, f"scipy motor, cogging {cogging}, seed {seed}, {kw}")


def _jittered(seed: int) -> np.ndarray:
    """T with every sample but the first moved by up to 30 % of the interval, as a logger's
    timestamps are [s]."""
    step = float(T[1] - T[0])
    return T + np.random.default_rng(seed).uniform(-0.3, 0.3, T.size) * step * (T > 0)


@pytest.fixture(scope="module")
def nets(tmp_path_factory):
    """The netlists by (volts, tau_c)."""
    folder = tmp_path_factory.mktemp("scan")
    out = {}
    for i, key in enumerate([(12.0, 0.0), (12.0, 1e-2), (0.05, 0.0), (4.0, 0.0)]):
        (folder / f"m{i}.yaml").write_text(_netlist(*key))
        out[key] = cs.load(folder / f"m{i}.yaml")
    return out


def _fitted(net, record):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fit_declared(net, record, [], list(record.names), None, 1e-8, 4, None)


@pytest.mark.parametrize("key", [(12.0, 0.0), (12.0, 1e-2)])
def test_the_scipy_motor_is_the_netlist(nets, key):
    """The reference the records come from agrees with circuitsim's simulation of the
    netlist to 1e-6 of each probe's range, with and without Coulomb friction."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sim = cs.compile(nets[key]).simulate(t_eval=T, rtol=1e-11, atol=1e-12)
    ref = _reference(0.0, volts=key[0], tau_c=key[1])
    for p in NOISE:
        assert np.max(np.abs(sim[p] - ref[p])) < 1e-6 * np.ptp(ref[p]), p


def test_step_responses_convolved_are_the_exact_sensitivity_of_a_linear_circuit(nets):
    """On a linear circuit the response to an input is the step response convolved with the
    input's increments. The scan's columns of a cogging (a torque sin or cos of 7 phi) and of
    an EMF harmonic (a voltage w sin or cos of 7 phi) agree with the catalog patch's own
    finite difference within 2 % on every probe -- the inductor's voltage, which the input
    reaches directly (a feedthrough), included."""
    setup, state = _fitted(nets[12.0, 0.0], _record(0.0, seed=1, probes=tuple(NOISE)))
    sites = scan.sites_of(build(state.raw))
    assert [(s.kind, s.where, s.shaft) for s in sites] == [("torque", "rotor", "rotor"),
                                                           ("voltage", "M", "rotor")]
    base, kernels, onsets, _, _ = scan._step_responses(setup, state, sites)
    phi, w = (np.asarray(base[f"rotor.{x}"], float) for x in ("phi", "w"))
    for site, effect, target in ((sites[0], "cogging", "rotor"),
                                 (sites[1], "emf-harmonic", "M")):
        conv = scan._Convolver(kernels[site], onsets, T.size)
        cand = next(c for c in effects.candidates(build(state.raw), {"rotor": [ORDER]})
                    if c.effect == effect and c.target == target)
        model = compile_raw(cand.apply(state.raw))
        null = {**state.params, **{n: 0.0 for n in cand.free}}
        names = sorted(cand.free)  # _a multiplies sin, _b cos
        runs = simulate_many(setup, model, [null, *({**null, n: cand.steps[n]} for n in names)])
        for n, f, run in zip(names, (np.sin, np.cos), runs[1:], strict=True):
            u = f(ORDER * phi) * (w if site.kind == "voltage" else 1.0)
            approx = conv(scan._midpoints(u), u)
            for p in setup.probes:
                exact = (np.asarray(run[p]) - np.asarray(runs[0][p])) / cand.steps[n]
                exact = exact[onsets[0]:] / setup.weights[p]  # the scan's input starts there
                err = np.linalg.norm(approx[p][onsets[0]:] - exact) / np.linalg.norm(exact)
                assert err < 0.02, (effect, n, p, err)



def test_the_exact_scan_agrees_with_the_linearised_one_on_a_linear_circuit(nets, monkeypatch):
    """On a linear circuit the linearisation is exact: every order's exact promise (its sine
    and cosine run through the circuit itself, ``scan._Exact``) matches the convolved step
    responses' within 3 % (or 3 BIC units) where either is significant, order 7 is first in both,
    and the check of the best three agrees, so the linearised promises are the ones used."""
    setup, state = _fitted(nets[12.0, 0.0], _record(4e-4, seed=2))
    seen: list = []
    checked = scan._Exact.checked

    def spy(self, site, margin, promises):
        out = checked(self, site, margin, promises)
        seen.append((self, site, promises, out))
        return out

    monkeypatch.setattr(scan._Exact, "checked", spy)
    assert scan.orders_by_gain(setup, state, BIC_MARGIN)["rotor"][0] == ORDER
    exact, site, approx, used = next(x for x in seen if x[1].kind == "torque")
    assert used is approx  # the check agreed
    scanned = [k + 1 for k in range(approx.size) if np.isfinite(approx[k])]
    full = exact.promises(site, scanned, approx.size)
    assert int(np.argmax(full)) + 1 == ORDER and approx[ORDER - 1] > 100
    big = [k for k in scanned if max(approx[k - 1], full[k - 1]) > 2 * BIC_MARGIN]
    for k in big:
        assert full[k - 1] == pytest.approx(approx[k - 1], rel=0.03, abs=3.0), k


def test_the_linearised_scan_is_trusted_only_where_its_best_orders_hold():
    """scan._check on the best three orders (the linearised best first): within a factor 2
    and in the same order it agrees; an order the exact columns rank 10 % above the first,
    or one the linearisation underestimates by over 2, hides a better order ("under": all
    orders are then scored exactly); promises only too high are a leak ("over"); orders
    below the margin on both counts are not judged."""
    m = BIC_MARGIN
    approx = np.full(10, -np.inf)
    approx[[0, 5, 6]] = [300.0, 200.0, 150.0]  # orders 1, 6, 7
    top = [1, 6, 7]
    exact = approx.copy()
    assert scan._check(approx, exact * 1.4, top, m) == "agrees"
    assert scan._check(approx, exact * 0.6, top, m) == "agrees"
    exact[6] = 340.0  # order 7: 2.3 times its promise and above the first
    assert scan._check(approx, exact, top, m) == "under"
    exact = approx.copy()
    exact[5] = 340.0  # order 6: within 2 times, but 13 % above the first
    assert scan._check(approx, exact, top, m) == "under"
    assert scan._check(approx, np.where(np.isfinite(approx), -20.0, -np.inf), top, m) == "over"
    assert scan._check(approx, approx / 3.0, top, m) == "over"  # all three times too high
    quiet = np.where(np.isfinite(approx), 5.0, -np.inf)
    assert scan._check(quiet, quiet * -3.0, top, m) == "agrees"

def test_a_scan_that_singles_out_no_order_is_scored_exactly():
    """scan._contenders counts the local maxima above the margin that promise CONTENDER of
    the best; where there are more of them than the scan may propose (a rotor starting from
    rest: every order's ripple is first a torque growing with the angle), ``checked`` scores
    every order exactly even though its best three hold, and the exact best is proposed.
    A scan with one clear peak keeps its own promises and is checked on its best orders
    only."""
    m = BIC_MARGIN
    k = np.arange(1, 65)
    flat = 250.0 + 30.0 * np.cos(2.1 * k)  # many local maxima, all within 0.75 of the best
    assert scan._contenders(flat, m) > scan.MAX_PER_SITE
    sharp = np.where(k == 20, 300.0, 40.0 + 20.0 * np.cos(2.1 * k))
    assert scan._contenders(sharp, m) == 1
    assert scan._contenders(np.full(64, m / 2), m) == 0
    truth = flat * 0.9
    truth[19] = 400.0  # order 20, exactly

    class Exact(scan._Exact):
        def __init__(self, truth):
            self.truth, self.asked = truth, []
            self.setup = type("S", (), {"log": lambda self, text: None})()

        def promises(self, site, orders, kmax):
            self.asked.append(list(orders))
            out = np.full(kmax, -np.inf)
            out[np.asarray(orders) - 1] = self.truth[np.asarray(orders) - 1]
            return out

    site = scan.Site("torque", "rotor", "rotor")
    ex = Exact(truth)
    full = ex.checked(site, m, flat)
    assert len(ex.asked) == 2 and len(ex.asked[1]) == 64
    assert scan._peaks(full, m, set())[0] == 20
    ex = Exact(sharp * 1.2)  # the exact promises within 2 times, in the same order
    kept = ex.checked(site, m, sharp)
    assert len(ex.asked) == 1 and len(ex.asked[0]) == scan.CHECKED
    assert scan._peaks(kept, m, set())[0] == 20


@pytest.mark.parametrize(("tau_c", "start"), [(0.0, 0), (1e-2, 0), (0.0, 100)])
def test_the_scan_ranks_the_true_order_first_on_a_reversing_rotor(nets, tau_c, start):
    """A cogging of order 7 at about 20 sigma on a rotor that reverses -- on viscous
    friction, on a Coulomb friction that holds it at rest before the drive starts, and in a
    record that starts 10 ms after the simulation -- is the torque site's best order."""
    rec = _record(4e-4, seed=2, tau_c=tau_c)
    if start:
        rec = Record(rec.t[start:].copy(), {p: rec[p][start:].copy() for p in rec.names},
                     rec.path)
    setup, state = _fitted(nets[12.0, tau_c], rec)
    found = scan.orders_by_gain(setup, state, BIC_MARGIN)
    assert found.get("rotor", [None])[0] == ORDER, found


def test_the_line_of_that_cogging_is_below_what_a_spectrum_can_call_one(nets):
    """The same record on viscous friction: the residual's spectral analysis proposes no
    order (its line smears as the rotor reverses); the scan is what finds it."""
    from circuitsim.loop.diagnose.residual import _orders, analyse

    setup, state = _fitted(nets[12.0, 0.0], _record(4e-4, seed=2))
    assert _orders(analyse(state.model, setup.record, state.fit, setup.probes)) == {}


@pytest.mark.parametrize("ar", [0.0, 0.7])
def test_noise_alone_proposes_no_order(nets, ar):
    """Records of the motor itself with white or AR(1) noise, 4 seeds each: no order's
    gain pays the BIC margin."""
    for seed in range(10, 14):
        setup, state = _fitted(nets[12.0, 0.0], _record(0.0, seed=seed, ar=ar))
        assert scan.orders_by_gain(setup, state, BIC_MARGIN) == {}, (ar, seed)


@pytest.mark.parametrize(("volts", "turns"), [(0.05, (0.01, 1.0)), (4.0, (1.0, 3.0))])
def test_a_load_the_model_lacks_is_no_order(nets, volts, turns):
    """A constant load of 2 mN m the netlist lacks, on a shaft driven so gently that it
    never turns a whole turn (an order is a property of a turn: it is not scanned) and on
    one that turns one to three turns (what a constant input of a site explains is no
    order's): no order is proposed."""
    setup, state = _fitted(nets[volts, 0.0], _record(0.0, seed=5, volts=volts, load=2e-3))
    span = float(np.ptp(np.asarray(state.fit.sim["rotor.phi"]))) / (2 * math.pi)
    assert turns[0] < span < turns[1], span
    assert scan.orders_by_gain(setup, state, BIC_MARGIN) == {}


def test_a_record_sampled_unevenly_is_scanned_on_an_even_grid_and_says_so(nets):
    """Timestamps that jitter by up to 30 % of the interval (the motor simulated at those
    very times): the scan runs on an even grid of as many samples, says so, and still ranks
    the cogging's order first."""
    said = []
    setup, state = _fitted(nets[12.0, 0.0], _record(4e-4, seed=2, times=_jittered(0)))
    assert not setup.record.uniform
    setup = dataclasses.replace(setup, say=said.append)
    found = scan.orders_by_gain(setup, state, BIC_MARGIN)
    assert found.get("rotor", [None])[0] == ORDER, found
    assert said[0] == f"order scan on an even grid of {T.size} samples: the record's times " \
        "are uneven", said


def test_a_jittered_record_is_diagnosed_with_the_cogging_it_holds(nets):
    """The whole loop on such a record with half that cogging (about 10 sigma): the cogging
    is the one effect named, its sine and cosine amplitudes within 3 standard errors of the
    scipy motor's, 2e-4 N m at phase 0.4 (a sin(7 phi) + b cos(7 phi)). Without the scan on
    the even grid this record was "nothing significant"."""
    from circuitsim.loop.diagnose import diagnose

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        d = diagnose(nets[12.0, 0.0], _record(2e-4, seed=2, times=_jittered(0)), [],
                     probes=["speed", "i"])
    assert [(e.effect, e.target) for e in d.effects] == [("cogging", "rotor")], d.summary()
    e = d.effects[0]
    for name, truth in (("cogging_rotor_7_a", 2e-4 * math.cos(0.4)),
                        ("cogging_rotor_7_b", 2e-4 * math.sin(0.4))):
        assert abs(e.parameters[name] - truth) < 3 * e.stderr[name], (name, e.parameters)


@pytest.mark.parametrize("ar", [0.0, 0.7])
def test_noise_alone_on_jittered_times_proposes_no_order(nets, ar):
    """The interpolation onto the even grid colours the noise; the scan's whitening learns
    that colour from the interpolated residual: white or AR(1) noise on jittered times, 3
    seeds each, proposes no order."""
    for seed in range(20, 23):
        rec = _record(0.0, seed=seed, ar=ar, times=_jittered(seed))
        setup, state = _fitted(nets[12.0, 0.0], rec)
        assert scan.orders_by_gain(setup, state, BIC_MARGIN) == {}, (ar, seed)


@pytest.mark.parametrize(("size", "factor"), [(1e-4, 1.0), (1e-3, 1.0), (1e-9, 1e5), (1.0, 1e-4)])
def test_a_step_is_rescaled_into_the_linear_range_only_when_far_from_it(size, factor):
    """_rescale: a step whose largest response is 0.3 noise units RMS over n samples times
    ``size`` / 1e-4 is kept within a factor 100 of that, else brought back to it."""
    n = 1000
    g = {"p": [np.full(n, 0.3 / 1e-4), np.zeros(n)]}  # a response of 0.3 per sample at 1e-4
    assert scan._rescale(g, size, n) == pytest.approx(factor)


@pytest.mark.slow
def test_a_cogging_on_a_reversing_rotor_through_the_loop(nets):
    """The whole diagnosis names the cogging of order 7 and its amplitude within 10 %."""
    from circuitsim.loop.diagnose import diagnose

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        d = diagnose(nets[12.0, 0.0], _record(4e-4, seed=3), [], probes=["speed", "i"])
    assert [(a.effect, a.target, a.parameters.get("order")) for a in d.effects] == \
        [("cogging", "rotor", ORDER)], d.summary()
    p = d.effects[0].parameters
    amp = math.hypot(*(v for n, v in p.items() if n.endswith(("_a", "_b"))))
    assert amp == pytest.approx(4e-4, rel=0.1), p
