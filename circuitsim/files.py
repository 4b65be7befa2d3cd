"""Files in and out: the one atomic writer and the one CSV reader (a leaf: errors only).

Every file circuitsim writes goes through :func:`atomic_write`, so an interrupted run leaves the
old file whole and a finished one has the mode the user's umask asks for (``mkstemp`` alone
would leave it 0600). Every CSV it reads (records, tables, identification data) goes through
:func:`read_rows` and :func:`numeric_rows`, so a bad cell is reported the same way everywhere:
file, row (the file's line) and column.
"""

from __future__ import annotations

import csv
import errno
import math
import os
import re
import shutil
import stat
import tempfile
import warnings
from collections.abc import Callable, Iterable
from pathlib import Path

import numpy as np

from circuitsim.errors import CircuitsimError


def _umask() -> int:
    # os.umask can only be read by setting it; set it back at once
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


class OutputError(CircuitsimError, OSError):
    """An output cannot be written (disk full, read-only or missing folder, a folder named as
    the file) or would overwrite an input. Exit code 3; 2 when the command line named it wrong.

    It is also an ``OSError``, so code that already handles I/O errors keeps doing so.
    """

    exit_code = 3


def check_output(path: str | os.PathLike, inputs: Iterable[str | os.PathLike] = (),
                 what: str = "output") -> None:
    """Refuse, before any work, an output that cannot be written or that is one of ``inputs``;
    create its missing folders (every output does: a run never fails on a new folder).

    Raises OutputError (exit code 2: the command line is wrong) naming the file and the fix.
    """
    p = os.fspath(path)
    real = os.path.realpath(p)
    for src in inputs:
        if os.path.exists(src) and os.path.exists(real) and os.path.samefile(real, src):
            raise _usage(f"{what} '{p}' is the input '{os.fspath(src)}': writing it would "
                         f"destroy the input; choose another file name")
    if os.path.isdir(real):
        raise _usage(f"{what} '{p}' is a folder; name a file inside it")
    if os.path.exists(real) and not _is_regular(real):
        return  # a device or pipe (/dev/null, a FIFO) is written through
    if what == "--plot":
        plot_format(p)
    folder = os.path.dirname(real) or "."
    existing = folder
    while not os.path.exists(existing):
        existing = os.path.dirname(existing)
    if not os.path.isdir(existing):
        raise _usage(f"{what} '{p}': '{existing}' is a file, not a folder")
    if not os.access(existing, os.W_OK | os.X_OK):
        raise _usage(f"{what} '{p}' is in a folder you cannot write ({existing}); write "
                     f"elsewhere")
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as exc:
        raise _usage(f"{what} '{p}': cannot create the folder {folder}: {exc.strerror}") \
            from None
    _try_folder(p, folder, what)


def _try_folder(p: str, folder: str, what: str) -> None:
    """Create and remove a file in ``folder``: the permission bits do not tell a read-only
    file system, a full disk's quota or a folder such as /proc that takes no new files
    (root passes every ``os.access``), and the output must fail now, not after the work."""
    try:
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".circuitsim-probe-")
    except OSError as exc:
        # the folder exists (made above): ENOENT here is a folder that takes no files
        hint = (" (this folder does not take new files)" if exc.errno == errno.ENOENT
                else _HINTS.get(exc.errno or 0, ""))
        raise _usage(f"{what} '{p}': cannot write into {folder}: "
                     f"{exc.strerror or exc}{hint}; write elsewhere") from None
    os.close(fd)
    os.unlink(probe)


#: What a plot may be written as, chosen by its file's extension
PLOT_FORMATS = ("png", "svg", "pdf")
#: [any unit] the largest size a data file's value may have: a sum of squares of a million
#: such values still fits a double (1.8e308); no reading in SI units comes near it
HUGE = 1e150


def plot_format(path: str | os.PathLike) -> str:
    """The format of a plot file from its extension ('png' for a device such as /dev/null);
    OutputError (exit 2) for any other: a PNG written into 'fig.txt' or 'fig.svg' is not
    what was asked for."""
    p = os.fspath(path)
    if os.path.exists(p) and not _is_regular(p):
        return "png"
    ext = os.path.splitext(p)[1].lstrip(".").lower()
    if ext not in PLOT_FORMATS:
        stem = os.path.splitext(os.path.basename(p))[0] or "plot"
        raise _usage(f"--plot '{p}': a plot is written as {', '.join(PLOT_FORMATS)}, chosen "
                     f"by the file's extension; name it e.g. '{stem}.png'")
    return ext


def _usage(message: str) -> OutputError:
    err = OutputError(message)
    err.exit_code = 2
    return err


def _is_regular(path: str) -> bool:
    try:
        return stat.S_ISREG(os.stat(path).st_mode)
    except OSError:
        return False


def atomic_write(path: str | os.PathLike, write: Callable[[str], None] | str | bytes,
                 *, make_dirs: bool = True) -> None:
    """Write ``path`` whole or not at all, with the mode the umask gives a new file.

    ``write`` is either the content (text or bytes) or a function that writes the content to
    the temporary path it is given (matplotlib's ``savefig``, numpy's ``savetxt``). A symbolic
    link is written through (the link stays, its target is replaced whole); a device or a pipe
    (``/dev/null``) is written directly. Raises OutputError (also an ``OSError``) when the
    file cannot be written; no temporary file is left behind.
    """
    # realpath: replace the file a link points at, never the link itself
    target = os.path.realpath(os.fspath(path))
    folder = os.path.dirname(target) or "."
    try:
        if os.path.exists(target) and not _is_regular(target):
            if os.path.isdir(target):
                raise IsADirectoryError(errno.EISDIR, "is a folder", target)
            _write_through(target, write)
            return
        if make_dirs:
            os.makedirs(folder, exist_ok=True)
        _replace(target, folder, write)
    except OutputError:
        raise
    except OSError as exc:
        hint = _HINTS.get(exc.errno or 0, "")
        if exc.errno == errno.ENOENT and os.path.isdir(folder):
            hint = " (this folder does not take new files; write elsewhere)"
        raise OutputError(f"cannot write '{os.fspath(path)}': {exc.strerror or exc}{hint}") \
            from None


_HINTS = {errno.ENOSPC: " (the disk is full; free space and run again)",
          errno.EDQUOT: " (the disk quota is exhausted)",
          errno.EROFS: " (the file system is read-only; write elsewhere)",
          errno.EACCES: " (no permission; write elsewhere)",
          errno.ENOENT: " (the folder does not exist; create it first)"}


def _replace(target: str, folder: str, write: Callable[[str], None] | str | bytes) -> None:
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
        # also on KeyboardInterrupt and SystemExit (the CLI turns SIGTERM into one)
        if os.path.exists(tmp):
            os.unlink(tmp)


def _write_through(target: str, write: Callable[[str], None] | str | bytes) -> None:
    """Write into a device or pipe as it is (it cannot be replaced, and must not be)."""
    if callable(write):
        with tempfile.TemporaryDirectory(prefix=".circuitsim-") as tmpdir:
            tmp = os.path.join(tmpdir, "out" + Path(target).suffix)
            write(tmp)
            with open(tmp, "rb") as src, open(target, "wb") as dst:
                shutil.copyfileobj(src, dst)
        return
    data = write.encode("utf-8") if isinstance(write, str) else write
    with open(target, "wb") as fh:
        fh.write(data)


_UNIT_SUFFIX = re.compile(r"\s*\[[^\[\]]*\]$")

RowError = Callable[[str, int], Exception]
"""Builds the caller's own error from (message, 1-based file line; 0 for the whole file)."""


def read_rows(path: str | os.PathLike, error: RowError) -> tuple[list[str], list[list[str]]]:
    """The header (stripped, units in brackets dropped) and the non-blank text rows of a CSV file ([], [] when empty).

    Raises ``error(...)`` for a missing, unreadable or non-UTF-8 file.
    """
    rows = _csv_rows(path, error, list)
    rows = [r for r in rows if any(c.strip() for c in r)]  # blank lines carry nothing
    if not rows:
        return [], []  # the caller says what an empty file should have held
    # a unit in brackets ('v_out [V]', as `circuitsim run` writes them) is not part of the name
    return [_UNIT_SUFFIX.sub("", h.strip()) for h in rows[0]], rows[1:]


def split_unit(cell: str) -> tuple[str, str | None]:
    """A header cell as (name, unit): ``'motor.i [A]'`` -> ``('motor.i', 'A')``, a cell
    without brackets -> ``(cell, None)``; both stripped."""
    cell = cell.strip()
    m = _UNIT_SUFFIX.search(cell)
    if m is None:
        return cell, None
    return cell[: m.start()].strip(), m.group(0).strip()[1:-1].strip()


def read_header(path: str | os.PathLike, error: RowError) -> list[str]:
    """The header of a CSV file (stripped, units in brackets dropped; [] when the file holds
    no row), reading only its first lines. Raises ``error(...)`` as :func:`read_rows`."""
    return [name for name, _ in read_header_units(path, error)]


def read_header_units(path: str | os.PathLike, error: RowError) -> list[tuple[str, str | None]]:
    """The header of a CSV file as (name, unit or None) per column (:func:`split_unit`;
    [] when the file holds no row). Raises ``error(...)`` as :func:`read_rows`."""
    def first(reader) -> list[tuple[str, str | None]]:
        for row in reader:
            if any(c.strip() for c in row):
                return [split_unit(h) for h in row]
        return []

    return _csv_rows(path, error, first)


def _csv_rows(path: str | os.PathLike, error: RowError, take):
    """``take(csv.reader)`` on the opened file; the file's own faults raised as ``error``."""
    p = os.fspath(path)
    try:
        # utf-8-sig: a spreadsheet's byte-order mark is not part of the first column's name
        with open(p, encoding="utf-8-sig", newline="") as fh:
            return take(csv.reader(fh))
    except FileNotFoundError:
        raise error(f"data file '{p}' not found. Check the path", 0) from None
    except IsADirectoryError:
        raise error(f"data file '{p}' is a folder, not a CSV file", 0) from None
    except OSError as exc:
        raise error(f"cannot read data file '{p}': {exc.strerror}", 0) from None
    except UnicodeDecodeError:
        raise error(f"data file '{p}' is not UTF-8 text. Export it as a CSV text file",
                    0) from None


def read_body(path: str | os.PathLike, header: list[str], error: RowError,
              echo: bool = True) -> np.ndarray:
    """The data rows after the header as a float array (rows x columns), in memory a small
    multiple of the numbers themselves (numpy's C parser; no list of strings per cell). On
    any doubt the file is scanned again row by row, and the first bad cell raises
    ``error`` as :func:`numeric_rows` does."""
    p = os.fspath(path)
    try:
        with open(p, encoding="utf-8", newline="") as fh, warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)  # no rows: the caller says so
            _skip_header(fh)
            arr = np.loadtxt(fh, delimiter=",", dtype=float, ndmin=2, comments=None)
        if arr.size == 0:
            return np.empty((0, len(header)))
        if arr.shape[1] == len(header) and np.all(np.abs(arr) <= HUGE):
            return arr
    except (ValueError, UnicodeDecodeError):
        pass
    return _scan_stream(p, header, error, echo)


def _skip_header(fh) -> None:
    """Advance ``fh`` past the blank lines and the header line."""
    for line in fh:
        if line.strip().strip(","):
            return


def _scan_stream(path: str, header: list[str], error: RowError, echo: bool) -> np.ndarray:
    from array import array

    values = array("d")
    try:
        with open(path, encoding="utf-8", newline="") as fh:
            rows = (r for r in csv.reader(fh) if any(c.strip() for c in r))
            next(rows, None)  # the header
            for i, row in enumerate(rows):
                values.extend(_scan_rows(path, header, [row], error, echo, first=i)[0])
    except UnicodeDecodeError:
        raise error(f"data file '{path}' is not UTF-8 text. Export it as a CSV text file",
                    0) from None
    return np.frombuffer(values, dtype=float).reshape(-1, len(header)).copy()


def numeric_rows(path: str | os.PathLike, header: list[str], rows: list[list[str]],
                 error: RowError, echo: bool = True) -> np.ndarray:
    """The rows as a float array (rows x columns); the first bad cell raises ``error``, quoting
    the cell only when ``echo`` (a file a netlist names may be private: never quoted)."""
    p = os.fspath(path)
    try:
        # the fast path; on any doubt the row-by-row scan finds the offending cell
        arr = np.array([[float(c) for c in r] for r in rows], dtype=float)
        if arr.shape != (len(rows), len(header)) or not np.all(np.abs(arr) <= HUGE):
            raise ValueError
        return arr.reshape(len(rows), len(header))
    except ValueError:
        return _scan_rows(p, header, rows, error, echo)


def _scan_rows(path: str, header: list[str], rows: list[list[str]],
               error: RowError, echo: bool = True, first: int = 0) -> np.ndarray:
    out = np.empty((len(rows), len(header)))
    for i, row in enumerate(rows):
        line = first + i + 2
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
                shown = f"'{s[:20]}'" if echo else "the value"
                raise error(f"row {line}, column '{header[j]}': {shown} is not a number. "
                            f"Write plain numbers in SI units (no unit suffixes, no thousands "
                            f"separators); put units in the netlist", line) from None
            if not math.isfinite(v):
                what = "missing or NaN" if math.isnan(v) else "infinite: a saturated reading?"
                raise error(f"row {line}, column '{header[j]}' is {s} ({what}). "
                            f"Remove the row, or interpolate the missing sample", line)
            if abs(v) > HUGE:
                shown = f"{v:.3g}" if echo else "a value"
                raise error(f"row {line}, column '{header[j]}' is {shown}, beyond {HUGE:g} in "
                            f"size: its square overflows double precision (a corrupt value, "
                            f"or a wrong unit?). Remove the row or correct it", line)
            out[i, j] = v
    return out
