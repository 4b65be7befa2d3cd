"""Names the user gives mean what they wrote, or are refused with the reason (issue 16).

Each case once gave a silent wrong answer: a node named like a port reference read another
quantity, a parameter named ``pi`` or ``t`` lost to the built-in meaning, a probe named ``time``
or a node name with a comma shifted the CSV header.
"""

from __future__ import annotations

import csv

import pytest

import circuitsim as cs
from circuitsim.errors import NetlistError, ParameterError

DIVIDER = """
title: divider
parameters:
  {params}
components:
  - {{name: V1, type: V, p: {top}, n: gnd, V: 3 V}}
  - {{name: R1, type: R, p: {top}, n: mid, R: 1 kohm}}
  - {{name: R2, type: R, p: mid, n: gnd, R: 1 kohm}}
probes:
  {probes}
analysis: {{stop: 1 ms}}
"""


def _net(write_netlist, top="top", params="Rx: 1 kohm", probes="v_mid: mid.v"):
    return write_netlist(DIVIDER.format(top=top, params=params, probes=probes))


def test_node_named_like_a_port_is_refused(write_netlist):
    # the node 'R1.n' held at 3 V would make the probe 'R1.n.v' ambiguous with R1's port n
    # (which sits at 1.5 V)
    path = _net(write_netlist, top="R1.n")
    with pytest.raises(NetlistError, match=r"net\.yaml:5:.*'R1\.n' reads as a port"):
        cs.load(path)


def test_node_name_with_a_comma_is_refused(write_netlist):
    path = _net(write_netlist, top="'a,b'")
    with pytest.raises(NetlistError, match=r"net\.yaml:5:.*comma"):
        cs.load(path)


@pytest.mark.parametrize("name", ["pi", "t", "time"])
def test_reserved_parameter_names_are_refused(write_netlist, name):
    path = _net(write_netlist, params=f"{name}: 2")
    with pytest.raises(ParameterError, match=rf"net\.yaml:3:.*'{name}' is reserved"):
        cs.load(path)


def test_dotted_parameter_name_is_refused(write_netlist):
    # a parameter 'mid.v' would shadow the node voltage inside a behavioural expression
    path = _net(write_netlist, params="mid.v: 2")
    with pytest.raises(ParameterError, match=r"net\.yaml:3:.*not a plain name"):
        cs.load(path)


def test_probe_named_time_is_refused(write_netlist):
    path = _net(write_netlist, probes="time: mid.v")
    with pytest.raises(NetlistError, match=r"net\.yaml:9:.*'time' is reserved"):
        cs.load(path)


def test_plain_names_keep_working_and_the_header_is_aligned(write_netlist, tmp_path):
    """The divider's CSV: one header cell per column, the node voltage V/2 exactly."""
    path = _net(write_netlist, probes="v_mid: mid.v\n  i_top: R1.i")
    res = cs.compile(cs.load(path)).simulate()
    out = tmp_path / "out.csv"
    res.to_csv(out)
    with open(out, newline="") as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["time [s]", "v_mid [V]", "i_top [A]"]
    assert all(len(r) == 3 for r in rows)
    assert float(rows[-1][1]) == pytest.approx(1.5, rel=1e-9)
    assert float(rows[-1][2]) == pytest.approx(3.0 / 2000.0, rel=1e-9)
