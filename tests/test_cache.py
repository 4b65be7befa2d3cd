"""Compile once per topology: the second compile imports the cached code, no sympy work."""

from __future__ import annotations

import pickle
import warnings

import pytest

import circuitsim as cs
from circuitsim.compiler import mna

from conftest import NETLISTS


def test_second_compile_uses_the_cache(monkeypatch):
    net = cs.load(NETLISTS / "examples" / "dc_motor.yaml")
    first = cs.compile(net)

    def boom(*a, **k):
        raise AssertionError("re-derived a cached topology")

    monkeypatch.setattr(mna, "assemble", boom)
    second = cs.compile(cs.load(NETLISTS / "examples" / "dc_motor.yaml"))
    assert second.key == first.key
    assert second.simulate(stop=0.05).success


def test_values_do_not_change_the_key_but_structure_does(write_netlist):
    a = cs.load(write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1}
          - {name: R1, type: R, p: a, n: gnd, R: 1}
    """, "a.yaml"))
    b = cs.load(write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 5 V}
          - {name: R1, type: R, p: a, n: gnd, R: 3 kohm}
    """, "b.yaml"))
    c = cs.load(write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1}
          - {name: R1, type: C, p: a, n: gnd, C: 1}
    """, "c.yaml"))
    assert a.topology_key() == b.topology_key() != c.topology_key()


def test_new_kernel_helpers_never_meet_a_model_cached_before(monkeypatch):
    # the generated kernels import the shared helpers under a name that is their source's
    # hash: a model cached with other helpers would name a module no longer written (and
    # quietly run on the Python route), so the helpers' source is part of every model's key
    from pathlib import Path

    from circuitsim.compiler import cache

    topology = cs.load(NETLISTS / "examples" / "dc_motor.yaml").topology_key()
    before = cache.cache_key(topology)
    read = Path.read_bytes

    def edited(path):
        data = read(path)
        return data + b"# edited" if path.name == "kernel_lib.py" else data

    monkeypatch.setattr(Path, "read_bytes", edited)
    assert cache.cache_key(topology) != before


def test_compiled_model_pickles_for_worker_processes():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(cs.load(NETLISTS / "kim2024" / "base.yaml"))
    clone = pickle.loads(pickle.dumps(model))
    res = clone.simulate(stop=0.01, params={"Ra": 1.2})
    ref = model.simulate(stop=0.01, params={"Ra": 1.2})
    assert res["i_total"][-1] == pytest.approx(ref["i_total"][-1], rel=1e-12)


def test_init_op_starts_at_the_averaged_steady_state():
    """Kim base: the operating point (ripple averaged over a turn) is the closed-form DC
    state, and a run from it is already steady."""
    from circuitsim.solve.op import operating_point

    from reference import kim_dc_steady_state

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(cs.load(NETLISTS / "kim2024" / "base.yaml"))
    w, _, _ = kim_dc_steady_state()
    op = operating_point(model)
    assert op["rotor.w"] == pytest.approx(w, rel=1e-9)
    res = model.simulate(stop=0.02, init="op")
    assert res["speed"][0] == pytest.approx(w, rel=1e-9)
    # only the ripple (2.2 rad/s at the 8th order) starts up; the mean is already there
    assert res.harmonic("speed", order=8, window=0.5).offset == pytest.approx(w, abs=0.02)


# --- the cache runs only what it wrote (issue 16) -------------------------------------------
RC = """
    components:
      - {name: V1, type: V, p: a, n: gnd, V: 1}
      - {name: R1, type: R, p: a, n: b, R: 1 kohm}
      - {name: C1, type: C, p: b, n: gnd, C: 1 uF}
    probes: {vc: C1.v, ic: C1.i}
    analysis: {stop: 5 ms, step: 0.1 ms, rtol: 1e-9, atol: 1e-12}
"""
PLANT = "import os\nos.environ['CIRCUITSIM_PLANTED'] = 'ran'\n"


def _rc_model(write_netlist):
    return cs.compile(cs.load(write_netlist(RC, "rc.yaml")))


def _recompiles_and_is_right(write_netlist, monkeypatch):
    """The next compile derives again (nothing planted runs) and the RC step is exact."""
    import numpy as np

    calls = []
    real = mna.assemble
    monkeypatch.setattr(mna, "assemble", lambda net: calls.append(1) or real(net))
    model = _rc_model(write_netlist)
    res = model.simulate()
    assert calls, "a tampered cache entry was used instead of deriving again"
    assert "CIRCUITSIM_PLANTED" not in __import__("os").environ
    assert res.probes == ("vc", "ic")
    np.testing.assert_allclose(res["vc"], 1 - np.exp(-res.t / 1e-3), atol=1e-6)


@pytest.fixture
def clean_env(monkeypatch):
    monkeypatch.delenv("CIRCUITSIM_PLANTED", raising=False)
    yield
    __import__("os").environ.pop("CIRCUITSIM_PLANTED", None)


def test_code_appended_to_a_cached_module_never_runs(write_netlist, monkeypatch, clean_env):
    from circuitsim.compiler.cache import cache_dir

    key = _rc_model(write_netlist).key
    with open(cache_dir() / f"{key}.py", "a", encoding="utf-8") as fh:
        fh.write("\n" + PLANT)
    _recompiles_and_is_right(write_netlist, monkeypatch)


def test_a_planted_bytecode_file_never_runs(write_netlist, monkeypatch, clean_env):
    """Bytecode in __pycache__ (the import system's cache) or in our own .code file."""
    import marshal
    import sys

    from circuitsim.compiler.cache import cache_dir

    key = _rc_model(write_netlist).key
    code = marshal.dumps(compile(PLANT, "x.py", "exec"))
    tag = sys.implementation.cache_tag
    (cache_dir() / "__pycache__").mkdir(exist_ok=True)
    (cache_dir() / "__pycache__" / f"{key}.{tag}.pyc").write_bytes(b"\0" * 16 + code)
    (cache_dir() / f"{key}.code").write_bytes(code)
    _recompiles_and_is_right(write_netlist, monkeypatch)


@pytest.mark.parametrize("damage", ["truncate", "meta_empty", "probe_count"])
def test_a_damaged_entry_is_derived_again(write_netlist, monkeypatch, clean_env, damage):
    """A truncated module that is still valid Python, metadata edited to {}, an edited probe
    count: each fails the hash and is derived again, never a traceback or a lost probe."""
    import json

    from circuitsim.compiler.cache import cache_dir

    key = _rc_model(write_netlist).key
    py, js = cache_dir() / f"{key}.py", cache_dir() / f"{key}.json"
    if damage == "truncate":
        text = py.read_text(encoding="utf-8")
        py.write_text(text[: text.index("def make")], encoding="utf-8")
    elif damage == "meta_empty":
        js.write_text("{}", encoding="utf-8")
    else:
        meta = json.loads(js.read_text(encoding="utf-8"))
        meta["n_probes"] = 1
        js.write_text(json.dumps(meta), encoding="utf-8")
    _recompiles_and_is_right(write_netlist, monkeypatch)


@pytest.mark.skipif(not hasattr(__import__("os"), "getuid"), reason="POSIX permissions only")
def test_a_cache_folder_others_can_write_is_refused(write_netlist, monkeypatch, tmp_path,
                                                    clean_env):
    """Anyone who can write the folder could plant a whole consistent entry (module, bytecode,
    metadata and hash): such a folder is not used at all, with a warning saying what to do."""
    import json
    import marshal
    import os

    from circuitsim.compiler import cache
    from circuitsim.errors import CircuitWarning

    private = _rc_model(write_netlist)
    shared = tmp_path / "shared"
    shared.mkdir()
    os.chmod(shared, 0o777)
    monkeypatch.setenv("CIRCUITSIM_CACHE", str(shared))
    src = PLANT.encode()
    js = json.dumps(private.meta).encode()
    code = marshal.dumps(compile(src, "x.py", "exec"))
    for suffix, data in ((".py", src), (".json", js), (".code", code)):
        (shared / f"{private.key}{suffix}").write_bytes(data)
    (shared / f"{private.key}.sha256").write_text(cache._digest(src, js, code))
    with pytest.warns(CircuitWarning, match="other users can write"):
        _recompiles_and_is_right(write_netlist, monkeypatch)
    assert sorted(p.name for p in shared.iterdir()) == sorted(
        f"{private.key}{s}" for s in (".py", ".json", ".code", ".sha256"))
