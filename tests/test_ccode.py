"""Kernels compiled by the C compiler (``solve/ccode.py``): Python's arithmetic to the bit
(true division, max and min, conditionals, NaN and infinities, libm's functions and pow),
a module outside the subset or a failing compiler left to numba, and numba's route, the one
without a compiler, still the Python route's to the bit."""

from __future__ import annotations

import ctypes
import math
import os

import numpy as np
import pytest

import circuitsim as cs

from conftest import NETLISTS

pytest.importorskip("numba")
pytestmark = pytest.mark.filterwarnings("ignore::circuitsim.errors.CircuitWarning")

#: a kernel module of one entry, in the generated kernels' subset: each output one construct
EDGES = '''
import math

import numpy
from numba import carray, njit

from {lib} import (RES, data_of, if_cos, if_tanh, libm_pow)  # noqa: F401

CFUNCS = {{}}


@njit(cache=True, error_model="numpy")
def _at(t, y, r, o):
    y0 = y[o + 0]
    y1 = y[o + 1]
    c0 = (y0 < -y1)
    r[o + 0] = (1/2)*y0 + 3/4
    r[o + 1] = max(0, y0)
    r[o + 2] = min(y1, 0, y0)
    r[o + 3] = ((y0 + 1) if c0 else (y1 - 2) if (y1 > 1.5) else (0))
    r[o + 4] = libm_pow(y0, 2.0) + libm_pow(y1, -1.0) + libm_pow(abs(y0), 0.5)
    r[o + 5] = if_cos(y1, y0) + if_tanh(0.0, y0) + math.exp(-y0) * math.atan2(y0, y1)
    r[o + 6] = -1 * y0 / y1 + int(y1) + float(2)
    r[o + 7] = math.log(y0) + math.sqrt(y1) + abs(y1) + 2*math.pi
    r[o + 8] = (1.0 if (0 < y0 <= y1) and not (y1 == 3.0) else -1.0)
    return 0


def entry(t, yy, ypv, rr, ud):
    y = carray(data_of(yy), 2, dtype=numpy.float64)
    r = carray(data_of(rr), 9, dtype=numpy.float64)
    s = 0.0
    for k in range(2):
        s += y[k]
    _at(t, y, r, numpy.int64(0))
    r[0] += s
    return 0

CFUNCS['entry'] = 'RES'
'''
EDGE_INPUTS = [(0.3, 2.0), (-1.5, 0.7), (2.0, 3.0), (0.0, -0.0), (-0.0, 1e-300), (1e308, 2.5),
               (float("nan"), 1.0), (1.0, float("nan")), (float("inf"), -2.0), (-7.25, 0.0),
               (5e-324, -3.5), (1.5, 1.5)]


def _vector(x: np.ndarray):
    """A SUNDIALS serial vector as the kernels read it: its content's data pointer 8 bytes in."""
    content = (ctypes.c_char * 16)()
    ctypes.c_void_p.from_buffer(content, 8).value = x.ctypes.data
    return ctypes.c_void_p(ctypes.addressof(content)), content


def _call(address: int, y: np.ndarray, n_out: int) -> np.ndarray:
    r = np.full(n_out, -99.0)
    vy, vr = _vector(y), _vector(r)
    fn = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_double, *[ctypes.c_void_p] * 4)(address)
    assert fn(0.0, ctypes.addressof(vy[0]), None, ctypes.addressof(vr[0]), None) == 0
    return r


@pytest.fixture
def folder(tmp_path, monkeypatch):
    monkeypatch.setenv("CIRCUITSIM_CACHE", str(tmp_path))
    return tmp_path


def _edges_module(folder):
    from circuitsim.solve import direct, kernel_lib

    source = EDGES.format(lib=kernel_lib.KERNEL_LIB)
    return source, direct.kernel_module(folder, source)


def test_the_c_library_computes_what_numba_computes_to_the_bit(folder):
    """Every construct of the subset, on ordinary and edge values (signed zeros, a
    subnormal, infinities, NaN in each place): the C library's outputs are numba's, bit for
    bit (a NaN's sign aside), and numba's are Python's own arithmetic."""
    import numba

    from circuitsim.solve import ccode, direct

    if ccode.compiler() is None:
        pytest.skip("no C compiler on this machine: numba compiles every module")
    source, module = _edges_module(folder)
    lib = ccode.library(folder, source)
    assert lib is not None, "the edges module is inside the subset and must compile"
    c_entry = ccode.Entry(lib, "entry").address
    nb_entry = numba.cfunc(module.RES, **direct.CFUNC_OPTIONS)(module.entry).address
    for y0, y1 in EDGE_INPUTS:
        y = np.array([y0, y1])
        with np.errstate(all="ignore"):
            a, b = _call(nb_entry, y, 9), _call(c_entry, y, 9)
        # bit for bit, but a NaN's sign: glibc's log(-1.5) is -NaN, numba's own domain
        # check returns +NaN; either fails IDA's step alike
        same_nan = np.isnan(a) & np.isnan(b)
        assert np.array_equal(np.isnan(a), np.isnan(b)), (y0, y1, a, b)
        assert a[~same_nan].tobytes() == b[~same_nan].tobytes(), (y0, y1, a, b)
    # numba's output is Python's: true division, max and min of Python, the conditionals
    y0, y1 = -1.5, 0.7
    a = _call(nb_entry, np.array([y0, y1]), 9)
    assert a[0] == (1 / 2) * y0 + 3 / 4 + (y0 + y1)
    assert a[1] == max(0, y0) and a[2] == min(y1, 0, y0)
    assert a[3] == (y0 + 1 if y0 < -y1 else y1 - 2 if y1 > 1.5 else 0)
    assert a[6] == -1 * y0 / y1 + int(y1) + float(2)
    assert a[8] == -1.0 and math.isnan(a[7])


@pytest.mark.parametrize("body", [
    "    x = y[0] ** 2",  # a power not turned into libm_pow
    "    x = y[0] // 2",  # floor division: Python's and C's differ on negatives
    "    x = y[0] % 2.0",
    "    x = y[0] and y[1]",  # Python's and gives an operand, not a truth value
    "    while y[0] > 0:\n        pass",
    "    x = numpy.sin(y[0])",
    "    x = GLOBAL_SCALE * y[0]",  # a module name the subset does not know
])
def test_a_module_outside_the_subset_is_left_to_numba(body):
    from circuitsim.solve import ccode

    source = (f"import numpy\nCFUNCS = {{}}\n\ndef entry(t, yy, ypv, rr, ud):\n"
              f"    y = carray(data_of(yy), 2, dtype=numpy.float64)\n{body}\n    return 0\n\n"
              f"CFUNCS['entry'] = 'RES'\n")
    assert ccode.translate(source) is None
    plain = source.replace(body, "    x = y[0]")
    assert ccode.translate(plain) is not None


def test_a_failing_compiler_leaves_the_module_to_numba(folder, monkeypatch, tmp_path):
    """A compiler that fails (here: one that exits 1) builds nothing; numba compiles the
    kernels and the run is the Python route's to the bit. ``off`` asks for numba."""
    from circuitsim.solve import ccode, direct

    monkeypatch.setenv("CIRCUITSIM_CC", "false")
    source, _ = _edges_module(folder)
    assert ccode.library(folder, source) is None
    assert not list(folder.glob("c*.so")) and not list(folder.glob("tmp*"))
    monkeypatch.setenv("CIRCUITSIM_CC", "off")
    assert ccode.compiler() is None and ccode.library(folder, source) is None
    monkeypatch.setattr(direct, "_LOADED", {})
    model = cs.compile(cs.load(NETLISTS / "kim2024" / "base.yaml"))
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "python")
    python = model.simulate(stop=0.02)
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "numba")
    kernels = model.simulate(stop=0.02)
    assert direct.c_library(direct._LOADED[model.key]) is None
    assert (python.nfev, python.njev) == (kernels.nfev, kernels.njev)
    assert np.array_equal(python.y, kernels.y) and np.array_equal(python.t, kernels.t)


def test_numba_and_the_c_library_give_the_same_runs(folder, monkeypatch, compile_text):
    """The same models on both compiled routes, each in a folder of its own: the same steps
    and numbers -- a motor with an EMF ripple and friction, and a 100-unknown ladder whose
    kernels carry the linear part as a sparse product and a varistor's powers."""
    from test_scale import rlc_ladder_with_a_nonlinear_load

    from circuitsim.solve import ccode, direct

    if ccode.compiler() is None:
        pytest.skip("no C compiler on this machine: numba compiles every module")
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "numba")
    models = [cs.compile(cs.load(NETLISTS / "kim2024" / "base.yaml")),
              compile_text(rlc_ladder_with_a_nonlinear_load(50))]
    runs = {}
    for cc in ("off", "on"):
        monkeypatch.setenv("CIRCUITSIM_CACHE", str(folder / cc))
        monkeypatch.setattr(direct, "_LOADED", {})
        if cc == "off":
            monkeypatch.setenv("CIRCUITSIM_CC", "off")
        else:
            monkeypatch.delenv("CIRCUITSIM_CC", raising=False)
        runs[cc] = [m.simulate(stop=0.01) for m in models]
        assert all((direct.c_library(direct._LOADED[m.key]) is None) == (cc == "off")
                   for m in models)
    for a, b in zip(runs["off"], runs["on"], strict=True):
        assert (a.nfev, a.njev) == (b.nfev, b.njev)
        assert np.array_equal(a.y, b.y) and np.array_equal(a.t, b.t)


def test_the_library_is_written_whole_with_the_umask(folder):
    """The library appears under its final name only when complete (built under a temporary
    name, then renamed), readable as the umask allows, and nothing else is left behind."""
    from circuitsim.solve import ccode

    if ccode.compiler() is None:
        pytest.skip("no C compiler on this machine: nothing is built")
    source, _ = _edges_module(folder)
    old = os.umask(0o027)
    try:
        assert ccode.library(folder, source) is not None
    finally:
        os.umask(old)
    built = list(folder.glob("c*.so"))
    assert len(built) == 1 and (built[0].stat().st_mode & 0o777) == 0o640
    assert not [p for p in folder.iterdir() if p.suffix == ".c" or p.name.startswith("tmp")]
    assert ccode.built(folder, source)
