"""Modified nodal analysis: gather component equations and flow balances into a DAE.

Pipeline stage 3. Unknowns are node potentials (voltage, speed), the flow at every component
port, component internal variables and, where asked for, node integrals (shaft angle).
Equations are each component's residuals plus one flow balance (KCL / torque balance) per
non-reference node. F(t, x, x', p) = 0 stays symbolic. The core knows no component type.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from circuitsim.component import (
    DOMAINS,
    WAVEFORMS,
    Component,
    Expression,
    Option,
    PortScope,
    RecordList,
    Scope,
    Signal,
    TableData,
    Waveform,
    as_expr,
)
from circuitsim.errors import NetlistError
from circuitsim.netlist import expr as ex
from circuitsim.netlist.load import ComponentSpec, Netlist


@dataclass(frozen=True)
class BreakSource:
    """A waveform with corners: its breakpoints come from these parameter symbols."""

    kind: str
    fields: tuple[tuple[str, sp.Symbol], ...]


@dataclass(frozen=True)
class Dae:
    """F(t, x, x', p) = 0 in sympy, with every name a probe may ask for."""

    t: sp.Symbol
    unknowns: tuple[sp.Symbol, ...]
    der: Mapping[sp.Symbol, sp.Symbol]
    equations: tuple[sp.Expr, ...]
    origins: tuple[str, ...]
    params: tuple[sp.Symbol, ...]
    exports: Mapping[str, sp.Expr]
    initial: Mapping[sp.Symbol, sp.Expr]
    probes: Mapping[str, sp.Expr]
    tables: tuple[TableData, ...] = ()
    breaks: tuple[BreakSource, ...] = ()
    units: Mapping[str, str] = field(default_factory=dict)
    integrals: Mapping[str, str] = field(default_factory=dict)  # state name -> domain

    def differentiated(self) -> set[sp.Symbol]:
        """Unknowns whose derivative appears in some equation."""
        used = set().union(*(e.free_symbols for e in self.equations))
        return {u for u, d in self.der.items() if d in used}

    def pretty(self, latex: bool = False) -> str:
        return format_equations(self.equations, self.origins, self.der, latex)


def format_equations(equations, origins, der: Mapping[sp.Symbol, sp.Symbol],
                     latex: bool = False) -> str:
    """One residual per line, derivatives written x', each with the element it came from."""
    subs = {d: sp.Symbol(f"{u.name}'") for u, d in der.items()}
    lines = []
    for eq, origin in zip(equations, origins, strict=True):
        e = eq.xreplace(subs)
        lines.append(f"{sp.latex(e)} = 0 \\quad \\text{{({origin})}}" if latex
                     else f"0 = {e}    [{origin}]")
    return "\n".join(lines)


class _Derivatives:
    """Hands out derivative symbols and differentiates expressions by the chain rule."""

    def __init__(self, t: sp.Symbol):
        self.t = t
        self.table: dict[sp.Symbol, sp.Symbol] = {}
        self.unknowns: set[sp.Symbol] = set()

    def symbol(self, u: sp.Symbol) -> sp.Symbol:
        if u not in self.table:
            self.table[u] = sp.Symbol(f"der({u.name})", real=True)
        return self.table[u]

    def __call__(self, e: sp.Expr) -> sp.Expr:
        e = as_expr(e)
        known = self.unknowns | set(self.table.values())
        out = sp.diff(e, self.t)
        for s in e.free_symbols & known:
            out += sp.diff(e, s) * self.symbol(s)
        return out


def assemble(net: Netlist) -> Dae:
    """Build the DAE of a netlist (structure only: parameters stay symbols)."""
    t = sp.Symbol("t", real=True)
    der = _Derivatives(t)
    unknowns: list[sp.Symbol] = []
    equations: list[sp.Expr] = []
    origins: list[str] = []
    exports: dict[str, sp.Expr] = {}
    units: dict[str, str] = {}
    initial: dict[sp.Symbol, sp.Expr] = {}
    params: dict[str, sp.Symbol] = {}
    breaks: list[BreakSource] = []
    tables: list[TableData] = []

    def new(name: str) -> sp.Symbol:
        s = sp.Symbol(name, real=True)
        unknowns.append(s)
        der.unknowns.add(s)
        return s

    potentials: dict[str, sp.Expr] = {}
    integrals: dict[str, sp.Expr] = {}
    integral_domains: dict[str, str] = {}
    flows: dict[str, list[sp.Symbol]] = {}
    for node, (dom_name, _) in net.nodes.items():
        dom = DOMAINS[dom_name]
        if node in dom.references:
            potentials[node] = sp.Integer(0)
        else:
            potentials[node] = new(f"{node}.{dom.across}")
            flows[node] = []
            units[f"{node}.{dom.across}"] = dom.across_unit
        exports[f"{node}.{dom.across}"] = potentials[node]

    def integral(node: str) -> sp.Expr:
        dom = DOMAINS[net.nodes[node][0]]
        if node in dom.references:
            return sp.Integer(0)
        if node not in integrals:
            sym = new(f"{node}.{dom.integral}")
            integrals[node] = sym
            equations.append(der(sym) - potentials[node])
            origins.append(f"{dom.integral} of node {node}")
            exports[f"{node}.{dom.integral}"] = sym
            units[f"{node}.{dom.integral}"] = dom.integral_unit or ""
            integral_domains[sym.name] = dom.name
        return integrals[node]

    # Behavioural components read other components' quantities: build them last.
    def behavioural(spec: ComponentSpec) -> bool:
        return any(isinstance(d, Expression) for d in spec.cls.declared().values())

    ordered = [c for c in net.components if not behavioural(c)] + \
        [c for c in net.components if behavioural(c)]
    for spec in ordered:
        comp, scope = _instantiate(spec, t, der, new, potentials, flows, integral, params,
                                   breaks, tables, exports, units, _dims(net))
        for eq in [*comp.bind(scope), *comp.equations(scope)]:
            equations.append(as_expr(eq))
            origins.append(f"{spec.name} ({spec.type})")
        stored = comp.energy(scope)
        if stored is not None:
            exports[f"{spec.name}.energy"] = as_expr(stored)
            units[f"{spec.name}.energy"] = "J"
        for var, val in comp.initial(scope).items():
            initial[var] = as_expr(val)
        for k, v in scope._exports.items():
            exports[f"{spec.name}.{k}"] = v
            for port in spec.cls.ports:
                dom = port.domain
                if k in (dom.across, dom.through):
                    units.setdefault(f"{spec.name}.{k}", dom.across_unit if k == dom.across
                                     else dom.through_unit)
        # power absorbed by the component, in total and per domain (an EMF converts between
        # its electrical and rotational sides; the two parts are what an energy audit needs)
        by_domain: dict[str, sp.Expr] = {}
        for port in spec.cls.ports:
            dom, p = port.domain, port.name
            by_domain[dom.name] = by_domain.get(dom.name, sp.Integer(0)) + dom.port_power(
                exports[f"{spec.name}.{p}.{dom.across}"], exports[f"{spec.name}.{p}.{dom.through}"])
        exports[f"{spec.name}.power"] = sum(by_domain.values(), sp.Integer(0))
        units[f"{spec.name}.power"] = "W"
        if len(by_domain) > 1:
            for dname, pw in by_domain.items():
                exports[f"{spec.name}.power_{dname}"] = pw
                units[f"{spec.name}.power_{dname}"] = "W"
    for node, fl in flows.items():
        dom = DOMAINS[net.nodes[node][0]]
        equations.append(sp.Add(*fl))
        origins.append(f"{'KCL' if dom.name == 'electrical' else 'balance'} at node {node}")
    probes = {}
    for name, probe in net.probes.items():
        missing = sorted(ex.names(probe.node) - set(exports))
        if missing:
            from difflib import get_close_matches

            close = get_close_matches(missing[0], list(exports), n=3)
            hint = f" (did you mean {', '.join(close)}?)" if close else \
                " (probes name nodes as NODE.v / SHAFT.w / SHAFT.phi and components as " \
                "NAME.i, NAME.v, NAME.PORT.i, NAME.power)"
            raise NetlistError(f"probe '{name}' refers to unknown quantity '{missing[0]}'{hint}",
                               probe.loc)
        probes[name] = ex.to_sympy(probe.node, exports)
        if probe.node.kind == "name":
            units[name] = units.get(probe.text.strip(), "")
        elif probe.node.kind == "neg" and probe.node.args[0].kind == "name":
            units[name] = units.get(str(probe.node.args[0].value), "")
    return Dae(t, tuple(unknowns), dict(der.table), tuple(equations), tuple(origins),
               tuple(params.values()), exports, initial, probes, tuple(tables), tuple(breaks),
               units, integral_domains)


def _dims(net: Netlist) -> dict[str, Any]:
    """Dimension of every netlist parameter (None: given without units)."""
    return {n: g.dim for n, g in net.parameters.items()}


def _behavioural(node, names: Mapping[str, Any], unit: str, units: Mapping[str, str],
                 pdims: Mapping[str, Any], spec: ComponentSpec, key: str) -> sp.Expr:
    """A behavioural expression in sympy, its dimension checked where it is known
    (mechanical quantities, parameters and numbers written with units), errors at its netlist
    line. Voltages and currents are not checked: a node may carry any signal (SPICE's
    behavioural convention; a position reference as a voltage, say)."""
    from circuitsim.units import unit_info

    def dim(n: str):
        u = units.get(n)
        if not u:
            return pdims.get(n)
        try:
            return None if u in ("V", "A", "W") else unit_info(u)[1]
        except ValueError:  # a unit pint does not know: leave the name unchecked
            return None

    env = {n: dim(n) for n in ex.names(node)}
    env["t"] = unit_info("s")[1]
    why = ex.unit_mismatch(node, unit, env)
    if why:
        raise NetlistError(f"expression '{key}': {why}", spec.loc, spec.name)
    try:
        return ex.to_sympy(node, names)
    except NetlistError as exc:
        raise NetlistError(f"expression '{key}': {exc.bare}", spec.loc, spec.name) from None


def _instantiate(spec: ComponentSpec, t, der, new, potentials, flows, integral, params,
                 breaks, tables, exports, units, pdims=None) -> tuple[Component, Scope]:
    pdims = pdims or {}
    def psym(name: str) -> sp.Symbol:
        if name not in params:
            params[name] = sp.Symbol(name, real=True)
        return params[name]

    values: dict[str, Any] = {}
    decl = spec.cls.declared()
    for key, d in decl.items():
        if isinstance(d, Option):
            values[key] = spec.structure[key]
        elif isinstance(d, RecordList):
            values[key] = [{f: psym(f"{spec.name}.{key}[{i}].{f}") for f in d.fields}
                           for i in range(spec.structure[key])]
        elif isinstance(d, Signal):
            kind, _ = spec.structure[key]
            prefix = f"{spec.name}.{key}."
            fields = {n[len(prefix):]: psym(n) for n in spec.values if n.startswith(prefix)}
            data = spec.tables[0] if kind == "table" else None
            if data is not None:
                tables.append(data)
            wave = WAVEFORMS[kind]()
            values[key] = wave.expr(t, fields, data)
            if type(wave).breakpoints is not Waveform.breakpoints:
                breaks.append(BreakSource(kind, tuple(fields.items())))
        elif isinstance(d, Expression):
            node = ex.parse(spec.structure[key], allow_unit=False)
            scope_names: dict[str, Any] = dict(exports)
            scope_names["t"] = t
            prefix = f"{spec.name}.{key}."
            scope_names.update({n[len(prefix):]: psym(n) for n in spec.values
                                if n.startswith(prefix)})
            missing = sorted(ex.names(node) - set(scope_names))
            if missing:
                from difflib import get_close_matches

                close = get_close_matches(missing[0], list(scope_names), n=3)
                raise NetlistError(
                    f"expression '{key}' names unknown quantity '{missing[0]}'" +
                    (f" (did you mean {', '.join(close)}?)" if close else
                     " (use netlist parameters, t, or quantities such as NODE.v, SHAFT.w, "
                     "COMP.i)"), spec.loc, spec.name)
            values[key] = _behavioural(node, scope_names, d.unit, units, pdims, spec, key)
        else:
            values[key] = psym(f"{spec.name}.{key}")
    comp = spec.cls(spec.name, values)
    ports: dict[str, PortScope] = {}
    nodes = dict(spec.ports)
    for port in spec.cls.ports:
        node = nodes[port.name]
        dom = port.domain
        flow = new(f"{spec.name}.{port.name}.{dom.through}")
        if node in flows:
            flows[node].append(flow)
        ports[port.name] = PortScope(dom, potentials[node], flow,
                                     lambda n=node: integral(n))
        exports[f"{spec.name}.{port.name}.{dom.across}"] = potentials[node]
        exports[f"{spec.name}.{port.name}.{dom.through}"] = flow
        units[f"{spec.name}.{port.name}.{dom.through}"] = dom.through_unit

    def make_var(name: str) -> sp.Symbol:
        return new(f"{spec.name}.{name}")

    scope = Scope(spec.name, ports, make_var, der, t)
    return comp, scope
