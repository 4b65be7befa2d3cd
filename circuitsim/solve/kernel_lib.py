"""What the numba kernels of every topology share (``compiler/codegen.py`` writes the rest).

The source is written into the cache folder as a module named by its hash
(``solve/direct.py``), which every topology's kernel module imports: numba then compiles the
output loop, the tables' lookup and the intrinsics that read SUNDIALS' structures once per
version and machine, not once per topology. Nothing here imports the rest of circuitsim.
"""

from __future__ import annotations

import hashlib

SOURCE = '''# what the numba kernels of every topology share, written by circuitsim.codegen: do not edit.
# Compiled once a machine (numba keeps it beside this file), not once a topology.
import math

import numpy
from llvmlite import ir
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic


def _second_field(context, builder, signature, args):
    # serial N_Vector and dense SUNMatrix alike: x->content, then the pointer 8 bytes into the
    # content (after two 32-bit fields) is the data (SUNDIALS 7, 32-bit indices)
    pp = ir.IntType(8).as_pointer().as_pointer()
    content = builder.load(builder.bitcast(args[0], pp))
    field = builder.gep(content, [ir.Constant(ir.IntType(64), 8)])
    return builder.load(builder.bitcast(field, pp))


@intrinsic
def data_of(typingctx, x):
    return types.voidptr(types.voidptr), _second_field


def _band_field(offset, kind):
    # a band SUNMatrix's content: int32 M, N, ldim, mu, ml, s_mu, then the data pointer
    def codegen(context, builder, signature, args):
        content = builder.load(builder.bitcast(args[0], ir.IntType(8).as_pointer().as_pointer()))
        field = builder.gep(content, [ir.Constant(ir.IntType(64), offset)])
        return builder.load(builder.bitcast(field, kind.as_pointer()))
    return codegen


@intrinsic
def band_data(typingctx, x):
    return types.voidptr(types.voidptr), _band_field(24, ir.IntType(8).as_pointer())


@intrinsic
def band_ldim(typingctx, x):
    return types.int32(types.voidptr), _band_field(8, ir.IntType(32))


@intrinsic
def band_smu(typingctx, x):
    return types.int32(types.voidptr), _band_field(20, ir.IntType(32))


@intrinsic
def sparse_data(typingctx, x):
    # a sparse SUNMatrix's content: int32 M, N, NNZ, NP, then the data pointer, int
    # sparsetype, the row indices and the column pointers (checked in solve/direct.py)
    return types.voidptr(types.voidptr), _band_field(16, ir.IntType(8).as_pointer())


@intrinsic
def sparse_rows(typingctx, x):
    return types.voidptr(types.voidptr), _band_field(32, ir.IntType(8).as_pointer())


@intrinsic
def sparse_ptrs(typingctx, x):
    return types.voidptr(types.voidptr), _band_field(40, ir.IntType(8).as_pointer())


def _int_to_pointer(context, builder, signature, args):
    return builder.inttoptr(args[0], ir.IntType(8).as_pointer())


@intrinsic
def as_pointer(typingctx, address):
    return types.voidptr(address), _int_to_pointer


def _call_pow(context, builder, signature, args):
    # C's pow, called as a library function that LLVM may not rewrite (it turns pow(x, 2.0)
    # into x*x and pow(x, -1.0) into 1/x, which round differently from glibc's pow)
    double = ir.DoubleType()
    fn = cgutils.get_or_insert_function(builder.module, ir.FunctionType(double, [double, double]),
                                        "pow")
    fn.attributes.add("nobuiltin")
    return builder.call(fn, args)


@intrinsic
def libm_pow(typingctx, x, y):
    """x ** y as Python computes it for floats: C's pow."""
    return types.float64(types.float64, types.float64), _call_pow


IDA_SOLVE = types.ExternalFunction("IDASolve", types.int32(
    types.voidptr, types.float64, types.voidptr, types.voidptr, types.voidptr, types.int32))


@njit(cache=True)
def outputs(mem, yy, yp, tspan, Y, YP, out_t, out_y, out_yp):
    """IDA_NORMAL to every output time, storing t, y and y' (the loop without Python), up to
    and including a root of the guards; the number of rows filled and IDA's last flag."""
    tret = numpy.zeros(1)
    k, flag, n = 1, 0, Y.size
    while k < tspan.size:
        flag = IDA_SOLVE(as_pointer(mem), tspan[k], as_pointer(tret.ctypes.data),
                         as_pointer(yy), as_pointer(yp), 1)
        if flag < 0:
            break
        out_t[k] = tret[0]
        # element by element: a slice assignment costs numba 2 s of compiling, once per cache
        for j in range(n):
            out_y[k, j] = Y[j]
            out_yp[k, j] = YP[j]
        k += 1
        if flag == 2:  # IDA_ROOT_RETURN: every guard is terminal; the root is the last row
            break
    return k, flag


@njit(cache=True, error_model="numpy")
def tab(u, h, i, x):
    """Table i's value at x as circuitsim.compiler.model._Table computes it (held at the ends):
    its points start at u[h + 2 i], u[h + 2 i + 1] of them: the x, the y, the slopes."""
    off, m = int(u[h + 2 * i]), int(u[h + 2 * i + 1])
    k = numpy.searchsorted(u[off:off + m], x, side="right") - 1
    if k < 0:
        return u[off + m]
    if k >= m - 1:
        return u[off + 2 * m - 1]
    return u[off + m + k] + u[off + 2 * m + k] * (x - u[off + k])


@njit(cache=True, error_model="numpy")
def knee_u(r, steps):
    """The u > 0 with atan(u) = r u (components.passive.knee_u: the same Newton steps, in the
    same order, from the same bound); a call because numba cannot type the walrus chain the
    Python route writes inline."""
    u = 1.5707963267948966 * math.sqrt(1 / (r * r) - 1)
    for _ in range(steps):
        u = u - (math.atan(u) - r * u) / (1 / (1 + u * u) - r)
    return u


@njit(cache=True, error_model="numpy")
def tab_slope(u, h, i, x):
    """Table i's slope at x (0 outside its points), as _Table.slope."""
    off, m = int(u[h + 2 * i]), int(u[h + 2 * i + 1])
    k = numpy.searchsorted(u[off:off + m], x, side="right") - 1
    return u[off + 2 * m + k] if 0 <= k < m - 1 else 0.0


RES = types.int32(types.float64, types.voidptr, types.voidptr, types.voidptr, types.voidptr)
#: IDA's root function: g(t, yy, yp, gout, user_data), the guards into gout
ROOT = types.int32(types.float64, types.voidptr, types.voidptr, types.voidptr, types.voidptr)
JAC = types.int32(types.float64, types.float64, types.voidptr, types.voidptr, types.voidptr,
                  types.voidptr, types.voidptr, types.voidptr, types.voidptr, types.voidptr)
'''

#: the functions a term of the kernels skips while the parameters multiplying it are zero
#: (``compiler/codegen.py``, ``_term``), each as ``if_<name>(z, x)``: ``<name>(x)`` unless the
#: factor ``z`` is zero, then 0.0. A call, not an inline conditional: numba's compile time
#: grows with the branches of one function far faster than with its calls.
GUARDED = ("sin", "cos", "exp", "tanh", "sinh", "cosh", "atan")
SOURCE += "".join(f"""

@njit(cache=True, error_model="numpy")
def if_{name}(z, x):
    return math.{name}(x) if z != 0.0 else 0.0
""" for name in GUARDED)

#: IDA's return flag for a root (SUNDIALS IDA_ROOT_RETURN; the output loop above stops at it)
ROOT_RETURN = 2

#: Hysteresis of a held relation (a relation in an expression: abs, sign, min, max, if),
#: relative to |lhs| + |rhs|, and an absolute floor: at its root IDA returns a point just past
#: the crossing, so the new mode's guard is positive by that much; the band keeps the rounding
#: of the restart from switching it straight back. Here because the kernels' root function
#: (compiler/codegen.py) and the Python route's (solve/events.py) must add the same numbers.
BAND_REL = 1e-10
BAND_ABS = 1e-300

#: the shared helpers' module name: their source's hash, so that numba's code kept for one
#: version is never taken for another's
KERNEL_LIB = "circuitsim_kernel_lib_" + hashlib.sha256(SOURCE.encode()).hexdigest()[:12]
