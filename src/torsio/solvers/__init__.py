"""Integrators derived from the one description of the dynamics: scipy (one run) and the
compiled batch engine (many runs)."""

from torsio.kernel_cache import announce_first_compile, use_user_cache_dir

# before any kernel module is imported: numba's cache goes to the user's cache folder
# (never into the installed package), and a first compile is announced on stderr
use_user_cache_dir()
announce_first_compile()
