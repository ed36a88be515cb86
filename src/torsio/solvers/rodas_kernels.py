"""The entry points of the compiled RODAS4 kernel, each compiled or loaded when first used.

numba compiles each with an explicit signature (:func:`torsio.solvers.compiled.kernel_signature`,
:func:`torsio.solvers.compiled.run_signatures`) and caches it on disk; loading a cached
entry point costs tens of milliseconds, so each is built on first use (PEP 562): a map
loads its batch kernel alone (:func:`integrate_serial`, which releases the GIL: a map on
several threads calls it from each, :func:`torsio.solvers.batch.simulate_lumped_batch`), a
single run the two of :mod:`torsio.solvers.single_run` (:func:`run_start`,
:func:`run_chunk`). The steps themselves are :mod:`torsio.solvers.rodas`.
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
    """Every point in turn, without the GIL (arguments: :func:`kernel_signature`)."""
    for k in range(wob.size):
        point(chain, top, torque, slope, p, settings, wob, omega, omega_set, out, k)


def _start_run(chain, top, torque, p, settings, wob, omega, table, vectors, small) -> None:
    """A single run: prepare it from the state in the work space (:func:`start`)."""
    start(chain, top, torque, p, settings, wob, omega, table, vectors, small)


def _run_chunk(
    chain, top, torque, slope, p, settings, wob, omega, table, vectors, small, grid,
    samples, stop,
) -> None:  # fmt: skip
    """A single run: advance it until the output sample ``stop`` is written (:func:`advance`)."""
    advance(chain, top, torque, slope, p, settings, wob, omega, table, vectors, small,
            grid, samples, stop)  # fmt: skip


_ENTRY_POINTS = {
    "integrate_serial": (_serial, kernel_signature, 0, {"nogil": True}),
    "run_start": (_start_run, run_signatures, 0, {"nogil": True}),
    "run_chunk": (_run_chunk, run_signatures, 1, {"nogil": True}),
}
"""Each entry point: its Python function, the signature (the function giving it and, for
the single run's pair, its index) and numba's flags."""

_BUILD_LOCK = threading.Lock()


def __getattr__(name: str) -> Any:
    """The entry point ``name`` of :data:`_ENTRY_POINTS`, built on first use (PEP 562)."""
    if name not in _ENTRY_POINTS:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    with _BUILD_LOCK:
        if name not in globals():
            function, signature, index, flags = _ENTRY_POINTS[name]
            chosen = signature()
            chosen = chosen[index] if isinstance(chosen, tuple) else chosen
            globals()[name] = njit(chosen, cache=True, error_model="numpy", **flags)(function)
    return globals()[name]
