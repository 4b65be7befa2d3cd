"""A record the model matches only after a unit's factor or a sign: a slip of the data.

A column read in the wrong unit (rpm read as rad/s, mA as A) or a sensor wired the other way
round differs from the model by a fixed factor: 60/(2 pi), 1000, -1. No effect of a motor
does that, and a fit or a diagnosis of such a record would report nonsense -- a sensor gain
at the edge of its range, or "something remains that I cannot name". It is found after the
declared model's fit: the factor g that maps the model's run onto the record (least
squares) lies within ``NEAR`` of a unit factor or of -1, and that factor leaves at most
``GAIN`` of the misfit the model leaves as it stands.

What may be the user's slip or the model's own is said, not refused (``hints``, in a fit's
warnings and a diagnosis's ``check:`` lines): a scale far from 1 that mends a probe
(``scale_hints``: a column in mA from a sensor 8 % high), a record whose clock starts late
or that spans a hundred times the netlist's analysis (``clock_hints``: a time column in ms).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

#: relative distance of the record-to-model factor from a unit's factor that counts as it [-]
NEAR = 0.03
#: share of the model's misfit [-] that scaling by the factor must leave at most
GAIN = 0.2

#: (the record's reading over the true value [-], what reads a column so), for any quantity
PREFIXES = ((1e3, ("a column in milli-units (mA, mV) read without its prefix, or in base "
                   "units read as kilo-units")),
            (1e-3, ("a column in base units read as milli-units, or in kilo-units (kW) read "
                    "without its prefix")),
            (1e6, "a column in micro-units read without its prefix"),
            (1e-6, "a column in base units read as micro-units"))
#: the same for a rotation speed [rad/s]
SPEEDS = ((60 / (2 * math.pi), "a column in rpm read as rad/s"),
          (2 * math.pi / 60, "a column in rad/s read as rpm"),
          (1 / (2 * math.pi), "a column in rev/s read as rad/s"),
          (2 * math.pi, "a column in rad/s read as rev/s"),
          (180 / math.pi, "a column in deg/s read as rad/s"),
          (math.pi / 180, "a column in rad/s read as deg/s"),
          (60.0, "a column in rpm read as rev/s"),
          (1 / 60, "a column in rev/s read as rpm"))
#: the same for an angle [rad]
ANGLES = ((1 / (2 * math.pi), "a column in turns read as rad"),
          (2 * math.pi, "a column in rad read as turns"),
          (180 / math.pi, "a column in degrees read as rad"),
          (math.pi / 180, "a column in rad read as degrees"))
SIGN = ("a sensor or a probe of the opposite sign: the sensor wired the other way round, or "
        "the probe's direction (a current into the node, not out of it) -- or, for a periodic "
        "signal, a record whose clock or phase is half a period off the model's")


#: a record-to-model factor at least this far from 1 either way [-] (or of the other sign)
#: that mends a probe's misfit is reported as a scale (``scale_hints``); a sensor's own gain
#: error is a few percent, the catalog's gain at most tens of percent
SCALE = 2.0
#: how far [-, relative] a scale may lie from a unit's factor to be named near it: a column
#: in mA from a sensor with its own 8 % gain error is 1080 times the model's
SCALE_NEAR = 0.3


def factors(unit: str) -> tuple[tuple[float, str], ...]:
    """The factors a column of a probe in ``unit`` may be off by, with what makes each: -1,
    a unit's factor, and a unit's factor with the sign reversed."""
    compact = unit.replace(" ", "")
    own = SPEEDS if compact in ("rad/s", "1/s") else ANGLES if compact == "rad" else ()
    units = (*PREFIXES, *own)
    return ((-1.0, SIGN), *units, *((-f, f"{why}, with the sign reversed") for f, why in units))


def refuse(model, record, residuals: Mapping[str, np.ndarray],
           runs: Mapping[str, np.ndarray] | None = None) -> None:
    """Raise DataError naming the record when ``slip_of`` finds a slip on any probe of
    ``residuals`` (record - the fitted ``model``, whose run is ``runs``)."""
    from circuitsim.loop.record import DataError

    slip = slip_of(record, residuals, list(residuals), model.meta.get("units", {}), runs)
    if slip is not None:
        raise DataError(f"{record.path}: {slip}")


def slip_of(record, residuals: Mapping[str, np.ndarray], probes: Sequence[str],
            units: Mapping[str, str], runs: Mapping[str, np.ndarray] | None = None
            ) -> str | None:
    """What a record of ``probes`` reads off by, from the model's fit (``residuals``:
    record - model on the record's grid), or None when the model is not off by a unit's
    factor or a sign on any probe. A probe whose residual is not on the record's grid (a
    caller's mistake) is not judged. A record whose clock starts later than its own length
    is not judged either: its misfit is the clock's (``clock_hints``), and a periodic
    signal half a period late reads as its negative."""
    t = np.asarray(record.t, float)
    if t.size > 1 and float(t[0]) > float(t[-1] - t[0]):
        return None
    found = []
    for p, y, m, g, left in _scales(record, residuals, probes, runs):
        # of the factors near g that scaling mends (their windows overlap: 57.3 and 60),
        # the one that mends most
        near = [(float(np.sum((y - f * m) ** 2)), f, why)
                for f, why in factors(units.get(p, "")) if abs(g / f - 1.0) <= NEAR]
        near = [c for c in near if c[0] <= GAIN**2 * left]
        if near:
            after, f, why = min(near, key=lambda c: c[0])
            found.append(f"the record's {p} is {g:.4g} times the model's (the factor "
                         f"{f:.4g}: {why}); scaled by it, the model's misfit falls to "
                         f"{math.sqrt(after / left):.1%} of what it is")
    if not found:
        return None
    return ("; ".join(found) + ". A motor's effects do not scale a reading by a unit's "
            "factor or flip its sign: correct the column (its unit in the header, as "
            "'speed [rpm]' or 'i [mA]', or its sign) or the probe's definition in the "
            "netlist -- or, where the model is truly off by this factor (a gear ratio it "
            "lacks), the netlist")


def _scales(record, residuals: Mapping[str, np.ndarray], probes: Sequence[str],
            runs: Mapping[str, np.ndarray] | None = None):
    """Per probe that can be judged: its name, the record's column y, the model's run m on
    the record's grid (``runs``' where given, else y - residual), the least-squares factor
    g from m to y [-] and the misfit left as it stands (the residual's sum of squares), all
    but g divided by the largest magnitude of y and m (a column 1e30 times the model's
    loses the model in y - residual, and its squares overflow). A probe whose residual is
    not on the record's grid (a caller's mistake) or whose model is flat is left out."""
    for p in probes:
        y = np.asarray(record[p], float)
        r = np.asarray(residuals.get(p, ()), float)
        if r.shape != y.shape:
            continue
        m = np.asarray(runs[p], float) if runs is not None and p in runs else y - r
        if m.shape != y.shape:
            m = y - r
        size = float(np.max(np.abs(np.concatenate([y, m])), initial=0.0))
        if not (math.isfinite(size) and size > 0.0):
            continue
        y, m, r = y / size, m / size, r / size
        mm, left = float(m @ m), float(r @ r)
        if mm > 0.0 and math.isfinite(mm) and math.isfinite(left):
            yield p, y, m, float(y @ m) / mm, left


def scale_hints(record, residuals: Mapping[str, np.ndarray], probes: Sequence[str],
                units: Mapping[str, str], runs: Mapping[str, np.ndarray] | None = None
                ) -> list[str]:
    """What to check when a probe of the record is the model's run scaled by a factor far
    from 1 (``SCALE``, or of the other sign) that mends its misfit to ``GAIN`` of it or less,
    but lies too far from a unit's factor for ``slip_of`` to refuse the record (a column in
    mA whose sensor also reads 8 % high; a gear ratio the netlist lacks; a scale typed
    wrong). Said, not refused: unlike a unit's exact factor, such a scale may be the model's
    own. ``residuals``: record - model on the record's grid."""
    out = []
    for p, y, m, g, left in _scales(record, residuals, probes, runs):
        # a flat record (g = 0) reads nothing of the model: no scale to name
        if left <= 0.0 or g == 0.0 or not (g < 0.0 or
                                           abs(math.log(abs(g))) >= math.log(SCALE)):
            continue
        after = float(np.sum((y - g * m) ** 2))
        if after > GAIN**2 * left:
            continue
        near = [(abs(math.log(g / f)), f, why) for f, why in factors(units.get(p, ""))
                if g / f > 0 and abs(g / f - 1.0) <= SCALE_NEAR]
        unit = ""
        if near:
            _, f, why = min(near)
            unit = (f" It is {g / f - 1.0:+.1%} off the factor {f:.4g} ({why}): that slip "
                    f"with a sensor's own gain error would read so.")
        out.append(f"the record's {p} is {g:.4g} times the model's run; scaled by that, the "
                   f"model's misfit of it falls to {math.sqrt(after / left):.1%}. No effect "
                   f"of a motor scales a reading so.{unit} Check the column's unit and the "
                   f"sensor's scale, or the netlist's values (a gear ratio, a motor "
                   f"constant) that set the probe's size")
    return out


#: a final misfit [of the probes' spread] beyond which the record's clock is questioned when
#: it starts long after the netlist's (``clock_hints``): above what a good model leaves on a
#: real log (the ODrive's cogging, 0.36 after the effects), far above a synthetic record's
GROSS_MISFIT = 0.5


#: how many times the netlist's own analysis a record must span before a gross misfit
#: questions its time unit (``clock_hints``) [-]: a record in ms read as s spans 1000 times it
LONG_SPAN = 100.0
#: how many times shorter than the netlist's analysis a record must be before a gross misfit
#: questions its time unit [-]: a record in minutes read as s spans 1/60 of its length
SHORT_SPAN = 50.0


def clock_hints(t: np.ndarray, error: float, stop: float | None = None) -> list[str]:
    """What to check when the model, effects and all, still misses the record grossly
    (``GROSS_MISFIT``): a record's clock that starts later than its own length (the
    netlist's inputs act from t = 0, so a logger's clock that did not start with the
    experiment puts every step of the model at the wrong time, and no effect can mend that),
    and a record that spans ``LONG_SPAN`` times the netlist's analysis ``stop`` [s] or more
    (a time column in ms or us read as s), or 1/``SHORT_SPAN`` of it or less (in minutes or
    hours)."""
    t0, length = float(t[0]), float(t[-1] - t[0])
    if not error >= GROSS_MISFIT:  # a NaN error (every probe flat) asks nothing
        return []
    out = []
    if t0 > length:
        out.append(f"the model still misses the record by {error:.0%} of its spread, and the "
                   f"record starts at t = {t0:.6g} s, after {t0 / length:.3g} times its own "
                   f"length: the model is simulated from t = 0 with the netlist's inputs. If "
                   f"the record's clock did not start with the netlist's, shift its time "
                   f"column (subtract {t0:.6g} s) or move the inputs' times")
    elif stop and stop > 0 and length >= LONG_SPAN * stop:
        out.append(f"the model still misses the record by {error:.0%} of its spread, and the "
                   f"record spans {length:.6g} s, {length / stop:.3g} times the netlist's "
                   f"analysis (stop {stop:.6g} s). If its time column is in ms or us, say so "
                   f"in its header ('time [ms]')")
    elif stop and stop > 0 and 0 < length * SHORT_SPAN <= stop:
        out.append(f"the model still misses the record by {error:.0%} of its spread, and the "
                   f"record spans {length:.6g} s, 1/{stop / length:.3g} of the netlist's "
                   f"analysis (stop {stop:.6g} s). If its time column is in minutes or hours, "
                   f"say so in its header ('time [min]')")
    return out


#: share of a record past a table's end (or before its start) [-] beyond which a gross
#: misfit names the table (``table_hints``): a table that ends a sample early is no clue
PAST_TABLE = 0.05


def table_hints(t: np.ndarray, error: float,
                tables: Sequence[tuple[str, str, float, float]]) -> list[str]:
    """What to check when the model still misses the record grossly (``GROSS_MISFIT``) and
    the record runs past a measured input's table, ``tables``: (its label, the component it
    drives, its first and last time [s]). A table holds its end values outside its times,
    so over that part of the record the model's input is constant -- a record of another
    run, or a time column in another unit than the table's."""
    if not error >= GROSS_MISFIT or t.size < 2:
        return []
    t0, t1 = float(t[0]), float(t[-1])
    length, out = t1 - t0, []
    for label, comp, x0, x1 in tables:
        past = max(t1 - max(x1, t0), 0.0) + max(min(x0, t1) - t0, 0.0)
        if past > PAST_TABLE * length:
            out.append(f"the model still misses the record by {error:.0%} of its spread, and "
                       f"the record ({t0:.6g}-{t1:.6g} s) runs past the times of the table "
                       f"{label} that drives {comp} ({x0:.6g}-{x1:.6g} s): the table holds its "
                       f"end values outside them, so over {past / length:.0%} of the record "
                       f"the model's input is constant. Check that the table is this run's "
                       f"and that both time columns are in the same unit")
    return out


def tables_of(model) -> list[tuple[str, str, float, float]]:
    """The model's measured inputs for ``table_hints``: (label, component, first and last
    time [s]) of each table."""
    net = getattr(model, "netlist", None)
    return [(tab.label, c.name, float(np.min(tab.x)), float(np.max(tab.x)))
            for c in getattr(net, "components", ()) for tab in c.tables if len(tab.x)]


def stop_of(model) -> float | None:
    """The analysis stop [s] the netlist states, None when it states none (the default 0.1 s
    says nothing of the record the author had in mind)."""
    net = getattr(model, "netlist", None)
    raw = getattr(net, "raw", None)
    if raw is None or "stop" not in (getattr(raw, "analysis", None) or {}):
        return None
    stop = float(net.analysis.stop)
    return stop if stop > 0 else None


def hints(model, record, residuals: Mapping[str, np.ndarray], error: float,
          runs: Mapping[str, np.ndarray] | None = None) -> list[str]:
    """What the user may check before reading a fit or a diagnosis of ``record``: its clock
    and time unit when the ``model``'s misfit ``error`` is gross (``clock_hints``), a table
    of its inputs the record runs past (``table_hints``), and a
    probe the model meets only scaled (``scale_hints``); ``residuals``: record - model,
    ``runs``: the model's run on the record's grid (where known)."""
    t = np.asarray(record.t, float)
    out = [*clock_hints(t, error, stop_of(model)), *table_hints(t, error, tables_of(model)),
           *scale_hints(record, residuals, list(residuals), model.meta.get("units", {}),
                        runs)]
    return out or gross_hints(record, residuals, error)


def gross_hints(record, residuals: Mapping[str, np.ndarray], error: float) -> list[str]:
    """A gross misfit (``GROSS_MISFIT``) that neither the clock nor a scale explains: the
    estimates are those of a model that does not describe the record, and their standard
    errors assume it does (a record stretched tenfold in time fitted R ninefold with a
    2 % standard error and no word). Names each probe missed grossly, by its NRMSE [-]."""
    if not error >= GROSS_MISFIT:
        return []
    worst = []
    for p, r in residuals.items():
        y = np.asarray(record[p], float)
        spread = float(np.std(y))
        nrmse = float(np.sqrt(np.mean(np.asarray(r, float) ** 2))) / spread if spread else 0.0
        if nrmse >= GROSS_MISFIT:
            worst.append(f"{p} by {nrmse:.0%} of its spread")
    where = f" ({', '.join(worst)})" if worst else ""
    said = (f"the model misses the record by {error:.0%} of its spread{where}: the estimates "
            f"are those of a model that does not describe this record, and their standard "
            f"errors assume it does. Check that the netlist's inputs (sources, loads, their "
            f"times) are the experiment's, the record's time column and the probes' units")
    return [said]
