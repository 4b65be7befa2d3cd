"""Measured data: CSV records with a time axis, and summary features, checked before use.

Two forms of measurement feed ``circuitsim fit``:

- a **record**: a CSV file with a header row, a ``time`` column [s] and one column per probe
  of the netlist, in SI units or in the unit its header names (``motor.i [A]``, ``w [rpm]``,
  as ``circuitsim run`` writes them), sampled at any uniform or non-uniform rate;
- **features**: a small YAML file of summary numbers, as a paper or a data sheet reports them
  (a steady value; the amplitude and frequency of a harmonic of the shaft rotation)::

      features:
        - {kind: mean, probe: speed, value: 6200 rpm, sigma: 50 rpm}
        - {kind: harmonic, probe: i_total, order: 8, amplitude: 0.38 A, frequency: 825.84 Hz}

Values carry units and are read by the restricted expression parser (``circuitsim.expr``),
never by ``eval``. Every error names the file, the row or line, the column or feature, and
what would fix it.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from circuitsim.errors import CircuitsimError, SourceLoc
from circuitsim.files import read_body, read_header_units


class DataError(CircuitsimError):
    """A measured record or feature file is malformed, or does not match the netlist."""


# --------------------------------------------------------------------------- records

MIN_ROWS = 8  # fewer samples cannot carry a waveform (nor a harmonic fit)


@dataclass(frozen=True)
class Record:
    """A measured time series: sample times ``t`` [s] and one array per column [SI].

    ``columns`` maps a probe name (or an input column) to its samples; ``path`` is the file
    it came from (for messages).
    """

    t: np.ndarray
    columns: Mapping[str, np.ndarray]
    path: str = "<memory>"

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(self.columns)

    @property
    def uniform(self) -> bool:
        """True when the sample spacing is constant (to 1e-6 relative)."""
        return is_uniform(self.t)


#: relative spread of the sample spacing up to which a record counts as evenly sampled
EVEN = 1e-6


def is_uniform(t: np.ndarray, jitter: float = EVEN) -> bool:
    """True when the spacing of the times ``t`` [s] is constant to ``jitter`` (relative)."""
    dt = np.diff(np.asarray(t, float))
    return bool(np.ptp(dt) <= jitter * np.mean(dt))


def even_grid(t: np.ndarray, jitter: float = EVEN) -> np.ndarray:
    """``t`` [s] itself when evenly spaced (to ``jitter``), else as many evenly spaced times
    over the same span."""
    t = np.asarray(t, float)
    return t if t.size < 3 or is_uniform(t, jitter) else np.linspace(t[0], t[-1], t.size)


def _row_error(path: str) -> Callable[[str, int], DataError]:
    return lambda message, line: DataError(message, SourceLoc(path, line))


def load_record(path: str | Path, probes: Sequence[str] | None = None, *,
                inputs: Sequence[str] = (), time: str = "time",
                units: Mapping[str, str] | None = None) -> Record:
    """Read a measured record from a CSV file with a header row.

    A column name may carry its unit in brackets, as ``circuitsim run`` writes them
    (``time [s]``, ``motor.i [A]``); a name without one is in SI units. A unit is checked
    against the probe's (``units``) and the column converted to SI (``w [rpm]``, ``i [mA]``
    and ``time [ms]`` are read right).

    Parameters
    ----------
    path : the CSV file; first row the column names, then one sample per row.
    probes : probe names of the netlist. Each column other than ``time`` must be one of
        them (or of ``inputs``); with None any column is accepted.
    inputs : column names that are measured inputs (they drive a table source), accepted
        besides the probes.
    time : name of the time column [s].
    units : the unit of each probe (``model.meta["units"]``), against which a unit in the
        header is checked; a column without an entry only needs a unit pint knows.

    Returns
    -------
    Record
        Times [s] and columns [SI] as float arrays.

    Raises
    ------
    DataError
        Naming the file and the row (file line) or column, for: an unreadable or empty file,
        no data rows, no ``time`` column, a column that is not a probe, duplicate columns,
        rows of the wrong length, values that are not numbers, NaNs, a time axis that does
        not increase or starts before 0, and a record without any probe column.
    """
    p = str(path)
    cells = read_header_units(p, _row_error(p))
    header = [name for name, _ in cells]
    if not header:
        raise DataError(f"data file '{p}' is empty. A record is a CSV with a header row "
                        f"('{time},PROBE,...') and one sample per row", SourceLoc(p))
    if all(_is_number(h) for h in header):
        raise DataError(f"data file '{p}' has no header row (the first row is numbers). Add "
                        f"a first row naming the columns: '{time},PROBE,...'", SourceLoc(p, 1))
    _check_first_line(p, header)
    _check_separator(p, header)
    _check_header(p, header, probes, inputs, time)
    factors = [_unit_factor(p, name, unit, units or {}, time) for name, unit in cells]
    arr = read_body(p, header, _row_error(p))
    if arr.shape[0] < MIN_ROWS:
        raise DataError(f"data file '{p}' has {arr.shape[0]} data rows; a record needs at "
                        f"least {MIN_ROWS}", SourceLoc(p, arr.shape[0] + 1))
    for j, f in enumerate(factors):
        if f != 1.0:
            arr[:, j] *= f
    return _record(p, header, arr, time)


def _unit_factor(p: str, name: str, unit: str | None, units: Mapping[str, str],
                 time: str) -> float:
    """The SI factor of a column's unit in brackets (1 without one), after checking it
    against the probe's unit (or seconds for the time column); DataError naming the column
    when it does not fit."""
    from circuitsim.units import UnitMismatch, column_factor

    if unit is None:
        return 1.0
    cell = f"column '{name} [{unit}]' of data file '{p}'"
    target = "s" if name == time else units.get(name, "")
    try:
        return column_factor(unit, target)
    except UnitMismatch as exc:
        what = "the time column" if name == time else f"the probe '{name}'"
        raise DataError(f"{cell}: {exc}; {what} is in {target}", SourceLoc(p, 1)) from None
    except ValueError as exc:
        raise DataError(f"{cell}: {exc}. Write the unit as in the netlist (e.g. A, V, rad/s, "
                        f"rpm), or leave the brackets out for SI", SourceLoc(p, 1)) from None


def _check_first_line(p: str, header: list[str]) -> None:
    """A first line that is no header: a logger's comment ('# ...'), said as such rather
    than as a missing time column; bytes that are no text (a binary file named .csv)."""
    first = ",".join(header)
    if any(ord(ch) < 32 and ch not in "\t\r\n" for ch in first):
        raise DataError(f"data file '{p}' is not a text CSV (its first line holds control "
                        f"characters). Export the record as comma-separated text",
                        SourceLoc(p, 1))
    if first.lstrip().startswith("#"):
        raise DataError(f"data file '{p}' starts with a comment line ('{first[:60]}'); a "
                        f"record's first line is its header ('time,PROBE,...'). Delete the "
                        f"lines above the header", SourceLoc(p, 1))


def _check_separator(p: str, header: list[str]) -> None:
    """A header of one cell that another separator splits (a spreadsheet's export in a
    locale whose decimal mark is the comma): said as such, not as a missing time column.
    Not read: its numbers may carry decimal commas, which a guess would misread."""
    if len(header) != 1:
        return
    for sep, name in ((";", "semicolons"), ("\t", "tabs")):
        if sep in header[0]:
            raise DataError(f"data file '{p}' separates its columns by {name}, not commas "
                            f"(header '{header[0]}'). Save it as a comma-separated file "
                            f"with decimal points (a spreadsheet's 'CSV (comma delimited)' "
                            f"in an English locale)", SourceLoc(p, 1))


def _check_header(p: str, header: list[str], probes: Sequence[str] | None,
                  inputs: Sequence[str], time: str) -> None:
    seen: set[str] = set()
    for j, h in enumerate(header):
        if not h:
            raise DataError(f"column {j + 1} of data file '{p}' has no name. Name it after a "
                            f"probe of the netlist, or delete it", SourceLoc(p, 1))
        if h in seen:
            raise DataError(f"column '{h}' appears twice in data file '{p}'. Keep one",
                            SourceLoc(p, 1))
        seen.add(h)
    if time not in header:
        raise DataError(f"data file '{p}' has no '{time}' column (columns: "
                        f"{', '.join(header)}){_near_text(time, header)}. Name the time "
                        f"column '{time}' (seconds)", SourceLoc(p, 1))
    if probes is not None and not probes:
        raise DataError(f"the netlist declares no probes, so no column of data file '{p}' "
                        f"can be compared with it. Add a 'probes:' section naming what each "
                        f"column measures (e.g. 'speed: rotor.w', 'i: La.i')", SourceLoc(p, 1))
    if probes is not None:
        allowed = {*probes, *inputs}
        for h in header:
            if h != time and h not in allowed:
                raise DataError(f"column '{h}' of data file '{p}' is not a probe of the "
                                f"netlist{_near_text(h, list(probes))} (probes: "
                                f"{', '.join(probes)}). Rename the column after a probe, add "
                                f"a probe '{h}' to the netlist, or delete the column; a "
                                f"measured input or a signal to leave unused is listed as "
                                f"one (on the command line, --inputs {h})",
                                SourceLoc(p, 1))
        if not any(h in probes for h in header):
            raise DataError(f"data file '{p}' has no column for any probe of the netlist "
                            f"(columns: {', '.join(header)}; probes: {', '.join(probes)}). "
                            f"Name each measured column after the probe it measures",
                            SourceLoc(p, 1))


#: [s] a record starting this late (11.6 days) and CLOCK_RATIO times its own length after
#: t = 0 carries a clock's time stamps, not the model's time (Unix, GPS and LabVIEW time are
#: 1e9 s and more; a slice of a long run starts at a few of its lengths)
CLOCK_TIME = 1e6
CLOCK_RATIO = 1000.0


def _record(p: str, header: list[str], arr: np.ndarray, time: str) -> Record:
    t = arr[:, header.index(time)]
    if t[0] < 0:
        raise DataError(f"time starts at {t[0]:g} s (row 2). The model starts from rest at "
                        f"t = 0: shift the time axis so the record starts at 0 or later",
                        SourceLoc(p, 2))
    if t[0] >= CLOCK_TIME and t[0] > CLOCK_RATIO * (t[-1] - t[0]):
        raise DataError(f"time starts at {t[0]:.10g} s (row 2), {t[0] / (t[-1] - t[0]):.3g} "
                        f"times the record's own length: the model starts from rest at t = 0 "
                        f"and would be simulated over all of that first. These look like a "
                        f"clock's time stamps (Unix time?): subtract the first time so the "
                        f"record starts at 0, and state the netlist's stimuli on that axis",
                        SourceLoc(p, 2))
    step = np.diff(t)
    if np.any(step <= 0):
        k = int(np.argmax(step <= 0))
        raise DataError(f"time does not increase at row {k + 3} ({t[k + 1]:g} s after "
                        f"{t[k]:g} s in row {k + 2}). Sort the rows by time and remove "
                        f"duplicate samples", SourceLoc(p, k + 3))
    # contiguous columns (a strided view would slow every later pass); the table goes after
    cols = {h: np.ascontiguousarray(arr[:, j]) for j, h in enumerate(header) if h != time}
    return Record(np.ascontiguousarray(t), cols, p)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _near_text(name: str, options: Sequence[str]) -> str:
    close = difflib.get_close_matches(name, list(options), n=3, cutoff=0.6)
    return f" (did you mean {', '.join(repr(c) for c in close)}?)" if close else ""


# -------------------------------------------------------------------------- features

FEATURE_KINDS = ("mean", "harmonic")


@dataclass(frozen=True)
class Feature:
    """One measured scalar: the steady ``mean`` of a probe, or the ``amplitude`` [probe unit]
    or ``frequency`` [Hz] of its harmonic of shaft order ``order``.

    ``value`` and ``sigma`` are SI; ``sigma`` is None when the file gives none (the fit then
    weighs the feature relative to its value). ``dim`` is the dimension the value was written
    in (None for a bare number), checked against the probe by :meth:`FeatureSet.check`.
    """

    quantity: str
    probe: str
    value: float
    sigma: float | None
    order: float | None
    loc: SourceLoc
    dim: Any = None

    @property
    def label(self) -> str:
        if self.quantity == "mean":
            return f"mean({self.probe})"
        return f"{self.quantity}({self.probe}, order {self.order:g})"


@dataclass(frozen=True)
class FeatureSet:
    """Measured features read from a YAML file (see the module docstring)."""

    features: tuple[Feature, ...]
    path: str = "<memory>"
    title: str = ""
    notes: dict = field(default_factory=dict)

    def __len__(self) -> int:
        return len(self.features)

    def check(self, model) -> None:
        """Raise DataError when a feature names no probe of ``model`` or has the wrong unit."""
        from circuitsim.units import compatible, explain_mismatch, unit_info

        probes = model.probe_names
        units = model.meta.get("units", {})
        for f in self.features:
            if f.probe not in probes:
                raise DataError(f"feature {f.label}: '{f.probe}' is not a probe of the netlist"
                                f"{_near_text(f.probe, probes)} (probes: {', '.join(probes)})."
                                f" Name a probe, or add one to the netlist's 'probes:'", f.loc)
            if f.dim is None:
                continue
            if f.quantity == "frequency":
                unit = "Hz"
            else:
                unit = units.get(f.probe, "")
            if not unit or unit == "1":
                continue
            target = unit_info(unit)[1]
            if not compatible(f.dim, target):
                raise DataError(f"feature {f.label}: {explain_mismatch(f.dim, target, unit)}",
                                f.loc)


def _feature_value(raw: Any, loc: SourceLoc, what: str, absolute: bool = False
                   ) -> tuple[float, Any]:
    """SI value and dimension (None for a bare number) of a number or '6200 rpm';
    ``absolute``: a level, so '40 degC' alone is 313.15 K (a sigma in degC is refused)."""
    from circuitsim.netlist import expr as ex
    from circuitsim.units import absolute_temperature

    if absolute and isinstance(raw, str):
        raw = absolute_temperature(raw) or raw

    if isinstance(raw, bool) or raw is None or isinstance(raw, (list, dict)):
        raise DataError(f"{what} must be a number with an optional unit (e.g. '0.38 A'), not "
                        f"{raw!r}", loc)
    if isinstance(raw, (int, float)):
        v = float(raw)
        dim = None
    else:
        try:
            node = ex.parse(str(raw))
            if ex.names(node):
                raise ex.ExprError(f"names ({', '.join(sorted(ex.names(node)))}) are not "
                                   f"allowed in a measured value", str(raw), 0)
            v = ex.evaluate(node, {})
            dim = ex.dimension(node, {}) if node.kind == "unit" else None
        except (ex.ExprError, ValueError, ZeroDivisionError) as exc:
            raise DataError(f"{what}: {exc}. Write a number with an optional unit, e.g. "
                            f"'6200 rpm' or '0.38 A'", loc) from None
    if not math.isfinite(v):
        raise DataError(f"{what} is not finite ({v})", loc)
    return v, dim


def load_features(path: str | Path) -> FeatureSet:
    """Read a features file (YAML; see the module docstring).

    Each entry of ``features:`` is ``{kind: mean, probe, value, sigma?}`` or ``{kind:
    harmonic, probe, order, amplitude?, frequency?, sigma?, sigma_frequency?}`` (at least one
    of amplitude and frequency; ``sigma`` is the amplitude's). A harmonic's frequency is in Hz;
    a rotation speed in rad/s, rpm or rev/s. Raises DataError naming the file and line.
    """
    from ruamel.yaml import YAML
    from ruamel.yaml.error import YAMLError

    from circuitsim.netlist.lines import yaml_line as _loc

    p = str(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        raise DataError(f"features file '{p}' not found. Check the path",
                        SourceLoc(p)) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise DataError(f"cannot read features file '{p}': {exc}", SourceLoc(p)) from None
    try:
        doc = YAML(typ="rt").load(text)
    except YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        line = mark.line + 1 if mark is not None else 0
        raise DataError(f"YAML syntax error: {getattr(exc, 'problem', None) or exc}. Check "
                        f"indentation, colons and quotes", SourceLoc(p, line)) from None
    shape = ("a features file is a YAML mapping with a list 'features:' of entries such as "
             "{kind: mean, probe: speed, value: 6200 rpm}")
    if doc is None:
        raise DataError(f"features file '{p}' is empty; {shape}", SourceLoc(p))
    if not isinstance(doc, Mapping) or "features" not in doc:
        raise DataError(shape, SourceLoc(p, 1))
    unknown = [k for k in doc if k not in ("features", "title", "notes")]
    if unknown:
        raise DataError(f"unknown key '{unknown[0]}' (allowed: features, title, notes)",
                        _loc(p, doc, key=unknown[0]))
    entries = doc["features"]
    if not isinstance(entries, list) or not entries:
        raise DataError(f"'features:' must be a non-empty list; {shape}",
                        _loc(p, doc, key="features"))
    out: list[Feature] = []
    for i, e in enumerate(entries):
        loc = _loc(p, entries, index=i)
        out += _parse_feature(e, loc, i)
    return FeatureSet(tuple(out), p, str(doc.get("title", "")), dict(doc.get("notes") or {}))


_KEYS = {"mean": {"kind", "probe", "value", "sigma"},
         "harmonic": {"kind", "probe", "order", "amplitude", "frequency", "sigma",
                      "sigma_frequency"}}


def _parse_feature(e: Any, loc: SourceLoc, i: int) -> list[Feature]:
    where = f"feature {i + 1}"
    if not isinstance(e, Mapping):
        raise DataError(f"{where} must be a mapping such as {{kind: mean, probe: speed, value: "
                        f"6200 rpm}}", loc)
    kind = e.get("kind")
    if kind not in FEATURE_KINDS:
        raise DataError(f"{where}: kind must be one of {', '.join(FEATURE_KINDS)}, not "
                        f"{kind!r}", loc)
    extra = sorted(set(map(str, e)) - _KEYS[kind])
    if extra:
        raise DataError(f"{where} ({kind}): unknown key '{extra[0]}'"
                        f"{_near_text(extra[0], sorted(_KEYS[kind]))} (allowed: "
                        f"{', '.join(sorted(_KEYS[kind]))})", loc)
    probe = e.get("probe")
    if not isinstance(probe, str) or not probe:
        raise DataError(f"{where} ({kind}) needs 'probe: NAME' (a probe of the netlist)", loc)
    if kind == "mean":
        if "value" not in e:
            raise DataError(f"{where} (mean of {probe}) needs 'value:', e.g. 'value: 6200 rpm'",
                            loc)
        v, dim = _feature_value(e["value"], loc, f"{where}: value", absolute=True)
        s, sdim = _sigma(e, "sigma", loc, where)
        _same_dim(dim, sdim, loc, where)
        return [Feature("mean", probe, v, s, None, loc, dim)]
    return _harmonic_features(e, loc, where, probe)


def _sigma(e: Mapping, key: str, loc: SourceLoc, where: str) -> tuple[float | None, Any]:
    """The standard deviation ``key`` of a feature entry (None when not given)."""
    if key not in e:
        return None, None
    s, dim = _feature_value(e[key], loc, f"{where}: {key}")
    if not s > 0:
        raise DataError(f"{where}: {key} must be positive (a standard deviation), got "
                        f"{s:g}", loc)
    return s, dim


def _harmonic_features(e: Mapping, loc: SourceLoc, where: str, probe: str) -> list[Feature]:
    """The amplitude and/or frequency features of one 'harmonic' entry."""
    if "order" not in e:
        raise DataError(f"{where} (harmonic of {probe}) needs 'order:' (per shaft revolution, "
                        f"e.g. 8 for a 2-pole 8-slot motor)", loc)
    order, _ = _feature_value(e["order"], loc, f"{where}: order")
    if not order > 0:
        raise DataError(f"{where}: order must be positive, got {order:g}", loc)
    if "amplitude" not in e and "frequency" not in e:
        raise DataError(f"{where} (harmonic of {probe}) needs 'amplitude:' or 'frequency:' "
                        f"(or both)", loc)
    feats = []
    if "amplitude" in e:
        v, dim = _feature_value(e["amplitude"], loc, f"{where}: amplitude")
        if not v > 0:
            raise DataError(f"{where}: amplitude must be positive (a peak value), got {v:g}",
                            loc)
        s, sdim = _sigma(e, "sigma", loc, where)
        _same_dim(dim, sdim, loc, where)
        feats.append(Feature("amplitude", probe, v, s, order, loc, dim))
    elif "sigma" in e:
        raise DataError(f"{where}: 'sigma' is the amplitude's; for the frequency write "
                        f"'sigma_frequency'", loc)
    if "frequency" in e:
        v, dim = _feature_value(e["frequency"], loc, f"{where}: frequency")
        if not v > 0:
            raise DataError(f"{where}: frequency must be positive, got {v:g}", loc)
        s, sdim = _sigma(e, "sigma_frequency", loc, where)
        _same_dim(dim, sdim, loc, where)
        feats.append(Feature("frequency", probe, v, s, order, loc, dim))
    return feats


def _same_dim(value_dim: Any, sigma_dim: Any, loc: SourceLoc, where: str) -> None:
    from circuitsim.units import compatible

    if value_dim is not None and sigma_dim is not None and not compatible(value_dim,
                                                                          sigma_dim):
        raise DataError(f"{where}: sigma has dimension {sigma_dim}, the value {value_dim}; "
                        f"give both in the same kind of unit", loc)


def load_data(path: str | Path, probes: Sequence[str] | None = None, *,
              inputs: Sequence[str] = (), time: str = "time",
              units: Mapping[str, str] | None = None) -> Record | FeatureSet:
    """A record (``.csv``, time column ``time`` [s]; ``load_record``) or a features file
    (``.yaml``/``.yml``), by extension."""
    suffix = Path(path).suffix.lower()
    if suffix in (".yaml", ".yml"):
        return load_features(path)
    if suffix in (".csv", ".txt", ""):
        return load_record(path, probes, inputs=inputs, time=time, units=units)
    raise DataError(f"data file '{path}': unknown kind '{suffix}'. Give a CSV record (.csv) "
                    f"or a features file (.yaml)", SourceLoc(str(path)))
