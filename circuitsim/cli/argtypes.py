"""Argparse ``type`` functions shared by the commands: a refusal raises
``argparse.ArgumentTypeError``, which argparse turns into 'error: argument --x: ...' and
exit 2 (bad input), never a traceback."""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable


def parse_quantity(text: str, unit: str) -> float:
    """A value typed on the command line, in SI: a number, a number with a unit (``10 ms``)
    or with a SPICE multiplier (``10m``, ``2k``), or a temperature alone in Celsius (``20
    degC``); the unit is checked against ``unit``.

    Raises ValueError saying what was wrong.
    """
    from circuitsim.netlist.load import typed_value
    from circuitsim.units import unit_info

    return typed_value(text, unit_info(unit)[1], unit)


def quantity(unit: str, minimum: float | None = 0.0, inclusive: bool = False
             ) -> Callable[[str], float]:
    """A finite value in ``unit`` above ``minimum`` (or at it when ``inclusive``)."""

    def parse(text: str) -> float:
        try:
            value = parse_quantity(text, unit)
        except ValueError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"'{text}' is not a finite value")
        if minimum is not None and (value < minimum or (value == minimum and not inclusive)):
            rel = ">=" if inclusive else ">"
            raise argparse.ArgumentTypeError(f"'{text}' must be {rel} {minimum:g} {unit}")
        return value

    parse.__name__ = f"value in {unit}"  # argparse names the type in its messages
    return parse


def whole(low: int, high: int | None = None, hint: str = "") -> Callable[[str], int]:
    """A whole number in [low, high] (no upper end when ``high`` is None); ``hint`` is added
    to the refusal of a number below ``low`` (what ``low`` means)."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"'{text}' is not a whole number") from None
        if high is None and value < low:
            raise argparse.ArgumentTypeError(f"'{text}' must be {low} or more{hint}")
        if high is not None and not low <= value <= high:
            raise argparse.ArgumentTypeError(f"'{text}' must lie in {low}..{high}")
        return value

    parse.__name__ = "whole number"
    return parse


def positive(text: str) -> float:
    """A finite number above 0."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number") from None
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"'{text}' must be a finite number > 0")
    return value


def fraction(text: str) -> float:
    """A number in (0, 1)."""
    value = positive(text)
    if value >= 1:
        raise argparse.ArgumentTypeError(f"'{text}' must be a fraction in (0, 1)")
    return value
