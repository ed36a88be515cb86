"""The entry points of the compiled RODAS4 kernel, each compiled or loaded when first used.

numba compiles each with an explicit signature (:func:`torsio.solvers.compiled.kernel_signature`,
:func:`torsio.solvers.compiled.run_signatures`) and caches it on disk; loading a cached
entry point costs tens of milliseconds, so each is built on first use (PEP 562): a map
loads its batch kernel alone (:func:`integrate_serial`, which releases the GIL: a map on
several threads calls it from each, :func:`torsio.solvers.batch.simulate_lumped_batch`), a
single run the two of :mod:`torsio.solvers.single_run` (:func:`run_start`,
:func:`run_chunk`: :func:`torsio.solvers.rodas.start` and :func:`torsio.solvers.rodas.advance`
themselves). The step loop, :func:`~torsio.solvers.rodas.advance`, is compiled once for
both: the batch kernel links the single run's compiled copy, or the reverse.
"""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING, Any

from torsio.solvers.compiled import kernel_signature, njit, run_signatures
from torsio.solvers.rodas import advance, point, start

__all__ = ["integrate_serial", "run_chunk", "run_start"]

if TYPE_CHECKING:  # built by __getattr__ below
    integrate_serial: Any
    run_chunk: Any
    run_start: Any


def _serial(chain, top, torque, slope, p, settings, wob, omega, omega_set, out) -> None:
    """Every point in turn, without the GIL (arguments: :func:`kernel_signature`; numba
    inlines :func:`point` here, so the batch is one compiled function over :func:`advance`)."""
    for k in range(wob.size):
        point(chain, top, torque, slope, p, settings, wob, omega, omega_set, out, k)


_ENTRY_POINTS = {
    "integrate_serial": (_serial, kernel_signature, 0),
    "run_start": (start, run_signatures, 0),
    "run_chunk": (advance, run_signatures, 1),
}
"""Each entry point: its function and its signature (the function giving it and, for the
single run's pair, its index). A single run calls :func:`start` and :func:`advance`
themselves, each compiled with its explicit signature and the flags of its decorator (a
wrapper around each would compile the whole step loop once more): numba caches them under
the same key as the batch's calls of them, so whichever comes first compiles them and the
other loads them."""

_BUILD_LOCK = threading.Lock()


def __getattr__(name: str) -> Any:
    """The entry point ``name`` of :data:`_ENTRY_POINTS`, built on first use (PEP 562)."""
    if name not in _ENTRY_POINTS:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    with _BUILD_LOCK:
        if name not in globals():
            function, signature, index = _ENTRY_POINTS[name]
            chosen = signature()
            chosen = chosen[index] if isinstance(chosen, tuple) else chosen
            if chosen is None:  # without numba: plain Python
                globals()[name] = function
            else:
                globals()[name] = _compiled(function, chosen)
    return globals()[name]


def _compiled(function: Any, signature: Any) -> Any:
    """``function`` (a step function of :mod:`torsio.solvers.rodas` with the flags of its
    decorator, or a plain function) compiled or loaded for ``signature``'s arguments.

    numba keys its cache on the signature as given: the arguments alone, as numba compiles
    a call from compiled code, so that the batch's calls of :func:`start` and
    :func:`advance` load what a single run compiled, and the reverse. Compiling is then
    disabled, so that a call from Python converts its arguments (a law's compiled functions
    to their function type) instead of compiling another specialization.
    """
    if hasattr(function, "py_func"):
        flags = {k: v for k, v in function.targetoptions.items() if k != "nopython"}
        function = function.py_func
    else:
        flags = {"nogil": True, "error_model": "numpy"}
    entry = njit(cache=True, **flags)(function)
    entry.compile(tuple(signature.args))
    entry.disable_compile()
    return entry
