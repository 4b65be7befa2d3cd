"""Netlist -> CompiledModel: graph checks, MNA assembly, index reduction, generated code, cache.

(Named ``compiler`` rather than ``compile`` so that ``circuitsim.compile``, the public
function, is never shadowed by a subpackage of the same name.)
"""

from circuitsim.compiler.model import CompiledModel, compile, derive

__all__ = ["CompiledModel", "compile", "derive"]
