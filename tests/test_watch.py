"""A run that cannot finish is stopped with a reason (solve/watch.py), and a run that can is
left alone: the pace rule on synthetic paces, then whole runs through the CLI."""

from __future__ import annotations

import numpy as np
import pytest

from circuitsim.solve import watch
from circuitsim.solve.watch import LIMIT, SLOWING, STRIKES, WINDOW, Runaway, Watch

#: [s] a pace (simulated time gained per window) projecting twice the limit from t ~ 0
SLOW = 0.5 * WINDOW / LIMIT


def _paced(paces: list[float], stop: float = 1.0) -> Watch:
    """A watch judged once per WINDOW evaluations, the simulated time moving by ``paces``."""
    w = Watch(lambda *a: None, stop, ("x", "y"), 1e-6, 1e-9)
    y, yp = np.array([1.0, 2.0]), np.array([0.0, 5e7])
    t = 1e-6
    w.judge(t, y, yp)
    for gained in paces:
        t += gained
        w.count += WINDOW
        w.judge(t, y, yp)
    return w


def test_a_pace_that_finishes_in_time_is_left_alone_however_it_falls():
    # 1e-2 s gained per window, falling to half of it: at most 2e7 evaluations to go
    w = _paced([1e-2 * 0.99 ** k for k in range(60)])
    assert w.paces == []


def test_a_long_run_at_a_steady_pace_over_the_limit_is_left_alone():
    # a PWM drive simulated for hours: over the limit, but not slowing down
    w = _paced([SLOW * (1 + 0.01 * (-1) ** k) for k in range(40)])
    assert len(w.paces) == STRIKES


def test_a_slow_start_that_speeds_up_is_left_alone():
    w = _paced([SLOW, SLOW * 0.8, 1e-2, SLOW, SLOW * 1.5, SLOW * 1.2])
    assert w.paces


def test_a_run_slowing_down_over_the_limit_is_stopped_with_the_fastest_variable():
    paces = [SLOW * (0.98 * SLOWING) ** (k / (STRIKES - 1)) for k in range(STRIKES)]
    with pytest.raises(Runaway) as exc:
        _paced(paces)
    text = str(exc.value)
    assert "fastest-changing variable: y = 2" in text
    assert "CIRCUITSIM_RUNAWAY=off" in text and "keeps falling" in text


def test_a_fall_too_small_is_not_enough():
    paces = [SLOW * (1 - 0.5 * (1 - SLOWING) * k / (STRIKES - 1)) for k in range(STRIKES + 3)]
    w = _paced(paces)
    assert len(w.paces) == STRIKES


def test_no_progress_at_all_is_stopped():
    with pytest.raises(Runaway):
        _paced([0.0] * STRIKES)


def test_the_watch_passes_the_residual_through_and_can_be_turned_off(monkeypatch):
    calls = []
    w = watch.watched(lambda t, y, yp, r, u: calls.append((t, u)), 1.0, ("x",), 1e-6, 1e-9)
    w(0.5, None, None, None, "data")
    assert calls == [(0.5, "data")] and w.count == 1
    monkeypatch.setenv("CIRCUITSIM_RUNAWAY", "off")
    f = object()
    assert watch.watched(f, 1.0, ("x",), 1e-6, 1e-9) is f  # type: ignore[arg-type]


CHIRP = """\
title: a source whose frequency rises without bound
parameters: {A: 1 V, a: 1e13 s^-2}
components:
  - {name: B1, type: BV, p: in, n: gnd, expr: "A*sin(a*t*t)"}
  - {name: R1, type: R, p: in, n: out, R: 1 kohm}
  - {name: C1, type: C, p: out, n: gnd, C: 1 nF}
probes: {v: out.v}
analysis: {stop: 10 ms, step: 1 us}
"""


def test_a_run_that_cannot_finish_stops_with_exit_1_and_says_why(tmp_path, capsys,
                                                                 monkeypatch):
    from circuitsim.cli.main import main

    # the route a `run` process takes (a fit earlier in this process may have asked for
    # the compiled kernels, which are not watched)
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "python")

    path = tmp_path / "chirp.yaml"
    path.write_text(CHIRP)
    rc = main(["run", str(path), "--no-files", "--quiet"])
    err = capsys.readouterr().err
    assert rc == 1
    assert "slows down" in err and "fastest-changing variable" in err
    assert "A parameter far from its physical value" in err


def test_the_compiled_route_stops_the_same_run(tmp_path, monkeypatch):
    """A sweep's or a fit's run goes on the compiled kernels: IDA's own count of evaluations
    is judged by the same rule (a sweep at 1e12 V ran 101 s to an "ok" row before)."""
    pytest.importorskip("numba")
    import circuitsim as cs
    from circuitsim.solve import direct

    groups = []
    to = direct.DirectIDA._to

    def spied(self, *args):
        groups.append(self.watch is not None)
        return to(self, *args)

    monkeypatch.setattr(direct.DirectIDA, "_to", spied)
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "numba")
    path = tmp_path / "chirp.yaml"
    path.write_text(CHIRP)
    res = cs.compile(cs.load(path)).simulate()
    assert groups and all(groups)  # the compiled route ran, watched
    assert not res.success
    assert "slows down" in res.message and "fastest-changing variable: out.v" in res.message


def test_a_value_that_overflows_the_arithmetic_is_named_without_numpy_warnings(capsys,
                                                                              monkeypatch):
    import warnings
    from pathlib import Path

    from circuitsim.cli.main import main

    net = Path(__file__).resolve().parents[1] / "netlists" / "examples" / "dc_motor.yaml"
    monkeypatch.setenv("CIRCUITSIM_KERNELS", "python")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        rc = main(["run", str(net), "--no-files", "--quiet", "--set", "V=1e301"])
    err = capsys.readouterr().err
    assert rc == 1
    assert "V1.V.v1 = 1e+301 are beyond any physical value" in err
    assert "overflow the solver's arithmetic" in err and "check the netlist's" in err
    assert not [w for w in caught if issubclass(w.category, RuntimeWarning)]


def test_an_operating_point_on_a_parameter_that_overflows_says_so(capsys):
    import warnings
    from pathlib import Path

    from circuitsim.cli.main import main

    net = Path(__file__).resolve().parents[1] / "netlists" / "examples" / "dc_motor.yaml"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        rc = main(["op", str(net), "--set", "V=1e301", "--time", "1"])
    err = capsys.readouterr().err
    assert rc == 1
    assert "operating point" in err and "beyond any physical value" in err
    assert not [w for w in caught if issubclass(w.category, RuntimeWarning)]


def test_initial_values_on_a_gear_ratio_that_overflows_say_so(capsys, monkeypatch):
    """A gear ratio of 1e300 squared overflows the Newton matrix of the initial values:
    LAPACK's SVD failed with a LinAlgError's traceback."""
    from pathlib import Path

    from circuitsim.cli.main import main

    monkeypatch.setenv("CIRCUITSIM_KERNELS", "python")
    net = Path(__file__).resolve().parents[1] / "netlists" / "breadth" / "geared_load.yaml"
    rc = main(["run", str(net), "--no-files", "--quiet", "--set", "N=1e300"])
    err = capsys.readouterr().err
    assert rc == 1
    assert "no consistent initial values" in err and "not finite there" in err
    assert "Gear.ratio = 1e+300 are beyond any physical value" in err
