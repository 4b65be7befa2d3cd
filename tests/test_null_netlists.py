"""The product's own netlists, each diagnosed on a record of its own run with white noise: the
diagnosis must find nothing, neither an effect nor a correction (a false alarm on the very
circuits the project ships). The switching inverters are left out: one run of their record
takes 10-20 s, and a diagnosis 50-900 runs (the diagnosis says so when it starts)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import circuitsim as cs
from circuitsim.loop.diagnose import diagnose
from circuitsim.loop.record import Record

from conftest import NETLISTS

CLEAN = ["examples/dc_motor.yaml", "examples/rlc.yaml", "examples/two_mass_motor.yaml",
         "breadth/drivetrain.yaml", "breadth/geared_load.yaml", "breadth/thermal_motor.yaml",
         "breadth/diode_charge.yaml", "kim2024/base.yaml", "kim2024/case4.yaml",
         "kapun2008/motor.yaml"]


def _null_record(net, seed: int = 5) -> Record:
    """The netlist's own run on its analysis grid (at most 20 000 rows), every probe that
    varies with white noise of 2 % of its spread."""
    with warnings.catch_warnings():
        # the Kim netlists declare the paper's k_t != k_e on purpose (REFERENCE.md), which
        # compile warns of; the warning is tested where it is raised
        warnings.simplefilter("ignore", cs.CircuitWarning)
        model = cs.compile(net)
    run = model.simulate()
    assert run.success, run.message
    k = max(1, -(-run.t.size // 20000))
    rng = np.random.default_rng(seed)
    cols = {}
    for p in model.probe_names:
        y = np.asarray(run[p], float)[::k]
        if np.std(y) > 0:
            cols[p] = y + 0.02 * np.std(y) * rng.standard_normal(y.size)
    return Record(np.asarray(run.t, float)[::k], cols, "null.csv")


@pytest.mark.slow
@pytest.mark.parametrize("name", CLEAN)
def test_a_netlists_own_run_holds_nothing_to_find(name):
    net = cs.load(NETLISTS / name)
    diag = diagnose(net, _null_record(net))
    assert not diag.effects and not diag.corrections, diag.summary()
