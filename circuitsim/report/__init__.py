"""Plots and HTML reports: the only part of circuitsim that imports matplotlib."""
