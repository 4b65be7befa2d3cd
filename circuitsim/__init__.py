"""circuitsim: acausal circuit-network simulator for electromechanical systems.

YAML netlist -> graph (networkx) -> MNA DAE (sympy) -> index 1 -> generated code -> IDA.
"""

from __future__ import annotations

__version__ = "0.1.0"

from circuitsim.compiler.model import CompiledModel, compile
from circuitsim.errors import (
    CircuitsimError,
    CircuitWarning,
    NetlistError,
    ParameterError,
    SingularCircuitError,
    SolverError,
)
from circuitsim.netlist import Netlist, load
from circuitsim.solve.result import SimResult, Status

# the studies load on first use, so that ``import circuitsim`` stays light
_LAZY = {
    "simulate": ("circuitsim.solve.integrate", "simulate"),
    "simulate_batch": ("circuitsim.solve.batch", "simulate_batch"),
    "sweep": ("circuitsim.studies.sweep", "sweep"),
    "fit": ("circuitsim.loop.fit", "fit"),
    "diagnose": ("circuitsim.loop.diagnose", "diagnose"),
    "identify": ("circuitsim.loop.identify", None),
    "Record": ("circuitsim.loop.record", "Record"),
    "load_record": ("circuitsim.loop.record", "load_record"),
}


def __getattr__(name: str):
    if name not in _LAZY:
        raise AttributeError(f"module 'circuitsim' has no attribute '{name}'")
    import importlib

    module, attr = _LAZY[name]
    mod = importlib.import_module(module)
    return mod if attr is None else getattr(mod, attr)


__all__ = [
    "CircuitWarning",
    "CircuitsimError",
    "CompiledModel",
    "Netlist",
    "NetlistError",
    "ParameterError",
    "Record",
    "SimResult",
    "SingularCircuitError",
    "SolverError",
    "Status",
    "compile",
    "diagnose",
    "fit",
    "identify",
    "load",
    "load_record",
    "simulate",
    "simulate_batch",
    "sweep",
]
