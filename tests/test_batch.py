"""K parameter sets in one stacked integration equal K solo runs (issue 14, item 5)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import circuitsim as cs
from circuitsim.solve.batch import simulate_batch

from conftest import NETLISTS, kim_steps

RC = """
    components:
      - {name: V1, type: V, p: a, n: gnd, V: {step: {v1: 2 V, t0: 1 ms, rise: 1 us}}}
      - {name: R1, type: R, p: a, n: b, R: 1 kohm}
      - {name: C1, type: C, p: b, n: gnd, C: 1 uF}
    probes: {vc: C1.v}
    analysis: {stop: 6 ms, step: 0.05 ms, rtol: 1e-9, atol: 1e-12}
"""


def test_batch_equals_solo_runs_and_the_closed_form(compile_text):
    """Three resistances and two step times (different waveform corners): each member
    agrees with its own solo run and with the RC step response."""
    model = compile_text(RC)
    sets = [{"R1.R": 500.0}, {"R1.R": 1000.0}, {"R1.R": 2000.0, "V1.V.t0": 2e-3}]
    batch = simulate_batch(model, sets)
    assert len(batch) == 3
    for q, res in zip(sets, batch, strict=True):
        solo = model.simulate(params=q)
        assert res.success and solo.success
        np.testing.assert_array_equal(res.t, solo.t)
        tau = q["R1.R"] * 1e-6
        t0 = q.get("V1.V.t0", 1e-3)
        # the 1 us ramp shifts the response by half its length
        after = res.t > t0 + 1e-6
        exact = 2 * (1 - np.exp(-(res.t[after] - t0 - 0.5e-6) / tau))
        assert np.max(np.abs(res["vc"][after] - exact)) < 2e-5  # the ramp's own effect
        assert np.max(np.abs(res["vc"] - solo["vc"])) < 1e-7
        assert res.params == solo.params


def test_batch_of_the_kim_base_model_matches_solo():
    """A nonlinear, index-reduced electromechanical model (band solver for small blocks)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(cs.load(NETLISTS / "kim2024" / "base.yaml"))
    sets = [{"Ra": 1.1 * (1 + 1e-3 * k)} for k in range(4)]
    batch = simulate_batch(model, sets, stop=0.02, rtol=1e-8, atol=1e-10)
    for q, res in zip(sets, batch, strict=True):
        solo = model.simulate(stop=0.02, params=q, rtol=1e-8, atol=1e-10)
        scale = np.max(np.abs(solo["i_total"]))
        assert np.max(np.abs(res["i_total"] - solo["i_total"])) < 1e-5 * scale
        assert res["speed"][-1] == pytest.approx(solo["speed"][-1], rel=1e-6)
    # the members differ by their own parameter, not by solver noise
    w = [res["speed"][-1] for res in batch]
    assert np.all(np.diff(w) < 0)  # more armature resistance, less speed


def test_an_invalid_member_raises_as_alone(compile_text):
    from circuitsim.errors import ParameterError

    model = compile_text(RC)
    with pytest.raises(ParameterError, match=r"R1\.R"):
        model.simulate(params={"R1.R": -1.0})
    with pytest.raises(ParameterError, match=r"R1\.R"):
        simulate_batch(model, [{"R1.R": 1000.0}, {"R1.R": -1.0}])


def test_steps_too_many_for_one_band_run_in_batches_led_by_the_point(monkeypatch):
    """Finite-difference steps from one point (``nearby``) beyond one banded block are run
    as batches each led by the point; a member's difference from the point is its own
    batch's, added to the first batch's point. On the Kim base model, ten steps of Ra in
    batches of three: every member's difference from the point agrees with the one-batch
    run's to 1e-5 and with solo runs' to 2e-5 of the difference itself (measured 1.2e-6 and
    4.5e-6), and stays proportional to its step within its curvature (1.3e-3 at ten steps):
    the differences are smooth, not solver noise."""
    from circuitsim.solve import batch as batch_mod

    model, n, sets = kim_steps(monkeypatch)
    # one process: the batches are counted here (test_fork checks the shared ones)
    monkeypatch.setenv("CIRCUITSIM_FORK", "off")
    whole = simulate_batch(model, sets, stop=0.02, rtol=1e-8, atol=1e-10, nearby=True)
    calls: list[int] = []
    one_batch = batch_mod.simulate_batch

    def counted(model, params_list, *args, **kw):
        calls.append(len(params_list))
        return one_batch(model, params_list, *args, **kw)

    monkeypatch.setattr(batch_mod, "BAND_MAX", 3 * n)
    monkeypatch.setattr(batch_mod, "simulate_batch", counted)
    chunked = counted(model, sets, stop=0.02, rtol=1e-8, atol=1e-10, nearby=True)
    assert calls == [11, 3, 3, 3, 3, 3]  # the call itself, then 5 batches of the point + 2
    assert len(chunked) == len(sets) and all(r.success for r in chunked)
    solo = [model.simulate(stop=0.02, params=q, rtol=1e-10, atol=1e-12) for q in sets]
    for j in range(1, len(sets)):
        got = chunked[j]["speed"] - chunked[0]["speed"]
        ref = whole[j]["speed"] - whole[0]["speed"]
        exact = solo[j]["speed"] - solo[0]["speed"]
        size = np.max(np.abs(exact))
        assert np.max(np.abs(got - ref)) < 1e-5 * size
        assert np.max(np.abs(got - exact)) < 2e-5 * size
        # proportional to the step: the first member's difference times j
        first = chunked[1]["speed"] - chunked[0]["speed"]
        assert np.max(np.abs(got - j * first)) < 2e-3 * size


def test_a_late_record_is_run_as_one_batch(monkeypatch):
    """A 1 ns rise at t = 0 read from t = 100 s: the batch merges its corners by the solo
    run's rule (relative to the corner's time), so it integrates as one batch. With the
    run's length as the measure it merged them, failed at t = 0 and ran each member alone."""
    from circuitsim.solve import batch as batch_mod

    model = cs.compile(cs.load(NETLISTS / "examples" / "dc_motor.yaml"))
    alone = []
    real = batch_mod._solo
    monkeypatch.setattr(batch_mod, "_solo", lambda *a, **k: alone.append(1) or real(*a, **k))
    t = np.linspace(100.0, 100.05, 51)
    runs = batch_mod.simulate_batch(model, [{"Rw.R": 1.0}, {"Rw.R": 1.01}], stop=100.05,
                                    t_eval=t)
    assert not alone and all(r.success for r in runs)
    k, V, b = 0.05, 12.0, 1e-5
    assert runs[0]["speed"] == pytest.approx(k * V / (k**2 + b * 1.0), rel=1e-6)
