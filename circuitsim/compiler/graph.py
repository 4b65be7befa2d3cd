"""Connectivity per domain (networkx) and the structural checks, in circuit words.

Pipeline stage 2. Runs before any sympy: floating sub-networks, loops of independent
across-sources, cut-sets of independent through-sources, dangling nodes and mechanical
nodes with no inertia are reported with the components and nodes involved.
"""

from __future__ import annotations

import difflib
import itertools
from dataclasses import dataclass

import networkx as nx

from circuitsim.component import DOMAINS
from circuitsim.errors import NetlistError, SingularCircuitError
from circuitsim.netlist.load import Netlist

REF = "<ref>"


@dataclass(frozen=True)
class CircuitGraph:
    """One multigraph per domain; edges carry (component, kind). Plus non-fatal findings."""

    graphs: dict[str, nx.MultiGraph]
    warnings: tuple[str, ...]

    def summary(self) -> str:
        lines = []
        for dom, g in self.graphs.items():
            if g.number_of_edges() == 0:
                continue
            nodes = sorted(n for n in g.nodes if n != REF)
            lines.append(f"{dom}: {len(nodes)} nodes ({', '.join(nodes)}), "
                         f"{g.number_of_edges()} branches")
            for a, b, d in sorted(g.edges(data=True), key=lambda e: e[2]["comp"]):
                ends = [n if n != REF else DOMAINS[dom].references[0] for n in (a, b)]
                lines.append(f"  {d['comp']:<12} {d['kind']}  {ends[0]} -- {ends[1]}")
        return "\n".join(lines)


def build(net: Netlist) -> CircuitGraph:
    """Build the graphs and run the checks; raise SingularCircuitError on a fatal finding."""
    graphs = {d: nx.MultiGraph() for d in DOMAINS}
    usage: dict[str, list[str]] = {}
    for c in net.components:
        ports = dict(c.ports)
        for port in c.cls.ports:
            graphs[port.domain.name].add_node(_n(ports[port.name], port.domain.name))
        for br in c.cls.branches:
            dom = next(p.domain.name for p in c.cls.ports if p.name == br.a)
            a = _n(ports[br.a], dom)
            b = _n(ports[br.b], dom) if br.b is not None else REF
            if a == b and br.kind == "C":
                # Its across variable is identically zero: no state, a singular system.
                across = DOMAINS[dom].across
                if br.b is None:
                    raise NetlistError(f"port '{br.a}' is on the reference '{ports[br.a]}', "
                                       f"where {across} is always zero, so the element does "
                                       f"nothing. Connect '{br.a}' to a moving node or remove "
                                       f"the element", c.loc, c.name)
                raise NetlistError(f"both ports '{br.a}' and '{br.b}' connect to node "
                                   f"'{ports[br.a]}': the element is short-circuited, so its "
                                   f"{across} is always zero. Connect '{br.b}' to another node "
                                   f"or remove the element", c.loc, c.name)
            graphs[dom].add_edge(a, b, comp=c.name, kind=br.kind)
        for _, node in c.ports:
            usage.setdefault(node, []).append(c.name)
    for node, users in usage.items():
        dom = net.nodes[node][0]
        if node in DOMAINS[dom].references:
            continue
        if len(users) == 1:
            others = [n for n in usage if n != node and n not in DOMAINS[dom].references]
            close = difflib.get_close_matches(node, others, n=1, cutoff=0.6)
            hint = f" (typo for '{close[0]}'?)" if close else ""
            comp = net.component(users[0])
            raise NetlistError(f"connects to node '{node}' which no other element uses{hint}; "
                               f"connect it or remove the element", comp.loc, comp.name)
    warnings: list[str] = []
    for dom, g in graphs.items():
        if g.number_of_nodes():
            _check(net, dom, g, warnings)
    return CircuitGraph(graphs, tuple(warnings))


def _n(node: str, dom: str) -> str:
    return REF if node in DOMAINS[dom].references else node


def _comps(g: nx.MultiGraph, nodes) -> list[str]:
    return sorted({d["comp"] for a, b, d in g.edges(data=True) if a in nodes or b in nodes})


def _check(net: Netlist, dom: str, g: nx.MultiGraph, warnings: list[str]) -> None:
    ref_name = DOMAINS[dom].references[0]
    if REF not in g:
        g.add_node(REF)
    for part in nx.connected_components(g):
        if REF not in part:
            nodes = sorted(part)
            comps = _comps(g, part)
            first = net.component(comps[0]) if comps else None
            raise SingularCircuitError(
                f"cannot determine the {dom} potentials of {{{', '.join(nodes)}}}: no path to "
                f"the reference '{ref_name}' (only {', '.join(comps)} connect them). Connect "
                f"one of these nodes to '{ref_name}'" +
                (" or add a bleed resistor" if dom == "electrical" else
                 " (through a support, damper or inertia)"),
                first.loc if first else None, first.name if first else None)
    _source_loops(net, dom, g)
    _source_cutsets(net, dom, g)
    if dom in ("rotational", "translational"):  # a thermal node may hold no heat
        _inertias(net, dom, g)


def _source_loops(net: Netlist, dom: str, g: nx.MultiGraph) -> None:
    """Loops made only of independent across sources: over-determined potentials."""
    vg = nx.Graph()
    for a, b, d in g.edges(data=True):
        if d["kind"] != "V":
            continue
        if a == b or (vg.has_node(a) and vg.has_node(b) and nx.has_path(vg, a, b)):
            path = [a] if a == b else nx.shortest_path(vg, a, b)
            comps = [d["comp"]] + [vg.edges[u, v]["comp"] for u, v in itertools.pairwise(path)]
            c = net.component(d["comp"])
            raise SingularCircuitError(
                f"sources {', '.join(sorted(comps))} form a loop of ideal "
                f"{'voltage' if dom == 'electrical' else 'speed'} sources: their values "
                f"conflict or the loop current is undetermined. Add a series resistance to "
                f"one of them", c.loc, c.name)
        vg.add_edge(a, b, comp=d["comp"])


def _source_cutsets(net: Netlist, dom: str, g: nx.MultiGraph) -> None:
    """Cut-sets made only of independent through sources: the nodes they isolate float."""
    ng = nx.Graph()
    ng.add_nodes_from(g.nodes)
    ng.add_edges_from((a, b) for a, b, d in g.edges(data=True) if d["kind"] != "I")
    if nx.number_connected_components(ng) > 1:
        for part in nx.connected_components(ng):
            if REF in part:
                continue
            srcs = sorted({d["comp"] for a, b, d in g.edges(data=True)
                           if (a in part) != (b in part)})
            c = net.component(srcs[0])
            raise SingularCircuitError(
                f"{', '.join(srcs)} form a cut-set of ideal "
                f"{'current' if dom == 'electrical' else 'torque/force'} sources around "
                f"{{{', '.join(sorted(part))}}}: nothing else connects those nodes, so their "
                f"potentials are undetermined. Add a shunt path (resistor, damper)",
                c.loc, c.name)


def _inertias(net: Netlist, dom: str, g: nx.MultiGraph) -> None:
    """A mechanical node with no inertia (or mass) and no speed source."""
    for node in g.nodes:
        if node == REF:
            continue
        kinds = {d["kind"] for a, b, d in g.edges(node, data=True)}
        if "C" not in kinds and "V" not in kinds:
            comps = _comps(g, {node})
            c = net.component(comps[0])
            raise SingularCircuitError(
                f"{dom} node '{node}' has no inertia or mass (connected: "
                f"{', '.join(comps)}): its speed follows algebraically from the torques, "
                f"which is rarely intended. Add an 'inertia' (or 'mass') on '{node}'",
                c.loc, c.name)
