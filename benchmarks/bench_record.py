"""Loading a large measured record: time and peak memory of ``load_record`` (issue 16).

A 1 000 000-row record (time + 5 columns, ~60 MB of CSV) is written to a temporary folder and
loaded in a fresh process, which reports its peak resident memory (ru_maxrss) before and after.
The target: memory a small multiple of the numbers (48 MB as float64).

    python benchmarks/bench_record.py [ROWS]
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

CHILD = """
import resource, sys, time
import numpy as np
from circuitsim.loop.record import load_record
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
t0 = time.perf_counter()
rec = load_record(sys.argv[1], None)
dt = time.perf_counter() - t0
after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(dt, before / 1024, after / 1024, rec.t.size, len(rec.names))
"""


def main(rows: int = 1_000_000) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "big.csv"
        t = np.arange(rows) * 1e-4
        rng = np.random.default_rng(0)
        data = np.column_stack([t, *(np.sin(2 * np.pi * 50 * t + k) + 0.01 *
                                     rng.normal(size=rows) for k in range(5))])
        with open(path, "w") as fh:
            fh.write("time,a,b,c,d,e\n")
            np.savetxt(fh, data, delimiter=",", fmt="%.10g")
        size = path.stat().st_size / 2**20
        start = time.perf_counter()
        out = subprocess.run([sys.executable, "-c", CHILD, str(path)], capture_output=True,
                             text=True, check=True).stdout.split()
        wall = time.perf_counter() - start
    dt, before, after, n, cols = out
    numbers = rows * 6 * 8 / 2**20
    print(f"{int(n)} rows x {int(cols) + 1} columns, {size:.0f} MB of CSV ({numbers:.0f} MB "
          f"as float64)")
    print(f"load_record: {float(dt):.2f} s; peak RSS {float(before):.0f} MB after imports, "
          f"{float(after):.0f} MB after loading (+{float(after) - float(before):.0f} MB); "
          f"process wall {wall:.1f} s")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000)
