"""One exception family for everything a user can get wrong, each carrying where it came from."""

from __future__ import annotations

import os
from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class SourceLoc:
    """A place in a netlist file: ``file:line`` (line is 1-based; 0 when unknown)."""

    file: str
    line: int = 0

    def __str__(self) -> str:
        name = self.file
        try:
            rel = os.path.relpath(name)
            if not rel.startswith(".."):
                name = rel
        except ValueError:
            pass
        return f"{name}:{self.line}" if self.line else name


class CircuitsimError(Exception):
    """Base of every error circuitsim raises on bad input or an unsolvable circuit.

    The message always says where (file, line, component) and what would fix it.
    """

    exit_code = 2

    def __init__(self, message: str, loc: SourceLoc | None = None, component: str | None = None):
        self.loc = loc
        self.component = component
        self.bare = message
        parts = []
        if loc is not None:
            parts.append(f"{loc}:")
        if component:
            parts.append(f"{component}:")
        parts.append(message)
        super().__init__(" ".join(parts))


class NetlistError(CircuitsimError):
    """The netlist file is malformed: syntax, unknown names, wrong structure."""


class ParameterError(CircuitsimError):
    """A parameter value is missing, has the wrong unit, or is outside its validity."""


class SingularCircuitError(CircuitsimError):
    """The circuit has no unique solution (floating nodes, source loops or cutsets)."""


class SolverError(CircuitsimError):
    """The integrator or a Newton solve failed; the message names time and variable."""

    exit_code = 1


class CircuitWarning(UserWarning):
    """Physics warnings (non-conserving coupling, inconsistent initial values)."""


def spoken(name: str) -> str:
    """A model variable's name as a message says it: ``der(x)`` as d(x)/dt, ``der(der(x))``
    as d²(x)/dt², and the index reduction's ``dummy(...)`` as the derivative it stands for
    (a person reads the circuit's names, not the compiler's)."""
    core = name[6:-1] if name.startswith("dummy(") and name.endswith(")") else name
    order = 0
    while core.startswith("der(") and core.endswith(")"):
        core, order = core[4:-1], order + 1
    if order == 0:
        return core
    power = "" if order == 1 else str(order).translate(str.maketrans("0123456789",
                                                                       "⁰¹²³⁴⁵⁶⁷⁸⁹"))
    return f"d{power}({core})/dt{power}"
