"""Every catalog effect through the whole loop, on two motors (issue #13, item 2).

Records are made from the declared netlist plus the hidden patch, simulated finely, resampled,
with white noise and ADC steps; the diagnosis must name the effect (or an equivalent it says
it cannot tell apart) and recover its parameters. Motor 1: the DC motor example (10 kHz,
0.3 s). Motor 2: the Kim & Kim base motor with its declared 8th-order EMF ripple (20 kHz,
0.25 s). Slow: each record costs a full diagnosis; `.ci/run` runs them.
"""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest

import circuitsim as cs
from circuitsim.loop import effects
from circuitsim.loop.diagnose import diagnose
from circuitsim.loop.record import Record
from circuitsim.netlist import build

from conftest import NETLISTS

pytestmark = pytest.mark.slow

MOTORS = {
    "dc": {"netlist": NETLISTS / "examples" / "dc_motor.yaml", "stop": 0.3, "rate": 10e3,
           "noise": {"speed": 0.1, "i": 1e-3}, "lsb": {"speed": 0.05, "i": 5e-4}},
    "kim": {"netlist": NETLISTS / "kim2024" / "base.yaml", "stop": 0.25, "rate": 20e3,
            "noise": {"speed": 0.2, "i_total": 5e-3}, "lsb": {"speed": 0.05, "i_total": 1e-3}},
    # a slow motor driven by a measured-like voltage sequence that stops at the end: it
    # passes through low speeds, where a breakaway peak acts
    "b": {"netlist": NETLISTS.parent / "benchmarks" / "diagnosis" / "netlists" / "motor_b.yaml",
          "stop": 5.0, "rate": 1e3, "noise": {"speed": 0.1, "current": 3e-3},
          "lsb": {"speed": 0.02, "current": 1e-3}},
    # a motor driving a load through a flexible coupling on a 10 Hz sine: the torque through
    # the coupling reverses, where a play shows; only the motor side is measured
    "tm": {"netlist": NETLISTS / "examples" / "two_mass_motor.yaml", "stop": 0.2,
           "rate": 10e3, "noise": {"speed": 0.1, "i": 2e-3}, "lsb": {"speed": 0.05, "i": 1e-3}},
    # a 24 V gearmotor whose current is read on a 20 mOhm shunt in series with the 1.1 ohm
    # winding (the benchmark's motor D, fast regime)
    "d": {"netlist": NETLISTS.parent / "benchmarks" / "diagnosis" / "netlists" / "motor_d.yaml",
          "stop": 0.4, "rate": 10e3, "noise": {"speed": 0.2, "current": 1e-2},
          "lsb": {"speed": 0.05, "current": 5e-3}},
    # the same motor on its logged 6 s duty command with reversals (the slow regime)
    "d-slow": {"netlist": NETLISTS.parent / "benchmarks" / "diagnosis" / "netlists" /
               "motor_d_slow.yaml", "stop": 6.0, "rate": 1e3,
               "noise": {"speed": 0.2, "current": 1e-2, "load_speed": 0.02},
               "lsb": {"speed": 0.05, "current": 5e-3, "load_speed": 0.01}},
    # a servo swinging a robot arm through a 100:1 harmonic drive (the benchmark's motor J,
    # slow regime): the arm turns through 4.7 rad in all, never a whole turn
    "j-slow": {"netlist": NETLISTS.parent / "benchmarks" / "diagnosis" / "netlists" /
               "motor_j_slow.yaml", "stop": 5.0, "rate": 1e3,
               "noise": {"speed": 0.2, "current": 2e-2, "load_speed": 5e-3},
               "lsb": {"speed": 0.05, "current": 5e-3, "load_speed": 1e-3}},
    # a barrier gate (the benchmark's motor AE): a 300:1 worm gearbox and a compliant crank
    # drive K lift a 3.5 m boom against its weight; fast (a 0.5 s command at 10 kHz) and
    # slow (its 8 s logged command at 200 Hz, the boom read too)
    "ae": {"netlist": NETLISTS.parent / "benchmarks" / "diagnosis" / "netlists" /
           "motor_ae_fast.yaml", "stop": 0.5, "rate": 10e3,
           "noise": {"current": 0.05, "speed": 0.5}, "lsb": {"current": 0.01, "speed": 0.1}},
    "ae-slow": {"netlist": NETLISTS.parent / "benchmarks" / "diagnosis" / "netlists" /
                "motor_ae_slow.yaml", "stop": 8.0, "rate": 200.0,
                "noise": {"current": 0.03, "speed": 0.4, "load_speed": 0.01},
                "lsb": {"current": 0.01, "speed": 0.1, "load_speed": 2e-3}},
    # a parking-brake caliper motor (the benchmark's motor AG, slow regime): short applies,
    # a re-clamp and a release over 6 s, the winding seen only while they last
    "ag-slow": {"netlist": NETLISTS.parent / "benchmarks" / "diagnosis" / "netlists" /
                "motor_ag_slow.yaml", "stop": 6.0, "rate": 200.0,
                "noise": {"current": 0.03, "speed": 0.8, "load_speed": 0.01},
                "lsb": {"current": 0.01, "speed": 0.1, "load_speed": 2e-3}},
}


def _candidate(net, effect, target, order, probes, shaped=False):
    """The catalog's candidate; ``shaped``: one with a shape parameter where the effect has
    both kinds (a warm-up rather than a straight drift), at its first start."""
    orders = {n: [order] for n in ("rotor", target)} if order else None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        units = cs.compile(net).meta["units"]
    found = [c for c in effects.candidates(net, orders, {p: units[p] for p in probes}, 1.0)
             if c.effect == effect and c.target == target and
             (order is None or c.fixed.get("order") == order)]
    return min(found, key=lambda c: bool(c.shape) != shaped)  # the first of the kind asked


def make_record(motor: str, patches, seed: int = 0, shaped: bool = False) -> Record:
    m = MOTORS[motor]
    net = cs.load(m["netlist"])
    probes = list(m["noise"])
    raw, values = net.raw, {}
    for effect, target, order, vals in patches:
        cand = _candidate(build(raw), effect, target, order, probes, shaped)
        raw = cand.apply(raw)
        values.update(dict(zip(cand.free, vals, strict=True)))
    return Record(*_sampled(m, raw, seed, values), f"{motor} + {patches}")


def _fine_run(m: dict, raw, values: dict | None = None):
    """(t, fine, res): the record's times at ``m``'s rate, a grid five times finer, and the
    run of ``raw`` on it at tight tolerances."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(build(raw))
    t = np.arange(round(m["stop"] * m["rate"]) + 1) / m["rate"]
    fine = np.linspace(0.0, m["stop"], 5 * (t.size - 1) + 1)
    res = model.simulate(stop=m["stop"], t_eval=fine, params=values or {}, rtol=1e-10,
                         atol=1e-12)
    assert res.success, res.message
    return t, fine, res


def _sampled(m: dict, raw, seed: int, values: dict | None = None):
    """(t, columns): ``raw`` run finely, resampled at ``m``'s rate, with its white noise and
    ADC steps."""
    t, fine, res = _fine_run(m, raw, values)
    rng = np.random.default_rng(seed)
    return t, {p: np.round((np.interp(t, fine, res[p]) + rng.normal(0.0, s, t.size)) /
                           m["lsb"][p]) * m["lsb"][p] for p, s in m["noise"].items()}


# effect, target, order, true values, relative tolerance on the parameters
DC = [
    ("source-resistance", "V1", None, [0.3], 0.1),
    ("force-offset", "rotor", None, [-4e-4], 0.1),
    ("inductor-saturation", "Lw", None, [0.2, 0.3], 0.3),
    ("unbalance", "rotor", 1, [2e-3, 0.0], 0.1),
    ("sensor-gain", "speed", None, [0.03], 0.1),
    ("sensor-offset", "i", None, [0.01], 0.1),
    ("sensor-delay", "i", None, [2e-4], 0.1),
]
KIM = [
    ("series-resistance", "La", None, [0.05], 0.1),
    ("coulomb-friction", "rotor", None, [2e-3], 0.1),
    ("viscous-friction", "rotor", None, [5e-5], 0.15),
    ("cogging", "rotor", 6, [2e-3, 0.0], 0.1),
    ("emf-harmonic", "M", 16, [5e-4, 0.0], 0.1),
    ("sensor-offset", "i_total", None, [0.05], 0.1),
    ("sensor-delay", "i_total", None, [1e-4], 0.1),
]
# a cause the record can carry under another name: (effect, target) pairs it may report
# (in the Kim circuit every element but the varistor is in one series loop: a resistance in
# series with any of them is the same circuit)
EQUIVALENT = {("series-resistance", "La"): {("series-resistance", n) for n in
                                            ("Ra", "Lc1", "Lc2", "M")} |
              {("source-resistance", "Vin")},
              ("coulomb-friction", "rotor"): {("force-offset", "rotor")},
              ("force-offset", "rotor"): {("coulomb-friction", "rotor")},
              ("source-resistance", "V1"): {("series-resistance", "Rw"),
                                           ("series-resistance", "Lw"),
                                           ("series-resistance", "M")}}


def _check(d, effect, target, order, vals, tol):
    found = [(a.effect, a.target) for a in d.effects]
    allowed = {(effect, target), *EQUIVALENT.get((effect, target), set())}
    assert len(d.effects) == 1 and found[0] in allowed, d.summary()
    a = d.effects[0]
    if found[0] != (effect, target):  # an equivalent: the report must say it cannot tell
        assert d.indistinct, (d.summary(), d.indistinct)
        return
    if order:
        assert a.parameters["order"] == order
        amp = np.hypot(*[v for k, v in a.parameters.items() if k != "order"])
        assert amp == pytest.approx(np.hypot(*vals), rel=tol), d.summary()
    else:
        got = [v for k, v in a.parameters.items() if k != "order"]
        assert got[0] == pytest.approx(vals[0], rel=tol), d.summary()


@pytest.mark.parametrize("case", DC, ids=[c[0] for c in DC])
def test_dc_motor_effect_through_the_loop(case):
    effect, target, order, vals, tol = case
    rec = make_record("dc", [(effect, target, order, vals)], seed=11)
    d = diagnose(cs.load(MOTORS["dc"]["netlist"]), rec)
    _check(d, effect, target, order, vals, tol)
    assert d.error_after < 0.5 * d.error_before


@pytest.mark.parametrize("case", KIM, ids=[c[0] for c in KIM])
def test_kim_motor_effect_through_the_loop(case):
    effect, target, order, vals, tol = case
    rec = make_record("kim", [(effect, target, order, vals)], seed=12)
    d = diagnose(cs.load(MOTORS["kim"]["netlist"]), rec)
    _check(d, effect, target, order, vals, tol)


def test_resistance_warming_up_through_the_loop():
    """A winding resistance settling 10 % higher with a 1 s time constant (10 %/s at the
    start, within what copper allows; a straight drift cannot follow it) on the slow motor's
    5 s record: named as a drift of Ra, its rise and time constant recovered."""
    rec = make_record("b", [("resistance-drift", "Ra", None, [0.1, 1.0])], seed=13,
                      shaped=True)
    d = diagnose(cs.load(MOTORS["b"]["netlist"]), rec)
    assert [(a.effect, a.target) for a in d.effects] == [("resistance-drift", "Ra")], \
        d.summary()
    got = d.effects[0].parameters
    rise = next(v for k, v in got.items() if k.endswith("_rise"))
    tau = next(v for k, v in got.items() if k.endswith("_tau"))
    assert rise == pytest.approx(0.1, rel=0.05), d.summary()
    assert tau == pytest.approx(1.0, rel=0.1), d.summary()


def test_a_warm_up_is_named_on_the_winding_not_on_the_shunt_in_series_with_it():
    """The winding (1.1 ohm) warming up 10 % with tau = 1 s: a 20 mOhm shunt in series
    carries the same current, and its own "warm-up" would fit alike with a rise of 550 %
    (beyond what copper allows, too). The element that changes least is named, the shunt
    as the same circuit."""
    rec = make_record("d-slow", [("resistance-drift", "Ra", None, [0.1, 1.0])], seed=21,
                      shaped=True)
    d = diagnose(cs.load(MOTORS["d-slow"]["netlist"]), rec)
    assert [(a.effect, a.target) for a in d.effects] == [("resistance-drift", "Ra")], \
        d.summary()
    got = d.effects[0].parameters
    assert next(v for k, v in got.items() if k.endswith("_rise")) == \
        pytest.approx(0.1, rel=0.05), d.summary()
    assert "Rsh" in d.summary(), d.summary()


def test_a_cooling_winding_beside_an_unbalance_through_the_loop():
    """A hot winding cooling 12 % with tau = 4 s over a 6 s record, beside a once-per-turn
    torque: without the unbalance the warm-up runs to its bound and a straight drift wins;
    once the unbalance is in, the straight line's law is bent by the square of time, and its
    shaped form (the warm-up) must be refitted in its place (fresh32's aj08), not the pair
    reported as stand-ins. Both named, with their values."""
    rec = make_record("ag-slow", [("resistance-drift", "Ra", None, [-0.12, 4.0]),
                                  ("unbalance", "rotor", 1, [1.36e-3, 2.67e-3])],
                      seed=8, shaped=True)
    d = diagnose(cs.load(MOTORS["ag-slow"]["netlist"]), rec)
    got = {a.effect: a.parameters for a in d.effects}
    assert set(got) == {"resistance-drift", "unbalance"}, d.summary()
    drift = {k.rsplit("_", 1)[-1]: v for k, v in got["resistance-drift"].items()}
    assert drift["rise"] == pytest.approx(-0.12, rel=0.1), d.summary()
    assert drift["tau"] == pytest.approx(4.0, rel=0.2), d.summary()
    ab = np.array(list(got["unbalance"].values())[:2])
    assert np.hypot(*ab) == pytest.approx(np.hypot(1.36e-3, 2.67e-3), rel=0.05), d.summary()


def test_stribeck_peak_and_its_speed_through_the_loop():
    """Coulomb friction with a breakaway peak of 1.5 mN m below 4 rad/s on a motor that
    coasts to rest: found as Stribeck friction, its peak and speed recovered (the speed
    starts from the catalog's nearest start, 3 rad/s, and is fitted)."""
    rec = make_record("b", [("coulomb-friction", "rotor", None, [1e-3]),
                            ("stribeck-friction", "rotor", None, [1.5e-3, 4.0])], seed=14)
    d = diagnose(cs.load(MOTORS["b"]["netlist"]), rec)
    assert "stribeck-friction" in {a.effect for a in d.effects}, d.summary()
    got = {k.rsplit("_", 1)[-1]: v for a in d.effects for k, v in a.parameters.items()}
    assert got["s"] == pytest.approx(1.5e-3, rel=0.1), d.summary()
    assert got["ws"] == pytest.approx(4.0, rel=0.1), d.summary()


def test_a_breakaway_on_a_rotor_that_declares_no_dry_friction_through_the_loop():
    """A rotor that declares a viscous friction alone sticks by 1.5 mN m that fades by
    4 rad/s (dried-out bushes; fresh53's be05): no dry friction of one level fits it, and
    the breakaway peak is offered on its own -- found as Stribeck friction on a motor that
    comes to rest and starts again through its command, its peak and speed recovered.
    (A record that passes through low speed once, in a start-up of a few milliseconds,
    fixes the peak's impulse, not its shape: the report says so.)"""
    rec = make_record("b", [("stribeck-friction", "rotor", None, [1.5e-3, 4.0])], seed=16)
    d = diagnose(cs.load(MOTORS["b"]["netlist"]), rec)
    assert [a.effect for a in d.effects] == ["stribeck-friction"], d.summary()
    got = {k.rsplit("_", 1)[-1]: v for a in d.effects for k, v in a.parameters.items()}
    assert got["s"] == pytest.approx(1.5e-3, rel=0.1), d.summary()
    assert got["ws"] == pytest.approx(4.0, rel=0.1), d.summary()


def test_kim_declared_ripple_off_is_a_correction_not_a_new_effect():
    """The record's 8th-order ripple is 10 % stronger than declared: the diagnosis re-tunes
    the declared term and names no new cause."""
    rec = make_record("kim", [("emf-harmonic", "M", 8, [0.1 * 0.0168 / (2 * np.pi), 0.0])],
                      seed=13)
    d = diagnose(cs.load(MOTORS["kim"]["netlist"]), rec)
    assert d.effects == [], d.summary()
    assert [(c.effect, c.parameters["order"]) for c in d.corrections] == [("emf-harmonic", 8)]


def test_two_effects_on_the_kim_motor_are_both_found():
    rec = make_record("kim", [("coulomb-friction", "rotor", None, [2e-3]),
                              ("cogging", "rotor", 6, [2e-3, 0.0])], seed=14)
    d = diagnose(cs.load(MOTORS["kim"]["netlist"]), rec)
    found = {a.effect for a in d.effects}
    assert "cogging" in found and found & {"coulomb-friction", "force-offset"}, d.summary()
    assert len(d.effects) == 2, d.summary()


def test_saturation_and_friction_together_on_the_dc_motor():
    rec = make_record("dc", [("inductor-saturation", "Lw", None, [0.2, 0.3]),
                             ("coulomb-friction", "rotor", None, [5e-4])], seed=15)
    d = diagnose(cs.load(MOTORS["dc"]["netlist"]), rec)
    found = {a.effect for a in d.effects}
    assert "inductor-saturation" in found, d.summary()
    assert found & {"coulomb-friction", "force-offset"}, d.summary()


def test_backlash_in_the_coupling_through_the_loop():
    rec = make_record("tm", [("backlash", "K", None, [0.01])], seed=5)
    d = diagnose(cs.load(MOTORS["tm"]["netlist"]), rec)
    _check(d, "backlash", "K", None, [0.01], 0.05)
    assert d.error_after < 0.2 * d.error_before


@pytest.mark.parametrize("gap", [0.2, 0.5])
def test_a_play_as_wide_as_the_couplings_twist_through_the_loop(gap):
    """The coupling twists by +-0.11 rad: a play of 0.2 rad leaves it in contact only near
    the peaks, one of 0.5 rad never lets it touch. Neither is a small change of the declared
    coupling, and the slope at gap 0 misjudges both (on the screen by slope alone both were
    "something remains that I cannot name"); the grid of plays finds them."""
    rec = make_record("tm", [("backlash", "K", None, [gap])], seed=11)
    d = diagnose(cs.load(MOTORS["tm"]["netlist"]), rec)
    _check(d, "backlash", "K", None, [gap], 0.02)
    assert d.error_after < 0.02 * d.error_before


def test_backlash_and_load_friction_together_on_the_two_mass_drive():
    rec = make_record("tm", [("backlash", "K", None, [0.005]),
                             ("coulomb-friction", "load", None, [2e-3])], seed=7)
    d = diagnose(cs.load(MOTORS["tm"]["netlist"]), rec)
    got = {a.effect: a for a in d.effects}
    assert set(got) == {"backlash", "coulomb-friction"}, d.summary()
    assert got["coulomb-friction"].target == "load"
    final = {k: v["estimate"] for k, v in d.final_parameters().items()}
    assert final["backlash_K_gap"] == pytest.approx(0.005, rel=0.05)
    assert final["coulomb_friction_load_c"] == pytest.approx(2e-3, rel=0.05)


def test_a_load_the_netlist_lacks_is_a_correction_of_the_declared_inertia():
    """A body on the shaft the netlist does not hold: the declared inertia is off, reported
    as a correction with its factor, not as a new cause."""
    rec = make_record("dc", [("inertia", "Jr", None, [0.3])], seed=13)
    d = diagnose(cs.load(MOTORS["dc"]["netlist"]), rec)
    assert not d.effects, d.summary()
    (fix,) = d.corrections
    assert (fix.effect, fix.target) == ("inertia", "Jr")
    final = {k: v["estimate"] for k, v in d.final_parameters().items()}
    assert final["inertia_Jr_dJ"] == pytest.approx(0.3, rel=0.05)
    assert d.error_after < 0.2 * d.error_before


def test_a_supply_inductance_is_a_correction_of_the_inductance_it_is_in_series_with():
    """0.25 mH of supply inductance written as a component of its own between the Kim
    motor's source and the rest (so the record does not come from the patch): in series
    with La, it is La off by 0.25/0.87, reported as a correction of La, not as a new cause
    and not as a sensor's delay."""
    m = MOTORS["kim"]
    net = cs.load(m["netlist"])
    raw = net.raw.copy()
    src = raw.component_entry("Vin")
    node, src["p"] = src["p"], "supply"
    raw.comps.append(({"name": "Lsupply", "type": "L", "p": "supply", "n": node,
                       "L": 0.25e-3}, raw.comps[0][1], raw.path))
    t, fine, res = _fine_run(m, raw)
    rng = np.random.default_rng(17)
    rec = Record(t, {p: np.interp(t, fine, res[p]) + rng.normal(0.0, s, t.size)
                     for p, s in m["noise"].items()}, "kim + supply inductance")
    d = diagnose(net, rec)
    assert not d.effects, d.summary()
    (fix,) = d.corrections
    assert (fix.effect, fix.target) == ("inductance", "La")
    final = {k: v["estimate"] for k, v in d.final_parameters().items()}
    assert final["inductance_La_dL"] == pytest.approx(0.25 / 0.87, rel=0.03)
    assert d.error_after < 0.2 * d.error_before


def test_a_brush_drop_with_a_soft_transition_through_the_loop():
    """A brush drop of 0.2 V reached over 5 mA (Vb tanh(i/5 mA), not the catalog's 1 mA) on
    the slow motor, whose current crosses zero slowly: named as a brush drop whose
    transition width is fitted (the refinement ``brush-transition``, reported as part of the
    drop), both values recovered, and nothing else named in its place."""
    rec = make_record("b", [("brush-drop", "M", None, [0.2]),
                            ("brush-transition", "M", None, [5e-3])], seed=16)
    d = diagnose(cs.load(MOTORS["b"]["netlist"]), rec)
    assert [(a.effect, a.target) for a in d.effects] == [("brush-drop", "M")], d.summary()
    got = {k.rsplit("_", 1)[-1]: v for k, v in d.effects[0].parameters.items()}
    assert got["Vb"] == pytest.approx(0.2, rel=0.02), d.summary()
    assert got["eps"] == pytest.approx(5e-3, rel=0.1), d.summary()


def _iron_loss(raw):
    """A loss torque growing as speed^1.5 on the rotor (iron loss), outside the catalog."""
    from circuitsim.errors import SourceLoc

    raw.comps.append(({"name": "IRON", "type": "btorque", "shaft": "rotor",
                       "expr": "-2e-6*rotor.w*sqrt(smooth_abs(rotor.w, 1e-3))"},
                      SourceLoc("<test>"), raw.path))
    return raw


def test_a_loss_growing_faster_than_a_viscous_friction_is_not_named_one():
    """An iron loss, 2e-6 w^1.5 N m against the rotor of the slow motor: a viscous friction
    fits most of it, but its law does not hold over the record's speeds (bent by |w|, it
    explains most of what is left), so no catalog effect is named and the report says why
    and describes what remains."""
    m = MOTORS["b"]
    net = cs.load(m["netlist"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(build(_iron_loss(net.raw.copy())))
    t = np.arange(round(m["stop"] * m["rate"]) + 1) / m["rate"]
    res = model.simulate(stop=m["stop"], t_eval=t, rtol=1e-10, atol=1e-12)
    assert res.success, res.message
    rng = np.random.default_rng(17)
    rec = Record(t, {p: res[p] + rng.normal(0.0, s, t.size) for p, s in m["noise"].items()},
                 "motor b + iron loss")
    d = diagnose(net, rec)
    assert not d.effects, d.summary()
    assert d.remaining["structure"], d.summary()
    assert "its law does not hold" in d.remaining.get("stand_ins", ""), d.summary()
    assert "viscous-friction on rotor" in d.remaining["stand_ins"], d.summary()


def test_an_unbalance_of_an_arm_that_never_turns_once_through_the_loop():
    """A torque once per turn of the arm (its weight on a tilted base: 0.3 N m sin(phi +
    0.8)) on an arm that swings through 4.7 rad and never turns once: no line in any
    spectrum can show its order, but order 1 is looked for on every shaft, and it is named
    as an unbalance of the arm (or of the drive's output before the compliant flexspline,
    which turns with it) with its amplitude and phase."""
    a, b = 0.3 * np.cos(0.8), 0.3 * np.sin(0.8)
    rec = make_record("j-slow", [("unbalance", "arm", 1, [a, b])], seed=18)
    d = diagnose(cs.load(MOTORS["j-slow"]["netlist"]), rec)
    assert [(x.effect, x.parameters["order"]) for x in d.effects] == [("unbalance", 1)], \
        d.summary()
    got = [v for k, v in d.effects[0].parameters.items() if k != "order"]
    assert np.hypot(*got) == pytest.approx(0.3, rel=0.05), d.summary()
    assert np.arctan2(got[1], got[0]) == pytest.approx(0.8, abs=0.05), d.summary()


def _outside_record(motor: str, torques: dict[str, str], seed: int,
                    series: dict[str, str] | None = None) -> Record:
    """A record of ``motor`` with behavioural torques (shaft -> expression [N*m]) and
    voltages in series with components (component -> expression [V]) the catalog does not
    hold, simulated finely, resampled, with white noise and ADC steps."""
    from circuitsim.errors import SourceLoc

    m = MOTORS[motor]
    raw = cs.load(m["netlist"]).raw.copy()
    for shaft, expr in torques.items():
        raw.comps.append(({"name": f"OUT_{shaft}", "type": "btorque", "shaft": shaft,
                           "expr": expr}, SourceLoc("<test>"), raw.path))
    for component, expr in (series or {}).items():
        effects.insert_series(raw, component, f"OUT_{component}", expr)
    return Record(*_sampled(m, raw, seed), f"{motor} + {torques} + {series or {}}")


def _a_stand_in(motor: str, rec: Record, reason: str):
    """Diagnose ``rec`` on ``motor``'s netlist: nothing named, structure described, and the
    stand-in's ``reason`` (its effect and why) in the report; the diagnosis."""
    d = diagnose(cs.load(MOTORS[motor]["netlist"]), rec)
    assert not d.effects, d.summary()
    assert d.remaining["structure"], d.summary()
    assert reason in d.remaining.get("stand_ins", ""), d.summary()
    return d


def test_a_play_in_the_barrier_drive_through_the_loop():
    """A play of 0.04 rad in the barrier gate's compliant drive: named, its law holds (the
    drive is as stiff both ways in contact), its width within 2 %."""
    rec = make_record("ae", [("backlash", "K", None, [0.04])], seed=3)
    d = diagnose(cs.load(MOTORS["ae"]["netlist"]), rec)
    _check(d, "backlash", "K", None, [0.04], 0.02)
    assert d.error_after < 0.05 * d.error_before
    _law_was_tested(d, "K.phi_rel about its mean")


def _law_was_tested(d, term: str) -> None:
    """The named effect's law was bent, by ``term`` among its shapes, and held."""
    (found,) = d.effects
    law = found.evidence["stability"]["law"]
    assert term in law["terms"], law
    assert law["delta_bic"] > -10.0, law  # the bend did not pass the BIC margin


def test_a_drive_half_as_stiff_one_way_is_not_named_a_play():
    """A crack in the barrier's drive that opens under tension: the drive is half as stiff
    when the hub leads the boom (a torque 0.5 Kc max(twist, 0) given back beside the
    coupling). A play fits most of it, and was named before the play had a law; bent by the
    twist about its mean and by |twist| (a stiffness that differs one way or grows with the
    twist), it takes a fair share of what is left, so the play is a stand-in: no catalog
    label, the structure described, the play named in the reason."""
    twist = "(hub.phi - boom.phi)"
    give = f"0.5*Kc*({twist} + abs({twist}))/2"
    rec = _outside_record("ae", {"hub": give, "boom": f"-({give})"}, seed=23)
    _a_stand_in("ae", rec, "backlash on K (its law does not hold")


def test_a_torque_of_the_booms_angle_that_is_no_weight_is_not_named_an_unbalance():
    """A wind's torque on the raised boom, -20 sin(angle) |sin(angle)| N m: over the boom's
    quarter turn it is -10 + 10 cos(2 angle), which an unbalance (once per turn) and a
    torque offset fit to 99.9 % of the misfit -- and were named so before an unbalance's
    law was bent by the angle. One weight's moment has the same amplitude at every angle;
    bent by the angle, the unbalance takes a fair share of what is left, so it is a stand-in
    and nothing is named. (A true unbalance on this boom is named: the next test.)"""
    wind = "-20*sin(boom.phi/1[rad])*abs(sin(boom.phi/1[rad]))"
    rec = _outside_record("ae-slow", {"boom": wind}, seed=23)
    d = _a_stand_in("ae-slow", rec, "unbalance on boom (its law does not hold")
    assert "a change with the angle boom.phi" in d.remaining["stand_ins"], d.summary()


def test_an_unbalance_of_the_boom_through_the_loop():
    """A true unbalance of the boom, 3.6 N m sin(angle + phase), on the same slow record: its
    law holds under the angle's bend, and it is named with its amplitude and phase."""
    rec = make_record("ae-slow", [("unbalance", "boom", 1, [3.0, -2.0])], seed=4)
    d = diagnose(cs.load(MOTORS["ae-slow"]["netlist"]), rec)
    assert [(x.effect, x.target) for x in d.effects] == [("unbalance", "boom")], d.summary()
    got = [v for k, v in d.effects[0].parameters.items() if k != "order"]
    assert got == pytest.approx([3.0, -2.0], abs=0.1), d.summary()
    _law_was_tested(d, "cos(boom.phi)")


def test_brushes_that_drop_more_one_way_are_not_named_a_brush_drop():
    """Brushes set at an angle for one direction of turning: 0.3 V drop while the current
    flows forward, 1.2 V while it flows back (0.75 tanh(i/1 mA) - 0.45 tanh(i/1 mA)^2), on
    the barrier gate, whose current reverses when it brakes and closes. A brush drop fits
    most of it (fresh31's ai12, from a simulator of its own, was named one); bent by the
    current's direction (a contact drops as much either way) it takes a fair share of what
    is left, so the drop is a stand-in and the report says how it bends."""
    sign = "tanh(M.i/1[mA])"
    rec = _outside_record("ae", {}, seed=29,
                          series={"M": f"0.75[V]*{sign} - 0.45[V]*{sign}^2"})
    d = _a_stand_in("ae", rec, "brush-drop on M (its law does not hold")
    # bent by the direction, negatively: the drop is larger when the current flows back
    assert re.search(r"the sign of M\.i \(-\d+% where", d.remaining["stand_ins"]), d.summary()


def test_a_brush_drop_on_the_barrier_gate_through_the_loop():
    """A true brush drop of 0.7 V on the same record: its law holds under the direction's
    bend too, and it is named with its drop within 2 %."""
    rec = make_record("ae", [("brush-drop", "M", None, [0.7])], seed=29)
    d = diagnose(cs.load(MOTORS["ae"]["netlist"]), rec)
    _check(d, "brush-drop", "M", None, [0.7], 0.02)
    _law_was_tested(d, "the sign of M.i")


def test_a_saturation_and_a_speed_delay_on_the_barrier_gate_through_the_loop():
    """A saturation acts in the current's transients, which the slow features an
    angle-locked model is screened on average away: its grid screen must be seen on the
    waveform too (fresh31's ai09: a constant inductance correction won instead, and the
    saturation it generalises never reached a refit). Both effects, with their values."""
    rec = make_record("ae", [("inductor-saturation", "La", None, [3.0, 0.5]),
                             ("sensor-delay", "speed", None, [4e-4])], seed=21)
    d = diagnose(cs.load(MOTORS["ae"]["netlist"]), rec)
    got = {a.effect: a.parameters for a in d.effects}
    assert set(got) == {"inductor-saturation", "sensor-delay"}, d.summary()
    sat = got["inductor-saturation"]
    assert sat["inductor_saturation_La_Ipar"] == pytest.approx(3.0, rel=0.03), d.summary()
    assert sat["inductor_saturation_La_ratio"] == pytest.approx(0.5, rel=0.03), d.summary()
    assert got["sensor-delay"]["sensor_delay_speed_tau"] == pytest.approx(4e-4, rel=0.05)
    assert not d.corrections, d.summary()
