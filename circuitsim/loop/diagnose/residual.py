"""Stage: analyse a fit's residual (noise floor, whiteness, spectral lines, shaft orders)."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

ORDER_TOL = 0.03  # a spectral peak is order k when |f/f_shaft - k| < ORDER_TOL k
#: Share of the structure of the residual on a shaft's angle a line must hold to be proposed
#: as an order (as the description asks to name one: describe)
ORDER_SHARE = 0.25  # so at most four lines a shaft: fresh15's x05 once proposed 131


#: The finest a record resolves, as a fraction of a probe's spread: no sensor reads better than
#: 20 bits of its range, and the integrator's own error (rtol 1e-8) is far below it. A residual
#: this small is no evidence of anything, whatever its shape (a noise-free record made by the
#: same model leaves 1e-8 of its spread, all of it smooth).
RESOLUTION = 1e-6


def spread(x) -> float:
    """A probe's standard deviation over the record [unit] (never 0)."""
    return max(float(np.std(np.asarray(x, float))), 1e-300)


def below_resolution(r, measured) -> bool:
    """The residual ``r`` is at most the resolution any record of ``measured`` carries."""
    return float(np.sqrt(np.mean(np.square(np.asarray(r, float))))) <= RESOLUTION * spread(
        measured)


def noise_sigma(r: np.ndarray, step: float = 0.0) -> float:
    """White-noise level of a residual from its third differences (robust: median), never
    below the quantisation noise step/sqrt(12) of an ADC of ``step`` [probe unit].

    Differencing removes smooth structure (a tone at 2 % of the sample rate keeps 0.2 % of
    its size after three differences) and multiplies white noise's variance by C(6, 3) = 20.
    A tone near the Nyquist frequency is amplified instead (up to 64/20 in variance), so the
    estimate is capped at the residual's own RMS: noise is a part of the residual. A record
    read by an ADC coarser than its noise holds the same value for runs of samples: most
    third differences are 0 and their median says nothing of the rounding error.
    """
    d = np.diff(r, n=3)
    est = float(1.4826 * np.median(np.abs(d - np.median(d))) / math.sqrt(20))
    return min(max(est, step / math.sqrt(12.0)), float(np.sqrt(np.mean(np.square(r)))))


def adc_step(x: np.ndarray) -> float:
    """The step [unit of x] of the lattice a quantised record's values lie on; 0 when they
    do not (a record with about as many distinct values as samples)."""
    x = np.asarray(x, float)
    u = np.unique(x[np.isfinite(x)])
    if u.size < 3 or u.size > x.size // 4:
        return 0.0
    q = float(np.min(np.diff(u)))
    k = (u - u[0]) / q
    return q if bool(np.all(np.abs(k - np.round(k)) < 1e-3)) else 0.0


def ljung_box(r: np.ndarray, lags: int = 20) -> tuple[float, float]:
    """(Q, p-value) of the Ljung-Box whiteness test."""
    from scipy.stats import chi2

    x = r - r.mean()
    n = x.size
    den = float(x @ x)
    if den == 0.0 or n <= lags + 1:
        return 0.0, 1.0
    rho = np.array([float(x[:-k] @ x[k:]) / den for k in range(1, lags + 1)])
    q = n * (n + 2) * float(np.sum(rho**2 / (n - np.arange(1, lags + 1))))
    return q, float(chi2.sf(q, lags))


def _shaft_speed(model, sim) -> dict[str, float]:
    """Mean speed [rad/s] of every shaft in a simulated run."""
    out = {}
    for n in model.shafts:
        try:
            out[n] = float(np.mean(sim[f"{n}.w"]))
        except KeyError:
            continue
    return out


def analyse(model, record, fit_res, probes: Sequence[str]) -> dict[str, Any]:
    """Residual statistics, labelled spectral peaks, whiteness and regressor correlations."""
    sim = fit_res.sim
    speeds = _shaft_speed(model, sim)
    t = record.t
    out: dict[str, Any] = {"probes": {}, "shafts": {k: {"speed": v, "frequency": v /
                                                        (2 * math.pi)}
                                                    for k, v in speeds.items()}}
    regressors: dict[str, np.ndarray] = {"time": t - t.mean()}
    for p in probes:
        regressors[f"model {p}"] = np.asarray(sim[p])
    for n in speeds:
        regressors[f"sign({n}.w)"] = np.sign(np.asarray(sim[f"{n}.w"]))
    for p in probes:
        r = np.asarray(fit_res.residuals[p])
        x = np.asarray(record[p])
        sigma = noise_sigma(r, adc_step(x))
        peaks = _time_peaks(t, r, out["shafts"], sim)
        peaks += _order_peaks(sim, speeds, t, r, peaks)
        q, pval = ljung_box(r)
        corr = {}
        for name, g in regressors.items():
            if np.std(g) > 0 and np.std(r) > 0:
                corr[name] = float(np.corrcoef(g, r)[0, 1])
        for n in speeds:
            phi = np.asarray(sim[f"{n}.phi"])
            for pk in peaks:
                k = pk["orders"].get(n)
                if k:
                    c = np.column_stack([np.sin(k * phi), np.cos(k * phi)])
                    coef = np.linalg.lstsq(c, r - r.mean(), rcond=None)[0]
                    corr[f"harmonic {k} of {n}.phi"] = float(
                        np.sqrt(np.mean((c @ coef) ** 2)) / max(np.std(r), 1e-300))
        out["probes"][p] = {
            "rms": float(np.sqrt(np.mean(r**2))),
            "nrmse": float(np.sqrt(np.mean(r**2)) / max(np.std(x), 1e-300)),
            "noise_sigma": sigma, "peaks": peaks,
            "whiteness": {"ljung_box_q": q, "p_value": pval, "white": pval > 1e-3},
            "correlation": corr,
        }
    return out


def _time_peaks(t: np.ndarray, r: np.ndarray, shafts: Mapping[str, Any], sim
                ) -> list[dict[str, Any]]:
    """The largest lines of the residual's time spectrum, labelled as shaft orders where a
    shaft turns steadily. A line counts when its amplitude exceeds what noise reaches in any
    bin with probability 1 % (Rayleigh amplitudes, Bonferroni over the bins), against the
    median amplitude as the background."""
    from circuitsim.signal import spectrum

    f, amp = spectrum(t, r)
    floor = float(np.median(amp[1:])) if amp.size > 2 else 0.0
    level = math.sqrt(math.log(max(amp.size, 2) / 0.01) / math.log(2.0)) * floor
    peaks: list[dict[str, Any]] = []
    for k in np.argsort(amp)[::-1][:200]:
        if f[k] <= 2 / (t[-1] - t[0]) or amp[k] < level:
            continue
        if any(abs(f[k] - q["frequency"]) < 3 / (t[-1] - t[0]) for q in peaks):
            continue
        label = {}
        for n, sp in shafts.items():
            w = np.asarray(sim[f"{n}.w"])
            if np.std(w) > 0.02 * abs(np.mean(w)):
                continue  # the speed changes: only the angle spectrum can name orders
            ratio = f[k] / sp["frequency"] if sp["frequency"] > 0 else 0
            kk = round(ratio)
            if kk >= 1 and abs(ratio - kk) < ORDER_TOL * kk:
                label[n] = kk
        peaks.append({"frequency": float(f[k]), "amplitude": float(amp[k]), "orders": label})
        if len(peaks) == 6:
            break
    return peaks


def on_travelled_angle(t: np.ndarray, w: np.ndarray, r: np.ndarray
                       ) -> tuple[np.ndarray, np.ndarray] | None:
    """``r`` resampled on a uniform grid of the angle a shaft of speed ``w`` [rad/s]
    *travels* [rad] (order tracking): a harmonic of the angle is a line at its order even
    while the speed changes, and a reversal keeps the order where the signed angle would fold
    back on itself. Only the samples where the shaft turns at a tenth of its top speed or more
    count (a start from rest, a pause). None when it travels under two turns."""
    w = np.abs(np.asarray(w, float))
    moving = w > 0.1 * max(float(np.max(w)), 1e-300) if w.size else w > 0
    if not np.any(moving):  # a shaft at rest over the whole record travels nothing
        return None
    travel = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(t))])[moving]
    keep = np.concatenate([[True], np.diff(travel) > 0])
    travel, x = travel[keep], np.asarray(r, float)[moving][keep]
    if travel.size <= 16 or travel[-1] - travel[0] < 4 * math.pi:
        return None
    grid = np.linspace(travel[0], travel[-1], travel.size)
    return grid, np.interp(grid, travel, x)


def _forward_angle(t: np.ndarray, phi: np.ndarray, w: np.ndarray, r: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray] | None:
    """``r`` on a uniform grid of the shaft's angle ``phi`` [rad] from the moment it turns
    steadily forward (a start from rest is skipped); None when it travels under two turns or
    its angle ever falls back (it reverses)."""
    moving = w > 0.1 * max(float(np.max(w)), 1e-300)
    if not moving.any():
        return None
    first = int(np.argmax(moving))
    phi, rr = phi[first:], r[first:]
    if phi[-1] - phi[0] < 4 * math.pi or not np.all(np.diff(phi) > 0):
        return None
    grid = np.linspace(phi[0], phi[-1], phi.size)
    return grid, np.interp(grid, phi, rr)


def _order_peaks(sim, speeds, t, r, known) -> list[dict[str, Any]]:
    """Peaks of the residual's spectrum in the shaft angle (order tracking), where the time
    spectrum smears a harmonic of a changing speed. A shaft that turns forward only is read
    on its angle from the moment it turns (``_forward_angle``); one that reverses, on the
    angle it travels (``on_travelled_angle``, as the description reads it). Either way a
    line counts when it stands out of the prewhitened spectrum (``noise.significant_lines``)
    and holds ``ORDER_SHARE`` of its structure (``_angle_lines``). Resampling on the angle
    colours even white noise, and a line fixed in time (a filter's ringing) or a drag that
    follows no angle smears over dozens of orders of a changing speed: against the median
    amplitude as a flat background each passed for an order (fresh6's k12 on a reversing
    shaft: cogging of orders 13-180 proposed, round after round; fresh15's x11 on a forward
    one until 2026-11-28: an eddy drag, 33 cogging orders a round, the highest 188). An order
    too faint for the spectrum is the order scan's to find, by its fit gain (``scan``)."""
    out: list[dict[str, Any]] = []
    for n in speeds:
        w = np.asarray(sim[f"{n}.w"], float)
        forward = _forward_angle(t, np.asarray(sim[f"{n}.phi"], float), w, r)
        resampled = forward or on_travelled_angle(t, w, r)  # None: under two turns
        for order, amp in _angle_lines(*resampled) if resampled else []:
            kk = round(order)
            if kk < 1 or abs(order - kk) > ORDER_TOL * kk:
                continue
            if any(p["orders"].get(n) == kk for p in known + out):
                continue
            # a reversing shaft's mean speed says little: its mean turning rate
            rate = speeds[n] if forward else float(np.mean(np.abs(w)))
            out.append({"frequency": float(kk * rate / (2 * math.pi)), "amplitude": amp,
                        "orders": {n: kk}, "domain": "angle"})
    return out


def _hann_amplitudes(grid: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(orders [cycles per turn], amplitude spectrum [unit of x]) of ``x`` on the angle
    ``grid`` [rad], detrended and Hann-windowed."""
    m = grid.size
    x = x - np.polyval(np.polyfit(grid, x, 1), grid)
    win = 0.5 - 0.5 * np.cos(2 * math.pi * np.arange(m) / m)
    amp = np.abs(np.fft.rfft(x * win)) * 2 / win.sum()
    return np.fft.rfftfreq(m, (grid[1] - grid[0]) / (2 * math.pi)), amp


def _angle_lines(grid: np.ndarray, x: np.ndarray) -> list[tuple[float, float]]:
    """(order, amplitude) of the significant lines of the residual ``x`` on the uniform angle
    ``grid`` [rad] that hold ``ORDER_SHARE`` of its structure, largest first."""
    from circuitsim.loop.diagnose.noise import fit_whitener, significant_lines

    x = x - np.polyval(np.polyfit(grid, x, 1), grid)
    step = (grid[1] - grid[0]) / (2 * math.pi)  # [turns]
    lines = significant_lines(fit_whitener(x).apply(x), step)
    orders, amp = _hann_amplitudes(grid, x)
    # what varies slower than once a turn (a drag following the speed) is no order's share
    turning = lines.freqs >= 0.5
    structured = float(lines.excess[turning].sum())
    return [(float(lines.freqs[k]), float(np.interp(lines.freqs[k], orders, amp)))
            for k in np.argsort(lines.excess)[::-1]
            if turning[k] and lines.excess[k] >= ORDER_SHARE * structured]


def _orders(analysis: Mapping[str, Any]) -> dict[str, list[int]]:
    found: dict[str, list[int]] = {}
    for pr in analysis["probes"].values():
        for pk in pr["peaks"]:
            for n, k in pk["orders"].items():
                found.setdefault(n, [])
                if k not in found[n]:
                    found[n].append(k)
    return found
