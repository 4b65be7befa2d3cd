"""The effect catalog: every candidate is a netlist patch that is exact at its null value and
does its physics away from it (issue #5, catalog)."""

from __future__ import annotations

import copy
import warnings

import numpy as np
import pytest

import circuitsim as cs
from circuitsim.loop import effects
from circuitsim.netlist import build
from circuitsim.solve.op import operating_point, probe_values

from conftest import NETLISTS

CASE1 = NETLISTS / "kim2024" / "case1.yaml"
TWO_MASS = NETLISTS / "examples" / "two_mass_motor.yaml"


def _compile(net):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cs.compile(net)


def test_catalog_covers_the_interface_ids():
    net = cs.load(CASE1)
    found = {c.effect for c in effects.candidates(net, {"rotor": [1, 8]}, {"i_total": "A"})}
    # a breakaway peak refines a friction the netlist has: proposed once there is one
    coulomb = next(c for c in effects.candidates(net) if c.effect == "coulomb-friction")
    found |= {c.effect for c in effects.candidates(build(coulomb.apply(net.raw)))}
    # a brush drop's transition width refines a drop accepted before
    brush = next(c for c in effects.candidates(net) if c.effect == "brush-drop")
    found |= {c.effect for c in effects.candidates(build(brush.apply(net.raw)))}
    # a play needs a declared coupling between two bodies
    found |= {c.effect for c in effects.candidates(cs.load(TWO_MASS))}
    assert found == set(effects.CATALOG_IDS)


def test_every_patch_is_exact_at_its_null_value():
    net = cs.load(CASE1)
    base = _compile(net).simulate(stop=0.02, rtol=1e-10, atol=1e-12)
    for c in effects.candidates(net, {"rotor": [1, 2]}, {"i_total": "A"}):
        res = _compile(build(c.apply(net.raw))).simulate(stop=0.02, rtol=1e-10, atol=1e-12)
        assert res.success, c.key
        np.testing.assert_allclose(res["i_total"], base["i_total"], atol=1e-7, err_msg=c.key)


def test_coulomb_friction_patch_lowers_the_speed_as_the_closed_form_says(tmp_path):
    """Kim base + a Coulomb torque Tc: omega = (k_t (V - e0) - Ra Tc) / (k_t k_e + B Ra)."""
    net = cs.load(NETLISTS / "kim2024" / "base.yaml")
    cand = next(c for c in effects.candidates(net) if c.effect == "coulomb-friction")
    (pname,) = cand.free
    patched = build(cand.apply(net.raw))
    model = _compile(patched)
    op = operating_point(model, {pname: 0.01})
    k_t, k_e, R, B = 0.14, 0.1017 / (2 * np.pi), 1.1, 2.95e-4
    w = (k_t * (12 - 1.151e-4) - R * 0.01) / (k_t * k_e + B * R)
    assert probe_values(model, op, {pname: 0.01})["speed"] == pytest.approx(w, rel=1e-6)
    # the patch written out is a netlist `circuitsim run` reproduces
    out = tmp_path / "fixed.yaml"
    cand.apply(net.raw).dump(out, "base + Coulomb friction")
    again = _compile(cs.load(out))
    assert again.key == model.key


def _op_probe(net, effect, values, probe="speed", probes=("i_total", "speed")):
    cand = next(c for c in effects.candidates(net, {"rotor": [1]}, list(probes))
                if c.effect == effect and (c.target in (probe, "rotor", "M")))
    model = _compile(build(cand.apply(net.raw)))
    named = dict(zip(cand.free, values, strict=True))
    return probe_values(model, operating_point(model, named), named)


def test_sensor_patches_read_through_their_law():
    """A gain error g reads (1 + g) x; an offset o reads x + o; the circuit is untouched."""
    net = cs.load(NETLISTS / "kim2024" / "base.yaml")
    model = _compile(net)
    base = probe_values(model, operating_point(model))
    gain = _op_probe(net, "sensor-gain", [0.05], "speed")
    offset = _op_probe(net, "sensor-offset", [0.2], "i_total")
    assert gain["speed"] == pytest.approx(1.05 * base["speed"], rel=1e-9)
    assert gain["i_total"] == pytest.approx(base["i_total"], rel=1e-9)
    assert offset["i_total"] == pytest.approx(base["i_total"] + 0.2, rel=1e-9)


def test_sensor_delay_patch_reads_the_probe_late():
    """The delay patch reads x(t - tau). Against the undelayed run shifted by tau, through
    the start-up of the Kim motor (a kink at t = 0, where a first-order Padé stage is at its
    worst), its error relative to what the shift itself changes falls in proportion to tau:
    below 2 % at 0.1 ms, a quarter of it at a quarter of the delay. At its null it reads x."""
    net = cs.load(NETLISTS / "kim2024" / "base.yaml")
    model = _compile(net)
    units = model.meta["units"]
    delay = next(c for c in effects.candidates(net, None, {"speed": units["speed"]})
                 if c.effect == "sensor-delay")
    (name,) = delay.free
    assert delay.free[name][0] > 0.0  # the Padé stage needs a capacitance
    patched = _compile(build(delay.apply(net.raw)))
    t = np.linspace(0.0, 0.05, 5001)
    base = model.simulate(stop=0.05, t_eval=t, rtol=1e-10, atol=1e-12)["speed"]

    def error(tau):
        late = patched.simulate(stop=0.05, t_eval=t, params={name: tau}, rtol=1e-10,
                                atol=1e-12)["speed"]
        shifted = np.interp(t - tau, t, base, left=0.0)
        return np.max(np.abs(late - shifted)) / np.max(np.abs(base - shifted))

    coarse, fine = error(4e-4), error(1e-4)
    assert fine < 0.02
    assert fine == pytest.approx(coarse / 4, rel=0.3)
    null = patched.simulate(stop=0.05, t_eval=t, rtol=1e-10, atol=1e-12)["speed"]
    np.testing.assert_allclose(null, base, atol=1e-6 * np.max(np.abs(base)))


def test_no_effect_is_proposed_on_a_patch_s_own_parts():
    """A sensor's filter or a series source added by a patch is not part of the circuit to
    diagnose: no series resistance, drift or saturation is proposed on it."""
    net = cs.load(NETLISTS / "kim2024" / "base.yaml")
    probes = {"speed": "rad/s", "i_total": "A"}
    before = {c.key for c in effects.candidates(net, None, probes)}
    delay = next(c for c in effects.candidates(net, None, probes) if c.effect == "sensor-delay")
    series = next(c for c in effects.candidates(net, None, probes)
                  if c.effect == "series-resistance")
    patched = build(series.apply(delay.apply(net.raw)))
    after = {c.key for c in effects.candidates(patched, None, probes)}
    assert after - before == set()  # nothing new on the added parts
    assert {delay.key, series.key} <= after  # the catalog itself is unchanged


def test_stribeck_patch_is_coulomb_friction_far_above_its_speed():
    """At 650 rad/s the breakaway peak (below ~1 rad/s) has decayed: the steady speed is the
    Coulomb closed form with tau_c = c, whatever the peak s."""
    net = cs.load(NETLISTS / "kim2024" / "base.yaml")
    k_t, k_e, R, B = 0.14, 0.1017 / (2 * np.pi), 1.1, 2.95e-4
    w = (k_t * (12 - 1.151e-4) - R * 0.01) / (k_t * k_e + B * R)
    coulomb = next(c for c in effects.candidates(net) if c.effect == "coulomb-friction")
    with_friction = build(coulomb.apply(net.raw))
    stribeck = next(c for c in effects.candidates(with_friction)
                    if c.effect == "stribeck-friction")
    model = _compile(build(stribeck.apply(with_friction.raw)))
    values = {**dict.fromkeys(coulomb.free, 0.01), **dict.fromkeys(stribeck.free, 0.02)}
    speed = probe_values(model, operating_point(model, values), values)["speed"]
    assert speed == pytest.approx(w, rel=1e-6)
    # on a shaft with no dry friction the same peak is offered alone: the friction's whole
    # dry part, sticking at rest and fading with speed
    alone = next(c for c in effects.candidates(net) if c.key == stribeck.key)
    assert alone.free == stribeck.free


def test_effect_parameters_have_physical_bounds():
    """Resistances, friction and drops are never negative; a saturation ratio is in (0, 1];
    a breakaway's Stribeck speed is positive."""
    net = cs.load(CASE1)
    cands = [*effects.candidates(net, {"rotor": [8]}, ["i_total"]),
             *effects.candidates(cs.load(TWO_MASS))]
    assert any(c.effect == "stribeck-friction" for c in cands)
    for c in cands:
        for name, (null, lo, hi) in c.free.items():
            assert lo <= null <= hi, c.key
            if c.effect == "stribeck-friction" and name in c.shape:
                assert lo > 0.0, c.key
            elif c.effect in ("series-resistance", "source-resistance", "brush-drop",
                              "backlash",
                              "coulomb-friction", "viscous-friction", "stribeck-friction"):
                assert lo == 0.0, c.key
            if c.effect == "inductor-saturation" and name.endswith("ratio"):
                assert 0.0 < lo and hi == 1.0, c.key
            if c.effect in ("inertia", "inductance"):  # a scaled value stays positive
                assert -1.0 < lo, c.key


def test_warmup_patch_is_the_closed_form_and_exact_at_null(tmp_path):
    """A 2 ohm resistor on 1 V warming up by 30 % with tau = 0.1 s draws
    i(t) = 1 / (2 (1 + 0.3 (1 - exp(-t/0.1)))); the straight-line drift stays its own
    candidate, and each start of the time constant is one candidate of one kind."""
    path = tmp_path / "r.yaml"
    path.write_text("components:\n"
                    "  - {name: V1, type: V, p: a, n: gnd, V: 1}\n"
                    "  - {name: R1, type: R, p: a, n: gnd, R: 2}\n"
                    "probes: {i: R1.i}\n")
    net = cs.load(path)
    drifts = [c for c in effects.candidates(net, None, (), duration=0.5)
              if c.effect == "resistance-drift"]
    assert len({c.kind for c in drifts}) == 1 and len({c.key for c in drifts}) == len(drifts)
    warm = next(c for c in drifts if c.shape)
    model = _compile(build(warm.apply(net.raw)))
    rise, tau = (n for n in warm.free)
    t = np.linspace(0.0, 0.5, 51)
    res = model.simulate(stop=0.5, t_eval=t, params={rise: 0.3, tau: 0.1},
                         rtol=1e-10, atol=1e-14)
    assert res["i"] == pytest.approx(1 / (2 * (1 + 0.3 * (1 - np.exp(-t / 0.1)))), rel=1e-8)
    null = model.simulate(stop=0.5, t_eval=t, rtol=1e-10, atol=1e-14)  # rise at its null
    assert np.all(null["i"] == 0.5)


def test_a_drift_is_bounded_by_how_far_and_how_fast_copper_can_heat(tmp_path):
    """A resistance drifts because its winding warms or cools. Copper's coefficient
    3.93e-3 /K over the widest swing of a winding (-20 to 180 degC: 200 K) bounds the
    change to -44 % .. +79 %; adiabatic heating at 150 A/mm^2 (rho J^2 / (c d) with
    rho = 1.68e-8 ohm m, c = 385 J/(kg K), d = 8960 kg/m^3: 110 K/s) bounds its rate to
    43 %/s. A +46 % warm-up within tau = 0.12 s (what a supply current limit was taken for) is
    beyond it, with the reason; the +10 % in 2 s of a warm winding is not."""
    path = tmp_path / "r.yaml"
    path.write_text("components:\n"
                    "  - {name: V1, type: V, p: a, n: gnd, V: 1}\n"
                    "  - {name: R1, type: R, p: a, n: gnd, R: 2}\n"
                    "probes: {i: R1.i}\n")
    heat = 1.68e-8 * 150e6 ** 2 / (385 * 8960)  # [K/s] with no cooling at all
    assert heat == pytest.approx(109.6, abs=0.1)
    for duration in (0.4, 6.0):
        drifts = [c for c in effects.candidates(cs.load(path), None, (), duration=duration)
                  if c.effect == "resistance-drift"]
        line = next(c for c in drifts if not c.shape)
        (alpha,) = line.free.values()
        # a straight line no faster than heating, spanning no more than the swing
        assert alpha[2] == pytest.approx(min(3.93e-3 * heat, 3.93e-3 * 200 / duration),
                                         rel=1e-3) and alpha[1] == -alpha[2]
        for warm in (c for c in drifts if c.shape):
            rise, tau = warm.free
            assert warm.free[rise][1:] == pytest.approx((1 / (1 + 0.786) - 1, 0.786))
            why = warm.limit({rise: 0.46, tau: 0.12})
            assert "R1" in why and "150 A/mm^2" in why and "+383%/s" in why
            assert warm.limit({rise: 0.1, tau: 2.0}) == ""
            assert warm.limit({rise: -0.1, tau: 0.1}) != ""  # cooling is bounded alike


def test_backlash_patch_is_the_dead_zone_closed_form_and_exact_at_null(tmp_path):
    """A torque step T on a rotor J1 coupled to a load J2 through a coupling with a play of
    total width g: inside the play nothing is transmitted, neither spring nor damper, so the
    rotor turns at T t / J1 and the load stays at rest until the twist T t^2 / (2 J1) reaches
    g / 2, at t_c = sqrt(g J1 / T); the netlist's step rises over 1 ns, which
    delays both by half of that. At g = 0 it is the declared coupling."""
    net = cs.load(NETLISTS / "breadth" / "drivetrain.yaml")
    cand = next(c for c in effects.candidates(net) if c.effect == "backlash")
    assert cand.target == "Coupling"
    patched = cand.apply(net.raw)
    assert patched.component_entry("Coupling")["type"] == "backlash"  # a readable netlist
    (gap,) = cand.free
    model = _compile(build(cand.apply(net.raw)))
    j1, torque, g, lag = 0.01, 1.0, 0.02, 0.5e-9
    t_c = np.sqrt(g * j1 / torque) + lag
    t = np.linspace(0.0, 0.9 * t_c, 31)
    res = model.simulate(stop=2 * t_c, t_eval=np.append(t, 2 * t_c), params={gap: g},
                         rtol=1e-10, atol=1e-12)
    w = torque * np.maximum(t - lag, 0.0) / j1
    assert res["w_rotor"][:-1] == pytest.approx(w, rel=1e-8, abs=1e-9)
    assert np.all(np.abs(res["w_load"][:-1]) < 1e-9)
    assert res["w_load"][-1] > 1e-3  # in contact after t_c: the load follows
    t = np.linspace(0.0, 0.2, 201)
    base = _compile(net).simulate(stop=0.2, t_eval=t, rtol=1e-10, atol=1e-12)
    null = model.simulate(stop=0.2, t_eval=t, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(null["twist"], base["twist"], rtol=1e-6, atol=1e-9)



def test_a_play_opens_about_a_prestressed_couplings_unstretched_twist():
    """The same drive with the coupling prestressed (phi_rel0 = 30 mrad: at rest the spring
    pushes by c phi_rel0): the play opens about phi_rel0, so a twist of 0 lies inside a play
    of 0.1 rad and nothing is transmitted until the twist T t^2 / (2 J1) reaches phi_rel0 +
    gap/2, at t_c = sqrt(2 J1 (phi_rel0 + gap/2) / T) (plus half the step's 1 ns rise). At
    gap 0 it is the prestressed coupling as declared."""
    net = cs.load(NETLISTS / "breadth" / "drivetrain.yaml")
    raw = net.raw.copy()
    raw.component_entry("Coupling")["phi_rel0"] = 0.03
    net = build(raw)
    cand = next(c for c in effects.candidates(net) if c.effect == "backlash")
    assert cand.target == "Coupling"
    (gap,) = cand.free
    model = _compile(build(cand.apply(net.raw)))
    j1, torque, g, p0, lag = 0.01, 1.0, 0.1, 0.03, 0.5e-9
    t_c = np.sqrt(2 * j1 * (p0 + g / 2) / torque) + lag
    t = np.linspace(0.0, 0.9 * t_c, 31)
    res = model.simulate(stop=1.2 * t_c, t_eval=np.append(t, 1.2 * t_c), params={gap: g},
                         rtol=1e-10, atol=1e-12)
    w = torque * np.maximum(t - lag, 0.0) / j1
    assert res["w_rotor"][:-1] == pytest.approx(w, rel=1e-8, abs=1e-9)
    assert np.all(np.abs(res["w_load"][:-1]) < 1e-9)
    assert res["w_load"][-1] > 1e-3  # in contact after t_c: the load follows
    t = np.linspace(0.0, 0.2, 201)
    base = _compile(net).simulate(stop=0.2, t_eval=t, rtol=1e-10, atol=1e-12)
    null = model.simulate(stop=0.2, t_eval=t, rtol=1e-10, atol=1e-12)
    assert np.ptp(base["twist"]) > 0.01  # the prestress moves the drive from t = 0
    np.testing.assert_allclose(null["twist"], base["twist"], rtol=1e-6, atol=1e-9)

def test_a_coupling_reads_no_shaft_angle_but_a_ripple_does():
    """Speed effects are compared on the waveform unless a law reads a shaft's angle itself:
    a spring reads the twist between two shafts (turning both alike changes nothing), a
    declared EMF ripple reads the angle."""
    from circuitsim.loop.diagnose.context import angle_locked

    assert not angle_locked(_compile(cs.load(TWO_MASS)))
    assert not angle_locked(_compile(cs.load(NETLISTS / "breadth" / "drivetrain.yaml")))
    assert angle_locked(_compile(cs.load(NETLISTS / "kim2024" / "base.yaml")))


def test_an_emf_harmonic_declares_its_order_on_its_shaft_too():
    """An EMF ripple of order 8 whose torque acts (``ripple_torque``, on by default): an
    EMF harmonic of order 8 on M and a torque of order 8 on its shaft both re-tune it. The
    Kim motor turns the ripple's torque off: there a torque of order 8 on the shaft is new
    (fresh53's be07, a cogging of order 8, had been reported as a correction). An inertia
    is re-tuned, never added."""
    net = cs.load(NETLISTS / "kim2024" / "base.yaml")
    declared = effects.declared_orders(net.raw)
    assert net.raw.component_entry("M")["ripple_torque"] is False
    assert declared == {("emf-harmonic", "M"): {8}}
    raw = copy.deepcopy(net.raw)
    del raw.component_entry("M")["ripple_torque"]
    declared = effects.declared_orders(raw)
    assert declared[("emf-harmonic", "M")] == {8} and declared[("cogging", "rotor")] == {8}
    (inertia,) = [c for c in effects.candidates(net) if c.effect == "inertia"]
    assert inertia.retunes and inertia.target == "Jr"
    model = _compile(build(inertia.apply(net.raw)))
    (dj,) = inertia.free
    t = np.linspace(0.0, 1e-4, 11)
    fast = model.simulate(stop=1e-4, t_eval=t, rtol=1e-10, atol=1e-14)
    slow = model.simulate(stop=1e-4, t_eval=t, params={dj: 1.0}, rtol=1e-10, atol=1e-14)
    # from rest, before the back-EMF acts: the speed is the torque's integral over J
    assert slow["speed"][1:5] == pytest.approx(fast["speed"][1:5] / 2, rel=1e-3)


def test_patches_that_scale_a_value_take_it_with_its_unit(tmp_path):
    """A value written with its unit (``2e-3 kg*m^2``, ``1 mH``) cannot sit inside
    arithmetic: the patch moves it into a parameter of its own and scales that. An inertia
    doubled halves the acceleration of a torque step; an inductance doubled doubles the RL
    time constant; a saturation at its null is the declared inductor."""
    path = tmp_path / "m.yaml"
    path.write_text("components:\n"
                    "  - {name: T1, type: torque, shaft: r, T: 1}\n"
                    "  - {name: J1, type: inertia, shaft: r, J: 2e-3 kg*m^2}\n"
                    "  - {name: V1, type: V, p: a, n: gnd, V: 1 V}\n"
                    "  - {name: R1, type: R, p: a, n: b, R: 1 ohm}\n"
                    "  - {name: L1, type: L, p: b, n: gnd, L: 1 mH}\n"
                    "probes: {w: r.w, i: L1.i}\n")
    net = cs.load(path)
    t = np.linspace(0.0, 0.01, 11)
    seen = set()
    for c in effects.candidates(net):
        if c.effect not in ("inertia", "inductance", "inductor-saturation"):
            continue
        seen.add(c.effect)
        res = _compile(build(c.apply(net.raw))).simulate(
            stop=0.01, t_eval=t, params={next(iter(c.free)): 1.0} if c.retunes else None,
            rtol=1e-10, atol=1e-12)
        if c.effect == "inertia":
            assert res["w"] == pytest.approx(t / 4e-3, rel=1e-9, abs=1e-12)
        else:
            tau = 2e-3 if c.retunes else 1e-3
            assert res["i"] == pytest.approx(1 - np.exp(-t / tau), rel=1e-7, abs=1e-12)
    assert seen == {"inertia", "inductance", "inductor-saturation"}
    assert {c.effect: c.retunes for c in effects.candidates(net)}["inductance"]


def test_a_brush_transition_is_the_drop_itself_at_its_null_and_softer_away_from_it():
    """brush-transition rewrites the accepted drop's law Vb tanh(i/1 mA) as Vb tanh(i/eps):
    at eps = 1 mA the circuit is the drop's to the integrator's tolerance; at a wider eps the
    drop is smaller where |i| is within a few eps of zero (the start-up from rest), and its
    width is bounded by BRUSH_EPS_MAX."""
    net = cs.load(CASE1)
    brush = next(c for c in effects.candidates(net) if c.effect == "brush-drop")
    raw = brush.apply(net.raw)
    fine = next(c for c in effects.candidates(build(raw)) if c.effect == "brush-transition")
    (eps, (null, lo, hi)), = fine.free.items()
    assert (null, hi) == (effects.BRUSH_EPS, effects.BRUSH_EPS_MAX) and 0 < lo < null
    vb = next(iter(brush.free))
    t = np.linspace(0.0, 0.02, 201)
    drop = _compile(build(raw)).simulate(stop=0.02, t_eval=t, params={vb: 0.5}, rtol=1e-10,
                                         atol=1e-12)
    refined = _compile(build(fine.apply(raw)))
    same = refined.simulate(stop=0.02, t_eval=t, params={vb: 0.5}, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(same["i_total"], drop["i_total"], rtol=1e-7, atol=1e-9)
    wide = refined.simulate(stop=0.02, t_eval=t, params={vb: 0.5, eps: 0.2}, rtol=1e-10,
                            atol=1e-12)
    # a softer contact drops less while the current is small: the start-up current is higher
    assert wide["i_total"][5] > drop["i_total"][5]


def test_order_one_is_looked_for_on_every_shaft():
    net = cs.load(TWO_MASS)
    shafts = {n for n, (d, _) in net.nodes.items() if d == "rotational" and n != "fixed"}
    assert effects.always_orders(net) == {n: [1] for n in shafts} and len(shafts) == 2


def test_a_law_bent_at_its_null_is_the_accepted_circuit():
    """law.bent_raw: the effect's contribution times the bend's shapes, each times a new
    parameter at 0, is the accepted circuit exactly; a bend of +10 % where |w| is largest
    strengthens the viscous friction by 10 % of its torque there (the speed falls)."""
    from circuitsim.loop.diagnose.law import _names, bent_raw

    net = cs.load(CASE1)
    visc = next(c for c in effects.candidates(net) if c.effect == "viscous-friction" and
                c.target == "rotor")
    raw = visc.apply(net.raw)
    b = next(iter(visc.free))
    names = _names(visc.law)
    bent = _compile(build(bent_raw(raw, visc.law)))
    scale = {n: 1.0 for _, _, n in names} | {names[0][2]: 700.0}
    t = np.linspace(0.0, 0.05, 51)
    base = _compile(build(raw)).simulate(stop=0.05, t_eval=t, params={b: 1e-4}, rtol=1e-10,
                                         atol=1e-12)
    null = bent.simulate(stop=0.05, t_eval=t, params={b: 1e-4, **scale}, rtol=1e-10,
                         atol=1e-12)
    np.testing.assert_allclose(null["speed"], base["speed"], rtol=1e-9, atol=1e-9)
    more = bent.simulate(stop=0.05, t_eval=t, params={b: 1e-4, **scale, names[0][0]: 0.1},
                         rtol=1e-10, atol=1e-12)
    assert np.all(more["speed"][10:] < base["speed"][10:])


def test_an_emf_harmonics_companion_torque_at_one_is_the_energy_consistent_harmonic():
    """law.bent_raw of a catalog EMF harmonic (a voltage alone) with its companion torque's
    coefficient at 1 is the `emf` element's own energy-consistent harmonic (`ripple_torque`,
    an independent implementation: the torque -(k + h sin(phi)) i beside the EMF); at 0 it
    is the catalog's patch, which leaves the torque out and so does not conserve energy."""
    from circuitsim.loop.diagnose.law import COMPANION, _names, bent_raw

    net = cs.load(NETLISTS / "examples" / "dc_motor.yaml")
    harm = next(c for c in effects.candidates(net, {"rotor": [1]})
                if c.effect == "emf-harmonic" and c.fixed["order"] == 1)
    a, b = harm.free  # the sine's and the cosine's coefficients [V s/rad]
    h = 0.01
    bent = _compile(build(bent_raw(harm.apply(net.raw), harm.law)))
    scales = {n: 1.0 for _, _, n in _names(harm.law)}
    t = np.linspace(0.0, 0.2, 201)
    run = {"stop": 0.2, "t_eval": t, "rtol": 1e-10, "atol": 1e-12}
    whole = bent.simulate(params={a: h, b: 0.0, **scales, COMPANION: 1.0}, **run)
    voltage = bent.simulate(params={a: h, b: 0.0, **scales, COMPANION: 0.0}, **run)
    raw = net.raw.copy()
    raw.comps = [({**c[0], "harmonics": [{"order": 1, "slope": h, "offset": 0.0,
                                          "phase": 0.0}], "ripple_torque": True}, *c[1:])
                 if str(c[0]["name"]) == "M" else c for c in raw.comps]
    ref = _compile(build(raw)).simulate(**run)
    for p in ("speed", "i"):
        span = float(np.ptp(ref[p]))
        np.testing.assert_allclose(whole[p], ref[p], atol=1e-7 * span)
        assert float(np.max(np.abs(voltage[p] - ref[p]))) > 1e-3 * span
