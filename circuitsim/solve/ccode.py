"""The kernels compiled by the system's C compiler instead of numba: the same numbers, to the
bit, for a fraction of the compile.

numba compiles a topology's kernels (``compiler/codegen.py``) in about two seconds, nearly all
of it type inference in Python (about a millisecond a statement; a diagnosis compiles some
thirty topologies: on a slow two-core machine a 50 kHz record's diagnosis spent 60 of its 105 s
there). The kernels are straight-line arithmetic on float64 in a small subset of Python, so
this module translates that subset to C99 -- statement by statement, with the same operations
in the same order, C's libm for numba's (numba calls the same library functions), no
contraction to fused multiply-adds and no fast-math -- and compiles it with ``cc -O2`` into a
shared library beside the numba module in the cache folder, named by the digest of its text
and of the compiler's command. IDA gets the library's functions by address, exactly as it gets
numba's cfuncs. Any construct outside the subset, or a compile that fails, leaves the module
to numba, as before; ``CIRCUITSIM_CC`` names the compiler (``off``: numba only).

The subset: assignments of names and of array elements (``=``, ``+=``), ``for`` over
``range``, ``if``, ``return``, arithmetic (``/`` is Python's true division), comparisons,
conditional expressions, ``and``/``or``/``not`` of comparisons, the ``math`` functions below,
``libm_pow``, ``knee_u`` and the gated functions of ``kernel_lib``, ``max``/``min``/``abs``/``int``/
``float``, the run-time tables (``tab``, ``tab_slope``), SUNDIALS' vectors and matrices read
as ``kernel_lib``'s intrinsics read them, and module-level int32 arrays. Types are inferred:
int64 for integers, double for the rest, pointers for ``carray``.
"""

from __future__ import annotations

import ast
import ctypes
import functools
import hashlib
import os
import shlex
import shutil
import subprocess
import sysconfig
import tempfile
from pathlib import Path
from typing import Any

#: the compiler's options: IEEE arithmetic as numba's (no fast-math, no fused multiply-add,
#: errno as C has it: no effect on the values; no builtins: GCC, as LLVM would, turns pow(x,
#: 2.0) into x*x and pow(x, -1.0) into 1/x, which round differently from libm's pow)
FLAGS = ("-O2", "-std=c99", "-fPIC", "-shared", "-ffp-contract=off", "-fno-fast-math",
         "-fno-builtin")
#: the longest a compile may take [s] (then numba compiles the module)
TIMEOUT = 120.0

#: math functions with a C99 twin of the same name (numba calls the same libm)
_MATH = {"sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh",
         "asinh", "acosh", "atanh", "exp", "expm1", "log", "log1p", "log10", "log2", "sqrt",
         "fabs", "copysign", "hypot", "erf", "erfc"}
_GATED = {"if_sin": "sin", "if_cos": "cos", "if_exp": "exp", "if_tanh": "tanh",
          "if_sinh": "sinh", "if_cosh": "cosh", "if_atan": "atan"}
#: what IDA passes: the signatures of kernel_lib's RES, ROOT and JAC
_SIGNATURES = {"RES": ("d", "v", "v", "v", "v"), "ROOT": ("d", "v", "v", "v", "v"),
               "JAC": ("d", "d", "v", "v", "v", "v", "v", "v", "v", "v")}
_CTYPE = {"d": "double", "i": "long long", "b": "int", "v": "void *", "pd": "double *",
          "pi": "int *"}

_PRELUDE = r"""
#include <math.h>
#include <string.h>
#include <stdlib.h>
/* SUNDIALS 7, 32-bit indices, as kernel_lib reads them (checked in solve/sundials_libs.py) */
static void *data_of(void *x) { return *(void **)((char *)*(void **)x + 8); }
static void *band_data(void *x) { return *(void **)((char *)*(void **)x + 24); }
static long long band_ldim(void *x) { return *(int *)((char *)*(void **)x + 8); }
static long long band_smu(void *x) { return *(int *)((char *)*(void **)x + 20); }
static void *sparse_data(void *x) { return *(void **)((char *)*(void **)x + 16); }
static void *sparse_rows(void *x) { return *(void **)((char *)*(void **)x + 32); }
static void *sparse_ptrs(void *x) { return *(void **)((char *)*(void **)x + 40); }
/* Python's max and min of two: the first unless the second is larger (smaller) */
static double py_max(double a, double b) { return b > a ? b : a; }
static double py_min(double a, double b) { return b < a ? b : a; }
/* numpy.searchsorted(x[0:m], v, side="right") - 1, NaN after everything */
static long long right_of(const double *x, long long m, double v) {
    long long lo = 0, hi = m;
    if (v != v) return m - 1;
    while (lo < hi) { long long mid = (lo + hi) / 2; if (x[mid] <= v) lo = mid + 1; else hi = mid; }
    return lo - 1;
}
static double tab(const double *u, long long h, long long i, double x) {
    long long off = (long long)u[h + 2 * i], m = (long long)u[h + 2 * i + 1];
    long long k = right_of(u + off, m, x);
    if (k < 0) return u[off + m];
    if (k >= m - 1) return u[off + 2 * m - 1];
    return u[off + m + k] + u[off + 2 * m + k] * (x - u[off + k]);
}
/* the u > 0 with atan(u) = r u: kernel_lib.knee_u's Newton steps in the same order */
static double knee_u(double r, long long steps) {
    double u = 1.5707963267948966 * sqrt(1.0 / (r * r) - 1.0);
    for (long long k = 0; k < steps; k++) u = u - (atan(u) - r * u) / (1.0 / (1.0 + u * u) - r);
    return u;
}
static double tab_slope(const double *u, long long h, long long i, double x) {
    long long off = (long long)u[h + 2 * i], m = (long long)u[h + 2 * i + 1];
    long long k = right_of(u + off, m, x);
    return (0 <= k && k < m - 1) ? u[off + 2 * m + k] : 0.0;
}
"""


class Unsupported(Exception):
    """A construct outside the subset: the module stays with numba."""


def _float(v: float) -> str:
    text = repr(float(v))
    if text in ("inf", "-inf", "nan"):
        return {"inf": "HUGE_VAL", "-inf": "(-HUGE_VAL)", "nan": "NAN"}[text]
    return text if any(c in text for c in ".en") else text + ".0"


class _Function:
    """One function's translation: its locals' types and its C statements."""

    def __init__(self, unit: _Unit, node: ast.FunctionDef, params: tuple[str, ...]):
        self.unit, self.node = unit, node
        names = [a.arg for a in node.args.args]
        if len(names) != len(params) or node.args.vararg or node.args.kwonlyargs:
            raise Unsupported(f"{node.name}: arguments")
        self.params = dict(zip(names, params, strict=True))
        self.locals: dict[str, str] = {}
        self.allocated: list[str] = []  # numpy.empty's arrays: freed before each return
        self.lines: list[str] = []

    def type_of(self, name: str) -> str:
        if name in self.params:
            return self.params[name]
        if name in self.locals:
            return self.locals[name]
        if name in self.unit.arrays:
            return "pi"
        raise Unsupported(f"name {name}")

    def bind(self, name: str, kind: str) -> None:
        if name in self.params:
            raise Unsupported(f"assignment to argument {name}")
        old = self.locals.get(name)
        if old is None or old == kind:
            self.locals[name] = kind
        elif {old, kind} == {"i", "b"}:  # a truth value and an integer: C's int of both
            self.locals[name] = "i"
        else:
            raise Unsupported(f"{name} changes type")

    # ------------------------------------------------------------------ expressions
    def expr(self, e: ast.expr) -> tuple[str, str]:
        """(C text, type) of an expression."""
        method = getattr(self, f"_{type(e).__name__}", None)
        if method is None:
            raise Unsupported(type(e).__name__)
        return method(e)

    def _Constant(self, e: ast.Constant) -> tuple[str, str]:
        v = e.value
        if isinstance(v, bool):
            return ("1" if v else "0"), "b"
        if isinstance(v, int):
            if abs(v) >= 2 ** 53:
                raise Unsupported("large integer")
            return f"{v}LL", "i"
        if isinstance(v, float):
            return _float(v), "d"
        raise Unsupported(f"constant {v!r}")

    def _Name(self, e: ast.Name) -> tuple[str, str]:
        return e.id, self.type_of(e.id)

    def _Attribute(self, e: ast.Attribute) -> tuple[str, str]:
        if isinstance(e.value, ast.Name) and e.value.id == "math" and e.attr in ("pi", "e"):
            return _float(3.141592653589793 if e.attr == "pi" else 2.718281828459045), "d"
        raise Unsupported("attribute")

    def _UnaryOp(self, e: ast.UnaryOp) -> tuple[str, str]:
        text, kind = self.expr(e.operand)
        if isinstance(e.op, ast.Not):
            return f"(!({text}))", "b"
        if kind not in ("d", "i", "b"):
            raise Unsupported("unary on a pointer")
        sign = {ast.USub: "-", ast.UAdd: "+"}.get(type(e.op))
        if sign is None:
            raise Unsupported("unary operator")
        return f"({sign}{text})", ("i" if kind == "b" else kind)

    def _BinOp(self, e: ast.BinOp) -> tuple[str, str]:
        (a, ka), (b, kb) = self.expr(e.left), self.expr(e.right)
        if not {ka, kb} <= {"d", "i", "b"}:
            raise Unsupported("arithmetic on a pointer")
        if isinstance(e.op, ast.Div):  # Python's true division, of ints too
            return f"((double)({a}) / (double)({b}))", "d"
        op = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*"}.get(type(e.op))
        if op is None:
            raise Unsupported(f"operator {type(e.op).__name__}")
        kind = "d" if "d" in (ka, kb) else "i"
        return f"({a} {op} {b})", kind

    def _Compare(self, e: ast.Compare) -> tuple[str, str]:
        ops = {ast.Lt: "<", ast.LtE: "<=", ast.Gt: ">", ast.GtE: ">=", ast.Eq: "==",
               ast.NotEq: "!="}
        left, kl = self.expr(e.left)
        parts = []
        for op, right in zip(e.ops, e.comparators, strict=True):
            if type(op) not in ops:
                raise Unsupported("comparison")
            r, kr = self.expr(right)
            if not {kl, kr} <= {"d", "i", "b"}:
                raise Unsupported("comparison of pointers")
            parts.append(f"({left} {ops[type(op)]} {r})")
            left, kl = r, kr
        return "(" + " && ".join(parts) + ")", "b"

    def _BoolOp(self, e: ast.BoolOp) -> tuple[str, str]:
        # Python's and/or give an operand, not a truth value: only truth values are taken
        parts = [self.expr(v) for v in e.values]
        if any(k != "b" for _, k in parts):
            raise Unsupported("and/or of numbers")
        op = " && " if isinstance(e.op, ast.And) else " || "
        return "(" + op.join(t for t, _ in parts) + ")", "b"

    def _IfExp(self, e: ast.IfExp) -> tuple[str, str]:
        (c, _), (a, ka), (b, kb) = self.expr(e.test), self.expr(e.body), self.expr(e.orelse)
        if not {ka, kb} <= {"d", "i", "b"}:
            raise Unsupported("conditional pointer")
        if "d" in (ka, kb):
            return f"(({c}) ? (double)({a}) : (double)({b}))", "d"
        return f"(({c}) ? ({a}) : ({b}))", "i"

    def _Subscript(self, e: ast.Subscript) -> tuple[str, str]:
        base, kind = self.expr(e.value)
        if kind not in ("pd", "pi") or isinstance(e.slice, ast.Slice):
            raise Unsupported("subscript")
        index, ki = self.expr(e.slice)
        if ki not in ("i", "b"):
            raise Unsupported("index not an integer")
        return f"{base}[{index}]", ("d" if kind == "pd" else "i")

    def _Call(self, e: ast.Call) -> tuple[str, str]:
        f = e.func
        if isinstance(f, ast.Attribute) and isinstance(f.value, ast.Name):
            return self._module_call(f.value.id, f.attr, e)
        if not isinstance(f, ast.Name):
            raise Unsupported("call")
        if f.id == "carray":
            return self._carray(e)
        if e.keywords:
            raise Unsupported(f"keywords to {f.id}")
        args = [self.expr(a) for a in e.args]
        return self._named_call(f.id, args)

    def _named_call(self, name: str, args: list[tuple[str, str]]) -> tuple[str, str]:
        texts = [t for t, _ in args]
        kinds = [k for _, k in args]
        numeric = all(k in ("d", "i", "b") for k in kinds)
        if name == "libm_pow" and len(args) == 2 and numeric:
            return f"pow({texts[0]}, {texts[1]})", "d"
        if name in _GATED and len(args) == 2 and numeric:
            return f"(({texts[0]}) != 0.0 ? {_GATED[name]}({texts[1]}) : 0.0)", "d"
        if name in ("max", "min") and len(args) >= 2 and numeric:
            out = texts[0]
            for t in texts[1:]:
                out = f"py_{name}({out}, {t})"
            return out, "d"
        if name == "abs" and len(args) == 1 and numeric:
            return (f"fabs({texts[0]})", "d") if kinds[0] == "d" else \
                (f"llabs({texts[0]})", "i")
        if name == "int" and len(args) == 1 and numeric:
            return f"((long long)({texts[0]}))", "i"
        if name == "float" and len(args) == 1 and numeric:
            return f"((double)({texts[0]}))", "d"
        if name == "knee_u" and kinds == ["d", "i"]:
            return f"knee_u({texts[0]}, {texts[1]})", "d"
        if name in ("tab", "tab_slope") and len(args) == 4 and kinds[0] == "pd":
            return f"{name}({', '.join(texts)})", "d"
        if name in ("data_of", "band_data", "sparse_data", "sparse_rows", "sparse_ptrs") \
                and kinds == ["v"]:
            return f"{name}({texts[0]})", "v"
        if name in ("band_ldim", "band_smu") and kinds == ["v"]:
            return f"{name}({texts[0]})", "i"
        if name in self.unit.defs:
            self.unit.call(name, tuple(kinds))
            return f"{name}({', '.join(texts)})", "i"
        raise Unsupported(f"function {name}")

    def _module_call(self, module: str, attr: str, e: ast.Call) -> tuple[str, str]:
        args = [self.expr(a) for a in e.args]
        if e.keywords or not all(k in ("d", "i", "b") for _, k in args):
            raise Unsupported(f"{module}.{attr}")
        texts = ", ".join(f"(double)({t})" for t, _ in args)
        if module == "math" and attr in _MATH:
            return f"{attr}({texts})", "d"
        if module == "numpy" and attr == "int64" and len(args) == 1:
            return f"((long long)({args[0][0]}))", "i"
        if module == "numpy" and attr == "empty" and len(args) == 1:
            return f"((double *)malloc(sizeof(double) * ({args[0][0]})))", "pd"
        raise Unsupported(f"{module}.{attr}")

    def _carray(self, e: ast.Call) -> tuple[str, str]:
        dtype = next((k.value for k in e.keywords if k.arg == "dtype"), None)
        kind = {"float64": "pd", "int32": "pi"}.get(getattr(dtype, "attr", ""))
        if kind is None or len(e.args) != 2 or len(e.keywords) != 1:
            raise Unsupported("carray")
        ptr, kp = self.expr(e.args[0])
        if kp != "v":
            raise Unsupported("carray of a non-pointer")
        self.expr(e.args[1])  # the size: checked to be an expression of the subset
        return f"(({_CTYPE[kind]})({ptr}))", kind

    # ------------------------------------------------------------------ statements
    def body(self, stmts: list[ast.stmt], indent: str) -> list[str]:
        out: list[str] = []
        for s in stmts:
            out += self.stmt(s, indent)
        return out

    def stmt(self, s: ast.stmt, indent: str) -> list[str]:
        if isinstance(s, ast.Expr):
            if isinstance(s.value, ast.Constant) and isinstance(s.value.value, str):
                return []  # a docstring
            text, _ = self.expr(s.value)
            return [f"{indent}{text};"]
        if isinstance(s, ast.Assign):
            return self._assign(s, indent)
        if isinstance(s, ast.AugAssign):
            return self._augassign(s, indent)
        if isinstance(s, ast.Return):
            text, kind = self.expr(s.value) if s.value is not None else ("0", "i")
            if kind not in ("i", "b"):
                raise Unsupported("return of a non-integer")
            return [*(f"{indent}free({n});" for n in self.allocated),
                    f"{indent}return {text};"]
        if isinstance(s, ast.For):
            return self._for(s, indent)
        if isinstance(s, ast.If):
            test, _ = self.expr(s.test)
            out = [f"{indent}if ({test}) {{", *self.body(s.body, indent + "    ")]
            if s.orelse:
                out += [f"{indent}}} else {{", *self.body(s.orelse, indent + "    ")]
            return [*out, f"{indent}}}"]
        raise Unsupported(type(s).__name__)

    def _assign(self, s: ast.Assign, indent: str) -> list[str]:
        if len(s.targets) != 1:
            raise Unsupported("chained assignment")
        target, value = s.targets[0], s.value
        if isinstance(target, ast.Tuple):
            if not isinstance(value, ast.Tuple) or len(value.elts) != len(target.elts):
                raise Unsupported("tuple assignment")
            names = {t.id for t in target.elts if isinstance(t, ast.Name)}
            if len(names) != len(target.elts) or any(
                    isinstance(n, ast.Name) and n.id in names
                    for v in value.elts for n in ast.walk(v)):
                raise Unsupported("tuple assignment reading its targets")
            return [line for t, v in zip(target.elts, value.elts, strict=True)
                    for line in self._assign(ast.Assign([t], v), indent)]
        if isinstance(target, ast.Subscript) and isinstance(target.slice, ast.Slice):
            return self._copy(target, value, indent)
        text, kind = self.expr(value)
        if isinstance(target, ast.Name):
            self.bind(target.id, kind)
            if "malloc(" not in text:
                return [f"{indent}{target.id} = {text};"]
            if target.id in self.allocated:
                raise Unsupported(f"{target.id} allocated twice")
            # out of memory: an unrecoverable failure for IDA (a negative flag), not a crash
            fail = [f"{indent}if ({target.id} == NULL) {{",
                    *(f"{indent}    free({n});" for n in self.allocated),
                    f"{indent}    return -1;", f"{indent}}}"]
            self.allocated.append(target.id)
            return [f"{indent}{target.id} = {text};", *fail]
        if isinstance(target, ast.Subscript):
            where, kt = self._Subscript(target)
            if kind not in ("d", "i", "b") or (kt == "i" and kind == "d"):
                raise Unsupported("element assignment")
            return [f"{indent}{where} = {text};"]
        raise Unsupported("assignment target")

    def _copy(self, target: ast.Subscript, value: ast.expr, indent: str) -> list[str]:
        """``carray(...)[:] = ARRAY``: a module-level int32 array copied whole."""
        sl = target.slice
        if sl.lower or sl.upper or sl.step or not isinstance(value, ast.Name) \
                or value.id not in self.unit.arrays:
            raise Unsupported("slice assignment")
        dest, kind = self.expr(target.value)
        if kind != "pi":
            raise Unsupported("slice assignment to doubles")
        n = len(self.unit.arrays[value.id])
        return [f"{indent}memcpy({dest}, {value.id}, sizeof(int) * {n});"]

    def _augassign(self, s: ast.AugAssign, indent: str) -> list[str]:
        op = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*"}.get(type(s.op))
        if op is None:
            raise Unsupported("augmented operator")
        text, kind = self.expr(s.value)
        if isinstance(s.target, ast.Name):
            old = self.type_of(s.target.id)
            if old not in ("d", "i") or (old == "i" and kind == "d"):
                raise Unsupported("augmented assignment changes type")
            return [f"{indent}{s.target.id} = {s.target.id} {op} ({text});"]
        if isinstance(s.target, ast.Subscript):
            where, kt = self._Subscript(s.target)
            if kt != "d" or kind not in ("d", "i", "b"):
                raise Unsupported("augmented element assignment")
            return [f"{indent}{where} = {where} {op} ({text});"]
        raise Unsupported("augmented target")

    def _for(self, s: ast.For, indent: str) -> list[str]:
        it = s.iter
        if s.orelse or not isinstance(s.target, ast.Name) or not (
                isinstance(it, ast.Call) and isinstance(it.func, ast.Name)
                and it.func.id == "range" and 1 <= len(it.args) <= 2 and not it.keywords):
            raise Unsupported("loop")
        bounds = [self.expr(a) for a in it.args]
        if any(k not in ("i", "b") for _, k in bounds):
            raise Unsupported("range of a non-integer")
        lo, hi = ("0LL", bounds[0][0]) if len(bounds) == 1 else (bounds[0][0], bounds[1][0])
        var = s.target.id
        self.bind(var, "i")
        # the bound is evaluated once, as Python's range is
        end = f"_end_{var}_{self.unit.serial()}"
        self.locals[end] = "i"
        return [f"{indent}{end} = {hi};", f"{indent}for ({var} = {lo}; {var} < {end}; {var}++) {{",
                *self.body(s.body, indent + "    "), f"{indent}}}"]

    def emit(self) -> list[str]:
        body = self.body(self.node.body, "    ")
        if not body or not body[-1].lstrip().startswith("return "):
            raise Unsupported(f"{self.node.name}: no return at the end")
        args = ", ".join(f"{_CTYPE[k]} {n}" for n, k in self.params.items())
        ret = "int" if self.node.name in self.unit.entries else "long long"
        decls = [f"    {_CTYPE[k]} {n};" for n, k in sorted(self.locals.items())]
        return [f"{'' if ret == 'int' else 'static '}{ret} {self.node.name}({args}) {{",
                *decls, *body, "}"]


class _Unit:
    """A kernel module's translation: its functions, typed from the entries IDA calls."""

    def __init__(self, tree: ast.Module):
        self.defs = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}
        self.entries: dict[str, str] = {}
        self.arrays: dict[str, list[int]] = {}
        self._serial = 0
        for node in tree.body:
            self._top(node)
        self.typed: dict[str, tuple[str, ...]] = {}
        self.done: dict[str, _Function] = {}

    def _top(self, node: ast.stmt) -> None:
        """CFUNCS['name'] = 'SIG' marks an entry; NAME = numpy.array([...], dtype=int32) an
        array; other module statements are left to Python."""
        if not isinstance(node, ast.Assign) or len(node.targets) != 1:
            return
        t, v = node.targets[0], node.value
        if isinstance(t, ast.Subscript) and isinstance(t.value, ast.Name) \
                and t.value.id == "CFUNCS" and isinstance(v, ast.Constant):
            self.entries[ast.literal_eval(t.slice)] = v.value
        elif isinstance(t, ast.Name) and isinstance(v, ast.Call) and \
                getattr(v.func, "attr", "") == "array" and len(v.args) == 1:
            dtype = next((k.value for k in v.keywords if k.arg == "dtype"), None)
            if getattr(dtype, "attr", "") == "int32":
                self.arrays[t.id] = [int(x) for x in ast.literal_eval(v.args[0])]

    def serial(self) -> int:
        self._serial += 1
        return self._serial

    def call(self, name: str, kinds: tuple[str, ...]) -> None:
        """A call of the module's function ``name`` with arguments of ``kinds``."""
        kinds = tuple("i" if k == "b" else k for k in kinds)
        if name in self.typed:
            if self.typed[name] != kinds:
                raise Unsupported(f"{name} called with other types")
            return
        self.typed[name] = kinds
        fn = _Function(self, self.defs[name], kinds)
        self.done[name] = fn
        fn.lines = fn.emit()

    def source(self) -> str:
        for name, sig in self.entries.items():
            if sig not in _SIGNATURES or name not in self.defs:
                raise Unsupported(f"entry {name}")
            self.call(name, _SIGNATURES[sig])
        arrays = [f"static const int {n}[{max(len(v), 1)}] = {{{', '.join(map(str, v)) or '0'}}};"
                  for n, v in self.arrays.items()]
        order = [n for n in self.defs if n in self.done]
        protos = [self.done[n].lines[0].replace(" {", ";") for n in order]
        body = [line for n in order for line in ["", *self.done[n].lines]]
        return "\n".join([_PRELUDE.strip(), *arrays, *protos, *body]) + "\n"


@functools.lru_cache(maxsize=64)  # 50 ms a large module; the worker's queue asks again and again
def translate(source: str) -> str | None:
    """The C99 text of a kernel module's entries (``CFUNCS``) and what they call, or None
    when the module uses anything outside the subset."""
    try:
        unit = _Unit(ast.parse(source))
        if not unit.entries:
            return None
        text = unit.source()
    except (Unsupported, SyntaxError, ValueError, KeyError):
        return None
    return text


def compiler() -> list[str] | None:
    """The C compiler's command (``CIRCUITSIM_CC``, else the one Python was built with, else
    ``cc``), or None when there is none or it is turned off."""
    given = os.environ.get("CIRCUITSIM_CC", "").strip()
    if given.lower() in ("0", "off", "no", "none"):
        return None
    words = shlex.split(given or sysconfig.get_config_var("CC") or "cc")
    if words and shutil.which(words[0]) is None:
        words = ["cc"] if shutil.which("cc") else []
    return words or None


def _target(folder: Path, source: str) -> tuple[list[str], str, Path] | None:
    """(compile command, C text, library path) of the kernel module ``source`` in ``folder``,
    or None: no compiler, or a construct outside the subset."""
    cc = compiler()
    text = translate(source) if cc else None
    if text is None:
        return None
    command = [*cc, *FLAGS]
    digest = hashlib.sha256(f"{command!r}\n{text}".encode()).hexdigest()[:24]
    return command, text, folder / f"c{digest}.so"


def built(folder: Path, source: str) -> bool:
    """Whether the library of the kernel module ``source`` is in ``folder`` already."""
    target = _target(folder, source)
    return target is not None and target[2].exists()


def library(folder: Path, source: str) -> Any | None:
    """The shared library of the kernel module ``source`` compiled into ``folder`` (loaded;
    built when absent), or None: no compiler, a construct outside the subset, a failed
    compile (numba then compiles the module)."""
    target = _target(folder, source)
    if target is None:
        return None
    command, text, path = target
    if not path.exists() and not _build(command, text, path):
        return None
    try:
        return ctypes.CDLL(str(path))
    except OSError:
        return None


def _build(command: list[str], text: str, path: Path) -> bool:
    """Compile ``text`` into ``path``, written whole (a temporary name, then renamed)."""
    fd, tmp = tempfile.mkstemp(suffix=".so", dir=path.parent)
    os.close(fd)
    c_file = tmp[:-3] + ".c"
    try:
        Path(c_file).write_text(text, encoding="utf-8")
        done = subprocess.run([*command, c_file, "-o", tmp, "-lm"], capture_output=True,
                              timeout=TIMEOUT, check=False)
        if done.returncode != 0:
            return False
        os.chmod(tmp, 0o644 & ~_umask())
        os.replace(tmp, path)
        return True
    except (OSError, subprocess.SubprocessError):
        return False
    finally:
        for leftover in (tmp, c_file):
            if os.path.exists(leftover):
                os.unlink(leftover)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


class Entry:
    """A compiled entry of the library, as IDA takes a numba cfunc: by ``address``."""

    def __init__(self, lib: Any, name: str):
        self.lib = lib  # held: the address is good while the library is loaded
        self.address = ctypes.cast(getattr(lib, name), ctypes.c_void_p).value
