"""A ripple locked to a shaft's angle above the output grid's Nyquist frequency is said to be
an alias, with the circuit's frequency, never reported as the folded line (solve/alias.py).

The Kim & Kim motor at 200 V turned at 10 809 rad/s and ``run`` printed its 8th-order current
ripple at 6238 Hz, the 13.76 kHz ripple folded by the 50 us output grid, as a result.
"""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from circuitsim.cli.main import main
from circuitsim.solve.alias import angle_orders

# a shaft held at w = T / b = 1500 rad/s by a torque and a damper, pulled by a torque of the
# angle: its speed ripples at 3 w / 2 pi = 716.2 Hz
SHAFT = """
    parameters: {{Tq: 150}}
    components:
      - {{name: T1, type: torque, shaft: s, T: Tq}}
      - {{name: J1, type: inertia, shaft: s, J: 1e-3}}
      - {{name: B1, type: damper, shaft: s, b: 0.1}}
      - {{name: P1, type: btorque, shaft: s, expr: "{law}"}}
    probes: {{w: s.w}}
    analysis: {{stop: 1, step: {step}, rtol: 1e-9, atol: 1e-12}}
"""
LAW = "0.5*sin(3*s.phi)*1[N*m]"
F3 = 3 * 1500 / (2 * np.pi)


def test_the_orders_of_a_shafts_laws_are_read_from_the_model(compile_text):
    for law, orders in ((LAW, [3]), ("(0.2*sin(2*s.phi) + 0.1*cos(5*s.phi))*1[N*m]", [2, 5]),
                        ("-1e-3*s.w*1[N*m*s/rad]", None)):
        model = compile_text(SHAFT.format(law=law, step="1 ms"))
        y = np.full(len(model.state_names), 0.3)
        got = angle_orders(model, y, np.full_like(y, 0.1), model.param_vector())
        assert got.get("s.phi") == orders, law


def _run(write_netlist, capsys, step: str) -> dict:
    path = write_netlist(SHAFT.format(law=LAW, step=step))
    assert main(["run", str(path), "--no-files", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    return out


def test_a_ripple_above_the_grids_nyquist_is_said_to_be_an_alias(write_netlist, capsys):
    """Sampled every 1 ms (Nyquist 500 Hz), the 716.2 Hz ripple shows at 1000 - 716.2 =
    283.8 Hz: the summary gives the circuit's frequency, the line seen, the order and the
    shaft, and a warning says what step resolves it. Every 0.1 ms it is the ripple itself."""
    out = _run(write_netlist, capsys, "1 ms")
    r = out["probes"]["w"]["ripple"]
    assert r["state"] == "aliased" and r["order"] == 3 and r["shaft"] == "s"
    assert r["frequency"] == pytest.approx(F3, rel=1e-4)
    assert r["seen"] == pytest.approx(1000 - F3, rel=1e-3)
    assert any("alias" in w and "order-3 ripple of s" in w for w in out["warnings"])
    fine = _run(write_netlist, capsys, "0.1 ms")["probes"]["w"]["ripple"]
    assert fine["state"] == "periodic"
    assert fine["frequency"] == pytest.approx(F3, rel=1e-4)
    # the speed ripple of a torque a sin(3 phi) on J at speed w: a / (J 3 w), and b
    assert fine["amplitude"] == pytest.approx(0.5 / np.hypot(1e-3 * 3 * 1500, 0.1), rel=1e-2)


def test_a_sweep_row_says_its_ripple_is_an_alias(write_netlist, tmp_path, capsys):
    path = write_netlist(SHAFT.format(law=LAW, step="1 ms"))
    table = tmp_path / "sweep.csv"
    assert main(["sweep", str(path), "--set", "Tq=150", "--jobs", "1", "--out", str(table),
                 "--quiet", "--no-energy"]) == 0
    (row,) = csv.DictReader(table.open())
    assert row["w.ripple_state"] == "aliased"
    assert float(row["w.ripple_freq"]) == pytest.approx(F3, rel=1e-4)
    assert "order-3 ripple of s" in row["message"]


def test_the_apis_dominant_ripple_warns_when_it_is_an_alias(compile_text):
    from circuitsim.errors import CircuitWarning

    res = compile_text(SHAFT.format(law=LAW, step="1 ms")).simulate()
    with pytest.warns(CircuitWarning, match="order-3 ripple of s"):
        h = res.harmonic("w")
    assert h.frequency == pytest.approx(1000 - F3, rel=1e-3)  # the samples' line, said so
    with pytest.raises(ValueError, match="Nyquist"):  # asked for by its order: refused
        res.harmonic("w", order=3)


def test_run_step_sets_the_output_grid_and_resolves_the_alias(write_netlist, capsys):
    """``run --step``, as the alias's words advise: the 1 ms netlist read every 0.1 ms shows
    the ripple itself; a step of 0, or beyond the stop time, is refused with exit 2."""
    path = write_netlist(SHAFT.format(law=LAW, step="1 ms"))
    assert main(["run", str(path), "--no-files", "--json", "--step", "0.1ms"]) == 0
    r = json.loads(capsys.readouterr().out)["probes"]["w"]["ripple"]
    assert r["state"] == "periodic" and r["frequency"] == pytest.approx(F3, rel=1e-4)
    for bad in ("0", "2s"):  # argparse's refusal exits, the run's returns: both code 2
        try:
            code = main(["run", str(path), "--no-files", "--step", bad])
        except SystemExit as exc:
            code = exc.code
        assert code == 2
    assert "at most the stop time" in capsys.readouterr().err
