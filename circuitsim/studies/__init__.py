"""Studies over the pipeline: parameter and topology sweeps."""
