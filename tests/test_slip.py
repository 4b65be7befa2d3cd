"""What a fit or a diagnosis meets first in a record: a record read in the wrong unit or with a
reversed sensor (``loop.slip``) is refused with exit 2, naming the factor, instead of a sensor
gain at the edge of its range or "something remains that I cannot name"; a slow model is
told what its diagnosis will take."""

from __future__ import annotations

import math

import numpy as np
import pytest

from circuitsim.cli.main import main
from circuitsim.loop.fit import fit_record
from circuitsim.loop.record import DataError, Record
from circuitsim.loop.slip import slip_of

from conftest import NETLISTS

MOTOR = NETLISTS / "examples" / "dc_motor.yaml"  # 12 V step on a DC motor, k_e = k_t


@pytest.fixture(scope="module")
def motor():
    """(the netlist's path, the compiled model, its run on the analysis grid)."""
    import circuitsim as cs

    model = cs.compile(cs.load(MOTOR))
    return MOTOR, model, model.simulate(stop=0.05)


def _record(run, speed: float = 1.0, current: float = 1.0, seed: int = 3) -> Record:
    """The model's run with white noise (0.5 % of each probe's spread), each probe scaled."""
    rng = np.random.default_rng(seed)
    cols = {}
    for p, k in (("speed", speed), ("i", current)):
        y = np.asarray(run[p], float)
        cols[p] = k * y + 0.005 * np.std(y) * rng.standard_normal(y.size)
    return Record(np.asarray(run.t, float), cols, "motor.csv")


@pytest.mark.parametrize(("speed", "current", "words"), [
    (60 / (2 * math.pi), 1.0, "rpm read as rad/s"),
    (2 * math.pi / 60, 1.0, "rad/s read as rpm"),
    (1.0, -1.0, "opposite sign"),
    (1.0, 1e-3, "read as milli-units"),
    (-60 / (2 * math.pi), 1.0, "rpm read as rad/s, with the sign reversed"),
])
def test_a_unit_or_sign_slip_is_refused_naming_its_factor(motor, speed, current, words):
    _, model, run = motor
    with pytest.raises(DataError) as got:
        fit_record(model, _record(run, speed, current), [], reduce=False)
    assert words in str(got.value) and "motor.csv" in str(got.value)


@pytest.mark.parametrize(("speed", "current"), [(1.0, 1.0), (0.9, 1.0), (1.0, 1.25)])
def test_a_record_the_model_meets_or_a_real_gain_is_no_slip(motor, speed, current):
    """A sensor gain of 0.9 or 1.25 is a gain (the catalog's), no unit's factor."""
    _, model, run = motor
    fit = fit_record(model, _record(run, speed, current), [], reduce=False,
                     refuse_slip=False)
    rec = _record(run, speed, current)
    assert slip_of(rec, fit.residuals, ["speed", "i"], model.meta["units"]) is None


def test_cli_diagnose_and_fit_exit_2_on_a_column_in_rpm_read_as_rad_s(motor, tmp_path, capsys):
    path, _, run = motor
    rec = _record(run, 60 / (2 * math.pi), 1.0)
    csv = tmp_path / "rec.csv"
    np.savetxt(csv, np.column_stack([rec.t, rec["speed"], rec["i"]]), delimiter=",",
               header="time [s],speed,i [A]", comments="")
    for cmd in ("diagnose", "fit"):
        assert main([cmd, str(path), str(csv), "--quiet"]) == 2
        err = capsys.readouterr().err
        assert "rpm read as rad/s" in err and "Traceback" not in err


def test_a_slow_model_is_told_what_the_diagnosis_will_take(motor, monkeypatch):
    """A model whose one simulation of the record takes long (a PWM bridge: 20 s) would be
    diagnosed for hours in silence: after the declared fit's first simulation the diagnosis
    says how long one took and what to expect, once. Here the threshold is set to 0 s."""
    import circuitsim as cs
    from circuitsim.loop.diagnose import engine

    path, _, run = motor
    lines: list[str] = []
    monkeypatch.setattr(engine, "SLOW_RUN", 0.0)
    engine.fit_declared(cs.load(path), _record(run), [], None, None, 1e-8, 4, lines.append)
    said = [s for s in lines if "one simulation of the declared model" in s]
    assert len(said) == 1 and "expect" in said[0] and "min" in said[0]
    monkeypatch.setattr(engine, "SLOW_RUN", 60.0)
    lines.clear()
    engine.fit_declared(cs.load(path), _record(run), [], None, None, 1e-8, 4, lines.append)
    assert not [s for s in lines if "one simulation" in s]


def test_a_run_that_fails_at_the_start_values_says_why(motor, monkeypatch):
    """The fit's runs are tighter than a plain run (rtol 1e-8): an inverter that runs at its
    own 1e-6 chatters there. The error carried only "fix the start values", and the user's
    `circuitsim run` then passed; it now carries the run's own message and the rtol."""
    import dataclasses

    from circuitsim.errors import SolverError

    _, model, run = motor
    real = model.simulate

    def failing(*args, **kwargs):
        res = real(*args, **kwargs)
        return dataclasses.replace(res, status=type(res.status).SOLVER_FAILED,
                                   detail="INV.Sb switched 64 times within 1.8e-12 s")

    monkeypatch.setattr(model, "simulate", failing)
    with pytest.raises(SolverError) as got:
        fit_record(model, _record(run), [], reduce=False)
    assert "INV.Sb switched 64 times" in str(got.value) and "rtol 1e-08" in str(got.value)


def test_a_periodic_record_on_a_late_clock_is_left_to_the_clock_hint():
    """A 50 Hz current whose record starts 10 ms late reads as the model's negative; its
    clock starts after its own length, so the slip check leaves it to ``clock_hints``."""
    t = 0.5 + np.linspace(0.0, 0.1, 1001)
    model_i = np.sin(2 * np.pi * 50 * t)
    rec = Record(t, {"i": -model_i}, "late.csv")
    assert slip_of(rec, {"i": -2 * model_i}, ["i"], {"i": "A"}) is None
    early = Record(t - 0.5, {"i": -model_i}, "early.csv")
    assert "opposite sign" in slip_of(early, {"i": -2 * model_i}, ["i"], {"i": "A"})


def test_of_overlapping_factors_the_one_that_mends_most_is_named():
    """57.3 (deg/s read as rad/s) and 60 (rpm read as rev/s) are both within 3 % of 58.9:
    the record is 58.8 times the model, and 60 (rpm read as rev/s) mends more."""
    t = np.linspace(0.0, 1.0, 501)
    w = 1.0 + t
    rec = Record(t, {"w": 60.0 * w * 0.98}, "w.csv")  # g = 58.8
    said = slip_of(rec, {"w": 60.0 * w * 0.98 - w}, ["w"], {"w": "rad/s"})
    assert said is not None and "rpm read as rev/s" in said


def test_the_slow_notice_waits_for_a_simulation_not_for_the_reduction(monkeypatch):
    """A long record's reduction speaks before any simulation: the notice times the first
    line the fit says after a simulation."""
    from circuitsim.loop.diagnose import engine
    from circuitsim.loop.diagnose.context import Setup

    lines: list[str] = []
    monkeypatch.setattr(engine, "SLOW_RUN", 0.0)
    setup = Setup(None, (), {}, (), 1e-8, 4, lines.append)
    hear = engine._first_run(setup)
    hear("record: 120001 rows; finding its content")
    assert not lines
    hear("start: 1 simulations, cost 12.5")
    hear("start: 2 simulations, cost 12.5")
    assert len(lines) == 1 and "one simulation of the declared model" in lines[0]


def test_a_record_kept_whole_is_fitted_whole(motor):
    """``--full-record`` (``diagnose(reduce=False)``): the declared fit works on every row
    of a long record; it was reduced again inside the fit (400 001 rows fitted on 50 001)."""
    import circuitsim as cs
    from circuitsim.loop.diagnose import engine

    path, model, _ = motor
    t = np.linspace(0.0, 0.5, 400_001)
    run = model.simulate(stop=0.5, t_eval=t)
    rng = np.random.default_rng(2)
    rec = Record(t, {p: np.asarray(run[p]) + 1e-3 * rng.standard_normal(t.size)
                     for p in ("speed", "i")}, "long.csv")
    _, state = engine.fit_declared(cs.load(path), rec, [], None, None, 1e-8, 4, None)
    assert all(np.asarray(r).size == t.size for r in state.fit.residuals.values())


@pytest.mark.parametrize(("current", "words"), [
    (1080.0, "+8.0% off the factor 1000 (a column in milli-units"),
    (3.7, "falls to"),
])
def test_a_probe_met_only_scaled_far_from_one_is_said_not_refused(motor, current, words):
    """A column in mA whose sensor reads 8 % high is 1080 times the model's run: too far from
    1000 for ``slip_of`` to refuse it, so ``scale_hints`` says it, naming the unit's factor
    it lies near; a scale of 3.7 (a gear ratio the netlist lacks) is said without one."""
    from circuitsim.loop.slip import scale_hints

    _, model, run = motor
    rec = _record(run, 1.0, current)
    fit = fit_record(model, rec, [], reduce=False, refuse_slip=False)
    assert slip_of(rec, fit.residuals, ["speed", "i"], model.meta["units"]) is None
    (hint,) = scale_hints(rec, fit.residuals, ["speed", "i"], model.meta["units"])
    assert hint.startswith(f"the record's i is {current:.4g} times") and words in hint
    assert ("off the factor" in hint) == (current > 1000)


@pytest.mark.parametrize("current", [1.0, 1.25, 0.6])
def test_a_sensor_gain_is_no_scale_to_question(motor, current):
    """Gains the catalog fits (a sensor 25 % high, 40 % low) ask nothing."""
    from circuitsim.loop.slip import scale_hints

    _, model, run = motor
    rec = _record(run, 1.0, current)
    fit = fit_record(model, rec, [], reduce=False, refuse_slip=False)
    assert scale_hints(rec, fit.residuals, ["speed", "i"], model.meta["units"]) == []


def test_the_diagnosis_says_a_probe_it_meets_only_scaled(motor):
    """End to end: the report's hints carry the scale of a current logged in mA by a sensor
    8 % high, whatever the search made of the rest."""
    from circuitsim.loop.diagnose import diagnose

    path, _, run = motor
    d = diagnose(path, _record(run, 1.0, 1080.0), [])
    assert any(h.startswith("the record's i is 1080 times") for h in d.hints)


def test_a_fit_warns_of_a_probe_it_meets_only_scaled_and_of_a_late_clock(motor):
    """``fit_record`` (the ``fit`` command) says what ``diagnose`` says: a current logged in
    mA by a sensor 8 % high, and a record whose clock starts 1 s after its own start."""
    _, model, run = motor
    fit = fit_record(model, _record(run, 1.0, 1080.0), [], reduce=False)
    assert any(w.startswith("the record's i is 1080 times") for w in fit.warnings)
    rec = _record(run)
    late = Record(rec.t + 1.0, {p: rec[p] for p in rec.names}, "late.csv")
    fit = fit_record(model, late, [], reduce=False)
    assert any("starts at t = 1 s" in w and "subtract 1 s" in w for w in fit.warnings)
    assert not fit_record(model, rec, [], reduce=False).warnings


def test_a_gross_misfit_no_slip_explains_is_said_with_its_probes(motor):
    """A record stretched tenfold in time (no clock or unit hint fits it: it starts at 0 and
    spans the netlist's own analysis) fitted R ninefold with a 2 % standard error and no
    word. The fit now says the model does not describe the record, naming each probe it
    misses by at least GROSS_MISFIT of its spread; a record the model meets says nothing."""
    from circuitsim.loop.slip import GROSS_MISFIT, gross_hints

    _, model, run = motor
    rec = _record(run)
    slow = Record(10.0 * rec.t, {p: rec[p] for p in rec.names}, "slow.csv")
    fit = fit_record(model, slow, ["R"], reduce=False)
    (said,) = [w for w in fit.warnings if w.startswith("the model misses the record by")]
    assert fit.error >= GROSS_MISFIT and "standard errors assume it does" in said
    missed = [p for p in ("speed", "i") if f"{p} by " in said]
    assert missed and all(fit.errors[p] >= GROSS_MISFIT for p in missed)
    assert gross_hints(slow, fit.residuals, 0.99 * GROSS_MISFIT) == []


@pytest.mark.parametrize("scale", [1e30, 1e-30, -1e20])
def test_a_column_scaled_far_beyond_any_unit_is_said(motor, scale):
    """A column 1e30 times the model's run: record - residual gave the model back as 0 (the
    run is lost below the column's rounding), so no scale was said and the fit's table read
    an NRMSE of 2.6 with no reason. The model's own run is used, and the sizes divided out
    before their squares (which overflow at 1e160)."""
    _, model, run = motor
    rec = _record(run)
    scaled = Record(rec.t, {"speed": rec["speed"], "i": scale * rec["i"]}, "scaled.csv")
    fit = fit_record(model, scaled, [], reduce=False)
    assert any(w.startswith(f"the record's i is {scale:.4g} times") for w in fit.warnings)


def test_an_undetermined_parameter_reads_as_such_in_the_fit_table():
    """A standard error of ten times the estimate or more is '>1000%', in its own column."""
    import dataclasses as dc

    from circuitsim.loop.fit import format_result

    fit = _fit_stub()
    text = format_result(dc.replace(fit, stderr={"R": 1.0587e7}))
    row = next(line for line in text.splitlines() if line.startswith("R "))
    assert row.split()[-2:] == [">1000%", "ohm"] and "1.0587e+07" in row.split()


def _fit_stub():
    from circuitsim.loop.fit import FitResult

    return FitResult(free=("R",), start={"R": 1.2}, estimate={"R": 7766.7}, stderr={"R": 1.0},
                     correlation=np.eye(1), condition=1.0, identifiable=True, warnings=(),
                     kind="record", success=True, message="", nfev=3, stages=(),
                     units={"R": "ohm"}, params={"R": 7766.7}, errors={"i": 0.1},
                     residuals={"i": np.zeros(3)})


def test_a_record_of_a_shaft_at_rest_throughout_reads_no_orders():
    """A record that ends before the motor starts (0.6 s of a test logged in minutes, read
    as 10 ms of rest) gives order tracking nothing to travel: no angle spectrum, no
    IndexError from an empty travel (the diagnosis had stopped with a traceback)."""
    from circuitsim.loop.diagnose.residual import on_travelled_angle

    t = np.linspace(0.0, 0.01, 201)
    assert on_travelled_angle(t, np.zeros_like(t), np.sin(t)) is None
    assert on_travelled_angle(t[:0], t[:0], t[:0]) is None
