"""Figures of the BLDC identification."""

from __future__ import annotations

import numpy as np

from circuitsim.report.plots import save_figure


def _plot_curve(curve, xlabel, ylabel, path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5, 3.2))
    ax.plot(range(len(curve)), curve, "o-")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    save_figure(fig, path)  # whole or not at all, in the format its extension names
    plt.close(fig)


def _plot_map(th, x, fit, direction, path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    order = np.argsort(th)
    fig, ax = plt.subplots(figsize=(8, 3.2))
    ax.plot(th[order], x[order], ".", ms=2, label="measured")
    ax.plot(th[order], fit.evaluate(th, direction)[order], "-", lw=1,
            label=f"fit, orders {', '.join(map(str, fit.orders))}")
    ax.set_xlabel("shaft angle [rad]")
    ax.set_ylabel("value")
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    save_figure(fig, path)  # whole or not at all, in the format its extension names
    plt.close(fig)
