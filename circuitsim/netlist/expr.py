"""Restricted expression language for netlist values and probes.

A netlist is data: nothing in it is ever handed to ``eval``, ``sympify`` or ``parse_expr``.
This module tokenises and parses arithmetic over numbers, names and a fixed set of functions,
comparisons (``<``, ``<=``, ``>``, ``>=``, ``==``, ``!=``: 1 when true, 0 when false) and
``if(condition, then, else)``, with an optional unit suffix applying to the whole value
(``0.0168/(2*pi) V*s/rad``) or a unit in brackets after any number (``2[mA]*exp(x.v/Vt)``).
Anything else is a syntax error before any evaluation happens. Text longer than MAX_LENGTH,
nested deeper than MAX_NESTING or with a tree deeper than MAX_DEPTH is refused at once (no
RecursionError, no hang), and so is a constant power too large for a float.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from circuitsim.units import Dim, compatible, dim_mul, dim_pow, dimensionless, unit_info


def _sign(x: float) -> float:
    return float((x > 0) - (x < 0))


def _smooth_abs(x: float, eps: float) -> float:
    return math.sqrt(x * x + eps * eps)


def _smooth_sign(x: float, eps: float) -> float:
    return math.tanh(x / eps)


def _clamp(x: float, lo: float, hi: float) -> float:
    return min(max(x, lo), hi)


FUNCTIONS: dict[str, tuple[int, Callable[..., float]]] = {
    "sin": (1, math.sin), "cos": (1, math.cos), "tan": (1, math.tan),
    "exp": (1, math.exp), "log": (1, math.log), "sqrt": (1, math.sqrt),
    "abs": (1, abs), "atan": (1, math.atan), "tanh": (1, math.tanh),
    "min": (2, min), "max": (2, max), "sign": (1, _sign), "clamp": (3, _clamp),
    # smooth variants for laws an integrator must differentiate through: sqrt(x^2 + eps^2)
    # and tanh(x/eps), eps in the unit of x
    "smooth_abs": (2, _smooth_abs), "smooth_sign": (2, _smooth_sign),
    "if": (3, lambda c, a, b: a if c else b),
}
CONSTANTS = {"pi": math.pi}
COMPARISONS = ("<", "<=", ">", ">=", "==", "!=")

#: Limits that keep hostile or runaway text from reaching a RecursionError or a hang.
MAX_LENGTH = 10_000  # characters
MAX_NESTING = 48  # parentheses, calls and unary signs inside each other
MAX_DEPTH = 400  # depth of the tree (a long chain a+b+c+... is deep too)

_UNIT_TEXT = r"[A-Za-zµΩ°_][A-Za-z0-9µΩ°_ */^().\-]*"
_TOKEN = re.compile(r"""
    (?P<ws>\s+)
  | (?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)(?:\s*\[(?P<unit>[^\]]*)\])?
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*(?:\.[A-Za-z_][A-Za-z0-9_]*)*)
  | (?P<op>\*\*|<=|>=|==|!=|[-+*/^(),<>])
""", re.VERBOSE)


class ExprError(ValueError):
    """Malformed or unsafe expression text; ``pos`` is the 0-based column."""

    def __init__(self, message: str, text: str, pos: int):
        self.pos = pos
        shown = text if len(text) <= 120 else f"{text[:100]}..."  # hostile text can be huge
        super().__init__(f"{message} in '{shown}' at column {pos + 1}")


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
            if m.group("num") is not None and m.group("unit") is not None:
                self.toks.append(("unum", m.group(), pos))
            elif m.lastgroup != "ws":
                self.toks.append((m.lastgroup, m.group(), pos))
            pos = m.end()
        self.i = 0
        self.nesting = 0

    def deeper(self, pos: int) -> None:
        self.nesting += 1
        if self.nesting > MAX_NESTING:
            raise ExprError(f"nested more than {MAX_NESTING} levels deep", self.text, pos)

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
        """A comparison (not chained: ``a < b < c`` is an error) or a sum."""
        self.deeper(self.peek()[2])
        node = self.sum()
        if self.peek()[0] == "op" and self.peek()[1] in COMPARISONS:
            op = self.take()[1]
            node = Node("cmp", op, (node, self.sum()))
        self.nesting -= 1
        return node

    def sum(self) -> Node:
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
            self.deeper(self.take()[2])
            inner = self.unary()
            self.nesting -= 1
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
        if kind == "unum":
            number, unit = val.split("[", 1)
            return _with_unit(Node("num", float(number)), unit[:-1].strip(), self.text, pos)
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
    if len(text) > MAX_LENGTH:
        raise ExprError(f"expression longer than {MAX_LENGTH} characters", text, MAX_LENGTH)
    p = _Parser(text)
    node = p.expr()
    kind, _, pos = p.peek()
    if kind != "end":
        rest = text[pos:].strip()
        if not allow_unit:
            raise ExprError(f"unexpected '{rest[:20]}'", text, pos)
        node = _with_unit(node, rest, text, pos)
    if _depth(node) > MAX_DEPTH:
        raise ExprError(f"expression nested more than {MAX_DEPTH} operations deep; split it "
                        f"into named parameters", text, 0)
    return node


def _with_unit(node: Node, unit: str, text: str, pos: int) -> Node:
    # A unit is letters, digits, *, /, ^, ** and parentheses only; anything else (quotes,
    # brackets, dots used as attribute access) is rejected before pint sees it.
    if not re.fullmatch(_UNIT_TEXT, unit) or "__" in unit:
        raise ExprError(f"unexpected '{unit[:20]}'", text, pos)
    try:
        factor, dim = unit_info(unit)
    except ValueError as exc:
        raise ExprError(str(exc), text, pos) from exc
    return Node("unit", (unit, factor, dim), (node,))


def _depth(root: Node) -> int:
    """Depth of the tree, without recursion (a flat chain of 10^4 additions is deep)."""
    deepest, stack = 0, [(root, 1)]
    while stack:
        node, d = stack.pop()
        deepest = max(deepest, d)
        if deepest > MAX_DEPTH:
            return deepest
        stack.extend((a, d + 1) for a in node.args)
    return deepest


def names(node: Node) -> set[str]:
    """Every name the expression refers to."""
    if node.kind == "name":
        return {str(node.value)}
    out: set[str] = set()
    for a in node.args:
        out |= names(a)
    return out


def is_polynomial(node: Node) -> bool:
    """True when the tree is only sums, differences and products of names and finite
    numbers (with units): finite and real wherever its names are, so ``to_sympy``'s check
    for ``x/0`` or ``sqrt(-1)`` cannot fail on it (and a loader need not import sympy)."""
    stack = [node]
    while stack:
        n = stack.pop()
        if n.kind == "num":
            ok = math.isfinite(float(n.value))  # type: ignore[arg-type]
        elif n.kind == "unit":
            ok = math.isfinite(n.value[1])  # type: ignore[index]
        else:
            ok = n.kind in ("name", "neg") or (n.kind == "bin" and n.value in ("+", "-", "*"))
        if not ok:
            return False
        stack.extend(n.args)
    return True


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
    if k == "call" and node.value == "if":  # only the branch taken is evaluated
        cond = evaluate(node.args[0], env)
        return evaluate(node.args[1] if cond != 0.0 else node.args[2], env)
    if k == "call":
        fn = FUNCTIONS[str(node.value)][1]
        return float(fn(*(evaluate(a, env) for a in node.args)))
    a, b = (evaluate(x, env) for x in node.args)
    if k == "cmp":
        return float(_COMPARE[str(node.value)](a, b))
    return _arith(str(node.value), a, b)


_COMPARE: dict[str, Callable[[float, float], bool]] = {
    "<": lambda a, b: a < b, "<=": lambda a, b: a <= b, ">": lambda a, b: a > b,
    ">=": lambda a, b: a >= b, "==": lambda a, b: a == b, "!=": lambda a, b: a != b}


def _arith(op: str, a: float, b: float) -> float:
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


#: Functions whose arguments share one dimension and whose value has it too.
_SAME_DIM = {"abs": 1, "min": 2, "max": 2, "clamp": 3, "smooth_abs": 2}
#: Functions of a dimensioned argument whose value is a pure number.
_ANY_TO_ONE = {"sign": 1, "smooth_sign": 2}


def dimension(node: Node, env: Mapping[str, Dim | None], wild: bool = False) -> Dim | None:
    """Dimension of the expression, or None when a bare number makes it unknowable.

    A name whose value was given without units is a wildcard (None), as in SPICE where
    every number is taken in the unit the element expects; with ``wild`` a bare number is
    one too (behavioural expressions: ``0.1*s.w`` gives the 0.1 the unit it needs).
    """
    k = node.kind
    if k == "num":
        return None if wild else dimensionless()
    if k == "name":
        return env[str(node.value)]
    if k == "neg":
        return dimension(node.args[0], env, wild)
    if k == "unit":
        inner = dimension(node.args[0], env)  # a number with its unit: known
        return None if inner is None else dim_mul(inner, node.value[2])  # type: ignore[index]
    if k == "call":
        return _call_dimension(node, [dimension(a, env, wild) for a in node.args])
    a, b = (dimension(x, env, wild) for x in node.args)
    op = node.value
    if k == "cmp" or op in "+-":
        if a is not None and b is not None and not compatible(a, b):
            raise ValueError(f"cannot {'compare' if k == 'cmp' else 'add'} {a} and {b}")
        return dimensionless() if k == "cmp" else (a if b is None else b) if a is None else a
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


def unit_mismatch(node: Node, unit: str, env: Mapping[str, Dim | None]) -> str | None:
    """Why a behavioural expression cannot be in ``unit``, or None. Bare numbers and
    parameters given without units are wildcards: only known dimensions are checked."""
    from circuitsim.units import explain_mismatch

    try:
        got = dimension(node, env, wild=True)
    except ValueError as exc:
        return str(exc)
    if got is None:
        return None
    _, want = unit_info(unit)
    return None if compatible(got, want) else explain_mismatch(got, want, unit)


def _same(dims: list[Dim | None], what: str) -> Dim | None:
    known = [d for d in dims if d is not None]
    for d in known[1:]:
        if not compatible(known[0], d):
            raise ValueError(f"{what}() needs arguments of one dimension, got {known[0]} "
                             f"and {d}")
    return dims[0]


def _call_dimension(node: Node, dims: list[Dim | None]) -> Dim | None:
    fn = str(node.value)
    if fn in _SAME_DIM:
        return _same(dims, fn)
    if fn in _ANY_TO_ONE:
        _same(dims, fn)
        return dimensionless()
    if fn == "if":
        return _same(dims[1:], fn)
    if fn == "sqrt":
        return None if dims[0] is None else dim_pow(dims[0], 0.5)
    for d in dims:
        if d is not None and d.dims and not compatible(d, dimensionless()):
            raise ValueError(f"{fn}() needs a dimensionless argument, got {d}")
    return dimensionless()


def to_sympy(node: Node, symbols: Mapping[str, object]):
    """Build a sympy expression from the tree (names mapped through ``symbols``).

    abs, sign, min, max, comparisons and if-then-else become ``Piecewise``: its derivative
    is taken piece by piece (sympy's Abs would need its argument known to be real, and
    its derivative would reach the generated code as re/im). Raises NetlistError when the
    result is infinite, undefined or complex (``x/0``, ``sqrt(-1)``) or a constant too large
    for a float: generated code could not evaluate it.
    """
    import sympy as sp

    from circuitsim.errors import NetlistError

    try:
        out = _to_sympy(node, symbols)
    except OverflowError:
        raise NetlistError("a constant in the expression is too large for a float (a power "
                           "tower?); rewrite it") from None
    if isinstance(out, sp.Basic):
        out = out.replace(sp.Abs, lambda x: _pw_abs(x)).replace(sp.sign, lambda x: _pw_sign(x))
        if out.has(sp.zoo, sp.nan, sp.oo, -sp.oo, sp.I):
            raise NetlistError(f"the expression evaluates to {out}: infinite, undefined or "
                               f"complex (a division by zero?); rewrite it so it stays finite")
    return out


def _pw_abs(x):
    import sympy as sp

    return sp.Piecewise((x, x >= 0), (-x, True))


def _pw_sign(x):
    import sympy as sp

    return sp.Piecewise((1, x > 0), (-1, x < 0), (0, True))


def _truth(c):
    """The condition of an ``if``: a comparison as itself, anything else as ``c != 0``."""
    import sympy as sp

    if isinstance(c, sp.Piecewise) and len(c.args) == 2 and c.args[0].expr == 1 and \
            c.args[1].expr == 0 and c.args[1].cond is sp.true:
        return c.args[0].cond
    return sp.Ne(c, 0)


def _call(fn: str, args: list):
    import sympy as sp

    if fn == "abs":
        return _pw_abs(args[0])
    if fn == "sign":
        return _pw_sign(args[0])
    if fn in ("min", "max"):
        a, b = args
        return sp.Piecewise((a, a <= b if fn == "min" else a >= b), (b, True))
    if fn == "clamp":
        x, lo, hi = args
        return sp.Piecewise((lo, x < lo), (hi, x > hi), (x, True))
    if fn == "smooth_abs":
        return sp.sqrt(args[0] ** 2 + args[1] ** 2)
    if fn == "smooth_sign":
        return sp.tanh(args[0] / args[1])
    if fn == "if":
        return sp.Piecewise((args[1], _truth(args[0])), (args[2], True))
    return getattr(sp, fn)(*args)


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
        return _call(str(node.value), [_to_sympy(a, symbols) for a in node.args])
    a, b = (_to_sympy(x, symbols) for x in node.args)
    if k == "cmp":
        rel = {"<": sp.Lt, "<=": sp.Le, ">": sp.Gt, ">=": sp.Ge, "==": sp.Eq, "!=": sp.Ne}
        return sp.Piecewise((1, rel[str(node.value)](a, b)), (0, True))
    if node.value == "**" and isinstance(a, sp.Number) and isinstance(b, sp.Number):
        # a constant power is computed as a float: sympy would compute 9**9**9 exactly
        return sp.Float(_arith("**", float(a), float(b)))
    return {"+": lambda: a + b, "-": lambda: a - b, "*": lambda: a * b,
            "/": lambda: a / b, "**": lambda: a**b}[str(node.value)]()
