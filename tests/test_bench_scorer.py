"""The diagnosis benchmark's scorer (benchmarks/diagnosis/run.py) on hand-made truths and
reports: when a named effect counts as a tie rather than a miss."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

RUN = Path(__file__).resolve().parents[1] / "benchmarks" / "diagnosis" / "run.py"


@pytest.fixture(scope="module")
def run():
    spec = importlib.util.spec_from_file_location("bench_run", RUN)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _entry(sigma: float) -> dict:
    """A two-effect truth: a warm-up of Ra and a Coulomb friction on the fan, which is
    ``sigma`` from the same friction on the rotor (location_sigma)."""
    return {"id": "x", "class": "two", "declared_terms": [],
            "effects": [{"effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
                         "expected": {}},
                        {"effect": "coulomb-friction", "target": "fan", "targets": ["fan"],
                         "expected": {}}],
            "location_sigma": [{"effect": "coulomb-friction", "target": "fan",
                                "other": "rotor", "sigma": sigma, "imprint_sigma": 850.0}]}


def _report(indistinct: list[str]) -> dict:
    effects = [{"effect": "coulomb-friction", "target": "rotor", "parameters": {}},
               {"effect": "resistance-drift", "target": "Ra", "parameters": {}}]
    return {"status": "ok", "effects": effects, "corrections": [], "indistinct": indistinct,
            "remaining": {"structure": False}}


SAID = [("coulomb-friction:fan and coulomb-friction:rotor explain this record almost "
         "equally well (ΔBIC -5062.0 vs -5061.3): the data cannot tell them apart")]


def test_an_effect_on_the_other_side_of_a_coupling_it_cannot_be_told_from_is_a_tie(run):
    sc = run.score(_entry(0.9), _report(SAID))
    assert sc["verdict"] == "tie" and not sc["right"]
    assert [m["truth"] for m in sc["matches"]] == ["resistance-drift"]


@pytest.mark.parametrize("sigma, said", [(18.4, SAID), (0.9, [])])
def test_a_place_the_data_tells_apart_or_a_report_silent_on_it_is_a_miss(run, sigma, said):
    """Beyond TIE_SIGMA the record can tell the two places apart (an unbalance on a blower,
    18 sigma from the rotor's); below it the report must still say it cannot."""
    assert run.score(_entry(sigma), _report(said))["verdict"] == "partial"


@pytest.mark.parametrize("structure", [False, True])
def test_a_null_record_is_right_only_when_the_report_says_nothing_remains(run, structure):
    """A null record with nothing accepted is right when the report says nothing remains,
    and a miss when it says something remains that it cannot name (a false alarm in words:
    the nine slow null records with 1/f speed noise said so before the coherence rule)."""
    entry = {"id": "n", "class": "null", "declared_terms": [], "effects": []}
    report = {"status": "ok", "effects": [], "corrections": [], "indistinct": [],
              "remaining": {"structure": structure}}
    assert run.score(entry, report)["right"] is (not structure)
