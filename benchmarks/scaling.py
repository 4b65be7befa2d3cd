"""Scaling benchmark: compile and solve cost against circuit size, beside ngspice.

Run from the repository root::

    python benchmarks/scaling.py                       # the default ladders (~2-4 min)
    python benchmarks/scaling.py --family rc --sizes 50 100 200 300
    python benchmarks/scaling.py --json out.json

Three families, each written as a user would write the netlist (one component per line):

* ``rc``: RC ladder, 1 kOhm series + 1 nF shunt per section, 1 V step from rest, 1 ms.
* ``rlc``: RLC ladder, 1 Ohm + 1 uH series, 1 nF shunt per section, 1 V step, 20 us.
* ``motors``: N Kim & Kim motors (``netlists/kim2024/motor.yaml``'s parts) on one 12 V bus,
  10 mOhm + 0.1 uH per bus segment, 5 ms from rest.

Each size runs in a fresh subprocess with an empty model cache, so "compile" is a cold
derivation (sympy, index reduction, code generation) plus the netlist load, in CPU seconds,
and "peak RSS" is that process's maximum resident set (compile + solve). "solve" is
``simulate`` on the compiled model, best of two, wall clock, scikit-sundae already imported.
The ngspice deck of the same circuit runs with trapezoidal integration, reltol 1e-6 and a
maximum step of 1/2000 of the run; its wall time includes process start-up. Final values of
the last node and of the node a tenth of the way along (for motors, the last node and the
last rotor speed) are compared with ngspice's: the column ``|dv|`` is the largest absolute
difference relative to the source voltage (speeds: relative to 648.5 rad/s).
Growth exponents are least-squares slopes of log(cost) against log(N).

With ``--compiled`` (numba installed: ``pip install ".[fast]"``) each size is also solved on the
compiled route (``CIRCUITSIM_KERNELS=numba``, ``circuitsim/solve/direct.py``): the first such
solve compiles the kernels (CPU seconds, column "kernels"; by the C compiler where one
exists, ``solve/ccode.py``, else by numba; ``CIRCUITSIM_CC=off`` forces numba), then both
routes are timed in turns, minimum of three each in CPU seconds (both are single-threaded;
the machine is shared), and the table gives the ratio compiled / Python and whether the two results are the same to the bit
(times, states and derivatives)::

    python benchmarks/scaling.py --compiled --family rc --sizes 300
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from ngspice import have_ngspice, run_ngspice

STOP = {"rc": 1e-3, "rlc": 2e-5, "motors": 5e-3}  # [s]
DEFAULT_SIZES = {"rc": [50, 100, 200, 300], "rlc": [100, 250, 500, 1000],
                 "motors": [10, 25, 50, 100]}
# motor parameters of netlists/kim2024/motor.yaml in SI units (k_e, A8_slope per rad/s)
KIM = {"Ra": 1.1, "La": 0.87e-3, "L_conn": 0.22e-6, "Rv": 500e6, "Cv": 1.6e-6, "J": 4.57e-6,
       "B": 2.95e-4, "k_t": 0.14, "k_e": 0.1017 / (2 * np.pi), "e0": 1.151e-4,
       "A8_slope": 0.0168 / (2 * np.pi), "A8_offset": 2.504e-5}


# ---------------------------------------------------------------- netlists and decks
def _yaml(title: str, comps: list[str], stop: float, probes: dict[str, str]) -> str:
    lines = [f"title: {title}", "components:"]
    lines += [f"  - {c}" for c in comps]
    lines += ["probes:"] + [f"  {k}: {v}" for k, v in probes.items()]
    lines += ["analysis:", f"  stop: {stop!r}", f"  step: {stop / 200!r}",
              "  rtol: 1e-6", "  atol: 1e-9"]
    return "\n".join(lines) + "\n"


def ladder_netlist(n: int, inductive: bool) -> str:
    """RC (1 kOhm, 1 nF) or RLC (1 Ohm + 1 uH, 1 nF) ladder of n sections."""
    comps = ["{name: Vs, type: V, p: n0, n: gnd, V: 1}"]
    for k in range(1, n + 1):
        if inductive:
            comps += [f"{{name: R{k}, type: R, p: n{k - 1}, n: x{k}, R: 1}}",
                      f"{{name: L{k}, type: L, p: x{k}, n: n{k}, L: 1e-6}}"]
        else:
            comps.append(f"{{name: R{k}, type: R, p: n{k - 1}, n: n{k}, R: 1000}}")
        comps.append(f"{{name: C{k}, type: C, p: n{k}, n: gnd, C: 1e-9}}")
    fam = "rlc" if inductive else "rc"
    return _yaml(f"{fam} ladder {n}", comps, STOP[fam],
                 {"v_end": f"n{n}.v", "v_mid": f"n{max(n // 10, 1)}.v"})


def ladder_deck(n: int, inductive: bool) -> str:
    fam = "rlc" if inductive else "rc"
    lines = [f"* {fam} ladder {n}", "Vs n0 0 DC 1"]
    for k in range(1, n + 1):
        if inductive:
            lines += [f"R{k} n{k - 1} x{k} 1", f"L{k} x{k} n{k} 1e-6 IC=0"]
        else:
            lines.append(f"R{k} n{k - 1} n{k} 1000")
        lines.append(f"C{k} n{k} 0 1e-9 IC=0")
    stop = STOP[fam]
    lines += [".options reltol=1e-6 method=trap",
              f".tran {stop / 2000!r} {stop!r} 0 {stop / 2000!r} uic"]
    return "\n".join(lines) + "\n"


def motors_netlist(n: int) -> str:
    """n Kim & Kim motors on one 12 V bus of R-L segments."""
    comps = ["{name: Vin, type: V, p: b0, n: gnd, V: 12}"]
    h = (f"harmonics: [{{order: 8, slope: {KIM['A8_slope']!r}, "
         f"offset: {KIM['A8_offset']!r}, phase: 0}}]")
    for k in range(1, n + 1):
        comps += [
            f"{{name: Rs{k}, type: R, p: b{k - 1}, n: s{k}, R: 0.01}}",
            f"{{name: Ls{k}, type: L, p: s{k}, n: b{k}, L: 1e-7}}",
            (f"{{name: Var{k}, type: varistor_rc, p: b{k}, n: gnd, R: {KIM['Rv']!r}, "
             f"C: {KIM['Cv']!r}}}"),
            f"{{name: Lc1_{k}, type: L, p: b{k}, n: mb{k}, L: {KIM['L_conn']!r}}}",
            f"{{name: Ra{k}, type: R, p: mb{k}, n: m1_{k}, R: {KIM['Ra']!r}}}",
            f"{{name: La{k}, type: L, p: m1_{k}, n: m2_{k}, L: {KIM['La']!r}}}",
            (f"{{name: M{k}, type: emf, p: m2_{k}, n: c{k}, shaft: r{k}, "
             f"k_t: {KIM['k_t']!r}, k_e: {KIM['k_e']!r}, e0: {KIM['e0']!r}, "
             f"ripple_torque: false, {h}}}"),
            f"{{name: Lc2_{k}, type: L, p: c{k}, n: gnd, L: {KIM['L_conn']!r}}}",
            f"{{name: Jr{k}, type: inertia, shaft: r{k}, J: {KIM['J']!r}}}",
            f"{{name: Bv{k}, type: damper, shaft: r{k}, b: {KIM['B']!r}}}",
        ]
    return _yaml(f"{n} motors on a bus", comps, STOP["motors"],
                 {"v_end": f"b{n}.v", "w_end": f"r{n}.w"})


def motors_deck(n: int) -> str:
    p = KIM
    lines = [f"* {n} Kim motors on a bus", "Vin b0 0 DC 12"]
    for k in range(1, n + 1):
        emf = (f"V = {p['k_e']!r}*v(w{k}) + {p['e0']!r} + ({p['A8_slope']!r}*v(w{k}) + "
               f"{p['A8_offset']!r})*sin(8*v(th{k}))")
        lines += [
            f"Rs{k} b{k - 1} s{k} 0.01", f"Ls{k} s{k} b{k} 1e-7 IC=0",
            f"Rv{k} b{k} va{k} {p['Rv']!r}", f"Cv{k} va{k} 0 {p['Cv']!r} IC=0",
            f"Lca{k} b{k} mb{k} {p['L_conn']!r} IC=0", f"Vm{k} mb{k} q{k} DC 0",
            f"Ra{k} q{k} m1_{k} {p['Ra']!r}", f"La{k} m1_{k} m2_{k} {p['La']!r} IC=0",
            f"Be{k} m2_{k} c{k} {emf}", f"Lcb{k} c{k} 0 {p['L_conn']!r} IC=0",
            f"Bt{k} 0 w{k} I = {p['k_t']!r}*i(vm{k})", f"Cj{k} w{k} 0 {p['J']!r} IC=0",
            f"Rb{k} w{k} 0 {1 / p['B']!r}", f"Bth{k} 0 th{k} I = v(w{k})",
            f"Cth{k} th{k} 0 1 IC=0",
        ]
    stop = STOP["motors"]
    lines += [".options reltol=1e-6 method=trap",
              f".tran {stop / 2000!r} {stop!r} 0 {stop / 2000!r} uic"]
    return "\n".join(lines) + "\n"


def netlist(fam: str, n: int) -> str:
    return motors_netlist(n) if fam == "motors" else ladder_netlist(n, fam == "rlc")


def deck(fam: str, n: int) -> str:
    return motors_deck(n) if fam == "motors" else ladder_deck(n, fam == "rlc")


def ngspice_vectors(fam: str, n: int) -> list[str]:
    return [f"v(b{n})", f"v(w{n})"] if fam == "motors" else [f"v(n{n})", f"v(n{max(n // 10, 1)})"]


# ---------------------------------------------------------------- one size, in a child
def compiled_route(model, python) -> dict:
    """The compiled route against the Python one on the same model: kernel compile [s CPU],
    the minimum of three solves each, taken in turns [s CPU], and whether they agree bit for
    bit."""
    t0 = time.process_time()
    os.environ["CIRCUITSIM_KERNELS"] = "numba"
    first = model.simulate()
    kernels_s = time.process_time() - t0
    from circuitsim.solve import direct

    if direct._LOADED.get(model.key) is None:
        return {"compiled": "not taken (see the warning on stderr)"}
    best = {"python": float("inf"), "numba": float("inf")}
    for _ in range(3):
        for route in ("python", "numba"):
            os.environ["CIRCUITSIM_KERNELS"] = route
            t0 = time.process_time()
            model.simulate()
            best[route] = min(best[route], time.process_time() - t0)
    same = all(np.array_equal(a, b) for a, b in ((python.t, first.t), (python.y, first.y),
                                                 (python.yp, first.yp)))
    return {"kernels_s": kernels_s, "solve_python_s": best["python"],
            "solve_numba_s": best["numba"], "bitwise": same}


def child(fam: str, n: int, compiled: bool = False) -> dict:
    """Compile cold and solve; runs in its own process with an empty cache."""
    import warnings

    import circuitsim as cs

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / f"{fam}{n}.yaml"
        path.write_text(netlist(fam, n))
        t0 = time.process_time()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            model = cs.compile(cs.load(path))
        t_compile = time.process_time() - t0
        import sksundae  # noqa: F401 - its import (0.5 s) is not the solve
        t_solve = float("inf")
        os.environ["CIRCUITSIM_KERNELS"] = "python"
        for _ in range(2):  # best of two: the machine is shared
            t0 = time.perf_counter()
            res = model.simulate()
            t_solve = min(t_solve, time.perf_counter() - t0)
        route = compiled_route(model, res) if compiled else {}
    second = "w_end" if fam == "motors" else "v_mid"
    finals = {"v_end": float(res["v_end"][-1]), second: float(res[second][-1])}
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # [MiB]
    return {"family": fam, "n": n, "unknowns": len(model.state_names),
            "nnz": model.meta.get("jac_nnz"), "compile_s": t_compile, "solve_s": t_solve,
            "rss_mib": rss, "ok": res.success, "finals": finals,
            "linsolver": model.linsolver, **route}


def measure(fam: str, n: int, timeout: float, compiled: bool = False) -> dict:
    env = dict(os.environ)
    with tempfile.TemporaryDirectory() as cache:
        env["CIRCUITSIM_CACHE"] = cache
        cmd = [sys.executable, __file__, "--child", fam, str(n)] + ["--compiled"] * compiled
        try:
            proc = subprocess.run(cmd, capture_output=True, text=True, env=env,
                                  timeout=timeout, check=False)
        except subprocess.TimeoutExpired:
            return {"family": fam, "n": n, "error": f"timed out after {timeout:g} s"}
    if proc.returncode != 0:
        return {"family": fam, "n": n, "error": proc.stderr.strip().splitlines()[-1:]}
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    if have_ngspice():
        t0 = time.perf_counter()
        data = run_ngspice(deck(fam, n), ngspice_vectors(fam, n), timeout=timeout)
        out["ngspice_s"] = time.perf_counter() - t0
        ref = [data[v][-1] for v in ngspice_vectors(fam, n)]
        got = list(out["finals"].values())
        scale = [12.0, 648.5] if fam == "motors" else [1.0, 1.0]
        out["dv"] = max(abs(a - b) / s for a, b, s in zip(got, ref, scale, strict=True))
    return out


def slope(rows: list[dict], key: str) -> float:
    ok = [r for r in rows if r.get(key)]
    if len(ok) < 2:
        return float("nan")
    x = np.log([r["n"] for r in ok])
    y = np.log([r[key] for r in ok])
    return float(np.polyfit(x, y, 1)[0])


def print_compiled(r: dict) -> None:
    if "solve_numba_s" not in r:
        print(f"         compiled route: {r.get('compiled', 'not measured')}")
        return
    py, nb = r["solve_python_s"], r["solve_numba_s"]
    print(f"         compiled route: kernels {r['kernels_s']:.1f} s CPU (once, then cached); "
          f"solve (CPU) Python {py:.3f} s, compiled {nb:.3f} s = {nb / py:.2f}x; "
          f"{'the same to the bit' if r['bitwise'] else 'DIFFERENT numbers'}", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--family", choices=["rc", "rlc", "motors"], action="append")
    ap.add_argument("--sizes", type=int, nargs="+")
    ap.add_argument("--timeout", type=float, default=300.0)
    ap.add_argument("--json")
    ap.add_argument("--compiled", action="store_true",
                    help="also time the compiled route (numba) against the Python one")
    ap.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.child:
        print(json.dumps(child(a.child[0], int(a.child[1]), a.compiled)))
        return
    rows: list[dict] = []
    for fam in a.family or ["rc", "rlc", "motors"]:
        fam_rows = []
        print(f"\n{fam}: N  unknowns  jac-nnz  compile[s]  solve[s]  peakRSS[MiB]  "
              f"ngspice[s]  |dv|  linsolver")
        for n in a.sizes or DEFAULT_SIZES[fam]:
            r = measure(fam, n, a.timeout, a.compiled)
            fam_rows.append(r)
            if "error" in r:
                print(f"  {n:5d}  {r['error']}")
                continue
            print(f"  {n:5d}  {r['unknowns']:7d}  {r['nnz']!s:>7}  {r['compile_s']:9.2f}  "
                  f"{r['solve_s']:8.3f}  {r['rss_mib']:8.0f}  {r.get('ngspice_s', 0):9.3f}  "
                  f"{r.get('dv', float('nan')):.1e}  {r['linsolver']}", flush=True)
            if a.compiled:
                print_compiled(r)
        print(f"  growth exponents: compile N^{slope(fam_rows, 'compile_s'):.2f}, solve "
              f"N^{slope(fam_rows, 'solve_s'):.2f}, nnz N^{slope(fam_rows, 'nnz'):.2f}, "
              f"ngspice N^{slope(fam_rows, 'ngspice_s'):.2f}")
        rows += fam_rows
    if a.json:
        Path(a.json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
