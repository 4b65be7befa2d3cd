"""The effect catalog: every candidate is a netlist patch that is exact at its null value and
does its physics away from it (issue #5, catalog)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import circuitsim as cs
from circuitsim.loop import effects
from circuitsim.netlist import build
from circuitsim.solve.op import operating_point, probe_values

from conftest import NETLISTS

CASE1 = NETLISTS / "kim2024" / "case1.yaml"


def _compile(net):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cs.compile(net)


def test_catalog_covers_the_interface_ids():
    net = cs.load(CASE1)
    found = {c.effect for c in effects.candidates(net, {"rotor": [8]})}
    assert found == set(effects.CATALOG_IDS)


def test_every_patch_is_exact_at_its_null_value():
    net = cs.load(CASE1)
    base = _compile(net).simulate(stop=0.02, rtol=1e-10, atol=1e-12)
    for c in effects.candidates(net, {"rotor": [2]}):
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
