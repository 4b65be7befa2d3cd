"""The cache folder, and small persistent tables of pure functions' results kept in it.

A warm run should not pay for a library it used only to compute something it computed before:
the SI factor of ``mH`` (pint, 0.2 s to import) or the schema verdict on an unchanged netlist
(jsonschema, 0.1 s). A :class:`Memo` keeps such answers in one JSON file of the cache folder,
named by a version that changes whenever the function could answer differently. Only a folder
that passes the model cache's ownership check is used (a planted table would change values,
as a planted module would change code); otherwise the table lives in memory for the process.
"""

from __future__ import annotations

import json
import os
import stat
from pathlib import Path
from typing import Any


def cache_dir() -> Path:
    """Where compiled models live: $CIRCUITSIM_CACHE, else ~/.cache/circuitsim."""
    env = os.environ.get("CIRCUITSIM_CACHE")
    base = Path(env) if env else Path(os.environ.get("XDG_CACHE_HOME",
                                                     Path.home() / ".cache")) / "circuitsim"
    return base


def unsafe(d: Path) -> str | None:
    """Why the folder must not be trusted with code that will run, or None if it may: it
    must belong to this user and be writable by no one else (anyone who can write there
    could plant a module that runs at the next cache hit)."""
    if not hasattr(os, "getuid"):  # Windows: per-user profile folders, no POSIX modes
        return None
    st = d.stat()
    if st.st_uid != os.getuid():
        return f"it belongs to user id {st.st_uid}, not to you"
    if st.st_mode & 0o022:
        return f"other users can write to it (mode {stat.S_IMODE(st.st_mode):o})"
    return None


def open_cache_dir() -> tuple[Path, str | None]:
    """The cache folder, created private (0700) if missing, and why it must not be used
    (None when it may)."""
    d = cache_dir()
    try:
        d.parent.mkdir(parents=True, exist_ok=True)
        d.mkdir(mode=0o700, exist_ok=True)
        why = unsafe(d)
    except OSError as exc:
        why = f"it cannot be used ({exc.strerror})"
        file = next((q for q in (d, *d.parents) if q.exists() and not q.is_dir()), None)
        if file is not None:  # mkdir says 'File exists', which misleads
            why = ("it is a file, not a folder" if file == d else
                   f"{file}, a part of its path, is a file")
    return d, why


class Memo:
    """A persistent str -> JSON value table, ``memo-NAME-VERSION.json`` in the cache folder.

    Read once per process (per cache folder), rewritten whole at each new entry: the tables
    hold tens of entries, and a new entry means the slow function just ran anyway.
    """

    def __init__(self, name: str, version: str, limit: int = 2000):
        self.file = f"memo-{name}-{version}.json"
        self.limit = limit  # entries; the oldest go first
        self._table: dict[str, Any] = {}
        self._folder: Path | None = None

    def _table_of(self, d: Path) -> dict[str, Any]:
        if d != self._folder:  # first use, or CIRCUITSIM_CACHE changed (tests, sweeps)
            self._folder, self._table = d, {}
            try:
                if unsafe(d) is None:
                    data = json.loads((d / self.file).read_text(encoding="utf-8"))
                    self._table = data if isinstance(data, dict) else {}
            except (OSError, ValueError):
                pass  # no folder or no table yet, or a damaged one: start empty
        return self._table

    def get(self, key: str) -> Any:
        """The stored value of ``key``, or None."""
        return self._table_of(cache_dir()).get(key)

    def put(self, key: str, value: Any) -> None:
        """Store ``value`` (JSON-serialisable) under ``key``; in memory only when the folder
        must not or cannot be used."""
        from circuitsim.files import atomic_write

        d, why = open_cache_dir()
        table = self._table_of(d)
        table[key] = value
        while len(table) > self.limit:
            del table[next(iter(table))]
        if why is None:
            try:
                atomic_write(d / self.file, json.dumps(table))
            except OSError:
                pass  # a full disk or a read-only home: the memo is only a shortcut
