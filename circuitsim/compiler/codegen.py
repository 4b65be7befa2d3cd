"""Generate and cache the numeric code of an index-1 DAE.

Pipeline stage 5. One Python module per topology, written with sympy's code printers after
common-subexpression elimination: one residual call for the whole network, its analytic
Jacobian dF/dy + cj dF/dy', the parts dF/dy, dF/dy', dF/dt (for consistent initial values and
linearisation), and a vectorised ``observe`` giving every probe and every eliminated variable.
Parameters are a run-time tuple, so a parameter change never reaches sympy.

The module is stored by ``cache`` and imported from there; a second run of the
same topology imports it without touching sympy.
"""

from __future__ import annotations

from typing import Any

CODEGEN_VERSION = "4"


def _printers():
    from sympy.printing.numpy import NumPyPrinter
    from sympy.printing.pycode import PythonCodePrinter

    class Scalar(PythonCodePrinter):
        def _print_Lookup(self, e):
            return f"T[{int(e.args[0])}]({self._print(e.args[1])})"

        def _print_LookupSlope(self, e):
            return f"TD[{int(e.args[0])}]({self._print(e.args[1])})"

        def _print_Pmod(self, e):
            x, per = (self._print(a) for a in e.args)
            return f"(({x}) % ({per}))"

    class Vector(NumPyPrinter):
        def _print_Lookup(self, e):
            return f"TV[{int(e.args[0])}]({self._print(e.args[1])})"

        def _print_LookupSlope(self, e):
            return f"TDV[{int(e.args[0])}]({self._print(e.args[1])})"

        def _print_Pmod(self, e):
            x, per = (self._print(a) for a in e.args)
            return f"numpy.mod({x}, {per})"

        def _print_And(self, e):  # numpy's logical_and.reduce fails on an array and a scalar
            return f"functools.reduce(numpy.logical_and, [{', '.join(map(self._print, e.args))}])"

        def _print_Or(self, e):
            return f"functools.reduce(numpy.logical_or, [{', '.join(map(self._print, e.args))}])"

    return Scalar({"fully_qualified_modules": True, "standard": "python3"}), \
        Vector({"fully_qualified_modules": True})


def _names(dae) -> dict:
    import sympy as sp

    m: dict = {dae.t: sp.Symbol("t")}
    for k, s in enumerate(dae.states):
        m[s] = sp.Symbol(f"y{k}")
        m[dae.yp[k]] = sp.Symbol(f"yp{k}")
    for k, p in enumerate(dae.params):
        m[p] = sp.Symbol(f"p{k}")
    return m


def _block(exprs: list, printer, indent: str, assign: list[str]) -> list[str]:
    """CSE over exprs, then lines ``assign[k] = <expr k>``."""
    import sympy as sp

    subs, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("c"), optimizations="basic")
    lines = []
    for sym, val in subs:
        lines.append(f"{indent}{sym} = {printer.doprint(val)}")
    for target, e in zip(assign, reduced, strict=True):
        lines.append(f"{indent}{target} = {printer.doprint(e)}")
    return lines


def _unpack(n: int, prefix: str, src: str, indent: str, used: set[str]) -> list[str]:
    names = [f"{prefix}{k}" if f"{prefix}{k}" in used else "_" for k in range(n)]
    if n == 0 or all(nm == "_" for nm in names):
        return []
    if n == 1:
        return [f"{indent}{names[0]}, = {src}"]
    return [f"{indent}{', '.join(names)} = {src}"]


def generate(dae) -> tuple[str, dict[str, Any]]:
    """Source of the generated module and its metadata (JSON-serialisable)."""
    import sympy as sp

    from circuitsim.component import as_expr

    scalar, vector = _printers()
    ren = _names(dae)
    n = len(dae.states)
    F = [as_expr(e).xreplace(ren) for e in dae.equations]
    Y = [ren[s] for s in dae.states]
    YP = [ren[s] for s in dae.yp]
    t = sp.Symbol("t")
    # A network whose unknowns were all eliminated (sources driving capacitors) has n = 0.
    Fy = sp.Matrix(F).jacobian(Y) if n else sp.zeros(0, 0)
    Fyp = sp.Matrix(F).jacobian(YP) if n else sp.zeros(0, 0)
    Ft = [sp.diff(f, t) for f in F]
    cj = sp.Symbol("cj")
    jac_entries = [(i, j, Fy[i, j] + cj * Fyp[i, j]) for i in range(n) for j in range(n)
                   if Fy[i, j] != 0 or Fyp[i, j] != 0]
    fy_entries = [(i, j, Fy[i, j]) for i in range(n) for j in range(n) if Fy[i, j] != 0]
    fyp_entries = [(i, j, Fyp[i, j]) for i in range(n) for j in range(n) if Fyp[i, j] != 0]
    names_out = list(dae.probes) + sorted(dae.exports)
    obs = [as_expr(dae.probes[k] if k in dae.probes else dae.exports[k]).xreplace(ren)
           for k in names_out]
    init_syms = [s for s in dae.initial]
    init_vals = [as_expr(dae.initial[s]).xreplace(ren) for s in init_syms]
    # a key may be an expression (a capacitor's v = p.v - n.v): resolve eliminated symbols
    init_exprs = [as_expr(s).xreplace(dict(dae.solved)).xreplace(ren) for s in init_syms]

    def body(name: str, args: str, exprs: list, targets: list[str], pre: list[str] = (),
             post: list[str] = (), vec: bool = False, fail: str = "") -> list[str]:
        used = {str(s) for e in exprs for s in as_expr(e).free_symbols}
        lines = [f"    def {name}({args}):"]
        if vec:
            lines += [f"        y{k} = Y[{k}]" for k in range(n) if f"y{k}" in used]
            lines += [f"        yp{k} = YP[{k}]" for k in range(n) if f"yp{k}" in used]
        else:
            lines += _unpack(n, "y", "y.tolist()", "        ", used)
            lines += _unpack(n, "yp", "yp.tolist()", "        ", used)
        lines += _unpack(len(dae.params), "p", "p", "        ", used)
        lines += list(pre)
        if fail:
            # Scalar code runs on Python floats, which raise where numpy would give inf or
            # nan (x**n/x at x = 0, log(0), sqrt(-1)): the solver gets NaN instead -- a failed
            # step it can retry smaller, or a clear "not finite" error -- never a traceback
            lines += ["        try:"]
            lines += _block(exprs, scalar, "            ", targets) or ["            pass"]
            lines += ["        except (ArithmeticError, ValueError, TypeError):", f"            {fail}"]
        else:
            lines += _block(exprs, vector if vec else scalar, "        ", targets)
        lines += list(post) or ["        return None"]
        return lines

    src = ["# Generated by circuitsim.codegen: do not edit. One module per topology.",
           "import functools", "import math", "import numpy", "", "",
           "def _real(v):",
           "    # a constant folded by Python (a negative number to a fractional power) is",
           "    # complex where numpy would give nan",
           "    if isinstance(v, complex) or numpy.iscomplexobj(v):",
           "        a = numpy.asarray(v)",
           "        return numpy.where(a.imag == 0, a.real, numpy.nan)",
           "    return v", "", "",
           "def make(T, TD, TV, TDV):"]
    src += body("residual", "t, y, yp, res, p", F, [f"res[{i}]" for i in range(n)],
                fail="res[:] = math.nan")
    src += body("jac", "t, y, yp, res, cj, JJ, p", [e for _, _, e in jac_entries],
                [f"JJ[{i}, {j}]" for i, j, _ in jac_entries], fail="JJ[:, :] = math.nan")
    src += body("parts", "t, y, yp, p", [e for *_, e in fy_entries] +
                [e for *_, e in fyp_entries] + Ft,
                [f"Fy[{i}, {j}]" for i, j, _ in fy_entries] +
                [f"Fyp[{i}, {j}]" for i, j, _ in fyp_entries] + [f"Ft[{i}]" for i in range(n)],
                pre=[f"        Fy = numpy.zeros(({n}, {n}))", f"        Fyp = numpy.zeros(({n}, {n}))",
                     f"        Ft = numpy.zeros({n})"],
                post=["        return Fy, Fyp, Ft"],
                fail="Fy[:, :] = Fyp[:, :] = Ft[:] = math.nan")
    src += body("observe", "t, Y, YP, p", obs, [f"out[{k}]" for k in range(len(obs))],
                pre=[f"        out = [None] * {len(obs)}"],
                post=["        return [_real(v) for v in out]"], vec=True)
    src += body("initial", "t, y, yp, p", init_vals + init_exprs,
                [f"out[{k}]" for k in range(2 * len(init_vals))],
                pre=[f"        out = [0.0] * {2 * len(init_vals)}"], post=["        return out"],
                fail=f"out = [math.nan] * {2 * len(init_vals)}")
    src += ["    return residual, jac, parts, observe, initial", ""]
    state_index = {s: k for k, s in enumerate(dae.states)}
    meta = {
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
        "n_equations": n,
        "jac_nnz": len(jac_entries),
        "integrals": {s.name: dae.integrals[s.name] for s in dae.states
                      if s.name in dae.integrals},
    }
    return "\n".join(src), meta


