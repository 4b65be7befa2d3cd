"""The kernels' two compilers measured: numba against the system's C compiler (``solve/ccode.py``).

Run from anywhere, with numba installed (``pip install .[fast]``) and a C compiler::

    python benchmarks/bench_ccode.py
    python benchmarks/bench_ccode.py --json out.json

For each model, in a fresh process with an empty cache folder and no compile-ahead worker,
once with ``CIRCUITSIM_CC=off`` (numba compiles the kernels) and once with the compiler: the
first solve on the kernels, less the best of three later solves, is the kernels' compile
[s]; the best of three is the run time [s]. numba's import and the output loop every topology
shares are paid before (on a small RC model), and the model's equations are derived before,
so neither is counted. Both routes must give the same times and states to the bit. Models:
the Kim & Kim base motor, fresh15's P-fast model with five catalog effects patched in (the
size of a diagnosis' joint screen), and RLC ladders of 50 and 200 sections with a varistor
clamp (100 and 400 unknowns: the large kernels' sparse product; 400 unknowns the sparse
solver's compressed columns).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "benchmarks"))

from common import best_of  # after the path it is found on

RC = """
components:
  - {name: V1, type: V, p: in, n: gnd, V: 1 V}
  - {name: R1, type: R, p: in, n: out, R: 1 kohm}
  - {name: C1, type: C, p: out, n: gnd, C: 1 uF}
probes: {v: out.v}
analysis: {stop: 1 ms, step: 10 us}
"""
MODELS = {"kim2024 base (7 unknowns)": ("base", 0.05),
          "P-fast motor + 5 catalog effects": ("patched", 0.05),
          "RLC ladder, 50 sections (100 unknowns)": ("ladder50", 2e-5),
          "RLC ladder, 200 sections (400 unknowns)": ("ladder200", 2e-5)}


def _netlist(kind: str, folder: Path):
    import circuitsim as cs

    if kind == "base":
        return cs.load(ROOT / "netlists" / "kim2024" / "base.yaml")
    if kind == "patched":
        return _patched()
    from test_scale import rlc_ladder_with_a_nonlinear_load

    path = folder / f"{kind}.yaml"
    path.write_text(rlc_ladder_with_a_nonlinear_load(int(kind[6:])), encoding="utf-8")
    return cs.load(path)


def _patched():
    """fresh15's motor P (a 50 kHz record's model) with the first candidate of each of five
    catalog effects patched in, at their start values: a diagnosis' joint screen compiles
    models of this kind (the declared model plus its candidates)."""
    import circuitsim as cs
    from circuitsim.loop.effects import candidates
    from circuitsim.netlist.load import build

    net = cs.load(ROOT / "benchmarks" / "diagnosis" / "netlists" / "motor_p.yaml")
    raw, seen = net.raw, set()
    for cand in candidates(net, duration=0.5):
        if cand.effect in seen or cand.effect.startswith("sensor"):
            continue
        seen.add(cand.effect)
        raw = cand.apply(raw)
        if len(seen) == 5:
            break
    return build(raw)


def child(kind: str, stop: float) -> dict:
    """In a fresh process: the kernels' compile and run time of one model on one route."""
    warnings.simplefilter("ignore")
    import circuitsim as cs
    from circuitsim.solve import direct

    os.environ["CIRCUITSIM_KERNELS"] = "numba"
    folder = Path(os.environ["CIRCUITSIM_CACHE"])
    small = folder / "rc.yaml"
    small.write_text(RC, encoding="utf-8")
    cs.compile(cs.load(small)).simulate()  # numba's import, the shared output loop
    model = cs.compile(_netlist(kind, folder))
    t0 = time.perf_counter()
    first = model.simulate(stop=stop)
    first_s = time.perf_counter() - t0
    run_s, _ = best_of(3, lambda: model.simulate(stop=stop))
    module = direct._LOADED.get(model.key)
    digest = hashlib.sha256(first.t.tobytes() + first.y.tobytes()).hexdigest()
    return {"compile": first_s - run_s, "run": run_s, "digest": digest, "nfev": first.nfev,
            "states": len(model.state_names),
            "c": module is not None and direct.c_library(module) is not None}


def _measure(kind: str, stop: float, cc: str) -> dict:
    env = {**os.environ, "CIRCUITSIM_CACHE": tempfile.mkdtemp(prefix="bench-cc-"),
           "CIRCUITSIM_AHEAD": "off"}
    if cc == "off":
        env["CIRCUITSIM_CC"] = "off"
    else:
        env.pop("CIRCUITSIM_CC", None)
    out = subprocess.run([sys.executable, __file__, "--child", kind, str(stop)], env=env,
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout.splitlines()[-1])


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    ap.add_argument("--json", help="also write the results to this JSON file")
    args = ap.parse_args(argv)
    if args.child:
        print(json.dumps(child(args.child[0], float(args.child[1]))))
        return 0
    from circuitsim.solve import ccode

    if ccode.compiler() is None:
        print("no C compiler (CIRCUITSIM_CC, the one Python was built with, or cc)")
        return 1
    print(f"{'model':42s} {'compile numba':>13s} {'compile C':>10s} {'ratio':>6s} "
          f"{'run numba':>10s} {'run C':>8s} {'ratio':>6s}  same bits")
    results = {}
    for label, (kind, stop) in MODELS.items():
        nb, c = _measure(kind, stop, "off"), _measure(kind, stop, "on")
        results[label] = {"numba": nb, "c": c}
        same = nb["digest"] == c["digest"] and nb["nfev"] == c["nfev"]
        print(f"{label:42s} {nb['compile']:11.2f} s {c['compile']:8.2f} s "
              f"{nb['compile'] / c['compile']:5.1f}x {nb['run'] * 1e3:7.1f} ms "
              f"{c['run'] * 1e3:5.1f} ms {nb['run'] / c['run']:5.2f}x  {same}"
              + ("" if c["c"] else "  (C route not taken)"))
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=1), encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
