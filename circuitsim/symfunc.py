"""The sympy functions components write into equations: periodic time and table lookups.

Kept apart from ``component.py`` because defining a sympy ``Function`` imports sympy; this
module is imported only when equations are built (``component.Pmod`` and friends call into
it), never by a run whose compiled model comes from the cache.
"""

from __future__ import annotations

import sympy as sp


class Pmod(sp.Function):
    """Periodic time: x mod T in [0, T). Its derivative in x is 1 (corners are breakpoints)."""

    nargs = 2

    def fdiff(self, argindex=1):
        if argindex == 1:
            return sp.Integer(1)
        x, T = self.args
        return -sp.floor(x / T)


class Lookup(sp.Function):
    """Linear interpolation of the run-time table number ``k`` at ``x``: Lookup(k, x)."""

    nargs = 2

    def fdiff(self, argindex=2):
        if argindex != 2:
            raise sp.ArgumentIndexError(self, argindex)
        return LookupSlope(*self.args)


class LookupSlope(sp.Function):
    """Slope of table ``k`` at ``x`` (piecewise constant, so its own derivative is 0)."""

    nargs = 2

    def fdiff(self, argindex=2):
        return sp.Integer(0)
