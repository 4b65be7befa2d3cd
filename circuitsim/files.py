"""Files in and out: the one atomic writer and the one CSV reader (a leaf: errors only).

Every file circuitsim writes goes through :func:`atomic_write`, so an interrupted run leaves the
old file whole and a finished one has the mode the user's umask asks for (``mkstemp`` alone
would leave it 0600). Every CSV it reads (records, tables, identification data) goes through
:func:`read_rows` and :func:`numeric_rows`, so a bad cell is reported the same way everywhere:
file, row (the file's line) and column.
"""

from __future__ import annotations

import csv
import math
import os
import tempfile
from collections.abc import Callable
from pathlib import Path

import numpy as np


def _umask() -> int:
    # os.umask can only be read by setting it; set it back at once
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def atomic_write(path: str | os.PathLike, write: Callable[[str], None] | str | bytes,
                 *, make_dirs: bool = True) -> None:
    """Write ``path`` whole or not at all, with the mode the umask gives a new file.

    ``write`` is either the content (text or bytes) or a function that writes the content to
    the temporary path it is given (matplotlib's ``savefig``, numpy's ``savetxt``).
    """
    target = os.path.abspath(os.fspath(path))
    folder = os.path.dirname(target) or "."
    if make_dirs:
        os.makedirs(folder, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=".circuitsim-", suffix=Path(target).suffix)
    try:
        if callable(write):
            os.close(fd)
            write(tmp)
        else:
            data = write.encode("utf-8") if isinstance(write, str) else write
            with os.fdopen(fd, "wb") as fh:
                fh.write(data)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, target)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


RowError = Callable[[str, int], Exception]
"""Builds the caller's own error from (message, 1-based file line; 0 for the whole file)."""


def read_rows(path: str | os.PathLike, error: RowError) -> tuple[list[str], list[list[str]]]:
    """The header (stripped) and the non-blank text rows of a CSV file ([], [] when empty).

    Raises ``error(...)`` for a missing, unreadable or non-UTF-8 file.
    """
    p = os.fspath(path)
    try:
        with open(p, encoding="utf-8", newline="") as fh:
            rows = list(csv.reader(fh))
    except FileNotFoundError:
        raise error(f"data file '{p}' not found. Check the path", 0) from None
    except IsADirectoryError:
        raise error(f"data file '{p}' is a folder, not a CSV file", 0) from None
    except OSError as exc:
        raise error(f"cannot read data file '{p}': {exc.strerror}", 0) from None
    except UnicodeDecodeError:
        raise error(f"data file '{p}' is not UTF-8 text. Export it as a CSV text file",
                    0) from None
    rows = [r for r in rows if any(c.strip() for c in r)]  # blank lines carry nothing
    if not rows:
        return [], []  # the caller says what an empty file should have held
    return [h.strip() for h in rows[0]], rows[1:]


def numeric_rows(path: str | os.PathLike, header: list[str], rows: list[list[str]],
                 error: RowError) -> np.ndarray:
    """The rows as a float array (rows x columns); the first bad cell raises ``error``."""
    p = os.fspath(path)
    try:
        # the fast path; on any doubt the row-by-row scan finds the offending cell
        arr = np.array([[float(c) for c in r] for r in rows], dtype=float)
        if arr.shape != (len(rows), len(header)) or not np.all(np.isfinite(arr)):
            raise ValueError
        return arr.reshape(len(rows), len(header))
    except ValueError:
        return _scan_rows(p, header, rows, error)


def _scan_rows(path: str, header: list[str], rows: list[list[str]],
               error: RowError) -> np.ndarray:
    out = np.empty((len(rows), len(header)))
    for i, row in enumerate(rows):
        line = i + 2
        if len(row) != len(header):
            raise error(f"row {line} has {len(row)} values, the header has {len(header)} "
                        f"({', '.join(header)}). Every row needs one value per column; remove "
                        f"the stray comma or fill the missing value", line)
        for j, cell in enumerate(row):
            s = cell.strip()
            if not s:
                raise error(f"row {line}, column '{header[j]}' is empty (a missing value). "
                            f"Remove the row, or interpolate the missing sample", line)
            try:
                v = float(s)
            except ValueError:
                raise error(f"row {line}, column '{header[j]}': '{s[:20]}' is not a number. "
                            f"Write plain numbers in SI units (no unit suffixes, no thousands "
                            f"separators); put units in the netlist", line) from None
            if not math.isfinite(v):
                raise error(f"row {line}, column '{header[j]}' is {s} (missing or NaN). "
                            f"Remove the row, or interpolate the missing sample", line)
            out[i, j] = v
    return out
