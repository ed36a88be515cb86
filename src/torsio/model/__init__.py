"""The structure: components, the drill string, discretizers, lumped models, the exact
continuum and modal analysis."""
