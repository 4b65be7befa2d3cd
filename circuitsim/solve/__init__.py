"""CompiledModel -> results: transient (IDA), consistent initial values, op, ac, pss.

Nothing here imports the compiler: the solver is handed a CompiledModel and uses only its
kernels and metadata.
"""

from circuitsim.solve.integrate import simulate
from circuitsim.solve.result import SimResult, Status

__all__ = ["SimResult", "Status", "simulate"]
