"""Every shipped netlist: a header saying what it models and its key result, checks clean,
simulates from rest. The key results themselves are asserted in test_closed_forms.py and
test_kim_base.py."""

from __future__ import annotations

import warnings

import pytest

import circuitsim as cs

from conftest import NETLISTS

# netlists only: a features file (measured targets for `circuitsim fit`) lives beside them
ALL = sorted(p for p in NETLISTS.rglob("*.yaml")
             if not p.read_text().lstrip("# \n").startswith("features") and
             "\nfeatures:" not in p.read_text())


def test_there_are_examples():
    names = {p.name for p in ALL}
    assert {"base.yaml", "motor.yaml", "rc.yaml", "rlc.yaml", "dc_motor.yaml"} <= names


@pytest.mark.parametrize("path", ALL, ids=[str(p.relative_to(NETLISTS)) for p in ALL])
def test_netlist_header_and_run(path):
    head = path.read_text().splitlines()
    assert head[0].startswith("# ") and sum(1 for ln in head[:12] if ln.startswith("#")) >= 2
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(cs.load(path))
    res = model.simulate(stop=min(model.netlist.analysis.stop, 0.02))
    assert res.success, res.message
    for name in model.probe_names:
        assert res[name].shape == res.t.shape
