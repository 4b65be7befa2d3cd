"""Tables a netlist reads from CSV files (measured inputs, lookup curves)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from circuitsim.errors import NetlistError, SourceLoc
from circuitsim.files import numeric_rows, read_header_units, read_rows


def read_column(file: Path, column: str, time: str = "time", loc: SourceLoc | None = None,
                comp: str | None = None, unit: str | None = None
                ) -> tuple[np.ndarray, np.ndarray]:
    """Read ``time`` [s] and ``column`` [SI] from a CSV with a header row.

    A unit in brackets in the header (``time [ms]``, ``v [mV]``, as ``circuitsim run`` writes
    them) is checked against seconds and ``unit`` (the signal's unit, when given) and the
    column converted to SI. Raises NetlistError (at the netlist's line) for a missing file or
    column, a column named twice, a unit that does not fit, a bad cell, or a time axis that
    does not increase.
    """
    where = loc or SourceLoc(str(file))

    def error(message: str, line: int) -> NetlistError:
        return NetlistError(f"data file '{file}': {message}" if line else message, where, comp)

    header, rows = read_rows(file, error)
    if not header:
        raise NetlistError(f"data file '{file}' is empty", where, comp)
    for name in (time, column):
        if name not in header:
            semi = "; the file seems to separate values by ';': export it comma-separated" \
                if any(";" in h for h in header) else ""
            raise NetlistError(f"data file '{file}' has no column '{name}' (columns: "
                               f"{', '.join(header)}){semi}", where, comp)
        if header.count(name) > 1:
            raise NetlistError(f"data file '{file}' has two columns named '{name}': rename "
                               f"or delete one", where, comp)
    units = dict(read_header_units(file, error))
    arr = numeric_rows(file, header, rows, error, echo=False)
    x, y = arr[:, header.index(time)], arr[:, header.index(column)]
    if len(x) < 2:
        raise NetlistError(f"data file '{file}' needs at least two rows", where, comp)
    x = x * _factor(file, time, units[time], "s", where, comp)
    y = y * _factor(file, column, units[column], unit, where, comp)
    if np.any(np.diff(x) <= 0):
        bad = int(np.argmax(np.diff(x) <= 0))
        raise NetlistError(f"data file '{file}': time does not increase at row {bad + 3}",
                           where, comp)
    return x, y


def _factor(file: Path, name: str, unit: str | None, want: str | None, where: SourceLoc,
            comp: str | None) -> float:
    """The SI factor of a header's unit in brackets (1 without one), checked against
    ``want`` (a unit; None or '@': anything). 'time [ms]' was dropped with its unit, so a
    record in ms ran a thousand times slower."""
    from circuitsim.units import UnitMismatch, column_factor

    if unit is None:
        return 1.0
    cell = f"data file '{file}': column '{name} [{unit}]'"
    try:
        return column_factor(unit, want)
    except UnitMismatch as exc:
        raise NetlistError(f"{cell}: {exc}", where, comp) from None
    except ValueError as exc:
        raise NetlistError(f"{cell}: {exc}. Write the unit as in the netlist (s, ms, V, mA), "
                           f"or leave the brackets out for SI", where, comp) from None
