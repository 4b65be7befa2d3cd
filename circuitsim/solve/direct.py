"""IDA calling compiled kernels directly: no Python per residual call (``pip install .[fast]``).

scikit-sundae calls the model through a Python callback, about 4.5 µs a call on top of the
residual's own arithmetic; that wrapper, not IDA, is most of a small model's solve. With numba
installed and ``CIRCUITSIM_KERNELS=numba`` set, a model whose generated module carries kernels
(``codegen._kernels``: the residual and the dense Jacobian as numba ``cfunc``s, compiled when a
solve first asks for them and kept by numba beside the model in the cache folder; the loop over
the output times, shared by every topology, is compiled once) is
integrated by the same IDA, scikit-sundae's bundled SUNDIALS libraries loaded with ctypes, with
the same options: the same steps and the same numbers, to the bit, many times faster
(``benchmarks/bench_compiled_route.py``). Importing numba and loading the kernels costs about
half a second per process, so it pays from a handful of solves in one process (sweeps,
scripts, fits); it is off by default. Batches of K members stacked in one band system
(``solve/batch.py``) run on stacked kernels. A model of 100 unknowns or more has kernels with
its Python route's arithmetic (the linear part as a CSR product, whose arrays travel in the
user data) and IDA gets the same linear solver as there: the dense one, or from 400 unknowns
SuperLU_MT on the Jacobian's compressed columns. A small model's run-time tables are
interpolated in the kernels on their points, which travel in the user data too. Models without
kernels (run-time tables at 100 unknowns or more) and large batches stay with scikit-sundae;
a batch of a model reading tables has stacked kernels that read the tables' points after the
members' parameters. A switching model (events, relations held between
roots: ``solve/events.py``) of fewer than 100 unknowns has its guards as a compiled root
function too (a table's rows are stops there as well), which IDA watches as scikit-sundae has
it watch the Python guards (every root terminal, falling through zero): the run stops at the
root, to the bit where the Python route stops. Where a C compiler is found, a kernel module is
built by it instead (``solve/ccode.py``: the same numbers, a tenth of numba's compile); IDA
takes that library's functions by address just the same.
"""

from __future__ import annotations

import ctypes
import functools
import hashlib
import importlib.util
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from circuitsim.solve.kernel_lib import ROOT_RETURN
from circuitsim.solve.route import kernels_requested


def wanted() -> bool:
    """Kernels asked for (``solve/route.py``) and numba installed."""
    return kernels_requested() and importlib.util.find_spec("numba") is not None


@dataclass
class Result:
    """What ``integrate`` reads of scikit-sundae's IDAResult."""

    t: np.ndarray
    y: np.ndarray
    yp: np.ndarray
    success: bool
    message: str
    nfev: int
    njev: int
    status: int = 0  # IDA's last flag (2: stopped at a root of the guards)
    i_events: np.ndarray | None = None  # at a root: one row, IDA's root information


@functools.cache
def _libraries() -> dict[str, Any]:
    """scikit-sundae's bundled SUNDIALS libraries, with the signatures used here, once checked
    to be the build the kernels read (``solve/sundials_libs.py``; else LibrariesUnavailable,
    whose message says why)."""
    from circuitsim.solve import sundials_libs
    from circuitsim.solve.sundae import ida_class

    ida_class()  # loaded with scikit-sundae's own modules (on Windows, its import adds the folder)
    from sksundae import _cy_common

    sundials_libs.check_build(getattr(_cy_common, "config", None))
    site = Path(importlib.util.find_spec("sksundae").origin).parent.parent
    lib = sundials_libs.load(sundials_libs.library_paths(site, sys.platform), sys.platform)
    sundials_libs.check_layouts(lib)
    # the compiled output loop calls IDASolve by name: given to LLVM by address, it does not
    # depend on the process-wide search that RTLD_GLOBAL offers on Linux and macOS only
    from llvmlite import binding

    binding.add_symbol("IDASolve", ctypes.cast(lib["ida"].IDASolve, ctypes.c_void_p).value)
    return lib


_LOADED: dict[str, Any] = {}
#: numba's options for every cfunc. They are part of a kernel module's name (``kernel_name``):
#: numba's cache key does not hold them, and machine code compiled with other options must
#: not be loaded for these.
CFUNC_OPTIONS: dict[str, Any] = {"cache": True, "error_model": "numpy"}


def _trusted_file(folder: Path, name: str, source: str) -> Path:
    """``name``.py in the cache folder holding ``source`` (written when absent or different)."""
    path = folder / f"{name}.py"
    if not path.exists() or path.read_text(encoding="utf-8") != source:
        from circuitsim.files import atomic_write

        atomic_write(path, source)
    return path


def _import(name: str, path: Path) -> Any:
    """The module at ``path`` under ``name``, registered before it runs: numba's kept code
    names the module's helpers by module name. One loaded from another cache folder (the
    process changed ``CIRCUITSIM_CACHE``) is replaced: its machine code is kept there."""
    held = sys.modules.get(name)
    if held is not None and Path(getattr(held, "__file__", "") or "") == path:
        return held
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[name]
        raise
    return module


def _kernel_lib(folder: Path) -> Any:
    """The helpers every topology's kernels import (``kernel_lib.SOURCE``): one file a
    version, so numba compiles the output loop and the tables' lookup once, not per topology."""
    from circuitsim.solve import kernel_lib

    name = kernel_lib.KERNEL_LIB
    return _import(name, _trusted_file(folder, name, kernel_lib.SOURCE))


def kernels(model) -> Any | None:
    """The model's compiled kernels (a module with ``residual`` and ``jacobian``), or None.

    The kernel source comes from the hash-checked cache entry; it is written beside it as a
    file so that numba can keep the machine code (in the folder's ``__pycache__``) for the next
    process. Only a folder the model cache trusts is used. Its cfuncs are compiled when first
    asked for (``cfunc``)."""
    from circuitsim.memo import open_cache_dir

    source = model.meta.get("kernels")
    if not source:
        return None
    if model.key in _LOADED:
        return _LOADED[model.key]
    folder, why = open_cache_dir()
    if why is not None:
        return None
    module = kernel_module(folder, source)
    _LOADED[model.key] = module
    return module


def kernel_name(source: str) -> str:
    """The name of a kernel module: a digest of its source and of numba's options. Topologies
    whose equations give the same code share one module and one compile -- a cogging or an
    EMF harmonic of another order (the order is a run-time parameter), one of two twin
    effects dropped."""
    text = f"{sorted(CFUNC_OPTIONS.items())!r}\n{source}"
    return "k" + hashlib.sha256(text.encode("utf-8")).hexdigest()[:24]


def kernel_module(folder: Path, source: str) -> Any:
    """The kernel module of ``source``, written into the trusted cache ``folder`` and
    imported from there (once a process: models of the same code share it, and the cfuncs
    it holds)."""
    _kernel_lib(folder)
    name = kernel_name(source)
    return _import(f"circuitsim_kernels_{name}", _trusted_file(folder, f"{name}_kernels", source))


def cfunc(module, name: str) -> Any:
    """The kernel ``name`` of a kernel module as a numba cfunc of its signature (compiled, or
    loaded from numba's kept code, on the first request; then held by the module)."""
    held = module.__dict__.setdefault("_COMPILED", {})
    if name not in held:
        lib = c_library(module)
        if lib is not None:
            from circuitsim.solve.ccode import Entry

            held[name] = Entry(lib, name)
            return held[name]
        import numba

        sig = getattr(module, module.CFUNCS[name])
        held[name] = numba.cfunc(sig, **CFUNC_OPTIONS)(getattr(module, name))
    return held[name]


def c_library(module) -> Any | None:
    """The kernel module compiled by the C compiler (``solve/ccode.py``: the same numbers
    for a tenth of numba's compile), built once a process and kept beside it; None when
    numba compiles it."""
    if "_C_LIBRARY" not in module.__dict__:
        from circuitsim.solve import ccode

        path = Path(module.__file__)
        module._C_LIBRARY = ccode.library(path.parent, path.read_text(encoding="utf-8"))
    return module._C_LIBRARY


def _kept(module, name: str) -> bool:
    """Whether numba keeps machine code of the module's function ``name`` in the cache."""
    path = Path(module.__file__)
    return any((path.parent / "__pycache__").glob(f"{path.stem}.{name}-*.nbi"))


#: (lend, claim) of the compile-ahead worker once one runs (``solve/ahead.py`` sets them:
#: it imports this module, not the other way round)
_LENDER: list[tuple[Callable, Callable]] = []


def lend_to(lend: Callable[..., list[str] | None], claim: Callable[[str], None]) -> None:
    """Hand kernels to ``lend`` (kernel source, lists of names -> a job for each, or None)
    while this process compiles others; ``claim`` (a job) before using them."""
    _LENDER[:] = [(lend, claim)]


#: a model's kernels of one member, lent to the worker when a batch first asks for the stacked
#: ones: the screen re-steps a candidate alone in its joint model soon after (Jacobian and
#: root function first: their bodies are the worker's own by then, the residual's this one's)
_SINGLES = ("jacobian", "roots", "residual")


def _compile_shared(module, model, names: tuple[str, ...]) -> None:
    """The cfuncs ``names`` of a model's kernels. The residual's and the Jacobian's are
    compiled from functions of their own, and a Jacobian not kept yet is lent to the
    compile-ahead worker (``lend_to``) while this process compiles the residual: numba keeps
    it in the cache both share, and it is loaded from there (or compiled here when the worker
    had not started on it). A batch's stacked kernels lend the single member's too, for later
    (``_SINGLES``), claimed when asked for."""
    if c_library(module) is not None:  # the whole module is one compile: nothing to lend
        for name in names:
            cfunc(module, name)
        return
    held = module.__dict__.setdefault("_COMPILED", {})
    lent_before = module.__dict__.setdefault("_LENT", {})
    for name in names:
        if name in lent_before and _LENDER:
            _LENDER[0][1](lent_before.pop(name))
    todo = [n for n in names if n not in held and not _kept(module, n)]
    lent = [n for n in todo[1:] if n.startswith("jacobian") and not _kept(module, "_jacobian_at")]
    later = [n for n in _SINGLES if "residual_batch" in todo and n in module.CFUNCS
             and n not in held and n not in lent_before and not _kept(module, n)]
    jobs = _LENDER[0][0](model.meta["kernels"], lent, later) if (lent or later) and _LENDER \
        else None
    if jobs and later:
        lent_before.update(dict.fromkeys(later, jobs[-1]))
    if jobs and lent:  # what is not lent, here meanwhile; then the lent, from the cache
        for name in todo:
            if name not in lent:
                cfunc(module, name)
        _LENDER[0][1](jobs[0])
    for name in names:
        cfunc(module, name)


class DirectIDA:
    """IDA with the kernels of one model: the part of scikit-sundae's ``IDA`` that
    ``integrate`` uses (``solve`` over a time span), with the same options."""

    def __init__(self, module, opts: dict, members: list | None = None,
                 data: np.ndarray | None = None, kind: str = "dense", watch: Any = None):
        self.module, self.opts = module, opts
        # the run's runaway watch (solve/watch.py), told IDA's evaluations as it goes
        self.watch = watch
        # one model, or K members stacked (solve/batch.py: band solver, K parameter vectors)
        self.members = members
        # a large model's user data (parameters, then its linear part's CSR arrays) and the
        # linear solver: 'dense', 'band' (a batch) or 'sparse' (SuperLU_MT)
        self.data, self.kind = data, kind

    def solve(self, tspan, y0, yp0) -> Result:
        """Outputs at ``tspan[1:]`` (a two-point span: the end only), stopping at its end."""
        lib, tspan = _libraries(), np.asarray(tspan, dtype=float)
        ctx = ctypes.c_void_p()
        lib["core"].SUNContext_Create(0, ctypes.byref(ctx))
        lib["core"].SUNContext_ClearErrHandlers(ctx)  # failures are reported in the Result
        held = self._setup(lib, ctx, tspan[0], y0, yp0)
        try:
            return self._run(lib, held, tspan)
        finally:
            self._free(lib, ctx, held)

    def _setup(self, lib, ctx, t0: float, y0, yp0) -> dict:
        """The SUNDIALS objects of one solve, set up as scikit-sundae sets them (its defaults
        are SUNDIALS' own: 4 Newton iterations, 10 convergence failures, order 5)."""
        core, ida, n, o = lib["core"], lib["ida"], len(y0), self.opts
        h: dict[str, Any] = {"n": n, "module": self.module}
        h["yy"], h["yp"], h["id"] = (lib["nvecserial"].N_VNew_Serial(n, ctx) for _ in range(3))
        for name, vec, value in (("Y", "yy", y0), ("YP", "yp", yp0), ("ID", "id", 1.0)):
            h[name] = np.ctypeslib.as_array(core.N_VGetArrayPointer(h[vec]), (n,))
            h[name][:] = value
        h["ID"][list(o.get("algebraic_idx") or [])] = 0.0
        h["p"], residual, jacobian = self._kernels_and_data()
        mem = h["mem"] = ctypes.c_void_p(ida.IDACreate(ctx))
        ida.IDASetUserData(mem, h["p"].ctypes.data)
        ida.IDAInit(mem, residual.address, float(t0), h["yy"], h["yp"])
        h["A"], h["LS"] = self._matrix(lib, ctx, h["yy"], n)
        ida.IDASetLinearSolver(mem, h["LS"], h["A"])
        ida.IDASetJacFn(mem, jacobian.address)
        ida.IDASStolerances(mem, float(o["rtol"]), float(o["atol"]))
        ida.IDASetId(mem, h["id"])
        ida.IDASetMaxStep(mem, float(o.get("max_step") or 0.0))
        ida.IDASetMaxNumSteps(mem, int(o.get("max_num_steps", 500)))
        if o.get("eventsfn") is not None:  # the guards, as scikit-sundae hands them to IDA
            h["roots"] = np.zeros(int(o["num_events"]), dtype=np.intc)
            h["direction"] = np.asarray(o["eventsfn"].direction, dtype=np.intc)
            ida.IDARootInit(mem, h["roots"].size, cfunc(self.module, "roots").address)
            ida.IDASetRootDirection(mem, h["direction"].ctypes.data)
        return h

    def _matrix(self, lib, ctx, yy, n: int) -> tuple[Any, Any]:
        """IDA's matrix and linear solver, as scikit-sundae makes them for these options."""
        if self.kind == "dense":
            a = lib["sunmatrixdense"].SUNDenseMatrix(n, n, ctx)
            return a, lib["sunlinsoldense"].SUNLinSol_Dense(yy, a, ctx)
        if self.kind == "band":
            o = self.opts
            a = lib["sunmatrixband"].SUNBandMatrix(n, o["uband"], o["lband"], ctx)
            return a, lib["sunlinsolband"].SUNLinSol_Band(yy, a, ctx)
        # compressed columns (CSC_MAT = 0); one thread, scikit-sundae's default
        a = lib["sunmatrixsparse"].SUNSparseMatrix(n, n, self.module.JAC_ROWS.size, 0, ctx)
        return a, lib["sunlinsolsuperlumt"].SUNLinSol_SuperLUMT(yy, a, 1, ctx)

    def _kernels_and_data(self) -> tuple[np.ndarray, Any, Any]:
        """The user data (the parameters; for a batch K, then each member's; for a large
        model its CSR arrays after them) and the two kernels. At least one entry: the kernels
        read p[0] when a model has none."""
        residual, jacobian = (cfunc(self.module, name) for name in _used(self.kind))
        if self.data is not None:
            return self.data, residual, jacobian
        if self.members is None:
            p = list(self.opts["userdata"])
            return np.array(p + [0.0] * (not p), dtype=float), residual, jacobian
        data = [float(len(self.members))] + [v for q in self.members for v in q]
        return np.array(data, dtype=float), residual, jacobian

    def _run(self, lib, h: dict, tspan: np.ndarray) -> Result:
        from circuitsim.solve.sundae import ida_messages

        ida, n = lib["ida"], h["n"]
        # a table's rows inside the span are stops (``opts["stops"]``, integrate.table_rows):
        # IDA is stopped exactly at each and goes on without a restart, as the Python route's
        # step loop does; they are stepped to like output times and dropped after
        rows = np.asarray(self.opts.get("stops", ()), dtype=float)
        # a row a rounding away from an output time or the span's ends (0.1 ms + 0.2 ms) is
        # that time: as two stops, IDA would be asked for a step of a few ulps, which it
        # answers with the time it stands at (the output time is lost) or fails
        near = np.clip(np.searchsorted(tspan, rows), 1, max(tspan.size - 1, 1))
        near = np.where(np.abs(tspan[near - 1] - rows) < np.abs(tspan[near] - rows),
                        near - 1, near)
        same = np.abs(tspan[near] - rows) <= 1e-12 * np.maximum(np.abs(rows), 1e-300)
        rows = np.where(same, tspan[near], rows)
        rows = rows[(rows > tspan[0]) & (rows < tspan[-1])]
        times = np.union1d(tspan[1:], rows)
        times = np.concatenate([tspan[:1], times])
        ends = np.append(np.searchsorted(times, rows), times.size - 1)
        out_y, out_yp = np.empty((times.size, n)), np.empty((times.size, n))
        out_t = np.empty(times.size)
        out_t[0], out_y[0], out_yp[0] = times[0], h["Y"], h["YP"]
        done, flag = 1, 0
        for end in ends:
            ida.IDASetStopTime(h["mem"], float(times[end]))
            done, flag = self._to(lib, h, times, done, end, (out_t, out_y, out_yp))
            if flag < 0 or flag == ROOT_RETURN:
                break
        keep = np.isin(out_t[:done], tspan)
        keep[0] = True
        events = None
        if flag == ROOT_RETURN:  # the root is the last row, as scikit-sundae appends it
            keep[done - 1] = True
            ida.IDAGetRootInfo(h["mem"], h["roots"].ctypes.data)
            events = h["roots"][None, :].copy()
        counts = [ctypes.c_long(), ctypes.c_long()]
        ida.IDAGetNumResEvals(h["mem"], ctypes.byref(counts[0]))
        ida.IDAGetNumJacEvals(h["mem"], ctypes.byref(counts[1]))
        return Result(out_t[:done][keep], out_y[:done][keep], out_yp[:done][keep], flag >= 0,
                      ida_messages().get(flag, f"IDA flag {flag}"), counts[0].value,
                      counts[1].value, flag, events)

    def _to(self, lib, h: dict, times: np.ndarray, done: int, end: int,
            out: tuple[np.ndarray, np.ndarray, np.ndarray]) -> tuple[int, int]:
        """Step to the output times up to ``times[end]`` in the compiled loop (2 µs an
        output time in Python), the rows filled after ``done``; a watched run in groups of
        about WINDOW evaluations, the watch told after each. The rows filled and IDA's flag."""
        from circuitsim.solve import kernel_lib
        from circuitsim.solve.watch import WINDOW

        outputs = sys.modules[kernel_lib.KERNEL_LIB].outputs
        out_t, out_y, out_yp = out
        group = end - done + 1 if self.watch is None else h.get("group", 16)
        while True:
            last = min(end, done - 1 + group)
            k, flag = outputs(h["mem"].value, h["yy"], h["yp"], times[done - 1:last + 1],
                              h["Y"], h["YP"], out_t[done - 1:], out_y[done - 1:],
                              out_yp[done - 1:])
            done += k - 1
            if self.watch is not None:
                count = ctypes.c_long()
                lib["ida"].IDAGetNumResEvals(h["mem"], ctypes.byref(count))
                evals, h["evals"] = count.value - h.get("evals", 0), count.value
                # the next group: about one window's evaluations at this group's rate
                group = h["group"] = int(np.clip(WINDOW * max(k - 1, 1) / max(evals, 1),
                                                 1, 4096))
                self.watch.advance(evals, float(out_t[done - 1]), h["Y"], h["YP"])
            if flag < 0 or flag == ROOT_RETURN or done > end:
                return done, flag

    @staticmethod
    def _free(lib, ctx, h: dict) -> None:
        lib["ida"].IDAFree(ctypes.byref(h["mem"]))
        lib["core"].SUNLinSolFree(h["LS"])
        lib["core"].SUNMatDestroy(h["A"])
        for vec in ("yy", "yp", "id"):
            lib["core"].N_VDestroy(h[vec])
        lib["core"].SUNContext_Free(ctypes.byref(ctx))


def ida_for(opts: dict, watch: Any = None) -> DirectIDA | None:
    """A DirectIDA for ``opts["kernels_of"]`` = (model, None) or, for a stacked batch, (model,
    members' parameter vectors) when kernels are wanted, the model has them and they fill
    the matrix of the linear solver the Python route would use, else None (also when they
    cannot be built or the libraries cannot serve them: the Python route then runs, with one
    warning a process for each reason). ``watch``: the run's runaway watch, if it has one."""
    model, members = opts["kernels_of"]
    if not wanted():
        return None
    try:
        module = kernels(model)
        if opts.get("eventsfn") is not None and not _roots_served(module, members, opts):
            return None
        # found in the wheel layouts of Linux, macOS and Windows, and checked to be the build
        # the kernels read (solve/sundials_libs.py); otherwise this raises, naming why
        _libraries()
        kind = _kind(module, model, members, opts.get("linsolver"))
        data = None
        if kind is not None and members is None and hasattr(module, "LINEAR"):
            data = _large_data(module, model, opts["userdata"])
        elif kind is not None and hasattr(module, "TABLES"):
            data = (_table_data(model, opts["userdata"]) if members is None else
                    _with_tables([float(len(members))] + [v for q in members for v in q],
                                 model.table_points()))
        if kind is not None:  # compiled here, where a failure means the Python route
            _compile_shared(module, model, _used(kind, opts))
    except Exception as exc:  # noqa: BLE001 - numba and the libraries fail in many ways
        _LOADED[model.key] = None
        _warn_once(exc)
        return None
    if module is None or kind is None:
        return None
    return DirectIDA(module, opts, members, data, kind, watch)


#: the refusals warned about in this process: a run asks once per segment, and a process runs
#: many models, but a reason is worth one warning
_WARNED: set[str] = set()


def _warn_once(exc: Exception) -> None:
    """Warn that the Python route runs instead, naming the reason, unless it was said before."""
    import warnings

    from circuitsim.errors import CircuitWarning

    why = (str(exc).strip().splitlines() or [""])[0][:200]
    message = (f"compiled kernels unavailable ({type(exc).__name__}: {why}); the Python "
               f"residual is used")
    if message not in _WARNED:
        _WARNED.add(message)
        warnings.warn(message, CircuitWarning, stacklevel=4)


def _used(kind: str, opts: dict | None = None) -> tuple[str, ...]:
    """The residual and Jacobian kernels IDA calls with the linear solver ``kind`` (and the
    root function, when ``opts`` hand IDA guards)."""
    used = {"dense": ("residual", "jacobian"), "sparse": ("residual", "jacobian_sparse"),
            "band": ("residual_batch", "jacobian_band")}[kind]
    return (*used, "roots") if opts and opts.get("eventsfn") is not None else used


def _roots_served(module, members, opts: dict) -> bool:
    """Whether the kernels watch the guards IDA is handed: a single model whose kernels carry
    the root function, with as many guards as the Python route watches, every one terminal
    as there."""
    if module is None or members is not None or not hasattr(module, "roots"):
        return False
    fn = opts["eventsfn"]
    return (module.N_ROOTS == int(opts["num_events"]) == len(fn.direction)
            and all(bool(x) for x in getattr(fn, "terminal", [True] * module.N_ROOTS)))


def _kind(module, model, members, linsolver: str | None) -> str | None:
    """The linear solver whose matrix the kernels fill, when it is the one the Python route
    takes (a size threshold changed after code generation: not)."""
    if module is None:
        return None
    if members is not None:
        return "band" if linsolver == "band" and hasattr(module, "residual_batch") else None
    if not hasattr(module, "LINEAR"):
        return "dense" if linsolver == "dense" else None
    has = "sparse" if hasattr(module, "jacobian_sparse") else "dense"
    return has if linsolver == has == model.linsolver else None


def _large_data(module, model, p) -> np.ndarray:
    """The user data of a large model's kernels: the parameters, then Ly's and Lyp's CSR
    arrays (index pointers, column indices, values) as float64, the very matrices the Python
    residual multiplies by."""
    matrices = getattr(model.fns[0], "matrices", None)
    if matrices is None:
        raise ValueError("the Python residual is not the sparse product the kernels repeat")
    n_p, ny, nyp = module.LINEAR
    ly, lyp = matrices(p)
    if (ly.nnz, lyp.nnz) != (ny, nyp):
        raise ValueError("the linear part's pattern differs from the kernels'")
    head = np.zeros(n_p)
    head[:len(p)] = p
    arrays = [head] + [a for m in (ly, lyp) for a in (m.indptr, m.indices, m.data)]
    return np.concatenate([np.asarray(a, dtype=float) for a in arrays])


def _table_data(model, p) -> np.ndarray:
    """The user data of kernels that read run-time tables: the parameters (at least one
    entry), the data's length, each table's start and number of points, then per table its
    x, its y and its slopes, the very numbers the Python route's tables interpolate with."""
    # the model itself, not its key: a key names a topology, and two netlists of one topology
    # may read different tables (the entry holds the model, so its id is not reused)
    key = (id(model), tuple(float(v) for v in p))
    if _TABLE_DATA.get("key") != key or _TABLE_DATA.get("model") is not model:
        _TABLE_DATA.update(key=key, model=model,
                           data=_with_tables(list(key[1] or (0.0,)), model.table_points()))
    return _TABLE_DATA["data"]


def _with_tables(head: list[float], tables) -> np.ndarray:
    """``head`` (the parameters: one model's, or K and each member's), the data's length,
    each table's start and number of points, then per table its x, its y and its slopes
    (one fewer than its points: the next table starts that much earlier than 3 x points)."""
    start = len(head) + 1 + 2 * len(tables)
    index, pieces, at = [], [], start
    for x, y, slopes in tables:
        index += [at, len(x)]
        pieces += [np.asarray(v, dtype=float) for v in (x, y, slopes)]
        at += len(x) + len(y) + len(slopes)
    return np.concatenate([np.asarray(head, dtype=float), np.array([at, *index], dtype=float),
                           *pieces])


#: the last model's table data, by model and parameters (one run asks per segment: built once)
_TABLE_DATA: dict[str, Any] = {}
