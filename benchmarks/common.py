"""Shared helpers of the benchmark scripts: timing and the versions of what is timed."""

from __future__ import annotations

import os
import platform
import re
import subprocess
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from ngspice import have_ngspice


def best_of(n: int, fn: Callable[[], Any]) -> tuple[float, Any]:
    """Minimum wall time [s] of ``n`` calls of ``fn`` and the last return value."""
    best, out = float("inf"), None
    for _ in range(n):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def versions() -> dict[str, str]:
    import scipy
    import sksundae

    out = {"python": platform.python_version(), "numpy": np.__version__,
           "scipy": scipy.__version__, "scikit-sundae": sksundae.__version__,
           "machine": f"{platform.machine()}, {os.cpu_count()} cores",
           "cpu": platform.processor() or "?"}
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            for line in fh:
                if line.startswith("model name"):
                    out["cpu"] = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    if have_ngspice():
        v = subprocess.run(["ngspice", "-v"], capture_output=True, text=True, check=False)
        m = re.search(r"ngspice-\S+", v.stdout)
        out["ngspice"] = m.group(0) if m else "?"
    return out
