"""netlists/kim2024/README.md is what netlists/kim2024/study.py computes (issue #3)."""

from __future__ import annotations

import importlib.util
import re

import pytest

from conftest import NETLISTS

README = (NETLISTS / "kim2024" / "README.md").read_text()


@pytest.fixture(scope="module")
def study():
    spec = importlib.util.spec_from_file_location("kim_study", NETLISTS / "kim2024" / "study.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _readme_row(case: str) -> list[str]:
    line = next(ln for ln in README.splitlines() if ln.startswith(f"| {case} |"))
    return [c.strip() for c in line.strip("|").split("|")]


def test_case_table_matches_the_readme(study):
    for r in study.case_table(jobs=2):
        cells = _readme_row(r["case"])
        assert float(cells[2]) == pytest.approx(r["i_total.mean"], abs=1e-5)
        assert float(cells[3]) == pytest.approx(r["speed.mean"], abs=1e-3)
        assert float(cells[4]) == pytest.approx(r["i_total.ripple_amp"], abs=1e-5)
        assert float(cells[5]) == pytest.approx(r["i_total.ripple_freq"], abs=0.01)
        assert float(cells[6]) == pytest.approx(r["attenuation_db"], abs=0.1)
        assert abs(r["energy.balance"]) < 1e-5 * r["energy.delivered"]


def test_case4_back_emf_answer(study):
    """Both motors: the EMF peak exceeds 12 V because its ripple exceeds the resistive drop,
    while its mean stays below the input."""
    for k_e in (None, study.K_T):
        d = study.case4_emf(k_e)
        assert d["emf_peak"] > 12.0 > d["emf_dc"]
        assert d["emf_ripple"] > d["drop"]
        row = re.escape(f"{d['emf_peak']:.4f}")
        assert re.search(row, README), f"README lacks EMF peak {d['emf_peak']:.4f}"
