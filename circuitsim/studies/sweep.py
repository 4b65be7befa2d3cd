"""Topology and parameter sweeps: compile each netlist once, vary the parameter vector.

A sweep is a list of runs (netlist x grid point). Runs go to any
``concurrent.futures.Executor`` — local processes by default, or a ``dask.distributed``
client's executor for a cluster — and come back as rows of a tidy table: the swept values,
the metrics asked for, the solver status. Rows are appended to the output CSV as runs finish,
so a killed sweep loses nothing finished, and ``resume`` skips what the file already holds.
A failed run is a row with its status and message, never a crashed sweep.
"""

from __future__ import annotations

import csv
import itertools
import math
import os
import sys
import time
import warnings
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures import Executor, ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from circuitsim.errors import CircuitsimError, ParameterError


def parse_range(text: str, unit: str | None = None, dim=None) -> list[float]:
    """Values of a sweep axis: ``1e-9..1e-1:log:9``, ``0..1:lin:5``, or ``1,2,5`` [SI].

    A value written with a unit is checked against ``unit`` (a unit string) or ``dim`` (a
    units.Dim); a SPICE multiplier scales the number (``10k`` is 10 000; see
    ``units.spice_value`` for ``1F`` and ``1M``).
    """
    from circuitsim.netlist import expr as ex
    from circuitsim.units import compatible, explain_mismatch, spice_value, unit_info

    target = dim if dim is not None else (unit_info(unit)[1] if unit else None)

    def num(s: str) -> float:
        try:
            plain = spice_value(s, target)
            if plain is not None:
                return float(plain)
            node = ex.parse(s.strip())
            if ex.names(node):
                raise ex.ExprError("names are not allowed here", s, 0)
            value = ex.evaluate(node, {})
            got = ex.dimension(node, {})
        except (ex.ExprError, ValueError, KeyError, ZeroDivisionError) as exc:
            raise ParameterError(f"sweep value '{s}': {exc}") from None
        if node.kind == "unit" and target is not None and got is not None and \
                not compatible(got, target):
            raise ParameterError(f"value '{s.strip()}': "
                                 f"{explain_mismatch(got, target, unit or str(target))}")
        return value

    text = text.strip()
    if ".." in text:
        span, _, rest = text.partition(":")
        kind, _, count = rest.partition(":")
        lo_s, _, hi_s = span.partition("..")
        lo, hi = num(lo_s), num(hi_s)
        try:
            n = int(count or 11)
        except ValueError:
            raise ParameterError(f"sweep range '{text}': the count must be a whole number, as "
                                 f"in 1e-9..1e-1:log:9") from None
        if n < 1:
            raise ParameterError(f"sweep range '{text}' needs at least one point")
        if (kind or "lin") == "log":
            if lo <= 0 or hi <= 0:
                raise ParameterError(f"a log range needs positive ends: '{text}'")
            return [float(v) for v in np.logspace(math.log10(lo), math.log10(hi), n)]
        if (kind or "lin") != "lin":
            raise ParameterError(f"sweep range '{text}': spacing is 'lin' or 'log'")
        return [float(v) for v in np.linspace(lo, hi, n)]
    return [num(s) for s in text.split(",") if s.strip()]


def grid_points(grid: Mapping[str, Sequence[float]], mode: str = "product"
                ) -> list[dict[str, float]]:
    """Cartesian product (``product``) or element-wise (``zip``) combination of axes."""
    names = list(grid)
    axes = [list(grid[n]) for n in names]
    if not names:
        return [{}]
    if mode == "zip":
        if len({len(a) for a in axes}) != 1:
            raise ParameterError("zipped sweep axes must have the same length: " +
                                 ", ".join(f"{n} ({len(a)})" for n, a in zip(names, axes,
                                                                            strict=True)))
        combos: Iterable = zip(*axes, strict=True)
    elif mode == "product":
        combos = itertools.product(*axes)
    else:
        raise ParameterError(f"sweep mode is 'product' or 'zip', not {mode!r}")
    return [dict(zip(names, c, strict=True)) for c in combos]


@dataclass(frozen=True)
class Metrics:
    """What each run reports: probe means, ripple of an order, energy audit, timing."""

    probes: tuple[str, ...] | None = None  # None: every probe
    order: float | None = None  # harmonic order per shaft revolution; None: dominant ripple
    window: float = 0.2
    energy: bool = True


@dataclass(frozen=True)
class Run:
    netlist: str
    params: Mapping[str, float]
    stop: float | None
    options: Mapping[str, Any] = field(default_factory=dict)

    def key(self) -> tuple:
        return (self.netlist, *sorted((k, _fmt(v)) for k, v in self.params.items()))


def _fmt(v: float) -> str:
    return repr(float(v))


def _run_one(model, run: Run, metrics: Metrics) -> dict[str, Any]:
    """Worker: simulate one grid point and reduce it to a row (never raises)."""
    from circuitsim import signal
    from circuitsim.solve.energy import energy_audit

    row: dict[str, Any] = {"netlist": run.netlist, **run.params}
    t0 = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = model.simulate(stop=run.stop, params=run.params, **run.options)
    except CircuitsimError as exc:
        row.update(status="error", message=exc.bare, wall=time.perf_counter() - t0)
        return row
    row["wall"] = time.perf_counter() - t0
    row["status"] = "ok" if res.success else res.status.name.lower()
    row["message"] = "" if res.success else res.message
    if not res.success or res.t.size < 16:
        return row
    w = res.window(metrics.window)
    for name in metrics.probes or res.probes:
        x = res[name]
        try:
            if metrics.order is not None:
                h = res.harmonic(name, order=metrics.order, window=metrics.window)
            else:
                h = signal.dominant_ripple(res.t[w], x[w])
            row[f"{name}.mean"] = float(h.offset) if h.amplitude > 0 else float(x[w].mean())
            row[f"{name}.ripple_freq"] = float(h.frequency)
            row[f"{name}.ripple_amp"] = float(h.amplitude)
        except ValueError as exc:
            row[f"{name}.mean"] = float(x[w].mean())
            row["message"] = f"{name}: {exc}"
    if metrics.energy:
        a = energy_audit(res)
        row["energy.delivered"] = a.total_delivered
        row["energy.dissipated"] = sum(a.dissipated.values())
        row["energy.stored"] = sum(a.stored.values())
        row["energy.created"] = sum(a.created.values())
        row["energy.balance"] = a.balance
    return row


_LOCAL_MODELS: dict[str, Any] = {}


def _worker(model, run: Run, metrics: Metrics) -> dict[str, Any]:
    # One process serves many runs of the same topology: keep its generated code loaded.
    cached = _LOCAL_MODELS.setdefault(model.key + run.netlist, model)
    return _run_one(cached, run, metrics)


def _read_done(path: Path) -> tuple[list[dict[str, Any]], list[str]]:
    if not path.exists() or path.stat().st_size == 0:
        return [], []
    with open(path, newline="", encoding="utf-8") as fh:
        reader = csv.DictReader(fh)
        rows = [dict(r) for r in reader]
        return rows, list(reader.fieldnames or [])


def _run_key_from_row(row: Mapping[str, Any], names: Sequence[str]) -> tuple:
    return (row["netlist"], *sorted((k, _fmt(float(row[k]))) for k in names))


class _Writer:
    """Appends rows to a CSV as they arrive; the header grows a column when a row needs one
    (then the file is rewritten once, atomically)."""

    def __init__(self, path: Path | None, existing: list[dict], fields: list[str]):
        self.path = path
        self.rows = list(existing)
        self.fields = list(fields)

    def add(self, row: dict[str, Any]) -> None:
        self.rows.append(row)
        if self.path is None:
            return
        new = [k for k in row if k not in self.fields]
        if new or not self.path.exists():
            self.fields += new
            tmp = self.path.with_name(f".{self.path.name}.tmp")
            with open(tmp, "w", newline="", encoding="utf-8") as fh:
                w = csv.DictWriter(fh, self.fields)
                w.writeheader()
                w.writerows(self.rows)
            os.replace(tmp, self.path)
            return
        with open(self.path, "a", newline="", encoding="utf-8") as fh:
            csv.DictWriter(fh, self.fields).writerow(row)
            fh.flush()
            os.fsync(fh.fileno())


def sweep(netlists: str | Path | Sequence[str | Path],
          grid: Mapping[str, Sequence[float]] | None = None, *, mode: str = "product",
          metrics: Metrics | None = None, stop: float | None = None,
          executor: Executor | None = None, jobs: int | None = None,
          out: str | Path | None = None, resume: bool = False,
          progress: Callable[[int, int, dict], None] | None = None,
          allow_outside: bool = False, **sim_options: Any) -> list[dict[str, Any]]:
    """Run every netlist at every grid point; return one row (a dict) per run.

    Parameters
    ----------
    netlists : one or more netlist files; each topology is derived and compiled once.
    grid : parameter name -> values [SI] (see ``parse_range`` for the CLI syntax).
    mode : 'product' (Cartesian) or 'zip'.
    metrics : what each row reports (default: every probe, dominant ripple, energy audit).
    executor : any concurrent.futures.Executor (e.g. ``dask.distributed.Client(...)
        .get_executor()``); default: a local process pool of ``jobs`` workers (1: in-process).
    out : CSV file; rows are appended as runs finish. ``resume`` skips runs already in it.
    sim_options : passed to ``CompiledModel.simulate`` (rtol, atol, step, init, ...).
    """
    from circuitsim.compiler.model import compile as compile_model
    from circuitsim.netlist.load import load

    paths = [netlists] if isinstance(netlists, (str, Path)) else list(netlists)
    metrics = metrics or Metrics()
    models = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for p in paths:
            models[str(p)] = compile_model(load(p, allow_outside=allow_outside))
    points = grid_points(grid or {}, mode)
    for name in (grid or {}):
        for model in models.values():
            model.param_values({name: points[0][name]})  # unknown names fail before any run
    runs = [Run(str(p), pt, stop, dict(sim_options)) for p in paths for pt in points]
    out_path = Path(out) if out else None
    existing, fields = _read_done(out_path) if (out_path and resume) else ([], [])
    if out_path and not resume and out_path.exists():
        out_path.unlink()
    done = {_run_key_from_row(r, list(grid or {})) for r in existing if r.get("netlist")}
    todo = [r for r in runs if r.key() not in done]
    writer = _Writer(out_path, existing, fields or ["netlist", *(grid or {})])
    total = len(runs)
    count = total - len(todo)
    own_pool = None
    if executor is None and (jobs or 1) > 1 and len(todo) > 1:
        own_pool = ProcessPoolExecutor(max_workers=jobs)
        executor = own_pool
    try:
        if executor is None:
            for r in todo:
                row = _run_one(models[r.netlist], r, metrics)
                writer.add(row)
                count += 1
                if progress:
                    progress(count, total, row)
        else:
            futures = {executor.submit(_worker, models[r.netlist], r, metrics): r for r in todo}
            for fut in as_completed(futures):
                r = futures[fut]
                try:
                    row = fut.result()
                except Exception as exc:  # noqa: BLE001 - a worker crash is one failed row
                    row = {"netlist": r.netlist, **r.params, "status": "crashed",
                           "message": f"{type(exc).__name__}: {exc}"}
                writer.add(row)
                count += 1
                if progress:
                    progress(count, total, row)
    finally:
        if own_pool is not None:
            own_pool.shutdown(cancel_futures=True)
    order = {r.key(): i for i, r in enumerate(runs)}
    rows = [dict(r) for r in writer.rows]
    for r in rows:  # rows read back from a resumed file are strings: make numbers numeric
        for k, v in r.items():
            if isinstance(v, str) and k not in ("netlist", "status", "message"):
                try:
                    r[k] = float(v)
                except ValueError:
                    pass
    rows.sort(key=lambda r: order.get(_run_key_from_row(r, list(grid or {})), len(order)))
    return rows


def progress_bar(stream=sys.stderr) -> Callable[[int, int, dict], None]:
    """A one-line progress bar for the CLI."""
    start = time.perf_counter()

    def show(done: int, total: int, row: dict) -> None:
        width = 30
        filled = int(width * done / max(total, 1))
        el = time.perf_counter() - start
        status = row.get("status", "")
        stream.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total} "
                     f"{el:6.1f} s  last: {status:<8}")
        if done == total:
            stream.write("\n")
        stream.flush()

    return show


