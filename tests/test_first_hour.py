"""What a new user meets first (issue 16): SPICE suffixes, an honest ripple summary, values
with units on the command line, --version, --help, op --time, pss without a shaft, plots."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import circuitsim as cs
from circuitsim.cli.main import build_parser, main
from circuitsim.errors import ParameterError
from circuitsim.signal import fisher_g_test, ripple_summary
from circuitsim.units import spice_value, unit_info

from conftest import NETLISTS

RC = NETLISTS / "examples" / "rc.yaml"
RLC = NETLISTS / "examples" / "rlc.yaml"
OHM, FARAD, METRE = (unit_info(u)[1] for u in ("ohm", "F", "m"))


@pytest.mark.parametrize("text, target, value", [
    ("10k", OHM, 1e4), ("10K", OHM, 1e4), ("2.2u", FARAD, 2.2e-6), ("1meg", OHM, 1e6),
    ("1MEG", OHM, 1e6), ("5mil", METRE, 5 * 25.4e-6), ("3f", FARAD, 3e-15), ("10 k", None, 1e4),
    ("4.7n", FARAD, 4.7e-9), ("1g", OHM, 1e9), ("2t", OHM, 2e12), ("10m", OHM, 0.01),
])
def test_spice_multipliers(text, target, value):
    assert float(spice_value(text, target)) == pytest.approx(value, rel=1e-15)


@pytest.mark.parametrize("text, target", [
    ("1F", FARAD),  # the femto trap, decided: on a capacitor F is the farad
    ("3m", METRE),  # on a length m is the metre
    ("3m", None),   # with nothing to decide, SI symbols keep their meaning
    ("2.2uF", FARAD), ("10kohm", OHM), ("1 mH", None), ("R", None), ("1e3", OHM),
])
def test_units_keep_their_si_meaning(text, target):
    assert spice_value(text, target) is None


def test_capital_m_is_refused_as_ambiguous():
    with pytest.raises(ValueError, match="'1m' \\(milli\\) or '1meg'"):
        spice_value("1M", OHM)


def test_spice_values_in_a_netlist(write_netlist):
    """R: 10k, a parameter 2k, C: 1F (farad), C: 10n; the divider settles to 2/3 of 3 V."""
    path = write_netlist("""
        title: spice
        parameters:
          Rp: 10k
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 3}
          - {name: R1, type: R, p: a, n: b, R: Rp}
          - {name: R2, type: R, p: b, n: gnd, R: 20K}
          - {name: C1, type: C, p: b, n: gnd, C: 10n}
          - {name: C2, type: C, p: a, n: gnd, C: 1F}
        probes: {v: b.v}
        analysis: {stop: 10m}
    """)
    net = cs.load(path)
    vals = {k: v.si(net.global_values()) for c in net.components for k, v in c.values.items()}
    assert vals["R1.R"] == 1e4 and vals["R2.R"] == 2e4 and vals["C1.C"] == pytest.approx(1e-8)
    assert vals["C2.C"] == 1.0 and net.analysis.stop == pytest.approx(0.01)
    res = cs.compile(net).simulate()
    # tau = (10k || 20k) * 10 nF = 67 us: settled long before 10 ms
    assert res["v"][-1] == pytest.approx(2.0, rel=1e-6)


def test_ambiguous_suffix_in_a_netlist_names_the_line(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1}
          - {name: R1, type: R, p: a, n: gnd, R: 1M}
    """)
    with pytest.raises(ParameterError, match=r"net\.yaml:3: R1: .*ambiguous"):
        cs.load(path)


def test_dimension_errors_name_the_unit(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1}
          - {name: R1, type: R, p: a, n: gnd, R: 5 uF}
    """)
    with pytest.raises(ParameterError, match=r"expected ohm \("):
        cs.load(path)


def test_spice_suffixes_on_the_command_line(capsys):
    # --set C=4u (SPICE) equals --set C=4uF: the same ringing frequency
    assert main(["run", str(RLC), "--no-files", "--json", "--set", "C=4u", "--stop", "20ms"]) == 0
    a = json.loads(capsys.readouterr().out)
    assert main(["run", str(RLC), "--no-files", "--json", "--set", "C=4uF"]) == 0
    b = json.loads(capsys.readouterr().out)
    assert a["stop"] == pytest.approx(0.02)
    assert a["probes"]["i"]["ripple"]["frequency"] == b["probes"]["i"]["ripple"]["frequency"]
    assert main(["ac", str(RLC), "--input", "V1", "--output", "v_c", "--f", "100..10k",
                 "--points", "3", "--json"]) == 0
    freqs = json.loads(capsys.readouterr().out)["frequency"]
    np.testing.assert_allclose(freqs, [100, 1000, 10000])


@pytest.mark.parametrize("args, words", [
    (["run", str(RC), "--stop", "inf"], "not a number"),
    (["run", str(RC), "--stop", "-1"], "must be > 0"),
    (["run", str(RC), "--stop", "1e400"], "not a finite value"),
    (["run", str(RC), "--stop", "5 V"], "expected s"),
    (["pss", str(RC), "--period", "0"], "must be > 0"),
])
def test_bad_command_line_values_exit_2(args, words, capsys):
    with pytest.raises(SystemExit) as info:
        main(args)
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err


def test_pss_without_a_shaft_asks_for_the_period(capsys):
    assert main(["pss", str(RC)]) == 2
    assert "--period" in capsys.readouterr().err


def test_version_and_help(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0 and capsys.readouterr().out.startswith("circuitsim 0.")
    text = build_parser().format_help()
    for verb in ("run", "sweep", "op", "ac", "pss", "fit", "diagnose", "check", "equations",
                 "components"):
        assert verb in text
    assert "Exit codes" in text
    # every option of every verb says what it does
    def missing(parser, prefix):
        for action in parser._actions:
            if isinstance(action.choices, dict):  # a group of sub-commands
                for name, sub in action.choices.items():
                    yield from missing(sub, f"{prefix} {name}")
            elif action.dest != "help" and not action.help:
                yield f"{prefix} {action.option_strings or action.dest}"

    assert list(missing(build_parser(), "circuitsim")) == []


def test_op_time_sees_a_later_source_value(write_netlist, capsys):
    """A load step at 0.2 s: op at 0 and at 0.3 s give V/2 and V/3 across R1."""
    path = write_netlist("""
        title: step load
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 6}
          - {name: R1, type: R, p: a, n: b, R: 1k}
          - {name: R2, type: R, p: b, n: gnd, R: 1k}
          - {name: I1, type: I, p: b, n: gnd, I: {step: {v0: 0, v1: 3 mA, t0: 0.2, rise: 1 ms}}}
        probes: {v: b.v}
    """)
    assert main(["op", str(path), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["probes"]["v"] == pytest.approx(3.0)
    assert main(["op", str(path), "--json", "--time", "0.3s"]) == 0
    # superposition: 3 V from the divider, minus 3 mA through 1k || 1k = 1.5 V
    assert json.loads(capsys.readouterr().out)["probes"]["v"] == pytest.approx(1.5)


# --- the ripple summary -------------------------------------------------------------------

def test_fisher_g_test_false_alarm_rate():
    """White noise: a line 'significant at 1e-2' appears in about 1 % of records."""
    rng = np.random.default_rng(7)
    p = [fisher_g_test(np.abs(np.fft.rfft(rng.normal(size=256)))[1:] ** 2)[1]
         for _ in range(2000)]
    assert 0.004 < np.mean(np.array(p) < 1e-2) < 0.02


def test_rc_step_is_settling_not_a_ripple(capsys):
    assert main(["run", str(RC), "--no-files", "--json"]) == 0
    probes = json.loads(capsys.readouterr().out)["probes"]
    assert probes["v_out"]["ripple"]["state"] == "settling"
    # the mean is the mean of the window: 1 - (exp(-4) - exp(-5)) for RC = 1 ms over 4..5 ms
    assert probes["v_out"]["mean"] == pytest.approx(1 - (math.exp(-4) - math.exp(-5)), rel=1e-3)


def test_periodic_steady_state_reports_the_line():
    t = np.linspace(0.8, 1.0, 20001)
    x = 12 + 0.008 * np.sin(2 * np.pi * 1e4 * t) + 0.002 * np.sin(2 * np.pi * 2e4 * t)
    r = ripple_summary(t, x)
    assert r.state == "periodic" and r.p_value < 1e-3
    assert r.frequency == pytest.approx(1e4, rel=1e-9) and r.amplitude == pytest.approx(0.008)
    assert r.mean == pytest.approx(12.0, abs=1e-9)


@pytest.mark.parametrize("wave, state", [
    (lambda t: np.exp(-t) * np.sin(2 * np.pi * 50 * t), "settling"),  # a decaying ring
    (lambda t: 3 + 0 * t, "none"),  # flat
    (lambda t: np.abs(np.sin(2 * np.pi * 0.5 * t)), "none"),  # one period in the window
    (lambda t: np.random.default_rng(1).normal(size=t.size), "none"),  # noise: no line
])
def test_no_ripple_is_claimed_without_a_periodic_steady_state(wave, state):
    t = np.linspace(0.0, 1.0, 2001)
    assert ripple_summary(t, wave(t)).state == state


def test_plot_title_with_dollar_and_bode_png(write_netlist, tmp_path, capsys):
    path = write_netlist("""
        title: costs $5 and $x^2$ of {braces}
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1}
          - {name: R1, type: R, p: a, n: b, R: 1k}
          - {name: C1, type: C, p: b, n: gnd, C: 1u}
        probes: {v: b.v}
        analysis: {stop: 5ms}
    """)
    png = tmp_path / "t.png"
    assert main(["run", str(path), "--out", str(tmp_path / "t.csv"), "--plot", str(png)]) == 0
    assert png.read_bytes()[:4] == b"\x89PNG"
    bode = tmp_path / "b.png"
    assert main(["ac", str(path), "--input", "V1", "--output", "v", "--f", "10..100k",
                 "--plot", str(bode)]) == 0
    assert bode.read_bytes()[:4] == b"\x89PNG"


def test_bode_phase_is_unwrapped():
    """Three RC poles: the phase runs smoothly to -270 degrees, without a 360 jump."""
    from types import SimpleNamespace

    import matplotlib

    matplotlib.use("Agg")
    from circuitsim.report import plots

    f = np.logspace(0, 5, 200)
    h = 1 / (1 + 1j * f / 100) ** 3
    res = SimpleNamespace(frequency=f, magnitude=np.abs(h), phase=np.degrees(np.angle(h)),
                          input="V1", output="v")
    captured = {}
    real = matplotlib.axes.Axes.semilogx

    def spy(self, x, y, *a, **k):
        captured.setdefault("lines", []).append(np.asarray(y))
        return real(self, x, y, *a, **k)

    matplotlib.axes.Axes.semilogx = spy
    try:
        plots._bode(res, "/dev/null")
    finally:
        matplotlib.axes.Axes.semilogx = real
    db, phase = captured["lines"]
    np.testing.assert_allclose(db, 20 * np.log10(np.abs(h)))
    assert np.all(np.diff(phase) < 0) and phase[-1] == pytest.approx(-270, abs=1)


def _run_in_pty(args: list[str]) -> tuple[int, bytes]:
    """Run the command with a pseudo-terminal (100 columns) as stdin, stdout and stderr."""
    import fcntl
    import os
    import pty
    import select
    import struct
    import subprocess
    import sys
    import termios

    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))
    proc = subprocess.Popen([sys.executable, "-m", "circuitsim.cli", *args], stdin=slave,
                            stdout=slave, stderr=slave, close_fds=True)
    os.close(slave)
    out = b""
    while select.select([master], [], [], 60)[0]:
        try:
            chunk = os.read(master, 4096)
        except OSError:  # the command ended and closed the terminal
            break
        if not chunk:
            break
        out += chunk
    os.close(master)
    return proc.wait(timeout=60), out


def test_progress_bar_on_a_terminal_only(tmp_path):
    import subprocess
    import sys

    code, out = _run_in_pty(["run", str(RC), "--no-files"])
    assert code == 0 and b"simulated:" in out and b"RC step: 0.005 s simulated" in out
    piped = subprocess.run([sys.executable, "-m", "circuitsim.cli", "run", str(RC),
                            "--no-files"], capture_output=True, text=True, timeout=120,
                           check=False)
    assert piped.returncode == 0 and "simulated:" not in piped.stderr


def test_fit_shows_progress_on_a_terminal_only(tmp_path):
    """`fit` draws a status bar (the stage, simulations so far and the cost) on a terminal;
    a pipe gets the result alone."""
    import subprocess
    import sys

    t = np.linspace(0.0, 5e-3, 501)
    v = 1 - np.exp(-t / 1.1e-3) + np.random.default_rng(0).normal(0, 1e-3, t.size)
    data = tmp_path / "rc.csv"
    data.write_text("time,v_out\n" + "".join(f"{a:.17g},{b:.17g}\n" for a, b in zip(t, v,
                                                                                 strict=True)))
    args = ["fit", str(RC), str(data), "--free", "R"]
    code, out = _run_in_pty(args)
    assert code == 0 and b"fit: " in out and b"simulations, cost" in out
    assert b"R  " in out  # the result table
    piped = subprocess.run([sys.executable, "-m", "circuitsim.cli", *args],
                           capture_output=True, text=True, timeout=120, check=False)
    assert piped.returncode == 0 and "simulations" not in piped.stderr
    assert "estimate" in piped.stdout


@pytest.mark.parametrize("args, words", [
    # an empty list left the grid without runs: IndexError in _compile_all, a traceback
    (["sweep", str(RC), "--set", "R1.R=,"], "hold no value"),
    # 1e8 points: a list of 1e8 floats, then a hang building the runs
    (["sweep", str(RC), "--set", "R1.R=1..2:lin:100000000"], "more than 100000"),
    (["sweep", str(RC), "--set", "R1.R=1..2:lin:1000", "--set", "C1.C=1u..2u:lin:1000"],
     "1000000 runs"),
    # inf Hz gave |H| = nan with exit 0; a negative frequency the conjugate's phase
    (["ac", str(RC), "--input", "V1", "--output", "v_out", "--f", "1e400"], "is inf"),
    (["ac", str(RC), "--input", "V1", "--output", "v_out", "--f=-10,10"], "-10 Hz"),
])
def test_bad_sweep_and_frequency_values_exit_2(args, words, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    try:
        code = main(args)
    except SystemExit as exc:  # argparse's own refusals
        code = exc.code
    assert code == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err


def test_an_output_step_longer_than_the_run_still_reaches_the_stop(compile_text):
    """step 2 ms for a 1 ms run rounded to a single output, t = 0: '0 s simulated', the
    values at rest as mean and final, exit 0."""
    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1}
          - {name: R1, type: R, p: a, n: b, R: 1 kohm}
          - {name: C1, type: C, p: b, n: gnd, C: 1 uF}
        probes: {v: b.v}
        analysis: {stop: 1 ms, step: 2 ms}
    """)
    res = model.simulate(rtol=1e-9, atol=1e-12)
    assert res.t[-1] == 1e-3
    assert res["v"][-1] == pytest.approx(1 - math.exp(-1), rel=1e-6)
