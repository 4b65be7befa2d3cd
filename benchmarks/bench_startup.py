"""Whole-process time of a warm ``circuitsim run`` against ``ngspice -b`` on the same circuit.

Run from anywhere::

    python benchmarks/bench_startup.py               # ~1 min on 2 cores
    python benchmarks/bench_startup.py --repeats 15 --json out.json

What is timed (wall clock of a subprocess, ``time.perf_counter``; every command once per round,
rounds interleaved so a load burst hits all of them; the median over the rounds (at least 7)
is the figure and gives the ratios and the verdicts, the minimum is printed beside it):

* ``circuitsim run netlists/kim2024/base.yaml --no-files`` with a warm model cache (a throw-away
  ``CIRCUITSIM_CACHE`` filled by one cold run first), and the same writing the CSV and the PNG.
  Bytecode is written (``PYTHONDONTWRITEBYTECODE`` is dropped for the subprocesses), as in an
  installed package.
* ``ngspice -b`` on the reference deck of the same model (``tests/ngspice.py::kim_base_deck``:
  trapezoidal, reltol 1e-6, tmax 10 us, 0.3 s from rest), without output, and writing its
  four waveforms with ``wrdata``.
* The floor of any Python route through scikit-sundae: the interpreter alone, ``import numpy``,
  and numpy + scikit-sundae's IDA imported the way circuitsim does (``solve/sundae.py``); plain
  ``import sksundae`` (which pulls in scipy.optimize) and ``import circuitsim.cli.main`` for
  comparison.

Targets (issue #14): warm ``--no-files`` <= 2 x ``ngspice -b``; with CSV and PNG <= 1 s.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from ngspice import have_ngspice, kim_base_deck

NETLIST = "netlists/kim2024/base.yaml"
TARGET_RATIO = 2.0  # warm --no-files / ngspice -b
TARGET_FILES = 1.0  # [s] warm run writing CSV and PNG
LEAN_IDA = "from circuitsim.solve.sundae import ida_class; ida_class()"
HEAVY = ("sympy", "pint", "jsonschema", "scipy.optimize", "scipy.fft", "scipy.sparse",
         "matplotlib")


def circuitsim_cmd() -> list[str]:
    """The console script beside this interpreter, else the launcher module."""
    script = Path(sys.executable).with_name("circuitsim")
    return [str(script)] if script.exists() else [sys.executable, "-m", "circuitsim_launch"]


def ngspice_deck(folder: Path, with_output: bool) -> Path:
    lines = kim_base_deck(t_stop=0.3, tmax=10e-6).rstrip().splitlines()
    while lines and lines[-1].strip().lower() in (".end", ""):
        lines.pop()
    data = folder / "out.dat"
    control = ["run", f"wrdata {data} i(vsup) i(vmot) v(w) v(th)"] if with_output else ["run"]
    path = folder / ("deck_out.cir" if with_output else "deck.cir")
    path.write_text("\n".join([*lines, ".control", *control, "quit", ".endc", ".end"]) + "\n")
    return path


def commands(work: Path) -> dict[str, list[str]]:
    cs = circuitsim_cmd()
    py = sys.executable
    out = {
        "circuitsim run --no-files (warm)": [*cs, "run", NETLIST, "--no-files", "--quiet"],
        "circuitsim run, CSV + PNG (warm)": [*cs, "run", NETLIST, "--quiet", "--out",
                                             str(work / "base.csv"), "--plot",
                                             str(work / "base.png")],
        "floor: python -c pass": [py, "-c", "pass"],
        "floor: import numpy": [py, "-c", "import numpy"],
        "floor: numpy + IDA (lean import)": [py, "-c", LEAN_IDA],
        "for comparison: import sksundae": [py, "-c", "import sksundae"],
        "for comparison: import circuitsim.cli.main": [py, "-c", "import circuitsim.cli.main"],
    }
    if have_ngspice():
        out["ngspice -b"] = ["ngspice", "-b", str(ngspice_deck(work, False))]
        out["ngspice -b, wrdata"] = ["ngspice", "-b", str(ngspice_deck(work, True))]
    return out


def timed(cmd: list[str], env: dict[str, str], cwd: Path) -> tuple[float, float]:
    """Wall clock [s] and the process's CPU time, user + system [s] (``wait4``'s rusage: less
    moved by other jobs than the wall clock on a shared machine)."""
    t0 = time.perf_counter()
    with tempfile.TemporaryFile() as err:
        proc = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)
        if proc.returncode != 0:
            err.seek(0)
            raise RuntimeError(f"{' '.join(cmd)} failed:\n{err.read()[-2000:].decode()}")
    return wall, usage.ru_utime + usage.ru_stime


def heavy_imports(env: dict[str, str]) -> list[str]:
    """Heavy modules a warm ``run --no-files`` has imported by its end."""
    code = ("import contextlib, io, sys, warnings\nwarnings.simplefilter('ignore')\n"
            "from circuitsim.cli.main import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            f"    main(['run', {NETLIST!r}, '--no-files', '--quiet'])\n"
            f"print(' '.join(m for m in {HEAVY!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=env, capture_output=True,
                         text=True, check=True)
    return out.stdout.split()


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=9, help="rounds (default 9, at least 7)")
    ap.add_argument("--json", help="also write the results to this JSON file")
    args = ap.parse_args(argv)
    if args.repeats < 7:
        ap.error("--repeats: at least 7 (the figure is a median)")

    work = Path(tempfile.mkdtemp(prefix="bench-startup-"))
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env["CIRCUITSIM_CACHE"] = str(work / "cache")
    env.setdefault("MPLBACKEND", "Agg")
    cmds = commands(work)
    first = next(iter(cmds.values()))
    cold = timed(first, env, ROOT)[0]  # derives the model and writes the bytecode
    times: dict[str, list[float]] = {name: [] for name in cmds}
    cpu: dict[str, list[float]] = {name: [] for name in cmds}
    for _ in range(args.repeats):
        for name, cmd in cmds.items():
            wall, used = timed(cmd, env, ROOT)
            times[name].append(wall)
            cpu[name].append(used)
    median = {name: statistics.median(v) for name, v in times.items()}
    heavy = heavy_imports(env)
    shutil.rmtree(work, ignore_errors=True)
    report(median, times, cpu, cold, heavy, args.repeats)
    if args.json:
        Path(args.json).write_text(json.dumps({"median": median, "times": times, "cpu": cpu,
                                               "cold": cold, "heavy": heavy}, indent=1))
    return 0


def report(median: dict[str, float], times: dict[str, list[float]],
           cpu: dict[str, list[float]], cold: float, heavy: list[str], repeats: int) -> None:
    """Medians [s], their ratios to ``ngspice -b``'s median, the minima, the CPU times' medians,
    and the verdicts (on the wall clock's medians)."""
    ng = median.get("ngspice -b")
    print(f"warm circuitsim run against ngspice -b, Kim & Kim base model (0.3 s from rest); "
          f"wall clock, median (minimum) of {repeats} interleaved rounds [s]; CPU median [s]")
    for name, value in median.items():
        ratio = f"{value / ng:5.2f}x ngspice -b" if ng else ""
        print(f"  {name:44} {value:6.3f} ({min(times[name]):6.3f})  {ratio}  "
              f"CPU {statistics.median(cpu[name]):6.3f}")
    print(f"  cold run (derivation, code generation, bytecode): {cold:.2f} s")
    print(f"  heavy modules imported by a warm run: {', '.join(heavy) or 'none'}")
    warm = median["circuitsim run --no-files (warm)"]
    files = median["circuitsim run, CSV + PNG (warm)"]
    floor = median["floor: numpy + IDA (lean import)"]
    print("targets (medians)")
    if ng:
        verdict = "MET" if warm <= TARGET_RATIO * ng else "MISSED"
        print(f"  warm --no-files <= {TARGET_RATIO:g} x ngspice -b: {warm:.3f} s / {ng:.3f} s = "
              f"{warm / ng:.2f}x -> {verdict} (import floor alone {floor:.3f} s = "
              f"{floor / ng:.2f}x)")
    ratio = f" = {files / ng:.2f}x ngspice -b" if ng else ""
    files_cpu = statistics.median(cpu["circuitsim run, CSV + PNG (warm)"])
    print(f"  with CSV and PNG <= {TARGET_FILES:g} s: {files:.3f} s{ratio} -> "
          f"{'MET' if files <= TARGET_FILES else 'MISSED'} (its CPU time {files_cpu:.3f} s; "
          f"load average {os.getloadavg()[0]:.1f})")


if __name__ == "__main__":
    raise SystemExit(main())
