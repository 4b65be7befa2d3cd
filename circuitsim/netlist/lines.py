"""Source lines of parsed YAML nodes (a leaf of the netlist package)."""

from __future__ import annotations

from typing import Any

from circuitsim.errors import SourceLoc


def yaml_line(path: str, node: Any, key: Any = None, index: int | None = None) -> SourceLoc:
    """Line (1-based) of a ruamel node, of one of its keys, or of one of its items."""
    try:
        if key is not None:
            return SourceLoc(path, node.lc.key(key)[0] + 1)
        if index is not None:
            return SourceLoc(path, node.lc.item(index)[0] + 1)
        return SourceLoc(path, node.lc.line + 1)
    except (AttributeError, KeyError, TypeError, IndexError):
        return SourceLoc(path, 0)
