"""numba for the kernels: ``njit`` and the kernels' explicit signatures.

numba is a dependency of torsio (``pyproject.toml``). Should it fail to import (a Python
version or platform it has no build for yet, a broken installation), ``njit`` returns
the functions unchanged (they run as plain Python, slowly) and :data:`HAVE_NUMBA` is
False: the batch engine then uses numpy.
"""

from __future__ import annotations

from typing import Any

from torsio.kernel_cache import use_user_cache_dir, watch_compiles

use_user_cache_dir()  # before any kernel is decorated: numba fixes its cache folder then
numba: Any
njit: Any
try:  # a dependency; without an importable numba the numpy engine is used
    import numba
    from numba import njit

    HAVE_NUMBA = True
    watch_compiles()  # notes on stderr while a kernel compiles (before the first is decorated)
except ImportError:  # pragma: no cover - exercised only without numba
    numba = None
    HAVE_NUMBA = False

    def _identity(*args: Any, **kwargs: Any) -> Any:
        """Stands in for numba.njit: the functions run as plain Python (slowly)."""
        if len(args) == 1 and callable(args[0]) and not kwargs:
            return args[0]
        return lambda function: function

    njit = _identity

__all__ = ["HAVE_NUMBA", "kernel_signature", "njit", "njit_inner", "numba", "run_signature"]


def njit_inner(**options: Any) -> Any:
    """``njit(**options)`` for a function that only compiled code calls.

    numba then builds no Python wrapper for it, which saves about a tenth of a second of
    compile for each (about 3 s of the step loop's first compile). Such a function cannot
    be called from Python (numba does not check it; the call would crash the process), nor
    be an entry point: a function that Python, a doctest or a test calls takes :func:`njit`
    (``tests/test_compiled_only.py``). numba's cache key does not tell the two apart, so a
    function is compiled one way only."""
    return njit(no_cpython_wrapper=True, **options)


def kernel_signature() -> Any:
    """Explicit signature of the batch kernels (None without numba).

    (chain, top, torque function, slope function, law parameters, settings, wob[k],
    Omega_ref[k], Omega_set[k], out[k]) -> None, the packed arrays as
    :mod:`torsio.solvers.layouts` lays them out (chain (``CHAIN_ROWS``, n), top
    (``TOP_SIZE``), settings (``RUN_SIZE``), out (points, ``OUT_COLUMNS``)). The two law
    functions are first-class function types, so one compiled kernel serves every law.
    """
    if not HAVE_NUMBA:
        return None
    from numba import types

    from torsio.solvers.law_kernels import law_type

    vector = types.float64[::1]
    law = law_type()
    return types.void(
        types.float64[:, ::1],
        vector,
        law,
        law,
        vector,
        vector,
        vector,
        vector,
        vector,
        types.float64[:, ::1],
    )


def run_signature() -> Any:
    """Explicit signature of a single run's kernel (None without numba).

    ``run_chunk(chain, top, torque, slope, parameters, settings, wob, Omega_ref, table,
    vectors, small, grid, samples, stop)``, ``table`` the set speed against time
    (``TABLE_ROWS``, k) (:func:`torsio.solvers.rodas.advance`).
    """
    if not HAVE_NUMBA:
        return None
    from numba import types

    from torsio.solvers.law_kernels import law_type

    vector, matrix, f8 = types.float64[::1], types.float64[:, ::1], types.float64
    law = law_type()
    return types.void(
        matrix, vector, law, law, vector, vector, f8, f8, matrix, matrix, matrix, vector,
        matrix, types.int64,
    )  # fmt: skip
