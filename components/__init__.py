"""circuitsim's component library. Importing it fills the registries.

Each module is one family; each class states ports, parameters with units, and sympy
equations, and nothing else. Nothing here imports the solver.
"""

from . import (
    bldc,
    controlled,
    diode,
    drivetrain,
    emf,
    fluxtable,
    inverter,
    mechanical,
    passive,
    sources,
    stickslip,
    switches,
    thermal,
    varistor,
    waveforms,
)

__all__ = ["bldc", "controlled", "diode", "drivetrain", "emf", "fluxtable", "inverter", "mechanical", "passive",
           "sources", "stickslip", "switches", "thermal", "varistor", "waveforms"]
