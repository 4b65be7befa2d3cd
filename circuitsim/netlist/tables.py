"""Tables a netlist reads from CSV files (measured inputs, lookup curves)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from circuitsim.errors import NetlistError, SourceLoc
from circuitsim.files import numeric_rows, read_rows


def read_column(file: Path, column: str, time: str = "time", loc: SourceLoc | None = None,
                comp: str | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Read ``time`` [s] and ``column`` [SI] from a CSV with a header row.

    Raises NetlistError (at the netlist's line) for a missing file or column, a bad cell, or
    a time axis that does not increase.
    """
    where = loc or SourceLoc(str(file))

    def error(message: str, line: int) -> NetlistError:
        return NetlistError(f"data file '{file}': {message}" if line else message, where, comp)

    header, rows = read_rows(file, error)
    if not header:
        raise NetlistError(f"data file '{file}' is empty", where, comp)
    for name in (time, column):
        if name not in header:
            raise NetlistError(f"data file '{file}' has no column '{name}' (columns: "
                               f"{', '.join(header)})", where, comp)
    arr = numeric_rows(file, header, rows, error, echo=False)
    x, y = arr[:, header.index(time)], arr[:, header.index(column)]
    if len(x) < 2:
        raise NetlistError(f"data file '{file}' needs at least two rows", where, comp)
    if np.any(np.diff(x) <= 0):
        bad = int(np.argmax(np.diff(x) <= 0))
        raise NetlistError(f"data file '{file}': time does not increase at row {bad + 3}",
                           where, comp)
    return x, y
