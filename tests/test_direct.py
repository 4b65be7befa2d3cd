"""IDA calling the compiled kernels directly (``CIRCUITSIM_KERNELS=numba``, needs numba) gives
the same steps and the same numbers as scikit-sundae calling the Python residual (#14)."""

from __future__ import annotations

import os

import numpy as np
import pytest

import circuitsim as cs

from conftest import NETLISTS

pytest.importorskip("numba")
pytestmark = pytest.mark.filterwarnings("ignore::circuitsim.errors.CircuitWarning")


def _both(model, monkeypatch, **kw):
    # off by name: unset, an earlier test's fit or diagnosis (route.many_solves) would have
    # switched the kernels on for the rest of the process, the "Python" run among them
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "python")
    python = model.simulate(**kw)
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "numba")
    return python, model.simulate(**kw)


def _same(a, b) -> None:
    assert a.success and b.success
    assert (a.nfev, a.njev) == (b.nfev, b.njev)
    for x, y in ((a.t, b.t), (a.y, b.y), (a.yp, b.yp)):
        assert np.array_equal(x, y)


def test_base_model_to_the_bit(monkeypatch):
    from circuitsim.solve import direct

    model = cs.compile(cs.load(NETLISTS / "kim2024" / "base.yaml"))
    assert model.meta["kernels"]
    python, kernels = _both(model, monkeypatch, stop=0.05)
    assert direct.kernels(model) is not None  # the direct route did run
    _same(python, kernels)


def test_corners_restarts_and_a_max_step(compile_text, monkeypatch):
    """A pulse source: integration restarts at every corner; its period bounds the step."""
    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {pulse: {v1: 0, v2: 5, delay: 1 ms,
             rise: 10 us, fall: 10 us, width: 2 ms, period: 5 ms}}}
          - {name: R1, type: R, p: a, n: b, R: 1k}
          - {name: L1, type: L, p: b, n: c, L: 10 mH}
          - {name: C1, type: C, p: c, n: gnd, C: 1 uF}
        probes: {vc: c.v}
        analysis: {stop: 20 ms, step: 10 us}
    """)
    _same(*_both(model, monkeypatch))


def test_periodic_steady_state_alike(monkeypatch):
    from circuitsim.solve.pss import periodic_steady_state

    model = cs.compile(cs.load(NETLISTS / "kim2024" / "base.yaml"))
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "python")
    a = periodic_steady_state(model, order=8).harmonic("i_total", 1)
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "numba")
    b = periodic_steady_state(model, order=8).harmonic("i_total", 1)
    assert a == b


def test_a_model_reading_a_table_runs_compiled_to_the_bit(compile_text, tmp_path, monkeypatch):
    """A measured column is interpolated inside the kernels, on its points passed in the user
    data (held at the ends beyond them, as the Python route's table)."""
    (tmp_path / "in.csv").write_text("time,v\n0,0\n0.001,2\n0.003,2\n0.004,-1\n")
    model = compile_text("""
        components:
          - {name: V1, type: V, p: in, n: gnd, V: {table: {file: in.csv, column: v}}}
          - {name: R1, type: R, p: in, n: out, R: 1k}
          - {name: C1, type: C, p: out, n: gnd, C: 1u}
        probes: {vout: out.v}
        analysis: {stop: 5 ms, step: 10 us}
    """)
    assert "TABLES" in model.meta["kernels"]
    python, kernels = _both(model, monkeypatch)
    assert _ran_direct(model)
    _same(python, kernels)


def test_table_rows_between_output_times_are_stops_compiled_to_the_bit(
        compile_text, tmp_path, monkeypatch):
    """Rows that fall between output times: both routes stop IDA at each (the compiled one
    in its own loop, its stop time advanced row by row) and drop them from the outputs."""
    (tmp_path / "in.csv").write_text(
        "time,v\n0,0\n0.00123,2\n0.00311,2\n0.004057,-1\n0.0041,0\n")
    model = compile_text("""
        components:
          - {name: V1, type: V, p: in, n: gnd, V: {table: {file: in.csv, column: v}}}
          - {name: R1, type: R, p: in, n: out, R: 1k}
          - {name: C1, type: C, p: out, n: gnd, C: 1u}
        probes: {vout: out.v}
        analysis: {stop: 5 ms, step: 100 us}
    """)
    python, kernels = _both(model, monkeypatch)
    assert _ran_direct(model)
    _same(python, kernels)
    assert kernels.t.size == 51


def test_table_rows_a_rounding_off_output_times_lose_no_output(compile_text, tmp_path,
                                                                 monkeypatch):
    """Rows written as sums (3 x 0.1 ms = 0.30000000000000003 ms) a rounding away from the
    output times and from the end of a pwl segment: each is that time, not a second stop a
    few ulps away (IDA would answer such a stop with the time it stands at, and the output
    time would be lost or the run fail)."""
    rows = [k * 1e-4 for k in range(11)]
    assert rows[3] != 3e-4  # the premise: written as a sum, it is not the decimal
    (tmp_path / "in.csv").write_text("time,v\n" + "".join(
        f"{t!r},{float(np.sin(3000 * t))!r}\n" for t in rows))
    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {table: {file: in.csv, column: v}}}
          - {name: R1, type: R, p: a, n: gnd, R: 1 ohm}
          - {name: V2, type: V, p: b, n: gnd, V: {pwl: [[0, 0], [0.3 ms, 3 V], [0.6 ms, -1 V]]}}
          - {name: R2, type: R, p: b, n: gnd, R: 2 ohm}
        probes: {i1: R1.i, i2: R2.i}
        analysis: {stop: 1 ms, step: 1 us, rtol: 1e-10, atol: 1e-12}
    """)
    python, kernels = _both(model, monkeypatch)
    assert _ran_direct(model)
    for res in (python, kernels):
        assert res.success and res.t.size == 1001
        np.testing.assert_allclose(res["i1"], np.interp(res.t, rows, np.sin(3000 * np.array(
            rows))), atol=1e-9)
        np.testing.assert_allclose(res["i2"], np.interp(res.t, [0, 3e-4, 6e-4], [0, 3, -1]) / 2,
                                   atol=1e-9)


def test_a_small_pwl_table_runs_compiled(compile_text, tmp_path, monkeypatch):
    """Points written in the netlist or a short CSV become a Piecewise of parameters."""
    (tmp_path / "pts.csv").write_text("time,v\n0,0\n0.001,2\n0.003,2\n0.004,-1\n")
    model = compile_text("""
        components:
          - {name: V1, type: V, p: in, n: gnd, V: {pwl: {file: pts.csv, column: v}}}
          - {name: R1, type: R, p: in, n: out, R: 1k}
          - {name: C1, type: C, p: out, n: gnd, C: 1u}
        probes: {vout: out.v}
        analysis: {stop: 5 ms, step: 10 us}
    """)
    assert model.meta["kernels"]
    _same(*_both(model, monkeypatch))


def test_no_libraries_means_the_usual_route_and_one_warning(compile_text, monkeypatch):
    """scikit-sundae's libraries not where a Linux wheel has them: a warning, then the
    Python residual, with the same result."""
    from circuitsim.errors import CircuitWarning
    from circuitsim.solve import direct

    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {step: {v0: 0, v1: 1, t0: 1 ms, rise: 0.1 ms}}}
          - {name: R1, type: R, p: a, n: b, R: 1k}
          - {name: C1, type: C, p: b, n: gnd, C: 1 uF}
        probes: {vc: b.v}
        analysis: {stop: 5 ms, step: 10 us}
    """)

    def missing():
        raise StopIteration("no libsundials_ida")

    monkeypatch.setattr(direct, "_libraries", missing)
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "python")
    python = model.simulate()
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "numba")
    with pytest.warns(CircuitWarning, match="compiled kernels unavailable"):
        fallback = model.simulate()
    _same(python, fallback)


def test_a_batch_runs_stacked_kernels_to_the_bit(monkeypatch):
    """K members in one band system, as fit and diagnose integrate them."""
    from circuitsim.solve.batch import simulate_batch

    model = cs.compile(cs.load(NETLISTS / "kim2024" / "base.yaml"))
    sets = [{"Ra": 1.1 * (1 + 1e-4 * j)} for j in range(4)]
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "python")
    python = simulate_batch(model, sets, stop=0.02)
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "numba")
    kernels = simulate_batch(model, sets, stop=0.02)
    for a, b in zip(python, kernels, strict=True):
        _same(a, b)


def _ran_direct(model) -> bool:
    """The model ran on its kernels -- with a C compiler on the machine, on the library the
    compiler built of them (``solve/ccode.py``: no kernel shape may fall back to numba
    unnoticed; test_ccode.py runs numba's route)."""
    from circuitsim.solve import ccode, direct

    module = direct._LOADED.get(model.key)
    return module is not None and (ccode.compiler() is None
                                   or direct.c_library(module) is not None)


@pytest.mark.slow
def test_a_large_model_runs_compiled_to_the_bit(compile_text, monkeypatch):
    """100 unknowns and more: the kernels repeat the Python route's sparse product of the
    linear part and its remaining terms (a varistor's powers among them), IDA gets the same
    dense solver: the same steps and numbers."""
    from test_scale import rlc_ladder_with_a_nonlinear_load

    model = compile_text(rlc_ladder_with_a_nonlinear_load(50))
    assert len(model.state_names) >= 100 and model.linsolver == "dense"
    python, kernels = _both(model, monkeypatch)
    assert _ran_direct(model)
    _same(python, kernels)


@pytest.mark.slow
def test_the_sparse_solver_runs_compiled_to_the_bit(compile_text, monkeypatch):
    """From SPARSE_FROM unknowns (here lowered to 100 before code generation) IDA factorises
    with SuperLU_MT on the Jacobian's compressed columns, which the kernel fills."""
    from test_scale import rlc_ladder_with_a_nonlinear_load

    from circuitsim.compiler import codegen
    from circuitsim.compiler import model as model_module

    monkeypatch.setattr(codegen, "SPARSE_FROM", 100)
    monkeypatch.setattr(model_module, "SPARSE_FROM", 100)
    model = compile_text(rlc_ladder_with_a_nonlinear_load(51))
    assert model.linsolver == "sparse" and "jacobian_sparse" in model.meta["kernels"]
    python, kernels = _both(model, monkeypatch)
    assert _ran_direct(model)
    _same(python, kernels)


def test_kernel_powers_call_c_pow():
    """Every power in a kernel goes through C's pow with float operands, as Python's float
    ``**`` does (numba and LLVM would multiply or divide instead, rounding otherwise)."""
    from circuitsim.compiler.codegen import _libm_powers

    line = "    a[3] = (p306)**(-3)*x**3 + -y**2.5 + (c1**c2)"
    assert _libm_powers(line) == ("    a[3] = libm_pow(p306, -3.0) * libm_pow(x, 3.0) + "
                                  "-libm_pow(y, 2.5) + libm_pow(c1, c2)")


def test_kernel_powers_of_a_deep_sum():
    """A kernel line that sums a thousand powers (a large network's equation) is rewritten
    -- the walk of its operators once recursed past Python's limit at about 400 terms --
    and gives Python's own value, every power through pow."""
    import sys

    from circuitsim.compiler.codegen import _libm_powers

    n = 1000
    line = "    r0 = " + " + ".join(f"y{k}**2*p{k}" for k in range(n))
    limit = sys.getrecursionlimit()
    out = _libm_powers(line)
    assert sys.getrecursionlimit() == limit
    assert out.count("libm_pow(") == n and "**" not in out
    values = {**{f"y{k}": 1.0 + k / n for k in range(n)}, **{f"p{k}": 0.5 for k in range(n)}}
    rewritten, plain = {"libm_pow": pow, **values}, dict(values)
    exec(compile(out.strip(), "kernel", "exec"), rewritten)  # noqa: S102 - generated here
    exec(compile(line.strip(), "kernel", "exec"), plain)  # noqa: S102 - generated here
    assert rewritten["r0"] == plain["r0"]


def _both_watched(model, monkeypatch, **kw):
    """``_both`` for a switching model, checking that the second run's segments went through
    the compiled route (its root function) and the first's did not."""
    from circuitsim.solve import direct

    runs = []
    solve = direct.DirectIDA.solve
    monkeypatch.setattr(direct.DirectIDA, "solve",
                        lambda self, *a: runs.append(os.environ["CIRCUITSIM_KERNELS"])
                        or solve(self, *a))
    python, kernels = _both(model, monkeypatch, **kw)
    assert runs and set(runs) == {"numba"}
    return python, kernels


def _same_events(a, b) -> None:
    """Two runs of a switching model: the same steps, values and switching instants."""
    _same(a, b)
    assert np.array_equal(a.t_events, b.t_events)


def test_a_held_relation_is_watched_by_the_compiled_root_function(compile_text,
                                                                  monkeypatch):
    """A drive whose load reads abs(w) and whose friction reads sign(w), run through a
    reversal: each relation's root is found by the kernels' root function, at the instant
    and with the steps of the Python guards, to the bit."""
    model = compile_text("""
        parameters: {Tc: 0.02 N*m, cf: 1e-3}
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {pwl: [[0, 0], [0.01, 24], [0.1, 24],
             [0.15, -24], [0.3, -24]]}}
          - {name: Ra, type: R, p: a, n: m1, R: 0.8}
          - {name: La, type: L, p: m1, n: m2, L: 1.2 mH}
          - {name: M, type: emf, p: m2, n: gnd, shaft: r, k_t: 0.15}
          - {name: J, type: inertia, shaft: r, J: 3.5e-4}
          - {name: Load, type: btorque, shaft: r,
             expr: "-cf*r.w*abs(r.w) - Tc*tanh(r.w/0.01)"}
        probes: {i: Ra.i, w: r.w}
        analysis: {stop: 0.3, step: 50 us, rtol: 1e-9, atol: 1e-12}
    """)
    assert "def roots" in model.meta["kernels"]
    python, kernels = _both_watched(model, monkeypatch)
    assert python.t_events.size >= 1  # the reversal
    _same_events(python, kernels)


def test_component_events_are_watched_by_the_compiled_root_function(compile_text,
                                                                    monkeypatch):
    """An ideal diode (event-switched, with its hysteresis) and a switch that a capacitor's
    own voltage opens and closes: the guards, the jumps and the restarts give the Python
    route's steps and instants, to the bit."""
    from test_breadth_events import RECTIFIER, RELAXATION

    diode, relax = compile_text(RECTIFIER), compile_text(RELAXATION)
    for model, switchings, kw in ((diode, 6, {}), (relax, 9, {"stop": 8e-3, "step": 1e-6})):
        assert "def roots" in model.meta["kernels"]
        python, kernels = _both_watched(model, monkeypatch, **kw)
        assert python.t_events.size >= switchings
        _same_events(python, kernels)


def test_a_chattering_relation_stops_alike_on_both_routes(compile_text, monkeypatch):
    """sign(w) friction coasting to rest has no consistent side there: both routes stop at
    the same root with the chatter named."""
    from test_breadth_relations import COAST_DOWN

    model = compile_text(COAST_DOWN)
    python, kernels = _both_watched(model, monkeypatch)
    for res in (python, kernels):
        assert not res.success and "chatter" in res.message
    assert np.array_equal(python.t_events, kernels.t_events)
    assert np.array_equal(python.t, kernels.t) and np.array_equal(python.y, kernels.y)


def test_a_switching_model_reading_a_table_stops_at_rows_and_roots_to_the_bit(
        compile_text, tmp_path, monkeypatch):
    """A measured voltage command (rows between output times) drives a motor whose load
    reads abs(w) through a reversal: the compiled loop stops at the rows and at the roots,
    as the Python route's row-by-row stepping does, to the bit."""
    t = np.linspace(0.0, 0.3, 41) + 0.00123
    t[0] = 0.0
    u = 24 * np.sin(2 * np.pi * t / 0.2)
    rows = "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(t, u, strict=True))
    (tmp_path / "u.csv").write_text("time,u\n" + rows)
    model = compile_text("""
        parameters: {cf: 1e-3}
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {table: {file: u.csv, column: u}}}
          - {name: Ra, type: R, p: a, n: m1, R: 0.8}
          - {name: La, type: L, p: m1, n: m2, L: 1.2 mH}
          - {name: M, type: emf, p: m2, n: gnd, shaft: r, k_t: 0.15}
          - {name: J, type: inertia, shaft: r, J: 3.5e-4}
          - {name: Load, type: btorque, shaft: r, expr: "-cf*r.w*abs(r.w)"}
        probes: {i: Ra.i, w: r.w}
        analysis: {stop: 0.3, step: 100 us, rtol: 1e-9, atol: 1e-12}
    """)
    assert "TABLES" in model.meta["kernels"] and "def roots" in model.meta["kernels"]
    python, kernels = _both_watched(model, monkeypatch)
    assert python.t_events.size >= 1 and python.t.size == 3001
    _same_events(python, kernels)


def test_a_batch_of_a_model_reading_tables_runs_stacked_kernels_to_the_bit(
        compile_text, tmp_path, monkeypatch):
    """K members of a motor under a measured voltage command and a measured load torque
    (two tables, rows between output times): the stacked kernels read the tables' points
    after the members' parameters, and give the Python route's numbers to the bit."""
    from circuitsim.solve import direct
    from circuitsim.solve.batch import simulate_batch

    t = np.linspace(0.0, 0.05, 23)
    rows = "".join(f"{float(a)!r},{float(12 + 6 * np.sin(400 * a))!r},"
                   f"{float(0.01 * np.cos(300 * a))!r}\n" for a in t)
    (tmp_path / "in.csv").write_text("time,u,load\n" + rows)
    model = compile_text("""
        parameters: {Ra: 0.8}
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {table: {file: in.csv, column: u}}}
          - {name: R1, type: R, p: a, n: m1, R: Ra}
          - {name: La, type: L, p: m1, n: m2, L: 1.2 mH}
          - {name: M, type: emf, p: m2, n: gnd, shaft: r, k_t: 0.05}
          - {name: J, type: inertia, shaft: r, J: 1e-5}
          - {name: B, type: damper, shaft: r, b: 1e-5}
          - {name: TL, type: torque, shaft: r, T: {table: {file: in.csv, column: load}}}
        probes: {i: R1.i, w: r.w}
        analysis: {stop: 0.05, step: 100 us, rtol: 1e-8, atol: 1e-10}
    """)
    assert "TABLES" in model.meta["kernels"] and "def residual_batch" in model.meta["kernels"]
    sets = [{"Ra": 0.8 * (1 + 1e-3 * j)} for j in range(4)]
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "python")
    python = simulate_batch(model, sets)
    runs = []
    solve = direct.DirectIDA.solve
    monkeypatch.setattr(direct.DirectIDA, "solve",
                        lambda self, *a: runs.append(self.kind) or solve(self, *a))
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "numba")
    kernels = simulate_batch(model, sets)
    assert runs and set(runs) == {"band"}
    for a, b in zip(python, kernels, strict=True):
        _same(a, b)
    assert not np.array_equal(python[0].y, python[-1].y)  # the members differ


def test_a_second_table_is_read_where_it_lies(compile_text, tmp_path, monkeypatch):
    """Two tables: each has one slope fewer than points, so the second starts 3 m - 1
    entries after the first (it was read one entry off: a force table shifted by a sample,
    0.3 N of 287 N on the EMPS pulses netlist). Both routes, the same numbers to the bit."""
    t = np.linspace(0.0, 0.01, 7) + np.array([0, 3e-4, 0, 1e-4, 0, 2e-4, 0])
    rows = "".join(f"{float(a)!r},{float(5 * np.sin(700 * a))!r},{float(3 + a * 100)!r}\n"
                   for a in t)
    (tmp_path / "in.csv").write_text("time,u,w\n" + rows)
    model = compile_text("""
        components:
          - {name: V1, type: V, p: a, n: gnd, V: {table: {file: in.csv, column: u}}}
          - {name: R1, type: R, p: a, n: b, R: 1k}
          - {name: C1, type: C, p: b, n: gnd, C: 1u}
          - {name: V2, type: V, p: c, n: gnd, V: {table: {file: in.csv, column: w}}}
          - {name: R2, type: R, p: c, n: gnd, R: 2 ohm}
        probes: {vb: b.v, i2: R2.i}
        analysis: {stop: 10 ms, step: 50 us, rtol: 1e-10, atol: 1e-12}
    """)
    python, kernels = _both(model, monkeypatch)
    assert _ran_direct(model)
    _same(python, kernels)
    # the algebraic current to the integrator's tolerance; a row off would be 1 % and more
    np.testing.assert_allclose(kernels["i2"], np.interp(kernels.t, t, 3 + t * 100) / 2,
                               rtol=1e-9)


def test_topologies_of_the_same_code_share_one_kernel_module(compile_text, monkeypatch):
    """A cogging of order 4 and one of order 6, on parts of different names: two models, one
    kernel module (the order is a run-time parameter, the module is named by its source), and
    each runs on it to the bit of its own Python route -- with its own order: the energy
    1/2 J w^2 + (T/N) cos(N phi) of each is constant."""
    from circuitsim.solve import direct

    text = """
        components:
          - {name: CG%d, type: cogging, shaft: s,
             harmonics: [{order: %d, amplitude: 0.01 N*m, phase: 0}]}
          - {name: Jr, type: inertia, shaft: s, J: 1e-5, w0: 50 rad/s}
        probes: {w: s.w, phi: s.phi}
        analysis: {stop: 0.2, step: 0.1 ms, rtol: 1e-11, atol: 1e-13}
    """
    four, six = (compile_text(text % (n, n)) for n in (4, 6))
    assert four.key != six.key and four.meta["kernels"]
    assert direct.kernels(four) is not None
    assert direct.kernels(four) is direct.kernels(six)
    for model, n in ((four, 4), (six, 6)):
        python, kernels = _both(model, monkeypatch)
        _same(python, kernels)
        assert direct._LOADED.get(model.key) is not None  # the direct route did run
        w, phi = kernels["w"], kernels["phi"]
        energy = 0.5 * 1e-5 * w ** 2 + 0.01 / n * np.cos(n * phi)
        assert np.ptp(energy) < 1e-8 * energy[0]


def test_an_inert_harmonic_skips_its_sine_on_both_routes_to_the_bit(compile_text, monkeypatch):
    """A torque harmonic held at zero amplitude (the screen's joint model carries dozens) is
    not evaluated, in the kernels (a guarded call) and in the Python code (a conditional)
    alike: both routes agree to the bit with the harmonic inert and live, and the inert
    rotor follows the closed form of J w' = T - b w."""
    model = compile_text("""
        parameters: {A: 0.0}
        components:
          - {name: T1, type: torque, shaft: s, T: 0.2}
          - {name: J1, type: inertia, shaft: s, J: 1e-3}
          - {name: B1, type: damper, shaft: s, b: 2e-3}
          - {name: CG, type: cogging, shaft: s, harmonics: [{order: 6, amplitude: A, phase: 0.3}]}
        probes: {w: s.w}
        analysis: {stop: 2.0, step: 1 ms, rtol: 1e-9}
    """)
    assert "if_sin(" in model.meta["kernels"]
    inert = _both(model, monkeypatch, params={"A": 0.0})
    live = _both(model, monkeypatch, params={"A": 0.05})
    _same(*inert)
    _same(*live)
    t, w = inert[1].t, inert[1]["w"]
    assert np.allclose(w, 100.0 * (1.0 - np.exp(-2.0 * t)), rtol=1e-6, atol=1e-5)
    assert np.max(np.abs(live[1]["w"] - w)) > 0.1  # the live harmonic acts


def test_the_guarded_functions_are_the_functions_or_zero(tmp_path):
    """``if_<name>(z, x)``: ``<name>(x)`` to the bit while z is not zero, 0.0 when it is,
    whatever x (an inert term no longer passes on an overflow)."""
    import math

    from circuitsim.solve import direct
    from circuitsim.solve.kernel_lib import GUARDED

    folder = tmp_path / "kernels"
    folder.mkdir(mode=0o700)
    lib = direct._kernel_lib(folder)
    for name in GUARDED:
        guarded, plain = getattr(lib, f"if_{name}"), getattr(math, name)
        for x in (-2.5, 0.0, 0.7, 30.0):
            assert guarded(-1.5, x) == plain(x)
        assert guarded(0.0, math.inf) == 0.0 and guarded(0.0, math.nan) == 0.0
