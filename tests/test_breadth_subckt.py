"""Subcircuits: definition, instantiation, scoped names, errors at both lines (issue 15)."""

from __future__ import annotations

import textwrap

import numpy as np
import pytest

import circuitsim as cs

LIB = """
subcircuits:
  rc_stage:
    ports: [in, out]
    parameters:
      R: 1 kohm
      C: 1 uF
    components:
      - {name: R1, type: R, p: in, n: mid, R: R}
      - {name: R2, type: R, p: mid, n: out, R: 1e-3*R}
      - {name: C1, type: C, p: out, n: gnd, C: C}
    probes:
      v_out: out.v
"""


def _write(tmp_path, name: str, text: str):
    p = tmp_path / name
    p.write_text(textwrap.dedent(text).lstrip("\n"), encoding="utf-8")
    return p


def test_instances_equal_the_flat_netlist_and_the_closed_form(tmp_path) -> None:
    _write(tmp_path, "lib.yaml", LIB)
    net = _write(tmp_path, "net.yaml", """
        include: [lib.yaml]
        subcircuits:
          two_stage:
            ports: [a, b]
            parameters: {Rx: 2 kohm}
            components:
              - {name: S1, type: rc_stage, in: a, out: m, R: Rx}
              - {name: S2, type: rc_stage, in: m, out: b, C: 2 uF}
        components:
          - {name: V1, type: V, p: in, n: gnd, V: {step: {v1: 1 V}}}
          - {name: X1, type: two_stage, a: in, b: o1}
          - {name: X2, type: rc_stage, in: in, out: o2, R: 3 kohm}
        probes: {v1: X1.S2.C1.v, v2: o2.v, vm: X1.m.v}
        analysis: {stop: 10 ms, step: 10 us, rtol: 1e-9, atol: 1e-12}
    """)
    flat = _write(tmp_path, "flat.yaml", """
        components:
          - {name: V1, type: V, p: in, n: gnd, V: {step: {v1: 1 V}}}
          - {name: A1, type: R, p: in, n: a1, R: 2 kohm}
          - {name: A2, type: R, p: a1, n: m, R: 2 ohm}
          - {name: A3, type: C, p: m, n: gnd, C: 1 uF}
          - {name: B1, type: R, p: m, n: b1, R: 1 kohm}
          - {name: B2, type: R, p: b1, n: o1, R: 1 ohm}
          - {name: B3, type: C, p: o1, n: gnd, C: 2 uF}
          - {name: C1, type: R, p: in, n: c1, R: 3 kohm}
          - {name: C2, type: R, p: c1, n: o2, R: 3 ohm}
          - {name: C3, type: C, p: o2, n: gnd, C: 1 uF}
        probes: {v1: o1.v, v2: o2.v, vm: m.v}
        analysis: {stop: 10 ms, step: 10 us, rtol: 1e-9, atol: 1e-12}
    """)
    a = cs.compile(cs.load(net)).simulate()
    b = cs.compile(cs.load(flat)).simulate()
    for name in ("v1", "v2", "vm"):
        assert np.allclose(a[name], b[name], atol=1e-9), name
    assert np.allclose(a["X2.v_out"], a["v2"], atol=1e-12)  # a probe of the block
    tau = 3.003e-3  # X2: (3 kohm + 3 ohm) * 1 uF, step rise 1 ns
    assert np.max(np.abs(a["v2"] - (1 - np.exp(-a.t / tau)))) < 1e-6


def test_instance_parameters_vary_at_run_time(tmp_path) -> None:
    _write(tmp_path, "lib.yaml", LIB)
    net = _write(tmp_path, "net.yaml", """
        include: [lib.yaml]
        components:
          - {name: V1, type: V, p: in, n: gnd, V: {step: {v1: 1 V}}}
          - {name: X1, type: rc_stage, in: in, out: o}
        probes: {v: o.v}
        analysis: {stop: 5 ms, step: 10 us, rtol: 1e-9, atol: 1e-12}
    """)
    model = cs.compile(cs.load(net))
    res = model.simulate(params={"X1.R": 2000.0})
    assert np.max(np.abs(res["v"] - (1 - np.exp(-res.t / 2.002e-3)))) < 1e-6


def test_scoped_names_in_the_equations(tmp_path) -> None:
    from circuitsim.compiler.model import derive

    _write(tmp_path, "lib.yaml", LIB)
    net = _write(tmp_path, "net.yaml", """
        include: [lib.yaml]
        components:
          - {name: V1, type: V, p: in, n: gnd, V: 1}
          - {name: X7, type: rc_stage, in: in, out: o}
    """)
    _, dae, _ = derive(cs.load(net))
    text = dae.pretty()
    assert "[X7.R1 (R)]" in text and "X7.mid.v" in text and "KCL at node X7.mid" in text


@pytest.mark.parametrize(("instance", "pattern"), [
    ("{name: X1, type: rc_stage, in: in}",
     r"net.yaml:4: X1: port 'out' of subcircuit 'rc_stage' \(defined at .*lib.yaml:2\)"),
    ("{name: X1, type: rc_stage, in: in, out: o, L: 1}",
     (r"net.yaml:4: X1: unknown parameter 'L' for subcircuit 'rc_stage' \(defined at "
      r".*lib.yaml:2\); its parameters: R, C")),
])
def test_instance_errors_name_both_lines(tmp_path, instance: str, pattern: str) -> None:
    _write(tmp_path, "lib.yaml", LIB)
    net = _write(tmp_path, "net.yaml", f"""
        include: [lib.yaml]
        components:
          - {{name: V1, type: V, p: in, n: gnd, V: 1}}
          - {instance}
          - {{name: R9, type: R, p: o, n: gnd, R: 1}}
    """)
    with pytest.raises(cs.NetlistError, match=pattern):
        cs.load(net)


def test_error_inside_a_definition_names_definition_and_instance(tmp_path) -> None:
    _write(tmp_path, "lib.yaml", LIB.replace("type: C, p: out", "type: Cx, p: out"))
    net = _write(tmp_path, "net.yaml", """
        include: [lib.yaml]
        components:
          - {name: V1, type: V, p: in, n: gnd, V: 1}
          - {name: X3, type: rc_stage, in: in, out: o}
    """)
    with pytest.raises(cs.NetlistError,
                       match=r"lib.yaml:10 \(in X3 at .*net.yaml:4\): X3.C1: unknown component "
                             r"type 'Cx'"):
        cs.load(net)


def test_a_block_using_itself_is_refused(tmp_path) -> None:
    net = _write(tmp_path, "net.yaml", """
        subcircuits:
          loop:
            ports: [a]
            components:
              - {name: Y, type: loop, a: a}
        components:
          - {name: X1, type: loop, a: n1}
          - {name: R1, type: R, p: n1, n: gnd, R: 1}
    """)
    with pytest.raises(cs.NetlistError, match=r"subcircuit 'loop' uses itself"):
        cs.load(net)


@pytest.mark.parametrize("port", ["gnd", "0", "fixed"])
def test_a_port_named_like_a_global_reference_is_refused(tmp_path, port: str) -> None:
    # bound to node b, port 'gnd' moved the block's ground there: b read 0.5 V (a divider)
    # where the block's resistor to ground leaves b at 0 V, without a word
    net = _write(tmp_path, "net.yaml", f"""
        subcircuits:
          s1:
            ports: [in, '{port}']
            components:
              - {{name: R, type: R, p: in, n: gnd, R: 1}}
        components:
          - {{name: V1, type: V, p: a, n: gnd, V: 1}}
          - {{name: X1, type: s1, in: a, '{port}': b}}
          - {{name: R1, type: R, p: b, n: gnd, R: 1}}
    """)
    with pytest.raises(cs.NetlistError, match=rf"net.yaml:2: subcircuit 's1': port '{port}' is "
                                              rf"a global reference .* name the port otherwise"):
        cs.load(net)


def test_flat_netlist_written_back_reloads(tmp_path) -> None:
    _write(tmp_path, "lib.yaml", LIB)
    net = _write(tmp_path, "net.yaml", """
        include: [lib.yaml]
        components:
          - {name: V1, type: V, p: in, n: gnd, V: {step: {v1: 1 V}}}
          - {name: X1, type: rc_stage, in: in, out: o, R: 2 kohm}
        probes: {v: o.v}
        analysis: {stop: 5 ms, step: 10 us}
    """)
    first = cs.load(net)
    first.raw.dump(tmp_path / "out.yaml")
    again = cs.load(tmp_path / "out.yaml")
    assert [c.name for c in again.components] == [c.name for c in first.components]
    assert again.global_values()["X1.R"] == pytest.approx(2000.0)


def test_a_source_inside_a_block_is_named_by_its_scoped_name(tmp_path) -> None:
    net = _write(tmp_path, "net.yaml", """
        subcircuits:
          osc:
            ports: [out]
            components:
              - {name: V1, type: V, p: out, n: gnd, V: {sine: {amplitude: 1 V, freq: 1 THz}}}
        components:
          - {name: X1, type: osc, out: a}
          - {name: R1, type: R, p: a, n: gnd, R: 1 kohm}
        analysis: {stop: 1 s, step: 1 ms}
    """)
    with pytest.raises(cs.ParameterError, match=r"net.yaml:5 \(in X1 at .*net.yaml:7\): "
                                                 r"X1.V1: the sine source repeats"):
        cs.compile(cs.load(net)).simulate()
