"""Thin ngspice driver and reference decks used to cross-check circuitsim.

``run_ngspice`` appends a ``.control`` block (``run`` + ``wrdata``) to a deck, runs
``ngspice -b`` in a temporary directory and parses the data into numpy arrays.

Notes on ngspice behaviour (ngspice 39, Debian):

* ``wrdata`` writes the scale (time) column once per vector: ``t v1 t v2 ...``. We keep the
  first time column and check that the others agree.
* ``wrdata`` prints ``numdgt`` significant digits; we ``set numdgt=15`` (the default, 8,
  would limit comparisons to ~1e-8).
* With ``.tran ... uic`` the point t = 0 is not stored: the first row is the first step.
* Batch mode exits with status 1 ("no simulations run") unless the control block ends with
  ``quit``; we add it.
* The step control only watches reactive charges/fluxes; for the Kim model the 826 Hz ripple
  needs ``tmax`` (1 us gives ~2e-6 relative error in I8, 10 us ~2e-4).
"""

from __future__ import annotations

import math
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

try:  # imported as tests.ngspice (repository root on sys.path)
    from .reference import KIM_BASE
except ImportError:  # imported as a top-level module (tests/ on sys.path)
    from reference import KIM_BASE  # type: ignore[no-redef]

__all__ = [
    "KIM_VECTORS",
    "RLC_VECTORS",
    "have_ngspice",
    "kim_base_deck",
    "rlc_deck",
    "run_ngspice",
]

#: Vectors of ``kim_base_deck``: supply current [A] (positive when the source delivers),
#: motor loop current [A], speed w [rad/s] (node voltage), rotor angle theta [rad].
KIM_VECTORS: list[str] = ["i(vsup)", "i(vmot)", "v(w)", "v(th)"]

#: Vectors of ``rlc_deck``: capacitor voltage [V] and loop current [A].
RLC_VECTORS: list[str] = ["v(cap)", "i(vsense)"]


def have_ngspice() -> bool:
    """True if an ``ngspice`` executable is on the PATH."""
    return shutil.which("ngspice") is not None


def _g(x: float) -> str:
    """Format a number for a SPICE deck without losing precision (no SI suffixes)."""
    return repr(float(x))


def run_ngspice(
    netlist: str, vectors: list[str], timeout: float = 120
) -> dict[str, NDArray[np.float64]]:
    """Run a transient deck through ``ngspice -b`` and return the requested vectors.

    Parameters
    ----------
    netlist : the deck: title line, elements, ``.tran`` / ``.options`` lines. A trailing
        ``.end`` is optional; the deck must not contain its own ``.control`` block.
    vectors : ngspice vector expressions, e.g. ``["v(w)", "i(vsup)"]`` (node voltages [V],
        source branch currents [A]).
    timeout : wall-clock limit for the ngspice process [s].

    Returns
    -------
    ``{"time": t [s], name: values, ...}`` keyed by the names exactly as given in
    ``vectors``. The t = 0 point is absent for ``uic`` runs (ngspice does not store it).

    Raises
    ------
    RuntimeError with ngspice's stderr/stdout if ngspice is missing, fails, times out or
    writes no (or malformed) data.
    """
    if not vectors:
        raise ValueError("no vectors requested")
    exe = shutil.which("ngspice")
    if exe is None:
        raise RuntimeError("ngspice not found on PATH")
    lines = netlist.rstrip().splitlines()
    if any(ln.strip().lower().startswith(".control") for ln in lines):
        raise ValueError("netlist must not contain a .control block")
    while lines and lines[-1].strip().lower() in (".end", ""):
        lines.pop()
    with tempfile.TemporaryDirectory(prefix="circuitsim-ngspice-") as tmp:
        out = Path(tmp) / "out.dat"
        deck = Path(tmp) / "deck.cir"
        control = [
            ".control",
            "set numdgt=15",
            "set filetype=ascii",
            "run",
            f"wrdata {out} {' '.join(vectors)}",
            "quit",
            ".endc",
            ".end",
        ]
        deck.write_text("\n".join([*lines, *control]) + "\n")
        try:
            proc = subprocess.run(
                [exe, "-b", str(deck)],
                cwd=tmp,
                capture_output=True,
                text=True,
                timeout=timeout,
                check=False,
            )
        except subprocess.TimeoutExpired as exc:
            raise RuntimeError(f"ngspice timed out after {timeout} s") from exc
        diag = f"ngspice exit {proc.returncode}\nstderr:\n{proc.stderr}\nstdout (tail):\n" + (
            "\n".join(proc.stdout.splitlines()[-30:])
        )
        if proc.returncode != 0 or not out.exists():
            raise RuntimeError(f"ngspice failed\n{diag}")
        try:
            data = np.loadtxt(out, dtype=float, ndmin=2)
        except ValueError as exc:
            raise RuntimeError(f"could not parse ngspice output: {exc}\n{diag}") from exc
    if data.shape[0] == 0 or data.shape[1] != 2 * len(vectors):
        raise RuntimeError(
            f"expected {2 * len(vectors)} columns (time, value per vector), got "
            f"{data.shape[1] if data.size else 0}\n{diag}"
        )
    t = data[:, 0]
    for k in range(1, len(vectors)):
        if not np.array_equal(data[:, 2 * k], t):
            raise RuntimeError(f"time columns disagree for vector {vectors[k]!r}")
    result: dict[str, NDArray[np.float64]] = {"time": t}
    for k, name in enumerate(vectors):
        result[name] = data[:, 2 * k + 1]
    return result


def kim_base_deck(
    t_stop: float = 0.3,
    tmax: float = 1e-6,
    lf: float = 0.0,
    rf: float = 0.0,
    reltol: float = 1e-6,
) -> str:
    """SPICE deck of the Kim & Kim 2024 model (``tests.reference.KIM_BASE``) from rest.

    Electrical part: ``Vin`` -> ``Vsup`` (0 V sense, supply current) -> [``Rf``, ``Lf``] ->
    node a; varistor ``Rv`` + ``Cv`` a-gnd; ``Lc`` a-b; ``Vmot`` (0 V sense, motor current);
    ``Ra``; ``La``; back-EMF behavioural voltage source ``Be``; ``Lc`` c-gnd.

    Mechanical analogue (node voltage = speed): current source ``k_t*i(vmot)`` into node w,
    capacitor ``J`` (inertia) and resistor ``1/B`` (viscous damper) from w to ground; the
    rotor angle is node th, a 1 F capacitor charged by a current ``v(w)``.

    Parameters
    ----------
    t_stop : end time [s]. tmax : maximum time step [s] (also the print step).
    lf, rf : series filter inductance [H] and resistance [ohm] (omitted when 0).
    reltol : ngspice ``reltol`` (trapezoidal integration).

    Vectors: ``KIM_VECTORS`` = supply current ``i(vsup)`` [A] (positive when delivering),
    motor current ``i(vmot)`` [A], ``v(w)`` [rad/s], ``v(th)`` [rad].
    """
    p = KIM_BASE
    if lf < 0.0 or rf < 0.0:
        raise ValueError("lf and rf must be >= 0")
    filt: list[str] = []
    node = "s1"
    if rf > 0.0:
        filt.append(f"Rf {node} f1 {_g(rf)}")
        node = "f1"
    if lf > 0.0:
        filt.append(f"Lf {node} a {_g(lf)}")
    else:
        filt.append(f"Vfilt {node} a DC 0")  # short (keeps the node names fixed)
    emf = (
        f"V = {_g(p['k_e'])}*v(w) + {_g(p['e0'])}"
        f" + ({_g(p['a8_slope'])}*v(w) + {_g(p['a8_offset'])})*sin(8*v(th))"
    )
    lines = [
        "* Kim & Kim 2024 brushed DC motor, base model (circuitsim reference deck)",
        f"Vin src 0 DC {_g(p['Vin'])}",
        "Vsup src s1 DC 0",
        *filt,
        f"Rv a va {_g(p['Rv'])}",
        f"Cv va 0 {_g(p['Cv'])} IC=0",
        f"Lc1 a b {_g(p['L_conn'])} IC=0",
        "Vmot b b1 DC 0",
        f"Ra b1 c1 {_g(p['Ra'])}",
        f"La c1 c2 {_g(p['La'])} IC=0",
        f"Be c2 c {emf}",
        f"Lc2 c 0 {_g(p['L_conn'])} IC=0",
        "* mechanics: node voltage v(w) = speed [rad/s]",
        f"Bt 0 w I = {_g(p['k_t'])}*i(vmot)",
        f"Cj w 0 {_g(p['J'])} IC=0",
        f"Rb w 0 {_g(1.0 / p['B'])}",
        "* rotor angle: v(th) = integral of v(w) [rad]",
        "Bth 0 th I = v(w)",
        "Cth th 0 1 IC=0",
        f".options reltol={_g(reltol)} method=trap",
        f".tran {_g(tmax)} {_g(t_stop)} 0 {_g(tmax)} uic",
        ".end",
    ]
    return "\n".join(lines) + "\n"


def rlc_deck(R: float, L: float, C: float, V: float, t_stop: float, tmax: float) -> str:
    """SPICE deck of a series RLC from rest with a step ``V`` [V] applied at t = 0 (``uic``).

    ``R`` [ohm], ``L`` [H], ``C`` [F], ``t_stop`` and ``tmax`` (max step) [s].
    Vectors: ``RLC_VECTORS`` = capacitor voltage ``v(cap)`` [V], loop current
    ``i(vsense)`` [A] (positive from the source through R, L into C).
    """
    if min(R, L, C) <= 0.0 or not math.isfinite(V):
        raise ValueError("R, L, C must be > 0 and V finite")
    lines = [
        "* series RLC step from rest (circuitsim reference deck)",
        f"V1 in 0 DC {_g(V)}",
        "Vsense in n1 DC 0",
        f"R1 n1 n2 {_g(R)}",
        f"L1 n2 cap {_g(L)} IC=0",
        f"C1 cap 0 {_g(C)} IC=0",
        ".options reltol=1e-6 method=trap",
        f".tran {_g(tmax)} {_g(t_stop)} 0 {_g(tmax)} uic",
        ".end",
    ]
    return "\n".join(lines) + "\n"


def require_ngspice() -> None:
    """In a test body: skip without ngspice, except on CI (env var CI set), where a missing
    tool is a failure (called in the body, not a fixture, so CI reports FAILED, not ERROR)."""
    import os

    import pytest

    if not have_ngspice():
        msg = "ngspice missing: install the Debian package (apt-get install ngspice)"
        if "CI" in os.environ:
            pytest.fail(msg)
        pytest.skip(msg)
