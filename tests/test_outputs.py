"""Outputs never destroy inputs, never leave half files or temporaries, and every I/O fault
ends with a message and a documented exit code (issue 16): 2 for a command line that names a
wrong output, 3 for an output that cannot be written, 130 for Ctrl-C.

Faults are injected for real: /dev/full (ENOSPC), a file-size limit (EFBIG), a read-only
folder, SIGINT sent to a running command.
"""

from __future__ import annotations

import csv
import json
import os
import re
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from circuitsim.cli.main import main
from circuitsim.files import OutputError, atomic_write

from conftest import NETLISTS

RC = NETLISTS / "examples" / "rc.yaml"


@pytest.fixture
def rc_copy(tmp_path):
    path = tmp_path / "rc.yaml"
    path.write_text(RC.read_text())
    return path


def test_run_refuses_to_overwrite_its_netlist(rc_copy, capsys):
    before = rc_copy.read_bytes()
    assert main(["run", str(rc_copy), "--out", str(rc_copy)]) == 2
    assert "is the input" in capsys.readouterr().err
    assert rc_copy.read_bytes() == before


def test_the_plot_format_follows_its_extension_or_is_refused(rc_copy, tmp_path, capsys):
    # a PNG was written into 'fig.txt' (and into 'fig.svg'), exit 0
    out = str(tmp_path / "r.csv")
    assert main(["run", str(rc_copy), "--out", out, "--plot", str(tmp_path / "fig.txt")]) == 2
    assert "a plot is written as png, svg, pdf" in capsys.readouterr().err
    assert not (tmp_path / "fig.txt").exists() and not (tmp_path / "r.csv").exists()
    heads = {"svg": b"<?xml", "pdf": b"%PDF", "png": b"\x89PNG"}
    for ext, head in heads.items():
        fig = tmp_path / f"fig.{ext.upper() if ext == 'pdf' else ext}"
        assert main(["run", str(rc_copy), "--out", out, "--plot", str(fig)]) == 0
        assert fig.read_bytes().startswith(head), ext


def test_run_refuses_a_link_to_its_netlist(rc_copy, tmp_path, capsys):
    link = tmp_path / "out.csv"
    link.symlink_to(rc_copy)
    assert main(["run", str(rc_copy), "--out", str(link)]) == 2
    assert "is the input" in capsys.readouterr().err
    assert link.is_symlink() and rc_copy.read_text() == RC.read_text()


def test_fit_refuses_to_overwrite_its_data(rc_copy, tmp_path, capsys):
    data = tmp_path / "meas.csv"
    data.write_text("time,v_out\n0,0\n1,1\n")
    assert main(["fit", str(rc_copy), str(data), "--report", str(data)]) == 2
    assert "is the input" in capsys.readouterr().err
    assert data.read_text() == "time,v_out\n0,0\n1,1\n"


def test_out_naming_a_folder_exits_2(rc_copy, tmp_path, capsys):
    assert main(["run", str(rc_copy), "--out", str(tmp_path)]) == 2
    assert "is a folder" in capsys.readouterr().err


def test_a_symlink_output_is_written_through(rc_copy, tmp_path):
    target = tmp_path / "real.csv"
    target.write_text("old")
    link = tmp_path / "link.csv"
    link.symlink_to(target)
    assert main(["run", str(rc_copy), "--out", str(link), "--plot",
                 str(tmp_path / "p.png")]) == 0
    assert link.is_symlink() and os.readlink(link) == str(target)
    assert target.read_text().startswith("time [s],v_out [V],i [A]\n")


def test_a_device_output_is_written_not_replaced(rc_copy, tmp_path):
    assert main(["run", str(rc_copy), "--out", os.devnull, "--plot", os.devnull]) == 0
    assert stat.S_ISCHR(os.stat(os.devnull).st_mode)


def test_missing_folders_are_created_for_every_output(rc_copy, tmp_path):
    out = tmp_path / "a" / "b" / "run.csv"
    png = tmp_path / "c" / "run.png"
    assert main(["run", str(rc_copy), "--out", str(out), "--plot", str(png)]) == 0
    assert out.exists() and png.read_bytes()[:4] == b"\x89PNG"


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_read_only_folder_exits_2_before_the_run(rc_copy, tmp_path, capsys):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        assert main(["run", str(rc_copy), "--out", str(ro / "x.csv")]) == 2
        assert "cannot write" in capsys.readouterr().err
    finally:
        ro.chmod(0o700)


@pytest.mark.skipif(not os.path.isdir("/sys/kernel"), reason="no sysfs on this system")
def test_a_folder_that_refuses_files_exits_2_before_the_run(rc_copy, tmp_path, capsys):
    # sysfs refuses new files even to root (the read-only-folder test above needs non-root):
    # a file tried in the folder finds it before the run, so the plot is not written either
    png = tmp_path / "p.png"
    assert main(["run", str(rc_copy), "--plot", str(png), "--out",
                 "/sys/kernel/circuitsim.csv"]) == 2
    err = capsys.readouterr().err
    assert "--out '/sys/kernel/circuitsim.csv': cannot write into /sys/kernel" in err
    assert "Traceback" not in err and not png.exists()
    assert not list(Path("/sys/kernel").glob(".circuitsim-probe-*"))


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="no /dev/full on this system")
def test_disk_full_exits_3_with_a_message(rc_copy, tmp_path, capsys):
    # /dev/full accepts the open and fails every write with ENOSPC
    assert main(["run", str(rc_copy), "--out", "/dev/full", "--plot",
                 str(tmp_path / "p.png")]) == 3
    err = capsys.readouterr().err
    assert "disk is full" in err and "Traceback" not in err


def test_a_failed_write_keeps_the_old_file_and_leaves_no_temporary(rc_copy, tmp_path):
    """A file-size limit makes the CSV write fail half-way (EFBIG, as a full disk would):
    exit 3, the old output intact, no hidden temporary beside it."""
    out = tmp_path / "run.csv"
    out.write_text("old results\n")
    code = ("import resource, sys; resource.setrlimit(resource.RLIMIT_FSIZE, (20000, 20000));"
            "from circuitsim.cli.main import main;"
            f"sys.exit(main(['run', {str(rc_copy)!r}, '--out', {str(out)!r}, '--plot', "
            f"{str(tmp_path / 'p.png')!r}]))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120, check=False)
    assert proc.returncode == 3, proc.stderr
    assert "cannot write" in proc.stderr and "Traceback" not in proc.stderr
    assert out.read_text() == "old results\n"
    assert not list(tmp_path.glob(".circuitsim-*"))


def test_an_interrupted_write_leaves_no_temporary(tmp_path):
    out = tmp_path / "x.csv"

    def write(tmp: str) -> None:
        with open(tmp, "w") as fh:
            fh.write("partial")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        atomic_write(out, write)
    assert not out.exists() and not list(tmp_path.iterdir())


def test_an_output_error_is_also_an_os_error(tmp_path):
    with pytest.raises(OSError) as info:
        atomic_write(tmp_path / "missing" / "x.txt", "x", make_dirs=False)
    assert isinstance(info.value, OutputError) and info.value.exit_code == 3


def test_new_files_get_the_umask_mode(tmp_path):
    old = os.umask(0o027)
    try:
        atomic_write(tmp_path / "a.txt", "x")
    finally:
        os.umask(old)
    assert stat.S_IMODE(os.stat(tmp_path / "a.txt").st_mode) == 0o640


def test_run_csv_has_units_and_honours_probe_after_decimate(rc_copy, tmp_path):
    """The RC step written after 2 ms, every 4th point, one probe: each row obeys
    v = 1 - exp(-t/RC) (RC = 1 ms) to the integrator's tolerance."""
    out = tmp_path / "v.csv"
    assert main(["run", str(rc_copy), "--out", str(out), "--plot", str(tmp_path / "v.png"),
                 "--probe", "v_out", "--after", "2ms", "--decimate", "4"]) == 0
    with open(out, newline="") as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["time [s]", "v_out [V]"]
    data = np.array(rows[1:], float)
    assert data[0, 0] == pytest.approx(2e-3) and data[-1, 0] == pytest.approx(5e-3)
    assert np.allclose(np.diff(data[:, 0]), 4 * 5e-6)  # the netlist's 5 us step, every 4th
    np.testing.assert_allclose(data[:, 1], 1 - np.exp(-data[:, 0] / 1e-3), atol=1e-6)


def test_after_past_the_stop_exits_2_and_writes_nothing(rc_copy, tmp_path, capsys):
    """--after 1 s on a 5 ms run wrote a CSV holding its header alone, exit 0."""
    out = tmp_path / "v.csv"
    assert main(["run", str(rc_copy), "--out", str(out), "--after", "1"]) == 2
    assert "--after 1 s is after the stop time 0.005 s" in capsys.readouterr().err
    assert not out.exists()
    assert main(["run", str(rc_copy), "--out", str(out), "--after", "5ms"]) == 0
    assert out.read_text().splitlines()[1].startswith("0.005,")  # the stop's row


def test_run_csv_reads_back_as_a_record(rc_copy, tmp_path):
    """The units in the header do not get in the way of `fit` reading a run's CSV."""
    from circuitsim.loop.record import load_record

    out = tmp_path / "v.csv"
    assert main(["run", str(rc_copy), "--out", str(out), "--plot",
                 str(tmp_path / "v.png")]) == 0
    assert out.read_text().startswith("time [s],v_out [V],i [A]\n")
    rec = load_record(out, ["v_out", "i"], units={"v_out": "V", "i": "A"})
    assert set(rec.names) == {"v_out", "i"} and rec.t[-1] == pytest.approx(5e-3)
    plain = tmp_path / "plain.csv"
    assert main(["run", str(rc_copy), "--out", str(plain), "--no-header-units",
                 "--plot", str(tmp_path / "p.png")]) == 0
    assert plain.read_text().startswith("time,v_out,i\n")
    again = load_record(plain, ["v_out", "i"], units={"v_out": "V", "i": "A"})
    np.testing.assert_array_equal(again["v_out"], rec["v_out"])


def _record_csv(path, header: str, scale: float = 1.0, t_scale: float = 1.0) -> None:
    """The RC step v = 1 - exp(-t / 1 ms) over 5 ms, written in the units of ``header``."""
    t = np.linspace(0.0, 5e-3, 101)
    v = 1 - np.exp(-t / 1e-3)
    path.write_text(header + "\n" + "".join(f"{a * t_scale!r},{b * scale!r}\n"
                                            for a, b in zip(t.tolist(), v.tolist(),
                                                            strict=True)))


def test_a_unit_in_the_header_is_checked_and_converted(tmp_path):
    """'v_out [mV]' and 'time [ms]' are read as SI; a unit of another dimension, or one pint
    does not know, is refused naming the file, the column and the probe's unit."""
    from circuitsim.loop.record import DataError, load_record

    units = {"v_out": "V", "i": "A"}
    path = tmp_path / "r.csv"
    _record_csv(path, "time [ms],v_out [mV]", scale=1e3, t_scale=1e3)
    rec = load_record(path, ["v_out", "i"], units=units)
    np.testing.assert_allclose(rec.t, np.linspace(0.0, 5e-3, 101), rtol=1e-12)
    np.testing.assert_allclose(rec["v_out"], 1 - np.exp(-rec.t / 1e-3), rtol=1e-12, atol=1e-15)
    _record_csv(path, "time,v_out [A]")
    with pytest.raises(DataError, match=r"r\.csv:1: column 'v_out \[A\]'.*probe 'v_out' is in V"):
        load_record(path, ["v_out", "i"], units=units)
    _record_csv(path, "time [V],v_out")
    with pytest.raises(DataError, match=r"column 'time \[V\]'.*time column is in s"):
        load_record(path, ["v_out", "i"], units=units)
    _record_csv(path, "time,v_out [bananas]")
    with pytest.raises(DataError, match=r"unknown unit"):
        load_record(path, ["v_out", "i"], units=units)


def test_fit_reads_a_plain_user_csv_and_a_csv_with_units_alike(rc_copy, tmp_path, capsys):
    """`fit` on the same RC record written as 'time,v_out' and as 'time [ms],v_out [mV]'
    gives the same estimate (R = 1 kohm: the record is the netlist's own closed form)."""
    out = {}
    for name, header, scale in (("plain", "time,v_out", 1.0),
                                ("units", "time [ms],v_out [mV]", 1e3)):
        path = tmp_path / f"{name}.csv"
        _record_csv(path, header, scale=scale, t_scale=scale)
        assert main(["fit", str(rc_copy), str(path), "--free", "R", "--set", "R=1.2k",
                     "--json"]) == 0
        out[name] = json.loads(capsys.readouterr().out)["parameters"]["R"]["estimate"]
    assert out["plain"] == pytest.approx(1000.0, rel=1e-5)
    assert out["units"] == pytest.approx(out["plain"], rel=1e-9)


def test_to_dataframe(rc_copy):
    pd = pytest.importorskip("pandas", reason="pandas is optional (in the test extras)")
    import circuitsim as cs

    res = cs.compile(cs.load(rc_copy)).simulate()
    df = res.to_dataframe()
    assert isinstance(df, pd.DataFrame) and list(df.columns) == ["v_out", "i"]
    assert df.attrs["units"] == {"v_out": "V", "i": "A"}
    np.testing.assert_allclose(df["v_out"].to_numpy(), res["v_out"])


def _loaded(pid: int, library: str) -> bool:
    try:
        return library in Path(f"/proc/{pid}/maps").read_text()
    except OSError:
        return False


@pytest.mark.skipif(not Path("/proc/self/maps").exists(), reason="needs Linux /proc")
def test_ctrl_c_exits_130_without_a_traceback(tmp_path):
    """SIGINT right after numpy's and scipy's compiled parts load (circuitsim is still being
    imported) and during the run: exit 130, one line. (Before the interpreter runs any code of ours,
    Python itself would report the interrupt.)"""
    net = tmp_path / "sine.yaml"  # a long run of a small circuit (compiled in a second)
    net.write_text("""
title: long sine
components:
  - {name: V1, type: V, p: a, n: gnd, V: {sine: {amplitude: 1, freq: 1 kHz}}}
  - {name: R1, type: R, p: a, n: b, R: 1k}
  - {name: C1, type: C, p: b, n: gnd, C: 1u}
probes: {v: b.v}
analysis: {stop: 500, step: 1 ms}
""")
    launch = "import sys; from circuitsim_launch import main; sys.exit(main())"
    script = [sys.executable, "-c", launch, "run", str(net), "--no-files"]
    for library, delay in (("_multiarray_umath", 0.0), ("scipy", 0.0), ("libsundials_ida", 0.5)):
        proc = subprocess.Popen(script, stderr=subprocess.PIPE, stdout=subprocess.DEVNULL,
                                text=True, cwd=tmp_path)
        deadline = time.monotonic() + 60
        while not _loaded(proc.pid, library) and proc.poll() is None and \
                time.monotonic() < deadline:
            time.sleep(0.002)
        time.sleep(delay)
        proc.send_signal(signal.SIGINT)
        start = time.monotonic()
        _, err = proc.communicate(timeout=60)
        assert time.monotonic() - start < 10, library
        assert proc.returncode == 130, (library, err)
        assert "Traceback" not in err, (library, err)


def test_identify_refuses_to_overwrite_its_record(tmp_path, capsys):
    data = tmp_path / "emf.csv"
    data.write_text("theta,omega,e1\n0,1,0\n")
    assert main(["identify", "emf", str(data), "--pp", "6", "--plot", str(data)]) == 2
    assert "is the input" in capsys.readouterr().err
    assert data.read_text() == "theta,omega,e1\n0,1,0\n"


def test_diagnose_probe_naming_no_column_exits_2(rc_copy, tmp_path, capsys):
    """`--probe` naming a column the record lacks: a message naming the columns, not a
    KeyError."""
    rec = tmp_path / "rec.csv"
    assert main(["run", str(rc_copy), "--out", str(rec), "--plot", str(tmp_path / "r.png"),
                 "--probe", "v_out"]) == 0
    capsys.readouterr()
    assert main(["diagnose", str(rc_copy), str(rec), "--probe", "i"]) == 2
    err = capsys.readouterr().err
    assert "no such column" in err and "v_out" in err and "Traceback" not in err



def test_diagnose_a_flat_column_exits_2_and_fit_reports_no_nrmse(rc_copy, tmp_path, capsys):
    """A column holding one value in every row (a disconnected sensor) has no noise to weigh
    it by: diagnose refuses it, naming it, instead of dividing by zero ("error inf"); fit
    fits it and reports its NRMSE (normalised by a spread of zero) as flat, not 1e300."""
    rec = tmp_path / "rec.csv"
    assert main(["run", str(rc_copy), "--out", str(rec), "--plot", str(tmp_path / "r.png"),
                 "--probe", "v_out"]) == 0
    lines = rec.read_text().splitlines()
    head, rows = lines[0], [ln.split(",") for ln in lines[1:]]
    rec.write_text("\n".join([head, *(f"{r[0]},0" for r in rows)]) + "\n")
    capsys.readouterr()
    assert main(["diagnose", str(rc_copy), str(rec), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "column 'v_out'" in err and "same value (0) in every row" in err
    assert "Traceback" not in err and "Check the sensor" in err
    assert main(["fit", str(rc_copy), str(rec), "--free", "R", "--quiet"]) == 0
    out = capsys.readouterr().out
    assert re.search(r"v_out\s+flat\s", out), out

LONG_RUN = """
title: long sine
components:
  - {name: V1, type: V, p: a, n: gnd, V: {sine: {amplitude: 1, freq: 1 kHz}}}
  - {name: R1, type: R, p: a, n: b, R: 1k}
  - {name: C1, type: C, p: b, n: gnd, C: 1u}
probes: {v: b.v}
analysis: {stop: 500, step: 1 ms}
"""


def test_sigterm_during_a_run_exits_143_and_leaves_the_old_output(tmp_path):
    net = tmp_path / "sine.yaml"
    net.write_text(LONG_RUN)
    out = tmp_path / "run.csv"
    out.write_text("old results\n")
    proc = subprocess.Popen([sys.executable, "-m", "circuitsim.cli", "run", str(net), "--out",
                             str(out), "--plot", str(tmp_path / "p.png")],
                            stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True)
    deadline = time.monotonic() + 60
    while not _loaded(proc.pid, "libsundials_ida") and time.monotonic() < deadline:
        time.sleep(0.01)
    time.sleep(0.5)
    proc.terminate()
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 143, err
    assert "Traceback" not in err
    assert out.read_text() == "old results\n"
    assert not list(tmp_path.glob(".circuitsim-*"))


def test_a_sweep_table_on_a_full_disk_exits_3(tmp_path):
    """The table's append fails (a file-size limit, as a full disk would): exit 3, one line."""
    out = tmp_path / "t.csv"
    code = ("import resource, sys, warnings; import circuitsim as cs;"
            "warnings.simplefilter('ignore');"
            f"cs.compile(cs.load({str(RC)!r}));"  # the model cache is written before the limit
            "resource.setrlimit(resource.RLIMIT_FSIZE, (600, 600));"
            "from circuitsim.cli.main import main;"
            f"sys.exit(main(['sweep', {str(RC)!r}, '--set', 'R=1k,2k,3k,4k', '--jobs', '1', "
            f"'--out', {str(out)!r}, '--quiet']))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120, check=False)
    assert proc.returncode == 3, proc.stderr
    assert "t.csv" in proc.stderr and "Traceback" not in proc.stderr
