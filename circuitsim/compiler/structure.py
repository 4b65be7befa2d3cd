"""Structural index reduction: alias elimination, Pantelides, dummy derivatives.

Pipeline stage 4. Turns the MNA DAE (index up to 2 or more: inductor cut-sets, capacitor /
voltage-source loops, inertias tied by constraints) into an index-1 DAE for IDA, generally:

1. Alias / linear elimination: an equation linear in an unknown with a constant numeric
   coefficient is solved for it and substituted, if that adds no fill-in (the number of
   equation-unknown incidences must not grow), smallest equations first, with an index from
   each unknown to its equations so a step touches only its neighbourhood: a ladder stays a
   ladder. For a differentiated unknown (x = a y + b(t) with y a state) its derivative is
   substituted too, which is exactly how series inductors or a capacitor across a source
   lose their extra index.
2. Pantelides' algorithm on the equation / highest-derivative bipartite graph finds the
   equations that must be differentiated.
3. Dummy derivatives (Mattsson & Soederlind 1993) replace enough derivatives by algebraic
   unknowns for the differentiated system to be index 1 and not over-determined.
4. Elimination again, then a perfect matching proves the result structurally index 1.

No topology is special-cased: everything works on the equations and their incidence.
"""

from __future__ import annotations

import heapq
import zlib
from collections.abc import Mapping
from dataclasses import dataclass

import networkx as nx
import numpy as np
import sympy as sp

from circuitsim.compiler.mna import (
    BreakSource,
    Crossing,
    Dae,
    SwitchEvent,
    format_equations,
    time_rate,
)
from circuitsim.component import as_expr
from circuitsim.errors import SingularCircuitError


@dataclass(frozen=True)
class IndexOneDae:
    """The index-1 system handed to code generation.

    ``states`` = differential unknowns (first ``n_diff``) then algebraic unknowns; ``yp`` the
    derivative symbol of each. ``solved`` maps every eliminated unknown or derivative to an
    expression of (t, states, yp, params), so nothing is lost for probing.
    """

    t: sp.Symbol
    states: tuple[sp.Symbol, ...]
    yp: tuple[sp.Symbol, ...]
    n_diff: int
    equations: tuple[sp.Expr, ...]
    origins: tuple[str, ...]
    params: tuple[sp.Symbol, ...]
    solved: Mapping[sp.Symbol, sp.Expr]
    exports: Mapping[str, sp.Expr]
    probes: Mapping[str, sp.Expr]
    initial: Mapping[sp.Symbol, sp.Expr]
    tables: tuple
    breaks: tuple[BreakSource, ...]
    units: Mapping[str, str]
    report: tuple[str, ...]
    integrals: Mapping[str, str]
    events: tuple[SwitchEvent, ...] = ()
    crossings: tuple[Crossing, ...] = ()
    differentiated_params: tuple[str, ...] = ()  # see _System

    def pretty(self, latex: bool = False) -> str:
        return format_equations(self.equations, self.origins,
                                dict(zip(self.states, self.yp, strict=True)), latex)


class _System:
    """Mutable working copy of the equations during reduction.

    ``steps`` records every elimination in order (unknown or derivative -> expression of the
    variables present at that step); ``resolved()`` composes them once at the end, so an
    elimination never rewrites the earlier ones (that rewrite made reduction O(N^2))."""

    def __init__(self, dae: Dae):
        self.t = dae.t
        self.eqs: list[sp.Expr] = list(dae.equations)
        self.origins: list[str] = list(dae.origins)
        self.unknowns: set[sp.Symbol] = set(dae.unknowns)
        self.der: dict[sp.Symbol, sp.Symbol] = dict(dae.der)
        self.anti: dict[sp.Symbol, sp.Symbol] = {d: u for u, d in self.der.items()}
        self.steps: dict[sp.Symbol, sp.Expr] = {}
        self.params = set(dae.params)
        # parameters in an equation that was differentiated: their own derivative was taken
        # as zero, so a small-signal perturbation of one misses its s*u term (ac refuses it)
        self.differentiated_params: set[sp.Symbol] = set()
        self.report: list[str] = []

    def der_of(self, s: sp.Symbol) -> sp.Symbol:
        if s not in self.der:
            d = sp.Symbol(f"der({s.name})", real=True)
            self.der[s] = d
            self.anti[d] = s
        return self.der[s]

    def is_variable(self, s) -> bool:
        return s in self.unknowns or s in self.anti

    def variables(self) -> set[sp.Symbol]:
        return self.unknowns | set(self.anti)

    def incidence(self, e: sp.Expr) -> set[sp.Symbol]:
        return {s for s in e.free_symbols if s in self.unknowns or s in self.anti}

    def used(self) -> set[sp.Symbol]:
        out: set[sp.Symbol] = set()
        for e in self.eqs:
            out |= e.free_symbols
        return out

    def differentiate(self, e: sp.Expr) -> sp.Expr:
        """Total time derivative (chain rule over unknowns and their derivatives)."""
        out = sp.diff(e, self.t)
        if out != 0:
            out = time_rate() * out
            self.params.add(time_rate())
        for s in sorted(self.incidence(e), key=lambda s: s.name):
            out += sp.diff(e, s) * self.der_of(s)
        return out

    def record(self, mapping: Mapping[sp.Symbol, sp.Expr]) -> None:
        self.steps.update(mapping)

    def resolved(self) -> dict[sp.Symbol, sp.Expr]:
        """Every eliminated unknown or derivative as an expression of the final variables.

        A step's expression only names variables still present when it was taken, i.e. ones
        eliminated later: composing in reverse order resolves each exactly once."""
        out: dict[sp.Symbol, sp.Expr] = {}
        for key in reversed(list(self.steps)):
            e = self.steps[key]
            hit = {s: out[s] for s in e.free_symbols if s in out}
            out[key] = e.xreplace(hit) if hit else e
        return out


def _linear_coeff(e: sp.Expr, v: sp.Symbol) -> sp.Expr | None:
    """Coefficient of v if e is linear in v with a constant numeric coefficient."""
    c = sp.Integer(0)
    for a in e.args if e.is_Add else (e,):
        if a == v:
            c += 1
        elif a.is_Mul and len(a.args) == 2 and a.args[0].is_Number and a.args[1] == v:
            c += a.args[0]  # the usual -1*v: no call to diff
        elif v in a.free_symbols:
            c += sp.diff(a, v)
    if c.free_symbols or not c.is_number or c == 0:
        return None
    return c


def _solve_for(e: sp.Expr, v: sp.Symbol, c: sp.Expr) -> sp.Expr:
    """v from e = 0, e linear in v with numeric coefficient c. A sum with the single term
    c*v is rearranged term by term (expand, the general route, dominated elimination)."""
    if e.is_Add:
        hits = [a for a in e.args if v in a.free_symbols]
        if len(hits) == 1 and (hits[0] == v or hits[0] == c * v):
            others = [a for a in e.args if a is not hits[0]]
            if c == 1:
                return sp.Add(*[-a for a in others])
            if c == -1:
                return sp.Add(*others)
            return sp.Add(*[-a / c for a in others])
    return sp.expand(v - e / c) if len(e.args) < 8 else v - e / c


class _Index:
    """Incidence bookkeeping for elimination: each live equation's variables and, for each
    variable, the equations that use it, updated only where a substitution lands."""

    def __init__(self, sys: _System):
        self.sys = sys
        self.live: dict[int, sp.Expr] = dict(enumerate(sys.eqs))
        self.inc: dict[int, set[sp.Symbol]] = {k: sys.incidence(e) for k, e in self.live.items()}
        self.occ: dict[sp.Symbol, set[int]] = {}
        for k, vs in self.inc.items():
            for v in vs:
                self.occ.setdefault(v, set()).add(k)
        self.version = dict.fromkeys(self.live, 0)

    def differentiated(self, u: sp.Symbol) -> bool:
        d = self.sys.der.get(u)
        return d is not None and bool(self.occ.get(d))

    def users(self, v: sp.Symbol) -> set[int]:
        out = set(self.occ.get(v, ()))
        d = self.sys.der.get(v)
        if d is not None:
            out |= self.occ.get(d, set())
        return out

    def set_eq(self, k: int, e: sp.Expr) -> None:
        for v in self.inc[k]:
            self.occ[v].discard(k)
        self.live[k] = e
        self.inc[k] = self.sys.incidence(e)
        for v in self.inc[k]:
            self.occ.setdefault(v, set()).add(k)
        self.version[k] += 1

    def drop(self, k: int) -> None:
        for v in self.inc.pop(k):
            self.occ[v].discard(k)
        del self.live[k]


def _fill(ix: _Index, k: int, mapping: Mapping[sp.Symbol, sp.Expr],
          new_inc: Mapping[sp.Symbol, set[sp.Symbol]]) -> int:
    """Change in the number of (equation, variable) incidences if equation k is used to
    substitute ``mapping`` into every other equation (a fill-in measure, exact up to
    cancellation)."""
    delta = -len(ix.inc[k])
    touched: set[int] = set()
    for s in mapping:
        touched |= ix.occ.get(s, set())
    for f in touched - {k}:
        inc = ix.inc[f]
        after = inc - set(mapping)
        for s in mapping:
            if s in inc:
                after |= new_inc[s]
        delta += len(after) - len(inc)
    return delta


def _candidate(ix: _Index, k: int, v: sp.Symbol):
    """The substitution that eliminates v with equation k, or None if it is not allowed."""
    sys = ix.sys
    e, inc = ix.live[k], ix.inc[k]
    if sys.der.get(v) in inc:
        return None
    c = _linear_coeff(e, v)
    if c is None:
        return None
    rest = _solve_for(e, v, c)
    rest_inc = sys.incidence(rest)
    mapping = {v: rest}
    new_inc = {v: rest_inc}
    if ix.differentiated(v):
        # Substituting a state is only exact if its derivative is known too, and that
        # stays index-preserving only when rest depends on states and t alone.
        if any(s in sys.anti or not ix.differentiated(s) for s in rest_inc):
            return None
        d = sys.differentiate(rest)
        mapping[sys.der[v]] = d
        new_inc[sys.der[v]] = sys.incidence(d)
    return mapping, _fill(ix, k, mapping, new_inc)


def _push(ix: _Index, heap: list, k: int) -> None:
    sys = ix.sys
    cands = sorted((v for v in ix.inc[k] if v in sys.unknowns),
                   key=lambda v: (ix.differentiated(v), -v.name.count("."), v.name))
    for rank, v in enumerate(cands):
        heapq.heappush(heap, (len(ix.inc[k]), k, rank, ix.version[k], v))


def eliminate(sys: _System) -> int:
    """Solve-and-substitute equations linear in an unknown with a numeric coefficient,
    as long as the substitution adds no fill-in (Markowitz-like: the total incidence must
    not grow), smallest equations first. Each step touches only the equations that use the
    eliminated unknown. Returns how many unknowns were eliminated."""
    ix = _Index(sys)
    heap: list = []
    for k in ix.live:
        _push(ix, heap, k)
    count = 0
    while heap:
        _, k, _, version, v = heapq.heappop(heap)
        if k not in ix.live or ix.version[k] != version or v not in ix.inc[k] \
                or v not in sys.unknowns:
            continue
        got = _candidate(ix, k, v)
        if got is None or got[1] > 0:
            continue
        mapping = got[0]
        touched: set[int] = set()
        for s in mapping:
            touched |= ix.occ.get(s, set())
        ix.drop(k)
        sys.unknowns.discard(v)
        sys.record(mapping)
        if len(mapping) > 1:  # a state and its derivative: rest was differentiated
            sys.differentiated_params |= mapping[v].free_symbols & sys.params
        for f in sorted(touched - {k}):
            ix.set_eq(f, ix.live[f].xreplace(mapping))
            _push(ix, heap, f)
        count += 1
    keep = sorted(ix.live)
    sys.eqs = [ix.live[k] for k in keep]
    sys.origins = [sys.origins[k] for k in keep]
    return count


def _highest(sys: _System, used: set[sp.Symbol]) -> list[sp.Symbol]:
    """Unknowns and derivatives that appear and are not themselves differentiated."""
    return [v for v in sys.variables() if v in used and sys.der.get(v) not in used]


def _match(sys: _System, eqs: list[int], cols: list[sp.Symbol]) -> dict:
    g = nx.Graph()
    g.add_nodes_from((("e", i) for i in eqs), bipartite=0)
    g.add_nodes_from((("v", v) for v in cols), bipartite=1)
    colset = set(cols)
    for i in eqs:
        for v in sys.incidence(sys.eqs[i]) & colset:
            g.add_edge(("e", i), ("v", v))
    return nx.bipartite.maximum_matching(g, top_nodes=[("e", i) for i in eqs])


def pantelides(sys: _System) -> list[int | None]:
    """Pantelides (1988): differentiate equations until the highest derivatives match.

    Returns B: B[i] is the index of the derivative of equation i (None if not differentiated).
    """
    B: list[int | None] = [None] * len(sys.eqs)
    used = sys.used()
    D: dict[sp.Symbol, sp.Symbol] = {v: d for v, d in sys.der.items() if d in used}
    assign: dict[sp.Symbol, int] = {}
    inc = [sys.incidence(e) for e in sys.eqs]

    def augment(i: int, ce: set[int], cv: set[sp.Symbol]) -> bool:
        ce.add(i)
        cands = [j for j in inc[i] if j not in D]
        for j in cands:
            if j not in assign:
                assign[j] = i
                return True
        for j in cands:
            if j not in cv:
                cv.add(j)
                if augment(assign[j], ce, cv):
                    assign[j] = i
                    return True
        return False

    n0 = len(sys.eqs)
    for k in range(n0):
        i = k
        for _ in range(4 * n0 + 4):
            ce: set[int] = set()
            cv: set[sp.Symbol] = set()
            if augment(i, ce, cv):
                break
            for j in cv:
                D[j] = sys.der_of(j)
            for lq in sorted(ce):
                sys.differentiated_params |= sys.eqs[lq].free_symbols & sys.params
                sys.eqs.append(sp.expand(sys.differentiate(sys.eqs[lq])))
                sys.origins.append(f"d/dt of ({sys.origins[lq]})")
                inc.append(sys.incidence(sys.eqs[-1]))
                B[lq] = len(sys.eqs) - 1
                B.append(None)
            for j in cv:
                assign[D[j]] = B[assign[j]]  # type: ignore[assignment]
            i = B[i]  # type: ignore[assignment]
        else:
            raise SingularCircuitError(
                f"the equations are structurally singular: equation '{sys.origins[k]}' cannot "
                f"be matched to an unknown even after differentiation. The circuit "
                f"over-determines some quantity (e.g. two ideal sources fixing the same "
                f"voltage or speed)")
    return B


def dummy_derivatives(sys: _System, B: list[int | None], nominal: Mapping[sp.Symbol, float]
                      ) -> None:
    """Mattsson-Soederlind: pick derivatives to become algebraic (dummy) unknowns."""
    pred = {b: i for i, b in enumerate(B) if b is not None}
    used = sys.used()
    level_eqs = [i for i in range(len(sys.eqs)) if B[i] is None and i in pred]
    cands = [v for v in _highest(sys, used) if v in sys.anti]
    dummies: list[sp.Symbol] = []
    while level_eqs:
        cols = [v for v in cands if any(v in sys.incidence(sys.eqs[i]) for i in level_eqs)]
        M = np.array([[_num(sp.diff(sys.eqs[i], v), nominal) for v in cols]
                      for i in level_eqs], dtype=float)
        if len(cols) < len(level_eqs):
            raise SingularCircuitError("index reduction failed: fewer derivatives than "
                                       "differentiated constraints (" +
                                       ", ".join(sys.origins[i] for i in level_eqs) + ")")
        import scipy.linalg as sla

        _, r, piv = sla.qr(M, pivoting=True)
        rank = int(np.sum(np.abs(np.diag(r)) > 1e-10 * max(1.0, np.abs(r).max())))
        if rank < len(level_eqs):
            raise SingularCircuitError("index reduction failed: the differentiated constraints "
                                       "are singular (" + ", ".join(sys.origins[i] for i in
                                                                     level_eqs) + ")")
        chosen = [cols[j] for j in piv[: len(level_eqs)]]
        dummies += chosen
        level_eqs = [pred[i] for i in level_eqs if pred[i] in pred]
        cands = [sys.anti[v] for v in chosen if sys.anti[v] in sys.anti]
    mapping = {}
    for d in dummies:
        dd = sp.Symbol(f"dummy({d.name})", real=True)
        sys.unknowns.add(dd)
        mapping[d] = dd
        sys.report.append(f"dummy derivative: {d.name} becomes algebraic")
    sys.eqs = [e.xreplace(mapping) for e in sys.eqs]
    sys.record(mapping)


def _num(e: sp.Expr, nominal: Mapping[sp.Symbol, float]) -> float:
    """Value of a Jacobian entry at nominal parameters and a generic point of the unknowns
    (a fixed, name-derived value: the same choice in every process)."""
    e = as_expr(e)
    vals = {s: nominal.get(s, 0.5 + 0.1 * (zlib.crc32(s.name.encode()) % 7))
            for s in e.free_symbols}
    try:
        return float(sp.N(e.xreplace(vals)))
    except (TypeError, ValueError):  # complex or undefined at that point: treat as absent
        return 0.0


def reduce_index(dae: Dae, nominal: Mapping[sp.Symbol, float]) -> IndexOneDae:
    """Make the DAE index 1 (see module docstring); ``nominal`` are parameter values used
    only to choose dummy derivatives numerically."""
    sys = _System(dae)
    n0 = len(sys.unknowns)
    eliminate(sys)
    sys.report.append(f"alias/linear elimination: {n0} -> {len(sys.unknowns)} unknowns")
    if not _is_index_one(sys):
        B = pantelides(sys)
        n_diff = sum(b is not None for b in B)
        sys.report.append(f"Pantelides: differentiated {n_diff} equation(s)")
        dummy_derivatives(sys, B, nominal)
        eliminate(sys)
        sys.report.append(f"after index reduction: {len(sys.unknowns)} unknowns")
    _check_square(sys)
    used = sys.used()
    diff = sorted((u for u in sys.unknowns if sys.der.get(u) in used), key=lambda s: s.name)
    alg = sorted((u for u in sys.unknowns if sys.der.get(u) not in used), key=lambda s: s.name)
    if not _is_index_one(sys):
        raise SingularCircuitError("could not reduce the circuit to index 1: " +
                                   _unmatched(sys))
    states = tuple(diff + alg)
    yp = tuple(sys.der_of(s) for s in states)
    resolve = sys.resolved()
    exports = {k: as_expr(v).xreplace(resolve) for k, v in dae.exports.items()}
    probes = {k: as_expr(v).xreplace(resolve) for k, v in dae.probes.items()}
    # a guard or a new value may name an eliminated unknown: write it in the states
    events = tuple(SwitchEvent(e.owner, e.guard.xreplace(resolve),
                               tuple((s, v.xreplace(resolve)) for s, v in e.sets))
                   for e in dae.events)
    crossings = tuple(Crossing(c.owner, c.mode, c.distance.xreplace(resolve),
                               c.scale.xreplace(resolve)) for c in dae.crossings)
    # the time rate joins the parameters if a differentiation brought it in
    params = (*dae.params, *sorted(sys.params - set(dae.params), key=lambda s: s.name))
    return IndexOneDae(dae.t, states, yp, len(diff), tuple(sys.eqs), tuple(sys.origins),
                       params, resolve, exports, probes, dict(dae.initial), dae.tables,
                       dae.breaks, dae.units, tuple(sys.report), dae.integrals, events,
                       crossings, tuple(sorted(p.name for p in sys.differentiated_params)))


def _check_square(sys: _System) -> None:
    if len(sys.eqs) != len(sys.unknowns):
        raise SingularCircuitError(
            f"{len(sys.eqs)} equations for {len(sys.unknowns)} unknowns: " + _unmatched(sys))


def _is_index_one(sys: _System) -> bool:
    used = sys.used()
    cols = [sys.der[u] if sys.der.get(u) in used else u for u in sys.unknowns]
    if len(cols) != len(sys.eqs):
        return False
    m = _match(sys, list(range(len(sys.eqs))), cols)
    return sum(1 for k in m if k[0] == "e") == len(sys.eqs)


def _unmatched(sys: _System) -> str:
    used = sys.used()
    cols = [sys.der[u] if sys.der.get(u) in used else u for u in sys.unknowns]
    m = _match(sys, list(range(len(sys.eqs))), cols)
    eqs = [sys.origins[i] for i in range(len(sys.eqs)) if ("e", i) not in m]
    vs = [v.name for v in cols if ("v", v) not in m]
    return (f"no unknown left for {'; '.join(eqs) or 'none'}; undetermined: "
            f"{', '.join(vs) or 'none'}. Look for ideal sources or constraints that fix the "
            f"same quantity twice, or a node only reachable through current sources")
