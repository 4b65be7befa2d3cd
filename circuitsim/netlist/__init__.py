"""Text -> Netlist: YAML with source lines, includes, the restricted expression parser, units.

The loader lives in ``load``; this package re-exports what the rest of circuitsim uses.
"""

from circuitsim.netlist.load import ComponentSpec, Netlist, RawNetlist, build, load

__all__ = ["ComponentSpec", "Netlist", "RawNetlist", "build", "load"]
