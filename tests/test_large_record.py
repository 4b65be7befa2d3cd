"""Long records: brought to the resolution their content needs, with the noise kept honest
(issue 16: a 1-million-row record fits and diagnoses, with progress, in memory a small
multiple of the data).

The reference is an independent closed form (``reference.dc_motor_sine``): the DC motor of
tests/data/dc_motor_sine.yaml is linear, x' = A x + B V(t) with x = (i, w) and V = 6 V + 6 V
sin(2 pi 5 Hz t) from rest, so its response is a constant, a sinusoid and a matrix
exponential -- no integrator involved.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from circuitsim.loop.diagnose.residual import ljung_box, noise_sigma
from circuitsim.loop.record import Record
from circuitsim.loop.reduce import WORK_ROWS, reduce_record

from conftest import HERE
from reference import dc_motor_sine

MOTOR = HERE / "data" / "dc_motor_sine.yaml"
TRUE = {"R": 1.0, "L": 1e-3, "k": 0.05, "J": 1e-5, "b": 1e-5}
NOISE = {"i": 2e-3, "w": 0.2}  # [A], [rad/s], white


def motor_response(t: np.ndarray) -> np.ndarray:
    """(i [A], w [rad/s]) of the motor of MOTOR, by the closed form."""
    return dc_motor_sine(t, **TRUE)


def motor_record(rows: int, seed: int = 0) -> Record:
    t = np.linspace(0.0, 1.0, rows)
    x = motor_response(t)
    rng = np.random.default_rng(seed)
    return Record(t, {"i": x[0] + rng.normal(0, NOISE["i"], rows),
                      "w": x[1] + rng.normal(0, NOISE["w"], rows)}, f"motor {rows}")


def write_record(path: Path, rec: Record, header: str = "time,i,w") -> None:
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(header + "\n")
        np.savetxt(fh, np.column_stack([rec.t, rec["i"], rec["w"]]), delimiter=",",
                   fmt="%.17g")


def test_the_closed_form_is_the_simulated_motor(compile_text):
    import circuitsim as cs

    model = cs.compile(cs.load(MOTOR, allow_outside=True))
    t = np.linspace(0.0, 1.0, 2001)
    res = model.simulate(t_eval=t)
    x = motor_response(t)
    assert np.max(np.abs(res["i"] - x[0])) < 1e-6 and np.max(np.abs(res["w"] - x[1])) < 1e-5


def test_a_short_record_is_used_as_it_is():
    rec = motor_record(2 * WORK_ROWS - 1)
    out, red = reduce_record(rec)
    assert out is rec and red.factor == 1 and not red.reduced


def test_an_oversampled_record_is_reduced_and_its_noise_shrinks_by_sqrt_q():
    """400 000 rows at 400 kHz of a motor whose content ends near a few kHz: every 8th row
    (the 50 000-row floor) after the filter; the signal comes through to within the working
    noise, which is sigma / sqrt(8), white, and what the diagnosis's noise estimate reads."""
    rec = motor_record(400_000)
    out, red = reduce_record(rec)
    assert red.factor == 8 and red.working_rows == out.t.size == 50_000
    assert red.content < red.passband / 2  # the margin the choice promises
    np.testing.assert_array_equal(out.t, rec.t[::8])  # the original sample times
    x = motor_response(out.t)
    for k, p in enumerate(("i", "w")):
        e = out[p] - x[k]
        sigma = NOISE[p] / np.sqrt(8)
        assert abs(np.std(e) / sigma - 1) < 0.02  # 50 000 samples: 0.3 % standard error
        assert abs(np.mean(e)) < 4 * sigma / np.sqrt(e.size)
        assert np.max(np.abs(e)) < 5.5 * sigma  # no edge or transient error above the noise
        assert ljung_box(e)[1] > 1e-3
        assert abs(noise_sigma(e) / sigma - 1) < 0.05


def test_content_to_the_nyquist_frequency_is_not_reduced():
    """A chirp up to 0.4 of the sample rate: nothing is oversampled, nothing is dropped."""
    t = np.arange(300_000) / 1e5
    sweep = np.sin(2 * np.pi * (0.5 * 4e4 / t[-1]) * t**2)
    rec = Record(t, {"i": sweep + np.random.default_rng(1).normal(0, 0.1, t.size)})
    out, red = reduce_record(rec)
    assert out is rec and red.factor == 1 and "not oversampled" in red.reason


def test_a_weak_high_line_keeps_the_rate_that_holds_it():
    """A 20 kHz line of a tenth of the noise's size on a slow signal sampled at 200 kHz is
    significant in the record (a periodogram line 2500x the noise bin), so the working
    Nyquist frequency stays above it, with the margin: here that is the record's own."""
    t = np.arange(1_000_000) / 2e5
    rng = np.random.default_rng(2)
    line = 0.1 * np.sin(2 * np.pi * 2e4 * t)
    rec = Record(t, {"x": np.sin(2 * np.pi * 3 * t) + line + rng.normal(0, 1.0, t.size)})
    out, red = reduce_record(rec)
    # content is resolved to the quarter-octave band that holds the line
    assert 2e4 <= red.content <= 2e4 * 2**0.25
    assert out is rec and red.factor == 1  # 0.15 fs / 20 kHz = 1.5: every row is needed
    slow = Record(t, {"x": np.sin(2 * np.pi * 3 * t) + rng.normal(0, 1.0, t.size)})
    assert reduce_record(slow)[1].factor == 20  # without the line: down to 50 000 rows


def test_a_jittered_time_axis_is_resampled_onto_a_uniform_one():
    rows = 200_000
    rng = np.random.default_rng(3)
    t = np.linspace(0.0, 1.0, rows)
    t[1:-1] += rng.uniform(-0.2, 0.2, rows - 2) * (t[1] - t[0])
    x = motor_response(t)
    out, red = reduce_record(Record(t, {"i": x[0] + rng.normal(0, NOISE["i"], rows),
                                        "w": x[1] + rng.normal(0, NOISE["w"], rows)}))
    assert red.resampled and red.factor == 4
    assert np.ptp(np.diff(out.t)) < 1e-9
    x = motor_response(out.t)
    for k, p in enumerate(("i", "w")):
        e = out[p] - x[k]
        # interpolating between samples 5 us apart moves no signal; it averages neighbouring
        # samples, so the working noise is at most sigma / sqrt(4)
        assert 0.6 < np.std(e) / (NOISE[p] / 2) < 1.02
        assert abs(np.mean(e)) < 4 * NOISE[p] / 2 / np.sqrt(e.size)


def test_fit_reports_the_reduction_and_its_progress():
    import warnings

    import circuitsim as cs
    from circuitsim.loop.fit import fit_record, format_result

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(cs.load(MOTOR, allow_outside=True))
    said: list[str] = []
    fit = fit_record(model, motor_record(200_000), ["k"], progress=said.append)
    assert fit.reduction.factor == 4 and fit.sim.t.size == 50_000
    assert fit.estimate["k"] == pytest.approx(TRUE["k"], rel=1e-5)
    assert any(m.startswith("record: filtering") for m in said)
    assert any(m.startswith("waveform: ") and "simulations, cost" in m for m in said)
    assert "200000 rows reduced to 50000" in format_result(fit)
    assert fit.as_dict()["record"]["working_rows"] == 50_000


@pytest.mark.slow
def test_reduced_fit_has_the_estimates_and_standard_errors_of_the_full_fit():
    """The dropped band holds only noise, so the information is the same: estimates agree to
    a fraction of a standard error and the standard errors to a few percent (300 000 rows,
    reduced 6x; the full fit is the one a user gets with --full-record)."""
    import warnings

    import circuitsim as cs
    from circuitsim.loop.fit import fit_record

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(cs.load(MOTOR, allow_outside=True))
        rec = motor_record(300_000, seed=4)
        free = ["R", "k", "J"]
        reduced = fit_record(model, rec, free)
        full = fit_record(model, rec, free, reduce=False)
    assert reduced.reduction.factor == 6 and full.reduction is None
    for n in free:
        se = full.stderr[n]
        assert abs(reduced.estimate[n] - full.estimate[n]) < 0.3 * se, n
        assert reduced.stderr[n] == pytest.approx(se, rel=0.05), n
        assert abs(full.estimate[n] - TRUE[n]) < 4 * se, n


CHILD = textwrap.dedent("""
    import json, resource, sys, time, warnings
    import circuitsim as cs
    from circuitsim.loop.diagnose import diagnose
    from circuitsim.loop.fit import fit_record
    from circuitsim.loop.record import load_record
    warnings.simplefilter("ignore")
    net = cs.load(sys.argv[1], allow_outside=True)
    model = cs.compile(net)
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    t0 = time.perf_counter()
    rec = load_record(sys.argv[2], model.probe_names)
    fit = fit_record(model, rec, ["R", "k", "J"])
    t1 = time.perf_counter()
    diag = diagnose(net, rec, ["R", "k", "J"], max_effects=1)
    t2 = time.perf_counter()
    print(json.dumps({"base": base, "peak": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
                      / 1024, "fit_s": t1 - t0, "diagnose_s": t2 - t1,
                      "estimate": fit.estimate, "stderr": fit.stderr,
                      "factor": fit.reduction.factor, "rows": fit.reduction.rows,
                      "diag_rows": diag.reduction.working_rows, "effects": len(diag.effects),
                      "final": {k: v["estimate"] for k, v in diag.final_parameters().items()}}))
""")


@pytest.mark.slow
def test_a_million_rows_fit_and_diagnose_in_a_small_multiple_of_the_data(tmp_path):
    """1 000 000 rows (time and two probes, 59 MB of CSV, 24 MB as float64) in a fresh
    process: the fit recovers R, k and J within 4 standard errors of the closed form's values,
    the diagnosis returns (the record has nothing the netlist lacks: no effect), and the
    process grows by less than 8x the numbers (3.3x the file) over its size after imports."""
    path = tmp_path / "big.csv"
    write_record(path, motor_record(1_000_000, seed=5))
    size = path.stat().st_size
    out = subprocess.run([sys.executable, "-c", CHILD, str(MOTOR), str(path)],
                         capture_output=True, text=True, timeout=1500, check=True)
    got = json.loads(out.stdout.strip().splitlines()[-1])
    assert got["rows"] == 1_000_000 and got["factor"] == 20 and got["diag_rows"] == 50_000
    for n in ("R", "k", "J"):
        assert abs(got["estimate"][n] - TRUE[n]) < 4 * got["stderr"][n], n
        assert got["stderr"][n] < 1e-4 * TRUE[n], n  # a million rows pin them down
        assert got["final"][n] == pytest.approx(got["estimate"][n], rel=1e-4), n
    assert got["effects"] == 0
    data = 1_000_000 * 3 * 8
    assert got["peak"] - got["base"] < 8 * data / 2**20, (got, size)
