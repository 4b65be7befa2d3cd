"""The Kapun et al. 2008 identification, end to end: `python netlists/kapun2008/study.py`.

Simulates the open-circuit back-EMF test (emf.yaml) and the torque test (bldc.yaml) once each,
adds measurement noise with 40 (torque) or 10 (back-EMF) seeds, identifies Table 2 and Table 3
from the noisy records and prints the Markdown tables of netlists/kapun2008/README.md; fits the
ODrive cogging maps; writes the figures next to this file and, given a folder
(`python netlists/kapun2008/study.py OUT`), two noisy example records as CSV for the CLI
(`OUT/emf_test_seed0.csv`, `OUT/torque_test_seed0.csv`; a few MB, so not in the repository).
Every number in that README comes from this script.
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np

import circuitsim as cs
from circuitsim.loop import identify as idf
from circuitsim.report import identify as plots

HERE = Path(__file__).resolve().parent
ODRIVE = Path("/work/shared/data/real/odrive-bldc-cogging/cogging_maps.csv")
PP = 6
J_TOT = 104e-7  # [kg m^2]
TS = 100e-6  # [s]
TABLE2 = {1: 5817e-6, 2: 3e-6, 3: 57e-6, 4: 0.0, 5: 28e-6}
TABLE3 = {"L_rra3": (94.3e-6, 2.3e-6), "L_rrb3": (52.7e-6, 3.0e-6),
          "L_rra6": (270.6e-6, 9.4e-6), "L_rrb6": (214.0e-6, 11.9e-6),
          "T_a1": (741.1e-6, 17.5e-6), "T_b1": (23.4e-6, 8.5e-6),
          "B": (52.5e-6, 10.6e-6), "C": (1320e-6, 343.8e-6)}
# Measurement noise (standard deviations): interpolated encoder angle, speed, 12-bit current
# and voltage channels.
NOISE_EMF = {"theta": 2e-5, "omega": 0.05, "e1": 5e-3}
NOISE_DRIVE = {"theta": 2e-5, "omega": 0.05, "i1": 5e-3, "i2": 5e-3, "i3": 5e-3}


def simulate(name: str) -> dict[str, np.ndarray]:
    """The noise-free record of a netlist, sampled every 100 us (probes of motor.yaml)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = cs.compile(cs.load(HERE / f"{name}.yaml"))
    res = model.simulate()
    if not res.success:
        raise RuntimeError(res.message)
    return {"time": res.t, **{k: res[k] for k in ("theta", "omega", "i1", "i2", "i3", "e1",
                                                   "T_mutual", "T_cogg")}}


def back_emf_study(rec: dict[str, np.ndarray], reps: int = 10):
    """J_min curve and Table 2 from ``reps`` noisy copies of the open-circuit record."""
    noisy = [idf.add_noise(rec, NOISE_EMF, seed) for seed in range(reps)]
    curve = idf.emf_error_curve(noisy[0]["theta"], noisy[0]["omega"], noisy[0]["e1"], PP, 9)
    fits = [idf.fit_back_emf(n["theta"], n["omega"], n["e1"], PP, range(1, 6)) for n in noisy]
    return curve, fits


def drive_study(rec: dict[str, np.ndarray], reps: int = 40, compensate: bool = True,
                start: int = 0):
    """Table 3 from ``reps`` noisy copies of the torque-test record (samples from ``start``)."""
    emf = idf.emf_from_coefficients(TABLE2, None, PP)
    fits = []
    for seed in range(reps):
        n = idf.add_noise(rec, NOISE_DRIVE, seed)
        tm = idf.mutual_torque(n["theta"], [n["i1"], n["i2"], n["i3"]], emf)
        obs = idf.disturbance_observer(n["omega"], tm, J_TOT, TS)
        H, names = idf.disturbance_regressors(n["theta"], n["omega"], PP, (3, 6))
        if compensate:
            H = idf.observer_filter(H, obs)
        fits.append(idf.lstsq(H[start:], obs.t_dist[start:], names))
    return fits, obs


def angle_spectrum(theta: np.ndarray, x: np.ndarray, per_turn: int = 4096) -> np.ndarray:
    """Amplitude of x per order of the shaft angle over whole turns (x resampled on theta)."""
    turns = int((theta[-1] - theta[0]) // (2 * np.pi))
    grid = theta[0] + np.arange(turns * per_turn) * 2 * np.pi / per_turn
    y = np.interp(grid, theta, x)
    spec = np.abs(np.fft.rfft(y - y.mean())) * 2 / y.size
    return spec[::turns][: per_turn // 2]


def main(records: Path | None = None) -> None:
    out = HERE
    emf_rec = simulate("emf")
    curve, efits = back_emf_study(emf_rec)
    st2 = idf.repeat_statistics(efits)
    peak, rms = idf.emf_constants(efits[0])
    print("### Back-EMF (Table 2), 10 noisy records of 30 000 samples\n")
    print("| coefficient | paper x1e-6 | identified mean x1e-6 | std | error |")
    print("|---|---|---|---|---|")
    for k, v in TABLE2.items():
        mu, sd = st2.row(f"a{k}")
        err = f"{(mu - v) / v:+.3%}" if v else f"{mu * 1e6:+.3f}e-6"
        print(f"| L_ra{k} | {v * 1e6:g} | {mu * 1e6:.3f} | {sd * 1e6:.3f} | {err} |")
    print(f"\nJ_min(K), K = 0..9 [V^2]: {', '.join(f'{j:.4g}' for j in curve)}; relevant "
          f"orders {idf.relevant_orders(curve)}")
    print(f"voltage constant: peak {peak * 1e3:.2f} mV s/rad, RMS {rms * 1e3:.2f} mV s/rad; "
          f"speed during the test {emf_rec['omega'][5000:].min():.1f}.."
          f"{emf_rec['omega'][5000:].max():.1f} rad/s\n")
    plots._plot_curve(curve, "number of harmonics K", "J_min [V^2]", out / "emf_jmin.png")

    rec = simulate("bldc")
    w = rec["omega"]
    steady = rec["time"] > 1.5
    spec = angle_spectrum(rec["theta"][steady], w[steady])
    top = np.argsort(spec[1:])[::-1][:4] + 1
    print("### Torque test (bldc.yaml), 2.5 s\n")
    print(f"speed: mean over t > 1.5 s {w[steady].mean():.2f} rad/s "
          f"((T_ref - C)/B = {(4.3e-3 - 1320e-6) / 52.5e-6:.2f}); final {w[-1]:.2f} rad/s")
    print(f"speed ripple orders per turn (largest first): "
          f"{', '.join(f'{k} ({spec[k]:.3f} rad/s)' for k in top)}")
    print(f"mutual torque mean {rec['T_mutual'][steady].mean() * 1e3:.4f} mN m; cogging peak "
          f"{np.abs(rec['T_cogg']).max() * 1e3:.3f} mN m (sampled)")
    exact = {k: v[0] for k, v in TABLE3.items()}
    pk, at = idf.peak_cogging(exact, PP, (3, 6))
    print(f"peak cogging torque of Table 3: {pk * 1e3:.4f} mN m at theta = {at:.4f} rad\n")

    emf = idf.emf_from_coefficients(TABLE2, None, PP)
    clean = idf.disturbance_observer(
        w, idf.mutual_torque(rec["theta"], [rec["i1"], rec["i2"], rec["i3"]], emf), J_TOT, TS)
    print(f"observer on the noise-free record: max |w - w_hat| after 0.1 s "
          f"{np.abs(clean.error[1000:]).max():.2e} rad/s (the paper's Fig. 9: < 2e-3)")
    n = idf.add_noise(rec, NOISE_DRIVE, 0)
    obs = idf.disturbance_observer(
        n["omega"], idf.mutual_torque(n["theta"], [n["i1"], n["i2"], n["i3"]], emf), J_TOT, TS)
    curve = idf.disturbance_error_curve(n["theta"], n["omega"], obs.t_dist, PP, 12,
                                        observer=obs)
    print(f"J_min of T_dist versus the number of cogging harmonics K = 0..12 (one noisy "
          f"record) [N^2 m^2]: {', '.join(f'{j:.4g}' for j in curve)}\n")
    plots._plot_curve(curve, "number of cogging harmonics K", "J_min [N^2 m^2]",
                    out / "cogging_jmin.png")

    for label, kw in (("regressors through the observer loop", {"compensate": True}),
                      ("plain fit of the compensator output", {"compensate": False}),
                      ("observer loop, steady part only (t > 1 s)",
                       {"compensate": True, "start": 10000})):
        fits, obs = drive_study(rec, **kw)
        st = idf.repeat_statistics(fits)
        print(f"### Table 3, 40 noisy records, {label}\n")
        print("| parameter | paper mean | paper std | identified mean | std | "
              "|error| / paper std |")
        print("|---|---|---|---|---|---|")
        for name, (mu_p, sd_p) in TABLE3.items():
            mu, sd = st.row(name)
            print(f"| {name} | {mu_p * 1e6:g} | {sd_p * 1e6:g} | {mu * 1e6:.2f} | "
                  f"{sd * 1e6:.2f} | {abs(mu - mu_p) / sd_p:.2f} |")
        print(f"\ncorrelation of B and C over the 40 records: {st.correlation('B', 'C'):+.4f}; "
              f"relative spread of C {st.row('C')[1] / st.row('C')[0]:.2%}, of B "
              f"{st.row('B')[1] / st.row('B')[0]:.2%}; observer speed error max "
              f"{np.abs(obs.error[100:]).max():.3g} rad/s\n")

    if records is not None:
        write_records(records, emf_rec, rec)
    if ODRIVE.is_file():
        odrive_study(out)


def write_records(folder: Path, emf_rec: dict, rec: dict) -> None:
    """Noisy example records (seed 0) as CSV, the input of `circuitsim identify`."""
    folder.mkdir(parents=True, exist_ok=True)
    out = folder
    n0 = idf.add_noise(rec, NOISE_DRIVE, 0)
    cols = ["time", "theta", "omega", "i1", "i2", "i3"]
    np.savetxt(out / "torque_test_seed0.csv", np.column_stack([n0[c] for c in cols]),
               delimiter=",", header=",".join(cols), comments="", fmt="%.9g")
    e0 = idf.add_noise(emf_rec, NOISE_EMF, 0)
    cols = ["time", "theta", "omega", "e1"]
    np.savetxt(out / "emf_test_seed0.csv", np.column_stack([e0[c] for c in cols]),
               delimiter=",", header=",".join(cols), comments="", fmt="%.9g")


def odrive_study(out: Path) -> None:
    rec = idf._read_csv(str(ODRIVE))
    trial = rec["trial"]
    print("### ODrive cogging maps: dominant orders per turn (greedy least squares)\n")
    print("| trial | orders (amplitude, A of Iq) | mean Iq [A] | rms residual [A] |")
    print("|---|---|---|---|")
    for t in ("a", "b", "c", "d", "e", "rev", "iso"):
        sel = trial == t
        fit = idf.fit_periodic_map(rec["angle_rad"][sel], rec["iq_hold_A"][sel], 6)
        rms = np.sqrt(fit.fit.jmin / fit.fit.n)
        print(f"| {t} | {', '.join(f'{k} ({fit.amplitude(k):.3f})' for k in fit.orders)} | "
              f"{fit.fit['c0']:+.3f} | {rms:.3f} |")
    sel = np.isin(trial, ["b", "d", "e", "rev"])
    direction = np.where(rec["sweep_direction"][sel] == "forward", 1.0, -1.0)
    fit = idf.fit_periodic_map(rec["angle_rad"][sel], rec["iq_hold_A"][sel], 6,
                               direction=direction)
    print(f"\ntrials b, d (forward) with e, rev (reverse): orders {fit.orders}, "
          f"Coulomb-like C = {fit.fit['C']:.4f} A (+- {fit.fit.std('C'):.4f}), "
          f"offset c0 = {fit.fit['c0']:+.4f} A")
    sel = trial == "b"
    fit = idf.fit_periodic_map(rec["angle_rad"][sel], rec["iq_hold_A"][sel], 6)
    plots._plot_map(rec["angle_rad"][sel], rec["iq_hold_A"][sel], fit, None,
                  out / "odrive_fit.png")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else None)
