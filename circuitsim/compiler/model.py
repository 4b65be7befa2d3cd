"""Compile a netlist once per topology into a CompiledModel; parameters vary at run time.

Orchestrates graph -> mna -> structure -> codegen, with the generated module cached on disk
by topology. A CompiledModel is picklable (a sweep worker re-imports the cached module).
"""

from __future__ import annotations

import bisect
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from circuitsim.compiler import cache, codegen
from circuitsim.compiler.names import TIME_RATE
from circuitsim.errors import CircuitWarning, ParameterError
from circuitsim.netlist.load import Netlist
from circuitsim.solve.route import kernels_requested


def _near(name: str, options) -> str:
    import difflib

    close = difflib.get_close_matches(name, list(options), n=3, cutoff=0.5)
    return f" (did you mean {', '.join(close)}?)" if close else ""


# [unknowns] the sizes from which the residual's linear part is a sparse product and IDA
# factorises with SuperLU_MT (codegen writes the compiled kernels to match)
MATRIX_RESIDUAL_FROM = codegen.MATRIX_RESIDUAL_FROM
SPARSE_FROM = codegen.SPARSE_FROM


def _bind(raw, meta: dict, linsolver: str) -> tuple:
    """The generated functions with dense adapters where the caller wants matrices:
    (residual, jac, parts, observe, initial, parts_flat, jac_flat)."""
    residual, jac_flat, parts_flat, observe, initial, linear, rest = raw
    n = len(meta["states"])
    if n >= MATRIX_RESIDUAL_FROM:
        residual = _split_residual(linear, rest, meta, n)
    rows, cols = (np.asarray(a, dtype=np.intp) for a in meta["jac_pattern"])
    fy_idx = tuple(np.asarray(a, dtype=np.intp) for a in meta["fy_pattern"])
    fyp_idx = tuple(np.asarray(a, dtype=np.intp) for a in meta["fyp_pattern"])
    buf = np.zeros(rows.size)

    def jac_dense(t, y, yp, res, cj, JJ, p):
        jac_flat(t, y, yp, res, cj, buf, p)
        JJ[rows, cols] = buf

    def parts(t, y, yp, p):
        fy, fyp, ft = parts_flat(t, y, yp, p)
        Fy, Fyp = np.zeros((n, n)), np.zeros((n, n))
        Fy[fy_idx] = fy
        Fyp[fyp_idx] = fyp
        return Fy, Fyp, ft

    jac = jac_flat if linsolver == "sparse" else jac_dense
    return residual, jac, parts, observe, initial, parts_flat, jac_flat


def _split_residual(linear, rest, meta: dict, n: int):
    """F = Ly(p) y + Lyp(p) y' + rest(t, y, y', p) with the linear part as sparse matrix
    products: the same values as the generated scalar residual, at a cost that no longer
    grows by a line of Python per equation. The matrices are built once per parameter
    vector."""
    import scipy.sparse as sps

    (ri, ci), (rpi, cpi) = meta["ly_pattern"], meta["lyp_pattern"]
    mats: dict[tuple, tuple] = {}

    def matrices(p: tuple) -> tuple:
        got = mats.get(p)
        if got is None:
            if len(mats) > 64:  # a long fit: keep the memory bounded
                mats.clear()
            ly, lyp = linear(p)
            got = mats[p] = (sps.csr_matrix((ly, (ri, ci)), shape=(n, n)),
                             sps.csr_matrix((lyp, (rpi, cpi)), shape=(n, n)))
        return got

    def residual(t, y, yp, res, p):
        Ly, Lyp = matrices(p)
        res[:] = Ly @ y + Lyp @ yp
        rest(t, y, yp, res, p)

    residual.matrices = matrices  # the compiled kernels take the same (solve/direct.py)
    return residual


class _Table:
    """Scalar linear interpolation held at the ends; fast enough to call per residual."""

    def __init__(self, x: np.ndarray, y: np.ndarray):
        self.x, self.y = np.asarray(x, float), np.asarray(y, float)
        self.xl, self.yl = self.x.tolist(), self.y.tolist()
        self.slopes = (np.diff(self.y) / np.diff(self.x)).tolist()

    def __call__(self, t: float) -> float:
        k = bisect.bisect_right(self.xl, t) - 1
        if k < 0:
            return self.yl[0]
        if k >= len(self.slopes):
            return self.yl[-1]
        return self.yl[k] + self.slopes[k] * (t - self.xl[k])

    def slope(self, t: float) -> float:
        k = bisect.bisect_right(self.xl, t) - 1
        return self.slopes[k] if 0 <= k < len(self.slopes) else 0.0

    def vec(self, t):
        return np.interp(t, self.x, self.y)

    def vec_slope(self, t):
        return np.vectorize(self.slope)(t)


@dataclass
class CompiledModel:
    """Numeric callables of one topology plus the netlist that gives their parameters."""

    netlist: Netlist
    key: str
    meta: dict
    warnings: tuple[str, ...] = ()
    _fns: Any = field(default=None, repr=False)
    _event_fns: Any = field(default=None, repr=False)
    _crossing_fn: Any = field(default=None, repr=False)

    def __getstate__(self):
        return {"netlist": self.netlist, "key": self.key, "meta": self.meta,
                "warnings": self.warnings, "_fns": None, "_event_fns": None,
                "_crossing_fn": None}

    def __setstate__(self, state):
        self.__dict__.update(state)

    @property
    def fns(self):
        """(residual, jac, parts, observe, initial) bound to this netlist's tables.

        ``jac`` suits ``ida_options()``: a flat array in the pattern's compressed-column
        order for the sparse solver, the dense n x n matrix otherwise; ``parts`` returns
        dense dF/dy, dF/dy' and dF/dt (``sparse_parts`` the sparse ones)."""
        if self._fns is None:
            cached = cache.load_cached(self.key)
            if cached is None:  # another machine or a cleared cache: derive again
                fresh = compile(self.netlist, use_cache=True)
                cached = (cache.load_cached(fresh.key) or (None, None))
            module, _ = cached
            tables = [_Table(t.x, t.y) for c in self.netlist.components for t in c.tables]
            raw = module.make([t.__call__ for t in tables], [t.slope for t in tables],
                              [t.vec for t in tables], [t.vec_slope for t in tables])
            self._fns = _bind(raw, self.meta, self.linsolver)
            if self.meta.get("events"):
                self._event_fns = module.make_events([t.__call__ for t in tables],
                                                     [t.slope for t in tables])
            if self.meta.get("crossings"):
                self._crossing_fn = module.make_crossings([t.__call__ for t in tables],
                                                          [t.slope for t in tables])
        return self._fns[:5]

    def table_points(self) -> list[tuple[list[float], list[float], list[float]]]:
        """Each run-time table's x, y and slopes, the numbers the Python route interpolates
        with (the compiled kernels get the same: solve/direct.py)."""
        tables = [_Table(t.x, t.y) for c in self.netlist.components for t in c.tables]
        return [(tab.xl, tab.yl, tab.slopes) for tab in tables]

    @property
    def event_fns(self):
        """(guards, jumps) of the switching events (see codegen._events), or None."""
        _ = self.fns
        return self._event_fns

    @property
    def crossing_fn(self):
        """``crossings(t, y, yp, p)`` of the held relations (see codegen._crossings), or None."""
        _ = self.fns
        return self._crossing_fn

    @property
    def linsolver(self) -> str:
        """IDA's linear solver for this model: 'sparse' (SuperLU_MT on the structural
        pattern) once the system is large enough for an O(n^3) dense LU to dominate, else
        'dense' (SuperLU_MT's fixed cost per factorisation is larger below ~400 unknowns)."""
        n = len(self.meta["states"])
        return "sparse" if n >= SPARSE_FROM and "jac_pattern" in self.meta else "dense"

    def ida_options(self) -> dict[str, Any]:
        """Linear-solver options for ``sksundae.ida.IDA`` matching ``fns``' ``jac``."""
        _, jac, *_ = self.fns
        if self.linsolver == "dense":
            opts = {"linsolver": "dense", "jacfn": jac}
            if kernels_requested():  # IDA may call compiled kernels
                opts["kernels_of"] = (self, None)  # (solve/direct.py)
            return opts
        import scipy.sparse as sps

        rows, cols = self.meta["jac_pattern"]
        n = len(self.state_names)
        pattern = sps.csc_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
        pattern.sort_indices()
        opts = {"linsolver": "sparse", "sparsity": pattern, "jacfn": jac}
        if kernels_requested():  # IDA may call compiled kernels (solve/direct.py)
            opts["kernels_of"] = (self, None)
        return opts

    @property
    def jac_flat(self):
        """The Jacobian kernel filling a flat array in ``meta["jac_pattern"]`` order,
        whatever the linear solver (a batch stacks these blocks)."""
        _ = self.fns
        return self._fns[6]

    def sparse_parts(self, t: float, y, yp, p):
        """dF/dy and dF/dy' as scipy CSC matrices, and dF/dt (for large systems)."""
        import scipy.sparse as sps

        _ = self.fns
        fy, fyp, ft = self._fns[5](t, y, yp, p)
        n = len(self.state_names)
        (ri, ci), (rp, cp) = self.meta["fy_pattern"], self.meta["fyp_pattern"]
        return (sps.csc_matrix((fy, (ri, ci)), shape=(n, n)),
                sps.csc_matrix((fyp, (rp, cp)), shape=(n, n)), ft)

    @property
    def state_names(self) -> tuple[str, ...]:
        return tuple(self.meta["states"])

    @property
    def probe_names(self) -> tuple[str, ...]:
        return tuple(self.meta["observed"][: self.meta["n_probes"]])

    @property
    def shafts(self) -> tuple[str, ...]:
        return tuple(n for n, (d, _) in self.netlist.nodes.items()
                     if d == "rotational" and n != "fixed")

    def param_values(self, overrides: Mapping[str, float] | None = None) -> dict[str, float]:
        """Every run-time parameter [SI] by name, with ``overrides`` applied and validated.

        An override may name a netlist parameter (``La``) or a component parameter
        (``Ra.R``).
        """
        overrides = dict(overrides or {})
        names = self.meta["params"]
        settable = [n for n in names if n != TIME_RATE]  # the analyses set it, never a user
        unknown = [k for k in overrides if k not in self.netlist.parameters and
                   k not in settable]
        if unknown:
            raise ParameterError(f"unknown parameter '{unknown[0]}'"
                                 f"{_near(unknown[0], [*self.netlist.parameters, *settable])}; "
                                 f"`circuitsim check NETLIST` lists them", None)
        glob = {k: v for k, v in overrides.items() if k in self.netlist.parameters}
        env = self.netlist.global_values(glob)
        values: dict[str, float] = {}
        for comp in self.netlist.components:
            for name, val in comp.values.items():
                values[name] = float(overrides[name]) if name in overrides else val.si(env)
                why = val.param.violation(values[name])
                if why:
                    raise ParameterError(f"{name} = {values[name]:g} [{val.unit}]: {why}",
                                         val.loc, comp.name)
        for c in self.meta.get("crossings", ()):  # relations evaluated as written
            values[c["name"]] = -1.0
        if TIME_RATE in names:
            values[TIME_RATE] = 1.0
        return values

    def frozen_vector(self, overrides: Mapping[str, float] | None = None) -> tuple[float, ...]:
        """The parameter vector with time frozen: every explicit time derivative (a source's
        rate of change in a differentiated equation) is zero, as at a DC operating point."""
        values = self.param_values(overrides)
        if TIME_RATE in values:
            values[TIME_RATE] = 0.0
        return tuple(values[n] for n in self.meta["params"])

    def param_vector(self, overrides: Mapping[str, float] | None = None) -> tuple[float, ...]:
        values = self.param_values(overrides)
        return tuple(values[n] for n in self.meta["params"])

    def physics_warnings(self, values: Mapping[str, float]) -> list[str]:
        out = []
        own: dict[str, dict[str, float]] = {}  # component -> its own scalar values
        for name, v in values.items():
            comp_name, _, key = name.rpartition(".")
            own.setdefault(comp_name, {})[key] = v
        for comp in self.netlist.components:
            local: dict[str, Any] = dict(comp.structure)
            local.update(own.get(comp.name, {}))
            for k, n in comp.structure.items():
                if isinstance(n, int) and not isinstance(n, bool):
                    local[k] = [None] * n
            inst = comp.cls(comp.name, local)
            out += [f"{comp.name}: {w}" for w in inst.warnings(local)]
        return out

    def simulate(self, stop: float | None = None, params: Mapping[str, float] | None = None,
                 **kw):
        """Transient from rest (or ``init='op'``); see integrate.simulate for the options."""
        from circuitsim.solve.integrate import simulate

        return simulate(self, stop=stop, params=params, **kw)


def compile(net: Netlist, use_cache: bool = True) -> CompiledModel:
    """Derive (or fetch from the cache) the compiled model of a netlist's topology."""
    key = cache.cache_key(net.topology_key())
    cached = cache.load_cached(key) if use_cache else None
    if cached is not None:
        _, meta = cached
        model = CompiledModel(net, key, meta)
    else:
        from circuitsim.compiler import graph, mna, structure

        cg = graph.build(net)
        dae = mna.assemble(net)
        nominal = {}
        probe = CompiledModel(net, key, {"params": [p.name for p in dae.params],
                                         "crossings": _modes(dae)})
        values = probe.param_values()
        for p in dae.params:
            nominal[p] = values[p.name]
        idx1 = structure.reduce_index(dae, nominal)
        source, meta = codegen.generate(idx1)
        meta["graph_warnings"] = list(cg.warnings)
        cache.store(key, source, meta)
        model = CompiledModel(net, key, meta)
    warn = model.physics_warnings(model.param_values())
    for w in warn:
        warnings.warn(w, CircuitWarning, stacklevel=2)
    model.warnings = tuple(warn)
    return model


def _modes(dae) -> list[dict]:
    """The held relations' mode parameters, named as ``param_values`` expects them."""
    return [{"name": c.mode.name} for c in dae.crossings]


def derive(net: Netlist):
    """The symbolic DAE and its index-1 form (for ``circuitsim equations``/``check``)."""
    from circuitsim.compiler import graph, mna, structure

    cg = graph.build(net)
    dae = mna.assemble(net)
    probe = CompiledModel(net, "", {"params": [p.name for p in dae.params],
                                    "crossings": _modes(dae)})
    values = probe.param_values()
    idx1 = structure.reduce_index(dae, {p: values[p.name] for p in dae.params})
    return cg, dae, idx1
