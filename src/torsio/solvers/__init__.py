"""Integrators derived from the one description of the dynamics: scipy (one run) and the
compiled batch engine (many runs)."""

# torsio.solvers.compiled points numba's cache to the user's cache folder before any kernel
# is decorated (never into the installed package) and reports numba's compiles on stderr
# while they run (torsio.kernel_cache): importing a module of constants (the layouts) loads
# no numba
