"""Circuits of many sections stay sparse and exact (issue 14): elimination adds no fill-in,
the Jacobian is derived at its structural nonzeros, the sparse solver and the sparse-matrix
residual give the same numbers as the scalar code, and a ladder agrees with ngspice."""

from __future__ import annotations

import numpy as np
import pytest

from circuitsim.compiler import cache
from circuitsim.compiler import model as model_module

from ngspice import have_ngspice, run_ngspice


def rc_ladder(n: int, stop: float = 2e-4) -> str:
    comps = ["{name: Vs, type: V, p: n0, n: gnd, V: {step: {v1: 1 V, rise: 1 us}}}"]
    for k in range(1, n + 1):
        comps += [f"{{name: R{k}, type: R, p: n{k - 1}, n: n{k}, R: 1 kohm}}",
                  f"{{name: C{k}, type: C, p: n{k}, n: gnd, C: 1 nF}}"]
    body = "\n".join(f"  - {c}" for c in comps)
    return (f"components:\n{body}\nprobes: {{v_end: n{n}.v, v_4: n4.v}}\n"
            f"analysis: {{stop: {stop!r}, step: {stop / 100!r}, rtol: 1e-8, atol: 1e-11}}\n")


def rlc_ladder_with_a_nonlinear_load(n: int) -> str:
    """RLC sections into a varistor clamp: linear network plus nonlinear and source terms."""
    comps = ["{name: Vs, type: V, p: n0, n: gnd, V: {sine: {amplitude: 40 V, freq: 50 kHz}}}"]
    for k in range(1, n + 1):
        comps += [f"{{name: R{k}, type: R, p: n{k - 1}, n: x{k}, R: 1 ohm}}",
                  f"{{name: L{k}, type: L, p: x{k}, n: n{k}, L: 1 uH}}",
                  f"{{name: C{k}, type: C, p: n{k}, n: gnd, C: 1 nF}}"]
    comps.append(f"{{name: MOV, type: varistor, p: n{n}, n: gnd, V_ref: 33 V, I_ref: 1 mA, "
                 f"alpha: 25, C: 1 nF}}")
    body = "\n".join(f"  - {c}" for c in comps)
    return (f"components:\n{body}\nprobes: {{v_end: n{n}.v}}\n"
            f"analysis: {{stop: 20 us, step: 0.1 us, rtol: 1e-7, atol: 1e-10}}\n")


def test_elimination_adds_no_fill_in(compile_text):
    """Jacobian nonzeros and unknowns grow linearly with the sections (they grew as N^2
    when every linear equation was substituted)."""
    a, b = (compile_text(rc_ladder(n)) for n in (100, 200))
    assert b.meta["jac_nnz"] / a.meta["jac_nnz"] == pytest.approx(2.0, rel=0.03)
    assert len(b.state_names) / len(a.state_names) == pytest.approx(2.0, rel=0.03)
    assert b.meta["jac_nnz"] < 4 * len(b.state_names)


def test_sparse_residual_equals_the_scalar_code(compile_text):
    """The matrix-product residual of a large model against the generated scalar one at
    random points, and the sparse Jacobian against finite differences of the residual."""
    model = compile_text(rlc_ladder_with_a_nonlinear_load(50))
    n = len(model.state_names)
    assert n >= model_module.MATRIX_RESIDUAL_FROM
    module, _ = cache.load_cached(model.key)
    scalar = module.make([], [], [], [])[0]
    p = model.param_vector()
    rng = np.random.default_rng(7)
    r_scalar, r_sparse, r_h = np.zeros(n), np.zeros(n), np.zeros(n)
    rows, cols = model.meta["jac_pattern"]
    JJ = np.zeros(len(rows))
    for _ in range(5):
        t, y, yp = rng.random() * 1e-5, rng.normal(size=n) * 10, rng.normal(size=n) * 1e6
        scalar(t, y, yp, r_scalar, p)
        model.fns[0](t, y, yp, r_sparse, p)
        np.testing.assert_allclose(r_sparse, r_scalar, rtol=1e-13,
                                   atol=1e-13 * np.max(np.abs(r_scalar)))
        cj = 1e6
        model.jac_flat(t, y, yp, r_sparse, cj, JJ, p)
        J = np.zeros((n, n))
        J[rows, cols] = JJ
        for j in rng.choice(n, 6, replace=False):
            h = 1e-7 * (1 + abs(y[j]))
            y2, yp2 = y.copy(), yp.copy()
            y2[j] += h
            yp2[j] += cj * h  # d/dy + cj d/dy' along one column
            model.fns[0](t, y2, yp2, r_h, p)
            np.testing.assert_allclose((r_h - r_sparse) / h, J[:, j], rtol=1e-5,
                                       atol=1e-5 * np.max(np.abs(J)))


@pytest.mark.ngspice
@pytest.mark.skipif(not have_ngspice(), reason="ngspice not on PATH")
@pytest.mark.parametrize("solver", ["dense", "sparse"])
def test_a_ladder_of_100_sections_agrees_with_ngspice(compile_text, monkeypatch, solver):
    """Both linear solvers (the sparse one chosen here below its usual size)."""
    if solver == "sparse":
        monkeypatch.setattr(model_module, "SPARSE_FROM", 50)
    n, stop = 100, 2e-4
    model = compile_text(rc_ladder(n, stop))
    assert model.linsolver == solver
    res = model.simulate()
    assert res.success, res.message
    deck = ["* rc ladder", "Vs n0 0 PWL(0 0 1e-6 1)"]
    for k in range(1, n + 1):
        deck += [f"R{k} n{k - 1} n{k} 1000", f"C{k} n{k} 0 1e-9 IC=0"]
    deck += [".options reltol=1e-7 method=gear", f".tran 1e-8 {stop!r} 0 1e-8 uic"]
    ref = run_ngspice("\n".join(deck) + "\n", [f"v(n{n})", "v(n4)"])
    for probe, vec in (("v_end", f"v(n{n})"), ("v_4", "v(n4)")):
        want = np.interp(res.t[1:], ref["time"], ref[vec])
        assert np.max(np.abs(res[probe][1:] - want)) < 1e-4
