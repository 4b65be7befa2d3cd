"""Bad input: every error names the file, the line, the component and a word of the fix.

Each test writes a small netlist, loads it (and, for the structural checks, compiles it) and
checks the message of the project's own exception. A hypothesis test feeds mutated copies of
netlists/examples/rlc.yaml to the loader: nothing but ``CircuitsimError`` may escape.
"""

from __future__ import annotations

import contextlib
import math
import re
import signal
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

import circuitsim as cs
from circuitsim.cli.main import main as cli_main

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


@contextlib.contextmanager
def _deadline(seconds: int):
    """Fail instead of hanging when the loader takes longer than ``seconds``."""

    def fire(*_):
        raise TimeoutError(f"the loader took more than {seconds} s")

    old = signal.signal(signal.SIGALRM, fire)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


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
    # The parser notices the unclosed brace of line 4 at the start of line 5, and says both.
    _check(ei.value, path, 5, None, "YAML syntax error", "flow mapping from line 4",
           "check indentation, colons and quotes")


@pytest.mark.parametrize(("text", "line", "words"), [
    ("components:\n  - name: R1\n    type: R\n   p: a\n", 4, ("block collection from line 2",)),
    ('components:\n  - {name: R1, type: R, p: a, n: gnd, R: "1 ohm}\n  - {name: V1}\n', 2,
     ("end of stream", "quoted scalar")),  # where the quote opened, not past the last line
    ("parameters:\n  R: 1 ohm\n  R: 2 ohm\ncomponents: []\n", 3, ("duplicate key",)),
    ("components:\n\t- {name: R1}\n", 2, ("'\\t'",)),
])
def test_yaml_syntax_errors_name_the_line(write_netlist, text, line, words):
    path = write_netlist(text)
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    _check(ei.value, path, line, None, "YAML syntax error", *words)


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


@pytest.mark.parametrize("setting, words", [
    ("rtol: 2", ("rtol = 2", "(0, 0.01]", "off by percents")),
    ("rtol: 0.1", ("rtol = 0.1", "(0, 0.01]")),
    ("step: 0 us", ("step = 0", "must be positive", "leave 'step' out")),
])
def test_analysis_settings_that_would_give_a_wrong_answer(write_netlist, setting, words):
    # rtol 2 let IDA accept 200 % errors per step: the RLC's capacitor ended at 0.99 V, not
    # 1.53 V, without a word (1.79 V at rtol 0.1); step 0 was read as 'no step given'
    path = write_netlist(f"""
        components:
          - {{name: V1, type: V, p: a, n: gnd, V: 1 V}}
          - {{name: R1, type: R, p: a, n: b, R: 1 ohm}}
          - {{name: C1, type: C, p: b, n: gnd, C: 1 mF}}
        analysis:
          stop: 5 ms
          {setting}
        """)
    with pytest.raises(cs.ParameterError) as ei:
        cs.load(path)
    _check(ei.value, path, 7, None, "analysis", *words)


@pytest.mark.parametrize(("kw", "words"), [
    # each of these returned a result before: t = [0] alone with success True (t_eval beyond
    # stop, a NaN time), values at a negative time, or IDA's own error printed mid-run
    ({"stop": 1e-3, "t_eval": [0.0, 2e-3]}, "outside the run from 0 to stop"),
    ({"t_eval": [-1e-3, 1e-3]}, "outside the run from 0 to stop"),
    ({"t_eval": [0.0, 2e-3, 1e-3]}, "t_eval must increase: t_eval[2]"),
    ({"t_eval": [0.0, math.nan]}, "non-empty list of finite times"),
    ({"t_eval": []}, "non-empty list of finite times"),
    ({"stop": math.inf}, "positive and finite"),
    ({"atol": -1.0}, "absolute tolerance must be positive"),
    ({"max_step": -1.0}, "must be 0 (unbounded) or a positive time"),
    ({"decimate": 0}, "whole numbers >= 1"),
    ({"chunk": 0}, "whole numbers >= 1"),
])
def test_api_run_settings_that_mean_nothing_are_refused(kw, words):
    model = _compile(cs.load(Path(__file__).resolve().parent.parent / "netlists" / "examples"
                             / "rlc.yaml"))
    kw = {k: (np.asarray(v, float) if k == "t_eval" else v) for k, v in kw.items()}
    with pytest.raises(cs.SolverError) as ei:
        model.simulate(**kw)
    assert words in str(ei.value)


def test_api_refuses_the_same_settings():
    model = _compile(cs.load(Path(__file__).resolve().parent.parent / "netlists" / "examples"
                             / "rlc.yaml"))
    for kw in ({"rtol": 2.0}, {"rtol": 0.0}, {"step": 0.0}):
        with pytest.raises(cs.SolverError, match="must"):
            model.simulate(stop=1e-3, **kw)
    # the bound itself is a legal, if loose, setting: 1 ms of the RLC within 1 % of the closed
    # form (0.1 % measured; 17 % at rtol 0.1, which is refused)
    v = model.simulate(stop=1e-3, rtol=0.01)["v_c"][-1]
    zeta, wn = 10 / 2 * math.sqrt(1e-6 / 10e-3), 1 / math.sqrt(10e-3 * 1e-6)
    wd = wn * math.sqrt(1 - zeta ** 2)
    exact = 1 - math.exp(-zeta * wn * 1e-3) * (math.cos(wd * 1e-3)
                                              + zeta * wn / wd * math.sin(wd * 1e-3))
    assert v == pytest.approx(exact, rel=0.01)


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


@pytest.mark.parametrize(("value", "words"), [
    ("1e999 H", ("L = inf", "must be a finite number")),
    ("1e999", ("L = inf", "must be a finite number")),  # YAML float overflows to inf
    (".nan", ("L = nan", "must be a finite number")),  # YAML's NaN
    ("1e308*1e308 H", ("L = inf", "must be a finite number")),
    ("nan", ("unknown parameter 'nan'", "define it under 'parameters:'")),
])
def test_non_finite_value(write_netlist, value, words):
    path = write_netlist(f"""
        components:
          - {{name: V1, type: V, p: a, n: gnd, V: 1 V}}
          - name: L1
            type: L
            p: a
            n: gnd
            L: {value}
        """)
    with pytest.raises(cs.ParameterError) as ei:
        cs.load(path)
    _check(ei.value, path, 7, "L1", *words)


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


def _r1_netlist(write_netlist, value: str):
    """A source and R1 whose value is ``value``, the value on line 7."""
    return write_netlist(f"""
        components:
          - {{name: V1, type: V, p: a, n: gnd, V: 1 V}}
          - name: R1
            type: R
            p: a
            n: gnd
            R: {value}
        """)


@pytest.mark.parametrize(("value", "words"), [
    ("2 * (1 + 0.004 * t)", ("unknown parameter 't'", "the time t may appear only", "BV",
                             "waveform")),
    ("2 * (1 + 0.01 * a.v)", ("unknown parameter 'a.v'", "circuit quantity ('a.v')",
                              "btorque")),
])
def test_a_value_naming_time_or_a_circuit_quantity_points_to_behavioural_parts(
        write_netlist, value, words):
    # 't' is reserved, so "define it under 'parameters:'" was advice the loader then refused
    path = _r1_netlist(write_netlist, value)
    with pytest.raises(cs.ParameterError) as ei:
        cs.load(path)
    _check(ei.value, path, 7, "R1", *words)
    assert "parameters:" not in str(ei.value)


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



@pytest.mark.parametrize(("value", "words"), [
    ("10**10**10", "overflows a float"), ("1/0", "division by zero")])
def test_a_parameter_that_cannot_be_evaluated_says_why_in_words(write_netlist, value, words):
    """Python's own words for an overflow ('(34, 'Numerical result out of range')') are not
    shown: the error says the value overflows and what to rewrite."""
    path = write_netlist(f"""
        parameters:
          R2: {value}
        components:
          - {{name: V1, type: V, p: a, n: gnd, V: 1 V}}
          - {{name: R1, type: R, p: a, n: gnd, R: R2}}
        """)
    with pytest.raises(cs.ParameterError) as ei:
        cs.load(path)
    _check(ei.value, path, 2, None, "parameter 'R2': ", words)
    assert "Numerical result" not in str(ei.value)

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
    import builtins
    import os

    monkeypatch.chdir(tmp_path)
    calls: list[str] = []
    real_import = builtins.__import__

    def spy_import(name, *args, **kwargs):
        # An import statement passes the module globals; the payload's __import__('os') does not.
        if name == "os" and not args and not kwargs:
            calls.append(f"__import__({name!r})")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", spy_import)
    monkeypatch.setattr(os, "system", lambda cmd: calls.append(f"system({cmd!r})") or 0)
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
    monkeypatch.undo()
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
# Regressions: inputs that once escaped as Python exceptions or hung the loader
# --------------------------------------------------------------------------------------


@pytest.mark.parametrize("where", ["component", "parameter"])
def test_negative_base_fractional_power(write_netlist, where):
    # (-8)**0.5 is complex in Python; it used to escape as TypeError from math.isfinite.
    comp_value, param_value = ("'(-8)^0.5 mH'", "1 mH") if where == "component" else \
        ("L0", "'(-8)**0.5 mH'")
    path = write_netlist(f"""
        parameters:
          L0: {param_value}
        components:
          - {{name: V1, type: V, p: a, n: gnd, V: 1 V}}
          - {{name: L1, type: L, p: a, n: gnd, L: {comp_value}}}
        """)
    with pytest.raises(cs.ParameterError) as ei:
        cs.load(path)
    if where == "component":
        _check(ei.value, path, 5, "L1", "negative base", "no real power")
    else:
        _check(ei.value, path, 2, None, "parameter 'L0'", "negative base", "no real power")


@pytest.mark.parametrize(("unit", "words"), [
    ("H^1e999", ("exponent must be a plain number",)),  # pint: DimensionalityError
    ("km^400", ("out of range",)),  # pint: OverflowError
    ("m^99^99", ("exponent must be a plain number",)),  # pint: DimensionalityError
    ("m^9^9^9", ("exponent must be a plain number",)),  # pint: computed 9**387420489
    ("m^(9^9^9)", ("exponent must be a plain number",)),
])
def test_unit_with_absurd_exponent(write_netlist, unit, words):
    path = write_netlist(f"""
        components:
          - {{name: V1, type: V, p: a, n: gnd, V: 1 V}}
          - name: L1
            type: L
            p: a
            n: gnd
            L: 1 {unit}
        """)
    # No deadline can interrupt one huge int power in C: the guard's own message shows that the
    # text was refused before pint evaluated it.
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    _check(ei.value, path, 7, "L1", "parameter 'L'", unit, *words)


def test_unit_exponents_that_stay_accepted(write_netlist):
    path = write_netlist("""
        parameters:
          J0: 4.57e-6 kg*m^2
          k: 1e-3 kg*m**2*s**-2*A^-1
          a: 1 m^(1/2)*m^0.5
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
        """)
    net = _load(path)
    assert net.parameters["J0"].value == pytest.approx(4.57e-6)
    assert net.parameters["k"].value == pytest.approx(1e-3)
    assert net.parameters["a"].value == pytest.approx(1.0)


def test_yaml_alias_bomb_is_refused_quickly(write_netlist):
    lines = ["title: &l0 [x, x, x, x, x, x, x, x, x, x]"]
    lines += [f"t{i}: &l{i} [" + ", ".join([f"*l{i - 1}"] * 10) + "]" for i in range(1, 9)]
    path = write_netlist("\n".join(lines) + "\ncomponents: []\n")
    with _deadline(20), pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    assert f"{path.name}:" in str(ei.value) and "aliases" in str(ei.value)


def test_yaml_nested_too_deeply(write_netlist):
    path = write_netlist("components: " + "[" * 1500 + "]" * 1500 + "\n")
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    assert f"{path.name}" in str(ei.value) and "nested too deeply" in str(ei.value)


@pytest.mark.parametrize(("value", "shown"), [
    ("!!bool x", "KeyError"),  # ruamel's constructors raised these bare
    ("!!int 0x", "IndexError"),
    ("-_", "IndexError"),
])
def test_yaml_scalar_the_parser_cannot_construct(write_netlist, value, shown):
    path = _r1_netlist(write_netlist, value)
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    msg = str(ei.value)
    assert msg.startswith(f"{ei.value.loc}: YAML error: {shown}") and path.name in msg, msg
    assert "'!!' tags" in msg


@pytest.mark.parametrize("sign", ["", "-"])
def test_integer_beyond_float_range(write_netlist, sign):
    # float(10**400) raised OverflowError out of the loader.
    path = write_netlist(f"""
        components:
          - {{name: V1, type: V, p: a, n: gnd, V: 1 V}}
          - name: R1
            type: R
            p: a
            n: gnd
            R: {sign}1{"0" * 400}
        """)
    with pytest.raises(cs.ParameterError) as ei:
        cs.load(path)
    _check(ei.value, path, 7, "R1", f"R = {sign}inf", "must be a finite number")


@pytest.mark.parametrize(("ports", "words"), [
    ("p: a, n: a", ("both ports 'p' and 'n'", "node 'a'", "short-circuited")),
    ("p: gnd, n: '0'", ("both ports 'p' and 'n'", "short-circuited")),
])
def test_shorted_capacitor(write_netlist, ports, words):
    # Used to crash in codegen with AttributeError: 'Zero' object has no attribute 'name'.
    path = write_netlist(f"""
        components:
          - {{name: V1, type: V, p: a, n: gnd, V: 1 V}}
          - {{name: R1, type: R, p: a, n: gnd, R: 1 ohm}}
          - {{name: C1, type: C, {ports}, C: 1 uF}}
        """)
    net = _load(path)
    with pytest.raises(cs.NetlistError) as ei:
        _compile(net)
    _check(ei.value, path, 4, "C1", *words, "remove the element")


def test_inertia_on_the_fixed_reference(write_netlist):
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
          - {name: Jr, type: inertia, shaft: fixed, J: 1e-5 kg*m^2}
        """)
    net = _load(path)
    with pytest.raises(cs.NetlistError) as ei:
        _compile(net)
    _check(ei.value, path, 4, "Jr", "port 'shaft'", "reference 'fixed'", "moving node")


@pytest.mark.parametrize(("probe", "shown"), [
    ("R1.i / 0", "zoo"),  # used to escape from codegen as KeyError: 'ComplexInfinity'
    ("a.v / (a.v - a.v)", "zoo"),
    ("sqrt(-1)", "I"),  # used to escape from compile() as TypeError (complex)
    ("1e999", "oo"),
])
def test_probe_that_cannot_be_evaluated(write_netlist, probe, shown):
    path = write_netlist(f"""
        components:
          - {{name: V1, type: V, p: a, n: gnd, V: 1 V}}
          - {{name: R1, type: R, p: a, n: gnd, R: 1 ohm}}
        probes:
          v: a.v
          bad: '{probe}'
        """)
    with pytest.raises(cs.NetlistError) as ei:
        cs.load(path)
    _check(ei.value, path, 6, None, "probe 'bad'", f"evaluates to {shown}",
           "infinite, undefined or complex", "rewrite it")


def test_shaft_element_on_the_fixed_reference_is_allowed(write_netlist):
    # 'fixed' is the reference of both mechanical domains; it used to be refused as
    # "the translational reference" on a rotational port.
    path = write_netlist("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
          - {name: Bv, type: damper, shaft: fixed, b: 1e-5 N*m*s/rad}
        """)
    net = _load(path)
    assert dict(net.component("Bv").ports) == {"shaft": "fixed"}


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
            "**", "#", "&a", "*a", "!!python/object:os.system", "\t", "%", "|", "__", ".",
            "!!float", "!!bool", "!!int", "_", "~", "1" + "0" * 400]
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


@settings(max_examples=150, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
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


TOKENS = ["1", "2", "-8", "0", "9", "0.5", "1e999", "1e-400", "pi", "L0", "w", "(", ")", "+",
          "-", "*", "/", "^", "**", " ", "mH", "H", "Hz", "rpm", "rad", "rev", "s", "ohm", "km",
          "degC", "%", "sqrt(", "log(", "exp(", "min(", ",", "abs(", "e", ".", "_", "µ", "Ω",
          "__", "'", "[", "]", ":", "#", "lambda", "import", "os"]


@settings(max_examples=150, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(toks=st.lists(st.sampled_from(TOKENS), min_size=1, max_size=9),
       where=st.sampled_from(["L", "i0", "w0", "parameter"]))
def test_random_expressions_raise_only_circuitsim_errors(tmp_path, toks, where):
    value = "'" + "".join(toks).replace("'", "''") + "'"
    comp = {"L": f"L: {value}", "i0": f"L: 1 mH, i0: {value}", "w0": "L: 1 mH",
            "parameter": "L: 1 mH"}[where]
    extra = f"\n  - {{name: J, type: inertia, shaft: r, J: 1, w0: {value}}}" \
        if where == "w0" else ""
    glob = f"\n  G: {value}" if where == "parameter" else ""
    path = tmp_path / "expr.yaml"
    path.write_text(f"parameters:\n  L0: 1 mH\n  w: 2 rad/s{glob}\ncomponents:\n"
                    f"  - {{name: V1, type: V, p: a, n: gnd, V: 1 V}}\n"
                    f"  - {{name: L1, type: L, p: a, n: gnd, {comp}}}{extra}\n", encoding="utf-8")
    try:
        net = _load(path)
    except cs.CircuitsimError as exc:
        assert "expr.yaml:" in str(exc)
        event(type(exc).__name__)
        return
    event("loaded")
    for spec in net.components:
        for v in spec.values.values():
            assert math.isfinite(v.si(net.global_values()))


def test_a_copied_netlist_keeps_its_lines_and_its_independence(write_netlist):
    """RawNetlist.copy (lines.copy_nodes, which replaced copy.deepcopy for speed) on a netlist
    with a YAML alias: an error in a component of the copy names the same file line as the
    original; editing the copy leaves the original as it was."""
    from circuitsim.netlist import build

    path = write_netlist("""
        parameters:
          Rv: 1 ohm
        components:
          - {name: V1, type: V, p: a, n: gnd, V: 1 V}
          - name: R1
            type: R
            p: a
            n: b
            R: &r 2 ohm
          - {name: R2, type: R, p: b, n: gnd, R: *r}
        """)
    raw = cs.load(path).raw
    copied = raw.copy()
    entry = copied.component_entry("R1")
    entry["R"] = "1 meter"  # a wrong dimension, reported at the line of R1's R
    with pytest.raises(cs.CircuitsimError) as ei:
        build(copied)
    _check(ei.value, path, 9, "R1", "parameter 'R'", "ohm")
    assert str(raw.component_entry("R1")["R"]) == "2 ohm"
    build(raw)  # the original still builds
    assert copied.params.keys() == raw.params.keys()
    assert copied.comps[0][1] == raw.comps[0][1]  # the entries' locations
