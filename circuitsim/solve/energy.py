"""Energy audit of a transient: the power balance of every component, integrated."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class EnergyAudit:
    """Where the energy of a transient went [J], per component, over [t0, t1].

    ``delivered``: by sources (independent across/through sources); ``dissipated``: turned into
    heat (resistors, dampers, friction, and the losses of lossy storage elements); ``stored``:
    change of stored energy (inductors, capacitors, inertias, masses); ``converted``: per
    multi-domain element (an EMF), the energy absorbed on each side; its sum is what the
    element creates or destroys, zero for an energy-conserving coupling. ``balance`` is
    delivered - dissipated - stored - net converter absorption (zero up to quadrature error).
    """

    t0: float
    t1: float
    delivered: dict[str, float]
    dissipated: dict[str, float]
    stored: dict[str, float]
    converted: dict[str, dict[str, float]]

    @property
    def total_delivered(self) -> float:
        return sum(self.delivered.values())

    @property
    def created(self) -> dict[str, float]:
        """Energy each converter *creates* (minus its net absorption) [J]."""
        return {k: -sum(v.values()) for k, v in self.converted.items()}

    @property
    def balance(self) -> float:
        return (self.total_delivered - sum(self.dissipated.values()) -
                sum(self.stored.values()) + sum(self.created.values()))

    def as_dict(self) -> dict:
        return {"t0": self.t0, "t1": self.t1, "delivered": self.delivered,
                "dissipated": self.dissipated, "stored": self.stored,
                "converted": self.converted, "created": self.created,
                "balance": self.balance}


def energy_audit(res, t0: float | None = None) -> EnergyAudit:
    """Energy audit of a SimResult from ``t0`` (default: start) to its end.

    Powers are integrated with the composite Simpson rule on the output samples, so the
    balance reflects the output step; components are classified by their declared branch
    kinds and by whether they store energy, never by type.
    """
    from scipy.integrate import simpson

    m = res.t >= (res.t[0] if t0 is None else t0)
    t = res.t[m]
    names = set(res.names)
    out: dict[str, dict] = {"delivered": {}, "dissipated": {}, "stored": {}, "converted": {}}
    for comp in res.model.netlist.components:
        n = comp.name
        power = res[f"{n}.power"][m]
        absorbed = float(simpson(power, x=t))
        kinds = {b.kind for b in comp.cls.branches}
        sides = [k for k in names if k.startswith(f"{n}.power_")]
        if kinds & {"V", "I"}:
            out["delivered"][n] = -absorbed
        elif f"{n}.energy" in names:
            e = res[f"{n}.energy"][m]
            out["stored"][n] = float(e[-1] - e[0])
            out["dissipated"][n] = absorbed - out["stored"][n]
        elif sides:
            out["converted"][n] = {k.split("power_", 1)[1]: float(simpson(res[k][m], x=t))
                                   for k in sorted(sides)}
        else:
            out["dissipated"][n] = absorbed
    # A storage element without losses shows a loss at quadrature-error level: drop it.
    scale = max([abs(v) for v in out["delivered"].values()] +
                [abs(v) for v in out["stored"].values()] + [1e-300])
    for n in list(out["dissipated"]):
        if n in out["stored"] and abs(out["dissipated"][n]) < 1e-6 * scale:
            del out["dissipated"][n]
    return EnergyAudit(float(t[0]), float(t[-1]), **out)
