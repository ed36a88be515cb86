"""numba, when it is installed: ``njit``, ``prange`` and the batch kernel's signature.

Without numba, ``njit`` returns the functions unchanged (they run as plain Python,
slowly) and :data:`HAVE_NUMBA` is False: the batch engine then uses numpy.
"""

from __future__ import annotations

from typing import Any

numba: Any
njit: Any
prange: Any
try:  # numba is optional: without it the numpy engine is used
    import numba
    from numba import njit, prange

    HAVE_NUMBA = True
except ImportError:  # pragma: no cover - exercised only without numba
    numba = None
    HAVE_NUMBA = False
    prange = range

    def _identity(*args: Any, **kwargs: Any) -> Any:
        """Stands in for numba.njit: the functions run as plain Python (slowly)."""
        if len(args) == 1 and callable(args[0]) and not kwargs:
            return args[0]
        return lambda function: function

    njit = _identity

__all__ = ["HAVE_NUMBA", "kernel_signature", "njit", "numba", "prange"]


def kernel_signature() -> Any:
    """Explicit signature of the batch kernels (None without numba).

    (chain[8, n], top, torque function, slope function, law parameters, settings,
    wob[k], Omega_ref[k], Omega_set[k], out[k, 6]) -> None. The two law functions are
    first-class function types, so one compiled kernel serves every law.
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
