"""Measured data (../shared/data/real, beside the project; absent on a user's clone, where
these tests skip with that reason): the diagnosis against what the data say directly.

The ODrive slow-speed log (a hobby BLDC, 12 slots and 7 pole pairs, held at 0.03 rev/s by
its position loop; MIT licence, see netlists/realdata/README.md): with the stiff-loop netlist
the logged Iq is the disturbance, so each cogging order the diagnosis names must carry the
amplitude a least-squares fit of Iq on that order's sine and cosine of the logged angle gives
(numpy alone, no model).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import circuitsim as cs
from circuitsim.loop.diagnose import diagnose
from circuitsim.loop.record import load_record

from conftest import NETLISTS, ROOT

pytestmark = pytest.mark.slow

ODRIVE_LOG = (ROOT.parent / "shared" / "data" / "real" / "odrive-bldc-cogging" /
              "slow_vel_0p03revps_no_anticogging.csv")
#: the orders of a 12-slot, 14-pole machine the log shows (the slot count, the electrical
#: period 7 and their multiples); the diagnosis must name at least these
ORDERS = (7, 12, 14, 28)


def _direct_amplitudes(angle: np.ndarray, iq: np.ndarray, orders) -> dict[int, float]:
    """Amplitude [A] of each order in Iq by linear least squares on the angle [rad]."""
    cols = [np.ones_like(angle)]
    for k in orders:
        cols += [np.cos(k * angle), np.sin(k * angle)]
    coef, *_ = np.linalg.lstsq(np.column_stack(cols), iq, rcond=None)
    return {k: float(np.hypot(coef[1 + 2 * j], coef[2 + 2 * j])) for j, k in enumerate(orders)}


@pytest.mark.skipif(not ODRIVE_LOG.exists(), reason="../shared/data/real is not beside the "
                    "project (a user's clone has no ../shared)")
def test_odrive_cogging_orders_match_the_logs_own_harmonics():
    record = load_record(ODRIVE_LOG, time="time_s", inputs=["position_rad"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        d = diagnose(cs.load(NETLISTS / "realdata" / "odrive_slow_stiff.yaml"), record,
                     probes=["iq_A"], max_effects=6)
    found = {int(e.parameters["order"]): float(np.hypot(*[v for k, v in e.parameters.items()
                                                         if k != "order"]))
             for e in d.effects if e.effect == "cogging"}
    assert set(ORDERS) <= set(found), found
    direct = _direct_amplitudes(np.asarray(record["position_rad"], float),
                                np.asarray(record["iq_A"], float), sorted(found))
    for k in ORDERS:
        # the model's closed loop filters the torque a little: 10 % or 0.03 A
        assert found[k] == pytest.approx(direct[k], rel=0.1, abs=0.03), (k, found, direct)
    assert d.error_after < 0.5 * d.error_before
