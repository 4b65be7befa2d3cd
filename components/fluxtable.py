"""Saturating inductor from a measured flux curve, its corners found by events.

The flux linkage is piecewise linear through the table rows, so the differential inductance
is constant on each segment: it and the segment's ends are discrete states, switched by an
event where |i| leaves the segment. Each corner of the curve is thus met exactly (a row of
the table acts as a breakpoint in the current, not in time).
"""

from __future__ import annotations

from circuitsim.component import Branch, Event, OnePort, Param, RecordList, register, sp
from circuitsim_components.switches import BAND

ROW = {"i": Param("A", "current of the row", positive=True),
       "psi": Param("Wb", "flux linkage at that current", positive=True)}

#: Upper end of the last segment, which continues the table's last slope for ever [A].
BEYOND = 1e30


def _slopes(rows) -> list:
    """Slope [H] of each segment ending at a row: (0, 0) to row 1, then row to row."""
    out, i0, p0 = [], sp.Integer(0), sp.Integer(0)
    for r in rows:
        out.append((r["psi"] - p0) / (r["i"] - i0))
        i0, p0 = r["i"], r["psi"]
    return out


def _above(h, rows, values: list):
    """values[k] for the first row k with h < i_k (values[-1] past the last row): at the
    top h = i_k of a segment, the next row's entry."""
    return sp.Piecewise(*[(v, h < r["i"]) for r, v in zip(rows, values, strict=False)],
                        (values[-1], True))


def _below(low, rows, values: list, first):
    """values[k] for the last row k with low > i_k (``first`` at or below the first row): at
    the bottom low = i_k of a segment, the previous row's entry."""
    pieces = [(values[k], low > rows[k]["i"]) for k in reversed(range(len(rows)))]
    return sp.Piecewise(*pieces, (first, True))


@register("Lsat_table", "saturating_inductor_table")
class SaturatingInductorTable(OnePort):
    """Inductor with a tabulated flux curve: psi(i) piecewise linear through (0, 0) and the
    rows (i_k, psi_k), odd in i, the last slope continued; v = L_k di/dt + R i.

    Parameters
    ----------
    points : list of {i [A], psi [Wb]} for i > 0, the currents increasing from row to row
    R : [ohm] series (winding) resistance
    i0 : [A] initial current
    """

    branches = (Branch("p", "n", "L"),)
    points = RecordList("flux curve: rows {i, psi} for i > 0, increasing", ROW, min_rows=1)
    R = Param("ohm", "series resistance", default=0.0, nonnegative=True)
    i0 = Param("A", "initial current", default=0.0)

    def equations(self, x):
        x.discrete("i_lo")
        x.discrete("i_hi")
        ld = x.discrete("L_d")  # the slope of the segment holding |i|
        return [x.v - ld * x.der(x.i) - self.R * x.i]

    def initial(self, x):
        # at rest in the first segment (the events move it wherever i0 lies)
        first = self.points[0]
        return {x.i: self.i0, x.i_hi: first["i"], x.L_d: first["psi"] / first["i"]}

    def events(self, x):
        rows, u = self.points, sp.Abs(x.i)
        slopes = _slopes(rows)
        currents = [r["i"] for r in rows]
        # |i| rises past the segment's top: the segment above it (the last slope continues
        # for ever); falls below its bottom: the segment below (none below 0). A relative
        # band of 1e-9 keeps a corner just crossed from switching straight back.
        up = Event(x.i_hi * (1 + BAND) - u, ((x.i_lo, x.i_hi),
                                (x.i_hi, _above(x.i_hi, rows, [*currents, sp.Float(BEYOND)])),
                                (x.L_d, _above(x.i_hi, rows, slopes))))
        down = Event(sp.Piecewise((1, x.i_lo <= 0), (u - x.i_lo * (1 - BAND), True)),
                     ((x.i_hi, x.i_lo), (x.i_lo, _below(x.i_lo, rows, currents, 0)),
                      (x.L_d, _below(x.i_lo, rows, [*slopes[1:], slopes[-1]], slopes[0]))))
        return [up, down]
