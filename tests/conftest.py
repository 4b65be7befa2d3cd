"""Shared fixtures: an isolated model cache, netlist helpers, the reference modules on path."""

from __future__ import annotations

import os
import sys
import textwrap
import warnings
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
NETLISTS = ROOT / "netlists"
sys.path.insert(0, str(HERE))


@pytest.fixture(scope="session", autouse=True)
def _isolated_cache(tmp_path_factory):
    """Every test session derives into its own cache (a stale one can hide a bug)."""
    os.environ["CIRCUITSIM_CACHE"] = str(tmp_path_factory.mktemp("cache"))


@pytest.fixture
def write_netlist(tmp_path):
    """Write YAML text (dedented) to a file and return its path."""

    def write(text: str, name: str = "net.yaml") -> Path:
        p = tmp_path / name
        p.write_text(textwrap.dedent(text).lstrip("\n"), encoding="utf-8")
        return p

    return write


@pytest.fixture
def compile_text(write_netlist):
    """Load and compile YAML text; physics warnings are silenced."""
    import circuitsim as cs

    def build(text: str):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            # a test's netlist in tmp_path may include the repository's (e.g. kim2024's
            # motor.yaml): the test is trusted, its folder is not the data's
            return cs.compile(cs.load(write_netlist(text), allow_outside=True))

    return build


def kim_steps(monkeypatch) -> tuple:
    """The Kim base model on the compiled kernels, its unknowns, and ten steps of Ra from
    one point (the point first): finite differences for the batch tests."""
    import circuitsim as cs

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(cs.load(NETLISTS / "kim2024" / "base.yaml"))
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "numba")
    sets = [{"Ra": 1.1}] + [{"Ra": 1.1 * (1 + 1e-4 * j)} for j in range(1, 11)]
    return model, len(model.state_names), sets


def white_over_pink(seed: int, n: int = 1200) -> tuple[np.ndarray, np.ndarray]:
    """White noise of 0.015 and a 1/f noise of 0.02 (its amplitude spectrum 1/sqrt(k), by
    FFT) over 6 s at 200 Hz, as fresh33's null record ak02 read its gate's speed; and the
    white noise alone."""
    rng = np.random.default_rng(seed)
    white = 0.015 * rng.normal(size=n)
    spectrum = np.fft.rfft(rng.normal(size=n))
    spectrum[0] = 0.0
    spectrum[1:] /= np.sqrt(np.arange(1, spectrum.size))
    pink = np.fft.irfft(spectrum, n)
    return white + pink * (0.02 / pink.std()), white
