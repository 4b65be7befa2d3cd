"""Hostile and broken netlists (issue 16): every one exits 2 within seconds, naming file:line,
without a traceback, without reading outside the netlist's folder tree unless allowed, and
without echoing what a data file holds. A hypothesis test mutates a netlist with hostile
fragments; what it found is kept below as plain regression tests."""

from __future__ import annotations

import time

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import circuitsim as cs
from circuitsim.cli.main import main

BASE = """title: t
components:
  - {name: V1, type: V, p: a, n: gnd, V: 1}
  - {name: R1, type: R, p: a, n: b, R: 1k}
  - {name: C1, type: C, p: b, n: gnd, C: 1u}
probes: {v: b.v}
analysis: {stop: 1 ms}
"""


def _bomb() -> str:
    lines = ["a0: &a0 [x, x, x, x, x, x, x, x, x]"]
    for i in range(1, 7):
        lines.append(f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]")
    return "\n".join(lines) + "\n"


CASES = {
    # name: (text or bytes, the line the message must name, words it must hold)
    "anchor bomb": (_bomb(), 2, "expands"),
    "bad encoding": (b"title: t\n\xff\xfe bad\n", 2, "UTF-8"),
    "deep nesting": ("title: t\nx: " + "[" * 3000 + "]" * 3000 + "\n", 2, "nested too deeply"),
    "merge key": ("title: t\nparameters:\n  <<: 5\ncomponents: []\n", 3, "merging"),
    "huge integer": (BASE.replace("R: 1k", "R: " + "9" * 5000), 4, "digits"),
    "include folder": ("include: [sub]\n" + BASE, 1, "is a folder"),
    "include device": ("include: [/dev/zero]\n" + BASE, 1, "outside"),
    "include outside": ("include: [../../../../etc/hostname]\n" + BASE, 1, "outside"),
    "table device": (BASE.replace("V: 1}", "V: {table: {file: /dev/zero, column: v}}}"), 3,
                     "outside"),
    "table outside": (BASE.replace("V: 1}", "V: {table: {file: /etc/passwd, column: v}}}"), 3,
                      "outside"),
    "include cycle": ("include: [net.yaml]\n" + BASE, 1, "include cycle"),
    "femto step": (BASE.replace("stop: 1 ms", "stop: 1, step: 1 fs"), 7, "output points"),
}


@pytest.fixture
def folder(tmp_path):
    """A netlist folder two levels below tmp_path, with a sub-folder."""
    d = tmp_path / "a" / "b"
    (d / "sub").mkdir(parents=True)
    return d


@pytest.mark.parametrize("name", list(CASES))
def test_hostile_netlist_exits_2_fast_with_file_and_line(name, folder, capsys):
    text, line, words = CASES[name]
    path = folder / "net.yaml"
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text)
    start = time.perf_counter()
    assert main(["check", str(path)]) == 2
    assert time.perf_counter() - start < 5.0
    err = capsys.readouterr().err
    assert f"net.yaml:{line}:" in err, err
    assert words in err and "Traceback" not in err


def test_include_fan_out_is_cut_short(folder, capsys):
    """Each file includes the next four times: 4^8 reads unless stopped."""
    for i in range(8):
        (folder / f"f{i}.yaml").write_text("include: [" + ", ".join([f"f{i + 1}.yaml"] * 4) +
                                           "]\n")
    (folder / "f8.yaml").write_text("parameters: {x: 1}\n")
    (folder / "net.yaml").write_text("include: [f0.yaml]\n" + BASE)
    start = time.perf_counter()
    assert main(["check", str(folder / "net.yaml")]) == 2
    assert time.perf_counter() - start < 5.0
    assert "more than 200 files are included" in capsys.readouterr().err


def test_allow_outside_reads_a_table_outside_the_tree(folder, tmp_path, capsys):
    data = tmp_path / "supply.csv"
    data.write_text("time,v\n0,2\n1,2\n")
    path = folder / "net.yaml"
    path.write_text(BASE.replace("V: 1}", f"V: {{table: {{file: {data}, column: v}}}}}}"))
    assert main(["op", str(path)]) == 2
    assert "outside" in capsys.readouterr().err
    assert main(["op", str(path), "--allow-outside", "--json"]) == 0
    assert '"v": 2.0' in capsys.readouterr().out
    # a device stays refused even when outside files are allowed: it would never end
    path.write_text(BASE.replace("V: 1}", "V: {table: {file: /dev/zero, column: v}}}"))
    assert main(["check", str(path), "--allow-outside"]) == 2
    assert "not a regular file" in capsys.readouterr().err


def test_data_content_is_never_echoed(folder, capsys):
    """A table or an include holding a secret: the message names the file, not the secret."""
    (folder / "keys.csv").write_text("time,v\n0,sk-SECRET-TOKEN\n1,2\n")
    (folder / "keys.yaml").write_text("components: sk-SECRET-TOKEN\n")
    path = folder / "net.yaml"
    path.write_text(BASE.replace("V: 1}", "V: {table: {file: keys.csv, column: v}}}"))
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "keys.csv" in err and "SECRET" not in err
    path.write_text("include: [keys.yaml]\n" + BASE)
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "keys.yaml:1" in err and "SECRET" not in err


# --- fuzzing --------------------------------------------------------------------------------

FRAGMENTS = ["&a", "*a", "<<: *a", "[" * 200, "{", "}", "include: [/dev/zero]",
             "include: [net.yaml]", "9" * 4500, "1e999", "$x$", "R1.n", "pi", "t", "time",
             "\t", "'", '"', ":", "- ", "!!float", "1M", "10k", "1F", "\x00", "a,b", "..",
             "table: {file: ../../x.csv, column: v}"]


@settings(max_examples=60, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(st.tuples(st.integers(0, len(BASE)), st.sampled_from(FRAGMENTS)),
                min_size=1, max_size=4))
def test_mutated_netlists_fail_only_cleanly(folder, edits):
    """Hostile fragments spliced into a netlist: it loads, or raises the project's own error
    naming the file, within 5 s. Anything else (a traceback, a hang) is a finding."""
    text = BASE
    for pos, frag in sorted(edits, reverse=True):
        text = text[:pos] + frag + text[pos:]
    path = folder / "net.yaml"
    path.write_text(text, encoding="utf-8", errors="surrogateescape")
    start = time.perf_counter()
    try:
        cs.load(path)
    except cs.CircuitsimError as exc:
        assert "net.yaml" in str(exc)
    assert time.perf_counter() - start < 5.0
