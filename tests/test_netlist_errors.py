"""Bad input: every error names the file, the line, the component and a word of the fix.

Each test writes a small netlist, loads it (and, for the structural checks, compiles it) and
checks the message of the project's own exception. A hypothesis test feeds mutated copies of
netlists/examples/rlc.yaml to the loader: nothing but ``CircuitsimError`` may escape.
"""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

import circuitsim as cs
from circuitsim.cli import main as cli_main

RLC = (Path(__file__).resolve().parent.parent / "netlists" / "examples" / "rlc.yaml").read_text(
    encoding="utf-8")


def _load(path: Path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cs.load(path)


def _compile(net):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cs.compile(net)


def _check(exc: BaseException, path: Path, line: int, component: str | None, *words: str) -> str:
    """The message names ``file:line``, the component and every word given (case-blind)."""
    msg = str(exc)
    assert f"{path.name}:{line}:" in msg, msg
    # exactly this line, not e.g. net.yaml:17 when 1 was expected
    assert re.search(rf"{re.escape(path.name)}:{line}(?!\d)", msg), msg
    if component is not None:
        assert re.search(rf"\b{re.escape(component)}\b", msg), msg
        assert exc.component == component
    for w in words:
        assert w.lower() in msg.lower(), f"{w!r} not in {msg!r}"
    assert exc.loc is not None and exc.loc.line == line
    assert Path(exc.loc.file).name == path.name
    return msg


# --------------------------------------------------------------------------------------
# Loader errors: syntax, names, parameters, units, validity, domains, expressions
# --------------------------------------------------------------------------------------


def test_yaml_syntax_error(write_netlist):
    path = write_netlist("""
        title: broken
        components:
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
          - {name: C1, type: C, p: a, n: gnd, C: 1 uF
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
        """)
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    msg = str(ei.value)
    assert "YAML syntax error" in msg
    # The parser notices the unclosed brace at the start of the next entry.
    assert ei.value.loc is not None and ei.value.loc.line in (4, 5), msg
    assert re.search(rf"{path.name}:[45]:", msg), msg
    assert "indentation" in msg or "quotes" in msg


def test_yaml_syntax_error_bad_indentation(write_netlist):
    path = write_netlist("""
        components:
          - name: R1
            type: R
           p: a
        """)
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    msg = str(ei.value)
    assert re.search(rf"{path.name}:[345]:", msg), msg
    assert "indentation" in msg


def test_unknown_component_type(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: resistr, p: a, n: gnd, R: 1 ohm}
        """)
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    msg = _check(ei.value, path, 3, "R1", "unknown component type", "resistr",
                 "circuitsim components")
    assert "'resistor'" in msg  # did you mean


def test_unknown_parameter(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - name: L1
            type: L
            p: a
            n: gnd
            L: 1 mH
            Rs: 1 ohm
        """)
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    _check(ei.value, path, 8, "L1", "unknown parameter 'Rs'", "known:", "i0")


def test_missing_parameter(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - name: C1
            type: C
            p: a
            n: gnd
        """)
    with pytest.raises(cs.ParameterError) as ei:
        cs.load(path)
    _check(ei.value, path, 3, "C1", "missing parameter 'C'", "add 'C: <value>'")


def test_missing_port(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, R: 1 ohm}
        """)
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    _check(ei.value, path, 3, "R1", "port 'n'", "not connected", "add 'n: <node>'")


def test_wrong_unit_dimension(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - name: L1
            type: L
            p: a
            n: gnd
            L: 5 ohm
        """)
    with pytest.raises(cs.ParameterError) as ei:
        cs.load(path)
    _check(ei.value, path, 7, "L1", "parameter 'L'", "expected", "in H")


def test_wrong_unit_dimension_through_named_parameter(write_netlist):
    path = write_netlist("""
        parameters:
          Lx: 5 ohm
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: L1, type: L, p: a, n: gnd, L: Lx}
        """)
    with pytest.raises(cs.ParameterError) as ei:
        cs.load(path)
    _check(ei.value, path, 5, "L1", "parameter 'L'", "expected", "in H")


def test_negative_inductance(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - name: L1
            type: L
            p: a
            n: gnd
            L: -2 mH
        """)
    with pytest.raises(cs.ParameterError) as ei:
        cs.load(path)
    _check(ei.value, path, 7, "L1", "L = -0.002", "must be positive", "inductance")


@pytest.mark.parametrize("value", ["nan", "1e999 H", "inf"])
def test_non_finite_value(write_netlist, value):
    path = write_netlist(f"""
        components:
          - {{name: V1, type: V, p: a, n: gnd, V: 1 V}}
          - name: L1
            type: L
            p: a
            n: gnd
            L: {value}
        """)
    with pytest.raises(cs.CircuitsimError) as ei:
        cs.load(path)
    _check(ei.value, path, 7, "L1", "'L'" if value == "inf" else "L")


def test_electrical_pin_on_shaft_node(write_netlist):
    path = write_netlist("""
        components:
          - {name: Jr, type: inertia, shaft: rotor, J: 1e-5 kg*m^2}
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - name: R1
            type: R
            p: a
            n: rotor
            R: 1 ohm
        """)
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    msg = _check(ei.value, path, 7, "R1", "port 'n' is electrical", "'rotor' is rotational",
                 "coupling component", "emf")
    assert f"{path.name}:2" in msg  # where the node was first used as a shaft


def test_electrical_pin_on_mechanical_reference(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: fixed, R: 1 ohm}
        """)
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    _check(ei.value, path, 3, "R1", "'fixed' is the rotational reference", "use gnd or 0")


def test_duplicate_component_name(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: b, R: 1 ohm}
          - {name: R1, type: R, p: b, n: gnd, R: 1 ohm}
        """)
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    msg = _check(ei.value, path, 4, "R1", "used twice", "net.yaml:3")
    assert "also at" in msg


def test_expression_naming_unknown_parameter(write_netlist):
    path = write_netlist("""
        parameters:
          Rload: 10 ohm
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - name: R1
            type: R
            p: a
            n: gnd
            R: 2*Rlaod
        """)
    with pytest.raises(cs.ParameterError) as ei:
        cs.load(path)
    _check(ei.value, path, 9, "R1", "unknown parameter 'Rlaod'", "did you mean 'Rload'",
           "define it under 'parameters:'")


def test_global_parameter_naming_unknown_parameter(write_netlist):
    path = write_netlist("""
        parameters:
          R0: 10 ohm
          R2: 2*R9
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: gnd, R: R2}
        """)
    with pytest.raises(cs.ParameterError) as ei:
        cs.load(path)
    _check(ei.value, path, 3, None, "parameter 'R2' refers to unknown parameter 'R9'")


CODE = [
    "__import__('os').system('touch PWNED')",
    "(lambda: 1)()",
    "().__class__",
    "open('PWNED', 'w')",
    "exec('1')",
    "R.__class__.__mro__",
    "1 ohm.__class__",
    "[1, 2][0]",
    "1 if 1 else 2",
    "1 ohm; import os",
]


@pytest.mark.parametrize("code", CODE)
def test_expression_running_code_is_rejected_unevaluated(write_netlist, tmp_path, monkeypatch,
                                                         code):
    monkeypatch.chdir(tmp_path)
    import builtins

    calls = []
    real_import = builtins.__import__

    def spy(name, *args, **kwargs):
        if name == "os" and args and args[0] is None:  # an import with no module globals
            calls.append(name)
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", spy)
    quoted = "'" + code.replace("'", "''") + "'"
    path = write_netlist(f"""
        parameters:
          R: 1 ohm
        components:
          - {{name: V1, type: V, p: a, n: gnd, V: 1 V}}
          - name: R1
            type: R
            p: a
            n: gnd
            R: {quoted}
        """)
    with pytest.raises(cs.CircuitsimError) as ei:
        cs.load(path)
    monkeypatch.setattr(builtins, "__import__", real_import)
    _check(ei.value, path, 9, "R1", "parameter 'R'")
    assert not (tmp_path / "PWNED").exists()
    assert not calls


def test_expression_running_code_in_global_parameter(write_netlist, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = write_netlist("""
        parameters:
          R: "__import__('os').system('touch PWNED')"
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: gnd, R: R}
        """)
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    _check(ei.value, path, 2, None, "parameter 'R'", "Values are numbers with optional units")
    assert not (tmp_path / "PWNED").exists()


def test_expression_running_code_in_probe(write_netlist, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
        probes:
          v: a.v
          evil: "__import__('os').system('touch PWNED')"
        """)
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    _check(ei.value, path, 6, None, "probe 'evil'")
    assert not (tmp_path / "PWNED").exists()


# --------------------------------------------------------------------------------------
# Rotation speed units: Hz is ambiguous by 2*pi, rpm is fine
# --------------------------------------------------------------------------------------


def test_rotation_speed_in_hz_is_rejected(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
          - name: Jr
            type: inertia
            shaft: rotor
            J: 1e-5 kg*m^2
            w0: 50 Hz
          - {name: Bv, type: damper, shaft: rotor, b: 1e-5 N*m*s/rad}
        """)
    with pytest.raises(cs.ParameterError) as ei:
        cs.load(path)
    _check(ei.value, path, 8, "Jr", "parameter 'w0'", "Hz is ambiguous by 2*pi", "rad/s",
           "rpm")


def test_rotation_speed_in_rpm_is_accepted(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
          - {name: Jr, type: inertia, shaft: rotor, J: 1e-5 kg*m^2, w0: 6200 rpm}
          - {name: Bv, type: damper, shaft: rotor, b: 1e-5 N*m*s/rad}
        """)
    net = _load(path)
    w0 = net.component("Jr").values["Jr.w0"].si(net.global_values())
    assert w0 == pytest.approx(6200 * 2 * math.pi / 60, rel=1e-12)
    assert w0 == pytest.approx(649.26, abs=5e-3)


def test_rotation_speed_in_rev_per_s_via_parameter_is_accepted(write_netlist):
    path = write_netlist("""
        parameters:
          n0: 10 rev/s
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
          - {name: Jr, type: inertia, shaft: rotor, J: 1e-5 kg*m^2, w0: n0}
          - {name: Bv, type: damper, shaft: rotor, b: 1e-5 N*m*s/rad}
        """)
    net = _load(path)
    w0 = net.component("Jr").values["Jr.w0"].si(net.global_values())
    assert w0 == pytest.approx(20 * math.pi, rel=1e-12)


def test_frequency_in_rad_per_s_is_rejected(write_netlist):
    path = write_netlist("""
        components:
          - name: V1
            type: V
            p: a
            n: gnd
            V: {sine: {amplitude: 1 V, freq: 314 rad/s}}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
        """)
    with pytest.raises(cs.ParameterError) as ei:
        cs.load(path)
    _check(ei.value, path, 6, "V1", "freq", "not per angle", "Hz")


# --------------------------------------------------------------------------------------
# Structural errors found by compile(): floating node, source loop, current-source cut-set
# --------------------------------------------------------------------------------------


def test_floating_node(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
          - name: C2
            type: C
            p: x
            n: y
            C: 1 uF
          - {name: R2, type: R, p: x, n: y, R: 1 ohm}
        """)
    net = _load(path)
    with pytest.raises(cs.SingularCircuitError) as ei:
        _compile(net)
    # names the first (alphabetically) of the components that connect the floating nodes
    msg = _check(ei.value, path, 4, "C2", "no path to the reference 'gnd'", "bleed resistor")
    assert "{x, y}" in msg and "C2, R2" in msg


def test_dangling_node(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: b, R: 1 ohm}
          - {name: R2, type: R, p: bb, n: gnd, R: 1 ohm}
        """)
    net = _load(path)
    with pytest.raises(cs.NetlistError) as ei:
        _compile(net)
    _check(ei.value, path, 3, "R1", "node 'b'", "typo for 'bb'", "connect it")


def test_voltage_source_loop(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
          - name: V2
            type: V
            p: a
            n: gnd
            V: 2 V
        """)
    net = _load(path)
    with pytest.raises(cs.SingularCircuitError) as ei:
        _compile(net)
    msg = _check(ei.value, path, 4, "V2", "loop of ideal voltage sources", "series resistance")
    assert "V1, V2" in msg


def test_current_source_cutset(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
          - name: I1
            type: I
            p: gnd
            n: x
            I: 1 mA
          - {name: C1, type: C, p: x, n: y, C: 1 uF}
          - {name: I2, type: I, p: y, n: gnd, I: 1 mA}
        """)
    net = _load(path)
    with pytest.raises(cs.SingularCircuitError) as ei:
        _compile(net)
    msg = _check(ei.value, path, 4, "I1", "cut-set of ideal current sources", "shunt path")
    assert "I1, I2" in msg and "x, y" in msg


def test_shaft_without_inertia(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
          - {name: T1, type: torque, shaft: rotor, T: 1 N*m}
          - {name: Bv, type: damper, shaft: rotor, b: 1e-5 N*m*s/rad}
        """)
    net = _load(path)
    with pytest.raises(cs.SingularCircuitError) as ei:
        _compile(net)
    _check(ei.value, path, 5, "Bv", "rotor", "add an 'inertia'")


# --------------------------------------------------------------------------------------
# The command line: exit code 2, one ``error:`` line, no traceback
# --------------------------------------------------------------------------------------


def test_cli_reports_wrong_unit(write_netlist, capsys):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: L1, type: L, p: a, n: gnd, L: 5 ohm}
        """)
    assert cli_main(["run", str(path), "--no-files"]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert err.startswith("error: ")
    assert "Traceback" not in err
    assert f"{path.name}:3:" in err and "L1" in err and "in H" in err


def test_cli_reports_source_loop(write_netlist, capsys):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: V2, type: V, p: a, n: gnd, V: 2 V}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
        """)
    assert cli_main(["run", str(path), "--no-files"]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert err.startswith("error: ")
    assert "Traceback" not in err
    assert f"{path.name}:3:" in err and "V2" in err and "series resistance" in err


def test_cli_reports_yaml_syntax_error(write_netlist, capsys):
    path = write_netlist("components: [\n")
    assert cli_main(["check", str(path)]) == 2
    _, err = capsys.readouterr()
    assert err.startswith("error: ") and "YAML syntax error" in err and "Traceback" not in err


# --------------------------------------------------------------------------------------
# Fuzz: mutated netlists raise nothing but CircuitsimError
# --------------------------------------------------------------------------------------

LINES = RLC.splitlines(keepends=True)
ALPHABET = ["'", '"', "[", "]", "{", "}", ":", ",", "-", " ", "mH", "Hz", "rpm", "rad/s", "1e999",
            "nan", "inf", "0", "-1", "1", "2.5", "x", "R", "L1", "gnd", "(", ")", "*", "/", "^",
            "**", "#", "&a", "*a", "!!python/object:os.system", "\t", "%", "|", "__", "."]
VALUE = re.compile(r"(?<=: )[^,{}\[\]\n]+")


@st.composite
def mutated(draw):
    lines = list(LINES)
    for _ in range(draw(st.integers(1, 3))):
        op = draw(st.sampled_from(["delete", "duplicate", "swap", "char", "value", "append"]))
        i = draw(st.integers(0, len(lines) - 1))
        if op == "delete" and len(lines) > 1:
            del lines[i]
        elif op == "duplicate":
            lines.insert(i, lines[i])
        elif op == "swap":
            j = draw(st.integers(0, len(lines) - 1))
            lines[i], lines[j] = lines[j], lines[i]
        elif op == "char" and lines[i]:
            k = draw(st.integers(0, len(lines[i]) - 1))
            new = draw(st.text(st.characters(min_codepoint=32, max_codepoint=126), max_size=3))
            lines[i] = lines[i][:k] + new + lines[i][k + 1:]
        elif op == "value":
            spans = [m.span() for m in VALUE.finditer(lines[i])]
            if spans:
                a, b = draw(st.sampled_from(spans))
                new = "".join(draw(st.lists(st.sampled_from(ALPHABET), min_size=1, max_size=4)))
                lines[i] = lines[i][:a] + new + lines[i][b:]
        elif op == "append":
            lines.insert(i, "".join(draw(st.lists(st.sampled_from(ALPHABET), max_size=6))) + "\n")
    return "".join(lines)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(text=mutated())
def test_mutated_netlists_raise_only_circuitsim_errors(tmp_path, text):
    path = tmp_path / "fuzz.yaml"
    path.write_text(text, encoding="utf-8")
    try:
        net = _load(path)
    except cs.CircuitsimError as exc:
        assert "fuzz.yaml" in str(exc)
        event(f"load: {type(exc).__name__}")
        return
    try:
        _compile(net)
    except cs.CircuitsimError as exc:
        event(f"compile: {type(exc).__name__}")
    else:
        event("compiled")
