"""Subcircuits: reusable blocks with ports and parameters, flattened before the graph.

A netlist (or a library file it includes) defines blocks under ``subcircuits:``::

    subcircuits:
      rc_stage:
        ports: [in, out]
        parameters: {R: 1 kohm, C: 1 uF}      # defaults, in the block's own scope
        components:
          - {name: R1, type: R, p: in, n: out, R: R}
          - {name: C1, type: C, p: out, n: gnd, C: C}
        probes: {v_out: out.v}

and uses them as components: ``{name: X1, type: rc_stage, in: a, out: b, R: 2 kohm}``.
Flattening renames everything inside an instance with its name: components ``X1.R1``,
internal nodes ``X1.mid``, parameters ``X1.R`` (global parameters, so a sweep or a fit can
vary them), probes ``X1.v_out``; ports become the nodes they are bound to and references
(gnd, fixed) stay global. Expressions are renamed token by token, never evaluated. Blocks may
use other blocks; a block using itself is an error. Errors inside an instance name the line
of the definition and the instance (``lib.yaml:7 (in X1 at net.yaml:12)``).
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from circuitsim.component import COMPONENTS, DOMAINS
from circuitsim.errors import NetlistError, SourceLoc
from circuitsim.netlist import expr as ex
from circuitsim.netlist.lines import yaml_line as _line

REFERENCES = frozenset(r for d in DOMAINS.values() for r in d.references)
#: Instances inside instances: deeper than this is surely a mistake (and a recursion guard).
MAX_DEPTH = 20


@dataclass(frozen=True, slots=True)
class ScopedLoc(SourceLoc):
    """A line in a subcircuit definition, with the instance(s) it was reached through."""

    via: str = ""

    def __str__(self) -> str:
        return f"{SourceLoc.__str__(self)} (in {self.via})" if self.via else \
            SourceLoc.__str__(self)


@dataclass(frozen=True)
class Subckt:
    """One definition as read: ports, default parameters, components, probes, where."""

    name: str
    ports: tuple[str, ...]
    params: Mapping[str, tuple[Any, SourceLoc]]
    comps: tuple[tuple[Mapping, SourceLoc, str], ...]
    probes: Mapping[str, tuple[Any, SourceLoc]]
    loc: SourceLoc


def read_subckts(doc: Mapping, path: str) -> dict[str, Subckt]:
    """The ``subcircuits:`` of one YAML document, checked for shape."""
    defs = doc.get("subcircuits") or {}
    if not isinstance(defs, Mapping):
        raise NetlistError("'subcircuits:' maps block names to {ports, parameters, "
                           "components}", _line(path, doc, key="subcircuits"))
    out = {}
    for name, body in defs.items():
        loc = _line(path, defs, key=name)
        if str(name) in COMPONENTS:
            raise NetlistError(f"subcircuit '{name}' has the name of a component type; "
                               f"rename it", loc)
        if not isinstance(body, Mapping) or not isinstance(body.get("components"), list) or \
                set(body) - {"ports", "parameters", "components", "probes", "description"}:
            raise NetlistError(f"subcircuit '{name}' must be a mapping with 'ports:' (a list), "
                               f"'components:' (a list) and optionally 'parameters:', "
                               f"'probes:'", loc)
        ports = body.get("ports") or []
        if not isinstance(ports, list) or not all(isinstance(p, str) for p in ports):
            raise NetlistError(f"subcircuit '{name}': 'ports:' is a list of names", loc)
        for port in ports:  # bound to a node, it would move the block's own ground with it
            if port in REFERENCES:
                raise NetlistError(f"subcircuit '{name}': port '{port}' is a global reference "
                                   f"({', '.join(sorted(REFERENCES))} each name one node, inside "
                                   f"and outside every block); name the port otherwise, e.g. "
                                   f"'{port}_local'", loc)
        params = body.get("parameters") or {}
        probes = body.get("probes") or {}
        comps = body["components"]
        out[str(name)] = Subckt(
            str(name), tuple(ports),
            {str(k): (params[k], _line(path, params, key=k)) for k in params},
            tuple((c, _line(path, comps, index=i), path) for i, c in enumerate(comps)),
            {str(k): (probes[k], _line(path, probes, key=k)) for k in probes}, loc)
    return out


def flatten(raw: Any) -> Any:
    """A copy of ``raw`` (a RawNetlist) with every subcircuit instance expanded; ``raw``
    itself when it uses none."""
    defs: Mapping[str, Subckt] = getattr(raw, "subckts", {}) or {}
    if not any(str(e.get("type")) in defs for e, _, _ in raw.comps):
        return raw
    out = raw.copy()
    out.comps = []
    for entry, loc, file in raw.comps:
        out.comps += _expand(entry, loc, file, defs, out, ())
    return out


def _expand(entry: Mapping, loc: SourceLoc, file: str, defs: Mapping[str, Subckt], out: Any,
            stack: tuple[str, ...]) -> list[tuple[Mapping, SourceLoc, str]]:
    sub = defs.get(str(entry.get("type")))
    if sub is None:
        return [(entry, loc, file)]
    name = str(entry["name"])
    if sub.name in stack or len(stack) >= MAX_DEPTH:
        chain = " -> ".join((*stack, sub.name))
        raise NetlistError(f"subcircuit '{sub.name}' uses itself ({chain})", loc, name)
    nodes = _bind_ports(entry, sub, loc, name)
    for key in entry:
        if key not in ("name", "type", *sub.ports) and key not in sub.params:
            raise NetlistError(f"unknown parameter '{key}' for subcircuit '{sub.name}' "
                               f"(defined at {sub.loc}); its parameters: "
                               f"{', '.join(sub.params) or 'none'}",
                               _line(file, entry, key=key), name)
    local = {str(c["name"]) for c, _, _ in sub.comps}
    internal = {str(v) for c, _, _ in sub.comps for k, v in c.items()
                if k in _port_names(c, defs) and str(v) not in nodes and str(v) not in REFERENCES}
    rename = _renamer(f"{name}.", set(sub.params), nodes, local | internal)
    via = f"{name} at {loc}"
    # every parameter made here has a ScopedLoc: its dotted name is the flattener's, never
    # the user's (whose parameter names may not hold a dot)
    for k, (default, dloc) in sub.params.items():
        if k in entry:
            iloc = _line(file, entry, key=k)
            out.params[f"{name}.{k}"] = (entry[k], ScopedLoc(iloc.file, iloc.line,
                                                             f"instance {name}"))
        else:
            out.params[f"{name}.{k}"] = (_rename_value(default, rename),
                                         ScopedLoc(dloc.file, dloc.line, via))
    for k, (text, ploc) in sub.probes.items():
        out.probes[f"{name}.{k}"] = (_rename_value(text, rename), ScopedLoc(ploc.file,
                                                                           ploc.line, via))
    flat = []
    for c, cloc, cfile in sub.comps:
        inner = _instance_entry(c, f"{name}.", nodes, defs, rename)
        flat += _expand(inner, ScopedLoc(cloc.file, cloc.line, via), cfile, defs, out,
                        (*stack, sub.name))
    return flat


def _bind_ports(entry: Mapping, sub: Subckt, loc: SourceLoc, name: str) -> dict[str, str]:
    nodes = {}
    for port in sub.ports:
        if port not in entry:
            raise NetlistError(f"port '{port}' of subcircuit '{sub.name}' (defined at "
                               f"{sub.loc}) is not connected; add '{port}: <node>'", loc, name)
        nodes[port] = str(entry[port])
    return nodes


def _port_names(c: Mapping, defs: Mapping[str, Subckt]) -> set[str]:
    typ = str(c.get("type"))
    if typ in defs:
        return set(defs[typ].ports)
    cls = COMPONENTS.get(typ)
    return {p.name for p in cls.ports} if cls is not None else set()


def _instance_entry(c: Mapping, prefix: str, nodes: Mapping[str, str],
                    defs: Mapping[str, Subckt], rename: Callable[[str], str]) -> Mapping:
    """A component of the block as it appears in the flat netlist (lines kept)."""
    new = copy.deepcopy(c)
    ports = _port_names(c, defs)
    for k in list(new):
        v = new[k]
        if k == "name":
            new[k] = f"{prefix}{v}"
        elif k in ports:
            node = str(v)
            new[k] = nodes.get(node, node if node in REFERENCES else f"{prefix}{node}")
        elif k != "type":
            new[k] = _rename_value(v, rename)
    return new


def _renamer(prefix: str, params: set[str], ports: Mapping[str, str],
             local: set[str]) -> Callable[[str], str]:
    """How a name written inside the block reads in the flat netlist."""

    def rename(name: str) -> str:
        head, dot, rest = name.partition(".")
        if not dot:
            return f"{prefix}{name}" if name in params else name
        if head in ports:
            return f"{ports[head]}.{rest}"
        return f"{prefix}{name}" if head in local else name

    return rename


def _rename_value(v: Any, rename: Callable[[str], str]) -> Any:
    """Rename the names in a value: text (an expression), or a mapping or list of them."""
    if isinstance(v, Mapping):
        out = copy.copy(v)
        for k in list(out):
            out[k] = _rename_value(out[k], rename)
        return out
    if isinstance(v, list):
        return [_rename_value(x, rename) for x in v]
    if not isinstance(v, str):
        return v
    return rename_text(v, rename)


def rename_text(text: str, rename: Callable[[str], str]) -> str:
    """``text`` with each name token (not a function, not in a unit) renamed; text that is
    not an expression (a file name, an option) comes back unchanged."""
    try:
        p = ex._Parser(text)
        p.expr()
    except ex.ExprError:
        return text
    end = p.peek()[2]  # a unit suffix starts here: its letters are not names
    out, last = [], 0
    for i, (kind, val, pos) in enumerate(p.toks):
        if kind != "name" or pos >= end or val in ex.CONSTANTS:
            continue
        nxt = p.toks[i + 1] if i + 1 < len(p.toks) else ("end", "", 0)
        if nxt[0] == "op" and nxt[1] == "(":
            continue
        out += [text[last:pos], rename(val)]
        last = pos + len(val)
    return "".join([*out, text[last:]])
