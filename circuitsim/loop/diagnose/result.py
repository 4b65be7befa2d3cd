"""The result objects of a diagnosis: plain data, a summary, a JSON form, no plotting."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from circuitsim.errors import CircuitsimError


class DiagnosisError(CircuitsimError):
    """The diagnosis cannot run on this record or netlist."""


@dataclass
class Accepted:
    effect: str
    target: str
    parameters: dict[str, float]
    stderr: dict[str, float | None]
    error_after: float
    evidence: dict[str, Any]


@dataclass
class Diagnosis:
    """What the diagnosis found; ``as_dict`` is the diag.json report."""

    error_before: float
    error_after: float
    errors_before: dict[str, float]
    errors_after: dict[str, float]
    effects: list[Accepted]
    indistinct: list[str]
    remaining: dict[str, Any]
    analysis_before: dict[str, Any]
    analysis_after: dict[str, Any]
    raw: Any = field(repr=False, default=None)
    fit_before: Any = field(repr=False, default=None)
    fit_after: Any = field(repr=False, default=None)
    record: Any = field(repr=False, default=None)
    timings: dict[str, float] = field(default_factory=dict)
    rejected: list[dict[str, Any]] = field(default_factory=list)
    corrections: list[Accepted] = field(default_factory=list)
    noise: dict[str, float] = field(default_factory=dict)
    reduction: Any = None  # loop.reduce.Reduction: the record as the diagnosis used it
    #: what the user may check before reading the verdict (a record's clock that starts long
    #: after the netlist's, a probe the model meets only scaled: ``engine._hints``)
    hints: list[str] = field(default_factory=list)

    def as_dict(self) -> dict[str, Any]:
        return _clean({
            "error_before": self.error_before, "error_after": self.error_after,
            "errors": {"before": self.errors_before, "after": self.errors_after},
            "effects": [{"effect": a.effect, "target": a.target, "parameters": a.parameters,
                         "stderr": a.stderr, "error_after": a.error_after,
                         "evidence": a.evidence} for a in self.effects],
            "indistinct": self.indistinct, "remaining": self.remaining,
            "analysis_before": self.analysis_before, "analysis_after": self.analysis_after,
            "corrections": [{"effect": a.effect, "target": a.target,
                             "parameters": a.parameters, "stderr": a.stderr,
                             "evidence": a.evidence} for a in self.corrections],
            "noise": self.noise,
            "considered_not_accepted": self.rejected, "timings": self.timings,
            "hints": self.hints,
            "final_fit": self.final_parameters(),
            **({"record": self.reduction.as_dict()} if self.reduction is not None else {}),
            "summary": self.summary(),
        })

    def final_parameters(self) -> dict[str, dict[str, float | None]]:
        """Every free parameter of the final model (declared ones and those of the accepted
        effects, refitted together): start, estimate and standard error [SI]. An effect's
        ``parameters`` are its values when it was accepted; later effects move them.
        ``before``: a declared parameter's estimate in the declared model (None for the
        effects' parameters, which that model lacks)."""
        fit = self.fit_after
        if fit is None:
            return {}
        before = self.fit_before.estimate if self.fit_before is not None else {}
        return {n: {"before": before.get(n), "estimate": fit.estimate[n],
                    "stderr": fit.stderr[n] if math.isfinite(fit.stderr[n]) else None}
                for n in fit.free}

    def summary(self) -> str:
        structure = bool(self.remaining.get("structure"))
        if self.effects:
            head = "; ".join(f"{a.effect} on {a.target} " +
                             ", ".join(f"{k} = {v:.4g}" for k, v in a.parameters.items()) +
                             (f" [{a.evidence['interpolation']}]"
                              if a.evidence.get("interpolation") else "") + _caveat(a)
                             for a in self.effects)
        elif structure:
            head = "something remains that I cannot name: no effect of the catalog explains it"
        elif self.remaining.get("below_resolution") or self.remaining.get("coloured"):
            head = "nothing significant: " + self.remaining["note"].split(": ", 1)[1]
        else:
            head = "nothing significant: no effect of the catalog explains the residual"
        fixes = "".join(f"; corrected the declared {a.effect} on {a.target} ("
                        + (f"order {a.parameters['order']:g}" if "order" in a.parameters else
                           ", ".join(f"{k} = {v:.4g}" for k, v in a.parameters.items()))
                        + ")" for a in self.corrections)
        tail = ("; structure remains: " + self.remaining["note"]) if structure else ""
        if self.indistinct:  # a label the data cannot single out is said to be so
            tail = "; " + "; ".join(self.indistinct) + tail
        hints = "".join(f"; check: {h}" for h in self.hints)
        return f"{head}{fixes} ({self._error_text()}){tail}{hints}"

    def _error_text(self) -> str:
        """The error before and after; where the final model's is the larger, each probe's
        too, and why: the error is the probes' spreads' measure, while the fits weigh each
        probe by its noise (fresh35's am12: a correction fitting the current better, 0.106 ->
        0.075, and the speed, whose noise is 30 times larger in its spread, worse, 0.121 ->
        0.156, read as "error 0.1138 -> 0.1222" alone)."""
        text = f"error {self.error_before:.4g} -> {self.error_after:.4g}"
        if not self.error_after > self.error_before * (1.0 + 1e-3):
            return text
        probes = ", ".join(f"{p} {self.errors_before[p]:.4g} -> {v:.4g}"
                           for p, v in self.errors_after.items() if p in self.errors_before)
        return (f"{text}: by probe {probes}; the fit weighs each probe by its noise, not "
                f"by the spread this error is measured in")


def _caveat(a: Accepted) -> str:
    """An accepted effect's caveats: its law test when its bend is significant but no
    verdict, a shape the record does not determine."""
    law = (a.evidence.get("stability") or {}).get("law") or {}
    notes = [law.get("caveat"), a.evidence.get("undetermined")]
    return "".join(f" ({n})" for n in notes if n)


def _clean(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {str(k): _clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    if isinstance(obj, (np.floating, float)):
        return float(obj) if math.isfinite(obj) else None
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj
