"""Diagnosis: trace a fit's residual to physical effects the netlist lacks."""

from circuitsim.loop.diagnose.engine import diagnose
from circuitsim.loop.diagnose.features import diagnose_features
from circuitsim.loop.diagnose.residual import noise_sigma
from circuitsim.loop.diagnose.result import Accepted, Diagnosis, DiagnosisError

__all__ = ["Accepted", "Diagnosis", "DiagnosisError", "diagnose", "diagnose_features",
           "noise_sigma"]
