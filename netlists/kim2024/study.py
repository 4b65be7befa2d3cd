"""The Kim & Kim 2024 filter study, end to end: `python netlists/kim2024/study.py`.

Prints the Markdown tables of netlists/kim2024/README.md (the six cases, the Fig. 9 sweep, the
case-4 back-EMF question, the energy audit) and writes the figures next to this file. Every
number in that README comes from this script.
"""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

import numpy as np

import circuitsim as cs
from circuitsim.studies.sweep import Metrics, parse_range, sweep

HERE = Path(__file__).resolve().parent
CASES = ["base", "case1", "case2", "case3", "case4", "case5", "case6"]
K_T = 0.14  # [N m/A], the paper's torque constant


def _model(name: str):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return cs.compile(cs.load(HERE / f"{name}.yaml"))


def case_table(jobs: int = 2) -> list[dict]:
    """Steady supply current, speed, 8th-order supply-current ripple of every case."""
    rows = sweep([HERE / f"{c}.yaml" for c in CASES], {},
                 metrics=Metrics(probes=("i_total", "speed"), order=8, window=0.1),
                 jobs=jobs)
    base = next(r for r in rows if r["netlist"].endswith("base.yaml"))
    for r in rows:
        r["case"] = Path(r["netlist"]).stem
        r["attenuation_db"] = 20 * math.log10(r["i_total.ripple_amp"] /
                                              base["i_total.ripple_amp"])
    return rows


def fig9(jobs: int = 2) -> list[dict]:
    return sweep(HERE / "case1.yaml", {"Lf": parse_range("1e-9..1e-1:log:9"), "Rf": [0.0]},
                 metrics=Metrics(probes=("i_total",), order=8, window=1 / 6, energy=False),
                 stop=0.3, jobs=jobs)


def case4_emf(k_e: float | None) -> dict:
    """Back-EMF against the 12 V input in case 4, with the paper's k_e or with k_e = k_t."""
    model = _model("case4")
    params = {} if k_e is None else {"k_e": k_e}
    stop = 0.3 if k_e is None else 1.5  # the conserving motor is slower (tau_m ~ 0.26 s)
    res = model.simulate(stop=stop, params=params, rtol=1e-8, atol=1e-10)
    w = res.window(0.1)
    emf, va = res["emf"], res["a.v"]
    h = res.harmonic("emf", order=8, window=0.1)
    i_dc = res.harmonic("i_motor", order=8, window=0.1).offset
    values = model.param_values(params)
    r_loop = values["Ra.R"]
    return {
        "k_e": values["M.k_e"], "speed": res.harmonic("speed", order=8, window=0.1).offset,
        "i_dc": i_dc, "emf_dc": h.offset, "emf_ripple": h.amplitude,
        "emf_peak": float(emf[w].max()), "emf_max_run": float(emf.max()),
        "t_emf_max": float(res.t[np.argmax(emf)]), "drop": r_loop * i_dc,
        "va_peak": float(va[w].max()), "res": res,
    }


def plot_case4(runs: dict[str, dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(runs), 1, figsize=(8, 5.5), sharex=False)
    for ax, (label, d) in zip(axes, runs.items(), strict=True):
        res = d["res"]
        t_end = res.t[-1]
        m = res.t >= t_end - 4e-3
        ax.plot((res.t[m] - t_end) * 1e3, res["emf"][m], label="back-EMF e")
        ax.plot((res.t[m] - t_end) * 1e3, res["a.v"][m], lw=0.8, label="motor terminal a")
        ax.axhline(12.0, color="k", ls="--", lw=0.8, label="input 12 V")
        ax.axhline(d["emf_dc"], color="C0", ls=":", lw=0.8, label="EMF mean")
        ax.set_title(f"{label}: k_e = {d['k_e']:.4g} V s/rad, speed {d['speed']:.1f} rad/s")
        ax.set_ylabel("voltage [V]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="lower right", ncols=4)
    axes[-1].set_xlabel("time before the end of the run [ms]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_fig9(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4))
    ax.loglog([r["Lf"] for r in rows], [r["i_total.ripple_amp"] for r in rows], "o-")
    ax.set_xlabel("series filter inductance Lf [H]")
    ax.set_ylabel("8th-order supply current ripple [A]")
    ax.set_title("Kim & Kim 2024 Fig. 9 (Rf = 0), circuitsim")
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main() -> int:
    out = sys.stdout.write
    rows = case_table()
    out("| case | filter | supply current [A] | speed [rad/s] | I8 [A] | f8 [Hz] | "
        "attenuation [dB] |\n|---|---|---|---|---|---|---|\n")
    for r in rows:
        title = cs.load(r["netlist"]).title.split(":")[-1].strip()
        out(f"| {r['case']} | {title} | {r['i_total.mean']:.5f} | {r['speed.mean']:.3f} | "
            f"{r['i_total.ripple_amp']:.5f} | {r['i_total.ripple_freq']:.2f} | "
            f"{r['attenuation_db']:.1f} |\n")
    out("\n| case | delivered [J] | dissipated [J] | stored [J] | created by the EMF [J] | "
        "balance [J] |\n|---|---|---|---|---|---|\n")
    for r in rows:
        out(f"| {r['case']} | {r['energy.delivered']:.4f} | {r['energy.dissipated']:.4f} | "
            f"{r['energy.stored']:.4f} | {r['energy.created']:.4f} | "
            f"{r['energy.balance']:.1e} |\n")
    f9 = fig9()
    out("\n| Lf [H] | I8 [A] | f8 [Hz] |\n|---|---|---|\n")
    for r in f9:
        out(f"| {r['Lf']:.0e} | {r['i_total.ripple_amp']:.6g} | "
            f"{r['i_total.ripple_freq']:.3f} |\n")
    plot_fig9(f9, HERE / "fig9.png")
    runs = {"paper's motor (k_t != k_e)": case4_emf(None),
            "energy-conserving motor (k_e = k_t)": case4_emf(K_T)}
    out("\n| motor | speed [rad/s] | I_dc [A] | R_a I_dc [V] | EMF mean [V] | EMF 8th "
        "ripple [V] | EMF peak [V] | terminal peak [V] |\n|---|---|---|---|---|---|---|---|\n")
    for label, d in runs.items():
        out(f"| {label} | {d['speed']:.2f} | {d['i_dc']:.4f} | {d['drop']:.4f} | "
            f"{d['emf_dc']:.4f} | {d['emf_ripple']:.4f} | {d['emf_peak']:.4f} | "
            f"{d['va_peak']:.4f} |\n")
    plot_case4(runs, HERE / "case4_emf.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
