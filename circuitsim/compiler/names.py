"""Names the derivation gives the compiled model, kept free of sympy: a cached model is run
without importing it (tests/test_lean_startup.py)."""

#: A run-time factor on every explicit time derivative (a source's rate of change where an
#: equation was differentiated, a law written in t): 1 in a transient, 0 at an operating
#: point, where the sources are held at their values at one instant.
TIME_RATE = "@time.rate"
