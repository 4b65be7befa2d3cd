"""Measured data: CSV columns with a time axis, checked before use."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .errors import NetlistError, SourceLoc


def read_column(file: Path, column: str, time: str = "time", loc: SourceLoc | None = None,
                comp: str | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Read ``time`` and ``column`` from a CSV with a header row; SI units assumed.

    Raises NetlistError for a missing file or column, NaNs, or a time axis that does not
    increase.
    """
    where = loc or SourceLoc(str(file))
    try:
        with open(file, encoding="utf-8") as fh:
            header = [h.strip() for h in fh.readline().strip().split(",")]
        arr = np.loadtxt(file, delimiter=",", skiprows=1, ndmin=2)
    except OSError:
        raise NetlistError(f"data file '{file}' not found", where, comp) from None
    except ValueError as exc:
        raise NetlistError(f"data file '{file}' is not a numeric CSV: {exc}", where,
                           comp) from None
    for name in (time, column):
        if name not in header:
            raise NetlistError(f"data file '{file}' has no column '{name}' (columns: "
                               f"{', '.join(header)})", where, comp)
    if arr.shape[1] != len(header):
        raise NetlistError(f"data file '{file}': rows have {arr.shape[1]} values, header has "
                           f"{len(header)}", where, comp)
    x, y = arr[:, header.index(time)], arr[:, header.index(column)]
    if len(x) < 2:
        raise NetlistError(f"data file '{file}' needs at least two rows", where, comp)
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        bad = int(np.argmax(~(np.isfinite(x) & np.isfinite(y))))
        raise NetlistError(f"data file '{file}' has a missing or NaN value in row {bad + 2}",
                           where, comp)
    if np.any(np.diff(x) <= 0):
        bad = int(np.argmax(np.diff(x) <= 0))
        raise NetlistError(f"data file '{file}': time does not increase at row {bad + 3}",
                           where, comp)
    return x, y
