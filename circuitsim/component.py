"""The component interface: ports, parameters with units and validity, a registry.

A component is a small class stating its ports, its parameters and a few sympy residuals.
It never sees the solver: the core gathers ``equations(x)`` through this interface and knows
no component by type.

Sign convention (as Modelica): a flow (current, torque, force) is positive *into* a port.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar

from circuitsim.lazy import LazyModule

if TYPE_CHECKING:
    import sympy as sp
else:
    # Components write equations with ``sp``; taken from here, sympy loads only when one is
    # first built, so a run served from the model cache never imports it (0.2-0.3 s).
    sp = LazyModule("sympy")


@dataclass(frozen=True, slots=True)
class Domain:
    """A physical domain: the across and through variables of its nodes.

    ``integral`` names the time integral of the across variable (angle of a shaft, position
    of a flange); the core creates it on a node only when a component asks for it.
    """

    name: str
    across: str
    through: str
    across_unit: str
    through_unit: str
    integral: str | None
    integral_unit: str | None
    references: tuple[str, ...]
    through_is_power: bool = False  # heat flow is itself a power; T * Q is not one

    def port_power(self, across: Any, through: Any) -> Any:
        """Power [W] entering a port of this domain."""
        return through if self.through_is_power else across * through


ELECTRICAL = Domain("electrical", "v", "i", "V", "A", None, None, ("gnd", "0"))
ROTATIONAL = Domain("rotational", "w", "tau", "rad/s", "N*m", "phi", "rad", ("fixed",))
TRANSLATIONAL = Domain("translational", "v", "f", "m/s", "N", "x", "m", ("fixed",))
# Temperatures are absolute [K]; the reference is 0 K (a heat capacity, a fixed temperature
# or a heat source acts against it, as a capacitor acts against ground).
THERMAL = Domain("thermal", "T", "Q", "K", "W", None, None, ("absolute_zero",), True)
DOMAINS = {d.name: d for d in (ELECTRICAL, ROTATIONAL, TRANSLATIONAL, THERMAL)}


@dataclass(frozen=True, slots=True)
class Port:
    """A named connection point in one domain."""

    name: str
    domain: Domain


def Pin(name: str) -> Port:
    return Port(name, ELECTRICAL)


def Flange(name: str) -> Port:
    return Port(name, ROTATIONAL)


def TFlange(name: str) -> Port:
    return Port(name, TRANSLATIONAL)


def HeatPort(name: str) -> Port:
    return Port(name, THERMAL)


@dataclass(frozen=True, slots=True)
class Param:
    """A numeric parameter: unit, meaning and validity. Its value is a run-time number.

    ``default`` may be a number (SI) or the name of another parameter of the same component.
    """

    unit: str
    doc: str
    default: float | str | None = None
    positive: bool = False
    nonnegative: bool = False
    integer: bool = False
    maximum: float | None = None
    nonzero: bool = False  # a ratio of 0 locks what it couples, instead of coupling it

    def violation(self, value: float) -> str | None:
        """Why ``value`` [SI] is invalid, or None."""
        if not math.isfinite(value):
            return "must be a finite number"
        if self.maximum is not None and value > self.maximum:
            return f"must not exceed {self.maximum:g}"
        if self.positive and value <= 0:
            return "must be positive"
        if self.nonnegative and value < 0:
            return "must not be negative"
        if self.nonzero and value == 0:
            return "must not be zero"
        if self.integer and float(value) != int(value):
            return "must be a whole number"
        return None


@dataclass(frozen=True, slots=True)
class Option:
    """A structural choice (changes the equations): a bool or one of some strings."""

    doc: str
    default: Any
    choices: tuple[Any, ...] = (True, False)


@dataclass(frozen=True, slots=True)
class RecordList:
    """A list of records, each with the numeric fields given (e.g. harmonics); ``min_rows``
    is the fewest the component can work with (a table needs one row)."""

    doc: str
    fields: Mapping[str, Param]
    min_rows: int = 0


@dataclass(frozen=True, slots=True)
class Signal:
    """A parameter that is a function of time: a constant or a waveform (see WAVEFORMS)."""

    unit: str
    doc: str
    default: float | None = None


@dataclass(frozen=True, slots=True)
class Expression:
    """A behavioural expression (like SPICE's B-source) of time ``t``, netlist parameters and
    circuit quantities named as probes are (``x.v``, ``M.i``, ``rotor.phi``). Numbers are SI."""

    unit: str
    doc: str


@dataclass(frozen=True, slots=True)
class Branch:
    """A conductive path between two ports (``None`` is the domain's reference) and its kind.

    Kinds, for the structural checks of the graph: ``V`` independent across source, ``I``
    independent through source, ``C`` stores across (capacitor, inertia), ``L`` stores
    through (inductor), ``R`` dissipative, ``X`` anything else (controlled, nonlinear).
    """

    a: str
    b: str | None
    kind: str


class Component:
    """Base class. Subclasses declare ``ports`` and Param/Option/RecordList/Signal attributes.

    Inside ``equations`` a parameter attribute reads as its sympy symbol, an Option as its
    value, a RecordList as a list of dicts of symbols and a Signal as a sympy function of t.
    """

    ports: ClassVar[tuple[Port, ...]] = ()
    branches: ClassVar[tuple[Branch, ...]] = ()

    def __init__(self, name: str, values: Mapping[str, Any]):
        self.name = name
        self._values = dict(values)

    def __getattribute__(self, attr: str) -> Any:
        cls_attr = type(self).__dict__.get(attr) or _inherited(type(self), attr)
        if isinstance(cls_attr, (Param, Option, RecordList, Signal, Expression)):
            return object.__getattribute__(self, "_values")[attr]
        return object.__getattribute__(self, attr)

    @classmethod
    def declared(cls) -> dict[str, Param | Option | RecordList | Signal | Expression]:
        """All parameter-like declarations of the class, in declaration order."""
        out: dict[str, Any] = {}
        for klass in reversed(cls.__mro__):
            for k, v in vars(klass).items():
                if isinstance(v, (Param, Option, RecordList, Signal, Expression)):
                    out[k] = v
        return out

    def bind(self, x: Scope) -> list[sp.Expr]:
        """Define shorthand variables on the scope; return the equations that go with them."""
        return []

    def equations(self, x: Scope) -> list[sp.Expr]:
        """Residuals that must equal zero."""
        raise NotImplementedError

    def initial(self, x: Scope) -> dict[sp.Symbol, sp.Expr]:
        """Initial values of variables (default: start from rest)."""
        return {}

    def energy(self, x: Scope) -> sp.Expr | None:
        """Energy stored in the component [J] (None if it stores none)."""
        return None

    def warnings(self, values: Mapping[str, float]) -> list[str]:
        """Physics warnings for these numeric parameter values [SI]."""
        return []

    def events(self, x: Scope) -> list[Event]:
        """Discrete changes found by the integrator's root finding (default: none)."""
        return []


@dataclass(frozen=True)
class Event:
    """A discrete change: when ``guard`` falls through zero, each discrete state named in
    ``sets`` takes its new value (expressions evaluated just before the change, so they may
    read the old states and t); the integrator then restarts with consistent values.

    A guard is written for the current mode and stays positive while the mode holds: a
    switch with hysteresis h closes on ``Vt + h - vc`` and opens on ``vc - Vt + h``. After a
    change the new guard must start positive (hysteresis, or the opposite of the old one),
    or the element would switch back at once.
    """

    guard: Any
    sets: tuple[tuple[Any, Any], ...]


def _inherited(cls: type, attr: str) -> Any:
    for klass in cls.__mro__[1:]:
        if attr in klass.__dict__:
            return klass.__dict__[attr]
    return None


class PortScope:
    """Symbols of one port: across/through and, on demand, the integral (angle, position)."""

    def __init__(self, domain: Domain, across: sp.Expr, through: sp.Symbol,
                 integral: Callable[[], sp.Expr]):
        self._domain = domain
        self._across = across
        self._through = through
        self._integral = integral

    def __getattr__(self, name: str) -> sp.Expr:
        d = self._domain
        if name == d.across:
            return self._across
        if name == d.through:
            return self._through
        if d.integral is not None and name == d.integral:
            return self._integral()
        raise AttributeError(f"a {d.name} port has no '{name}'")


class Scope:
    """Per-instance symbol scope handed to ``Component.equations``.

    ``x.p.v``/``x.p.i`` (pins), ``x.shaft.w``/``x.shaft.tau``/``x.shaft.phi`` (rotational),
    ``x.flange.v``/``x.flange.f``/``x.flange.x`` (translational), ``x.var(name)`` an internal
    unknown, ``x.der(expr)`` a time derivative, ``x.t`` time. Assigning ``x.v = ...`` exports a
    named quantity that probes can read as ``NAME.v``.
    """

    def __init__(self, comp: str, ports: Mapping[str, Any], make_var: Callable[[str], sp.Symbol],
                 der: Callable[[sp.Expr], sp.Expr], t: sp.Symbol):
        object.__setattr__(self, "_comp", comp)
        object.__setattr__(self, "_ports", dict(ports))
        object.__setattr__(self, "_make_var", make_var)
        object.__setattr__(self, "_exports", {})
        object.__setattr__(self, "_discrete", [])
        object.__setattr__(self, "der", der)
        object.__setattr__(self, "t", t)

    def var(self, name: str) -> sp.Symbol:
        sym = self._make_var(name)
        self._exports.setdefault(name, sym)
        return sym

    def discrete(self, name: str) -> sp.Symbol:
        """A discrete state: constant between events (its derivative is zero), changed only
        by an Event. It is an unknown like any other, so probes read it at every output."""
        sym = self.var(name)
        self._discrete.append(sym)
        return sym

    def __getattr__(self, name: str) -> Any:
        ports = object.__getattribute__(self, "_ports")
        if name in ports:
            return ports[name]
        exports = object.__getattribute__(self, "_exports")
        if name in exports:
            return exports[name]
        raise AttributeError(f"{self._comp} has no port or variable '{name}'")

    def __setattr__(self, name: str, value: Any) -> None:
        self._exports[name] = value


@dataclass
class Registry:
    """Explicit registries filled by decorators: components and waveforms."""

    components: dict[str, type[Component]] = field(default_factory=dict)
    waveforms: dict[str, type] = field(default_factory=dict)


REGISTRY = Registry()
COMPONENTS = REGISTRY.components
WAVEFORMS = REGISTRY.waveforms


def register(*names: str) -> Callable[[type[Component]], type[Component]]:
    """Class decorator: make a component available under ``type:`` names in netlists."""

    def deco(cls: type[Component]) -> type[Component]:
        for n in names:
            if n in COMPONENTS and COMPONENTS[n] is not cls:
                raise ValueError(f"component type '{n}' registered twice")
            COMPONENTS[n] = cls
        cls.type_names = names  # type: ignore[attr-defined]
        return cls

    return deco


def register_waveform(name: str) -> Callable[[type], type]:
    def deco(cls: type) -> type:
        WAVEFORMS[name] = cls
        cls.kind = name  # type: ignore[attr-defined]
        return cls

    return deco


class Waveform:
    """A signal of time with numeric parameters. ``expr(t, p)`` gets a dict of symbols."""

    params: ClassVar[dict[str, Param]] = {}
    scalar_key: ClassVar[str | None] = None

    def expr(self, t: sp.Symbol, p: Mapping[str, sp.Expr], data: Any = None) -> sp.Expr:
        raise NotImplementedError

    def breakpoints(self, p: Mapping[str, float], t_stop: float) -> list[float]:
        """Times [s] where the waveform has a corner (the integrator restarts there)."""
        return []

    def period(self, p: Mapping[str, float]) -> float:
        """Period [s] of a periodic waveform (0: not periodic); output sampled coarser than
        half of it aliases."""
        return 0.0

    def max_step(self, p: Mapping[str, float]) -> float:
        """Largest integrator step [s] the waveform allows (0: no bound). A smooth periodic
        source bounds it so IDA cannot step over what happens within one period."""
        return 0.0


class OnePort(Component):
    """Two pins p, n. v = p.v - n.v; i enters at p and leaves at n."""

    ports = (Pin("p"), Pin("n"))
    branches = (Branch("p", "n", "X"),)

    def bind(self, x: Scope) -> list[sp.Expr]:
        x.v = x.p.v - x.n.v
        x.i = x.p.i
        return [x.p.i + x.n.i]


class Converter(Component):
    """Electromechanical two-port: pins p, n and a shaft flange. v = p.v - n.v, i enters at p
    and leaves at n; w is the shaft speed and tau the torque into the converter's flange (the
    shaft receives -tau)."""

    ports = (Pin("p"), Pin("n"), Flange("shaft"))
    branches = (Branch("p", "n", "X"), Branch("shaft", None, "X"))

    def bind(self, x: Scope) -> list[sp.Expr]:
        x.v = x.p.v - x.n.v
        x.i = x.p.i
        x.w = x.shaft.w
        x.tau = x.shaft.tau
        return [x.p.i + x.n.i]


class OneFlange(Component):
    """One rotational flange acting against the fixed reference: w = shaft speed,
    tau = torque into the shaft flange."""

    ports = (Flange("shaft"),)
    branches = (Branch("shaft", None, "X"),)

    def bind(self, x: Scope) -> list[sp.Expr]:
        x.w = x.shaft.w
        x.tau = x.shaft.tau
        return []


class OneTFlange(Component):
    """One translational flange acting against the fixed reference: v = flange speed,
    f = force into the flange."""

    ports = (TFlange("flange"),)
    branches = (Branch("flange", None, "X"),)

    def bind(self, x: Scope) -> list[sp.Expr]:
        x.v = x.flange.v
        x.f = x.flange.f
        return []


def as_expr(x: Any) -> sp.Basic:
    """A sympy object from a sympy object or a Python number. Text is refused: a netlist is
    data and never reaches sympy's parser (which evaluates strings)."""
    if isinstance(x, sp.Basic):
        return x
    if isinstance(x, bool):
        return sp.Integer(int(x))
    if isinstance(x, int):
        return sp.Integer(x)
    if isinstance(x, float):
        return sp.Float(x)
    raise TypeError(f"expected a sympy expression or a number, got {type(x).__name__}")


def Pmod(x: Any, T: Any) -> sp.Expr:
    """Periodic time: x mod T in [0, T), as a sympy function (``symfunc.Pmod``)."""
    from circuitsim import symfunc

    return symfunc.Pmod(x, T)


def Lookup(k: Any, x: Any) -> sp.Expr:
    """Linear interpolation of the run-time table number ``k`` at ``x`` (``symfunc.Lookup``)."""
    from circuitsim import symfunc

    return symfunc.Lookup(k, x)


def LookupSlope(k: Any, x: Any) -> sp.Expr:
    """Slope of table ``k`` at ``x`` (``symfunc.LookupSlope``)."""
    from circuitsim import symfunc

    return symfunc.LookupSlope(k, x)


@dataclass(frozen=True)
class TableData:
    """A measured signal that drives a source: samples ``x`` [s] and values ``y`` [SI]."""

    x: Any
    y: Any
    label: str
    index: int = -1
