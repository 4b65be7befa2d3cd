"""Sweeps lose no run and mix no tables (issue 16). Each test injects the fault for real: a
worker process that kills itself, a table cut mid-row, a table made with other settings, a
parent killed with SIGKILL, Ctrl-C sent to a running sweep."""

from __future__ import annotations

import csv
import multiprocessing
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from circuitsim.cli.main import main
from circuitsim.studies import sweep as sw
from circuitsim.studies.sweep import Metrics, SweepError, settings_path, sweep

from conftest import NETLISTS

RC = NETLISTS / "examples" / "rc.yaml"
GRID = {"R": [500.0, 1000.0, 2000.0]}
M = Metrics(probes=("v_out",), energy=False)
fork_only = pytest.mark.skipif(multiprocessing.get_start_method() != "fork",
                               reason="the injected worker reaches the pool by fork")


def _rows(path: Path) -> list[dict]:
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def _dying_worker(marks: Path, victim: float, times: int):
    """A pool worker that kills its own process (as the OOM killer would) the first ``times``
    times it is given the run R = ``victim``; marker files count the attempts across
    processes."""
    real = sw._worker

    def worker(model, run, metrics):
        if run.params.get("R") == victim:
            n = len(list(marks.glob("try-*")))
            (marks / f"try-{n}").touch()
            if n < times:
                os._exit(9)
        return real(model, run, metrics)

    # pickled by reference: the forked workers find this function under the same name
    worker.__module__, worker.__qualname__ = sw.__name__, "_worker"
    return worker


@fork_only
def test_a_killed_worker_is_retried(tmp_path, monkeypatch):
    monkeypatch.setattr(sw, "_worker", _dying_worker(tmp_path, 1000.0, times=1))
    rows = sweep(RC, GRID, metrics=M, jobs=2, out=tmp_path / "t.csv")
    assert [r["status"] for r in rows] == ["ok", "ok", "ok"]
    assert len(list(tmp_path.glob("try-*"))) == 2  # killed once, then done
    # the retried run has the numbers of a run in one process
    solo = sweep(RC, {"R": [1000.0]}, metrics=M, jobs=1)
    assert rows[1]["v_out.mean"] == solo[0]["v_out.mean"]


@fork_only
def test_a_run_that_always_kills_its_worker_is_a_crashed_row_and_exit_1(tmp_path, monkeypatch,
                                                                        capsys):
    monkeypatch.setattr(sw, "_worker", _dying_worker(tmp_path, 2000.0, times=99))
    out = tmp_path / "t.csv"
    code = main(["sweep", str(RC), "--set", "R=500,1000,2000", "--jobs", "2", "--out",
                 str(out), "--probe", "v_out", "--no-energy", "--quiet"])
    assert code == 1
    statuses = {r["R"]: r["status"] for r in _rows(out)}
    assert statuses == {"500.0": "ok", "1000.0": "ok", "2000.0": "crashed"}
    assert len(list(tmp_path.glob("try-*"))) == 1 + sw.RETRIES
    # a resume runs the crashed run again (here it is fixed) and the sweep is complete
    monkeypatch.setattr(sw, "_worker", _dying_worker(tmp_path / "none", -1.0, times=0))
    assert main(["sweep", str(RC), "--set", "R=500,1000,2000", "--jobs", "2", "--out",
                 str(out), "--probe", "v_out", "--no-energy", "--quiet", "--resume"]) == 0
    assert sorted(r["status"] for r in _rows(out)) == ["ok", "ok", "ok"]


def test_a_torn_last_row_is_not_done(tmp_path):
    out = tmp_path / "t.csv"
    full = sweep(RC, GRID, metrics=M, out=out)
    text = out.read_text()
    out.write_text(text[: text.rstrip("\n").rfind("\n") + 12])  # cut the last row mid-line
    seen = []
    resumed = sweep(RC, GRID, metrics=M, out=out, resume=True,
                    progress=lambda d, t, r: seen.append(d))
    assert seen == [3]  # only the torn run ran again
    assert [r["v_out.mean"] for r in resumed] == [r["v_out.mean"] for r in full]
    assert len(_rows(out)) == 3 and out.read_text().endswith("\n")


def test_resume_across_other_settings_is_refused(tmp_path):
    out = tmp_path / "t.csv"
    sweep(RC, GRID, metrics=M, stop=2e-3, out=out)
    assert settings_path(out).exists()
    with pytest.raises(SweepError, match="stop"):
        sweep(RC, GRID, metrics=M, stop=3e-3, out=out, resume=True)
    with pytest.raises(SweepError, match="metrics"):
        sweep(RC, GRID, metrics=Metrics(energy=False), stop=2e-3, out=out, resume=True)
    settings_path(out).unlink()
    with pytest.raises(SweepError, match="no settings file"):
        sweep(RC, GRID, metrics=M, stop=2e-3, out=out, resume=True)


def test_resume_after_the_netlist_changed_is_refused(tmp_path):
    net = tmp_path / "rc.yaml"
    net.write_text(RC.read_text())
    out = tmp_path / "t.csv"
    sweep(net, GRID, metrics=M, out=out)
    net.write_text(RC.read_text().replace("C: 1 uF", "C: 2 uF"))
    with pytest.raises(SweepError, match="netlists"):
        sweep(net, GRID, metrics=M, out=out, resume=True)


def _children(pid: int) -> list[int]:
    try:
        text = Path(f"/proc/{pid}/task/{pid}/children").read_text()
    except OSError:
        return []
    return [int(c) for c in text.split()]


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().split(")")[-1].split()[0]
    except OSError:
        return False
    return state != "Z"


SLOW_SWEEP = ("import sys; from circuitsim.cli.main import main; sys.exit(main(['sweep', "
              "{net!r}, '--set', 'R=1k,2k,3k,4k,5k,6k', '--jobs', '2', '--stop', '20', "
              "'--no-energy', '--quiet', '--out', {out!r}]))")
# the Python route: compiled kernels would finish the sweep before the signal arrives
SLOW_ENV = {**os.environ, "CIRCUITSIM_KERNELS": "python"}
# Ctrl-C acts as on a terminal even when the test runner was started in the background (a
# shell's `&` makes its jobs ignore SIGINT, and Python then leaves it ignored)
INTERRUPTIBLE = "import signal; signal.signal(signal.SIGINT, signal.default_int_handler); "


@pytest.mark.skipif(not Path("/proc/self/task").exists(), reason="needs Linux /proc")
def test_workers_die_with_a_killed_parent(tmp_path):
    code = SLOW_SWEEP.format(net=str(RC), out=str(tmp_path / "t.csv"))
    proc = subprocess.Popen([sys.executable, "-c", code], env=SLOW_ENV,
                            stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    workers: list[int] = []
    deadline = time.monotonic() + 60
    while len(workers) < 2 and time.monotonic() < deadline:
        time.sleep(0.2)
        workers = _children(proc.pid)
    assert len(workers) >= 2, "the sweep started no workers"
    proc.kill()
    proc.wait()
    deadline = time.monotonic() + 10
    while any(_alive(w) for w in workers) and time.monotonic() < deadline:
        time.sleep(0.2)
    assert not any(_alive(w) for w in workers)


def test_ctrl_c_ends_a_sweep_quickly_without_worker_tracebacks(tmp_path):
    code = INTERRUPTIBLE + SLOW_SWEEP.format(net=str(RC), out=str(tmp_path / "t.csv"))
    proc = subprocess.Popen([sys.executable, "-c", code], env=SLOW_ENV,
                            stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True, start_new_session=True)
    deadline = time.monotonic() + 60
    while len(_children(proc.pid)) < 2 and time.monotonic() < deadline:
        time.sleep(0.2)
    time.sleep(0.5)
    os.killpg(proc.pid, signal.SIGINT)  # the terminal sends it to the whole group
    start = time.monotonic()
    _, err = proc.communicate(timeout=30)
    assert time.monotonic() - start < 10
    assert proc.returncode == 130, err
    assert "Traceback" not in err, err


@fork_only
def test_a_worker_killed_once_is_retried_and_the_command_exits_0(tmp_path, monkeypatch):
    """The command's view of the first test: the retried run is a plain 'ok' row, and a
    sweep whose runs all end well exits 0 though a worker died on the way."""
    monkeypatch.setattr(sw, "_worker", _dying_worker(tmp_path, 1000.0, times=1))
    out = tmp_path / "t.csv"
    assert main(["sweep", str(RC), "--set", "R=500,1000,2000", "--jobs", "2", "--out",
                 str(out), "--probe", "v_out", "--no-energy", "--quiet"]) == 0
    assert sorted(r["status"] for r in _rows(out)) == ["ok", "ok", "ok"]
    assert len(list(tmp_path.glob("try-*"))) == 2


@pytest.mark.slow
def test_a_dask_worker_killed_mid_run_loses_no_run(tmp_path):
    """A dask.distributed cluster (2 worker processes) loses a worker to SIGKILL while it is
    running a task: the scheduler gives the lost worker's tasks to the other one (the nanny
    restarts the dead one), every run is in the table with the numbers of a serial sweep."""
    distributed = pytest.importorskip("distributed")
    grid = {"R": [250.0, 500.0, 1000.0, 2000.0, 4000.0, 8000.0]}
    slow = {"stop": 0.05, "step": 1e-7}  # ~1 s a run: long enough to be killed inside one
    serial = sweep(RC, grid, metrics=M, jobs=1, **slow)
    killed: list[int] = []
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        pids = client.run(os.getpid)

        def kill_a_busy_worker(done: int, total: int, row: dict) -> None:
            if killed:
                return
            busy = [w for w, keys in client.processing().items() if keys and w in pids]
            if busy:
                killed.append(pids[busy[0]])
                os.kill(pids[busy[0]], signal.SIGKILL)

        out = tmp_path / "t.csv"
        rows = sweep(RC, grid, metrics=M, executor=client.get_executor(), out=out,
                     progress=kill_a_busy_worker, **slow)
    assert killed, "no worker was busy when the first run finished"
    assert [r["status"] for r in rows] == ["ok"] * 6
    assert sorted(float(r["R"]) for r in _rows(out)) == grid["R"]
    # another process may differ in the last bit (its own BLAS and import order)
    assert [r["v_out.mean"] for r in rows] == pytest.approx([r["v_out.mean"] for r in serial],
                                                            rel=1e-12)


def test_an_interrupted_sweep_leaves_even_when_its_exit_would_hang():
    """The grace timer ends a process whose exit waits for ever (here a thread that never
    finishes, as a pool's manager thread waiting on a killed worker can), with code 130."""
    code = ("import threading; from circuitsim.studies.sweep import _exit_within; "
            "threading.Thread(target=threading.Event().wait).start(); _exit_within(0.5, 130)")
    start = time.monotonic()
    proc = subprocess.run([sys.executable, "-c", code], check=False, timeout=30)
    assert proc.returncode == 130
    assert time.monotonic() - start < 10
