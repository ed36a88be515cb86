"""The entry points of the compiled RODAS4 kernel, each compiled or loaded when first used.

numba compiles each with an explicit signature (:func:`torsio.solvers.compiled.kernel_signature`,
:func:`torsio.solvers.compiled.run_signature`) and caches it on disk; loading a cached
entry point costs tens of milliseconds, so each is built on first use (PEP 562): a map
loads its batch kernel alone (:func:`integrate_serial`, which releases the GIL: a map on
several threads calls it from each, :func:`torsio.solvers.batch.simulate_lumped_batch`), a
single run and a small batch (:func:`run_points`) the step loop alone (:func:`run_chunk`:
:func:`torsio.solvers.rodas.advance` itself). The step loop is compiled once for both:
the batch kernel links the single run's compiled copy, or the reverse.
"""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING, Any

import numpy as np

from torsio.solvers.compiled import kernel_signature, njit, run_signature
from torsio.solvers.rodas import advance, point

__all__ = ["SMALL_BATCH", "integrate_serial", "run_chunk", "run_points"]

SMALL_BATCH = 64
"""Batches of fewer points run point by point through the single run's entry point
(:func:`run_points`): a short study (the report's critical weight on bit, a bisection step)
then need not wait for the batch loop's compile (about 4 s of CPU), and costs about 30 µs a
point more in calls from Python."""

if TYPE_CHECKING:  # built by __getattr__ below
    integrate_serial: Any
    run_chunk: Any


def _serial(chain, top, torque, slope, p, settings, wob, omega, omega_set, out) -> None:
    """Every point in turn, without the GIL (arguments: :func:`kernel_signature`; numba
    inlines :func:`point` here, so the batch is one compiled function over :func:`advance`)."""
    for k in range(wob.size):
        point(chain, top, torque, slope, p, settings, wob, omega, omega_set, out, k)


def run_points(chain, top, torque, slope, p, settings, wob, omega, omega_set, out) -> None:
    """Every point in turn as :func:`_serial` runs it (:func:`torsio.solvers.rodas.point`:
    from rest at its set speed, ramped over ``RUN_RAMP``), each by one call of
    :func:`run_chunk`: the same compiled steps, the same rows."""
    from torsio.solvers import layouts as slot
    from torsio.solvers.chain_kernel import finish_run
    from torsio.solvers.set_speed import twist_table

    chunk = __getattr__("run_chunk")  # built or loaded on first use (PEP 562)
    ramp, has_top = settings[slot.RUN_RAMP], top[slot.TOP_HAS_NODE] != 0.0
    no_grid, no_samples, stop = np.zeros(0), np.zeros((0, 1)), np.int64(0)
    for k in range(wob.size):
        vectors = np.zeros((slot.VECTOR_ROWS, chain.shape[1]))
        small = np.zeros((slot.SMALL_ROWS, slot.SMALL_COLUMNS))
        table = twist_table([[0.0, ramp], [0.0, omega_set[k]]] if ramp > 0.0
                            else [[ramp], [omega_set[k]]], omega[k])  # fmt: skip
        vectors[slot.VEC_V] = -omega[k]  # start-up from rest
        chunk(chain, top, torque, slope, p, settings, wob[k], omega[k], table, vectors, small,
              no_grid, no_samples, stop)  # fmt: skip
        finish_run(settings, omega[k], has_top, small, out[k])


_ENTRY_POINTS = {
    "integrate_serial": (_serial, kernel_signature),
    "run_chunk": (advance, run_signature),
}
"""Each entry point: its function and the function giving its signature. A single run
calls :func:`~torsio.solvers.rodas.advance` itself, compiled with its explicit signature
and the flags of its decorator (a wrapper around it would compile the whole step loop
once more): numba caches it under the same key as the batch's call of it, so whichever
comes first compiles it and the other loads it."""

_BUILD_LOCK = threading.Lock()


def __getattr__(name: str) -> Any:
    """The entry point ``name`` of :data:`_ENTRY_POINTS`, built on first use (PEP 562)."""
    if name not in _ENTRY_POINTS:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    with _BUILD_LOCK:
        if name not in globals():
            function, signature = _ENTRY_POINTS[name]
            chosen = signature()
            if chosen is None:  # without numba: plain Python
                globals()[name] = function
            else:
                globals()[name] = _compiled(function, chosen)
    return globals()[name]


def _compiled(function: Any, signature: Any) -> Any:
    """``function`` (a step function of :mod:`torsio.solvers.rodas` with the flags of its
    decorator, or a plain function) compiled or loaded for ``signature``'s arguments.

    numba keys its cache on the signature as given: the arguments alone, as numba compiles
    a call from compiled code, so that the batch's call of
    :func:`~torsio.solvers.rodas.advance` loads what a single run compiled, and the
    reverse. Compiling is then disabled, so that a call from Python converts its arguments
    (a law's compiled functions to their function type) instead of compiling another
    specialization.
    """
    if hasattr(function, "py_func"):
        if function.targetoptions.get("no_cpython_wrapper"):  # numba's cache key ignores it
            raise TypeError(f"{function.py_func.__name__} is njit_inner: no entry point")
        flags = {k: v for k, v in function.targetoptions.items() if k != "nopython"}
        function = function.py_func
    else:
        flags = {"nogil": True, "error_model": "numpy"}
    entry = njit(cache=True, **flags)(function)
    entry.compile(tuple(signature.args))
    entry.disable_compile()
    return entry
