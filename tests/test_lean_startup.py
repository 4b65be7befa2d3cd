"""A run served from the model cache imports none of the heavy libraries it has no use for, and
the shortcuts that make it so give the answers of the libraries they stand in for (#14)."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import NETLISTS, ROOT

# sympy: derivation; pint, jsonschema: answered from the memo tables; scipy.optimize, scipy.fft:
# scikit-sundae's import and the ripple fit no longer need them; matplotlib: only for a plot
HEAVY = ("sympy", "pint", "jsonschema", "scipy.optimize", "scipy.fft", "matplotlib", "dask",
         "circuitsim.loop.fit", "circuitsim.loop.diagnose")  # the study verbs' modules

RUN = """
import contextlib, io, json, sys, warnings
warnings.simplefilter("ignore")
from circuitsim.cli.main import main
with contextlib.redirect_stdout(io.StringIO()) as out:
    code = main(["run", sys.argv[1], "--no-files", "--quiet", "--json"])
print(json.dumps({"code": code, "summary": json.loads(out.getvalue()),
                  "heavy": sorted(m for m in sys.argv[2:] if m in sys.modules)}))
"""


def _run(netlist, cache) -> dict:
    env = {**os.environ, "CIRCUITSIM_CACHE": str(cache)}
    proc = subprocess.run([sys.executable, "-c", RUN, str(netlist), *HEAVY], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=300, check=True)
    return json.loads(proc.stdout.splitlines()[-1])


def test_a_cached_run_imports_no_heavy_library(tmp_path):
    netlist = NETLISTS / "kim2024" / "base.yaml"
    cold = _run(netlist, tmp_path / "cache")
    assert "sympy" in cold["heavy"]  # the first run derives the model
    warm = _run(netlist, tmp_path / "cache")
    assert warm["code"] == 0 and warm["heavy"] == []
    assert warm["summary"]["probes"] == cold["summary"]["probes"]


def test_remembered_units_are_pints_answers(tmp_path, monkeypatch):
    from circuitsim import units

    monkeypatch.setenv("CIRCUITSIM_CACHE", str(tmp_path))
    names = ["mH", "V*s/rev", "rpm", "kg*m^2", "N*m*s/rad", "uF", "k", "meg", "no_such_unit"]

    def answers() -> list:
        units.unit_info.cache_clear()
        out = []
        for name in names:
            try:
                out.append(units.unit_info(name))
            except ValueError as exc:
                out.append(str(exc))
        return out

    fresh = answers()  # pint computes and the memo stores
    monkeypatch.setattr(units, "registry", lambda: pytest.fail("pint asked again"))
    assert answers() == fresh


def test_a_hand_edited_unit_entry_is_computed_again(tmp_path, monkeypatch):
    import json

    from circuitsim import units

    monkeypatch.setenv("CIRCUITSIM_CACHE", str(tmp_path))
    units.unit_info.cache_clear()
    right = units.unit_info("mH")
    table = next(tmp_path.glob("memo-units-*.json"))
    table.write_text(json.dumps({"mH": ["one", [], 0.0]}))
    units._memo.cache_clear()
    units.unit_info.cache_clear()
    assert units.unit_info("mH") == right


def test_bounded_minimum_takes_scipys_steps():
    from scipy.optimize import minimize_scalar

    from circuitsim.signal import bounded_minimum

    cases = [(lambda u: (u - 0.3) ** 2, -1.5, 1.5), (lambda u: np.cos(7 * u) + 0.1 * u, -2, 2),
             (lambda u: abs(u - 0.1) ** 0.5, -1, 3), (lambda u: float(np.floor(4 * u)) ** 2,
                                                       -1, 1)]
    for f, lo, hi in cases:
        for xatol in (1e-10, 1e-5):
            ref = minimize_scalar(f, bounds=(lo, hi), method="bounded",
                                  options={"xatol": xatol, "maxiter": 500})
            assert bounded_minimum(f, lo, hi, xatol=xatol, maxiter=500) == float(ref.x)


def test_ida_import_leaves_scipy_whole():
    """The stand-ins used while scikit-sundae is imported are gone afterwards."""
    code = ("from circuitsim.solve.sundae import ida_class; ida_class(); import sys; "
            "assert 'scipy.optimize._numdiff' not in sys.modules; "
            "from scipy.optimize import minimize_scalar; import scipy.sparse as s; "
            "assert type(s).__name__ == 'module'; print('ok')")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, timeout=120)
    assert out.stdout.strip() == "ok"
