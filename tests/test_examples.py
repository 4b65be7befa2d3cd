"""Every shipped netlist: a header saying what it models and its key result, checks clean,
simulates from rest. The key results themselves are asserted in test_closed_forms.py and
test_kim_base.py."""

from __future__ import annotations

import warnings

import pytest

import circuitsim as cs

from conftest import NETLISTS

# netlists only: a features file (measured targets for `circuitsim fit`) lives beside them,
# and a library of subcircuits (no components of its own) is run through its users
ALL = sorted(p for p in NETLISTS.rglob("*.yaml")
             if not p.read_text().lstrip("# \n").startswith("features") and
             "\nfeatures:" not in p.read_text() and
             not ("\nsubcircuits:" in p.read_text() and "\ncomponents:" not in p.read_text()))


def test_there_are_examples():
    names = {p.name for p in ALL}
    assert {"base.yaml", "motor.yaml", "rc.yaml", "rlc.yaml", "dc_motor.yaml"} <= names


# a run of more than ~5 s belongs to the slow set (.ci/run runs it; the README command not)
SLOW = {"kapun2008/bldc.yaml", "inverters/kim_hbridge.yaml", "inverters/bldc_inverter.yaml"}


def _needs(path):
    """Marks for one netlist: slow, or skipped when the data it reads (outside the
    repository, in ../shared) is absent, as on a fresh clone."""
    marks = [pytest.mark.slow] if str(path.relative_to(NETLISTS)) in SLOW else []
    outside = [f for f in _table_files(path) if not f.is_relative_to(NETLISTS.parent)]
    missing = [f for f in outside if not f.exists()]
    if missing:
        marks.append(pytest.mark.skip(reason=f"reads {missing[0]}, which is not in this "
                                             f"checkout (the ../shared data folder)"))
    return marks


def _table_files(path):
    import re

    text = path.read_text()
    return [(path.parent / m).resolve() for m in re.findall(r"file:\s*([^,}\s]+)", text)]


CASES = [pytest.param(p, marks=_needs(p), id=str(p.relative_to(NETLISTS))) for p in ALL]


@pytest.mark.parametrize("path", CASES)
def test_netlist_header_and_run(path):
    head = path.read_text().splitlines()
    assert head[0].startswith("# ") and sum(1 for ln in head[:12] if ln.startswith("#")) >= 2
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        # a netlist reading data outside the repository (../shared) says so on purpose
        outside = any(not f.is_relative_to(NETLISTS.parent) for f in _table_files(path))
        model = cs.compile(cs.load(path, allow_outside=outside))
    res = model.simulate(stop=min(model.netlist.analysis.stop, 0.02))
    assert res.success, res.message
    for name in model.probe_names:
        assert res[name].shape == res.t.shape
