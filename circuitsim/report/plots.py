"""Figures of a run, an AC sweep and a parameter sweep (PNG)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from circuitsim.files import atomic_write, plot_format

MAX_PANELS = 8
DPI = 110  # [1/in] of the PNG files


def _plain(text: str) -> str:
    """Text shown as written: a '$' would start matplotlib's mathtext and may not parse."""
    return str(text).replace("$", r"\$")


def save_figure(fig, path: str) -> None:
    """Write ``fig`` whole or not at all, as PNG, SVG or PDF by the file's extension. A PNG
    at zlib level 1 instead of PIL's 6: the same pixels in a file about 30 % larger, encoded
    in half the time (40 ms of a run's 1 s)."""
    fmt = plot_format(path)
    extra = {"pil_kwargs": {"compress_level": 1}} if fmt == "png" else {}
    atomic_write(path, lambda p: fig.savefig(p, dpi=DPI, format=fmt, **extra))


def _figure(**kw):
    """A matplotlib ``Figure`` on the Agg canvas, without pyplot (no figure registry, no GUI
    backend search: nothing here is shown on screen) and without the docstrings matplotlib
    writes for every artist class as it is imported (about 80 ms of a run's 1 s; the classes
    work the same, only ``help(Line2D.set)`` lists no properties)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(**kw)
    FigureCanvasAgg(fig)
    return fig


def _lean_import() -> None:
    """Import matplotlib's figure modules skipping the property lists it puts into each artist
    class's ``set`` docstring as the class is created; the first import in the process only,
    and only this once (classes defined later get theirs)."""
    import sys

    if "matplotlib.figure" in sys.modules:
        return
    from matplotlib import artist

    update = artist.Artist.__dict__.get("_update_set_signature_and_docstring")
    if not isinstance(update, classmethod):  # another matplotlib: import it as it comes
        return
    artist.Artist._update_set_signature_and_docstring = classmethod(lambda cls: None)
    try:
        import matplotlib.backends.backend_agg
        import matplotlib.figure  # noqa: F401
    finally:
        artist.Artist._update_set_signature_and_docstring = update


def envelope(t: np.ndarray, y: np.ndarray, columns: int) -> tuple[np.ndarray, np.ndarray]:
    """``(t, y)`` reduced for drawing ``columns`` pixels wide: per column its first, minimum,
    maximum and last point in time order, so every peak and the line's path through the
    column stay (the same pixels up to anti-aliasing). Short series come back whole."""
    n = t.size
    per = max(1, n // columns)
    if per < 32:  # Agg simplifies paths itself: below ~32 points a column nothing is gained
        return t, y
    m = n // per * per
    blocks = y[:m].reshape(-1, per)
    lo, hi = blocks.argmin(1), blocks.argmax(1)
    base = np.arange(0, m, per)
    idx = np.concatenate([base, base + np.minimum(lo, hi), base + np.maximum(lo, hi),
                          base + per - 1, np.arange(m, n)])
    idx = np.unique(idx)  # sorted: time order
    return t[idx], y[idx]


def plot(res, path: str, names: list[str] | None = None, window: float | None = None) -> None:
    """One panel per series (at most 8; the figure says how many were left out) against time;
    with ``window`` (a fraction of the run), a second column zooms on the steady window."""
    every = list(names or res.probes or res.states)
    shown = every[:MAX_PANELS]
    cols = 2 if window else 1
    width = 8 + 4 * (cols - 1)  # [in]
    fig = _figure(figsize=(width, 2.2 * len(shown) + 0.8))
    axes = fig.subplots(len(shown), cols, sharex="col", squeeze=False)
    zoom = res.window(window) if window else None
    for row, name in enumerate(shown):
        unit = res.model.meta["units"].get(name, "")
        for col in range(cols):
            ax = axes[row, col]
            mask = zoom if col == 1 else slice(None)
            ax.plot(*envelope(res.t[mask], res[name][mask], int(width * DPI / cols)), lw=0.7)
            ax.grid(alpha=0.3)
        axes[row, 0].set_ylabel(_plain(name) + (f" [{_plain(unit)}]" if unit else ""))
    axes[-1, 0].set_xlabel("time [s]")
    if cols == 2:
        axes[0, 1].set_title(f"steady window (last {window:.0%})", fontsize=9)
        axes[-1, 1].set_xlabel("time [s]")
    title = _plain(res.model.netlist.title)
    if len(every) > len(shown):
        title += f"\n({len(every) - len(shown)} more series not shown: choose with --probe)"
    fig.suptitle(title)
    fig.tight_layout()
    save_figure(fig, path)


def _bode(res, path: str) -> None:
    """Bode plot: magnitude in dB, phase in degrees unwrapped along the frequency axis."""
    fig = _figure(figsize=(7, 5))
    a1, a2 = fig.subplots(2, 1, sharex=True)
    mag = np.asarray(res.magnitude, float)
    with np.errstate(divide="ignore"):
        db = 20 * np.log10(mag)
    a1.semilogx(res.frequency, db)
    a1.set_ylabel(_plain(f"|{res.output} / {res.input}| [dB]"))
    # numpy.unwrap removes the 360° jumps of a phase reported in (-180, 180]
    phase = np.degrees(np.unwrap(np.radians(np.asarray(res.phase, float))))
    a2.semilogx(res.frequency, phase)
    a2.set_ylabel("phase [deg]")
    a2.set_xlabel("frequency [Hz]")
    for a in (a1, a2):
        a.grid(alpha=0.3, which="both")
    fig.tight_layout()
    save_figure(fig, path)


def _log_scale(values: list[float]) -> bool:
    """Log when every value is positive and they span more than a decade."""
    v = np.asarray([x for x in values if np.isfinite(x)], float)
    return bool(v.size > 1 and np.all(v > 0) and v.max() / v.min() > 10)


def plot_sweep(rows: list[dict[str, Any]], x: str, y: str, path: str,
               logx: bool | None = None, logy: bool | None = None) -> None:
    """Metric ``y`` (any column) against swept parameter ``x``, one line per netlist; each
    axis is logarithmic when its values are positive and span more than a decade (``None``),
    or as asked."""
    ax = _figure(figsize=(7, 4.2)).subplots()
    fig = ax.figure
    xs_all: list[float] = []
    ys_all: list[float] = []
    for net in dict.fromkeys(r["netlist"] for r in rows):
        pts = sorted((float(r[x]), float(r[y])) for r in rows
                     if r["netlist"] == net and r.get(y) not in (None, ""))
        if pts:
            xs, ys = zip(*pts, strict=True)
            xs_all += xs
            ys_all += ys
            ax.plot(xs, ys, "o-", label=_plain(Path(net).stem))
    if logx if logx is not None else _log_scale(xs_all):
        ax.set_xscale("log")
    if logy if logy is not None else _log_scale(ys_all):
        ax.set_yscale("log")
    ax.set_xlabel(_plain(x))
    ax.set_ylabel(_plain(y))
    ax.grid(alpha=0.3, which="both")
    if xs_all:
        ax.legend()
    fig.tight_layout()
    save_figure(fig, path)
