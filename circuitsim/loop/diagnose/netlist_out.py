"""The patched netlist written back with fitted values."""

from __future__ import annotations

from collections.abc import Mapping, MutableMapping

from circuitsim.loop.diagnose.result import DiagnosisError


def _with_values(raw, params: Mapping[str, float]):
    """A copy of the raw netlist with the fitted (and overridden) values written in:
    netlist parameters by name, component parameters (``La.L``) in their component."""
    out = raw.copy()
    for name, v in params.items():
        if name in out.params:
            out.params[name] = (repr(float(v)), out.params[name][1])
        elif "." in name:
            comp, *path = name.split(".")
            node = out.component_entry(comp)
            # a waveform field ('V1.V.v1') sits one level down, under the waveform's kind:
            # V: {step: {v1: ...}}
            for key in path[:-1]:
                node = node[key]
                if isinstance(node, Mapping) and key not in ("table",) and len(node) == 1 \
                        and isinstance(next(iter(node.values())), Mapping):
                    node = next(iter(node.values()))
            if not isinstance(node, MutableMapping):
                raise DiagnosisError(f"cannot write the value of {name} into the netlist "
                                     f"(its entry is not a mapping); give it as a netlist "
                                     f"parameter instead")
            node[path[-1]] = float(v)
    return out


def build_raw(raw):
    from circuitsim.netlist.load import build

    return build(raw)


def load_raw_netlist(raw):
    """Type a raw netlist (for candidate generation on the current, patched netlist)."""
    from circuitsim.netlist.load import build

    return build(raw)
