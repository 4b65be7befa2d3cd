"""``circuitsim cache``: list the cache folder, prune it, clear it (``cachefolder``)."""

from __future__ import annotations

import json
import time
from collections import Counter

from circuitsim import cachefolder as cf


def _folder():
    """The cache folder, refused when it is not the user's own (another user's files are
    not for circuitsim to remove)."""
    from circuitsim.memo import cache_dir, unsafe

    folder = cache_dir()
    if folder.exists() and not folder.is_dir():
        raise cf.CacheError(f"the cache folder {folder} is a file, not a folder; point "
                            f"CIRCUITSIM_CACHE at a folder only you can write")
    if folder.is_dir():
        why = unsafe(folder)
        if why is not None:
            raise cf.CacheError(f"the cache folder {folder} is not managed: {why}; point "
                                f"CIRCUITSIM_CACHE at a folder only you can write")
    return folder


def _cmd_info(args) -> int:
    folder = _folder()
    found, other = cf.entries(folder)
    kinds = Counter(e.kind for e in found)
    size = {k: sum(e.size for e in found if e.kind == k) for k in kinds}
    if args.json:
        print(json.dumps({"folder": str(folder), "entries": dict(kinds), "bytes": size,
                          "other_bytes": other,
                          "legacy_kernels": sum(e.legacy for e in found),
                          "oldest_use": min((e.used for e in found), default=None),
                          "latest_use": max((e.used for e in found), default=None)},
                         indent=1))
        return 0
    total = sum(size.values())
    print(f"cache folder {folder}: {len(found)} entries, {cf.megabytes(total)}")
    for kind in ("model", "kernels", "kernel library", "memo"):
        if kinds[kind]:
            print(f"  {kind:15s} {kinds[kind]:6d}  {cf.megabytes(size[kind])}")
    legacy = [e for e in found if e.legacy]
    if legacy:
        print(f"  of the kernels, {len(legacy)} named the old way and never read again: "
              f"{cf.megabytes(sum(e.size for e in legacy))}")
    current = [e for e in found if not e.legacy]
    if current:
        days = (time.time() - current[0].used) / 86400.0
        print(f"  least recently used {days:.1f} days ago")
    if other:
        print(f"  other files (not circuitsim's, never touched): {cf.megabytes(other)}")
    print("`circuitsim cache prune --max-size 500MB` or `--older-than 30d` removes the entries "
          "used least recently; `circuitsim cache clear` all of them")
    return 0


def _cmd_prune(args) -> int:
    if args.max_size is None and args.older_than is None:
        raise cf.CacheError("cache prune needs --max-size SIZE, --older-than AGE or both "
                            "(e.g. --max-size 500MB, --older-than 30d)")
    limit = cf.parse_size(args.max_size) if args.max_size is not None else None
    age = cf.parse_age(args.older_than) if args.older_than is not None else None
    folder = _folder()
    found, _ = cf.entries(folder)
    count, freed = cf.remove(cf.choose(found, limit, age))
    kept = sum(e.size for e in found) - freed
    print(f"removed {count} entries ({cf.megabytes(freed)}); kept {len(found) - count} "
          f"({cf.megabytes(kept)}) in {folder}")
    if limit is not None and kept > limit:
        print(f"  the rest was used in the last {cf.GRACE / 60:.0f} minutes and may be in use: "
              f"kept above the limit")
    return 0


def _cmd_clear(args) -> int:
    folder = _folder()
    found, _ = cf.entries(folder)
    count, freed = cf.remove(found)
    print(f"removed {count} entries ({cf.megabytes(freed)}) from {folder}")
    return 0


def add_cli(subparsers) -> None:
    """Register ``circuitsim cache {info, prune, clear}``."""
    c = subparsers.add_parser("cache", help="list, prune or clear the folder of compiled "
                              "models and kernels")
    c.set_defaults(func=_cmd_info, json=False)
    sub = c.add_subparsers(dest="cache_command", metavar="ACTION")
    i = sub.add_parser("info", help="what the folder holds (the default)")
    i.add_argument("--json", action="store_true", help="print one JSON object")
    i.set_defaults(func=_cmd_info)
    p = sub.add_parser("prune", help="remove the entries used least recently")
    p.add_argument("--max-size", help="keep at most this much, e.g. 500MB or 2GB")
    p.add_argument("--older-than", help="remove what was not used for this long, e.g. 30d")
    p.set_defaults(func=_cmd_prune)
    k = sub.add_parser("clear", help="remove every entry (a running job derives what it "
                       "needs again)")
    k.set_defaults(func=_cmd_clear)
