"""What circuitsim keeps in its cache folder, and keeping the folder in bounds.

The folder (``memo.cache_dir``: $CIRCUITSIM_CACHE, else ~/.cache/circuitsim) holds entries,
each named by a digest of what it holds:

- a compiled model per topology: ``mKEY.py``, ``.json``, ``.code`` and ``.sha256``
  (``compiler/cache.py``);
- a kernel module per distinct kernel source, ``kNAME_kernels.py`` (``solve/direct.py``),
  with numba's machine code for it in ``__pycache__/kNAME_kernels.*.nbi|nbc``; before
  kernels were named by their source they were named by their model, ``mKEY_kernels.py``:
  such files are never read again and go first;
- a kernel module compiled by the C compiler (``solve/ccode.py``), ``cNAME.so``, named by
  its C text and the compiler's command;
- the kernels' helper library, one per version: ``circuitsim_kernel_lib_HASH.py`` and its
  numba files;
- small tables of pure functions' results: ``memo-NAME-VERSION.json`` (``memo.py``).

Nothing expires by itself. A diagnosis compiles tens of topologies and a topology sweep
more, and a new circuitsim version, a changed component or a new kernel naming names every
entry anew and leaves the old ones unused. ``circuitsim cache`` lists the folder, ``cache
prune`` removes the entries used least recently (down to a size, or those unused for a
time), ``cache clear`` removes them all. Only files of these forms are touched: a folder
shared with other files keeps them.

An entry's last use is the latest access or change time of its files. Reading a file
updates its access time at most once a day on Linux's default ``relatime`` mounts, which is
the resolution an expiry in days needs; on a ``noatime`` mount it is the time the entry was
written. Nothing is written to mark a use: a kernel module's time stamp is part of numba's
own cache key, and touching it would make numba compile again.

Removing an entry while another process uses it costs that process time, never a wrong
answer: a model whose files are gone or half gone fails its hash check and is derived again,
a kernel module absent is written again, and numba compiles what it no longer finds. Entries
used in the last ``GRACE`` seconds are still kept by ``prune``, as they are likely in use.
"""

from __future__ import annotations

import re
import time
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from circuitsim.errors import CircuitsimError

#: [s] an entry used more recently than this is never pruned: it may be in use right now
GRACE = 600.0
_ENTRY = re.compile(r"^(?P<stem>[mk][0-9a-f]{24}_kernels|m[0-9a-f]{24}|c[0-9a-f]{24}|"
                    r"circuitsim_kernel_lib_[0-9a-f]{12}|memo-[A-Za-z0-9_]+-[0-9a-f]+)"
                    r"(?P<rest>\..+)?$")
_MODEL_SUFFIXES = (".sha256", ".py", ".json", ".code")  # the hash first: removed, it voids
_NUMBA = re.compile(r"\.py\d+(\.\d+)?\.nb[ic]$")


class CacheError(CircuitsimError):
    """The cache folder cannot be managed as asked."""


@dataclass(frozen=True)
class Entry:
    """One thing the folder keeps: its files, their size [bytes] and its last use [s since
    the epoch]."""

    stem: str
    files: tuple[Path, ...]
    size: int
    used: float

    @property
    def legacy(self) -> bool:
        """Kernels named by their model, as before they were named by their source: no
        version of circuitsim that names them so reads this folder's entries any more."""
        return self.stem.startswith("m") and self.stem.endswith("_kernels")

    def idle(self, now: float) -> float:
        """How long it has not been used [s]; a legacy entry's is unbounded."""
        return float("inf") if self.legacy else now - self.used

    @property
    def kind(self) -> str:
        if self.stem.startswith("memo-"):
            return "memo"
        if self.stem.startswith("circuitsim_kernel_lib_"):
            return "kernel library"
        if self.stem.startswith("c"):
            return "compiled kernels"
        return "kernels" if self.stem.endswith("_kernels") else "model"


def _stem(path: Path) -> str | None:
    """The entry a file of the folder (or of its ``__pycache__``) belongs to, or None when it
    is not one of circuitsim's."""
    m = _ENTRY.match(path.name)
    if m is None:
        return None
    rest, stem = m.group("rest") or "", m.group("stem")
    code = stem.endswith("_kernels") or stem.startswith("circuitsim_kernel_lib_")
    if path.parent.name == "__pycache__":
        return stem if code and _NUMBA.search(rest) else None
    if code:
        return stem if rest == ".py" else None
    if stem.startswith("memo-"):
        return stem if rest == ".json" else None
    if stem.startswith("c"):
        return stem if rest == ".so" else None
    return stem if rest in _MODEL_SUFFIXES else None


def entries(folder: Path) -> tuple[list[Entry], int]:
    """The entries in ``folder``, legacy ones first, then least recently used first, and the
    size of the files that are not circuitsim's [bytes]."""
    groups: dict[str, list[tuple[Path, int, float]]] = {}
    other = 0
    for path in _files(folder):
        try:
            st = path.stat()
        except OSError:
            continue  # removed meanwhile by another process
        stem = _stem(path)
        if stem is None:
            other += st.st_size
        else:
            groups.setdefault(stem, []).append((path, st.st_size, max(st.st_atime,
                                                                      st.st_mtime)))
    out = [Entry(stem, tuple(sorted(p for p, _, _ in fs)), sum(s for _, s, _ in fs),
                 max(u for _, _, u in fs)) for stem, fs in groups.items()]
    out.sort(key=lambda e: (not e.legacy, e.used, e.stem))
    return out, other


def _files(folder: Path) -> Iterable[Path]:
    if not folder.is_dir():
        return
    for path in folder.iterdir():
        if path.is_file() and not path.is_symlink():
            yield path
    pycache = folder / "__pycache__"
    if pycache.is_dir() and not pycache.is_symlink():
        yield from (p for p in pycache.iterdir() if p.is_file() and not p.is_symlink())


def choose(found: list[Entry], max_size: int | None = None, older_than: float | None = None,
           now: float | None = None, grace: float = GRACE) -> list[Entry]:
    """The entries to remove: those unused for ``older_than`` [s], then the least recently
    used until the rest holds at most ``max_size`` [bytes]; never one used in the last
    ``grace`` [s]. Legacy entries count as unused for ever. ``found`` is in the order
    ``entries`` gives."""
    now = time.time() if now is None else now
    removable = [e for e in found if e.idle(now) >= grace]
    out = [e for e in removable if older_than is not None and e.idle(now) >= older_than]
    if max_size is not None:
        total = sum(e.size for e in found) - sum(e.size for e in out)
        for e in removable:
            if total <= max_size:
                break
            if e not in out:
                out.append(e)
                total -= e.size
    return out


def remove(chosen: Iterable[Entry]) -> tuple[int, int]:
    """Remove the entries' files, a model's hash first (a model half removed is void, not
    wrong); (entries removed, bytes freed). A file already gone is not an error."""
    count = freed = 0
    for e in chosen:
        order = sorted(e.files, key=lambda p: p.suffix != ".sha256")
        for path in order:
            try:
                path.unlink()
            except FileNotFoundError:
                continue
            except OSError as exc:
                raise CacheError(f"cannot remove {path}: {exc.strerror or exc}") from exc
        count += 1
        freed += e.size
    return count, freed


_SIZE = re.compile(r"^\s*(?P<n>\d+(\.\d*)?|\.\d+)\s*(?P<unit>([kKMGT]i?)?B?)\s*$")
_AGE = re.compile(r"^\s*(?P<n>\d+(\.\d*)?|\.\d+)\s*(?P<unit>s|min|h|d|w)\s*$")
_SIZE_FACTOR = {"": 1, "k": 1e3, "K": 1e3, "M": 1e6, "G": 1e9, "T": 1e12,
                "ki": 1024, "Ki": 1024, "Mi": 1024**2, "Gi": 1024**3, "Ti": 1024**4}
_AGE_FACTOR = {"s": 1.0, "min": 60.0, "h": 3600.0, "d": 86400.0, "w": 604800.0}


def parse_size(text: str) -> int:
    """A size such as ``500MB``, ``2G``, ``1.5 GiB`` or ``800000`` [bytes]."""
    m = _SIZE.match(text)
    if m is None:
        raise CacheError(f"'{text}' is not a size: write a number with an optional unit, "
                         f"as in 500MB, 2GB or 1.5GiB")
    return int(float(m.group("n")) * _SIZE_FACTOR[m.group("unit").rstrip("B")])


def parse_age(text: str) -> float:
    """An age such as ``30d``, ``12h``, ``2w`` or ``90min`` [s]."""
    m = _AGE.match(text)
    if m is None:
        raise CacheError(f"'{text}' is not an age: write a number and one of s, min, h, d or "
                         f"w, as in 30d or 12h")
    return float(m.group("n")) * _AGE_FACTOR[m.group("unit")]


def megabytes(n: int) -> str:
    return f"{n / 1e6:.1f} MB"
