"""The on-disk cache of compiled models: one generated module and its metadata per topology.

A second run of the same topology imports the module without touching sympy.
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import os
import sys
from pathlib import Path
from types import ModuleType

from circuitsim.compiler.codegen import CODEGEN_VERSION
from circuitsim.files import atomic_write


def cache_dir() -> Path:
    """Where compiled models live: $CIRCUITSIM_CACHE, else ~/.cache/circuitsim."""
    env = os.environ.get("CIRCUITSIM_CACHE")
    base = Path(env) if env else Path(os.environ.get("XDG_CACHE_HOME",
                                                     Path.home() / ".cache")) / "circuitsim"
    return base


def _code_fingerprint() -> str:
    """Hash of the derivation code and the component library, so an edited component or
    pipeline stage never meets a stale cached model."""
    import circuitsim_components

    h = hashlib.sha256()
    root = Path(__file__).parents[1]
    files = [root / "component.py", root / "units.py", root / "errors.py",
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


def store(key: str, source: str, meta: dict) -> None:
    """Write the module and metadata atomically (a killed run leaves no half file)."""
    d = cache_dir()
    d.mkdir(parents=True, exist_ok=True)
    for suffix, text in ((".py", source), (".json", json.dumps(meta))):
        atomic_write(d / f"{key}{suffix}", text)


def load_cached(key: str) -> tuple[ModuleType, dict] | None:
    d = cache_dir()
    py, js = d / f"{key}.py", d / f"{key}.json"
    if not (py.exists() and js.exists()):
        return None
    try:
        meta = json.loads(js.read_text(encoding="utf-8"))
        return import_module(key, py), meta
    except (OSError, ValueError, SyntaxError):
        return None


def import_module(key: str, path: Path) -> ModuleType:
    """Import a generated module from its file (so Python caches its bytecode too)."""
    spec = importlib.util.spec_from_file_location(f"circuitsim_generated_{key}", path)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod
