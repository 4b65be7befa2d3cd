"""Sweep engine and the Kim & Kim filter study (issue #3)."""

from __future__ import annotations

import csv

import pytest

from circuitsim.errors import ParameterError
from circuitsim.studies.sweep import Metrics, grid_points, parse_range, sweep

from conftest import NETLISTS

CASE1 = NETLISTS / "kim2024" / "case1.yaml"
CASE4 = NETLISTS / "kim2024" / "case4.yaml"
# SOLVER-NOTES, Fig. 9 (Rf = 0): 8th-order ripple amplitude [A] against Lf [H]
FIG9 = {1e-9: 0.380641, 1e-6: 0.380221, 1e-5: 0.376479, 1e-4: 0.342658, 1e-3: 0.179293,
        1e-2: 0.030793, 1e-1: 0.0033134}
M8 = Metrics(probes=("i_total",), order=8, window=1 / 6, energy=False)


def test_parse_range_and_grids():
    assert parse_range("1e-9..1e-1:log:9")[4] == pytest.approx(1e-5)
    assert parse_range("0..1:lin:5") == [0, 0.25, 0.5, 0.75, 1]
    assert parse_range("1 mH, 2 mH") == [1e-3, 2e-3]
    assert len(grid_points({"a": [1, 2, 3], "b": [4, 5]})) == 6
    assert grid_points({"a": [1, 2], "b": [4, 5]}, "zip") == [{"a": 1, "b": 4},
                                                              {"a": 2, "b": 5}]


@pytest.mark.parametrize("text", ["1,2,,5", "1,2,", ",1"])
def test_a_list_with_an_empty_item_is_refused_not_shortened(text):
    with pytest.raises(ParameterError, match="empty item"):
        parse_range(text)


def test_a_parameter_swept_on_two_axes_is_refused(tmp_path, capsys):
    from circuitsim.cli.main import main

    net = NETLISTS / "examples" / "rc.yaml"
    out = tmp_path / "s.csv"
    rc = main(["sweep", str(net), "--set", "R=1k..2k:lin:2", "--set", "R=3k,4k",
               "--out", str(out), "--quiet"])
    assert rc == 2 and "--set R is given twice" in capsys.readouterr().err
    assert not out.exists()


def test_fig9_sweep_matches_the_reference():
    """One call, one compiled topology, nine parameter vectors; Rf = 0, 0.3 s from rest."""
    rows = sweep(CASE1, {"Lf": parse_range("1e-9..1e-1:log:9"), "Rf": [0.0]}, metrics=M8,
                 stop=0.3)
    assert len(rows) == 9 and all(r["status"] == "ok" for r in rows)
    for r in rows:
        ref = next((v for k, v in FIG9.items() if abs(k - r["Lf"]) < 1e-6 * k), None)
        if ref is not None:
            assert r["i_total.ripple_amp"] == pytest.approx(ref, rel=1e-3), r["Lf"]
        assert r["i_total.ripple_freq"] == pytest.approx(825.70, abs=0.01)


def test_table_has_a_row_per_point_and_failures_are_rows(tmp_path):
    rows = sweep([CASE1, CASE4], {"Lf": [1e-3, 2e-3], "Vin": [6.0, 12.0]}, stop=0.02,
                 metrics=Metrics(energy=True), out=tmp_path / "t.csv")
    assert len(rows) == 8
    assert {(r["netlist"].endswith("case1.yaml"), r["Lf"], r["Vin"]) for r in rows} == {
        (c, lf, v) for c in (True, False) for lf in (1e-3, 2e-3) for v in (6.0, 12.0)}
    for r in rows:
        assert abs(r["energy.balance"]) < 1e-4 * r["energy.delivered"]
    with open(tmp_path / "t.csv") as fh:
        assert len(list(csv.DictReader(fh))) == 8


def test_a_failed_run_is_a_row_not_a_crash(write_netlist):
    """A Coulomb friction sharpened to 1e-14 rad/s makes IDA give up; the sweep goes on."""
    path = write_netlist("""
        parameters: {wb: 0.1}
        components:
          - {name: T1, type: torque, shaft: s, T: {sine: {amplitude: 1, freq: 50 Hz}}}
          - {name: Jr, type: inertia, shaft: s, J: 1e-6}
          - {name: F1, type: friction, shaft: s, tau_c: 0.5, w_brk: wb}
        probes: {w: s.w}
        analysis: {stop: 0.05, rtol: 1e-10, atol: 1e-14}
    """)
    rows = sweep(path, {"wb": [0.1, 1e-14, 0.2]}, metrics=Metrics(energy=False))
    assert [r["status"] for r in rows] == ["ok", "solver_failed", "ok"]
    assert "at t = " in rows[1]["message"]
    assert rows[2]["w.mean"] == rows[2]["w.mean"]  # the run after the failure has numbers


def test_resume_after_a_killed_sweep_gives_the_same_table(tmp_path):
    grid = {"Lf": [1e-4, 1e-3, 1e-2], "Rf": [0.0, 0.1]}
    full = sweep(CASE1, grid, stop=0.02, metrics=M8)
    out = tmp_path / "sweep.csv"

    def killer(done, total, row):
        if done == 3:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        sweep(CASE1, grid, stop=0.02, metrics=M8, out=out, progress=killer)
    with open(out) as fh:
        assert len(list(csv.DictReader(fh))) == 3  # finished rows were kept
    seen = []
    resumed = sweep(CASE1, grid, stop=0.02, metrics=M8, out=out, resume=True,
                    progress=lambda d, t, r: seen.append(d))
    assert seen == [4, 5, 6]  # only the missing runs ran
    key = ("Lf", "Rf", "i_total.ripple_amp", "i_total.mean")
    assert [tuple(r[k] for k in key) for r in resumed] == [tuple(r[k] for k in key)
                                                            for r in full]


@pytest.mark.slow
def test_local_processes_and_dask_cluster_agree(tmp_path):
    distributed = pytest.importorskip("distributed")
    grid = {"Lf": [1e-4, 1e-3, 1e-2]}
    local = sweep(CASE1, grid, stop=0.02, metrics=M8, jobs=2)
    serial = sweep(CASE1, grid, stop=0.02, metrics=M8, jobs=1)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        remote = sweep(CASE1, grid, stop=0.02, metrics=M8, executor=client.get_executor())
    for a, b, c in zip(local, serial, remote, strict=True):
        assert a["Lf"] == b["Lf"] == c["Lf"]
        assert a["i_total.ripple_amp"] == b["i_total.ripple_amp"] == c["i_total.ripple_amp"]
