"""Energy audit: delivered = dissipated + stored + what a converter creates (issue #3, 3)."""

from __future__ import annotations

import warnings

import pytest

import circuitsim as cs
from circuitsim.solve.energy import energy_audit

from conftest import NETLISTS


def _model(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cs.compile(cs.load(path))


def test_audit_of_an_energy_conserving_motor():
    res = _model(NETLISTS / "examples" / "dc_motor.yaml").simulate(rtol=1e-10, atol=1e-13)
    a = energy_audit(res)
    assert abs(a.balance) < 1e-6 * a.total_delivered
    assert a.created["M"] == pytest.approx(0.0, abs=1e-9 * a.total_delivered)
    assert set(a.dissipated) == {"Rw", "Bv"} and set(a.stored) == {"Lw", "Jr"}
    # the inertia's stored energy is 1/2 J w^2 at the end
    assert a.stored["Jr"] == pytest.approx(0.5 * 1e-5 * res["speed"][-1] ** 2, rel=1e-12)


def test_audit_reports_the_papers_non_conserving_coupling():
    """k_t = 0.14 N m/A but k_e = 0.0162 V s/rad: the EMF hands the shaft k_t/k_e = 8.65 times
    the electrical energy it absorbs; the audit shows the created energy and still balances."""
    res = _model(NETLISTS / "kim2024" / "base.yaml").simulate(rtol=1e-9, atol=1e-12)
    a = energy_audit(res)
    el, mech = a.converted["M"]["electrical"], -a.converted["M"]["rotational"]
    assert mech / el == pytest.approx(0.14 / (0.1017 / (2 * 3.141592653589793)), rel=0.02)
    assert a.created["M"] == pytest.approx(mech - el, rel=1e-12)
    assert abs(a.balance) < 1e-6 * a.total_delivered
