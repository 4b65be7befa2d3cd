"""Closing the loop with measured data: records, fits, the effect catalog, diagnosis,
BLDC identification."""
