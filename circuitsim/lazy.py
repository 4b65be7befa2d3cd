"""A module imported on first use, so that a run which never needs it never pays for it.

sympy costs 0.2-0.3 s to import; a run whose compiled model comes from the cache never
builds an equation, so the component library holds sympy through a :class:`LazyModule` and
sympy loads only when a component's equations are first built (a cache miss, ``circuitsim
equations``).
"""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import Any


class LazyModule:
    """Stands for the module ``name`` and imports it at the first attribute read.

    Nothing is patched: ``sys.modules`` only ever holds the real module, put there by the
    ordinary import machinery (whose per-module lock makes the first read safe from any
    thread). Each attribute read once is kept, so later reads cost what a module's do.
    """

    def __init__(self, name: str):
        self._name = name

    def __getattr__(self, attr: str) -> Any:
        # only called for names not yet kept in the instance's __dict__; a dunder read (copy,
        # pickle probing) or a half-built instance must not start an import
        if attr.startswith("__") or attr == "_name":
            raise AttributeError(attr)
        value = getattr(self.module(), attr)
        setattr(self, attr, value)
        return value

    def module(self) -> ModuleType:
        """The real module, imported now if it was not yet."""
        return importlib.import_module(self._name)

    def __repr__(self) -> str:
        return f"<lazy module {self._name!r}>"
