"""Fitting and diagnosing a 1-million-row record: wall time and peak memory (issue 16).

The record is the DC motor of ``tests/data/dc_motor_sine.yaml`` (6 V + 6 V sine at 5 Hz from
rest) by its closed form (``tests/reference.py::dc_motor_sine``), sampled at 1 MHz for 1 s,
with white noise of 2 mA and 0.2 rad/s: columns ``time, i, w``, 59 MB of CSV, 24 MB as
float64. Each command runs in a fresh process (through ``circuitsim.cli.main``), which reports
its peak resident memory (ru_maxrss); the same command on a 10 000-row record of the same
motor is the baseline of the code path (imports, model, solver), so the difference is what
the data cost.

    python benchmarks/bench_large_record.py [ROWS]
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
from reference import dc_motor_sine

NETLIST = ROOT / "tests" / "data" / "dc_motor_sine.yaml"
CHILD = """
import json, resource, sys, time
from circuitsim.cli.main import main
t0 = time.perf_counter()
code = main(sys.argv[1:])
wall = time.perf_counter() - t0
print(json.dumps({"code": code, "wall": wall,
                  "rss": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
"""


def write_record(path: Path, rows: int, seed: int = 5) -> None:
    """The motor's record at ``rows`` samples over 1 s, with white noise."""
    t = np.linspace(0.0, 1.0, rows)
    x = dc_motor_sine(t)
    rng = np.random.default_rng(seed)
    data = np.column_stack([t, x[0] + rng.normal(0, 2e-3, rows), x[1] +
                            rng.normal(0, 0.2, rows)])
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("time,i,w\n")
        np.savetxt(fh, data, delimiter=",", fmt="%.17g")


def run(verb: str, data: Path, cache: str) -> dict:
    """One ``circuitsim VERB`` in a fresh process: exit code, wall time [s], peak RSS [MiB]."""
    args = [verb, str(NETLIST), str(data), "--free", "R,k,J", "--allow-outside", "--quiet"]
    env = {**os.environ, "CIRCUITSIM_CACHE": cache}
    out = subprocess.run([sys.executable, "-c", CHILD, *args], capture_output=True, text=True,
                         check=True, env=env)
    got = json.loads(out.stdout.strip().splitlines()[-1])
    got["report"] = "\n".join(line for line in out.stdout.splitlines()
                              if line.startswith(("record:", "R ", "k ", "J ", "  R =",
                                                  "  k =", "  J =", "nothing", "something",
                                                  "fit of")))
    return got


def main(rows: int = 1_000_000) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        big, small = Path(tmp) / "big.csv", Path(tmp) / "small.csv"
        write_record(big, rows)
        write_record(small, 10_000)
        size = big.stat().st_size / 2**20
        numbers = rows * 3 * 8 / 2**20
        print(f"{rows} rows x 3 columns: {size:.0f} MB of CSV, {numbers:.0f} MB as float64")
        for verb in ("fit", "diagnose"):
            run(verb, small, tmp)  # compiles the model into the cache: not timed
            base = run(verb, small, tmp)
            start = time.perf_counter()
            got = run(verb, big, tmp)
            wall = time.perf_counter() - start
            extra = got["rss"] - base["rss"]
            print(f"\ncircuitsim {verb}: exit {got['code']}, {got['wall']:.1f} s in the "
                  f"command ({wall:.1f} s with the interpreter); peak RSS {got['rss']:.0f} MB "
                  f"({base['rss']:.0f} MB for 10 000 rows): +{extra:.0f} MB = "
                  f"{extra / numbers:.1f}x the numbers, {extra / size:.1f}x the file")
            print(got["report"])


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000)
