"""The cache folder kept in bounds (``cachefolder``, ``circuitsim cache``): every file
circuitsim writes is known, other files are never touched, the least recently used entries
go first, and a pruned or cleared folder gives the same numbers again."""

from __future__ import annotations

import os
import time

import numpy as np
import pytest

import circuitsim as cs
from circuitsim import cachefolder as cf
from circuitsim.cli.main import main
from circuitsim.compiler import mna

from conftest import NETLISTS

pytestmark = pytest.mark.filterwarnings("ignore::circuitsim.errors.CircuitWarning")
DC_MOTOR = NETLISTS / "examples" / "dc_motor.yaml"


@pytest.fixture
def folder(tmp_path, monkeypatch):
    """An empty private cache folder of this test's own."""
    d = tmp_path / "cache"
    d.mkdir(mode=0o700)
    monkeypatch.setenv("CIRCUITSIM_CACHE", str(d))
    return d


def _run(monkeypatch, kernels: str):
    monkeypatch.setenv("CIRCUITSIM_KERNELS", kernels)
    return cs.compile(cs.load(DC_MOTOR)).simulate(stop=0.05)


def _all_files(d):
    """Every file of the folder and of its ``__pycache__``."""
    return sorted(p for p in [*d.iterdir(), *(d / "__pycache__").glob("*")] if p.is_file())


@pytest.mark.parametrize("cc", ["off", "on"])
def test_every_file_a_run_writes_is_an_entry_and_clear_gives_the_same_numbers(folder,
                                                                            monkeypatch, cc):
    """A run on the compiled kernels fills the folder with a model, its kernel module, the
    kernels' library and numba's machine code for both -- or, with a C compiler, the
    module's compiled library instead of numba's code for it: every file belongs to an
    entry. Cleared, the folder is empty, and the next run derives and compiles again to the
    bit."""
    pytest.importorskip("numba")
    from circuitsim.solve import ccode, direct

    if cc == "off":
        monkeypatch.setenv("CIRCUITSIM_CC", "off")
    elif ccode.compiler() is None:
        pytest.skip("no C compiler on this machine: numba's route is the other case")
    # kernels an earlier test loaded in this process, from its own folder, are not reused
    monkeypatch.setattr(direct, "_LOADED", {})
    first = _run(monkeypatch, "numba")
    found, other = cf.entries(folder)
    assert other == 0, [p.name for p in _all_files(folder)]
    kinds = {e.kind for e in found}
    assert {"model", "kernels", "kernel library"} <= kinds, kinds
    assert ("compiled kernels" in kinds) == (cc == "on")
    assert sum(len(e.files) for e in found) == len(_all_files(folder))
    numba_kept = any(f.parent.name == "__pycache__" for e in found if e.kind == "kernels"
                     for f in e.files)  # numba's own files go with their module
    assert numba_kept == (cc == "off")
    assert main(["cache", "clear"]) == 0
    assert _all_files(folder) == []
    monkeypatch.setattr(direct, "_LOADED", {})
    again = _run(monkeypatch, "numba")
    assert np.array_equal(first.y, again.y) and np.array_equal(first.t, again.t)
    assert {e.kind for e in cf.entries(folder)[0]} >= {"model", "kernels"}  # written again


def test_other_files_are_never_touched(folder, monkeypatch):
    """Files that only look like circuitsim's (another digest length, another suffix) and
    files of other programs stay through a clear."""
    _run(monkeypatch, "python")
    foreign = [folder / "notes.txt", folder / "m0123.py", folder / ("m" + "a" * 24 + ".txt"),
               folder / ("k" + "b" * 24 + "_kernels.txt")]
    for f in foreign:
        f.write_text("keep me")
    found, other = cf.entries(folder)
    assert other == 4 * len("keep me") and found
    assert main(["cache", "clear"]) == 0
    assert sorted(_all_files(folder)) == sorted(foreign)


def _entry(stem: str, size: int, used: float) -> cf.Entry:
    return cf.Entry(stem, (), size, used)


def test_prune_takes_the_least_recently_used_and_spares_what_is_in_use():
    """Closed form on entries of known size and use: down to a size, the oldest go first
    (kernels named the old way before everything); by age, those idle longer; an entry used
    in the last ten minutes stays whatever the limit."""
    now = 1e9
    day = 86400.0
    legacy = _entry("m" + "1" * 24 + "_kernels", 50, now - 60.0)  # recent file, old naming
    old = _entry("m" + "2" * 24, 100, now - 40 * day)
    mid = _entry("k" + "3" * 24 + "_kernels", 100, now - 5 * day)
    busy = _entry("m" + "4" * 24, 100, now - 60.0)
    found = [legacy, old, mid, busy]  # as ``entries`` orders them
    assert cf.choose(found, max_size=250, now=now) == [legacy, old]
    assert cf.choose(found, max_size=0, now=now) == [legacy, old, mid]  # busy stays
    assert cf.choose(found, older_than=30 * day, now=now) == [legacy, old]
    assert cf.choose(found, max_size=150, older_than=30 * day, now=now) == [legacy, old, mid]
    assert cf.choose(found, now=now) == []


def test_prune_on_a_real_folder_removes_what_was_idle(folder, monkeypatch):
    """Two topologies compiled; one's files dated 40 days back: ``prune --older-than 30d``
    removes that one alone, and the other's next compile is a cache hit."""
    _run(monkeypatch, "python")

    def models():
        return [e for e in cf.entries(folder)[0] if e.kind == "model"]

    (before,) = models()
    long_ago = time.time() - 40 * 86400.0
    for f in before.files:
        os.utime(f, (long_ago, long_ago))
    cs.compile(cs.load(NETLISTS / "examples" / "rc.yaml"))
    assert len(models()) == 2
    assert main(["cache", "prune", "--older-than", "30d"]) == 0
    (left,) = models()
    assert left.stem != before.stem and not any(f.exists() for f in before.files)

    def boom(*a, **k):
        raise AssertionError("re-derived a topology the prune kept")

    monkeypatch.setattr(mna, "assemble", boom)
    assert cs.compile(cs.load(NETLISTS / "examples" / "rc.yaml")).simulate().success


@pytest.mark.parametrize(("text", "value"), [("500MB", 500e6), ("2G", 2e9), ("1.5GiB",
                                              1.5 * 1024**3), ("800000", 8e5), ("10 kB", 1e4)])
def test_sizes_read_as_bytes(text, value):
    assert cf.parse_size(text) == int(value)


@pytest.mark.parametrize(("text", "value"), [("30d", 30 * 86400.0), ("12h", 43200.0),
                                              ("2w", 1209600.0), ("90min", 5400.0)])
def test_ages_read_as_seconds(text, value):
    assert cf.parse_age(text) == value


@pytest.mark.parametrize("args", [["cache", "prune"], ["cache", "prune", "--max-size", "5XB"],
                                  ["cache", "prune", "--older-than", "30 days"]])
def test_bad_requests_exit_2_and_say_what_to_write(folder, capsys, args):
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.startswith("error:") and ("e.g." in err or "as in" in err), err


def test_a_folder_others_can_write_is_not_managed(tmp_path, monkeypatch, capsys):
    d = tmp_path / "shared"
    d.mkdir()
    d.chmod(0o777)
    (d / ("m" + "c" * 24 + ".py")).write_text("x")
    monkeypatch.setenv("CIRCUITSIM_CACHE", str(d))
    assert main(["cache", "clear"]) == 2
    assert "not managed" in capsys.readouterr().err
    assert (d / ("m" + "c" * 24 + ".py")).exists()


def test_info_lists_the_folder(folder, monkeypatch, capsys):
    _run(monkeypatch, "python")
    assert main(["cache"]) == 0
    out = capsys.readouterr().out
    assert str(folder) in out and "model" in out


def test_a_cache_path_that_is_a_file_is_said_so(tmp_path, monkeypatch, capsys):
    """CIRCUITSIM_CACHE at a file: `cache info` reported '0 entries' and `clear` 'removed 0'
    as if it were an empty folder, and a run warned with mkdir's 'File exists'."""
    from circuitsim.memo import open_cache_dir

    file = tmp_path / "a-file"
    file.write_text("not a folder")
    monkeypatch.setenv("CIRCUITSIM_CACHE", str(file))
    for action in ("info", "clear"):
        assert main(["cache", action]) == 2
        assert "is a file, not a folder" in capsys.readouterr().err
    assert open_cache_dir()[1] == "it is a file, not a folder"
    monkeypatch.setenv("CIRCUITSIM_CACHE", str(file / "below"))
    assert open_cache_dir()[1] == f"{file}, a part of its path, is a file"
    assert file.read_text() == "not a folder"
