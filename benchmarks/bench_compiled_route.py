"""The compiled route measured: IDA calling the model's numba kernels directly, no Python per step.

Run from anywhere, with numba installed (``pip install .[fast]``)::

    python benchmarks/bench_compiled_route.py
    python benchmarks/bench_compiled_route.py --json out.json

On the Kim & Kim base model (0.3 s from rest, rtol 2e-6, atol 1e-8, the netlist's 50 us output
grid: the setting of ``bench_base.py`` that meets I8 error <= 1e-5) it compares, in one run:

* ``model.simulate()`` as by default (scikit-sundae calling the generated Python residual) and
  with ``CIRCUITSIM_KERNELS=numba`` (the same IDA, scikit-sundae's bundled SUNDIALS libraries,
  calling the generated numba ``cfunc`` kernels: ``circuitsim/solve/direct.py``), best of 7
  each, and whether the two give the same times, states and derivatives to the bit;
* ngspice (``tests/ngspice.py::kim_base_deck``, trapezoidal, tmax 10 us), best of 3, as in
  ``bench_base.py`` (its own transient-analysis time);
* the price per process: importing numba and compiling the kernels (empty cache folder), then
  loading them from numba's cache (a second process on the same folder).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "benchmarks"))
NETLIST = ROOT / "netlists" / "kim2024" / "base.yaml"
KW = {"rtol": 2e-6, "atol": 1e-8}

from common import best_of  # after the path it is found on


def child() -> dict:
    """In a fresh process: the Python route, the first compiled solve (numba's import and the
    kernels' compile or cache load included), then both routes timed."""
    warnings.simplefilter("ignore")
    import circuitsim as cs

    model = cs.compile(cs.load(NETLIST))
    os.environ.pop("CIRCUITSIM_KERNELS", None)
    python = model.simulate(**KW)
    os.environ["CIRCUITSIM_KERNELS"] = "numba"
    t0 = time.perf_counter()
    kernels = model.simulate(**KW)
    first = time.perf_counter() - t0
    t_direct, _ = best_of(7, lambda: model.simulate(**KW))
    os.environ.pop("CIRCUITSIM_KERNELS")
    t_python, _ = best_of(7, lambda: model.simulate(**KW))
    same = all(np.array_equal(a, b) for a, b in ((python.t, kernels.t), (python.y, kernels.y),
                                                 (python.yp, kernels.yp)))
    return {"first_direct": first, "direct": t_direct, "python": t_python, "same": same,
            "nfev": [python.nfev, kernels.nfev]}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--json", help="also write the results to this JSON file")
    args = ap.parse_args(argv)
    if args.child:
        print(json.dumps(child()))
        return 0
    try:
        import numba  # noqa: F401
    except ImportError:
        print("numba is not installed: `pip install .[fast]` to measure this route")
        return 1
    env = {**os.environ, "CIRCUITSIM_CACHE": tempfile.mkdtemp(prefix="bench-cache-")}
    env.pop("CIRCUITSIM_KERNELS", None)
    runs = [json.loads(subprocess.run([sys.executable, __file__, "--child"], env=env,
                                      capture_output=True, text=True, check=True
                                      ).stdout.splitlines()[-1]) for _ in range(2)]
    ng = _ngspice()
    report(runs, ng)
    if args.json:
        Path(args.json).write_text(json.dumps({"runs": runs, "ngspice": ng}, indent=1))
    return 0


def _ngspice() -> float | None:
    from ngspice import have_ngspice

    if not have_ngspice():
        return None
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_base import ngspice_timed

    return ngspice_timed(10e-6, 3)["rusage"]


def report(runs: list[dict], ng: float | None) -> None:
    cold, warm = runs
    direct = min(r["direct"] for r in runs)
    python = min(r["python"] for r in runs)
    print("Kim & Kim base model, 0.3 s from rest, rtol 2e-6, atol 1e-8, 6001 output points")
    print(f"  simulate, Python residual (default)       {python * 1e3:7.1f} ms, "
          f"{cold['nfev'][0]} residual calls")
    print(f"  simulate, CIRCUITSIM_KERNELS=numba        {direct * 1e3:7.1f} ms, "
          f"{cold['nfev'][1]} residual calls; same numbers to the bit: "
          f"{all(r['same'] for r in runs)}")
    if ng:
        print(f"  ngspice, trap, tmax 10 us                 {ng * 1e3:7.1f} ms -> Python "
              f"{python / ng:.2f}x, kernels {direct / ng:.2f}x ngspice")
    print(f"  first compiled solve in a process: {cold['first_direct']:.2f} s with an empty "
          f"cache (numba's import, the kernels' compile), {warm['first_direct']:.2f} s once "
          f"numba has cached them")
    fixed = warm["first_direct"] - direct
    print(f"  a process recovers that after about {fixed / (python - direct):.0f} solves of "
          f"this model")


if __name__ == "__main__":
    raise SystemExit(main())
