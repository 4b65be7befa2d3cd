"""Units: parse quantities with pint, check dimensions, convert to SI floats.

Angles are dimensionless in SI, so pint alone cannot tell ``rad/s`` from ``Hz``. A rotation
given in Hz is ambiguous by 2*pi, so we count the exponent of angle units on both sides and
refuse a mismatch.
"""

from __future__ import annotations

import contextlib
import functools
import math
import re
from dataclasses import dataclass

ANGLE_UNITS = frozenset({"radian", "degree", "revolution", "turn", "arcminute", "arcsecond",
                         "gradian", "revolutions_per_minute", "revolutions_per_second", "rev",
                         "rps"})
# Exponent of angle carried by composite angle units pint keeps as one name.
_ANGLE_EXP = {"revolutions_per_minute": 1, "revolutions_per_second": 1, "rps": 1}
_POWER = re.compile(r"\*\*|\^")
_NUM = r"[-+]?(?:\d{1,3}(?:\.\d{0,6})?|\.\d{1,6})"
# What may follow a power operator: a short number, or a parenthesised one or fraction; never
# another power, a longer number or a name glued to it.
_EXPONENT = re.compile(rf"\s*(?:{_NUM}|\(\s*{_NUM}\s*(?:/\s*{_NUM}\s*)?\))"
                       rf"(?![\w.(]|\s*(?:\*\*|\^))")


@functools.lru_cache(maxsize=1)
def registry():
    """The shared pint registry (created lazily: importing pint costs ~0.4 s)."""
    import pint

    try:
        ureg = pint.UnitRegistry(cache_folder=":auto:")
    except Exception:  # noqa: BLE001 - an unwritable cache folder must not stop a run
        ureg = pint.UnitRegistry()
    for line in ("rev = revolution", "rps = revolution / second"):
        # a pint version that already defines the name keeps its own definition
        if line.split()[0] in ureg:
            continue
        with contextlib.suppress(Exception):
            ureg.define(line)
    return ureg


@dataclass(frozen=True, slots=True)
class Dim:
    """Physical dimension: pint dimensionality plus the angle exponent pint drops."""

    dims: tuple[tuple[str, float], ...]
    angle: float

    def __str__(self) -> str:
        parts = [f"{k.strip('[]')}^{v:g}" for k, v in self.dims]
        if self.angle:
            parts.append(f"angle^{self.angle:g}")
        return "·".join(parts) or "dimensionless"


def angle_exponent(units) -> float:
    """Sum of exponents of angle units in a pint UnitsContainer."""
    total = 0.0
    for name, exp in units.items():
        if name in ANGLE_UNITS:
            total += exp * _ANGLE_EXP.get(name, 1)
    return total


@functools.lru_cache(maxsize=512)
def unit_info(unit: str) -> tuple[float, Dim]:
    """SI factor and dimension of a unit string such as ``"mH"`` or ``"V*s/rad"``.

    Raises ValueError when pint does not know the unit.
    """
    if unit.strip() in ("", "1"):
        return 1.0, Dim((), 0.0)
    known = _memo().get(unit)
    if not _well_formed(known):  # not there yet (or an entry edited by hand): ask pint
        try:
            factor, dim = _pint_info(unit)
            known = [factor, [list(kv) for kv in dim.dims], dim.angle]
        except ValueError as exc:
            if len(unit) > _MEMO_ERRORS_UP_TO:  # hostile text must not grow the table
                raise
            known = {"error": str(exc)}
        _memo().put(unit, known)
    if isinstance(known, list):
        factor, dims, angle = known
        return factor, Dim(tuple((k, v) for k, v in dims), angle)
    # pint refused it (the loader asks about SPICE suffixes such as 'k')
    raise ValueError(known["error"])


def _well_formed(known: object) -> bool:
    """A memo entry as ``unit_info`` writes it: [factor, [[dimension, exponent], ...], angle]
    or {"error": message}."""
    if isinstance(known, dict):
        return isinstance(known.get("error"), str)
    return (isinstance(known, list) and len(known) == 3 and isinstance(known[1], list)
            and all(isinstance(x, (int, float)) for x in (known[0], known[2]))
            and all(isinstance(kv, list) and len(kv) == 2 and isinstance(kv[0], str)
                    and isinstance(kv[1], (int, float)) for kv in known[1]))


# [characters] refusals of longer unit text are not remembered across runs
_MEMO_ERRORS_UP_TO = 24


def _pint_info(unit: str) -> tuple[float, Dim]:
    """``unit_info`` computed by pint."""
    ureg = registry()
    # pint evaluates exponents as Python ints: 'm^9^9^9' would compute 9**387420489.
    if not all(_EXPONENT.match(unit, m.end()) for m in _POWER.finditer(unit)):
        raise ValueError(f"unknown unit '{unit}': an exponent must be a plain number "
                         f"such as m^2, s^-1 or m^(1/2)")
    try:
        q = ureg.Quantity(1.0, ureg.parse_units(unit))
        factor, dim = _si_and_dim(q)
    except OverflowError as exc:
        raise ValueError(f"unit '{unit}' is out of range") from exc
    except Exception as exc:  # pint raises several unrelated types
        raise ValueError(f"unknown unit '{unit}'") from exc
    offset = _offset(ureg, unit)
    if offset:
        raise ValueError(
            f"'{unit}' is an offset unit (0 {unit} = {offset:g} K): a value in it would be "
            f"scaled by {factor:g}, not shifted. Write an absolute temperature alone "
            f"('20 degC' is 293.15 K) or in K; a temperature difference in K or delta_{unit}")
    if not (math.isfinite(factor) and factor != 0.0 and math.isfinite(dim.angle)
            and all(math.isfinite(v) for _, v in dim.dims)):
        raise ValueError(f"unit '{unit}' is out of range")
    return factor, dim


def _offset(ureg, unit: str) -> float:
    """Where 0 of ``unit`` lies in SI [K]: 273.15 for degC, 0 for any scaled unit."""
    try:
        return float(ureg.Quantity(0.0, ureg.parse_units(unit)).to_base_units().magnitude)
    except Exception:  # noqa: BLE001 - pint refuses offsets inside compound units: none here
        return 0.0


#: A temperature written alone in an offset unit: '20 degC', '68 degF', '-5 °C'
_ABSOLUTE = re.compile(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*"
                       r"(degC|degF|°C|°F|celsius|fahrenheit|degree_Celsius|degree_Fahrenheit)"
                       r"\s*")


def absolute_temperature(text: str) -> str | None:
    """``text`` in kelvin (``'293.15[K]'``) when it is a number in an offset unit alone, such
    as ``'20 degC'``; None for anything else (an offset unit elsewhere is refused by
    ``unit_info``: ``2 * 20 degC`` has no single meaning)."""
    m = _ABSOLUTE.fullmatch(text)
    if m is None:
        return None
    ureg = registry()
    kelvin = ureg.Quantity(float(m.group(1)), ureg.parse_units(m.group(2))).to("K").magnitude
    return f"{float(kelvin)!r}[K]"  # brackets: never read as a SPICE kilo


@functools.lru_cache(maxsize=1)
def _memo():
    """Units pint has converted before, kept across runs: importing pint and building its
    registry cost 0.2-0.3 s, more than a whole warm run should take. The table is named by
    this file and by the installed pint, so an upgrade or an edit here starts a new one."""
    import hashlib
    import importlib.util
    import os
    from pathlib import Path

    from circuitsim.memo import Memo

    h = hashlib.sha256(Path(__file__).read_bytes())
    spec = importlib.util.find_spec("pint")
    if spec is not None and spec.origin:
        st = os.stat(spec.origin)
        h.update(f"{spec.origin}|{st.st_size}|{st.st_mtime_ns}".encode())
    return Memo("units", h.hexdigest()[:16])


def _si_and_dim(q) -> tuple[float, Dim]:
    ang = angle_exponent(q._units)
    base = q.to_base_units()
    dims = tuple(sorted((str(k), float(v)) for k, v in base.dimensionality.items()))
    return float(base.magnitude), Dim(dims, ang)


def dimensionless() -> Dim:
    return Dim((), 0.0)


def dim_mul(a: Dim, b: Dim, power: float = 1.0) -> Dim:
    """Dimension of a * b**power."""
    acc: dict[str, float] = dict(a.dims)
    for k, v in b.dims:
        acc[k] = acc.get(k, 0.0) + power * v
    dims = tuple(sorted((k, v) for k, v in acc.items() if abs(v) > 1e-12))
    return Dim(dims, a.angle + power * b.angle)


def dim_pow(a: Dim, power: float) -> Dim:
    return Dim(tuple((k, v * power) for k, v in a.dims), a.angle * power)


def compatible(value: Dim, target: Dim) -> bool:
    """True when a value of dimension ``value`` may be used where ``target`` is declared."""
    return value.dims == target.dims and abs(value.angle - target.angle) < 1e-12


def explain_mismatch(value: Dim, target: Dim, target_unit: str) -> str:
    """Say why two dimensions do not match, in words a user can act on."""
    if value.dims == target.dims:
        if target.angle and not value.angle:
            return (f"a rotation must carry an angle unit (rad/s, rpm or rev/s), never Hz: "
                    f"Hz is ambiguous by 2*pi; write it in {target_unit}")
        if value.angle and not target.angle:
            return (f"this quantity is not per angle: give it in {target_unit} "
                    f"(a frequency in Hz, not rad/s)")
        return f"the angle units do not match {target_unit}"
    return (f"has dimension {describe(value)}, expected {describe(target)} (a value in "
            f"{target_unit})")


class UnitMismatch(ValueError):
    """A known unit of the wrong dimension (the message says why, in words to act on)."""


def column_factor(unit: str, want: str | None) -> float:
    """The SI factor of a data column's unit (a CSV header's 'name [unit]'), checked against
    ``want`` (None, '', '1' or '@': unchecked; a unit pint does not know: unchecked too).
    ValueError for a unit it cannot read, UnitMismatch for one of the wrong dimension."""
    factor, dim = unit_info(unit)
    if want and want not in ("1", "@"):
        try:
            target = unit_info(want)[1]
        except ValueError:  # nothing to check against
            return factor
        if not compatible(dim, target):
            raise UnitMismatch(explain_mismatch(dim, target, want))
    return factor


# SPICE multipliers, case-insensitive as in SPICE. 'mil' is a thousandth of an inch.
SPICE_SCALE = {"f": 1e-15, "p": 1e-12, "n": 1e-9, "u": 1e-6, "µ": 1e-6, "μ": 1e-6, "m": 1e-3,
               "k": 1e3, "meg": 1e6, "g": 1e9, "t": 1e12, "mil": 25.4e-6}
# Letters that are also an SI unit symbol a netlist may mean: with no expected unit to decide,
# they keep the SI meaning (a wrong guess then fails the dimension check loudly, while a bare
# SPICE number would be taken silently in any unit).
_SI_SYMBOLS = frozenset({"m", "g", "F", "T", "N", "K"})
_SPICE_NUMBER = re.compile(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([A-Za-zµμ]+)\s*")


def spice_value(text: str, target: Dim | None = None) -> str | None:
    """A number followed by a SPICE multiplier alone (``10k``, ``2.2u``, ``1 meg``) as plain
    number text (``'10000.0'``), or None when ``text`` is anything else.

    The femto trap, decided: letters that are also a unit of the expected dimension ``target``
    are that unit, so ``1F`` on a capacitor is one farad (write ``1f`` or ``1 fF`` for femto),
    ``3m`` on a length three metres, ``5g`` on a mass five grams. With no expected dimension
    (a netlist parameter), ``m g F T N K`` keep their SI meaning (``293.15 K`` is kelvin;
    write ``10k`` for kilo there). ``1M`` is refused (ValueError):
    milli in SPICE, mega to most readers; write ``1m`` or ``1meg``.
    """
    match = _SPICE_NUMBER.fullmatch(text)
    if match is None:
        return None
    number, suffix = match.groups()
    scale = SPICE_SCALE.get(suffix.lower())
    if scale is None:
        return None
    if suffix == "M":
        raise ValueError(f"'{text.strip()}' is ambiguous: M is milli in SPICE and mega to most "
                         f"readers; write '{number}m' (milli) or '{number}meg' (mega)")
    try:
        _, dim = unit_info(suffix)
    except ValueError:
        dim = None
    if dim is not None and (compatible(dim, target) if target is not None
                            else suffix in _SI_SYMBOLS):
        return None  # the SI unit it also names
    return repr(float(number) * scale)


# Names for the dimensions a user meets, so a message says 'ohm', not 'current^-2·length^2·...'
_NAMED_UNITS = ("V", "A", "ohm", "S", "F", "H", "W", "J", "C", "Wb", "T", "s", "Hz", "m", "kg",
                "N", "N*m", "N*m*s/rad", "kg*m^2", "rad", "rad/s", "V*s/rad", "m/s", "K")


@functools.lru_cache(maxsize=1)
def _dim_names() -> dict[Dim, str]:
    out: dict[Dim, str] = {}
    for unit in _NAMED_UNITS:
        out.setdefault(unit_info(unit)[1], unit)
    return out


def unit_name(dim: Dim) -> str:
    """A dimension's common unit (``ohm``), else its base dimensions."""
    return _dim_names().get(dim) or str(dim)


def describe(dim: Dim) -> str:
    """A dimension in words: its unit's name when it has a common one (``ohm``), else the base
    dimensions."""
    name = _dim_names().get(dim)
    return f"{name} ({dim})" if name else str(dim)
