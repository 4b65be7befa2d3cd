"""circuitsim: acausal circuit-network simulator for electromechanical systems.

YAML netlist -> graph (networkx) -> MNA DAE (sympy) -> index 1 -> generated code -> IDA.
"""

from __future__ import annotations

__version__ = "0.1.0"

from .errors import CircuitsimError, NetlistError, ParameterError, SingularCircuitError, SolverError
from .model import CompiledModel, compile
from .netlist import Netlist, load
from .result import SimResult, Status

__all__ = [
    "CircuitsimError",
    "CompiledModel",
    "Netlist",
    "NetlistError",
    "ParameterError",
    "SimResult",
    "SingularCircuitError",
    "SolverError",
    "Status",
    "compile",
    "load",
]
