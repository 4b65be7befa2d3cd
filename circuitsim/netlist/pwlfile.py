"""PWL points from a CSV file: ``{pwl: {file: points.csv, column: v, time: time}}``."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from circuitsim.errors import NetlistError, SourceLoc

#: Every PWL point is a run-time parameter and a breakpoint; a longer record is a ``table``.
MAX_POINTS = 1000


def pwl_points(body: Any, path: str, loc: SourceLoc, comp: str,
               check: Callable[[Path], None] | None = None, unit: str | None = None) -> Any:
    """The inline ``[[t, v], ...]`` form of a PWL given as a CSV file (SI numbers), or
    ``body`` unchanged when it is already inline. ``check`` vets the file before it is read
    (the loader's rule for where input files may lie and how large they may be); ``unit``
    is the signal's, against which a unit in the file's header is checked."""
    if not isinstance(body, Mapping):
        return body
    from circuitsim.netlist.tables import read_column

    extra = set(body) - {"file", "column", "time"}
    if "file" not in body or "column" not in body or extra:
        raise NetlistError("a pwl from a file is {file: points.csv, column: NAME} (and "
                           "optionally time: NAME); inline it is [[t0, v0], [t1, v1], ...]",
                           loc, comp)
    file = Path(path).parent / str(body["file"])
    if check is not None:
        check(file)
    x, y = read_column(file, str(body["column"]), str(body.get("time", "time")), loc, comp,
                       unit)
    if len(x) > MAX_POINTS:
        raise NetlistError(f"pwl file '{file.name}' has {len(x)} points (at most {MAX_POINTS}: "
                           f"each is a breakpoint); for a long record use {{table: {{file: "
                           f"..., column: ...}}}}", loc, comp)
    return [[float(a), float(b)] for a, b in zip(x, y, strict=True)]
