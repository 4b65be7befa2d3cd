"""Kapun 2008 identification on records simulated by circuitsim, and on the ODrive map
(issue #6). Each netlist is simulated once; the repetitions add independent noise to it."""

from __future__ import annotations

import subprocess
import sys
import warnings

import numpy as np
import pytest

import circuitsim as cs
from circuitsim.loop import identify as idf

from conftest import HERE, NETLISTS

KAPUN = NETLISTS / "kapun2008"
PP, J_TOT, TS = 6, 104e-7, 100e-6
TABLE2 = {1: 5817e-6, 2: 3e-6, 3: 57e-6, 4: 0.0, 5: 28e-6}
TABLE3 = {"L_rra3": (94.3e-6, 2.3e-6), "L_rrb3": (52.7e-6, 3.0e-6),
          "L_rra6": (270.6e-6, 9.4e-6), "L_rrb6": (214.0e-6, 11.9e-6),
          "T_a1": (741.1e-6, 17.5e-6), "T_b1": (23.4e-6, 8.5e-6),
          "B": (52.5e-6, 10.6e-6), "C": (1320e-6, 343.8e-6)}
# encoder angle [rad], speed [rad/s], 12-bit current [A] and voltage [V] channels
NOISE_EMF = {"theta": 2e-5, "omega": 0.05, "e1": 5e-3}
NOISE_DRIVE = {"theta": 2e-5, "omega": 0.05, "i1": 5e-3, "i2": 5e-3, "i3": 5e-3}
ODRIVE = HERE / "data" / "odrive_cogging_b_e.csv"


def _record(name: str) -> dict[str, np.ndarray]:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = cs.compile(cs.load(KAPUN / f"{name}.yaml")).simulate()
    assert res.success, res.message
    return {"time": res.t, **{k: res[k] for k in ("theta", "omega", "i1", "i2", "i3", "e1")}}


@pytest.fixture(scope="module")
def emf_record():
    return _record("emf")


@pytest.fixture(scope="module")
def drive_record():
    rec = _record("bldc")
    assert rec["time"].size == 25_001 and rec["time"][1] == pytest.approx(TS)
    return rec


@pytest.fixture(scope="module")
def drive_fits(drive_record):
    """40 noisy copies of the torque test through observer + least squares."""
    emf = idf.emf_from_coefficients(TABLE2, None, PP)
    plain, compensated, steady = [], [], []
    for seed in range(40):
        n = idf.add_noise(drive_record, NOISE_DRIVE, seed)
        tm = idf.mutual_torque(n["theta"], [n["i1"], n["i2"], n["i3"]], emf)
        obs = idf.disturbance_observer(n["omega"], tm, J_TOT, TS)
        H, names = idf.disturbance_regressors(n["theta"], n["omega"], PP, (3, 6))
        Hf = idf.observer_filter(H, obs)
        compensated.append(idf.lstsq(Hf, obs.t_dist, names))
        plain.append(idf.lstsq(H, obs.t_dist, names))
        steady.append(idf.lstsq(Hf[10_000:], obs.t_dist[10_000:], names))
    return (idf.repeat_statistics(compensated), idf.repeat_statistics(plain),
            idf.repeat_statistics(steady))


def test_lstsq_recovers_exact_parameters_and_covariance():
    """x = H a + noise: â → a, and the covariance is σ² (HᵀH)⁻¹ (the textbook formula)."""
    rng = np.random.default_rng(1)
    H = np.column_stack([rng.normal(size=500), 1e-6 * rng.normal(size=500), np.ones(500)])
    a = np.array([2.0, 3e5, -1.0])
    fit = idf.lstsq(H, H @ a, ["x", "y", "z"])
    assert np.allclose(fit.values, a, rtol=1e-10)
    noise = rng.normal(0, 0.1, 500)
    fit = idf.lstsq(H, H @ a + noise, ["x", "y", "z"])
    resid = H @ a + noise - H @ fit.values
    s2 = resid @ resid / (500 - 3)
    assert np.allclose(fit.covariance, s2 * np.linalg.inv(H.T @ H), rtol=1e-8)


def test_observer_output_is_the_disturbance_through_its_loop():
    """A plant J w' = T_m - T_dist integrated by the trapezoidal rule: the observer's output is
    exactly H(z) T_dist with H the bilinear transform of (kp s + ki)/(J s² + kp s + ki)."""
    n = 4000
    t = np.arange(n) * TS
    t_dist = 1e-3 * (np.sin(2000 * t) + 0.5 * np.cos(370 * t) + (t > 0.1))
    t_m = 4e-3 + 1e-3 * np.sin(50 * t)
    acc = (t_m - t_dist) / J_TOT
    w = 3.0 + np.concatenate([[0.0], np.cumsum((acc[1:] + acc[:-1]) * TS / 2)])
    obs = idf.disturbance_observer(w, t_m, J_TOT, TS, bandwidth=800.0)
    assert np.max(np.abs(obs.t_dist - idf.observer_filter(t_dist, obs))) < 1e-9 * 1e-3
    # and it converges to the disturbance itself once the loop has settled (slow content)
    slow = idf.disturbance_observer(w, t_m, J_TOT, TS, bandwidth=3000.0)
    late = t > 0.2
    assert np.max(np.abs(slow.t_dist - t_dist)[late]) < 0.05e-3


def test_table2_back_emf_within_1_percent(emf_record):
    """Table 2 from 10 noisy open-circuit records: harmonics 1, 3, 5 within 1 %, the even
    ones near zero; phases 2 and 3 are alike by construction of the netlist."""
    fits = []
    for seed in range(10):
        n = idf.add_noise(emf_record, NOISE_EMF, seed)
        fits.append(idf.fit_back_emf(n["theta"], n["omega"], n["e1"], PP, range(1, 6)))
    st = idf.repeat_statistics(fits)
    for k in (1, 3, 5):
        assert st.row(f"a{k}")[0] == pytest.approx(TABLE2[k], rel=0.01)
    assert abs(st.row("a4")[0]) < 0.5e-6
    for k in range(1, 6):
        assert abs(st.row(f"b{k}")[0]) < 0.5e-6  # the paper: all L_rb = 0
    peak, rms = idf.emf_constants(fits[0])
    assert rms == pytest.approx(24.7e-3, abs=0.05e-3)
    assert peak == pytest.approx(34.72e-3, abs=0.05e-3)  # see test_bldc: Eq. 25 prints 35.1


def test_emf_error_curve_selects_1_3_5(emf_record):
    """J_min versus K drops at K = 1, 3, 5 only (the paper's Fig. 6), with noise present;
    the record's speed is not constant."""
    n = idf.add_noise(emf_record, NOISE_EMF, 99)
    curve = idf.emf_error_curve(n["theta"], n["omega"], n["e1"], PP, 9)
    assert idf.relevant_orders(curve) == (1, 3, 5)
    assert np.all(np.diff(curve) <= 0)
    run = emf_record["time"] > 0.5
    w = emf_record["omega"][run]
    assert w.max() - w.min() > 0.1 * w.mean()


def test_table3_within_the_papers_spread(drive_fits):
    """40 noisy torque-test records (25 000 samples of 100 us each) through the observer and
    least squares: every Table 3 mean recovered within the paper's standard deviation."""
    st = drive_fits[0]
    assert st.m == 40
    for name, (mu, sd) in TABLE3.items():
        assert abs(st.row(name)[0] - mu) < sd, name


def test_coulomb_friction_is_poorly_identified_and_correlated_with_B(drive_fits):
    """B and C trade off (correlation near -1 over the 40 records). C is told apart from B
    only by the start-up: from the steady part of the same records its spread exceeds 50 %
    of its value and grows a hundredfold, while the cogging harmonics barely change."""
    full, _, steady = drive_fits
    assert full.correlation("B", "C") < -0.95
    assert steady.correlation("B", "C") < -0.999
    assert steady.row("C")[1] > 0.5 * TABLE3["C"][0]
    assert steady.row("C")[1] > 100 * full.row("C")[1]
    assert steady.row("L_rra6")[1] < 2 * full.row("L_rra6")[1]
    # the relative spread of C is the largest of the well-excited parameters
    rel = {n: full.row(n)[1] / abs(full.row(n)[0]) for n in ("B", "C", "L_rra6", "T_a1")}
    assert max(rel, key=rel.get) == "C"


def test_observer_lag_biases_the_plain_fit(drive_fits):
    """Fitting the compensator output directly (Kapun's fit) at a 1 kHz observer loop lifts the
    36-per-turn harmonic by a few per cent; passing the regressors through the loop removes it."""
    full, plain, _ = drive_fits
    for name in ("L_rra6", "L_rrb6"):
        err_plain = abs(plain.row(name)[0] - TABLE3[name][0]) / TABLE3[name][0]
        err_comp = abs(full.row(name)[0] - TABLE3[name][0]) / TABLE3[name][0]
        assert err_comp < 0.005
        assert err_plain > 3 * err_comp


def test_peak_cogging_of_the_identified_harmonics(drive_fits):
    est = {n: v for n, v in zip(drive_fits[0].names, drive_fits[0].mean, strict=True)}
    peak, at = idf.peak_cogging(est, PP, (3, 6))
    assert peak == pytest.approx(7.01e-3, abs=0.05e-3)
    assert at == pytest.approx(0.3228, abs=2e-3)


def test_odrive_cogging_map_dominant_orders():
    """The ODrive holding-current map (12 slots, 7 pole pairs): the greedy least squares finds
    orders 7 (electrical), 28, 14, 36, 12 (slot harmonics) first, then 84 = lcm(12, 14); the
    forward/reverse offset is a Coulomb-like term of about 0.17-0.19 A (data README)."""
    rec = idf._read_csv(str(ODRIVE))
    fwd = rec["trial"] == "b"
    fit = idf.fit_periodic_map(rec["angle_rad"][fwd], rec["iq_hold_A"][fwd], 6)
    assert fit.orders[:5] == (7, 28, 14, 36, 12)
    assert 84 in fit.orders
    assert fit.amplitude(28) == pytest.approx(0.56, abs=0.02)
    assert all(np.diff(fit.curve) < 0)
    direction = np.where(rec["sweep_direction"] == "forward", 1.0, -1.0)
    both = idf.fit_periodic_map(rec["angle_rad"], rec["iq_hold_A"], 6, direction=direction)
    assert 0.15 < both.fit["C"] < 0.21
    # both sweeps repeat the slot harmonics
    rev = idf.fit_periodic_map(rec["angle_rad"][~fwd], rec["iq_hold_A"][~fwd],
                               orders=fit.orders)
    for k in (28, 14, 36, 12):
        assert rev.amplitude(k) == pytest.approx(fit.amplitude(k), rel=0.1)


def _cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "circuitsim.cli", *args], check=False,
                          capture_output=True,
                          text=True, timeout=120)


def test_cli_identify_chain(tmp_path, emf_record, drive_record):
    """`identify emf` → coefficients; `identify cogging` on a raw record runs the observer."""
    n = idf.add_noise(emf_record, NOISE_EMF, 3)
    emf_csv = tmp_path / "emf.csv"
    cols = ["time", "theta", "omega", "e1"]
    np.savetxt(emf_csv, np.column_stack([n[c] for c in cols]), delimiter=",",
               header=",".join(cols), comments="")
    out = _cli("identify", "emf", str(emf_csv), "--pp", "6", "--json")
    assert out.returncode == 0, out.stderr
    import json

    res = json.loads(out.stdout)
    assert res["relevant_orders"] == [1, 3, 5]
    assert res["a"]["1"] == pytest.approx(5817e-6, rel=1e-3)
    d = idf.add_noise(drive_record, NOISE_DRIVE, 4)
    drv_csv = tmp_path / "drive.csv"
    cols = ["time", "theta", "omega", "i1", "i2", "i3"]
    np.savetxt(drv_csv, np.column_stack([d[c] for c in cols]), delimiter=",",
               header=",".join(cols), comments="")
    emf_arg = ",".join(f"{k}:{res['a'][str(k)]}" for k in (1, 2, 3, 4, 5))
    out = _cli("identify", "cogging", str(drv_csv), "--pp", "6", "--J", "1.04e-5",
               "--emf", emf_arg, "--json")
    assert out.returncode == 0, out.stderr
    mech = json.loads(out.stdout)
    for name in ("L_rra6", "L_rrb6", "B"):
        assert abs(mech[name] - TABLE3[name][0]) < TABLE3[name][1]
    bad = _cli("identify", "emf", str(emf_csv), "--pp", "6", "--voltage", "e9")
    assert bad.returncode == 2 and "no column 'e9'" in bad.stderr


def test_cli_identify_map():
    out = _cli("identify", "map", str(ODRIVE), "--where", "trial=b", "--count", "5")
    assert out.returncode == 0, out.stderr
    assert "28" in out.stdout and "36" in out.stdout


@pytest.mark.parametrize("argv, words", [
    (["emf", "--pp", "0"], "--pp: '0' must lie in 1..500"),  # was a LinAlgError traceback
    (["emf", "--pp", "-6"], "--pp: '-6' must lie in 1..500"),  # was a result for p = -6
    (["emf", "--pp", "6", "--k-max", "100000000"], "must lie in 1..1000"),  # was a hang
    (["emf", "--pp", "6", "--rel-tol", "nan"], "--rel-tol: 'nan' must be a finite number"),
    (["emf", "--pp", "6", "--rel-tol", "2"], "must be a fraction in (0, 1)"),
    (["cogging", "--pp", "6", "--J", "0"], "--J: '0' must be a finite number > 0"),
    (["map", "--count", "0"], "--count: '0' must lie in 1..1000"),
])
def test_identify_options_out_of_range_are_refused_before_any_work(argv, words, capsys):
    from circuitsim.cli.main import main

    with pytest.raises(SystemExit) as exc:
        main(["identify", argv[0], "no-such-record.csv", *argv[1:]])
    assert exc.value.code == 2 and words in capsys.readouterr().err


@pytest.mark.parametrize("text", ["0,3", "-1", "1:5e-3,0:1"])
def test_harmonic_orders_below_one_are_refused(text):
    from circuitsim.loop.record import DataError

    with pytest.raises(DataError, match=">= 1"):
        if ":" in text:
            idf._emf_arg(text, 6)
        else:
            idf._ints(text)
