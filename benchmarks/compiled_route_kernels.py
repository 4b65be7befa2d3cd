"""numba ``cfunc`` residual and Jacobian of the Kim & Kim base model, for IDA called directly.

Written by hand from the generated module's ``residual`` and ``jac`` (the same expressions, the
same parameter order); in a library route a second code printer would emit them. Imported only
by ``bench_compiled_route.py`` in a process that has numba. The N_Vector and SUNMatrix data
pointers are read through two small LLVM intrinsics rather than SUNDIALS' accessor functions
called through ctypes, because a kernel that holds a ctypes function pointer cannot be cached.
"""

from __future__ import annotations

import math

import numpy as np
from llvmlite import ir
from numba import carray, cfunc, types
from numba.extending import intrinsic

N, NP = 4, 24  # states, parameters of the base model


def _second_field(context, builder, signature, args):
    # serial N_Vector and dense SUNMatrix alike: x->content, then the pointer 8 bytes into the
    # content (after two 32-bit sunindextype/sunbooleantype fields) is the data
    pp = ir.IntType(8).as_pointer().as_pointer()
    content = builder.load(builder.bitcast(args[0], pp))
    field = builder.gep(content, [ir.Constant(ir.IntType(64), 8)])
    return builder.load(builder.bitcast(field, pp))


@intrinsic
def data_of(typingctx, x):
    """``x->content->data`` of a serial N_Vector or a dense SUNMatrix (SUNDIALS 7, 32-bit
    indices, as scikit-sundae's wheels build it)."""
    return types.voidptr(types.voidptr), _second_field


RES = types.int32(types.float64, types.voidptr, types.voidptr, types.voidptr, types.voidptr)
JAC = types.int32(types.float64, types.float64, types.voidptr, types.voidptr, types.voidptr,
                  types.voidptr, types.voidptr, types.voidptr, types.voidptr, types.voidptr)


@cfunc(RES, cache=True)
def residual(t, yy, yp, rr, ud):
    y = carray(data_of(yy), N, dtype=np.float64)
    d = carray(data_of(yp), N, dtype=np.float64)
    r = carray(data_of(rr), N, dtype=np.float64)
    p = carray(ud, NP, dtype=np.float64)
    r[0] = p[23] + (-1 * y[1]) + (-1 * p[0] * p[1] * d[1])
    r[1] = d[2] + (-1 * y[3])
    r[2] = (p[23] + (-1 * p[11]) + (-1 * p[10] * y[3]) + (-1 * p[16] * d[0]) + (-1 * p[17] * y[0])
            + (-1 * p[2] * d[0]) + (-1 * p[3] * y[0]) + (-1 * p[5] * y[0]) + (-1 * p[6] * d[0])
            + (-1 * p[7] * y[0]) + (-1 * (p[14] + (p[13] * y[3])) * math.sin(p[12] * y[2] + p[15])))
    r[3] = (p[19] * d[3]) + (p[22] * y[3]) + (-1 * p[9] * y[0])
    return 0


@cfunc(JAC, cache=True)
def jacobian(t, cj, yy, yp, rr, J, ud, t1, t2, t3):
    y = carray(data_of(yy), N, dtype=np.float64)
    p = carray(ud, NP, dtype=np.float64)
    a = carray(data_of(J), N * N, dtype=np.float64)  # column-major
    c0 = p[15] + (p[12] * y[2])
    a[2] = (-1 * p[17]) + (-1 * p[3]) + (-1 * p[5]) + (-1 * p[7]) + \
        (cj * ((-1 * p[16]) + (-1 * p[2]) + (-1 * p[6])))
    a[3] = -1 * p[9]
    a[N] = -1 + (-1 * cj * p[0] * p[1])
    a[1 + 2 * N] = cj
    a[2 + 2 * N] = -1 * p[12] * (p[14] + (p[13] * y[3])) * math.cos(c0)
    a[1 + 3 * N] = -1.0
    a[2 + 3 * N] = (-1 * p[10]) + (-1 * p[13] * math.sin(c0))
    a[3 + 3 * N] = p[22] + (cj * p[19])
    return 0
