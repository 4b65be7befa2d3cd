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
import time
import warnings
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures import Executor, ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from circuitsim.errors import CircuitsimError, ParameterError

#: More values than this on an axis, or runs in a grid, is a typo (1..2:lin:100000000 built a
#: list of 1e8 floats and then hung building the runs), not a study anyone can wait for.
MAX_POINTS = 100_000


def parse_range(text: str, unit: str | None = None, dim=None) -> list[float]:
    """Values of a sweep axis: ``1e-9..1e-1:log:9``, ``0..1:lin:5``, or ``1,2,5`` [SI].

    A value written with a unit is checked against ``unit`` (a unit string) or ``dim`` (a
    units.Dim); a SPICE multiplier scales the number (``10k`` is 10 000; see
    ``units.spice_value`` for ``1F`` and ``1M``).
    """
    from circuitsim.netlist.load import typed_value
    from circuitsim.units import unit_info

    target = dim if dim is not None else (unit_info(unit)[1] if unit else None)

    def num(s: str) -> float:
        try:
            value = typed_value(s, target, unit)
        except ValueError as exc:
            raise ParameterError(f"sweep value '{s.strip()}': {exc}") from None
        if not math.isfinite(value):
            raise ParameterError(f"sweep value '{s.strip()}' is {value}: give a finite number")
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
        if n > MAX_POINTS:
            raise ParameterError(f"sweep range '{text}': {n} points, more than "
                                 f"{MAX_POINTS}; ask for fewer")
        if (kind or "lin") == "log":
            if lo <= 0 or hi <= 0:
                raise ParameterError(f"a log range needs positive ends: '{text}'")
            return [float(v) for v in np.logspace(math.log10(lo), math.log10(hi), n)]
        if (kind or "lin") != "lin":
            raise ParameterError(f"sweep range '{text}': spacing is 'lin' or 'log'")
        return [float(v) for v in np.linspace(lo, hi, n)]
    items = text.split(",")
    if not any(s.strip() for s in items):
        raise ParameterError(f"sweep values '{text}' hold no value: give a list as 1,2,5 or "
                             f"a range as 1..10:lin:5")
    if not all(s.strip() for s in items):  # '1,2,,5': a value lost in typing, not skipped
        raise ParameterError(f"sweep values '{text}' hold an empty item: give a list as "
                             f"1,2,5")
    return [num(s) for s in items]


def grid_points(grid: Mapping[str, Sequence[float]], mode: str = "product"
                ) -> list[dict[str, float]]:
    """Cartesian product (``product``) or element-wise (``zip``) combination of axes."""
    names = list(grid)
    axes = [list(grid[n]) for n in names]
    if not names:
        return [{}]
    empty = [n for n, a in zip(names, axes, strict=True) if not a]
    if empty:
        raise ParameterError(f"sweep axis '{empty[0]}' has no value: give it at least one")
    if mode == "product" and math.prod(len(a) for a in axes) > MAX_POINTS:
        raise ParameterError(f"the sweep grid holds {math.prod(len(a) for a in axes)} runs, "
                             f"more than {MAX_POINTS}: fewer values, or --zip the axes")
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
    from circuitsim.solve.alias import Aliasing
    from circuitsim.solve.energy import energy_audit
    from circuitsim.solve.route import many_solves

    many_solves()  # a sweep's process solves its topology many times

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
    aliasing = Aliasing(res, metrics.window)
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
            # whether the window holds a periodic steady state at all (see ripple_summary):
            # the columns above fit a sine whatever the window holds
            row[f"{name}.ripple_state"] = signal.ripple_summary(res.t[w], x[w]).state
            alias = None if metrics.order is not None else aliasing.of(h.frequency)
            if alias is not None:  # the grid's line is not the circuit's (solve/alias.py)
                row[f"{name}.ripple_freq"] = alias.true
                row[f"{name}.ripple_state"] = "aliased"
                row["message"] = f"{name}: its ripple on the output grid is {alias.words()}"
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


class SweepError(CircuitsimError):
    """A sweep table cannot be resumed as asked (other settings, no settings file)."""


# A run whose worker process died (killed, out of memory, a crash in native code) is sent
# again this many times before it is written down as 'crashed'.
RETRIES = 2


def settings_path(out: Path) -> Path:
    """Where a table's settings live: beside it, ``TABLE.csv.settings.json``."""
    return out.with_name(out.name + ".settings.json")


def _digest(files: Sequence[str]) -> str:
    import hashlib

    h = hashlib.sha256()
    for f in files:
        h.update(Path(f).read_bytes())
    return h.hexdigest()[:16]


def _settings(models: Mapping[str, Any], grid: Mapping[str, Sequence[float]], mode: str,
              metrics: Metrics, stop: float | None, options: Mapping[str, Any]) -> dict:
    """What makes two tables comparable: the netlists' content, the axes, the run settings
    (not the grid values: a resumed sweep may add points)."""
    from dataclasses import asdict

    return {"netlists": {p: _digest(m.netlist.inputs) for p, m in models.items()},
            "axes": list(grid), "mode": mode, "stop": stop,
            "metrics": {k: list(v) if isinstance(v, tuple) else v
                        for k, v in asdict(metrics).items()},
            "options": {k: v for k, v in sorted(options.items())}}


def _check_settings(out: Path, settings: dict) -> None:
    import json

    side = settings_path(out)
    if not side.exists():
        raise SweepError(f"{out}: no settings file ({side.name}) beside the table, so a resume "
                         f"cannot tell whether it was made with the same netlists and options; "
                         f"run again without --resume")
    try:
        old = json.loads(side.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        old = None
    if old != json.loads(json.dumps(settings)):
        diff = sorted(k for k in settings if not isinstance(old, dict) or
                      old.get(k) != json.loads(json.dumps(settings[k])))
        raise SweepError(f"{out} was made with other settings ({', '.join(diff) or 'all'} "
                         f"differ: netlist content, axes, stop time, metrics or solver "
                         f"options); resuming would mix two sweeps. Run without --resume, or "
                         f"write to another --out")


def _read_done(path: Path) -> tuple[list[dict[str, Any]], list[str], bool]:
    """Rows of a table, its columns, and whether a torn last row (a kill mid-write) was cut."""
    if not path.exists() or path.stat().st_size == 0:
        return [], [], False
    text = path.read_text(encoding="utf-8")
    torn = not text.endswith("\n")
    if torn:  # the last line was cut mid-write: that run is not done
        text = text[:text.rfind("\n") + 1]
    reader = csv.DictReader(text.splitlines(keepends=True))
    fields = list(reader.fieldnames or [])
    rows = []
    for r in reader:
        if None in r or any(v is None for v in r.values()):  # too many or too few cells
            torn = True
            continue
        rows.append(dict(r))
    return rows, fields, torn


def _run_key_from_row(row: Mapping[str, Any], names: Sequence[str]) -> tuple | None:
    try:
        return (row["netlist"], *sorted((k, _fmt(float(row[k]))) for k in names))
    except (KeyError, TypeError, ValueError):
        return None


class _Writer:
    """Appends rows to a CSV as they arrive; the header grows a column when a row needs one
    (then the file is rewritten once, atomically)."""

    def __init__(self, path: Path | None, existing: list[dict], fields: list[str],
                 rewrite: bool = False):
        self.path = path
        self.rows = list(existing)
        self.fields = list(fields)
        if path is not None and rewrite:
            self._rewrite()

    def _rewrite(self) -> None:
        from circuitsim.files import atomic_write

        def write(tmp: str) -> None:
            with open(tmp, "w", newline="", encoding="utf-8") as fh:
                w = csv.DictWriter(fh, self.fields)
                w.writeheader()
                w.writerows(self.rows)

        atomic_write(self.path, write)  # type: ignore[arg-type]

    def add(self, row: dict[str, Any]) -> None:
        self.rows.append(row)
        if self.path is None:
            return
        new = [k for k in row if k not in self.fields]
        if new or not self.path.exists():
            self.fields += new
            self._rewrite()
            return
        try:
            with open(self.path, "a", newline="", encoding="utf-8") as fh:
                csv.DictWriter(fh, self.fields).writerow(row)
                fh.flush()
                os.fsync(fh.fileno())
        except OSError as exc:
            from circuitsim.files import OutputError

            raise OutputError(f"cannot append to the sweep table '{self.path}': "
                              f"{exc.strerror or exc}; the rows so far are kept, free space "
                              f"and run again with --resume") from None


def _compile_all(paths: Sequence[str | Path], grid: Mapping[str, Sequence[float]],
                 points: list[dict[str, float]], allow_outside: bool) -> dict[str, Any]:
    from circuitsim.compiler.model import compile as compile_model
    from circuitsim.netlist.load import load

    models = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for p in paths:
            models[str(p)] = compile_model(load(p, allow_outside=allow_outside))
    for name in grid:
        for model in models.values():
            model.param_values({name: points[0][name]})  # unknown names fail before any run
    return models


def _open_table(out: Path | None, resume: bool, settings: dict, axes: list[str]
                ) -> tuple[_Writer, set[tuple]]:
    """The writer for ``out`` and the keys of the runs it already holds. On resume, the
    settings must match, a torn last row is dropped and crashed runs are run again."""
    import json

    from circuitsim.files import atomic_write

    if out is None:
        return _Writer(None, [], ["netlist", *axes]), set()
    if resume and out.exists():
        _check_settings(out, settings)
        rows, fields, torn = _read_done(out)
        keep = [r for r in rows if r.get("status") != "crashed" and
                _run_key_from_row(r, axes) is not None]
        writer = _Writer(out, keep, fields or ["netlist", *axes],
                         rewrite=torn or len(keep) < len(rows))
        return writer, {_run_key_from_row(r, axes) for r in keep}  # type: ignore[misc]
    if out.exists():
        out.unlink()
    atomic_write(settings_path(out), json.dumps(settings, indent=1) + "\n")
    return _Writer(out, [], ["netlist", *axes]), set()


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
        .get_executor(retries=2)``, whose scheduler then retries the tasks of a lost worker);
        default: a local process pool of ``jobs`` workers (1: in-process). A run whose worker
        dies is sent again up to ``RETRIES`` times before it becomes a 'crashed' row.
    out : CSV file; rows are appended as runs finish, the settings are kept beside it
        (``settings_path``). ``resume`` skips runs already in it, runs crashed ones again,
        drops a torn last row, and refuses (SweepError) a table made with other settings.
    sim_options : passed to ``CompiledModel.simulate`` (rtol, atol, step, init, ...).
    """
    paths = [netlists] if isinstance(netlists, (str, Path)) else list(netlists)
    metrics = metrics or Metrics()
    grid = dict(grid or {})
    points = grid_points(grid, mode)
    models = _compile_all(paths, grid, points, allow_outside)
    runs = [Run(str(p), pt, stop, dict(sim_options)) for p in paths for pt in points]
    settings = _settings(models, grid, mode, metrics, stop, sim_options)
    writer, done = _open_table(Path(out) if out else None, resume, settings, list(grid))
    todo = [r for r in runs if r.key() not in done]
    state = {"count": len(runs) - len(todo), "total": len(runs)}

    def finished(row: dict[str, Any]) -> None:
        writer.add(row)
        state["count"] += 1
        if progress:
            progress(state["count"], state["total"], row)

    if executor is None and ((jobs or 1) <= 1 or len(todo) <= 1):
        for r in todo:
            finished(_run_one(models[r.netlist], r, metrics))
    else:
        _execute(todo, models, metrics, executor, jobs or 1, finished)
    return _ordered(runs, writer.rows, list(grid))


def _ordered(runs: list[Run], rows: list[dict], axes: list[str]) -> list[dict[str, Any]]:
    order = {r.key(): i for i, r in enumerate(runs)}
    out = [dict(r) for r in rows]
    for r in out:  # rows read back from a resumed file are strings: make numbers numeric
        for k, v in r.items():
            if isinstance(v, str) and k not in ("netlist", "status", "message"):
                try:
                    r[k] = float(v)
                except ValueError:
                    pass
    out.sort(key=lambda r: order.get(_run_key_from_row(r, axes), len(order)))
    return out


def _worker_init(parent: int) -> None:
    """In each pool worker: Ctrl-C is the parent's to handle (no worker tracebacks), and the
    worker ends when its parent is gone (a killed sweep leaves no orphans)."""
    import signal
    import threading

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    # a SIGTERM from _stop_pool must end the worker at once, also inside the integrator's C
    # code (a Python handler inherited from the parent would wait for it to return)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)

    def watch() -> None:
        while True:
            time.sleep(0.5)
            if os.getppid() != parent:
                os._exit(1)

    threading.Thread(target=watch, daemon=True).start()


def _new_pool(jobs: int) -> ProcessPoolExecutor:
    return ProcessPoolExecutor(max_workers=jobs, initializer=_worker_init,
                               initargs=(os.getpid(),))


def _stop_pool(pool: ProcessPoolExecutor) -> None:
    """Stop at once: cancel what has not started and end the workers (a run in progress
    would otherwise hold the exit for its whole duration)."""
    procs = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for p in procs:
        if p.is_alive():
            p.terminate()
    for p in procs:
        p.join(timeout=2)
        if p.is_alive():
            p.kill()
            p.join(timeout=2)


def _execute(todo: list[Run], models: Mapping[str, Any], metrics: Metrics,
             executor: Executor | None, jobs: int, finished: Callable[[dict], None]) -> None:
    """Run ``todo`` on ``executor`` (default: an own process pool), sending a run again when
    its worker died; a pool broken by a dead worker is replaced."""
    own = executor is None
    pool = _new_pool(jobs) if own else executor
    tries = {r.key(): 0 for r in todo}
    pending, isolate = list(todo), False
    try:
        while pending:
            # once a worker has died, one run at a time: a death then fails its own run
            # only, never the runs that happened to share the broken pool with it
            batches = [[r] for r in pending] if isolate else [pending]
            pending = []
            for batch in batches:
                failed, broken = _submit(pool, batch, models, metrics, finished)
                for r, exc in failed:
                    tries[r.key()] += 1
                    if tries[r.key()] <= RETRIES:
                        pending.append(r)
                        continue
                    finished({"netlist": r.netlist, **r.params, "status": "crashed",
                              "message": f"{type(exc).__name__}: {exc} (after {RETRIES} "
                                         f"retries)"})
                if broken and own:
                    _stop_pool(pool)  # type: ignore[arg-type]
                    pool, isolate = _new_pool(jobs), True
    except KeyboardInterrupt:
        if own:
            _exit_within(INTERRUPT_GRACE, 130)
        raise
    finally:
        if own:
            _stop_pool(pool)  # type: ignore[arg-type]


#: [s] how long an interrupted sweep may take to stop its pool and leave.
INTERRUPT_GRACE = 5.0


def _exit_within(seconds: float, code: int) -> None:
    """End the process after ``seconds`` whatever it is doing then. An interrupted pool can
    hang the exit: the interpreter joins the pool's manager thread at exit, and that thread
    may wait for ever on a worker the interrupt killed (seen once in about twenty Ctrl-Cs on a
    loaded machine). Every row already written is whole (each is written and flushed at
    once), so leaving then loses nothing the table holds."""
    import threading

    timer = threading.Timer(seconds, os._exit, args=(code,))
    timer.daemon = True
    timer.start()


def _submit(pool, runs: list[Run], models: Mapping[str, Any], metrics: Metrics,
            finished: Callable[[dict], None]) -> tuple[list[tuple[Run, Exception]], bool]:
    """Run ``runs`` on ``pool``; the ones that failed (with why), and whether a dead worker
    broke the pool."""
    from concurrent.futures.process import BrokenProcessPool

    futures = {pool.submit(_worker, models[r.netlist], r, metrics): r for r in runs}
    failed, broken = [], False
    for fut in as_completed(futures):
        try:
            finished(fut.result())
        except Exception as exc:  # noqa: BLE001 - a worker crash is a retry, then a row
            broken = broken or isinstance(exc, BrokenProcessPool)
            failed.append((futures[fut], exc))
    return failed, broken
