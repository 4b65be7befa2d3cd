"""The ``circuitsim`` command: thin verbs over the Python API."""

from circuitsim.cli.main import main

__all__ = ["main"]
