"""Generate and cache the numeric code of an index-1 DAE.

Pipeline stage 5. One Python module per topology: one residual call for the whole network;
its Jacobian dF/dy + cj dF/dy' at the structural nonzeros only (a flat array in
compressed-column order, with the pattern in the metadata); the flat parts dF/dy, dF/dy',
dF/dt (consistent initial values, linearisation); the residual split into a linear part
(coefficients from the parameters alone, evaluated as a sparse matrix product for large
models) and the remaining terms; and every probe and eliminated variable as a vectorised
expression compiled only when asked for. Sums and products are printed directly; common
subexpressions are searched only among the non-polynomial expressions. Parameters are a
run-time tuple, so a parameter change never reaches sympy.

The module is stored by ``cache`` and loaded from there after a content check; a second run
of the same topology does no symbolic work.
"""

from __future__ import annotations

import ast
import functools
import re
import sys
from typing import Any

from circuitsim.solve.kernel_lib import BAND_ABS, BAND_REL, GUARDED, KERNEL_LIB

CODEGEN_VERSION = "30"  # 24-25: the root function (25: with tables); 26: batches with tables;
# 27: relations' modes numbered in canonical order; 28: an inert term's function skipped;
# 29: sums and products inside functions printed directly; 30: the knee of a coil's
# saturation a call in the kernels (kernel_lib.knee_u)

# [unknowns] from here on the residual's linear part is a sparse matrix product (measured on
# RLC ladders: 5x slower than the scalar code at 16 unknowns, 2x at 50, equal at 100) ...
MATRIX_RESIDUAL_FROM = 100
# ... and IDA factorises with SuperLU_MT instead of a dense LU (its ~10 ms per factorisation
# loses to the dense O(n^3) LU up to a few hundred unknowns: measured crossover 250-500)
SPARSE_FROM = 400


class _Direct:
    """Sums, products and integer powers inside a function's arguments or a piecewise
    branch written as ``_print`` writes them at the top: sympy's own printers sort a
    sum's terms and test a product's signs first, which was most of a compile's time
    (a model's probes, printed for the vectorised route, are mostly piecewise)."""

    def _print_Add(self, e, order=None):
        return "(" + " + ".join(map(self._print, e.args)) + ")"

    def _print_Mul(self, e):
        return "(" + "*".join(map(self._print, e.args)) + ")"

    def _print_Pow(self, e, rational=False):
        if e.exp.is_Integer and e.exp >= 0:  # numpy refuses an integer's negative power
            return f"({self._print(e.base)})**({int(e.exp)})"
        return super()._print_Pow(e, rational=rational)

    def _print_Float(self, e):
        return repr(float(e))

    def _print_Symbol(self, e):
        return _renamed(e, self)


def _printers(names: dict | None = None):
    """The scalar, vectorised and kernel printers; the vectorised one renames symbols by
    ``names`` (``_renamed``)."""
    from sympy.printing.numpy import NumPyPrinter
    from sympy.printing.pycode import PythonCodePrinter

    class Scalar(_Direct, PythonCodePrinter):
        guard = "inline"  # an inert term's function, see _term

        def _print_Lookup(self, e):
            return f"T[{int(e.args[0])}]({self._print(e.args[1])})"

        def _print_LookupSlope(self, e):
            return f"TD[{int(e.args[0])}]({self._print(e.args[1])})"

        def _print_Pmod(self, e):
            x, per = (self._print(a) for a in e.args)
            return f"(({x}) % ({per}))"

    class Vector(_Direct, NumPyPrinter):
        def _print_Lookup(self, e):
            return f"TV[{int(e.args[0])}]({self._print(e.args[1])})"

        def _print_LookupSlope(self, e):
            return f"TDV[{int(e.args[0])}]({self._print(e.args[1])})"

        def _print_Pmod(self, e):
            x, per = (self._print(a) for a in e.args)
            return f"numpy.mod({x}, {per})"

        def _print_Piecewise(self, e):
            # nested where(): broadcasts a constant branch against an array one, which
            # numpy.select (the printer's default) refuses
            pieces = list(e.args)
            last = pieces.pop()
            out = self._print(last.expr) if bool(last.cond == True) else "numpy.nan"
            if not bool(last.cond == True):
                pieces.append(last)
            for expr, cond in reversed(pieces):
                out = f"numpy.where({self._print(cond)}, {self._print(expr)}, {out})"
            return out

        def _print_And(self, e):  # numpy's logical_and.reduce fails on an array and a scalar
            return f"functools.reduce(numpy.logical_and, [{', '.join(map(self._print, e.args))}])"

        def _print_Or(self, e):
            return f"functools.reduce(numpy.logical_or, [{', '.join(map(self._print, e.args))}])"

    class Kernel(Scalar):
        guard = "call"  # the kernels' guarded calls (kernel_lib.py)
        calls = True  # a function computed by iteration is kernel_lib's call (knee_u)

    options = {"fully_qualified_modules": True, "standard": "python3"}
    vector = Vector({"fully_qualified_modules": True})
    vector.names = names
    return Scalar(options), vector, Kernel(options)


def _names(dae) -> dict:
    import sympy as sp

    m: dict = {dae.t: sp.Symbol("t")}
    for k, s in enumerate(dae.states):
        m[s] = sp.Symbol(f"y{k}")
        m[dae.yp[k]] = sp.Symbol(f"yp{k}")
    for k, p in enumerate(dae.params):
        m[p] = sp.Symbol(f"p{k}")
    return m


def _block(exprs: list, printer, indent: str, assign: list[str], op: str = "=") -> list[str]:
    """Lines ``assign[k] = <expr k>``, with common subexpressions of the non-polynomial
    expressions (functions, tables, fractional powers) computed once. Polynomials in the
    unknowns and parameters -- nearly every equation of a network -- share too little for
    the search to pay (it was most of the compile time of large circuits)."""

    heavy = [k for k, e in enumerate(exprs) if not _polynomial(e)]
    lines = []
    reduced = list(exprs)
    if heavy:
        subs, red = _cse(tuple(exprs[k] for k in heavy))
        for sym, val in subs:
            lines.append(f"{indent}{sym} = {_print(val, printer)}")
        for k, e in zip(heavy, red, strict=True):
            reduced[k] = e
    for target, e in zip(assign, reduced, strict=True):
        lines.append(f"{indent}{target} {op} {_print(e, printer)}")
    return lines


@functools.lru_cache(maxsize=256)
def _cse(exprs: tuple) -> tuple[list, list]:
    """sympy's common subexpressions of ``exprs``, remembered: the kernels repeat the scalar
    code's residual and Jacobian, and a diagnosis's topologies share most of them."""
    import sympy as sp

    return sp.cse(list(exprs), symbols=sp.numbered_symbols("c"), order="none")


def _polynomial(e) -> bool:
    """Only sums, products and integer powers of symbols and numbers."""
    if e.is_Symbol or e.is_Number:
        return True
    if e.is_Add or e.is_Mul:
        return all(_polynomial(a) for a in e.args)
    if e.is_Pow:
        return e.exp.is_Integer and _polynomial(e.base)
    return False


def _print(e, printer) -> str:
    """Python source of e: sums, products, integer powers, symbols and numbers written
    directly (sympy's printers cost ~0.1-0.2 ms an expression, which dominated code
    generation at a few thousand unknowns); everything else through ``printer``."""
    if e.is_Symbol:
        return _renamed(e, printer)
    if e.is_Integer:
        return str(int(e))
    if e.is_Float:
        return repr(float(e))
    if e.is_Add:
        return "(" + " + ".join(_term(a, printer) for a in e.args) + ")"
    if e.is_Mul:
        return "(" + "*".join(_print(a, printer) for a in e.args) + ")"
    if e.is_Pow and e.exp.is_Integer:
        return f"({_print(e.base, printer)})**({int(e.exp)})"
    return f"({printer.doprint(e)})"


_PARAM = re.compile(r"p\d+")


def _renamed(e, printer) -> str:
    """A symbol's name in the generated code: through the printer's ``names`` when it has
    them (the probes, printed without a substitution of every expression first)."""
    names = getattr(printer, "names", None)
    return (names.get(e, e) if names else e).name


def _term(a, printer) -> str:
    """A term of a sum. A product of parameters and a function (a harmonic's amplitude times
    its sine, a friction level times its tanh) evaluates the function only while the
    parameters' product is not zero: the screen's joint model carries dozens of inert
    patches at their null values, and every batch member paid every one of their
    transcendental calls. The value is the product's but for the sign of a zero and a
    non-finite function value, which an inert term no longer passes on. The scalar code
    (the Python route) and the kernels skip alike, so they stay equal to the bit."""
    form = getattr(printer, "guard", None)
    if form is None or not a.is_Mul:
        return _print(a, printer)
    zeros = [f.name for f in a.args if f.is_Symbol and _PARAM.fullmatch(f.name)]
    skip = [f.func.__name__ in GUARDED and len(f.args) == 1 for f in a.args]
    if not zeros or not any(skip):
        return _print(a, printer)
    z = "*".join(zeros)
    parts = []
    for f, guarded in zip(a.args, skip, strict=True):
        text = _print(f, printer)
        head = f"(math.{f.func.__name__}("
        if guarded and text.startswith(head):
            text = (f"if_{f.func.__name__}({z}, {text[len(head):-1]}" if form == "call" else
                    f"({text} if {z} != 0.0 else 0.0)")
        parts.append(text)
    return "(" + "*".join(parts) + ")"


def _unpack(n: int, prefix: str, src: str, indent: str, used: set[str]) -> list[str]:
    names = [f"{prefix}{k}" if f"{prefix}{k}" in used else "_" for k in range(n)]
    if n == 0 or all(nm == "_" for nm in names):
        return []
    if n == 1:
        return [f"{indent}{names[0]}, = {src}"]
    return [f"{indent}{', '.join(names)} = {src}"]


def _derivatives(F: list, Y: list, YP: list, t) -> tuple[dict, dict, list]:
    """dF/dy and dF/dy' at their structural nonzeros only (each equation is differentiated
    by the few unknowns it names, never by all n), and dF/dt."""
    import sympy as sp

    ypos = {s: j for j, s in enumerate(Y)}
    yppos = {s: j for j, s in enumerate(YP)}
    fy: dict[tuple[int, int], Any] = {}
    fyp: dict[tuple[int, int], Any] = {}
    for i, f in enumerate(F):
        for s in sorted(f.free_symbols, key=lambda s: s.name):
            target, j = (fy, ypos[s]) if s in ypos else (fyp, yppos.get(s))
            if j is None:
                continue
            # only the terms that name s (a network equation is a short sum of products)
            terms = f.args if f.is_Add else (f,)
            d = sp.Add(*[_term_diff(a, s) for a in terms if s in a.free_symbols])
            if d != 0:
                target[(i, j)] = d
    return fy, fyp, [sp.diff(f, t) for f in F]


@functools.lru_cache(maxsize=1 << 15)
def _term_diff(a, s):
    """d a / d s, directly for s and c*s with c free of s (most terms of a network).
    Remembered: a diagnosis compiles dozens of topologies that share most of their terms (the
    same patches on the same circuit), and sympy's ``diff`` of a function's term -- a
    friction's tanh, a harmonic's sine, a piecewise law -- was a third of a compile."""
    import sympy as sp

    if a == s:
        return sp.Integer(1)
    if a.is_Mul and a.args.count(s) == 1:
        rest = [f for f in a.args if f != s]
        if not any(s in f.free_symbols for f in rest):
            return sp.Mul(*rest)
    return sp.diff(a, s)


def _linear_term(a, ypos: dict, yppos: dict):
    """(0 for y / 1 for y', column, coefficient) if a = coefficient * one unknown or
    derivative, the coefficient free of every unknown, derivative and t; else None."""
    import sympy as sp

    factors = a.args if a.is_Mul else (a,)
    hits = [f for f in factors if f in ypos or f in yppos]
    if len(hits) != 1:
        return None
    s = hits[0]
    rest = [f for f in factors if f is not s]
    if any(q.name == "t" or q in ypos or q in yppos
           for f in rest for q in f.free_symbols):
        return None
    return (0, ypos[s]) if s in ypos else (1, yppos[s]), sp.Mul(*rest)


def _linear_functions(F: list, Y: list, YP: list, n: int, n_par: int, scalar):
    """F = Ly(p) y + Lyp(p) y' + rest(t, y, y', p): the coefficient matrices' values as a
    function of the parameters alone (``linear``) and the remaining terms (``rest``), which
    for a network are a few sources and nonlinear parts. The model evaluates the linear part
    as a sparse matrix product, so the per-call cost of a large network is not n lines of
    Python (the full ``residual`` stays, with the same values, for small models)."""
    import sympy as sp

    ypos = {s: j for j, s in enumerate(Y)}
    yppos = {s: j for j, s in enumerate(YP)}
    coef: list[dict] = [{}, {}]
    rest_rows, rest_exprs = [], []
    for i, f in enumerate(F):
        other = []
        for a in f.args if f.is_Add else (f,):
            hit = _linear_term(a, ypos, yppos)
            if hit is None:
                other.append(a)
            else:
                (kind, j), c = hit
                coef[kind][(i, j)] = coef[kind].get((i, j), 0) + c
        if other:
            rest_rows.append(i)
            rest_exprs.append(sp.Add(*other))
    ly, lyp = coef
    src = _body("linear", "p", [*ly.values(), *lyp.values()],
                [f"Ly[{k}]" for k in range(len(ly))] + [f"Lyp[{k}]" for k in range(len(lyp))],
                n, n_par, scalar, pre=[f"        Ly = numpy.zeros({len(ly)})",
                                       f"        Lyp = numpy.zeros({len(lyp)})"],
                post=["        return Ly, Lyp"], fail="Ly[:] = Lyp[:] = math.nan")
    src += _body("rest", "t, y, yp, res, p", rest_exprs, [f"res[{i}]" for i in rest_rows],
                 n, n_par, scalar, fail="res[:] = math.nan", add=True)
    meta = {"ly_pattern": [[i for i, _ in ly], [j for _, j in ly]],
            "lyp_pattern": [[i for i, _ in lyp], [j for _, j in lyp]]}
    return src, meta, (rest_rows, rest_exprs)


def _pattern(fy: dict, fyp: dict) -> list[tuple[int, int]]:
    """The Jacobian's nonzeros (i, j) in compressed-sparse-column order (the order IDA's
    sparse solver stores them in)."""
    return sorted(set(fy) | set(fyp), key=lambda ij: (ij[1], ij[0]))


def _outputs(dae, ren: dict) -> tuple[list[str], list]:
    from circuitsim.component import as_expr

    names_out = list(dae.probes) + sorted(dae.exports)
    # not substituted: the printer renames (``_renamed``); xreplace rebuilt every piecewise
    # probe, a third of a small model's generate
    obs = [as_expr(dae.probes[k] if k in dae.probes else dae.exports[k]) for k in names_out]
    return names_out, obs


def _initial(dae, ren: dict) -> tuple[list, list, list]:
    from circuitsim.component import as_expr

    init_syms = list(dae.initial)
    init_vals = [as_expr(dae.initial[s]).xreplace(ren) for s in init_syms]
    # a key may be an expression (a capacitor's v = p.v - n.v): resolve eliminated symbols
    init_exprs = [as_expr(s).xreplace(dict(dae.solved)).xreplace(ren) for s in init_syms]
    return init_syms, init_vals, init_exprs


def _body(name: str, args: str, exprs: list, targets: list[str], n: int, n_params: int,
          printer, pre: list[str] = (), post: list[str] = (), vec: bool = False,
          fail: str = "", cse: bool = True, add: bool = False) -> list[str]:
    """One generated function: unpack the arguments it uses, evaluate, store."""
    from circuitsim.component import as_expr

    used = {str(s) for e in exprs for s in as_expr(e).free_symbols}
    lines = [f"    def {name}({args}):"]
    if vec:
        lines += [f"        y{k} = Y[{k}]" for k in range(n) if f"y{k}" in used]
        lines += [f"        yp{k} = YP[{k}]" for k in range(n) if f"yp{k}" in used]
    else:
        lines += _unpack(n, "y", "y.tolist()", "        ", used)
        lines += _unpack(n, "yp", "yp.tolist()", "        ", used)
    lines += _unpack(n_params, "p", "p", "        ", used)
    lines += list(pre)
    block = _block if cse else _plain
    op = "+=" if add else "="  # accumulate into the targets, or set them
    if fail:
        # Scalar code runs on Python floats, which raise where numpy would give inf or
        # nan (x**n/x at x = 0, log(0), sqrt(-1)): the solver gets NaN instead -- a failed
        # step it can retry smaller, or a clear "not finite" error -- never a traceback
        lines += ["        try:"]
        lines += block(exprs, printer, "            ", targets, op) or ["            pass"]
        lines += ["        except (ArithmeticError, ValueError, TypeError):", f"            {fail}"]
    else:
        lines += block(exprs, printer, "        ", targets, op)
    lines += list(post) or ["        return None"]
    return lines


def _plain(exprs: list, printer, indent: str, assign: list[str], op: str = "=") -> list[str]:
    """Lines ``assign[k] = <expr k>`` without common-subexpression search (for many small,
    independent outputs, where the search costs more than it saves)."""
    return [f"{indent}{target} {op} {_print(e, printer)}"
            for target, e in zip(assign, exprs, strict=True)]


_HEADER = ["# Generated by circuitsim.codegen: do not edit. One module per topology.",
           "import functools", "import math", "import numpy", "", "",
           "def _real(v):",
           "    # a constant folded by Python (a negative number to a fractional power) is",
           "    # complex where numpy would give nan",
           "    if isinstance(v, complex) or numpy.iscomplexobj(v):",
           "        a = numpy.asarray(v)",
           "        return numpy.where(a.imag == 0, a.real, numpy.nan)",
           "    return v", "", ""]


_OBSERVE = [
    "    codes = {}",
    "",
    "    def observe(t, Y, YP, p, which=None):",
    "        env = _Names(Y, YP, p)",
    "        env.update(t=t, TV=TV, TDV=TDV)",
    "        out = []",
    "        for k in range(len(OBSERVED)) if which is None else which:",
    "            if k not in codes:",
    "                codes[k] = compile(OBSERVED[k], f'<observed {k}>', 'eval')",
    "            out.append(_real(eval(codes[k], globals(), env)))",
    "        return out",
    "",
]

_NAMES = [
    "class _Names(dict):",
    "    # y12 -> Y[12], yp3 -> YP[3], p5 -> p[5], looked up when an expression needs them",
    "    def __init__(self, Y, YP, p):",
    "        super().__init__()",
    "        self.src = {'yp': YP, 'y': Y, 'p': p}",
    "",
    "    def __missing__(self, name):",
    "        for prefix in ('yp', 'y', 'p'):",
    "            if name.startswith(prefix) and name[len(prefix):].isdigit():",
    "                v = self[name] = self.src[prefix][int(name[len(prefix):])]",
    "                return v",
    "        raise KeyError(name)",
    "",
    "",
]


_KERNEL_HEADER = f'''# numba kernels of a topology's equations (every topology of the same code shares
# them), generated by circuitsim.codegen: do not edit.
# IDA calls them directly (circuitsim.solve.direct); nothing here runs Python per step. The
# functions named in CFUNCS are compiled as cfuncs of their signature when a solve first asks
# for them (a topology run singly never compiles its batch kernels).
import math

import numpy
from numba import carray, njit

from {KERNEL_LIB} import (JAC, RES, ROOT, as_pointer, band_data, band_ldim, band_smu,  # noqa: F401
                           data_of, if_atan, if_cos, if_cosh, if_exp, if_sin, if_sinh, if_tanh,
                           knee_u, libm_pow, sparse_data, sparse_ptrs, sparse_rows, tab,
                           tab_slope)

CFUNCS = {{}}
'''


def _kernels(F: list, jac_exprs: list, pattern: list, n: int, n_par: int, scalar,
             guards: tuple[list, list, list[int]] | None = None) -> str | None:
    """Source of numba ``cfunc`` kernels for IDA to call directly: the residual and the dense
    Jacobian (column-major) of one member, and of K members stacked (``ud`` = K, then each
    member's parameters) with the Jacobian in SUNDIALS' band storage, as ``solve/batch.py``
    integrates them; with ``guards`` (a switching model's, ``_guard_parts``) also IDA's root
    function ``roots``. A model reading run-time tables gets the same, the tables' points in
    the user data after the parameters (``TABLES``; ``_batch_with_tables``; solve/direct.py)."""
    src = [_KERNEL_HEADER.rstrip()]
    shared = _shared_kernels(F, jac_exprs, pattern, n, n_par, scalar)
    vec = "carray(data_of({}), {}, dtype=numpy.float64)"
    one = [f"    y = {vec.format('yy', n)}", f"    d = {vec.format('ypv', n)}",
           f"    p = carray(ud, {max(n_par, 1)}, dtype=numpy.float64)"]
    if not any("T[" in line or "TD[" in line for line in shared):
        roots = _roots(guards, n, n_par, scalar, one) if guards else []
        if any("T[" in line or "TD[" in line for line in roots):
            roots = []  # a guard reading a table: the switching stays on the Python route
        return "\n".join([*src, *shared, *roots]) + "\n"
    h = max(n_par, 1) + 1  # the tables' header: ud[h - 1] = the user data's length, ...
    pre = [*one, (f"    u = carray(ud, int(carray(ud, {h}, dtype=numpy.float64)[{h - 1}]), "
                  "dtype=numpy.float64)")]
    single = _kernel("residual", "RES", "t, yy, ypv, rr, ud", F, [f"r[{i}]" for i in range(n)],
                     [*pre, f"    r = {vec.format('rr', n)}"], n, n_par, scalar)
    single += _kernel("jacobian", "JAC", "t, cj, yy, ypv, rr, J, ud, t1, t2, t3", jac_exprs,
                      [f"a[{i + j * n}]" for i, j in pattern],
                      [*pre, f"    a = {vec.format('J', n * n)}"], n, n_par, scalar)
    single += _roots(guards, n, n_par, scalar, pre) if guards else []
    single = [_table_calls(line, h) for line in single]
    single += _batch_with_tables(F, jac_exprs, pattern, n, n_par, scalar)
    return "\n".join([*src, *single, "", "", "TABLES = True"]) + "\n"


def _shared_kernels(F: list, jac_exprs: list, pattern: list, n: int, n_par: int, scalar
                    ) -> list[str]:
    """The kernels of a model without tables: the residual and the Jacobian once each, as
    njit bodies of one member at offsets into the states (``o``) and parameters (``q``), the
    Jacobian entry (i, j) at ``a[base + i + j sj]`` (dense column-major: base 0, sj = n; a
    band member: base = o ldim + smu, sj = ldim - 1); and four thin cfuncs calling them, for
    one model and for K members stacked. numba's compile time is mostly per body, so a
    topology run both singly and in batches compiles each body once."""
    vec = "carray(data_of({}), {}, dtype=numpy.float64)"
    one = [f"    y, d = {vec.format('yy', n)}, {vec.format('ypv', n)}",
           f"    p = carray(ud, {max(n_par, 1)}, dtype=numpy.float64)"]
    zero = "numpy.int64(0)"  # one type for the bodies' offsets, single and batched alike
    src = _member_bodies("_residual_at", "_jacobian_at", "", F, jac_exprs, pattern, n, n_par,
                         scalar)
    src += _wrapper("residual", "RES", "t, yy, ypv, rr, ud",
                    [*one, f"    r = {vec.format('rr', n)}",
                     f"    _residual_at(t, y, d, p, r, {zero}, {zero})"])
    src += _wrapper("jacobian", "JAC", "t, cj, yy, ypv, rr, J, ud, t1, t2, t3",
                    [*one, f"    a = {vec.format('J', n * n)}",
                     (f"    _jacobian_at(t, cj, y, d, p, a, {zero}, numpy.int64({n}), {zero}, "
                     f"{zero})")])
    return src + _stacked_wrappers("_residual_at", "_jacobian_at", "", [], n, n_par)


def _batch_with_tables(F: list, jac_exprs: list, pattern: list, n: int, n_par: int, scalar
                       ) -> list[str]:
    """The stacked kernels of K members of a model reading run-time tables: the member
    bodies of ``_shared_kernels`` with the tables' points as arguments. The user data is K,
    each member's parameters, then the tables as a single model's kernels read them after
    its parameters (``hb - 1``: the data's length; from ``hb``, each table's start and
    number of points; then the points), so that ``tab`` reads them alike."""
    tables = [f"    hb = 2 + K * {n_par}",
              ("    u = carray(ud, int(carray(ud, hb, dtype=numpy.float64)[hb - 1]), "
               "dtype=numpy.float64)")]
    src = _member_bodies("_residual_tab", "_jacobian_tab", ", u, hb", F, jac_exprs, pattern, n,
                         n_par, scalar)
    src = [_table_calls(line, "hb") for line in src]
    return src + _stacked_wrappers("_residual_tab", "_jacobian_tab", ", u, hb", tables, n,
                                   n_par)


def _member_bodies(res: str, jac: str, extra: str, F: list, jac_exprs: list, pattern: list,
                   n: int, n_par: int, scalar) -> list[str]:
    """The residual and Jacobian bodies of one member (arguments ``extra`` after the
    offsets), the Jacobian entry (i, j) at ``a[base + i + j sj]``."""
    src = _member_body(res, f"t, y, d, p, r, o, q{extra}", F,
                       [f"r[o + {i}]" for i in range(n)], n, n_par, scalar)
    return src + _member_body(jac, f"t, cj, y, d, p, a, base, sj, o, q{extra}", jac_exprs,
                              [f"a[base + {i} + {j} * sj]" if j else f"a[base + {i}]"
                               for i, j in pattern], n, n_par, scalar)


def _stacked_wrappers(res: str, jac: str, extra: str, pre: list[str], n: int, n_par: int
                      ) -> list[str]:
    """``residual_batch`` and ``jacobian_band``: K members (``ud`` = K, then each member's
    parameters; ``pre`` reads what follows them) calling the member bodies in turn."""
    vec = "carray(data_of({}), {}, dtype=numpy.float64)"
    many = ["    K = int(carray(ud, 1, dtype=numpy.float64)[0])",
            f"    y, d = {vec.format('yy', f'K * {n}')}, {vec.format('ypv', f'K * {n}')}",
            f"    p = carray(ud, 1 + K * {n_par}, dtype=numpy.float64)", *pre]
    member = f"    for k in range(K):\n        o, q = k * {n}, 1 + k * {n_par}"
    src = _wrapper("residual_batch", "RES", "t, yy, ypv, rr, ud",
                   [*many, f"    r = {vec.format('rr', f'K * {n}')}", member,
                    f"        {res}(t, y, d, p, r, o, q{extra})"])
    return src + _wrapper("jacobian_band", "JAC", "t, cj, yy, ypv, rr, J, ud, t1, t2, t3",
                          [*many, "    ldim, smu = band_ldim(J), band_smu(J)",
                           f"    a = carray(band_data(J), ldim * K * {n}, dtype=numpy.float64)",
                           member, (f"        {jac}(t, cj, y, d, p, a, o * ldim + smu, "
                                    f"numpy.int64(ldim - 1), o, q{extra})")])


def _guard_parts(dae, ren: dict) -> tuple[list, list, list[int]] | None:
    """A switching model's guards for the kernels' root function: the components' event
    guards, the held relations' distances and band scales (each list in the order and with
    the expressions of the Python route's ``guards`` and ``crossings``, so that the common
    subexpressions, and so the roundings, are the same), and each relation's mode index in
    the parameters. None without switching."""
    from circuitsim.component import as_expr

    events, crossings = getattr(dae, "events", ()), getattr(dae, "crossings", ())
    if not events and not crossings:
        return None
    where = {s: k for k, s in enumerate(dae.params)}
    return ([as_expr(e.guard).xreplace(ren) for e in events], _held(crossings, ren),
            [where[c.mode] for c in crossings])


def _held(crossings, ren: dict) -> list:
    """The held relations' distances (positive where each holds), then their band scales."""
    return [c.distance.xreplace(ren) for c in crossings] + \
           [c.scale.xreplace(ren) for c in crossings]


def _roots(guards: tuple[list, list, list[int]], n: int, n_par: int, scalar, pre: list[str]
           ) -> list[str]:
    """IDA's root function as a cfunc (``ROOT``): the event guards, then per held relation
    its distance, signed for the mode it holds (a parameter), plus its hysteresis band --
    the arithmetic of ``solve/events.py``'s ``Switching.guards``, to the bit. ``pre`` reads
    the states, derivatives and parameters (and the tables' points) as the residual does."""
    events, held, modes = guards
    k, n_ev = len(modes), len(events)
    lines = [*pre, f"    g = carray(gout, {n_ev + k}, dtype=numpy.float64)"]
    if events:
        lines += _assignments(events, [f"g[{j}]" for j in range(n_ev)], n, n_par, scalar)
    if held:
        lines += _assignments(held, [f"h_{j}" for j in range(2 * k)], n, n_par, scalar)
        lines += [f"    g[{n_ev + j}] = (h_{j} if p[{m}] > 0.5 else -h_{j}) + "
                  f"{BAND_REL!r} * h_{k + j} + {BAND_ABS!r}" for j, m in enumerate(modes)]
    return [*_wrapper("roots", "ROOT", "t, yy, ypv, gout, ud", lines),
            f"N_ROOTS = {n_ev + k}"]


def _member_body(name: str, args: str, exprs: list, targets: list[str], n: int, n_par: int,
                 scalar) -> list[str]:
    """An njit body of one member (states from offset ``o``, parameters from ``q``)."""
    return ["", "", '@njit(cache=True, error_model="numpy")', f"def {name}({args}):",
            *_assignments(exprs, targets, n, n_par, scalar, "o + ", "q + "), "    return 0"]


def _assignments(exprs: list, targets: list[str], n: int, n_par: int, scalar, o: str = "",
                 q: str = "") -> list[str]:
    """A kernel's statements: the states, derivatives and parameters the expressions use,
    read at offsets ``o`` and ``q`` (a batch member's), then the assignments to ``targets``."""
    from circuitsim.component import as_expr

    used = {str(s) for e in exprs for s in as_expr(e).free_symbols}
    body = [f"    y{k} = y[{o}{k}]" for k in range(n) if f"y{k}" in used]
    body += [f"    yp{k} = d[{o}{k}]" for k in range(n) if f"yp{k}" in used]
    body += [f"    p{k} = p[{q}{k}]" for k in range(n_par) if f"p{k}" in used]
    return body + [_libm_powers(line) for line in _block(exprs, scalar, "    ", targets)]


def _wrapper(name: str, sig: str, args: str, lines: list[str]) -> list[str]:
    """A kernel IDA calls (a cfunc of ``sig`` once compiled: ``CFUNCS``)."""
    return ["", "", f"def {name}({args}):", *lines, "    return 0", "",
            f"CFUNCS[{name!r}] = {sig!r}"]


_TABLE_CALL = re.compile(r"\b(TD?)\[(\d+)\]\(")


def _table_calls(line: str, h: int) -> str:
    """``T[i](x)`` and ``TD[i](x)`` (the Python route's table callables) as the kernels'
    ``tab(u, h, i, x)`` and ``tab_slope(u, h, i, x)`` on the points in the user data."""
    return _TABLE_CALL.sub(lambda m: f"{'tab' if m.group(1) == 'T' else 'tab_slope'}"
                                     f"(u, {h}, {m.group(2)}, ", line)


class _PowCalls(ast.NodeTransformer):
    """``a ** b`` as ``libm_pow(a, b)`` with float operands (see ``_libm_powers``)."""

    def visit_BinOp(self, node: ast.BinOp) -> ast.AST:
        self.generic_visit(node)
        if not isinstance(node.op, ast.Pow):
            return node
        return ast.Call(ast.Name("libm_pow", ast.Load()),
                        [_as_float(node.left), _as_float(node.right)], [])


def _as_float(node: ast.AST) -> ast.AST:
    """A number written in the source (3, -3) as a float literal; anything else as it is."""
    sign = 1.0
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        sign, inner = -1.0, node.operand
    else:
        inner = node
    if isinstance(inner, ast.Constant) and isinstance(inner.value, int | float):
        return ast.Constant(sign * float(inner.value))
    return node


def _libm_powers(line: str) -> str:
    """A kernel line with every power through C's ``pow``: Python's float ``**`` calls it,
    numba would multiply repeatedly for an integer exponent and LLVM would rewrite
    ``pow(x, 2.0)`` and ``pow(x, -1.0)``, each rounding otherwise; so the kernels give the
    Python route's numbers to the bit."""
    if "**" not in line:
        return line
    indent = line[:len(line) - len(line.lstrip())]
    limit = sys.getrecursionlimit()
    # the walk recurses once per operator of a chain: a sum of thousands of terms (a large
    # network's equation, a model with many harmonic terms) is that deep
    sys.setrecursionlimit(max(limit, 40 * line.count(" ") + 1000))
    try:
        tree = ast.fix_missing_locations(_PowCalls().visit(ast.parse(line.strip())))
        return indent + ast.unparse(tree)
    finally:
        sys.setrecursionlimit(limit)


def _large_kernels(rest: tuple[list[int], list], lin_meta: dict, jac_exprs: list,
                   pattern: list, n: int, n_par: int, scalar) -> str | None:
    """Kernels of a model of ``MATRIX_RESIDUAL_FROM`` unknowns or more, with the Python
    route's arithmetic: the residual as Ly y + Lyp y' (scipy's CSR product, row by row in
    the same order) plus the remaining terms, the Jacobian entry by entry into the matrix the
    model's linear solver takes (dense below ``SPARSE_FROM`` unknowns, else SuperLU_MT's
    compressed columns, whose indices IDA zeroes before every call). The user data: the
    parameters (at least one entry), then Ly's and Lyp's CSR arrays (index pointers, column
    indices, values) as float64, built from ``linear(p)`` in solve/direct.py."""
    n_p = max(n_par, 1)
    ny, nyp = len(lin_meta["ly_pattern"][0]), len(lin_meta["lyp_pattern"][0])
    a_y, a_yp = n_p, n_p + n + 1 + 2 * ny  # where Ly's and Lyp's arrays start in ud
    size = a_yp + n + 1 + 2 * nyp
    vec = "carray(data_of({}), {}, dtype=numpy.float64)"
    pre = [f"    y = {vec.format('yy', n)}", f"    d = {vec.format('ypv', n)}",
           f"    p = carray(ud, {n_p}, dtype=numpy.float64)"]
    matvec = [f"    u = carray(ud, {size}, dtype=numpy.float64)", f"    for i in range({n}):"]
    for acc, at, nnz, x in (("s", a_y, ny, "y"), ("s2", a_yp, nyp, "d")):
        matvec += [f"        {acc} = 0.0",
                   f"        for k in range(int(u[{at} + i]), int(u[{at + 1} + i])):",
                   f"            {acc} += u[{at + n + 1 + nnz} + k] * {x}[int(u[{at + n + 1} + k])]"]
    matvec += ["        r[i] = s + s2"]
    src = [_KERNEL_HEADER.rstrip(), "", "", f"LINEAR = ({n_p}, {ny}, {nyp})"]
    rows, exprs = rest
    src += _chunked("residual", "RES", "t, yy, ypv, rr, ud", exprs, [f"r[{i}]" for i in rows],
                    [*pre, f"    r = {vec.format('rr', n)}", *matvec], "0.0, y, d, p, r",
                    n, n_par, scalar, op="+=")
    args = "t, cj, yy, ypv, rr, J, ud, t1, t2, t3"
    if n < SPARSE_FROM:
        src += _chunked("jacobian", "JAC", args, jac_exprs,
                        [f"a[{i + j * n}]" for i, j in pattern],
                        [*pre, f"    a = {vec.format('J', n * n)}"], "cj, y, d, p, a", n, n_par,
                        scalar)
    else:
        ptrs = [0] * (n + 1)  # column pointers of the compressed-column pattern
        for _, j in pattern:
            ptrs[j + 1] += 1
        for j in range(n):
            ptrs[j + 1] += ptrs[j]
        src += ["", "", f"JAC_ROWS = numpy.array({[i for i, _ in pattern]}, dtype=numpy.int32)",
                f"JAC_PTRS = numpy.array({ptrs}, dtype=numpy.int32)"]
        nnz = len(pattern)
        src += _chunked("jacobian_sparse", "JAC", args, jac_exprs,
                        [f"a[{k}]" for k in range(nnz)],
                        [*pre, f"    a = carray(sparse_data(J), {nnz}, dtype=numpy.float64)",
                         f"    carray(sparse_rows(J), {nnz}, dtype=numpy.int32)[:] = JAC_ROWS",
                         f"    carray(sparse_ptrs(J), {n + 1}, dtype=numpy.int32)[:] = JAC_PTRS"],
                        "cj, y, d, p, a", n, n_par, scalar)
    text = "\n".join(src) + "\n"
    return None if ("T[" in text or "TD[" in text) else text


CHUNK = 64  # statements per compiled part of a large kernel
_CSE_NAME = re.compile(r"\bc(\d+)\b")


def _chunked(name: str, sig: str, args: str, exprs: list, targets: list[str], pre: list[str],
             call: str, n: int, n_par: int, scalar, op: str = "=") -> list[str]:
    """A large kernel as a cfunc calling parts of ``CHUNK`` statements each: numba's compile
    time grows as the cube of a function's length (12 s for 500 statements, 81 s for 1000)
    and linearly over parts (11 ms a statement). The common subexpressions travel between
    the parts in an array ``cs``; ``call``: what the parts take after ``t`` (``cj``, the
    states, derivatives, parameters and the array the targets name)."""
    lines = [_libm_powers(line) for line in _block(exprs, scalar, "    ", targets, op)]
    n_cse = sum(1 for line in lines if re.match(r"    c\d+ = ", line))
    lines = [_CSE_NAME.sub(r"cs[\1]", line) for line in lines]
    source = {"yp": "d", "y": "y", "p": "p"}
    out: list[str] = []
    calls = []
    for start in range(0, len(lines), CHUNK):
        part = lines[start:start + CHUNK]
        used = sorted(set(re.findall(r"\b(yp|y|p)(\d+)\b", "\n".join(part))))
        part_name = f"_{name}_{start // CHUNK}"
        out += ["", "", '@njit(cache=True, error_model="numpy")',
                f"def {part_name}(t, {call.replace('0.0', 'cj')}, cs):",
                *[f"    {kind}{k} = {source[kind]}[{k}]" for kind, k in used], *part,
                "    return 0"]
        calls.append(f"    {part_name}(t, {call}, cs)")
    return [*out, "", "", f"def {name}({args}):", *pre,
            f"    cs = numpy.empty({max(n_cse, 1)})", *calls, "    return 0", "",
            f"CFUNCS[{name!r}] = {sig!r}"]


def _kernel(name: str, sig: str, args: str, exprs: list, targets: list[str], pre: list[str],
            n: int, n_par: int, scalar) -> list[str]:
    """One cfunc of one member: the arrays, the names the expressions use, the assignments."""
    return _wrapper(name, sig, args, [*pre, *_assignments(exprs, targets, n, n_par, scalar)])


def generate(dae) -> tuple[str, dict[str, Any]]:
    """Source of the generated module and its metadata (JSON-serialisable).

    The module's ``jac`` fills a flat array with the Jacobian dF/dy + cj dF/dy' at the
    nonzeros of ``meta["jac_pattern"]`` (compressed-sparse-column order); ``parts`` returns
    the flat values of dF/dy and dF/dy' (patterns ``fy_pattern``, ``fyp_pattern``) and dF/dt.
    """
    import sympy as sp

    from circuitsim.component import as_expr

    ren = _names(dae)
    scalar, vector, kernel = _printers(ren)
    n, n_par = len(dae.states), len(dae.params)
    F = [as_expr(e).xreplace(ren) for e in dae.equations]
    t, cj = sp.Symbol("t"), sp.Symbol("cj")
    fy, fyp, Ft = _derivatives(F, [ren[s] for s in dae.states], [ren[s] for s in dae.yp], t)
    pattern = _pattern(fy, fyp)
    jac_exprs = [fy.get(ij, 0) + cj * fyp.get(ij, 0) for ij in pattern]
    names_out, obs = _outputs(dae, ren)
    init_syms, init_vals, init_exprs = _initial(dae, ren)
    n_init = len(init_vals)
    src = [*_HEADER, *_NAMES, "def make(T, TD, TV, TDV):"]
    src += _body("residual", "t, y, yp, res, p", F, [f"res[{i}]" for i in range(n)], n, n_par,
                 scalar, fail="res[:] = math.nan")
    src += _body("jac", "t, y, yp, res, cj, JJ, p", jac_exprs,
                 [f"JJ[{k}]" for k in range(len(pattern))], n, n_par, scalar,
                 fail="JJ[:] = math.nan")
    src += _body("parts", "t, y, yp, p", [*fy.values(), *fyp.values(), *Ft],
                 [f"Fy[{k}]" for k in range(len(fy))] + [f"Fyp[{k}]" for k in range(len(fyp))]
                 + [f"Ft[{i}]" for i in range(n)], n, n_par, scalar,
                 pre=[f"        Fy = numpy.zeros({len(fy)})",
                      f"        Fyp = numpy.zeros({len(fyp)})", f"        Ft = numpy.zeros({n})"],
                 post=["        return Fy, Fyp, Ft"],
                 fail="Fy[:] = Fyp[:] = Ft[:] = math.nan")
    src += _OBSERVE
    src += _body("initial", "t, y, yp, p", init_vals + init_exprs,
                 [f"out[{k}]" for k in range(2 * n_init)], n, n_par, scalar,
                 pre=[f"        out = [0.0] * {2 * n_init}"], post=["        return out"],
                 fail=f"out = [math.nan] * {2 * n_init}")
    lin_src, lin_meta, rest = _linear_functions(F, [ren[s] for s in dae.states],
                                                [ren[s] for s in dae.yp], n, n_par, scalar)
    src += [*lin_src, "    return residual, jac, parts, observe, initial, linear, rest", ""]
    # every probe and exported quantity as the source of one vectorised expression, compiled
    # only when asked for: a circuit of thousands of parts exports tens of thousands of
    # quantities, and evaluating them all at every output point would cost gigabytes
    src += ["OBSERVED = ["] + [f"    {_print(e, vector)!r}," for e in obs] + ["]", ""]
    meta = _meta(dae, names_out, init_syms)
    for part in (_events, _crossings):  # separate factories: no cost without switching
        part_src, part_meta = part(dae, ren, n, n_par, scalar)
        src, meta = [*src, *part_src], {**meta, **part_meta}
    meta.update({"jac_nnz": len(pattern), "jac_pattern": [[i for i, _ in pattern],
                                                          [j for _, j in pattern]],
                 "fy_pattern": [[i for i, _ in fy], [j for _, j in fy]],
                 "fyp_pattern": [[i for i, _ in fyp], [j for _, j in fyp]], **lin_meta})
    # the kernels repeat the Python route's arithmetic (the sparse product from 100 unknowns)
    meta["kernels"] = (_kernels(F, jac_exprs, pattern, n, n_par, kernel, _guard_parts(dae, ren))
                       if n < MATRIX_RESIDUAL_FROM else
                       _large_kernels(rest, lin_meta, jac_exprs, pattern, n, n_par, kernel))
    return "\n".join(src), meta


def _events(dae, ren: dict, n: int, n_par: int, scalar) -> tuple[list[str], dict[str, Any]]:
    """``make_events(T, TD)`` -> (guards, jumps): ``guards(t, y, yp, g, p)`` fills every
    switching guard (the root functions IDA watches), ``jumps(t, y, yp, p)`` returns the new
    values of the discrete states, event after event (``meta["events"]`` says which states
    each one sets). A separate factory, so a model without events costs nothing."""
    from circuitsim.component import as_expr

    events = getattr(dae, "events", ())
    if not events:
        return [], {"events": []}
    index = {s: k for k, s in enumerate(dae.states)}
    guards = [as_expr(e.guard).xreplace(ren) for e in events]
    values, info = [], []
    for e in events:
        info.append({"owner": e.owner, "start": len(values),
                     "targets": [index[s] for s, _ in e.sets]})
        values += [as_expr(v).xreplace(ren) for _, v in e.sets]
    src = ["def make_events(T, TD):"]
    src += _body("guards", "t, y, yp, g, p", guards, [f"g[{k}]" for k in range(len(guards))],
                 n, n_par, scalar, fail="g[:] = math.nan")
    src += _body("jumps", "t, y, yp, p", values, [f"out[{k}]" for k in range(len(values))],
                 n, n_par, scalar, pre=[f"        out = [0.0] * {len(values)}"],
                 post=["        return out"], fail=f"out = [math.nan] * {len(values)}")
    src += ["    return guards, jumps", ""]
    return src, {"events": info}


def _crossings(dae, ren: dict, n: int, n_par: int, scalar
               ) -> tuple[list[str], dict[str, Any]]:
    """``make_crossings(T, TD)`` -> ``crossings(t, y, yp, p)``: the distance of every held
    relation (positive where it holds), then the scale of its hysteresis band
    (``meta["crossings"]``: its owner and the index of its mode in ``p``)."""
    crossings = getattr(dae, "crossings", ())
    if not crossings:
        return [], {"crossings": []}
    where = {s: k for k, s in enumerate(dae.params)}
    out = _held(crossings, ren)
    src = ["def make_crossings(T, TD):"]
    src += _body("crossings", "t, y, yp, p", out, [f"out[{k}]" for k in range(len(out))],
                 n, n_par, scalar, pre=[f"        out = numpy.zeros({len(out)})"],
                 post=["        return out"], fail="out[:] = math.nan")
    src += ["    return crossings", ""]
    return src, {"crossings": [{"owner": c.owner, "mode": where[c.mode], "name": c.mode.name}
                               for c in crossings]}


def _meta(dae, names_out: list[str], init_syms: list) -> dict[str, Any]:
    from circuitsim.component import as_expr

    state_index = {s: k for k, s in enumerate(dae.states)}
    return {
        "states": [s.name for s in dae.states],
        "n_diff": dae.n_diff,
        "params": [p.name for p in dae.params],
        "observed": names_out,
        "n_probes": len(dae.probes),
        "initial": [[str(s), state_index.get(s, -1),
                     sorted(q.name for q in as_expr(dae.initial[s]).free_symbols)]
                    for s in init_syms],
        "units": dict(dae.units),
        "breaks": [[b.kind, [[f, p.name] for f, p in b.fields]] for b in dae.breaks],
        "n_tables": len(dae.tables),
        "report": list(dae.report),
        "n_equations": len(dae.states),
        "integrals": {s.name: dae.integrals[s.name] for s in dae.states
                      if s.name in dae.integrals},
        "differentiated_params": list(dae.differentiated_params),
    }
