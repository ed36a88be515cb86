"""Integrators derived from the one description of the dynamics: scipy (one run) and the
compiled batch engine (many runs)."""
