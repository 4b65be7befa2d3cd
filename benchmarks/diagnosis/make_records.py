"""Generate the diagnosis benchmark's records (deterministic) and its truth file.

    python benchmarks/diagnosis/make_records.py            # all records -> records/*.csv
    python benchmarks/diagnosis/make_records.py --only c01,n02
    python benchmarks/diagnosis/make_records.py --truth-only   # rewrite truth.json only

Uses simulators.py only (scipy): circuitsim is not imported. Each record is a CSV with a
``time`` column [s], one column per probe [SI] (and the input column ``u`` [V] for motor B's
slow regime), written to records/<id>.csv (git-ignored; about 0.2-0.9 MB each). truth.json
(committed) holds, per record, the motor, netlist, regime, noise, class, true effects with
their physical parameters and the values the catalog's parameters should take, the declared
parameters the user frees, the split, and the effect's signature in noise sigmas.

The split is fixed by a rule (README.md): within each class, in id order, every third record
(the 3rd, 6th, ...) is ``heldout``; the others are ``tune``.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import recordkit
import simulators as sims

RECORDS = HERE / "records"
TRUTH = HERE / "truth.json"

REGIMES = {  # sample rate [Hz], duration [s], netlist (relative to the repository root)
    ("A", "fast"): (50e3, 0.4, "netlists/kim2024/base.yaml"),
    ("B", "fast"): (20e3, 0.4, "benchmarks/diagnosis/netlists/motor_b_fast.yaml"),
    ("B", "slow"): (1e3, 5.0, "benchmarks/diagnosis/netlists/motor_b.yaml"),
    ("C", "reversing"): (10e3, 0.6, "benchmarks/diagnosis/netlists/motor_c.yaml"),
}
WHITE = {  # the default white noise per probe [SI]
    ("A", "fast"): {"i_total": 5e-3, "speed": 0.05},
    ("B", "fast"): {"current": 2e-3, "speed": 0.05},
    ("B", "slow"): {"current": 3e-3, "speed": 0.1},
    ("C", "reversing"): {"current": 2e-3, "speed": 0.05, "load_speed": 0.05},
}
# every element of the armature loop: a series resistance anywhere in it is the same effect
LOOP = {"A": ["Ra", "La", "Lc1", "Lc2", "M", "Vin"], "B": ["Ra", "La", "M", "Vin", "U"],
        "C": ["Ra", "La", "M", "Vin"]}
SOURCE = {("A", "fast"): "Vin", ("B", "fast"): "Vin", ("B", "slow"): "U",
          ("C", "reversing"): "Vin"}
# terms the declared netlist already has: an accepted effect of this kind corrects a declared
# term and is not a new effect (it is reported, not scored)
DECLARED = {"A": [{"effect": "emf-harmonic", "target": "M", "order": 8}], "B": [], "C": []}
MARGINAL_SIGMA = 8.0
#: scalar catalog effects a marginal record's truth is compared with (motors A and B), each
#: at a size small enough for its imprint to be linear in it
ALTERNATIVES = (
    ("series-resistance", {"Rser": 1e-3}), ("brush-drop", {"Vb": 1e-3, "Vb_eps": 5e-3}),
    ("coulomb-friction", {"Fc": 1e-5, "wc": 0.05}), ("viscous-friction", {"Bx": 1e-7}),
    ("inductance", {"Ls": 1e-6}), ("resistance-drift", {"drift": ("linear", 1e-3)}),
)


# ---------------------------------------------------------------------- effect helpers
# Each returns (simulator fx fragment, truth entry). ``expected``: the value each free
# parameter of the catalog's patch should take (by the suffix of its name), where the patch
# has the same functional form; ``also_accept``: other catalog labels that are the same
# physics in this circuit (with their own expected values).

def series_resistance(m, rg, r):
    return {"Rser": r}, {
        "effect": "series-resistance", "target": "Ra", "targets": LOOP[m],
        "parameters": {"R_series_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "source-resistance", "targets": [SOURCE[(m, rg)]],
                         "expected": {"R": r}}]}


def source_resistance(m, rg, r):
    return {"Rs": r}, {
        "effect": "source-resistance", "target": SOURCE[(m, rg)], "targets": [SOURCE[(m, rg)]],
        "parameters": {"R_source_ohm": r}, "expected": {"R": r},
        "also_accept": [{"effect": "series-resistance", "targets": LOOP[m],
                         "expected": {"R": r}}]}


def brush_drop(m, rg, vb):
    return {"Vb": vb, "Vb_eps": 5e-3}, {
        "effect": "brush-drop", "target": "M", "targets": ["M"],
        "parameters": {"V_brush_V": vb, "i_smoothing_A": 5e-3}, "expected": {"Vb": vb}}


def coulomb(m, rg, fc):
    return {"Fc": fc, "wc": 0.05}, {
        "effect": "coulomb-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"T_coulomb_Nm": fc, "w_smoothing_rad_s": 0.05}, "expected": {"c": fc},
        "also_accept": [{"effect": "force-offset", "targets": ["rotor"],
                         "expected": {"F": -fc}}]}


def coulomb_load(m, rg, fc):
    """Coulomb friction on motor C's load node (it turns both ways: not a torque offset)."""
    return {"Fc_load": fc, "wc_load": 0.05}, {
        "effect": "coulomb-friction", "target": "load", "targets": ["load"],
        "parameters": {"T_coulomb_Nm": fc, "w_smoothing_rad_s": 0.05}, "expected": {"c": fc}}


def backlash(m, rg, gap):
    """A play of total width ``gap`` [rad] in motor C's coupling K (the catalog's free
    parameter backlash_K_gap)."""
    return {"backlash": gap}, {
        "effect": "backlash", "target": "K", "targets": ["K"],
        "parameters": {"gap_rad": gap, "form": "0 while |phi_rel| < gap/2, else "
                       "c (phi_rel -+ gap/2) + d w_rel, the damping never pulling"},
        "expected": {"gap": gap}}


def viscous(m, rg, bx):
    return {"Bx": bx}, {
        "effect": "viscous-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"B_extra_Nms_rad": bx}, "expected": {"b": bx}}


def cogging(m, rg, order, amp, ph):
    return {"cogging": [(order, amp, ph)]}, {
        "effect": "cogging", "target": "rotor", "targets": ["rotor"], "order": order,
        "parameters": {"order": order, "T_cogging_Nm": amp, "phase_rad": ph},
        "expected": {"a": amp * math.cos(ph), "b": amp * math.sin(ph)}}


def emf_harmonic(m, rg, order, slope, ph):
    return {"emf": [(order, slope, ph)]}, {
        "effect": "emf-harmonic", "target": "M", "targets": ["M"], "order": order,
        "parameters": {"order": order, "slope_V_s_rad": slope, "phase_rad": ph},
        "expected": {"a": slope * math.cos(ph), "b": slope * math.sin(ph)}}


def saturation(m, rg, ipar, ratio):
    return {"sat": (ipar, ratio)}, {
        "effect": "inductor-saturation", "target": "La", "targets": ["La"],
        "parameters": {"I_knee_A": ipar, "L_ratio_saturated": ratio},
        "expected": {"Ipar": ipar, "ratio": ratio}}


#: the declared armature inductance the supply's is in series with [H]
L_DECLARED = {"A": 0.87e-3, "B": 1.2e-3, "C": 1.2e-3}


def supply_inductance(m, rg, ls):
    """An inductance ``ls`` [H] between the supply and the drive: in series with the
    armature, it is the declared La off by ls / La, which the catalog reports as a
    correction of La (not as a new cause)."""
    return {"Ls": ls}, {
        "effect": "inductance", "target": "La", "targets": ["La"], "correction": True,
        "parameters": {"L_supply_H": ls}, "expected": {"dL": ls / L_DECLARED[m]}}


def drift_linear(m, rg, alpha):
    return {"drift": ("linear", alpha)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + alpha*t)", "alpha_per_s": alpha},
        "expected": {"alpha": alpha}}


def drift_heating(m, rg, rise, tau):
    return {"drift": ("heating", rise, tau)}, {
        "effect": "resistance-drift", "target": "Ra", "targets": ["Ra"],
        "parameters": {"form": "R0*(1 + rise*(1 - exp(-t/tau)))", "rise": rise, "tau_s": tau},
        "expected": {"rise": rise, "tau": tau}}


def sensor(m, rg, probe, kind, value):
    key = {"gain": "sensor-gain", "offset": "sensor-offset", "delay": "sensor-delay"}[kind]
    return {"sensor": {probe: {kind: value}}}, {
        "effect": key, "target": probe, "targets": [probe],
        "parameters": {kind: value}, "expected": {kind: value}}


def stribeck(m, rg, fs, fc, ws, wc=0.05):
    return {"stribeck": (fs, fc, ws, wc)}, {
        "effect": "stribeck-friction", "target": "rotor", "targets": ["rotor"],
        "parameters": {"T_breakaway_Nm": fs, "T_coulomb_Nm": fc, "w_stribeck_rad_s": ws,
                       "w_smoothing_rad_s": wc,
                       "form": "(Tc + (Tbrk - Tc) exp(-(w/ws)^2)) tanh(w/wc)"},
        # the catalog's peak s stands over its Coulomb level c
        "expected": {"c": fc, "s": fs - fc, "ws": ws}}


def unbalance(m, rg, amp, ph):
    return {"unbalance": (amp, ph)}, {
        "effect": "unbalance", "target": "rotor", "targets": ["rotor"], "order": 1,
        "parameters": {"m_g_r_Nm": amp, "phase_rad": ph},
        "expected": {"a": amp * math.cos(ph), "b": amp * math.sin(ph)},
        "also_accept": [{"effect": "cogging", "targets": ["rotor"], "order": 1,
                         "expected": {"a": amp * math.cos(ph), "b": amp * math.sin(ph)}}]}


def outside(kind, fx, params):
    return fx, {"effect": f"outside:{kind}", "target": None, "targets": None,
                "parameters": params, "expected": {}}


def add(*parts):
    fx, effects = {}, []
    for f, e in parts:
        for k, v in f.items():
            if k in ("cogging", "emf", "load_ripple") and k in fx:
                fx[k] = [*fx[k], *v]
            elif k == "sensor" and k in fx:
                fx[k] = {**fx[k], **v}
            else:
                fx[k] = v
        effects.append(e)
    return fx, effects


# ---------------------------------------------------------------------- the record list

def _torsion(jm, j2, f, zeta):
    ks = (2 * math.pi * f) ** 2 / (1 / jm + 1 / j2)
    cs = 2 * zeta * math.sqrt(ks * jm * j2 / (jm + j2))
    return j2, ks, cs


def record_specs() -> list[dict]:
    """Every record: id, class, motor, regime, a builder of (fx, effects) from an amplitude
    (``marginal``: the amplitude is scaled so the signature is MARGINAL_SIGMA), noise, free."""
    A, B = "A", "B"
    S = []

    def rec(rid, cls, motor, regime, build=None, amp=None, marginal=False, noise=None,
            free=(), note=""):
        S.append({"id": rid, "class": cls, "motor": motor, "regime": regime,
                  "build": build or (lambda a: ({}, [])), "amp": amp, "marginal": marginal,
                  "noise": noise, "free": list(free), "note": note})

    # ---- null: nothing is missing from the declared model
    rec("n01", "null", A, "fast", note="white noise")
    rec("n02", "null", A, "fast", noise={"i_total": {"ar1": [5e-3, 0.9]},
                                          "speed": {"white": 0.05}},
        note="AR(1) current noise, phi 0.9")
    rec("n03", "null", A, "fast",
        build=lambda a: ({"params": {"Ra": 1.1 * 1.03, "B": 2.95e-4 * 0.97}}, []),
        free=["Ra", "B"], note="declared Ra 3 % low and B 3 % high; the user frees Ra, B")
    rec("n04", "null", B, "slow", noise={"current": {"white": 3e-3}, "speed": {"pink": 0.3}},
        note="1/f speed noise")
    rec("n05", "null", B, "fast", noise={"current": {"white": 2e-3, "quant": 4e-3},
                                          "speed": {"white": 0.05, "quant": 0.1}},
        note="ADC quantisation (4 mA, 0.1 rad/s steps)")
    rec("n06", "null", B, "slow",
        build=lambda a: ({"params": {"R": 2.5 * 1.03, "J": 4e-6 * 0.97}}, []),
        free=["R", "J"], note="declared R 3 % low and J 3 % high; the user frees R, J")

    # ---- one catalog effect
    rec("c01", "catalog", A, "fast", lambda a: add(series_resistance(A, "fast", a)), 0.08,
        note="strong")
    rec("c02", "catalog", A, "fast", lambda a: add(coulomb(A, "fast", a)), 2e-3,
        marginal=True)
    rec("c03", "catalog", A, "fast", lambda a: add(saturation(A, "fast", a, 0.5)), 1.2,
        note="strong")
    rec("c04", "catalog", A, "fast", lambda a: add(emf_harmonic(A, "fast", 16, a, 0.7)),
        1e-4, marginal=True)
    rec("c05", "catalog", A, "fast", lambda a: add(sensor(A, "fast", "i_total", "delay", a)),
        2e-7, marginal=True)
    rec("c06", "catalog", A, "fast", lambda a: add(unbalance(A, "fast", a, 0.4)), 1e-3,
        note="strong")
    rec("c07", "catalog", B, "fast", lambda a: add(brush_drop(B, "fast", a)), 0.25,
        note="strong")
    rec("c08", "catalog", B, "fast", lambda a: add(cogging(B, "fast", 6, a, -0.5)), 1e-4,
        marginal=True)
    rec("c09", "catalog", B, "fast",
        lambda a: add(sensor(B, "fast", "current", "offset", a)), 0.01, note="strong")
    rec("c10", "catalog", B, "slow", lambda a: add(viscous(B, "slow", a)), 1e-6,
        note="50 % more viscous friction than declared")
    rec("c11", "catalog", B, "slow", lambda a: add(drift_heating(B, "slow", a, 2.0)), 0.08,
        note="armature warming up: +8 % with a 2 s time constant")
    rec("c12", "catalog", B, "slow", lambda a: add(stribeck(B, "slow", 2.5e-3, a, 5.0)),
        1e-3, note="breakaway 2.5 mN m, Coulomb 1 mN m")

    # ---- two catalog effects
    rec("t01", "two", A, "fast",
        lambda a: add(series_resistance(A, "fast", 0.05), coulomb(A, "fast", 5e-3)))
    rec("t02", "two", A, "fast",
        lambda a: add(saturation(A, "fast", 1.5, 0.6), cogging(A, "fast", 16, 3e-3, 1.0)))
    rec("t03", "two", B, "slow",
        lambda a: add(brush_drop(B, "slow", 0.2), viscous(B, "slow", 1e-6)))
    rec("t04", "two", B, "slow",
        lambda a: add(drift_linear(B, "slow", 0.02), sensor(B, "slow", "speed", "gain", 0.97)))
    rec("t05", "two", B, "fast",
        lambda a: add(source_resistance(B, "fast", 0.3), cogging(B, "fast", 6, 5e-4, 0.3)))
    rec("t06", "two", A, "fast",
        lambda a: add(sensor(A, "fast", "i_total", "offset", 0.02), viscous(A, "fast", 2e-5)))

    # ---- outside the catalog
    rec("o01", "outside", A, "fast", lambda a: add(outside(
        "supply-ripple", {"supply_ripple": (0.3, 100.0, "rectified")},
        {"amplitude_V": 0.3, "frequency_Hz": 100.0,
         "shape": "0.3*(|sin(pi*100*t)| - 2/pi): rectified 50 Hz mains"})))
    rec("o02", "outside", A, "fast", lambda a: add(outside(
        "torsional-resonance", {"torsion": _torsion(4.57e-6, 2e-6, 300.0, 0.05)},
        dict(zip(("J2_kgm2", "k_shaft_Nm_rad", "c_shaft_Nms_rad"),
                 _torsion(4.57e-6, 2e-6, 300.0, 0.05), strict=True), resonance_Hz=300.0))))
    rec("o03", "outside", B, "fast", lambda a: add(outside(
        "pwm-chopper", {"chopper": (0.15, 3000.0, 0.1)},
        {"amplitude_V": 0.15, "frequency_Hz": 3000.0,
         "shape": "0.15*tanh(sin(2 pi 3000 t)/0.1)"})))
    rec("o04", "outside", B, "slow", lambda a: add(outside(
        "belt-order-1.5", {"belt": (1.5, 4e-4, 0.0)},
        {"order": 1.5, "T_Nm": 4e-4, "shape": "shaft receives T sin(1.5 theta)"})))
    rec("o05", "outside", B, "fast", lambda a: add(outside(
        "supply-ripple", {"supply_ripple": (0.2, 100.0, "sine")},
        {"amplitude_V": 0.2, "frequency_Hz": 100.0, "shape": "0.2*sin(2 pi 100 t)"})))
    rec("o06", "outside", B, "slow", lambda a: add(outside(
        "torsional-resonance", {"torsion": _torsion(4e-6, 3e-6, 40.0, 0.1)},
        dict(zip(("J2_kgm2", "k_shaft_Nm_rad", "c_shaft_Nms_rad"),
                 _torsion(4e-6, 3e-6, 40.0, 0.1), strict=True), resonance_Hz=40.0))))

    # the split: within each class, in id order, every third record is held out
    by_class: dict[str, int] = {}
    for s in S:
        k = by_class.get(s["class"], 0) + 1
        by_class[s["class"]] = k
        s["split"] = "heldout" if k % 3 == 0 else "tune"
        s["seed"] = 1000 + S.index(s)
    return S + fresh_specs() + fresh2_specs() + fresh3_specs()


def fresh_specs() -> list[dict]:
    """A second blind set, written when the catalog gained a free Stribeck speed and a
    warm-up law (round 3) and run once on the final code of that round, before anyone looked
    at its records: other amplitudes, time constants, speeds, noise and frequencies."""
    A, B = "A", "B"
    S: list[dict] = []

    def rec(rid, cls, motor, regime, build=None, noise=None, note=""):
        S.append({"id": rid, "class": cls, "motor": motor, "regime": regime,
                  "build": build or (lambda a: ({}, [])), "amp": None, "marginal": False,
                  "noise": noise, "free": [], "note": note, "split": "fresh",
                  "seed": 2000 + len(S)})

    rec("f01", "null", B, "fast", noise={"current": {"ar1": [3e-3, 0.8]},
                                          "speed": {"white": 0.05}},
        note="AR(1) current noise, phi 0.8")
    rec("f02", "catalog", A, "fast", lambda a: add(source_resistance(A, "fast", 0.04)))
    rec("f03", "catalog", B, "slow", lambda a: add(drift_heating(B, "slow", 0.05, 1.0)),
        note="armature warming up: +5 % with a 1 s time constant")
    rec("f04", "catalog", B, "slow", lambda a: add(stribeck(B, "slow", 2e-3, 8e-4, 2.0)),
        note="breakaway 2 mN m, Coulomb 0.8 mN m, Stribeck speed 2 rad/s")
    rec("f05", "catalog", B, "fast", lambda a: add(sensor(B, "fast", "speed", "gain", 1.02)))
    rec("f06", "two", A, "fast",
        lambda a: add(brush_drop(A, "fast", 0.1), viscous(A, "fast", 1e-5)))
    rec("f07", "outside", A, "fast", lambda a: add(outside(
        "supply-ripple", {"supply_ripple": (0.2, 150.0, "sine")},
        {"amplitude_V": 0.2, "frequency_Hz": 150.0, "shape": "0.2*sin(2 pi 150 t)"})))
    rec("f08", "outside", B, "slow", lambda a: add(outside(
        "torsional-resonance", {"torsion": _torsion(4e-6, 2e-6, 60.0, 0.05)},
        dict(zip(("J2_kgm2", "k_shaft_Nm_rad", "c_shaft_Nms_rad"),
                 _torsion(4e-6, 2e-6, 60.0, 0.05), strict=True), resonance_Hz=60.0))))
    return S


def fresh2_specs() -> list[dict]:
    """The blind set of motor C (a two-mass drive with a compliant coupling K, catalog entry
    ``backlash`` added): written before the backlash entry existed and run once by someone
    else. Probes current, speed and load_speed, except g07 (no load encoder)."""
    C, rg = "C", "reversing"
    S: list[dict] = []

    def rec(rid, cls, build=None, amp=None, marginal=False, noise=None, probes=None, note=""):
        S.append({"id": rid, "class": cls, "motor": C, "regime": rg,
                  "build": build or (lambda a: ({}, [])), "amp": amp, "marginal": marginal,
                  "iters": 5, "noise": noise, "free": [], "note": note, "split": "fresh2",
                  "seed": 3000 + len(S), **({"probes": probes} if probes else {})})

    rec("g01", "null", noise={"current": {"ar1": [2e-3, 0.9]}, "speed": {"white": 0.05},
                              "load_speed": {"ar1": [0.05, 0.7]}},
        note="AR(1) current (phi 0.9) and load-speed (phi 0.7) noise")
    rec("g02", "catalog", lambda a: add(backlash(C, rg, a)), 0.02,
        note="strong: 20 mrad (1.15 deg) of play")
    # the clipped contact damping makes a vanishing play differ from the spring_damper
    # (~18 sigma of speed here): g03's play is scaled so that its own imprint, beyond that
    # limit (a play of 1e-8 rad), is MARGINAL_SIGMA
    rec("g03", "catalog", lambda a: add(backlash(C, rg, a)), 1e-4, marginal=True,
        note="marginal: the play's imprint beyond a vanishing play's is 8 sigma (against the "
             "declared spring_damper it is larger: the clipped damping alone makes ~18 "
             "sigma of speed)")
    S[-1]["marginal_vs"] = {"backlash": 1e-8}
    rec("g04", "catalog", lambda a: add(backlash(C, rg, a)), 0.01,
        noise={"current": {"white": 2e-3, "quant": 5e-3},
               "speed": {"white": 0.05, "quant": 0.1},
               "load_speed": {"pink": 0.1, "quant": 0.1}},
        note="10 mrad of play; ADC steps 5 mA and 0.1 rad/s, 1/f load-speed noise")
    rec("g05", "two", lambda a: add(backlash(C, rg, 0.005), coulomb_load(C, rg, 1e-3)),
        note="5 mrad of play and a 1 mN m Coulomb friction on the load")
    rec("g06", "outside", lambda a: add(outside(
        "hardening-coupling", {"hardening": 30.0},
        {"k_hardening_per_rad2": 30.0,
         "shape": "coupling torque c phi_rel (1 + 30 phi_rel^2) + d w_rel: +7.5 % stiffness "
                  "at 50 mrad of twist"})),
        note="a hardening coupling (no play)")
    rec("g07", "catalog", lambda a: add(backlash(C, rg, a)), 0.008,
        probes=["current", "speed"],
        note="8 mrad of play; no load encoder: current and motor speed only")
    return S


def fresh3_specs() -> list[dict]:
    """The blind set of the supply inductance (catalog entry ``inductance``, a correction of
    the declared inductance it is in series with): written after that entry, before anyone
    ran these records, and run once. Three motors, both regimes, one marginal, one with a
    second effect, one null with coloured and quantised noise."""
    S: list[dict] = []

    def rec(rid, cls, motor, regime, build=None, amp=None, marginal=False, noise=None,
            note=""):
        S.append({"id": rid, "class": cls, "motor": motor, "regime": regime,
                  "build": build or (lambda a: ({}, [])), "amp": amp, "marginal": marginal,
                  "iters": 3, "noise": noise, "free": [], "note": note, "split": "fresh3",
                  "seed": 4000 + len(S)})

    rec("h01", "catalog", "A", "fast", lambda a: add(supply_inductance("A", "fast", a)), 0.2e-3,
        note="0.2 mH of supply inductance before the varistor")
    rec("h02", "catalog", "B", "slow", lambda a: add(supply_inductance("B", "slow", a)), 0.5e-3,
        noise={"current": {"ar1": [3e-3, 0.8]}, "speed": {"white": 0.1}},
        note="0.5 mH of supply inductance; AR(1) current noise, phi 0.8")
    rec("h03", "catalog", "B", "fast", lambda a: add(supply_inductance("B", "fast", a)), 0.05e-3,
        marginal=True, note="")
    rec("h04", "catalog", "C", "reversing",
        lambda a: add(supply_inductance("C", "reversing", a)), 0.4e-3,
        noise={"current": {"white": 2e-3, "quant": 5e-3}, "speed": {"white": 0.05, "quant": 0.1},
               "load_speed": {"white": 0.05}},
        note="0.4 mH of supply inductance; ADC steps 5 mA and 0.1 rad/s")
    rec("h05", "two", "B", "fast", lambda a: add(supply_inductance("B", "fast", 0.3e-3),
                                                 brush_drop("B", "fast", 0.2)),
        note="0.3 mH of supply inductance and a 0.2 V brush drop")
    rec("h06", "null", "B", "slow", noise={"current": {"ar1": [3e-3, 0.9], "quant": 2e-3},
                                           "speed": {"pink": 0.2}},
        note="AR(1) current noise (phi 0.9) with 2 mA ADC steps; 1/f speed noise")
    return S


# ---------------------------------------------------------------------- generation

_NULL_CACHE: dict = {}


def _grid(motor, regime):
    fs, dur, _ = REGIMES[(motor, regime)]
    return np.arange(round(dur * fs) + 1) / fs


def _null(motor, regime):
    key = (motor, regime)
    if key not in _NULL_CACHE:
        _NULL_CACHE[key] = sims.simulate(motor, regime, _grid(motor, regime))
    return _NULL_CACHE[key]


def signature(motor, regime, clean, probes=None) -> dict[str, float]:
    """||effect - null|| / white sigma, per probe: the size of the effect's imprint in noise
    sigmas of the default white noise (a matched-filter SNR before any refit). ``probes``:
    the record's probes (default: all of the motor's)."""
    null = _null(motor, regime)
    return {p: float(np.linalg.norm(clean[p] - null[p]) / s)
            for p, s in WHITE[(motor, regime)].items() if probes is None or p in probes}


def separations(spec, clean) -> dict[str, float]:
    """How far a marginal record's truth is from each scalar alternative, in noise sigmas:
    min over a of || imprint(truth) - a imprint(alternative) || (white sigmas per probe, the
    alternatives' imprints linear at their small size). Below ~2 sigma no test can tell the
    two apart from this record, whatever the method: the record is a tie by construction."""
    motor, regime = spec["motor"], spec["regime"]
    t, null = _grid(motor, regime), _null(motor, regime)
    white = {p: s for p, s in WHITE[(motor, regime)].items() if p in probes_of(spec)}

    def imprint(y):
        return np.concatenate([(y[p] - null[p]) / s for p, s in white.items()])
    truth = imprint(clean)
    _, effects = spec["build"](spec["amp"])
    own = {lab["effect"] for e in effects for lab in [e, *e.get("also_accept", [])]}
    out = {}
    for label, fx in ALTERNATIVES:
        if label in own:
            continue
        alt = imprint(sims.simulate(motor, regime, t, fx))
        a = float(truth @ alt / (alt @ alt))
        out[label] = float(np.linalg.norm(truth - a * alt))
    return out


def probes_of(spec) -> list[str]:
    return list(spec.get("probes") or sims.PROBES[spec["motor"]])


def build(spec) -> tuple[dict, list, dict, dict]:
    motor, regime = spec["motor"], spec["regime"]
    t = _grid(motor, regime)
    amp = spec["amp"]
    fx, effects = spec["build"](amp)
    clean = sims.simulate(motor, regime, t, fx)
    sig = signature(motor, regime, clean, probes_of(spec))
    # a marginal record is scaled on its imprint against the null, or against ``marginal_vs``
    # (the effect's limit at a vanishing amplitude, where that limit is not the null)
    ref = sims.simulate(motor, regime, t, spec["marginal_vs"]) if "marginal_vs" in spec \
        else None

    def scaled_sig():
        if ref is None:
            return sig
        return {p: float(np.linalg.norm(clean[p] - ref[p]) / s)
                for p, s in WHITE[(motor, regime)].items() if p in probes_of(spec)}
    if spec["marginal"]:
        for _ in range(spec.get("iters", 2)):  # scale the amplitude (near-linear imprint)
            amp = amp * MARGINAL_SIGMA / max(scaled_sig().values())
            fx, effects = spec["build"](amp)
            clean = sims.simulate(motor, regime, t, fx)
            sig = signature(motor, regime, clean, probes_of(spec))
        if ref is not None:
            spec["signature_beyond"] = scaled_sig()
    return fx, effects, clean, sig


def noise_spec(spec) -> dict:
    if spec["noise"] is not None:
        return spec["noise"]
    return {p: {"white": s} for p, s in WHITE[(spec["motor"], spec["regime"])].items()
            if p in probes_of(spec)}


def truth_entry(spec, effects, sig) -> dict:
    motor, regime = spec["motor"], spec["regime"]
    fs, dur, netlist = REGIMES[(motor, regime)]
    ns = noise_spec(spec)
    declared_error = {}
    fx0, _ = spec["build"](spec["amp"])
    if "params" in fx0:
        base = {"A": sims.MOTOR_A, "B": sims.MOTOR_B, "C": sims.MOTOR_C}[motor]
        declared_error = {k: {"declared": base[k], "true": v} for k, v in fx0["params"].items()}
    return {
        "id": spec["id"], "class": spec["class"], "split": spec["split"], "motor": motor,
        "netlist": netlist, "regime": regime, "sample_rate_Hz": fs, "duration_s": dur,
        "csv": f"benchmarks/diagnosis/records/{spec['id']}.csv",
        "probes": probes_of(spec),
        "inputs": ["u"] if (motor, regime) == ("B", "slow") else [],
        "free": spec["free"], "declared_error": declared_error,
        "noise": ns, "noise_text": recordkit.noise_text(ns), "seed": spec["seed"],
        "effects": effects, "declared_terms": DECLARED[motor],
        "signature_sigma": sig, "marginal": spec["marginal"], "note": spec["note"],
        **({"signature_sigma_beyond_vanishing": spec["signature_beyond"]}
           if "signature_beyond" in spec else {}),
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default="", help="record ids, comma-separated")
    ap.add_argument("--truth-only", action="store_true", help="do not write CSVs")
    args = ap.parse_args()
    only = {s.strip() for s in args.only.split(",") if s.strip()}
    RECORDS.mkdir(exist_ok=True)
    specs = record_specs()
    old = json.loads(TRUTH.read_text()) if TRUTH.exists() else {"records": []}
    truth = {e["id"]: e for e in old["records"]}
    for spec in specs:
        if only and spec["id"] not in only:
            continue
        t0 = time.perf_counter()
        _fx, effects, clean, sig = build(spec)
        entry = truth_entry(spec, effects, sig)
        if spec["marginal"] and spec["class"] == "catalog" and spec["motor"] in ("A", "B"):
            entry["separation_sigma"] = separations(spec, clean)
        truth[spec["id"]] = entry
        if not args.truth_only:
            rng = np.random.default_rng(spec["seed"])
            ns = noise_spec(spec)
            cols = {p: sims.add_noise(rng, clean[p], ns[p]) for p in probes_of(spec)}
            if "u" in clean:
                cols["u"] = clean["u"]
            recordkit.write_csv(RECORDS / f"{spec['id']}.csv", _grid(spec["motor"], spec["regime"]), cols)
        print(f"{spec['id']} {spec['class']:8s} {spec['motor']}-{spec['regime']:4s} "
              f"{spec['split']:7s} {', '.join(e['effect'] for e in effects) or '-':45s} "
              f"signature {', '.join(f'{k} {v:.3g}' for k, v in sig.items())} "
              f"({time.perf_counter() - t0:.1f} s)", flush=True)
    order = [s["id"] for s in specs]
    out = {"about": "truth of the circuitsim diagnosis benchmark (README.md); generated by "
                    "make_records.py",
           "marginal_sigma": MARGINAL_SIGMA,
           # entries of other generators (make_records_d.py's fresh4) are kept after these
           "records": [truth[i] for i in order if i in truth]
           + [e for i, e in truth.items() if i not in set(order)]}
    TRUTH.write_text(json.dumps(out, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
