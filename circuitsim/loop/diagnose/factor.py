"""Stage 5c': found terms that scale one shaft's whole declared load by one factor.

A loss proportional to the torque a drive carries to a shaft -- a lead screw's nut whose
friction grows with the thrust, a transmission's efficiency -- is, while the shaft turns one
way, the shaft's own declared load times a constant: its inertia, its viscous drag and its
Coulomb friction each scaled by the same 1 + f. The catalog fits it with three terms -- an
inertia correction, a viscous friction and a Coulomb friction on that shaft -- and they
explain the record to its noise, so no test on the residual can see it (fresh28's af11: a
nut friction of 0.3 times the thrust, found as +42.7 %, +43.0 % and +42.8 % of the screw's
declared inertia, drag and friction). Three separate causes with one common size are one
cause the catalog does not hold; a heavier load would scale the inertia and the friction,
not the drag. At least ``FACTOR_TERMS`` such terms on one shaft, their relative sizes
within ``FACTOR_AGREE`` of one another, are stand-ins together.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

#: terms of one shaft whose common factor makes them one cause: all three kinds (inertia,
#: drag, Coulomb friction); two could share a size by chance on a pair of catalog effects
FACTOR_TERMS = 3
#: the largest spread of their relative sizes, over their mean, that still reads as one
#: factor [-] (af11: 0.007; two independent effects of random sizes agree this well only
#: by chance)
FACTOR_AGREE = 0.05
#: declared component types whose value a found term scales, by the found effect: (type,
#: parameter, port) of the declared rotational and translational terms
DECLARED = {"viscous-friction": (("damper", "b", "shaft"), ("tdamper", "d", "flange")),
            "coulomb-friction": (("friction", "tau_c", "shaft"), ("tfriction", "f_c", "flange"))}
#: the port a body sits on, by its type (the types of ``effects.INERTIAS``)
BODY_PORT = {"inertia": "shaft", "mass": "flange"}
WORDS = {"viscous-friction": "viscous drag", "coulomb-friction": "Coulomb friction"}


@dataclass(frozen=True)
class OneFactor:
    """A found term's share of one shaft's common factor, in words for the report."""

    node: str
    term: str  # what it scales, in words
    relative: float  # its size over the declared term's [-]
    common: float  # the mean over the shaft's terms [-]

    def why(self) -> str:
        return (f"it adds {self.relative:+.1%} to {self.node}'s declared {self.term}, as the "
                f"other terms found on {self.node} add {self.common:+.1%} to theirs")


def one_factor(net: Any, chosen: list[Any], params: Mapping[str, float]
               ) -> list[tuple[Any, OneFactor]]:
    """The ``chosen`` effects and corrections that scale one shaft's (or flange's) declared
    inertia (or mass), drag and Coulomb friction by one factor (see the module docstring),
    each with its verdict; empty when no node has ``FACTOR_TERMS`` of them agreeing within
    ``FACTOR_AGREE``.
    ``net``: the declared netlist (built), ``params``: the fitted values [SI]."""
    env = net.global_values(overrides=dict(params))
    by_node: dict[str, list[tuple[Any, str, float]]] = {}
    for choice in chosen:
        term = _relative(net, env, choice.candidate, params)
        if term is not None:
            node, words, rel = term
            by_node.setdefault(node, []).append((choice, words, rel))
    out = []
    for node, terms in by_node.items():
        rels = [r for _, _, r in terms]
        mean = sum(rels) / len(rels)
        if (len({w for _, w, _ in terms}) >= FACTOR_TERMS and mean > 0.0
                and max(rels) - min(rels) <= FACTOR_AGREE * mean):
            out += [(c, OneFactor(node, w, r, mean)) for c, w, r in terms]
    return out


def _relative(net: Any, env: Mapping[str, float], candidate: Any,
              params: Mapping[str, float]) -> tuple[str, str, float] | None:
    """(node, the declared term in words, the found term's size over it) of a body's
    correction (an inertia or a mass) or of a viscous or Coulomb friction on a shaft or a
    flange that declares one; None for any other effect."""
    from circuitsim.netlist.expr import evaluate

    if len(candidate.free) != 1 or next(iter(candidate.free)) not in params:
        return None
    name = next(iter(candidate.free))
    if candidate.effect == "inertia":
        comp = net.component(candidate.target)
        node = dict(comp.ports).get(BODY_PORT.get(comp.type, ""))
        return (node, f"{comp.type} {comp.name}", float(params[name])) if node else None
    if candidate.effect not in DECLARED:
        return None
    declared = sum(evaluate(c.values[f"{c.name}.{key}"].node, env)
                   for kind, key, port in DECLARED[candidate.effect] for c in net.components
                   if c.type == kind and dict(c.ports).get(port) == candidate.target
                   and f"{c.name}.{key}" in c.values)
    if not declared > 0.0:
        return None
    return candidate.target, WORDS[candidate.effect], float(params[name]) / declared
