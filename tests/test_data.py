"""Measured records and feature files: parsing, and every error naming file, row/column, fix."""

from __future__ import annotations

import math
import textwrap
import warnings
from typing import ClassVar

import numpy as np
import pytest

from circuitsim.loop.record import (
    DataError,
    Feature,
    FeatureSet,
    load_data,
    load_features,
    load_record,
)

PROBES = ("speed", "i_total")


def _csv(tmp_path, text: str, name: str = "rec.csv"):
    p = tmp_path / name
    p.write_text(textwrap.dedent(text).lstrip("\n"), encoding="utf-8")
    return p


def _rows(n: int = 10, dt: float = 1e-3) -> str:
    return "".join(f"{k * dt:g},{600 + k},{1.5 - 0.01 * k}\n" for k in range(n))


def test_uniform_record_round_trip(tmp_path):
    p = _csv(tmp_path, "time,speed,i_total\n" + _rows())
    rec = load_record(p, PROBES)
    assert rec.names == ("speed", "i_total")
    np.testing.assert_allclose(rec.t, np.arange(10) * 1e-3)
    np.testing.assert_allclose(rec["speed"], 600 + np.arange(10))
    assert rec.uniform


def test_non_uniform_record_and_subset_of_probes(tmp_path):
    t = np.cumsum(np.r_[0.0, np.linspace(1e-4, 3e-4, 11)])
    body = "".join(f"{math.sin(x)!r},{float(x)!r}\n" for x in t)
    rec = load_record(_csv(tmp_path, "i_total,time\n" + body), PROBES)
    assert not rec.uniform
    np.testing.assert_array_equal(rec.t, t)  # repr round-trips exactly
    np.testing.assert_array_equal(rec["i_total"], np.sin(t))


def test_input_columns_are_accepted(tmp_path):
    p = _csv(tmp_path, "time,speed,v_ref\n" + _rows())
    assert load_record(p, PROBES, inputs=["v_ref"]).names == ("speed", "v_ref")


def _error(call) -> str:
    with pytest.raises(DataError) as info:
        call()
    assert info.value.exit_code == 2
    return str(info.value)


@pytest.mark.parametrize("text, where, words", [
    ("", "rec.csv", ["empty", "header row"]),
    ("\n\n", "rec.csv", ["empty"]),
    ("0,1,2\n" + _rows(), "rec.csv:1", ["no header row", "Add a first row"]),
    ("time,speed,i_total\n" + _rows(3), "rec.csv:4", ["3 data rows", "at least 8"]),
    ("time,,i_total\n" + _rows(), "rec.csv:1", ["column 2", "no name", "Name it"]),
    ("time,speed,speed\n" + _rows(), "rec.csv:1", ["'speed' appears twice", "Keep one"]),
    ("Time,speed,i_total\n" + _rows(), "rec.csv:1",
     ["no 'time' column", "did you mean 'Time'", "Name the time column 'time'"]),
    ("time,speeed,i_total\n" + _rows(), "rec.csv:1",
     ["column 'speeed'", "not a probe", "did you mean 'speed'", "Rename the column"]),
    ("time,v_ref\n" + "".join(f"{k},{k}\n" for k in range(9)), "rec.csv:1",
     ["not a probe"]),
    ("time,speed,i_total\n" + _rows(4) + "0.004,1\n" + _rows(5, 1e-3).replace("0,", "9,", 1),
     "rec.csv:6", ["row 6 has 2 values", "header has 3", "remove the stray comma"]),
    ("time,speed,i_total\n" + _rows(4) + "0.004,1 rpm,2\n" + _rows(5),
     "rec.csv:6", ["row 6, column 'speed'", "'1 rpm' is not a number", "SI units"]),
    ("time,speed,i_total\n" + _rows(4) + "0.004,nan,2\n" + _rows(5),
     "rec.csv:6", ["row 6, column 'speed'", "missing or NaN", "interpolate"]),
    ("time,speed [degC],i_total\n" + _rows(9), "rec.csv:1",
     ["column 'speed [degC]'", "offset unit", "scaled by 274.15, not shifted"]),
    ("time,speed,i_total\n" + _rows(4) + "0.004,-inf,2\n" + _rows(5),
     "rec.csv:6", ["row 6, column 'speed'", "is -inf (infinite", "interpolate"]),
    ("time,speed,i_total\n" + _rows(4) + "0.004,,2\n" + _rows(5),
     "rec.csv:6", ["row 6, column 'speed'", "empty", "missing"]),
    ("time,speed,i_total\n-0.001,1,2\n" + _rows(8), "rec.csv:2",
     ["starts at -0.001 s", "shift the time axis"]),
    ("time,speed,i_total\n" + "".join(f"{1.7e9 + k * 1e-3!r},1,2\n" for k in range(9)),
     "rec.csv:2", ["starts at 1700000000 s", "times the record's own length",
                   "Unix time", "subtract the first time"]),
    ("time,speed,i_total\n" + _rows(5) + _rows(4), "rec.csv:7",
     ["time does not increase at row 7", "0 s after 0.004 s in row 6", "Sort the rows"]),
    ("time,speed,i_total\n" + _rows(4) + "0.004,1e300,2\n" + _rows(5),
     "rec.csv:6", ["row 6, column 'speed' is 1e+300", "square overflows", "correct it"]),
    ("time,speed,i_total\n", "rec.csv:1", ["0 data rows", "at least 8"]),
    ("time;speed;i_total\n" + _rows().replace(",", ";"), "rec.csv:1",
     ["separates its columns by semicolons", "decimal points"]),
    ("time\tspeed\ti_total\n" + _rows().replace(",", "\t"), "rec.csv:1",
     ["separates its columns by tabs", "comma-separated"]),
    ("# bench 3, 2026-11-30\ntime,speed,i_total\n" + _rows(), "rec.csv:1",
     ["starts with a comment line", "Delete the lines above the header"]),
    ("\x00\x01\x02\n" + _rows(), "rec.csv:1", ["not a text CSV", "control characters"]),
])
def test_record_errors_name_file_row_column_and_fix(tmp_path, text, where, words):
    p = _csv(tmp_path, text)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the error alone: no library's warning before it
        msg = _error(lambda: load_record(p, PROBES))
    assert where in msg, msg
    for w in words:
        assert w in msg, (w, msg)


def test_record_without_probe_columns(tmp_path):
    p = _csv(tmp_path, "time,v_ref\n" + "".join(f"{k},{k}\n" for k in range(9)))
    msg = _error(lambda: load_record(p, PROBES, inputs=["v_ref"]))
    assert "no column for any probe" in msg and "Name each measured column" in msg


def test_missing_and_unreadable_files(tmp_path):
    msg = _error(lambda: load_record(tmp_path / "nope.csv", PROBES))
    assert "nope.csv" in msg and "not found" in msg and "Check the path" in msg
    (tmp_path / "bin.csv").write_bytes(b"time,speed\n\xff\xfe\x00")
    assert "not UTF-8" in _error(lambda: load_record(tmp_path / "bin.csv", PROBES))
    assert "unknown kind '.mat'" in _error(lambda: load_data(tmp_path / "r.mat"))


# ----------------------------------------------------------------------- features

def _yaml(tmp_path, text: str, name: str = "feat.yaml"):
    p = tmp_path / name
    p.write_text(textwrap.dedent(text).lstrip("\n"), encoding="utf-8")
    return p


def test_features_with_units_are_si(tmp_path):
    p = _yaml(tmp_path, """
        title: targets
        features:
          - {kind: mean, probe: speed, value: 6200 rpm, sigma: 50 rpm}
          - {kind: harmonic, probe: i_total, order: 8, amplitude: 380 mA,
             frequency: 825.84 Hz, sigma_frequency: 0.1 Hz}
          - {kind: mean, probe: i_total, value: 1.37}
        """)
    fs = load_data(p)
    assert isinstance(fs, FeatureSet) and fs.title == "targets" and len(fs) == 4
    speed, amp, freq, cur = fs.features
    assert speed.value == pytest.approx(6200 * 2 * math.pi / 60, rel=1e-12)
    assert speed.sigma == pytest.approx(50 * 2 * math.pi / 60, rel=1e-12)
    assert (amp.quantity, amp.order, amp.value, amp.sigma) == ("amplitude", 8, 0.38, None)
    assert (freq.quantity, freq.value, freq.sigma) == ("frequency", 825.84, 0.1)
    assert cur.value == 1.37 and cur.dim is None
    assert str(speed.loc).endswith("feat.yaml:3")


class _Model:
    """Just what FeatureSet.check reads from a compiled model."""

    probe_names = PROBES
    meta: ClassVar[dict] = {"units": {"speed": "rad/s", "i_total": "A"}}


@pytest.mark.parametrize("body, line, words", [
    ("", None, ["empty"]),
    ("- 1\n", 1, ["YAML mapping with a list 'features:'"]),
    ("features: []\n", 1, ["non-empty list"]),
    ("features:\n  - {kind: mean, probe: speed, value: 1}\ncomment: x\n", 3,
     ["unknown key 'comment'"]),
    ("features:\n  - [mean, speed]\n", 2, ["feature 1 must be a mapping"]),
    ("features:\n  - {kind: rms, probe: speed, value: 1}\n", 2,
     ["kind must be one of mean, harmonic", "'rms'"]),
    ("features:\n  - {kind: mean, probe: speed, valeu: 1}\n", 2,
     ["unknown key 'valeu'", "did you mean 'value'"]),
    ("features:\n  - {kind: mean, value: 1}\n", 2, ["needs 'probe: NAME'"]),
    ("features:\n  - {kind: mean, probe: speed}\n", 2, ["needs 'value:'", "6200 rpm"]),
    ("features:\n  - {kind: mean, probe: speed, value: \"__import__('os')\"}\n", 2,
     ["feature 1: value", "Write a number with an optional unit"]),
    ("features:\n  - {kind: mean, probe: speed, value: 2*w0}\n", 2,
     ["names (w0) are not allowed"]),
    ("features:\n  - {kind: mean, probe: speed, value: 1 zorkmids}\n", 2,
     ["unknown unit"]),
    ("features:\n  - {kind: mean, probe: speed, value: 1, sigma: -2}\n", 2,
     ["sigma must be positive"]),
    ("features:\n  - {kind: mean, probe: speed, value: 600 rpm, sigma: 1 A}\n", 2,
     ["sigma has dimension", "same kind of unit"]),
    ("features:\n  - {kind: harmonic, probe: i_total, amplitude: 1 A}\n", 2,
     ["needs 'order:'", "per shaft revolution"]),
    ("features:\n  - {kind: harmonic, probe: i_total, order: 0, amplitude: 1 A}\n", 2,
     ["order must be positive"]),
    ("features:\n  - {kind: harmonic, probe: i_total, order: 8}\n", 2,
     ["needs 'amplitude:' or 'frequency:'"]),
    (("features:\n  - {kind: harmonic, probe: i_total, order: 8, frequency: 800 Hz, "
      "sigma: 1 Hz}\n"), 2, ["'sigma' is the amplitude's", "sigma_frequency"]),
    ("features:\n  - {kind: harmonic, probe: i_total, order: 8, amplitude: -1 A}\n", 2,
     ["amplitude must be positive"]),
    ("features:\n  - {kind: mean, probe: speed, value: 1\n", None, ["YAML syntax error"]),
    ("features:\n  - {kind: mean, probe: T, value: 40 degC, sigma: 0.5 degC}\n", 2,
     ["sigma: 'degC' is an offset unit", "in K"]),
])
def test_feature_file_errors(tmp_path, body, line, words):
    p = _yaml(tmp_path, body)
    msg = _error(lambda: load_features(p))
    assert (f"feat.yaml:{line}:" if line else "feat.yaml") in msg, msg
    for w in words:
        assert w in msg, (w, msg)


@pytest.mark.parametrize("entry, words", [
    ("{kind: mean, probe: sped, value: 1}", ["'sped' is not a probe", "did you mean 'speed'"]),
    ("{kind: mean, probe: speed, value: 100 Hz}", ["never Hz", "rad/s"]),
    ("{kind: mean, probe: i_total, value: 2 V}", ["has dimension", "a value in A"]),
    ("{kind: harmonic, probe: i_total, order: 8, frequency: 5000 rad/s}",
     ["not per angle", "Hz"]),
])
def test_features_checked_against_the_netlist(tmp_path, entry, words):
    fs = load_features(_yaml(tmp_path, f"features:\n  - x\n  - {entry}\n".replace(
        "  - x\n", "  - {kind: mean, probe: speed, value: 1}\n")))
    msg = _error(lambda: fs.check(_Model()))
    assert "feat.yaml:3:" in msg, msg
    for w in words:
        assert w in msg, (w, msg)


def test_a_measured_temperature_in_celsius_is_absolute(tmp_path):
    fs = load_features(_yaml(tmp_path, "features:\n  - {kind: mean, probe: T, value: 40 degC, "
                                       "sigma: 0.5 K}\n"))
    assert fs.features[0].value == pytest.approx(313.15, abs=1e-9)  # not 40 x 274.15


def test_missing_features_file(tmp_path):
    msg = _error(lambda: load_data(tmp_path / "f.yaml"))
    assert "f.yaml" in msg and "not found" in msg


def test_feature_label():
    from circuitsim.errors import SourceLoc

    f = Feature("amplitude", "i_total", 0.38, None, 8, SourceLoc("x", 1))
    assert f.label == "amplitude(i_total, order 8)"


def test_a_netlist_without_probes_is_told_to_declare_them(tmp_path):
    p = _csv(tmp_path, "time,speed\n" + "".join(f"{k},{k}\n" for k in range(9)))
    msg = _error(lambda: load_record(p, []))
    assert "rec.csv:1" in msg and "declares no probes" in msg and "'probes:'" in msg
