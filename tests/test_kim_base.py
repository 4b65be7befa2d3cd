"""Kim & Kim 2024 base model: the paper's numbers and long-run stability (issue #2, 1 and 5).

The 8th-order ripple amplitude depends on the extraction: fitting the fundamental together with
its 2nd and 3rd harmonics (circuitsim.signal.harmonic's default) gives 0.3806444 A; a sine-only
fit, as in SOLVER-NOTES, gives 0.3806411 A because the 2.5 mA 2nd harmonic leaks in over a
non-integer number of periods. Both are inside the issue's 0.38064 +- 0.0005 A.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import circuitsim as cs
from circuitsim import signal
from circuitsim.cli.main import main

from conftest import NETLISTS
from reference import simulate_kim_lsoda, small_signal_i8

BASE = NETLISTS / "kim2024" / "base.yaml"


@pytest.fixture(scope="module")
def base_model():
    with pytest.warns(cs.CircuitWarning, match="does not conserve energy"):
        return cs.compile(cs.load(BASE))


def test_cli_run_reproduces_the_paper(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["run", str(BASE), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    speed, current = out["probes"]["speed"], out["probes"]["i_total"]
    assert speed["mean"] == pytest.approx(648.505, abs=0.01)
    assert current["mean"] == pytest.approx(1.36649, abs=1e-4)
    assert current["ripple"]["frequency"] == pytest.approx(825.70, abs=0.05)
    assert current["ripple"]["amplitude"] == pytest.approx(0.38064, abs=0.0005)
    # files were written: CSV with the probes and their units (issue 16), a PNG
    header = (tmp_path / "base.csv").read_text().splitlines()[0]
    assert header.split(",") == ["time [s]", *(f"{n} [{p['unit']}]"
                                               for n, p in out["probes"].items())]
    assert "speed [rad/s]" in header and "i_total [A]" in header
    assert (tmp_path / "base.png").read_bytes()[:4] == b"\x89PNG"


def test_base_against_lsoda_and_small_signal(base_model):
    res = base_model.simulate(rtol=1e-8, atol=1e-10)
    w = res.window(1 / 6)
    h = res.harmonic("i_total", order=8, window=1 / 6)
    assert h.frequency == pytest.approx(825.70264, abs=2e-4)
    # the small-signal formula with the mechanical feedback (REFERENCE.md): 0.3806458 A
    assert h.amplitude == pytest.approx(small_signal_i8(), rel=2e-5)
    # same extraction on the independent hand-written ODE
    t, i, omega, *_ = simulate_kim_lsoda(t_eval=res.t)
    ref = signal.harmonic(t[w], i[w], near=825.7)
    assert h.amplitude == pytest.approx(ref.amplitude, rel=2e-6)
    assert np.max(np.abs(res["speed"] - omega)) < 1e-6 * 648.5
    sine_only = signal.harmonic(res.t[w], res["i_total"][w], near=825.7,
                                harmonics_in_model=False)
    assert sine_only.amplitude == pytest.approx(0.3806411, abs=5e-7)


def test_parameters_change_without_recompiling(base_model):
    key = base_model.key
    res = base_model.simulate(stop=0.3, params={"La": 0.9e-3})
    assert base_model.key == key and res.success
    h = res.harmonic("i_total", order=8, window=1 / 6)
    assert h.amplitude == pytest.approx(small_signal_i8({"La": 0.9e-3}), rel=5e-5)


@pytest.mark.slow
def test_fig6_failure_does_not_occur_in_a_20s_run(base_model):
    """Ripple is sin(8 phi) of the rotor angle: after 20 s its amplitude equals the 0.3 s
    value within 1e-4 and no other harmonic grows (the paper's chirp does not appear)."""
    short = base_model.simulate(stop=0.3)
    long = base_model.simulate(stop=20.0, step=10e-6, keep_after=19.95, decimate=1000)
    assert long.success, long.message
    assert long.t.size < 20_000  # decimated before the analysed window
    a = short.harmonic("i_total", order=8, window=1 / 6)
    b = signal.harmonic(long.t[long.t >= 19.95], long["i_total"][long.t >= 19.95], near=825.7)
    assert b.amplitude == pytest.approx(a.amplitude, rel=1e-4)
    assert b.frequency == pytest.approx(a.frequency, abs=1e-3)

    def spectrum_without_8th(t, x, h):
        resid = x - (h.offset + h.trend * (t - (t[0] + t[-1]) / 2)
                     + h.amplitude * np.sin(2 * np.pi * h.frequency * t + h.phase))
        return signal.spectrum(t, resid)

    _fa, sa = spectrum_without_8th(short.t[short.window(1 / 6)],
                                  short["i_total"][short.window(1 / 6)], a)
    _fb, sb = spectrum_without_8th(long.t[long.t >= 19.95], long["i_total"][long.t >= 19.95], b)
    assert sb.max() <= 1.05 * sa.max() + 1e-6
