"""Integrators derived from the one description of the dynamics: scipy (one run) and the
compiled batch engine (many runs)."""

from torsio.kernel_cache import use_user_cache_dir

# before any kernel module is imported: numba's cache goes to the user's cache folder
# (never into the installed package); the kernel modules announce a first compile
# (torsio.solvers.compiled), so importing an options module here announces nothing
use_user_cache_dir()
