"""Figures of a run, an AC sweep and a parameter sweep (PNG)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from circuitsim.files import atomic_write


def plot(res, path: str, names: list[str] | None = None) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(names or res.probes or res.states)[:8]
    fig, axes = plt.subplots(len(names), 1, figsize=(8, 2.2 * len(names) + 0.6), sharex=True,
                             squeeze=False)
    for ax, name in zip(axes[:, 0], names, strict=True):
        ax.plot(res.t, res[name], lw=0.7)
        unit = res.model.meta["units"].get(name, "")
        ax.set_ylabel(f"{name}" + (f" [{unit}]" if unit else ""))
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("time [s]")
    fig.suptitle(res.model.netlist.title)
    fig.tight_layout()
    atomic_write(path, lambda p: fig.savefig(p, dpi=110, format="png"))
    plt.close(fig)


def _bode(res, path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 5), sharex=True)
    a1.loglog(res.frequency, res.magnitude)
    a1.set_ylabel(f"|{res.output} / {res.input}|")
    a2.semilogx(res.frequency, res.phase)
    a2.set_ylabel("phase [deg]")
    a2.set_xlabel("frequency [Hz]")
    for a in (a1, a2):
        a.grid(alpha=0.3, which="both")
    fig.tight_layout()
    atomic_write(path, lambda p: fig.savefig(p, dpi=110, format="png"))
    plt.close(fig)


def plot_sweep(rows: list[dict[str, Any]], x: str, y: str, path: str,
               logx: bool = True, logy: bool = True) -> None:
    """Metric ``y`` against swept parameter ``x``, one line per netlist."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from circuitsim.files import atomic_write

    fig, ax = plt.subplots(figsize=(7, 4.2))
    for net in dict.fromkeys(r["netlist"] for r in rows):
        pts = sorted((float(r[x]), float(r[y])) for r in rows
                     if r["netlist"] == net and r.get(y) not in (None, ""))
        if pts:
            xs, ys = zip(*pts, strict=True)
            ax.plot(xs, ys, "o-", label=Path(net).stem)
    if logx:
        ax.set_xscale("log")
    if logy:
        ax.set_yscale("log")
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    fig.tight_layout()
    atomic_write(path, lambda p: fig.savefig(p, dpi=110, format="png"))
    plt.close(fig)
