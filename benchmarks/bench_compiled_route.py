"""The compiled route measured: IDA called directly with numba ``cfunc`` kernels, no Python per step.

Run from anywhere, with numba installed (it is not a circuitsim dependency)::

    pip install numba
    python benchmarks/bench_compiled_route.py

On the Kim & Kim base model (0.3 s from rest, rtol 2e-6, atol 1e-8, the netlist's 50 us output
grid: the setting of ``bench_base.py`` that meets I8 error <= 1e-5) it compares, in one run:

* ``model.simulate`` (scikit-sundae: IDA calling the generated Python residual), best of 5;
* the same IDA (scikit-sundae's bundled SUNDIALS libraries, loaded with ctypes; the same
  options: dense linear solver, our Jacobian, the same tolerances, start and output times)
  calling the numba kernels of ``compiled_route_kernels.py`` directly, best of 7; the states
  are compared with ``simulate``'s;
* ngspice (``tests/ngspice.py::kim_base_deck``, trapezoidal, tmax 10 us), best of 3, as in
  ``bench_base.py`` (its own transient-analysis time);
* the price per process: importing numba, compiling the kernels (empty numba cache) and loading
  them from numba's cache (second process), each in a fresh subprocess.

The kernels are written by hand from the generated module (a library route would print them);
the libraries are scikit-sundae's private copies, which is what makes the route fragile.
"""

from __future__ import annotations

import argparse
import ctypes
import glob
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
HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(ROOT / "tests"))
NETLIST = ROOT / "netlists" / "kim2024" / "base.yaml"
RTOL, ATOL = 2e-6, 1e-8
IDA_NORMAL = 1


def _libraries() -> dict[str, ctypes.CDLL]:
    """scikit-sundae's bundled SUNDIALS libraries, with the signatures used here."""
    import importlib.util

    libs = Path(importlib.util.find_spec("sksundae").origin).parent.parent / "scikit_sundae.libs"
    lib = {name: ctypes.CDLL(glob.glob(str(libs / f"libsundials_{name}-*.so*"))[0],
                             mode=ctypes.RTLD_GLOBAL)
           for name in ("core", "nvecserial", "sunmatrixdense", "sunlinsoldense", "ida")}
    vp, dbl, i32 = ctypes.c_void_p, ctypes.c_double, ctypes.c_int
    for name, res, args in (
            ("core.SUNContext_Create", i32, [i32, ctypes.POINTER(vp)]),
            ("core.N_VGetArrayPointer", ctypes.POINTER(dbl), [vp]),
            ("nvecserial.N_VNew_Serial", vp, [i32, vp]),
            ("sunmatrixdense.SUNDenseMatrix", vp, [i32, i32, vp]),
            ("sunlinsoldense.SUNLinSol_Dense", vp, [vp, vp, vp]),
            ("ida.IDACreate", vp, [vp]), ("ida.IDAInit", i32, [vp, vp, dbl, vp, vp]),
            ("ida.IDASStolerances", i32, [vp, dbl, dbl]),
            ("ida.IDASetLinearSolver", i32, [vp, vp, vp]), ("ida.IDASetJacFn", i32, [vp, vp]),
            ("ida.IDASetUserData", i32, [vp, vp]),
            ("ida.IDASetMaxNumSteps", i32, [vp, ctypes.c_long]),
            ("ida.IDASetStopTime", i32, [vp, dbl]),
            ("ida.IDASolve", i32, [vp, dbl, ctypes.POINTER(dbl), vp, vp, i32]),
            ("ida.IDAGetNumResEvals", i32, [vp, ctypes.POINTER(ctypes.c_long)])):
        owner, fn = name.split(".")
        f = getattr(lib[owner], fn)
        f.restype, f.argtypes = res, args
    return lib


def solve_direct(lib, kernels, p, y0, yp0, t_eval) -> tuple[np.ndarray, int]:
    """IDA from t_eval[0] with outputs at t_eval: (states (n_points, n), residual calls).
    The SUNDIALS objects of this measurement are not freed."""
    core, ida, n = lib["core"], lib["ida"], kernels.N
    ctx = ctypes.c_void_p()
    core.SUNContext_Create(0, ctypes.byref(ctx))
    yy, yp = (lib["nvecserial"].N_VNew_Serial(n, ctx) for _ in range(2))
    Y = np.ctypeslib.as_array(core.N_VGetArrayPointer(yy), (n,))
    YP = np.ctypeslib.as_array(core.N_VGetArrayPointer(yp), (n,))
    Y[:], YP[:] = y0, yp0
    mem = ida.IDACreate(ctx)
    pv = np.ascontiguousarray(p, dtype=np.float64)
    ida.IDASetUserData(mem, pv.ctypes.data)
    ida.IDAInit(mem, kernels.residual.address, t_eval[0], yy, yp)
    A = lib["sunmatrixdense"].SUNDenseMatrix(n, n, ctx)
    ida.IDASetLinearSolver(mem, lib["sunlinsoldense"].SUNLinSol_Dense(yy, A, ctx), A)
    ida.IDASetJacFn(mem, kernels.jacobian.address)
    ida.IDASStolerances(mem, RTOL, ATOL)
    ida.IDASetMaxNumSteps(mem, 200_000)  # as circuitsim sets it
    ida.IDASetStopTime(mem, t_eval[-1])
    out = np.empty((t_eval.size, n))
    out[0] = Y
    tret = ctypes.c_double()
    ref, step = ctypes.byref(tret), ida.IDASolve
    for k in range(1, t_eval.size):
        if step(mem, t_eval[k], ref, yy, yp, IDA_NORMAL) < 0:
            raise RuntimeError(f"IDASolve failed before t = {t_eval[k]}")
        out[k] = Y
    calls = ctypes.c_long()
    ida.IDAGetNumResEvals(mem, ctypes.byref(calls))
    return out, calls.value


def child() -> dict:
    """In a fresh process: numba's import, the kernels' compile or cache load, both solves."""
    t0 = time.perf_counter()
    import numba  # noqa: F401

    t1 = time.perf_counter()
    sys.path.insert(0, str(HERE))
    import compiled_route_kernels as kernels

    t2 = time.perf_counter()
    warnings.simplefilter("ignore")
    import circuitsim as cs

    model = cs.compile(cs.load(NETLIST))
    ref = model.simulate(rtol=RTOL, atol=ATOL)
    lib = _libraries()
    args = (lib, kernels, model.param_vector(), ref.y[:, 0], ref.yp[:, 0], ref.t)
    direct, calls = solve_direct(*args)
    t_direct = min(_timed(lambda: solve_direct(*args)) for _ in range(7))
    t_sim = min(_timed(lambda: model.simulate(rtol=RTOL, atol=ATOL)) for _ in range(5))
    diff = float(np.max(np.abs(direct.T - ref.y) / (np.abs(ref.y).max(axis=1)[:, None] + 1e-300)))
    return {"numba_import": t1 - t0, "kernels": t2 - t1, "direct": t_direct, "simulate": t_sim,
            "calls_direct": calls, "calls_simulate": ref.nfev, "max_rel_diff": diff}


def _timed(fn) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


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
        print("numba is not installed: `pip install numba` to measure this route")
        return 1
    env = {**os.environ, "NUMBA_CACHE_DIR": tempfile.mkdtemp(prefix="bench-numba-"),
           "CIRCUITSIM_CACHE": tempfile.mkdtemp(prefix="bench-cache-")}
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
    from bench_base import ngspice_timed

    return ngspice_timed(10e-6, 3)["rusage"]


def report(runs: list[dict], ng: float | None) -> None:
    cold, warm = runs
    best_direct = min(r["direct"] for r in runs)
    best_sim = min(r["simulate"] for r in runs)
    print("Kim & Kim base model, 0.3 s from rest, rtol 2e-6, atol 1e-8, 6001 output points")
    print(f"  model.simulate (scikit-sundae, Python residual)   {best_sim * 1e3:7.1f} ms, "
          f"{cold['calls_simulate']} residual calls")
    print(f"  IDA direct + numba cfunc kernels                 {best_direct * 1e3:7.1f} ms, "
          f"{cold['calls_direct']} residual calls; states differ from simulate's by "
          f"{max(r['max_rel_diff'] for r in runs):.1e} (relative)")
    if ng:
        print(f"  ngspice, trap, tmax 10 us                        {ng * 1e3:7.1f} ms -> "
              f"simulate {best_sim / ng:.2f}x, direct {best_direct / ng:.2f}x ngspice")
    print(f"  per process: import numba {min(r['numba_import'] for r in runs):.2f} s; kernels "
          f"compiled {cold['kernels']:.2f} s (empty cache), loaded from numba's cache "
          f"{warm['kernels']:.2f} s")
    fixed = min(r["numba_import"] for r in runs) + warm["kernels"]
    print(f"  the route pays for itself after about {fixed / (best_sim - best_direct):.0f} "
          f"base-model solves in one process")


if __name__ == "__main__":
    raise SystemExit(main())
