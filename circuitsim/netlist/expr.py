"""Restricted expression language for netlist values and probes.

A netlist is data: nothing in it is ever handed to ``eval``, ``sympify`` or ``parse_expr``.
This module tokenises and parses arithmetic over numbers, names and a fixed set of functions,
with an optional unit suffix applying to the whole value (``0.0168/(2*pi) V*s/rad``).
Anything else is a syntax error before any evaluation happens.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from circuitsim.units import Dim, compatible, dim_mul, dim_pow, dimensionless, unit_info

FUNCTIONS: dict[str, tuple[int, Callable[..., float]]] = {
    "sin": (1, math.sin), "cos": (1, math.cos), "tan": (1, math.tan),
    "exp": (1, math.exp), "log": (1, math.log), "sqrt": (1, math.sqrt),
    "abs": (1, abs), "atan": (1, math.atan), "tanh": (1, math.tanh),
    "min": (2, min), "max": (2, max),
}
CONSTANTS = {"pi": math.pi}

_TOKEN = re.compile(r"""
    (?P<ws>\s+)
  | (?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*(?:\.[A-Za-z_][A-Za-z0-9_]*)*)
  | (?P<op>\*\*|[-+*/^(),])
""", re.VERBOSE)


class ExprError(ValueError):
    """Malformed or unsafe expression text; ``pos`` is the 0-based column."""

    def __init__(self, message: str, text: str, pos: int):
        self.pos = pos
        super().__init__(f"{message} in '{text}' at column {pos + 1}")


@dataclass(frozen=True, slots=True)
class Node:
    """Expression tree node. ``kind``: num, name, neg, bin, call, unit."""

    kind: str
    value: object = None
    args: tuple[Node, ...] = ()


class _Parser:
    def __init__(self, text: str):
        self.text = text
        self.toks: list[tuple[str, str, int]] = []
        pos = 0
        while pos < len(text):
            m = _TOKEN.match(text, pos)
            if m is None:
                # Not an operator we know: the rest may be a unit suffix; decided by the caller.
                self.toks.append(("rest", text[pos:], pos))
                break
            if m.lastgroup != "ws":
                self.toks.append((m.lastgroup, m.group(), pos))
            pos = m.end()
        self.i = 0

    def peek(self) -> tuple[str, str, int]:
        return self.toks[self.i] if self.i < len(self.toks) else ("end", "", len(self.text))

    def take(self) -> tuple[str, str, int]:
        tok = self.peek()
        self.i += 1
        return tok

    def expect(self, op: str) -> None:
        kind, val, pos = self.take()
        if val != op or kind != "op":
            raise ExprError(f"expected '{op}'", self.text, pos)

    def expr(self) -> Node:
        node = self.term()
        while self.peek()[1] in "+-" and self.peek()[0] == "op":
            op = self.take()[1]
            node = Node("bin", op, (node, self.term()))
        return node

    def term(self) -> Node:
        node = self.unary()
        while self.peek()[0] == "op" and self.peek()[1] in ("*", "/"):
            op = self.take()[1]
            node = Node("bin", op, (node, self.unary()))
        return node

    def unary(self) -> Node:
        kind, val, _ = self.peek()
        if kind == "op" and val in "+-":
            self.take()
            inner = self.unary()
            return Node("neg", None, (inner,)) if val == "-" else inner
        return self.power()

    def power(self) -> Node:
        base = self.atom()
        if self.peek()[0] == "op" and self.peek()[1] in ("**", "^"):
            self.take()
            return Node("bin", "**", (base, self.unary()))
        return base

    def atom(self) -> Node:
        kind, val, pos = self.take()
        if kind == "num":
            return Node("num", float(val))
        if kind == "name":
            if self.peek()[1] == "(" and self.peek()[0] == "op":
                if val not in FUNCTIONS:
                    raise ExprError(f"unknown function '{val}' (allowed: "
                                    f"{', '.join(sorted(FUNCTIONS))})", self.text, pos)
                self.take()
                args = [self.expr()]
                while self.peek()[1] == "," and self.peek()[0] == "op":
                    self.take()
                    args.append(self.expr())
                self.expect(")")
                if len(args) != FUNCTIONS[val][0]:
                    raise ExprError(f"{val}() takes {FUNCTIONS[val][0]} argument(s)",
                                    self.text, pos)
                return Node("call", val, tuple(args))
            if val in CONSTANTS:
                return Node("num", CONSTANTS[val])
            return Node("name", val)
        if kind == "op" and val == "(":
            node = self.expr()
            self.expect(")")
            return node
        what = "end of text" if kind == "end" else f"'{val[:20]}'"
        raise ExprError(f"unexpected {what}", self.text, pos)


def parse(text: str, *, allow_unit: bool = True) -> Node:
    """Parse ``text`` into a tree; a trailing unit (``0.87 mH``) becomes a ``unit`` node.

    Raises ExprError on anything that is not arithmetic over numbers, names and the
    functions in FUNCTIONS.
    """
    if not isinstance(text, str) or not text.strip():
        raise ExprError("empty expression", str(text), 0)
    p = _Parser(text)
    node = p.expr()
    kind, _, pos = p.peek()
    if kind == "end":
        return node
    rest = text[pos:].strip()
    if not allow_unit:
        raise ExprError(f"unexpected '{rest[:20]}'", text, pos)
    # A unit suffix is letters, digits, *, /, ^, ** and parentheses only; anything else
    # (quotes, brackets, dots used as attribute access) is rejected before pint sees it.
    if not re.fullmatch(r"[A-Za-zµΩ°_][A-Za-z0-9µΩ°_ */^().\-]*", rest) or "__" in rest:
        raise ExprError(f"unexpected '{rest[:20]}'", text, pos)
    try:
        factor, dim = unit_info(rest)
    except ValueError as exc:
        raise ExprError(str(exc), text, pos) from exc
    return Node("unit", (rest, factor, dim), (node,))


def names(node: Node) -> set[str]:
    """Every name the expression refers to."""
    if node.kind == "name":
        return {str(node.value)}
    out: set[str] = set()
    for a in node.args:
        out |= names(a)
    return out


def evaluate(node: Node, env: Mapping[str, float]) -> float:
    """Numeric value in SI, names looked up in ``env`` (already SI floats)."""
    k = node.kind
    if k == "num":
        return float(node.value)  # type: ignore[arg-type]
    if k == "name":
        return float(env[str(node.value)])
    if k == "neg":
        return -evaluate(node.args[0], env)
    if k == "unit":
        return evaluate(node.args[0], env) * node.value[1]  # type: ignore[index]
    if k == "call":
        fn = FUNCTIONS[str(node.value)][1]
        return float(fn(*(evaluate(a, env) for a in node.args)))
    a, b = (evaluate(x, env) for x in node.args)
    op = node.value
    if op == "+":
        return a + b
    if op == "-":
        return a - b
    if op == "*":
        return a * b
    if op == "/":
        if b == 0.0:
            raise ZeroDivisionError("division by zero")
        return a / b
    if a < 0.0 and not float(b).is_integer():
        # Python would return a complex number, which no parameter can hold.
        raise ValueError(f"a negative base ({a:g}) has no real power {b:g}")
    return a**b


def dimension(node: Node, env: Mapping[str, Dim | None]) -> Dim | None:
    """Dimension of the expression, or None when a bare number makes it unknowable.

    A name whose value was given without units is a wildcard (None), as in SPICE where
    every number is taken in the unit the element expects.
    """
    k = node.kind
    if k == "num":
        return dimensionless()
    if k == "name":
        return env[str(node.value)]
    if k == "neg":
        return dimension(node.args[0], env)
    if k == "unit":
        inner = dimension(node.args[0], env)
        return None if inner is None else dim_mul(inner, node.value[2])  # type: ignore[index]
    if k == "call":
        for a in node.args:
            d = dimension(a, env)
            if d is not None and node.value not in ("abs", "min", "max") and \
                    not compatible(d, dimensionless()) and d.dims:
                raise ValueError(f"{node.value}() needs a dimensionless argument, got {d}")
        if node.value in ("abs", "min", "max"):
            return dimension(node.args[0], env)
        return dimensionless()
    a, b = (dimension(x, env) for x in node.args)
    op = node.value
    if op in "+-":
        if a is None or b is None:
            return a if b is None else b
        if not compatible(a, b):
            raise ValueError(f"cannot add {a} and {b}")
        return a
    if op == "**":
        if b is not None and b.dims:
            raise ValueError("an exponent must be dimensionless")
        if a is None:
            return None
        if node.args[1].kind != "num":
            if a.dims:
                raise ValueError("a dimensioned base needs a constant exponent")
            return a
        return dim_pow(a, float(node.args[1].value))  # type: ignore[arg-type]
    if a is None or b is None:
        return None
    return dim_mul(a, b, 1.0 if op == "*" else -1.0)


def to_sympy(node: Node, symbols: Mapping[str, object]):
    """Build a sympy expression from the tree (names mapped through ``symbols``).

    Raises NetlistError when the result is infinite, undefined or complex (``x/0``,
    ``sqrt(-1)``): generated code could not evaluate it.
    """
    import sympy as sp

    from circuitsim.errors import NetlistError

    out = _to_sympy(node, symbols)
    if isinstance(out, sp.Basic) and out.has(sp.zoo, sp.nan, sp.oo, -sp.oo, sp.I):
        raise NetlistError(f"the expression evaluates to {out}: infinite, undefined or "
                           f"complex (a division by zero?); rewrite it so it stays finite")
    return out


def _to_sympy(node: Node, symbols: Mapping[str, object]):
    import sympy as sp

    k = node.kind
    if k == "num":
        v = float(node.value)  # type: ignore[arg-type]
        return sp.Integer(int(v)) if v.is_integer() and abs(v) < 1e15 else sp.Float(v)
    if k == "name":
        return symbols[str(node.value)]
    if k == "neg":
        return -_to_sympy(node.args[0], symbols)
    if k == "unit":
        return _to_sympy(node.args[0], symbols) * sp.Float(node.value[1])  # type: ignore[index]
    if k == "call":
        fn = {"abs": sp.Abs, "min": sp.Min, "max": sp.Max, "log": sp.log}.get(
            str(node.value)) or getattr(sp, str(node.value))
        return fn(*(_to_sympy(a, symbols) for a in node.args))
    a, b = (_to_sympy(x, symbols) for x in node.args)
    return {"+": lambda: a + b, "-": lambda: a - b, "*": lambda: a * b,
            "/": lambda: a / b, "**": lambda: a**b}[str(node.value)]()
