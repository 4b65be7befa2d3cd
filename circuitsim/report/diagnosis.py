"""HTML report of a diagnosis, with its figures."""

from __future__ import annotations

import base64
import html
import io
from collections.abc import Sequence

import numpy as np

from circuitsim.files import atomic_write
from circuitsim.loop.diagnose.describe import lines_text
from circuitsim.loop.diagnose.operating import band_text
from circuitsim.loop.diagnose.result import Accepted, Diagnosis


def _figures(diag: Diagnosis, probes: Sequence[str]) -> dict[str, bytes]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from circuitsim.signal import spectrum

    rec = diag.record
    t = rec.t
    out = {}
    fig, axes = plt.subplots(len(probes), 1, figsize=(8, 2.6 * len(probes)), squeeze=False)
    zoom = t >= t[-1] - 0.1 * (t[-1] - t[0])
    for ax, p in zip(axes[:, 0], probes, strict=True):
        ax.plot(t[zoom], rec[p][zoom], "k.", ms=2, label="measured")
        ax.plot(t[zoom], diag.fit_before.sim[p][zoom], lw=1, label="model before")
        ax.plot(t[zoom], diag.fit_after.sim[p][zoom], lw=1, label="model after")
        ax.set_ylabel(p)
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("time [s]")
    out["waveforms"] = _png_bytes(fig)
    fig, axes = plt.subplots(len(probes), 1, figsize=(8, 2.6 * len(probes)), squeeze=False)
    shafts = diag.analysis_before.get("shafts", {})
    for ax, p in zip(axes[:, 0], probes, strict=True):
        for label, fr in (("before", diag.fit_before), ("after", diag.fit_after)):
            f, a = spectrum(t, np.asarray(fr.residuals[p]))
            ax.semilogy(f[1:], a[1:] + 1e-300, lw=0.8, label=f"residual {label}")
        for pk in diag.analysis_before["probes"][p]["peaks"]:
            lab = ", ".join(f"{k}x {n}" for n, k in pk["orders"].items())
            if lab:
                ax.annotate(lab, (pk["frequency"], pk["amplitude"]), fontsize=7)
        ax.set_ylabel(f"{p} residual")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
        if shafts:
            ax.set_title("orders of " + ", ".join(f"{n} ({v['frequency']:.4g} Hz)"
                                                  for n, v in shafts.items()), fontsize=8)
    axes[-1, 0].set_xlabel("frequency [Hz]")
    out["spectra"] = _png_bytes(fig)
    return out


def _feature_figure(diag: Diagnosis) -> bytes:
    """Measured features (with their sigmas) against the model before and after, one panel
    per feature (their units differ)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    before, after = diag.fit_before, diag.fit_after
    labels = list(before.measured)
    fig, axes = plt.subplots(1, len(labels), figsize=(3.2 * len(labels), 3.0), squeeze=False)
    for ax, lab in zip(axes[0], labels, strict=True):
        sigma = before.sigma.get(lab) or 0.0
        ax.errorbar([0], [before.measured[lab]], yerr=[sigma], fmt="ko", capsize=4,
                    label="measured")
        ax.plot([1], [before.predicted[lab]], "o", label="model before")
        ax.plot([2], [after.predicted[lab]], "s", label="model after")
        ax.set_xticks([0, 1, 2], ["measured", "before", "after"], fontsize=8)
        ax.set_title(lab, fontsize=8)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    return _png_bytes(fig)


def _png_bytes(fig) -> bytes:
    """The figure as PNG bytes (for embedding); the figure is closed."""
    import matplotlib.pyplot as plt

    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100)
    plt.close(fig)
    return buf.getvalue()


def _png(data: bytes) -> str:
    return f'<img src="data:image/png;base64,{base64.b64encode(data).decode()}">'


def write_html(diag: Diagnosis, path: str, title: str = "circuitsim diagnosis") -> None:
    """The report as one self-contained HTML page: summary, effects table, plots (measured
    vs model before and after; for a record also the residual spectra)."""
    if diag.record is not None:
        figs = _figures(diag, list(diag.errors_before))
        plots = (f"<h2>Measured and model</h2>{_png(figs['waveforms'])}"
                 f"<h2>Residual spectra</h2>{_png(figs['spectra'])}")
        crit = "&Delta;BIC"
    else:
        plots = f"<h2>Measured features and model</h2>{_png(_feature_figure(diag))}"
        crit = "&chi;&sup2; after"

    def evidence(a: Accepted) -> str:
        e = a.evidence
        if e.get("delta_bic") is not None:
            return f"{e['delta_bic']:.1f}"
        return f"{e['chi2_after']:.3g}" if e.get("chi2_after") is not None else "n/a"

    rows = "".join(
        f"<tr><td>{i + 1}</td><td>{html.escape(a.effect)}</td><td>{html.escape(a.target)}</td>"
        f"<td>{html.escape(', '.join(f'{k} = {v:.5g}' for k, v in a.parameters.items()))}</td>"
        f"<td>{html.escape(', '.join(f'{k}: {v:.2g}' if v is not None else f'{k}: n/a' for k, v in a.stderr.items()))}</td>"
        f"<td>{a.error_after:.4g}</td><td>{evidence(a)}</td></tr>"
        for i, a in enumerate(diag.effects))
    body = f"""<!doctype html><html><head><meta charset="utf-8"><title>{html.escape(title)}</title>
<style>body{{font-family:sans-serif;max-width:60em;margin:auto}}td,th{{padding:2px 8px}}</style>
</head><body><h1>{html.escape(title)}</h1>
<p>{html.escape(diag.summary())}</p>
<p>Error (RMS over probes of NRMSE): before {diag.error_before:.5g}, after {diag.error_after:.5g}.</p>
<table border="1"><tr><th>#</th><th>effect</th><th>target</th><th>parameters</th><th>stderr</th>
<th>error after</th><th>{crit}</th></tr>{rows}</table>
<p>{'<br>'.join(html.escape(s) for s in diag.indistinct)}</p>
{_corrections(diag)}{_final_fit(diag)}{_remaining(diag)}
{plots}
</body></html>"""
    atomic_write(path, body, make_dirs=False)


def _corrections(diag: Diagnosis) -> str:
    if not diag.corrections:
        return ""
    rows = "".join(
        f"<tr><td>{html.escape(a.effect)}</td><td>{html.escape(a.target)}</td>"
        f"<td>{html.escape(', '.join(f'{k} = {v:.5g}' for k, v in a.parameters.items()))}"
        f"</td></tr>" for a in diag.corrections)
    return ("<h2>Corrections of declared terms (not new causes)</h2><table border=\"1\">"
            "<tr><th>term</th><th>on</th><th>correction</th></tr>" + rows + "</table>")


def _num(v: float | None, fmt: str) -> str:
    return "n/a" if v is None else format(v, fmt)


def _final_fit(diag: Diagnosis) -> str:
    final = diag.final_parameters()
    if not final:
        return ""

    rows = "".join(
        f"<tr><td>{html.escape(n)}</td><td>{_num(v['before'], '.6g')}</td>"
        f"<td>{_num(v['estimate'], '.6g')}</td><td>{_num(v['stderr'], '.2g')}</td></tr>"
        for n, v in final.items())
    return ("<h2>Final fit (all free parameters together, SI)</h2><table border=\"1\">"
            "<tr><th>parameter</th><th>declared model</th><th>estimate</th><th>stderr</th>"
            "</tr>" + rows + "</table>")


def _remaining(diag: Diagnosis) -> str:
    rest = diag.remaining or {}
    probes = rest.get("probes") or {}
    if not isinstance(probes, dict) or not probes:
        return f"<h2>What remains</h2><p>{html.escape(str(rest.get('note', '')))}</p>"
    rows = []
    for p, e in probes.items():
        lines = lines_text(e) or "-"
        when = ", ".join(f"{a:.3g}-{b:.3g} s" for a, b in e["timing"]["strongest"])
        if "onset" in e["timing"]:
            a, b = e["timing"]["onset"]
            when += f"{'; ' if when else ''}starts in {a:.3g}-{b:.3g} s, lasts to the end"
        grows = "; ".join(filter(None, [
            ", ".join(f"{f['signal']} ({f['rank_correlation']:.2f})"
                      for f in e.get("follows") or []),
            band_text(e.get("band"), lead="")])) or "-"
        level = e.get("rms_over_noise")
        rows.append(f"<tr><td>{html.escape(p)}</td><td>{_num(level, '.3g')}</td>"
                    f"<td>{e['structured_share']:.1%}</td>"
                    f"<td>{html.escape(e['timing']['kind'])}</td><td>{html.escape(when)}</td>"
                    f"<td>{html.escape(grows)}</td><td>{html.escape(lines)}</td></tr>")
    return ("<h2>What remains</h2><p>" + html.escape(str(rest.get("note", ""))) +
            "</p><table border=\"1\"><tr><th>probe</th><th>rms / white noise</th>"
            "<th>structure share (prewhitened)</th><th>kind</th>"
            "<th>strongest</th><th>grows with (rank correlation)</th>"
            "<th>lines (share of the structure)</th></tr>" + "".join(rows) +
            "</table>")
