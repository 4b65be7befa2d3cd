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


#: ruamel's attribute holding a node's line and column (``node.lc``)
_LINE_COL = "_yaml_line_col"
_ATOMS = (str, int, float, bool, type(None), SourceLoc)  # ruamel's scalars subclass these


def copy_nodes(value: Any, memo: dict[int, Any] | None = None) -> Any:
    """A deep copy of parsed YAML (and the tuples, sets and frozen dataclasses holding it)
    that keeps each node's lines but not its comments or formatting.

    ``copy.deepcopy`` copies a ruamel sequence's comment attributes once per item: copying a
    netlist for each of a diagnosis's patches took 1.2 s of r11's 43 s (0.17 s this way).
    Objects met twice (YAML aliases) are copied once, as deepcopy does; the line records are
    shared, since nothing writes them after parsing."""
    import copy
    import dataclasses

    memo = {} if memo is None else memo
    if isinstance(value, _ATOMS):
        return value
    known = memo.get(id(value))
    if known is not None:
        return known
    if isinstance(value, dict):
        out: Any = type(value)()
        memo[id(value)] = out
        for k in value:
            out[k] = copy_nodes(value[k], memo)
    elif isinstance(value, list):
        out = type(value)()
        memo[id(value)] = out
        out.extend(copy_nodes(x, memo) for x in value)
    elif type(value) is tuple:
        return tuple(copy_nodes(x, memo) for x in value)
    elif type(value) in (set, frozenset):
        return type(value)(value)  # members are hashable, hence immutable here
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        return dataclasses.replace(value, **{f.name: copy_nodes(getattr(value, f.name), memo)
                                             for f in dataclasses.fields(value) if f.init})
    else:
        return copy.deepcopy(value, memo)
    if hasattr(value, _LINE_COL):
        setattr(out, _LINE_COL, getattr(value, _LINE_COL))
    return out
