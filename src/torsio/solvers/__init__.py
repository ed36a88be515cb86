"""Integrators derived from the one description of the dynamics: scipy (one run) and the
compiled batch engine (many runs)."""

from torsio.kernel_cache import use_user_cache_dir

# before any kernel module is imported: numba's cache goes to the user's cache folder
# (never into the installed package); torsio.solvers.compiled reports numba's compiles
# on stderr while they run (torsio.kernel_cache.watch_compiles)
use_user_cache_dir()
