"""The command line: run/check/equations/components, exit codes, --set with units."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from circuitsim.cli.main import component_table, main

from conftest import NETLISTS, ROOT

RLC = NETLISTS / "examples" / "rlc.yaml"
BASE = NETLISTS / "kim2024" / "base.yaml"


def test_run_writes_csv_and_png(tmp_path, capsys):
    out, png = tmp_path / "w.csv", tmp_path / "w.png"
    assert main(["run", str(RLC), "--out", str(out), "--plot", str(png)]) == 0
    text = capsys.readouterr().out
    assert "v_c" in text and "csv:" in text
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    assert data[-1, 0] == pytest.approx(0.02)
    assert data[:, 1].max() == pytest.approx(1.8545, abs=1e-3)  # overshoot in the header
    assert png.read_bytes()[:4] == b"\x89PNG"
    assert not list(tmp_path.glob(".circuitsim-*"))  # no temporary left behind


def test_set_overrides_with_units(capsys):
    assert main(["run", str(RLC), "--no-files", "--json", "--set", "C=4uF"]) == 0
    out = json.loads(capsys.readouterr().out)
    # RLC ringing frequency 1/(2 pi sqrt(L C)) * sqrt(1 - zeta^2), zeta = 0.1 with C = 4 uF
    f = 1 / (2 * np.pi * np.sqrt(10e-3 * 4e-6)) * np.sqrt(1 - 0.1**2)
    assert out["probes"]["i"]["ripple"]["frequency"] == pytest.approx(f, rel=2e-2)


def test_a_window_of_too_few_points_says_so(write_netlist, capsys):
    # an output step as long as the run leaves the window one point: 'no periodic ripple' was
    # a claim nobody could have checked
    path = write_netlist(RLC.read_text(encoding="utf-8").replace(
        "analysis: {stop: 20 ms, step: 2 us", "analysis: {stop: 1 ms, step: 1 ms"))
    assert main(["run", str(path), "--no-files", "--json"]) == 0
    ripple = json.loads(capsys.readouterr().out)["probes"]["v_c"]["ripple"]
    assert ripple["state"] == "too few points" and ripple["points"] == 1
    assert main(["run", str(path), "--no-files"]) == 0
    assert "too few to judge" in capsys.readouterr().out


def _sweep(tmp_path, *flags: str) -> int:
    return main(["sweep", str(RLC), "--set", "C=1uF,2uF", "--out", str(tmp_path / "s.csv"),
                 "--quiet", "--jobs", "1", "--stop", "1ms", *flags])


@pytest.mark.parametrize("order", ["0", "-2"])
def test_bad_sweep_flags_exit_2_before_any_run(tmp_path, capsys, order):
    assert _sweep(tmp_path, "--jobs", "0") == 2
    assert "--jobs is a whole number >= 1" in capsys.readouterr().err
    with pytest.raises(SystemExit) as ei:  # argparse's own refusal
        _sweep(tmp_path, "--order", order)
    assert ei.value.code == 2 and "argument --order" in capsys.readouterr().err
    assert not (tmp_path / "s.csv").exists()


def test_an_unknown_sweep_metric_keeps_the_table_and_lists_the_columns(tmp_path, capsys):
    out, png = tmp_path / "s.csv", tmp_path / "s.png"
    code = _sweep(tmp_path, "--plot", str(png), "--metric", "v_c.maen")
    err = capsys.readouterr().err
    assert code == 2 and "--metric v_c.maen: the table has no such column" in err
    assert "v_c.mean" in err  # the column meant is listed
    assert len(out.read_text(encoding="utf-8").splitlines()) == 3 and not png.exists()


def test_set_an_ambient_in_fahrenheit(capsys):
    thermal = str(NETLISTS / "breadth" / "thermal_motor.yaml")
    means = []
    for ambient in ("T_amb=68degF", "T_amb=293.15K"):
        assert main(["run", thermal, "--no-files", "--json", "--stop", "60s", "--set",
                     ambient]) == 0
        means.append(json.loads(capsys.readouterr().out)["probes"]["T_winding"]["mean"])
    assert means[0] == pytest.approx(means[1], abs=1e-9)
    assert main(["run", thermal, "--no-files", "--set", "V=20 degC"]) == 2  # not 293 kV
    assert "has dimension K" in capsys.readouterr().err


@pytest.mark.parametrize("setting, words", [
    ("C=5ohm", "dimension"),
    ("Nope=1", "unknown parameter 'Nope'"),
    ("C=-1uF", "must be positive"),
    ("C=__import__('os')", "unknown function"),
])
def test_bad_set_exits_2(capsys, setting, words):
    assert main(["run", str(RLC), "--no-files", "--set", setting]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and words in err and "Traceback" not in err


def test_solver_failure_exits_1(write_netlist, capsys):
    """A Coulomb friction sharpened to 1e-14 rad/s is effectively discontinuous: IDA gives up,
    and the message names the time and the variable."""
    path = write_netlist("""
        components:
          - {name: T1, type: torque, shaft: s, T: {sine: {amplitude: 1, freq: 50 Hz}}}
          - {name: Jr, type: inertia, shaft: s, J: 1e-6}
          - {name: F1, type: friction, shaft: s, tau_c: 0.5, w_brk: 1e-14}
        probes: {w: s.w}
        analysis: {stop: 0.1, rtol: 1e-10, atol: 1e-14}
    """)
    assert main(["run", str(path), "--no-files"]) == 1
    err = capsys.readouterr().err
    assert "at t = " in err and "s.w" in err


@pytest.mark.parametrize("gain", ["1", "0.5"])
def test_equations_singular_at_their_values_are_named_as_such(write_netlist, capsys, gain):
    """A VCVS of gain 1 on its own input: v = 1 * v holds for any v. Structurally sound, it
    failed as 'convergence failed; fastest-changing variable' as if a tolerance were the
    trouble. At gain 0.5 the same circuit is regular (v = 0) and runs."""
    path = write_netlist(f"""
        components:
          - {{name: E1, type: E, p: a, n: gnd, cp: a, cn: gnd, gain: {gain}}}
          - {{name: R1, type: R, p: a, n: gnd, R: 1 ohm}}
        probes: {{v: a.v}}
        analysis: {{stop: 1 ms}}
    """)
    code = main(["run", str(path), "--no-files"])
    err = capsys.readouterr().err
    if gain == "0.5":
        assert code == 0, err
        return
    assert code == 1
    assert "The equations are singular here, whatever the step" in err
    assert "R1.p.i" in err and "fastest-changing" not in err


def test_check_and_equations(capsys):
    assert main(["check", str(BASE)]) == 0
    out = capsys.readouterr().out
    assert "25 equations, 25 unknowns" in out and "4 unknowns (4 differential" in out
    assert "does not conserve energy" in out and out.rstrip().endswith("ok")
    assert main(["equations", str(BASE)]) == 0
    eqs = capsys.readouterr().out
    assert "der(" not in eqs and "rotor.w'" in eqs and "[KCL at node a]" in eqs
    assert main(["equations", str(BASE), "--reduced", "--latex"]) == 0
    assert "\\quad" in capsys.readouterr().out


def test_components_table_is_in_readme(capsys):
    assert main(["components"]) == 0
    listing = capsys.readouterr().out
    for name in ("emf", "varistor", "inertia", "friction", "cogging", "torque", "mass"):
        assert name in listing
    assert component_table(markdown=True) in (ROOT / "README.md").read_text()


def test_console_script_entry_point(tmp_path):
    """The installed `circuitsim` command, as a user runs it."""
    proc = subprocess.run([sys.executable, "-m", "circuitsim.cli", "run", str(RLC), "--json",
                           "--no-files"], capture_output=True, text=True, cwd=tmp_path,
                          timeout=120, check=False)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["probes"]["v_c"]["mean"] == pytest.approx(1.0, abs=1e-3)


def test_a_probe_without_a_real_value_is_an_error_not_a_nan(write_netlist, capsys):
    """(-1 V)^1.5 has no real value: run and op must fail naming the probe (exit 1), not
    print nan with exit 0 or a traceback."""
    from circuitsim.cli.main import main

    path = write_netlist("""
        title: sq
        components:
          - {name: V1, type: V, p: b, n: gnd, V: -1}
          - {name: B1, type: BI, p: b, n: gnd, expr: "1e-4*(b.v)^1.5"}
        probes: {i: B1.i}
        analysis: {stop: 1e-3}
    """)
    assert main(["run", str(path), "--no-files"]) == 1
    assert "probe 'i' is nan" in capsys.readouterr().err
    assert main(["op", str(path)]) == 1
    assert "probe 'i' is nan" in capsys.readouterr().err


@pytest.mark.parametrize("order, words", [("3", "the circuit has no shaft angle"),
                                          ("0", "a whole number >= 1")])
def test_ac_order_without_a_shaft_or_below_one_is_bad_input(capsys, order, words):
    """`ac --order 3` on a circuit with no shaft ended in a ValueError's traceback."""
    rc = main(["ac", str(RLC), "--output", "v_c", "--order", order])
    assert rc == 2 and words in capsys.readouterr().err
