"""The on-disk cache of compiled models: one generated module and its metadata per topology.

A second run of the same topology imports the module without touching sympy.
"""

from __future__ import annotations

import builtins
import hashlib
import json
import marshal
import os
import sys
from pathlib import Path
from types import ModuleType

from circuitsim.compiler.codegen import CODEGEN_VERSION
from circuitsim.files import atomic_write
from circuitsim.memo import cache_dir, open_cache_dir  # noqa: F401 - cache_dir: public here


def _code_fingerprint() -> str:
    """Hash of the derivation code and the component library, so an edited component or
    pipeline stage never meets a stale cached model; and of the helpers the generated kernels
    import by a name that changes with them (``solve/kernel_lib.py``): a model cached before
    would name helpers no longer written, and run on the Python route."""
    import circuitsim_components

    h = hashlib.sha256()
    root = Path(__file__).parents[1]
    files = [root / "component.py", root / "symfunc.py", root / "units.py", root / "errors.py",
             root / "solve" / "kernel_lib.py",
             *sorted((root / "netlist").glob("*.py")), *sorted((root / "compiler").glob("*.py")),
             *sorted(Path(circuitsim_components.__file__).parent.glob("*.py"))]
    for f in files:
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


def cache_key(topology: str) -> str:
    import circuitsim

    raw = (f"{topology}|{CODEGEN_VERSION}|{circuitsim.__version__}|{sys.version_info[:2]}|"
           f"{_code_fingerprint()}")
    return "m" + hashlib.sha256(raw.encode()).hexdigest()[:24]


# Models derived in this process, for a cache folder that cannot be used (see _usable).
_MEMORY: dict[str, tuple[str, dict]] = {}
_WARNED: set[str] = set()


def _usable() -> Path | None:
    """The cache folder, created private (0700) if missing; None if it is unsafe, with one
    warning per folder saying what to do."""
    d, why = open_cache_dir()
    if why is None:
        return d
    if str(d) not in _WARNED:
        import warnings

        from circuitsim.errors import CircuitWarning

        _WARNED.add(str(d))
        warnings.warn(f"model cache {d} is not used: {why}. Compiled models are kept in memory "
                      f"only; point CIRCUITSIM_CACHE at a folder only you can write "
                      f"(chmod 700)", CircuitWarning, stacklevel=4)
    return None


def _digest(*parts: bytes) -> str:
    h = hashlib.sha256()
    for part in parts:
        h.update(hashlib.sha256(part).digest())
    return h.hexdigest()


def store(key: str, source: str, meta: dict) -> None:
    """Write the module, its bytecode, its metadata and their hash atomically (a killed run
    leaves no half file; a half or edited file fails the hash and is derived again)."""
    d = _usable()
    if d is None:
        _MEMORY[key] = (source, meta)
        return
    src = source.encode("utf-8")
    js = json.dumps(meta).encode("utf-8")
    code = marshal.dumps(builtins.compile(src, str(d / f"{key}.py"), "exec"))
    for suffix, data in ((".py", src), (".json", js), (".code", code)):
        atomic_write(d / f"{key}{suffix}", data)
    atomic_write(d / f"{key}.sha256", _digest(src, js, code))


def _read(d: Path, key: str) -> tuple[bytes, bytes, bytes] | None:
    """The three files if they are whole, ours, and match the stored hash; else None."""
    try:
        parts = []
        for suffix in (".py", ".json", ".code"):
            f = d / f"{key}{suffix}"
            if hasattr(os, "getuid") and f.stat().st_uid != os.getuid():
                return None
            parts.append(f.read_bytes())
        want = (d / f"{key}.sha256").read_text(encoding="utf-8").strip()
    except (OSError, UnicodeDecodeError):
        return None
    return (parts[0], parts[1], parts[2]) if _digest(*parts) == want else None


def load_cached(key: str) -> tuple[ModuleType, dict] | None:
    """The cached module and metadata of ``key``, or None (then the caller derives again):
    nothing runs unless its content matches the hash written with it."""
    if key in _MEMORY:
        source, meta = _MEMORY[key]
        return _module(key, builtins.compile(source, f"<circuitsim model {key}>", "exec")), meta
    d = _usable()
    got = _read(d, key) if d is not None else None
    if got is None:
        return None
    _, js, code = got
    try:
        meta = json.loads(js)
        return _module(key, marshal.loads(code)), meta
    except (ValueError, TypeError, EOFError, SyntaxError):
        return None


def _module(key: str, code) -> ModuleType:
    """A module object running ``code`` (the verified bytecode; no import machinery, so
    no stray __pycache__ file is ever consulted)."""
    mod = ModuleType(f"circuitsim_generated_{key}")
    exec(code, mod.__dict__)  # noqa: S102 - our own generated code, hash-checked
    return mod
