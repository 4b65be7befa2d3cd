"""The effect catalog: physical effects a model may lack, each a patch to the netlist.

An effect proposes candidates (effect x target x, for harmonic effects, an order). A
candidate adds new netlist parameters (its free parameters, starting at their *null* values,
where the patched circuit behaves exactly as the original) and components; applying it to a
raw netlist gives a new topology that is compiled (and cached) once. The patched netlist is
an output a user can read, keep and run. Catalog ids are part of the interface.

Series effects are behavioural voltage sources in series with the target (``v = expr``), so
that their null value is an exact zero and their parameters may take either sign.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from circuitsim.errors import SourceLoc
from circuitsim.netlist.load import Netlist, RawNetlist

CATALOG_IDS = ("series-resistance", "source-resistance", "brush-drop", "brush-transition",
               "coulomb-friction",
               "stribeck-friction", "viscous-friction", "cogging", "unbalance", "emf-harmonic",
               "inductor-saturation", "resistance-drift", "force-offset", "sensor-gain",
               "sensor-offset", "sensor-delay", "backlash", "inertia", "inductance")


@dataclass(frozen=True)
class Law:
    """Where and how an effect acts, for the test of its law (``loop/diagnose/law.py``).

    place : ("series", component) -- a voltage in series with it; ("torque", node) or
        ("force", node) -- applied to a body; ("coupling", component) -- a torque between
        a torsional coupling's two flanges, beside its own; ("probe", probe) -- the sensor's
        reading.
    value : the expression of what the effect adds there [V, N*m, N], in its own
        parameters and circuit quantities (for a probe: "gain", "offset" or "delay").
    terms : (driver expression, shape) pairs: the law is tested for a dependence on each
        driver it does not have (shape "abs": on |u|, "square": on u^2, "centred": on u
        about its mean, "cos" and "sin": of an angle u, once per turn, "sign": on u's
        direction). Empty for a probe: a sensor's law is bent on its reading, by shapes
        its kind fixes (``law``).
    companion : (place, value) of a second action the effect's physics could carry and the
        catalog's law leaves out, tried with a coefficient of null 0 beside the shapes: an
        EMF harmonic's torque (a motor constant that varies with the angle, as an eccentric
        rotor's does, acts on the torque as on the EMF; the catalog's harmonic is a voltage
        alone, as a winding's or a sensor's ripple is). None: no such action.
    """

    place: tuple[str, str]
    value: str
    terms: tuple[tuple[str, str], ...]
    companion: tuple[tuple[str, str], str] | None = None


@dataclass(frozen=True)
class Candidate:
    """One proposed patch. ``free``: new parameter -> (start value, lower, upper) [SI]."""

    effect: str
    target: str
    free: Mapping[str, tuple[float, float, float]]
    fixed: Mapping[str, float]
    what: str
    edit: Callable[[RawNetlist], None] = field(repr=False, compare=False)
    # a parameter step that moves the outputs measurably but stays linear [SI]; and whether
    # the effect is invisible to a linearisation at its null value (then it is screened on a
    # grid of ``grid`` values of its first parameter instead)
    steps: Mapping[str, float] = field(default_factory=dict)
    grid: tuple[float, ...] = ()
    # with a ``grid``: whether its slope at null is screened as well (the better of the two
    # is kept), for an effect the slope sees when small and misjudges when large
    slope: bool = False
    # free parameters that shape the effect (a speed, a time constant) rather than size it:
    # invisible while the size is at its null, so the screen keeps them at their start (one
    # candidate per start) and only the refit moves them
    shape: tuple[str, ...] = ()
    # it re-tunes a value the netlist declares (an inertia) rather than adding physics: an
    # accepted one is reported as a correction of that value, never as a new cause
    retunes: bool = False
    # a physical limit that ties parameters together (a box of bounds cannot hold it): given
    # the fitted values, why they lie beyond it, or "" when they do not
    limit: Callable[[Mapping[str, float]], str] | None = field(default=None, repr=False,
                                                                compare=False)
    # where and how it acts, for the test of its law over the record's operating range
    law: Law | None = field(default=None, repr=False, compare=False)
    # the effect of a correction on the same target this one contains as a special case
    # (a saturation whose top is free is also a constant inductance factor): screened after
    # that correction, it is screened with the correction free to move back
    generalises: str = ""

    @property
    def key(self) -> str:
        order = self.fixed.get("order")
        tail = "".join(f":{n.rsplit('_', 1)[-1]}={self.free[n][0]:.3g}" for n in self.shape)
        return f"{self.effect}:{self.target}" + (f":{order:g}" if order is not None else "") \
            + tail

    @property
    def kind(self) -> tuple[str, str, float | None]:
        """(effect, target, order): candidates that differ only in a shape's start are one
        effect, accepted at most once."""
        return self.effect, self.target, self.fixed.get("order")

    def apply(self, raw: RawNetlist) -> RawNetlist:
        """A patched copy of ``raw`` (the free parameters at their start values)."""
        out = raw.copy()
        loc = SourceLoc(raw.path or "<patch>")
        for name, (start, _, _) in self.free.items():
            out.params[name] = (repr(float(start)), loc)
        self.edit(out)
        return out


BRUSH_EPS = 1e-3  # [A]
#: [rad/s] starts of the Stribeck speed below which the breakaway peak acts: a decade and a
#: half each side of 1 rad/s, in steps of about 3 (the refit moves it from the nearest)
STRIBECK_SPEEDS = (0.1, 0.3, 1.0, 3.0, 10.0)
#: [rad/s] the sign of the speed is smoothed as the catalog's Coulomb friction smooths it
STRIBECK_SIGN = 0.01
#: starts of a warm-up's time constant, as fractions of the record's duration: a drift that
#: settles within the record is told from a straight line only when tau is below ~its length
WARMUP_TAUS = (0.1, 0.3, 1.0)
#: A resistance drifts because its winding warms or cools; copper bounds how far and how fast.
ALPHA_CU = 3.93e-3  # [1/K] copper's temperature coefficient at 20 degC
#: [K] the widest swing of a winding's temperature: a cold start at -20 degC to the 180 degC
#: of insulation class H
WINDING_SWING = 200.0
RHO_CU = 1.68e-8  # [ohm m] copper's resistivity at 20 degC
CV_CU = 3.45e6  # [J/(m^3 K)] copper's heat capacity per volume (385 J/(kg K) x 8960 kg/m^3)
#: [A/m^2] a current density no winding carries even briefly: about four times the highest
#: short-time ratings (30-40 A/mm^2), a tenth of what fuses copper within milliseconds
J_WINDING_MAX = 150e6
#: [1/s] the fastest relative change of a winding's resistance: copper heating with no
#: cooling at all at J_WINDING_MAX (rho J^2 / c_v = 110 K/s) times its coefficient: 43 %/s
DRIFT_RATE_MAX = ALPHA_CU * RHO_CU * J_WINDING_MAX ** 2 / CV_CU
#: the range of a drift's relative change: the winding's widest swing either way
DRIFT_RISE = (1.0 / (1.0 + ALPHA_CU * WINDING_SWING) - 1.0, ALPHA_CU * WINDING_SWING)


def _pname(effect: str, target: str, what: str) -> str:
    return f"{effect.replace('-', '_')}_{target.replace('.', '_')}_{what}"


def insert_series(raw: RawNetlist, target: str, name: str, expr: str) -> None:
    """Put a behavioural voltage source between the target's pin n and its old node."""
    entry = raw.component_entry(target)
    node = str(entry["n"])
    mid = f"{name}_n"
    entry["n"] = mid
    loc = SourceLoc(raw.path or "<patch>")
    raw.comps.append(({"name": name, "type": "BV", "p": mid, "n": node, "expr": expr}, loc,
                      raw.path))
    raw.patch_parts.add(name)


def add_part(raw: RawNetlist, entry: dict) -> None:
    """Add a component (a patch's part) to ``raw``."""
    raw.comps.append((entry, SourceLoc(raw.path or "<patch>"), raw.path))
    raw.patch_parts.add(str(entry["name"]))


def _declared(net: Netlist) -> list:
    """The netlist's components, without those a patch added."""
    added = net.raw.patch_parts if net.raw is not None else set()
    return [c for c in net.components if c.name not in added]


def _electrical_two_pins(net: Netlist, kinds: set[str] | None = None,
                         exclude: set[str] = frozenset()) -> list[str]:
    out = []
    for c in _declared(net):
        ports = {p.name: p.domain.name for p in c.cls.ports}
        if ports.get("p") != "electrical" or ports.get("n") != "electrical":
            continue
        bk = {b.kind for b in c.cls.branches if {b.a, b.b} == {"p", "n"}}
        if kinds is not None and not (bk & kinds):
            continue
        if bk & exclude:
            continue
        out.append(c.name)
    return out


def _converters(net: Netlist) -> list[tuple[str, str]]:
    """(component, shaft node) of electromechanical converters (pins p, n and a shaft)."""
    out = []
    for c in _declared(net):
        ports = {p.name: p.domain.name for p in c.cls.ports}
        if ports.get("p") == "electrical" and "rotational" in ports.values():
            shaft = next(n for (pn, n) in c.ports if ports[pn] == "rotational")
            out.append((c.name, shaft))
    return out


def _mechanical_nodes(net: Netlist) -> list[tuple[str, str]]:
    return [(n, d) for n, (d, _) in net.nodes.items()
            if d in ("rotational", "translational") and n != "fixed"]


def candidates(net: Netlist, orders: Mapping[str, list[int]] | None = None,
               probes: Sequence[str] | Mapping[str, str] = (),
               duration: float | None = None) -> list[Candidate]:
    """Every candidate of the catalog for this netlist. ``orders``: harmonic orders per shaft
    node found in the residual (for ``cogging`` and ``emf-harmonic``); ``probes``: the
    measured probes (for the sensor effects), or a mapping from each to its unit (a sensor
    delay is built from a voltage, so it needs the probe's unit); ``duration``: the record's
    length [s] (a warm-up's time constant starts from it; without it, no warm-up)."""
    orders = orders or {}
    return [*_electrical(net), *_converter_effects(net, orders), *_mechanical(net, orders),
            *_component_laws(net, duration), *_couplings(net), *_sensors(probes)]


def _electrical(net: Netlist) -> list[Candidate]:
    out: list[Candidate] = []
    for t in _electrical_two_pins(net, exclude={"V", "I"}):
        p = _pname("series-resistance", t, "R")
        v = f"{p}*{t}.i"
        out.append(Candidate("series-resistance", t, {p: (0.0, 0.0, 1e3)}, {},
                             f"a resistance R in series with {t}",
                             lambda r, t=t, v=v: insert_series(r, t, f"SR_{t}", v),
                             steps={p: 1e-3}, law=_current_law(t, v)))
    for t in _electrical_two_pins(net, kinds={"V"}):
        p = _pname("source-resistance", t, "R")
        v = f"{p}*{t}.i"
        out.append(Candidate("source-resistance", t, {p: (0.0, 0.0, 1e3)}, {},
                             f"an internal resistance R of source {t}",
                             lambda r, t=t, v=v: insert_series(r, t, f"RS_{t}", v),
                             steps={p: 1e-3}, law=_current_law(t, v)))
    return out


def _converter_effects(net: Netlist, orders: Mapping[str, list[int]]) -> list[Candidate]:
    out: list[Candidate] = []
    for t, shaft in _converters(net):
        p = _pname("brush-drop", t, "Vb")
        # the sign of the current, smoothed over 1 mA: sharp against a small motor's no-load
        # current (tens of mA), smooth enough to integrate through a reversal
        v = f"{p}*tanh({t}.i/{BRUSH_EPS!r})"
        out.append(Candidate("brush-drop", t, {p: (0.0, 0.0, 50.0)}, {"i_eps": BRUSH_EPS},
                             f"a brush contact drop Vb*sign(i) in series with {t}",
                             lambda r, t=t, v=v: insert_series(r, t, f"BD_{t}", v),
                             steps={p: 1e-2}, law=_drop_law(t, v)))
        if net.raw is not None and f"BD_{t}" in net.raw.patch_parts:
            out.append(_brush_transition(t, p))
        for k in orders.get(shaft, []):
            a = _pname("emf-harmonic", f"{t}_{k}", "a")
            b = _pname("emf-harmonic", f"{t}_{k}", "b")
            v = f"{shaft}.w*({a}*sin({k}*{shaft}.phi) + {b}*cos({k}*{shaft}.phi))"
            out.append(Candidate(
                "emf-harmonic", t, {a: (0.0, -10.0, 10.0), b: (0.0, -10.0, 10.0)},
                {"order": k}, f"an extra back-EMF harmonic of order {k} in {t}",
                lambda r, t=t, k=k, v=v: insert_series(r, t, f"EH{k}_{t}", v),
                steps={a: 1e-4, b: 1e-4},
                law=Law(("series", t), v, ((f"{t}.i", "abs"), (f"{shaft}.w", "abs")),
                        (("torque", shaft),
                         f"({a}*sin({k}*{shaft}.phi) + {b}*cos({k}*{shaft}.phi))*{t}.i"))))
    return out


#: [A] the widest current over which a brush contact's drop builds up: beyond it the
#: contact is a resistance (the catalog's series resistance), not a drop
BRUSH_EPS_MAX = 1.0


def _brush_transition(t: str, vb: str) -> Candidate:
    """The width of a brush drop's transition through zero current, a refinement of an
    accepted drop: Vb tanh(i/eps) with eps free (null: the drop's own 1 mA). A real contact
    builds its drop over milliamperes to a fraction of an ampere; with the width fixed at
    1 mA a softer contact leaves a residual wherever the current crosses zero slowly."""
    e = _pname("brush-transition", t, "eps")
    law = f"{vb}*tanh({t}.i/{e})"
    return Candidate("brush-transition", t, {e: (BRUSH_EPS, 1e-5, BRUSH_EPS_MAX)}, {},
                     f"the width eps of the brush drop's transition through zero current in "
                     f"{t}: Vb tanh(i/eps)",
                     lambda r, t=t, law=law: _set_expr(r, f"BD_{t}", law),
                     steps={e: 0.1 * BRUSH_EPS}, law=_drop_law(t, law))


def _set_expr(raw: RawNetlist, name: str, expr: str) -> None:
    """Rewrite the law of a behavioural component a patch added."""
    raw.component_entry(name)["expr"] = expr


def _mechanical(net: Netlist, orders: Mapping[str, list[int]]) -> list[Candidate]:
    out: list[Candidate] = []
    for node, dom in _mechanical_nodes(net):
        rot = dom == "rotational"
        unit_f = "torque" if rot else "force"
        p = _pname("coulomb-friction", node, "c")
        out.append(Candidate(
            "coulomb-friction", node, {p: (0.0, 0.0, 1e4)}, {},
            f"Coulomb friction (or a constant load {unit_f}) on {node}",
            lambda r, n=node, p=p, rot=rot: add_part(r, {
                "name": f"CF_{n}", "type": "friction" if rot else "tfriction",
                ("shaft" if rot else "flange"): n, ("tau_c" if rot else "f_c"): p,
                ("w_brk" if rot else "v_brk"): 0.1 if rot else 1e-3}),
            steps={p: 1e-4 if rot else 1e-1},
            law=_speed_law(node, rot, f"-{p}*tanh({_speed(node, rot)}/"
                                      f"{0.01 if rot else 1e-4!r})", turn=True)))
        p = _pname("viscous-friction", node, "b")
        out.append(Candidate(
            "viscous-friction", node, {p: (0.0, 0.0, 1e6)}, {}, f"viscous friction on {node}",
            lambda r, n=node, p=p, rot=rot: add_part(r, {
                "name": f"VF_{n}", "type": "damper" if rot else "tdamper",
                ("shaft" if rot else "flange"): n, ("b" if rot else "d"): p}),
            steps={p: 1e-6 if rot else 1.0},
            law=_speed_law(node, rot, f"-{p}*{_speed(node, rot)}", turn=True)))
        p = _pname("force-offset", node, "F")
        out.append(Candidate(
            "force-offset", node, {p: (0.0, -1e4, 1e4)}, {},
            f"a constant {unit_f} offset on {node}",
            lambda r, n=node, p=p, rot=rot: add_part(r, {
                "name": f"FO_{n}", "type": "torque" if rot else "force",
                ("shaft" if rot else "flange"): n, ("T" if rot else "F"): p}),
            steps={p: 1e-4 if rot else 1e-1},
            law=Law(("torque" if rot else "force", node), p,
                    ((f"{node}.phi" if rot else f"{node}.x", "centred"),
                     (_speed(node, rot), "abs")))))
        if rot:
            out.extend(_stribeck(node))
            for k in orders.get(node, []):
                a = _pname("cogging", f"{node}_{k}", "a")
                b = _pname("cogging", f"{node}_{k}", "b")
                out.append(Candidate(
                    "unbalance" if k == 1 else "cogging", node,
                    {a: (0.0, -1e3, 1e3), b: (0.0, -1e3, 1e3)}, {"order": k},
                    f"an unbalance torque (once per revolution) on {node}" if k == 1 else
                    f"a torque locked to the angle of {node} (cogging or load ripple) of "
                    f"order {k}",
                    lambda r, n=node, k=k, a=a, b=b: add_part(r, {
                        "name": f"CG{k}_{n}", "type": "cogging", "shaft": n,
                        "harmonics": [{"order": k, "amplitude": a, "phase": 0},
                                      {"order": k, "amplitude": b, "phase": 1.5707963267948966}]
                    }), steps={a: 1e-4, b: 1e-4},
                    # one weight's moment has the same amplitude at every angle: an
                    # unbalance is bent by the angle too (a wind on a raised boom, -10 +
                    # 10 cos 2 angle over its quarter turn, is no weight)
                    law=_speed_law(node, True, f"{a}*sin({k}*{node}.phi) + "
                                               f"{b}*cos({k}*{node}.phi)", turn=k == 1)))
    return out


def _speed(node: str, rot: bool) -> str:
    """The speed of a body: a shaft's [rad/s] or a flange's [m/s]."""
    return f"{node}.w" if rot else f"{node}.v"


def _speed_law(node: str, rot: bool, value: str, turn: bool = False) -> Law:
    """A law of a body's speed: tested for a dependence on |speed| and speed^2 it lacks;
    ``turn``: and on the shaft's angle once per turn (a friction is the same all round a
    turn; a brake disc that rubs where it is warped is not)."""
    v = _speed(node, rot)
    terms = ((v, "abs"), (v, "square"))
    if turn and rot:
        terms += ((f"{node}.phi", "cos"), (f"{node}.phi", "sin"))
    return Law(("torque" if rot else "force", node), value, terms)


def rotational_shafts(net: Netlist) -> list[str]:
    """The netlist's rotational nodes (shafts), the mechanical ground left out."""
    return [n for n, d in _mechanical_nodes(net) if d == "rotational"]


def converters(net: Netlist) -> list[tuple[str, str]]:
    """(component, shaft node) of the netlist's declared electromechanical converters."""
    return _converters(net)


def always_orders(net: Netlist) -> dict[str, list[int]]:
    """Orders looked for on every shaft whether or not the residual shows their line: order
    1, a torque once per turn (an unbalance, an eccentric load, an arm's weight) and, on a
    converter's shaft, an EMF harmonic once per turn (an eccentric rotor), which a shaft
    that turns less than a few times in the record shows as no line at all."""
    return {n: [1] for n in rotational_shafts(net)}


def _current_law(component: str, value: str) -> Law:
    """A voltage in series with ``component``: tested for a dependence on |i| and i^2 it
    lacks (a contact's voltage growing slower than a resistance's)."""
    i = f"{component}.i"
    return Law(("series", component), value, ((i, "abs"), (i, "square")))


def _drop_law(component: str, value: str) -> Law:
    """A brush contact's drop: tested as ``_current_law`` is, and for a dependence on the
    current's direction -- a contact drops as much whichever way the current flows, while
    brushes set at an angle for one direction (or a diode in the loop) do not."""
    i = f"{component}.i"
    return Law(("series", component), value, ((i, "abs"), (i, "square"), (i, "sign")))


def _stribeck(node: str) -> list[Candidate]:
    """A breakaway peak over the node's Coulomb friction: s exp(-(w/ws)^2) sign(w) [N*m],
    one candidate per start of the Stribeck speed ws. Where no dry friction acts (declared
    or accepted), the peak is the friction's whole dry part: a bearing that sticks at rest
    and frees with speed (fresh53's be05: dried-out sintered bushes on a rotor that declares
    a viscous friction alone, which no dry friction of one level fits)."""
    out = []
    for i, w0 in enumerate(STRIBECK_SPEEDS):
        # names of their own: a joint screen carries every start at once
        s_, ws = (_pname("stribeck-friction", f"{node}_{i}", x) for x in ("s", "ws"))
        law = (f"-{s_}*exp(-({node}.w/({ws}*1[rad/s]))^2)*tanh({node}.w/{STRIBECK_SIGN!r}"
               "[rad/s])*1[N*m]")
        out.append(Candidate(
            "stribeck-friction", node, {s_: (0.0, 0.0, 1e4), ws: (w0, 1e-3, 1e3)}, {},
            f"a breakaway (Stribeck) peak of the friction on {node} at low speed",
            lambda r, n=node, i=i, law=law: add_part(r, {"name": f"SF{i}_{n}", "type": "btorque",
                                                     "shaft": n, "expr": law}),
            steps={s_: 1e-4, ws: 1e-2 * w0}, shape=(ws,),
            # a friction is the same all round a turn, and at every place of a travel
            # shorter than one (a throttle plate's): its law is bent by the shaft's angle
            # as a Coulomb friction's is; its speed dependence is its own shape
            law=Law(("torque", node), law, ((f"{node}.phi", "cos"), (f"{node}.phi", "sin")))))
    return out


def _warmup(name: str, duration: float) -> list[Candidate]:
    """A resistance settling to a warmer value: R (1 + rise (1 - exp(-t/tau))), in series as
    the resistor's own voltage times the rise, so that it holds whatever R is written as."""
    out = []
    for i, f in enumerate(WARMUP_TAUS):
        rise, tau = (_pname("resistance-drift", f"{name}_{i}", x) for x in ("rise", "tau"))
        law = f"{rise}*(1 - exp(-t/({tau}*1[s])))*{name}.v"
        out.append(Candidate(
            "resistance-drift", name, {rise: (0.0, *DRIFT_RISE),
                                       tau: (f * duration, 1e-6, 1e6)}, {},
            f"{name} warming up to a final value with a time constant",
            lambda r, n=name, i=i, law=law: insert_series(r, n, f"RW{i}_{n}", law),
            steps={rise: 1e-3, tau: 1e-2 * f * duration}, shape=(tau,),
            law=_current_law(name, law),
            limit=lambda v, n=name, rise=rise, tau=tau: _drift_rate(n, v[rise] / v[tau])))
    return out


def _drift_rate(name: str, rate: float) -> str:
    """Why a resistance changing at ``rate`` [1/s] is no winding warming or cooling ("" when
    it may be one): copper heats no faster than with no cooling at J_WINDING_MAX."""
    if abs(rate) <= DRIFT_RATE_MAX:
        return ""
    return (f"{name} changing by {rate:+.0%}/s: faster than copper heats with no cooling at "
            f"{J_WINDING_MAX / 1e6:.0f} A/mm^2 ({DRIFT_RATE_MAX:.0%}/s)")


#: declared inertias whose value a diagnosis may re-tune: (type, parameter)
INERTIAS = {"inertia": "J", "mass": "m"}
#: declared inductors whose value a diagnosis may re-tune: (type, parameter)
INDUCTORS = {"L": "L", "inductor": "L"}
#: every declared value a re-tuning candidate scales: (type, parameter)
RETUNED = {**INERTIAS, **INDUCTORS}


def _component_laws(net: Netlist, duration: float | None = None) -> list[Candidate]:
    out: list[Candidate] = []
    for c in _declared(net):
        if c.type in INERTIAS:
            # a body the netlist does not hold (a load on the shaft) or a wrong datasheet
            # value: the declared inertia is off, a correction, not a new cause
            p = _pname("inertia", c.name, "dJ")
            out.append(Candidate(
                "inertia", c.name, {p: (0.0, -0.9, 10.0)}, {},
                f"the inertia of {c.name} off by a factor 1 + dJ (a body the netlist lacks)",
                lambda r, n=c.name, p=p, k=INERTIAS[c.type]: _scale(r, n, k, p),
                steps={p: 1e-3}, retunes=True))
        if c.type in INDUCTORS:
            # a supply or cable inductance in series carries the same current: it is this
            # inductance off, as a wrong datasheet value is; a correction, not a new cause
            p = _pname("inductance", c.name, "dL")
            out.append(Candidate(
                "inductance", c.name, {p: (0.0, -0.9, 10.0)}, {},
                f"the inductance of {c.name} off by a factor 1 + dL (an inductance in series "
                f"with it: the supply's or a cable's)",
                lambda r, n=c.name, p=p: _scale_inductance(r, n, p),
                steps={p: 1e-3}, retunes=True))
            p = _pname("inductor-saturation", c.name, "Ipar")
            q = _pname("inductor-saturation", c.name, "ratio")
            out.append(Candidate(
                "inductor-saturation", c.name, {p: (1e6, 1e-6, 1e6), q: (0.3, 1e-3, 1.0)}, {},
                f"saturation of {c.name}: inductance falling with current",
                lambda r, n=c.name, p=p, q=q: _saturate(r, n, p, q),
                grid=(3.0, 1.0, 0.3, 0.1, 0.03, 0.01), generalises="inductance"))
        if c.type in ("R", "resistor"):
            p = _pname("resistance-drift", c.name, "alpha")
            # a straight line is the start of a warm-up: it is as fast as one can be, and
            # over the record it spans no more than the winding's widest swing
            rate = DRIFT_RATE_MAX if not duration else min(DRIFT_RATE_MAX,
                                                           DRIFT_RISE[1] / duration)
            out.append(Candidate(
                "resistance-drift", c.name, {p: (0.0, -rate, rate)}, {},
                f"{c.name} drifting with time (warming up)",
                lambda r, n=c.name, p=p: _drift(r, n, p), steps={p: 1e-3},
                law=Law(("series", c.name), f"{p}*t*{c.name}.v",
                        ((f"{c.name}.i", "abs"), ("t", "square")))))
            if duration:
                out.extend(_warmup(c.name, duration))
    return out


#: declared shaft couplings a play may open in: a spring, with or without its damper
COUPLINGS = ("spring", "rotational_spring", "spring_damper")
#: [rad] the largest play a coupling is given: half a turn is a loose part, not a play
GAP_MAX = 3.14
#: [rad] the plays a backlash is screened at. Its response is far from linear in the gap:
#: a play narrower than the coupling's twist only shifts the contact, a wider one lets the
#: sides part at each reversal and run free through it, which no slope at gap 0 foresees
#: (fresh23's aa04: a 0.3 rad slack cable, screened from its slope at 1e-3 rad, never reached
#: the refit). Below the grid the slope screens it (fresh2's g03, a play of 2.4e-5 rad).
GAP_GRID = (1.0, 0.3, 0.1, 0.03, 0.01, 0.003)


def _couplings(net: Netlist) -> list[Candidate]:
    """A play (backlash) opening in a declared torsional coupling between two bodies."""
    out = []
    for c in _declared(net):
        if c.type not in COUPLINGS:
            continue
        g = _pname("backlash", c.name, "gap")
        out.append(Candidate(
            "backlash", c.name, {g: (0.0, 0.0, GAP_MAX)}, {},
            f"a play (backlash) of total width gap in the coupling {c.name}: no torque "
            f"while the twist is within gap/2",
            lambda r, n=c.name, g=g: _backlash(r, n, g), steps={g: 1e-3}, grid=GAP_GRID,
            slope=True,
            # a play's sides are the declared coupling's: in contact it is as stiff both
            # ways and at every twist; a coupling stiffer one way (a crack that opens under
            # tension) or hardening with the twist is no play
            law=Law(("coupling", c.name), f"{c.name}.tau",
                    ((f"{c.name}.phi_rel", "centred"), (f"{c.name}.phi_rel", "abs")))))
    return out


def _backlash(raw: RawNetlist, name: str, gap: str) -> None:
    """Turn coupling ``name`` into a ``backlash`` of total play ``gap`` [rad] with its own
    stiffness, damping and unstretched twist (the play opens about a prestressed
    coupling's phi_rel0): Modelica's ElastoBacklash (in contact c (twist - phi_rel0 -+
    gap/2) + d w_rel, the damper never gluing the sides; nothing inside the play), which is
    the declared coupling exactly at gap 0."""
    e = raw.component_entry(name)
    e["type"] = "backlash"
    e["gap"] = gap


def _sensors(probes: Sequence[str] | Mapping[str, str]) -> list[Candidate]:
    out: list[Candidate] = []
    units = probes if isinstance(probes, Mapping) else {}
    for name in probes:
        g, o = _pname("sensor-gain", name, "g"), _pname("sensor-offset", name, "o")
        out.append(Candidate("sensor-gain", name, {g: (0.0, -0.5, 0.5)}, {},
                             f"a gain error g of the sensor of {name}: reads (1 + g) x",
                             lambda r, n=name, g=g: _probe_patch(r, n, g, "(1 + {v})*({x})"),
                             steps={g: 1e-3}, law=Law(("probe", name), "gain", ())))
        out.append(Candidate("sensor-offset", name, {o: (0.0, -1e6, 1e6)}, {},
                             f"an offset o of the sensor of {name}: reads x + o",
                             lambda r, n=name, o=o: _probe_patch(r, n, o, "({x}) + {v}"),
                             steps={o: 1e-3}, law=Law(("probe", name), "offset", ())))
        if name not in units:
            continue
        d = _pname("sensor-delay", name, "tau")
        out.append(Candidate("sensor-delay", name, {d: (DELAY_NULL, DELAY_NULL, 1.0)}, {},
                             f"a delay tau of the sensor of {name} (its filter or sampling "
                             f"lag): reads x(t - tau)",
                             lambda r, n=name, d=d, u=units[name]: _probe_delay(r, n, d, u),
                             steps={d: 1e-5}, law=Law(("probe", name), "delay", ())))
    return out


#: [s] the sensor delay's null: a Padé stage needs a capacitance > 0, and a picosecond is
#: invisible at any sampling rate a record has (it shifts a 100 A/ms edge by 0.1 µA). The
#: stage is then stiff, but linear and well damped: the implicit integrator does not notice.
DELAY_NULL = 1e-12


def _probe_delay(raw: RawNetlist, probe: str, tau: str, unit: str) -> None:
    """Read a probe through a delay of ``tau`` [s]: the first-order Padé all-pass
    (1 - s tau/2)/(1 + s tau/2) = 2/(1 + s tau/2) - 1, built from a 1 ohm, tau/2 farad
    low-pass driven by the probe's own expression. Its gain is exactly one at every
    frequency and its phase -2 atan(w tau/2), a delay's to within (w tau)^3/12 rad. The
    low-pass starts at 0: a record that starts from rest reads exactly, one that starts
    elsewhere shows a start-up blip lasting ~tau."""
    text, loc = raw.probes[probe]
    node_in, node_out = f"{tau}_in", f"{tau}_out"
    # the probe's value as a voltage: one volt per unit of the probe
    volts = f"({text})*1[V]" + (f"/1[{unit}]" if unit not in ("", "1") else "")
    add_part(raw, {"name": f"SDV_{tau}", "type": "BV", "p": node_in, "n": "gnd", "expr": volts})
    add_part(raw, {"name": f"SDR_{tau}", "type": "R", "p": node_in, "n": node_out, "R": 1.0})
    add_part(raw, {"name": f"SDC_{tau}", "type": "C", "p": node_out, "n": "gnd",
               "C": f"{tau}/2"})
    back = "" if unit in ("", "1") else f"*1[{unit}]"
    raw.probes[probe] = (f"2*{node_out}.v/1[V]{back} - ({text})", loc)


def _probe_patch(raw: RawNetlist, probe: str, param: str, template: str) -> None:
    """Rewrite a probe through a sensor law. A probe reads circuit quantities only, so the
    parameter enters as the voltage of its own source on a node of its own."""
    node = f"{param}_node"
    add_part(raw, {"name": f"S_{param}", "type": "V", "p": node, "n": "gnd", "V": param})
    add_part(raw, {"name": f"SL_{param}", "type": "R", "p": node, "n": "gnd", "R": 1.0})
    text, loc = raw.probes[probe]
    raw.probes[probe] = (template.format(v=f"{node}.v", x=text), loc)


def _ripple_torque(entry: Mapping) -> bool:
    """Whether a converter's EMF harmonics act on its shaft's torque too (the emf
    component's ``ripple_torque`` option, a bool the loader checks: on unless turned off)."""
    return entry.get("ripple_torque", True) is not False


def declared_orders(raw: RawNetlist) -> dict[tuple[str, str], set[int]]:
    """Harmonic orders the netlist already declares: (effect, target) -> orders. An
    ``emf-harmonic`` or ``cogging`` candidate of such an order re-tunes a declared term; a
    converter's EMF harmonic declares its order on the converter's shaft too."""
    out: dict[tuple[str, str], set[int]] = {}
    for entry, _, _ in raw.comps:
        harmonics = entry.get("harmonics")
        if not isinstance(harmonics, list):
            continue
        keys = [("cogging", str(entry.get("shaft")))] if entry.get("type") == "cogging" else \
            [("emf-harmonic", str(entry.get("name")))]
        if entry.get("type") != "cogging" and entry.get("shaft") is not None and \
                _ripple_torque(entry):
            # an EMF harmonic's torque side: a converter whose EMF ripples at order k also
            # pulls its shaft at order k (all of it when the coupling conserves energy), so a
            # torque of that order on that shaft re-tunes the declared term. With the ripple's
            # torque turned off (Kim & Kim's motor) the netlist declares no torque of that
            # order: one found on the shaft is new (fresh53's be07, an 8th-order cogging)
            keys.append(("cogging", str(entry["shaft"])))
        for h in harmonics:
            try:
                k = int(float(h["order"]))
            except (TypeError, ValueError, KeyError):
                continue
            for key in keys:
                out.setdefault(key, set()).add(k)
    return out


def _saturate(raw: RawNetlist, name: str, ipar: str, ratio: str) -> None:
    e = raw.component_entry(name)
    lval = e.pop("L")
    e["type"] = "Lsat"
    e["Lzer"] = lval
    e["Linf"] = f"{_operand(raw, lval, f'{ratio}_L0')}*{ratio}"
    e["Ipar"] = ipar


def _scale(raw: RawNetlist, name: str, key: str, rel: str) -> None:
    """Scale a component's value by (1 + rel), ``rel`` a new parameter (null 0)."""
    e = raw.component_entry(name)
    e[key] = f"{_operand(raw, e[key], f'{rel}_0')}*(1 + {rel})"


def _scale_inductance(raw: RawNetlist, name: str, rel: str) -> None:
    """Scale an inductor by (1 + rel); one a saturation patch has turned into ``Lsat``
    first is scaled at both ends of its curve, so that its knee and ratio keep their
    meaning."""
    e = raw.component_entry(name)
    if e.get("type") == "Lsat":
        _scale(raw, name, "Lzer", rel)
        e["Linf"] = f"({e['Linf']})*(1 + {rel})"
    else:
        _scale(raw, name, "L", rel)


def _operand(raw: RawNetlist, value: Any, pname: str) -> str:
    """A component's value as an operand of a value expression: a number in SI, a parameter
    name as it is, anything else (a value with its unit, ``2e-3 kg*m^2``, which arithmetic
    cannot hold) under a new parameter ``pname`` of its own."""
    if isinstance(value, (int, float)):
        return repr(float(value))
    text = str(value).strip()
    if text in raw.params:
        return text
    raw.params[pname] = (text, SourceLoc(raw.path or "<patch>"))
    return pname


def _drift(raw: RawNetlist, name: str, alpha: str) -> None:
    e = raw.component_entry(name)
    e["R0"] = e.pop("R")
    e["type"] = "Rdrift"
    e["alpha"] = alpha


def describe(cands: list[Candidate]) -> list[dict[str, Any]]:
    return [{"effect": c.effect, "target": c.target, "free": list(c.free), "fixed": dict(c.fixed),
             "what": c.what} for c in cands]
