"""Modified nodal analysis: gather component equations and flow balances into a DAE.

Pipeline stage 3. Unknowns are node potentials (voltage, speed), the flow at every component
port, component internal variables and, where asked for, node integrals (shaft angle).
Equations are each component's residuals plus one flow balance (KCL / torque balance) per
non-reference node. F(t, x, x', p) = 0 stays symbolic. The core knows no component type.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from circuitsim.compiler.names import TIME_RATE
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
class SwitchEvent:
    """A component's discrete change (see ``Component.events``), with the component named
    for messages: when ``guard`` falls through zero the discrete states take their values."""

    owner: str
    guard: sp.Expr
    sets: tuple[tuple[sp.Symbol, sp.Expr], ...]


@dataclass(frozen=True)
class Crossing:
    """A relation of a behavioural expression that switches (see ``hold_relations``):
    ``distance`` is positive where it holds, ``scale`` sizes its hysteresis band, ``mode`` is
    the run-time parameter holding its truth between events (-1: evaluated as written)."""

    owner: str
    mode: sp.Symbol
    distance: sp.Expr
    scale: sp.Expr


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
    events: tuple[SwitchEvent, ...] = ()
    crossings: tuple[Crossing, ...] = ()

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


def time_rate() -> sp.Symbol:
    """The TIME_RATE parameter's symbol."""
    return sp.Symbol(TIME_RATE, real=True)


class _Derivatives:
    """Hands out derivative symbols and differentiates expressions by the chain rule."""

    def __init__(self, t: sp.Symbol, rate: Callable[[], sp.Symbol]):
        self.t = t
        self.rate = rate  # the TIME_RATE parameter, registered when first needed
        self.table: dict[sp.Symbol, sp.Symbol] = {}
        self.unknowns: set[sp.Symbol] = set()
        self.derivs: set[sp.Symbol] = set()  # the table's values, for O(1) membership

    def symbol(self, u: sp.Symbol) -> sp.Symbol:
        if u not in self.table:
            self.table[u] = sp.Symbol(f"der({u.name})", real=True)
            self.derivs.add(self.table[u])
        return self.table[u]

    def __call__(self, e: sp.Expr) -> sp.Expr:
        e = as_expr(e)
        out = sp.diff(e, self.t)
        if out != 0:
            out = self.rate() * out
        for s in e.free_symbols:
            if s in self.unknowns or s in self.derivs:
                out += sp.diff(e, s) * self.symbol(s)
        return out


class _Assembly:
    """The growing DAE while components are gathered: unknowns, equations and every name a
    probe may ask for. One method per stage of ``assemble``."""

    def __init__(self, net: Netlist):
        self.net = net
        self.t = sp.Symbol("t", real=True)
        self.der = _Derivatives(self.t, lambda: self.psym(TIME_RATE))
        self.unknowns: list[sp.Symbol] = []
        self.equations: list[sp.Expr] = []
        self.origins: list[str] = []
        self.exports: dict[str, sp.Expr] = {}
        self.units: dict[str, str] = {}
        self.initial: dict[sp.Symbol, sp.Expr] = {}
        self.params: dict[str, sp.Symbol] = {}
        self.breaks: list[BreakSource] = []
        self.tables: list[TableData] = []
        self.potentials: dict[str, sp.Expr] = {}
        self.integrals: dict[str, sp.Expr] = {}
        self.integral_domains: dict[str, str] = {}
        self.flows: dict[str, list[sp.Symbol]] = {}
        self.events: list[SwitchEvent] = []
        self.crossings: list[Crossing] = []

    def new(self, name: str) -> sp.Symbol:
        s = sp.Symbol(name, real=True)
        self.unknowns.append(s)
        self.der.unknowns.add(s)
        return s

    def psym(self, name: str) -> sp.Symbol:
        if name not in self.params:
            self.params[name] = sp.Symbol(name, real=True)
        return self.params[name]

    def nodes(self) -> None:
        """A potential per non-reference node (0 on a reference) and its flow list."""
        for node, (dom_name, _) in self.net.nodes.items():
            dom = DOMAINS[dom_name]
            if node in dom.references:
                self.potentials[node] = sp.Integer(0)
            else:
                self.potentials[node] = self.new(f"{node}.{dom.across}")
                self.flows[node] = []
                self.units[f"{node}.{dom.across}"] = dom.across_unit
            self.exports[f"{node}.{dom.across}"] = self.potentials[node]

    def integral(self, node: str) -> sp.Expr:
        """The node's integral (a shaft's angle), created when a component first asks."""
        dom = DOMAINS[self.net.nodes[node][0]]
        if node in dom.references:
            return sp.Integer(0)
        if node not in self.integrals:
            sym = self.new(f"{node}.{dom.integral}")
            self.integrals[node] = sym
            self.equations.append(self.der(sym) - self.potentials[node])
            self.origins.append(f"{dom.integral} of node {node}")
            self.exports[f"{node}.{dom.integral}"] = sym
            self.units[f"{node}.{dom.integral}"] = dom.integral_unit or ""
            self.integral_domains[sym.name] = dom.name
        return self.integrals[node]

    def component(self, spec: ComponentSpec) -> None:
        """A component's equations, initial values, stored energy and exports."""
        comp, scope = _instantiate(spec, self)
        for eq in [*comp.bind(scope), *comp.equations(scope)]:
            self.equations.append(as_expr(eq))
            self.origins.append(f"{spec.name} ({spec.type})")
        self.discrete(spec, comp, scope)
        stored = comp.energy(scope)
        if stored is not None:
            self.exports[f"{spec.name}.energy"] = as_expr(stored)
            self.units[f"{spec.name}.energy"] = "J"
        for var, val in comp.initial(scope).items():
            self.initial[var] = as_expr(val)
        for k, v in scope._exports.items():
            self.exports[f"{spec.name}.{k}"] = v
            for port in spec.cls.ports:
                dom = port.domain
                if k in (dom.across, dom.through):
                    self.units.setdefault(f"{spec.name}.{k}", dom.across_unit
                                          if k == dom.across else dom.through_unit)
        self.power(spec)

    def discrete(self, spec: ComponentSpec, comp: Component, scope: Scope) -> None:
        """Discrete states hold between events (der = 0); the events that change them."""
        for sym in scope._discrete:
            self.equations.append(self.der(sym))
            self.origins.append(f"{spec.name} ({spec.type}): discrete state {sym.name}")
        for ev in comp.events(scope):
            sets = tuple((s, as_expr(v)) for s, v in ev.sets)
            self.events.append(SwitchEvent(spec.name, as_expr(ev.guard), sets))

    def power(self, spec: ComponentSpec) -> None:
        """Power absorbed by the component, in total and per domain (an EMF converts between
        its electrical and rotational sides; the two parts are what an energy audit needs)."""
        by_domain: dict[str, sp.Expr] = {}
        for port in spec.cls.ports:
            dom, p = port.domain, port.name
            by_domain[dom.name] = by_domain.get(dom.name, sp.Integer(0)) + dom.port_power(
                self.exports[f"{spec.name}.{p}.{dom.across}"],
                self.exports[f"{spec.name}.{p}.{dom.through}"])
        self.exports[f"{spec.name}.power"] = sum(by_domain.values(), sp.Integer(0))
        self.units[f"{spec.name}.power"] = "W"
        if len(by_domain) > 1:
            for dname, pw in by_domain.items():
                self.exports[f"{spec.name}.power_{dname}"] = pw
                self.units[f"{spec.name}.power_{dname}"] = "W"

    def balances(self) -> None:
        """One flow balance (KCL, torque balance) per non-reference node."""
        for node, fl in self.flows.items():
            dom = DOMAINS[self.net.nodes[node][0]]
            self.equations.append(sp.Add(*fl))
            self.origins.append(f"{'KCL' if dom.name == 'electrical' else 'balance'} at node "
                                f"{node}")

    def probes(self) -> dict[str, sp.Expr]:
        """The netlist's probes as expressions of the exports, with their units."""
        probes = {}
        for name, probe in self.net.probes.items():
            missing = sorted(ex.names(probe.node) - set(self.exports))
            if missing:
                from difflib import get_close_matches

                close = get_close_matches(missing[0], list(self.exports), n=3)
                hint = f" (did you mean {', '.join(close)}?)" if close else \
                    " (probes name nodes as NODE.v / SHAFT.w / SHAFT.phi and components as " \
                    "NAME.i, NAME.v, NAME.PORT.i, NAME.power)"
                raise NetlistError(f"probe '{name}' refers to unknown quantity "
                                   f"'{missing[0]}'{hint}", probe.loc)
            probes[name] = ex.to_sympy(probe.node, self.exports)
            if probe.node.kind == "name":
                self.units[name] = self.units.get(probe.text.strip(), "")
            elif probe.node.kind == "neg" and probe.node.args[0].kind == "name":
                self.units[name] = self.units.get(str(probe.node.args[0].value), "")
        return probes


def assemble(net: Netlist) -> Dae:
    """Build the DAE of a netlist (structure only: parameters stay symbols)."""
    asm = _Assembly(net)
    asm.nodes()

    # Behavioural components read other components' quantities: build them last.
    def behavioural(spec: ComponentSpec) -> bool:
        return any(isinstance(d, Expression) for d in spec.cls.declared().values())

    for spec in [c for c in net.components if not behavioural(c)] + \
            [c for c in net.components if behavioural(c)]:
        asm.component(spec)
    asm.balances()
    probes = asm.probes()
    return Dae(asm.t, tuple(asm.unknowns), dict(asm.der.table), tuple(asm.equations),
               tuple(asm.origins), tuple(asm.params.values()), asm.exports, asm.initial,
               probes, tuple(asm.tables), tuple(asm.breaks), asm.units, asm.integral_domains,
               tuple(asm.events), tuple(asm.crossings))


def _instantiate(spec: ComponentSpec, asm: _Assembly) -> tuple[Component, Scope]:
    """The component object with its declared values as symbols, and its port scope."""
    values: dict[str, Any] = {}
    for key, d in spec.cls.declared().items():
        if isinstance(d, Option):
            values[key] = spec.structure[key]
        elif isinstance(d, RecordList):
            values[key] = [{f: asm.psym(f"{spec.name}.{key}[{i}].{f}") for f in d.fields}
                           for i in range(spec.structure[key])]
        elif isinstance(d, Signal):
            values[key] = _signal(spec, key, asm)
        elif isinstance(d, Expression):
            values[key] = _expression(spec, key, asm)
        else:
            values[key] = asm.psym(f"{spec.name}.{key}")
    comp = spec.cls(spec.name, values)
    ports: dict[str, PortScope] = {}
    nodes = dict(spec.ports)
    for port in spec.cls.ports:
        node = nodes[port.name]
        dom = port.domain
        flow = asm.new(f"{spec.name}.{port.name}.{dom.through}")
        if node in asm.flows:
            asm.flows[node].append(flow)
        ports[port.name] = PortScope(dom, asm.potentials[node], flow,
                                     lambda n=node: asm.integral(n))
        asm.exports[f"{spec.name}.{port.name}.{dom.across}"] = asm.potentials[node]
        asm.exports[f"{spec.name}.{port.name}.{dom.through}"] = flow
        asm.units[f"{spec.name}.{port.name}.{dom.through}"] = dom.through_unit

    def make_var(name: str) -> sp.Symbol:
        return asm.new(f"{spec.name}.{name}")

    return comp, Scope(spec.name, ports, make_var, asm.der, asm.t)


def _signal(spec: ComponentSpec, key: str, asm: _Assembly) -> sp.Expr:
    """A waveform's expression of t; its table and corners are noted."""
    kind, _ = spec.structure[key]
    prefix = f"{spec.name}.{key}."
    fields = {n[len(prefix):]: asm.psym(n) for n in spec.values if n.startswith(prefix)}
    data = spec.tables[0] if kind == "table" else None
    if data is not None:
        asm.tables.append(data)
    wave = WAVEFORMS[kind]()
    if type(wave).breakpoints is not Waveform.breakpoints:
        asm.breaks.append(BreakSource(kind, tuple(fields.items())))
    return wave.expr(asm.t, fields, data)


def _expression(spec: ComponentSpec, key: str, asm: _Assembly) -> sp.Expr:
    """A behavioural expression over t, its own parameters and other quantities."""
    node = ex.parse(spec.structure[key], allow_unit=False)
    scope_names: dict[str, Any] = dict(asm.exports)
    scope_names["t"] = asm.t
    prefix = f"{spec.name}.{key}."
    scope_names.update({n[len(prefix):]: asm.psym(n) for n in spec.values
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
    unit = spec.cls.declared()[key].unit
    out = _behavioural(node, scope_names, unit, asm.units, _dims(asm.net), spec, key)
    return hold_relations(out, asm, f"{spec.name}.{key}", spec.name)


def hold_relations(e: Any, asm: _Assembly, prefix: str, owner: str) -> Any:
    """Each relation (``<``, ``<=``, ``>``, ``>=`` inside if, abs, sign, min, max, clamp or a
    comparison) of ``e`` that depends on time or on an unknown becomes a Crossing, as
    Modelica treats relations: its truth is a run-time parameter ``PREFIX.modeK`` held
    between events, so the residual is smooth within a step and Newton cannot chatter
    across the kink; the integrator finds the root of its distance and switches it there.
    Mode -1 evaluates the relation as written (operating point, AC, batches and any run
    that does not follow events). Relations of parameters alone, and == or != (true only
    at an instant), stay as written."""
    if not isinstance(e, sp.Basic) or not e.has(sp.Piecewise):
        return e
    live = asm.der.unknowns | asm.der.derivs | {asm.t}
    held: dict[sp.Basic, sp.Basic] = {}
    # in sympy's canonical order, not a set's: the modes are numbered alike in every process
    # (by hash order, two processes generated two orders of EMPS's clamp modes)
    for pw in sorted(e.atoms(sp.Piecewise), key=sp.default_sort_key):
        for _, cond in pw.args:
            for rel in sorted(cond.atoms(sp.Lt, sp.Le, sp.Gt, sp.Ge), key=sp.default_sort_key):
                if rel in held or not rel.free_symbols & live:
                    continue
                mode = asm.psym(f"{prefix}.mode{len(held)}")
                sign = 1 if isinstance(rel, (sp.Gt, sp.Ge)) else -1
                asm.crossings.append(Crossing(owner, mode, sign * (rel.lhs - rel.rhs),
                                              sp.Abs(rel.lhs) + sp.Abs(rel.rhs)))
                held[rel] = sp.Or(sp.And(mode < 0, rel), mode > sp.Rational(1, 2))
    return e.xreplace(held) if held else e


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
