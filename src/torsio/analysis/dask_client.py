"""Connecting to and closing a Dask client, each within a deadline."""

from __future__ import annotations

import math
from typing import Any

from torsio.errors import ConfigError

CONNECT_TIMEOUT = 10.0
"""Seconds to wait for a Dask scheduler (and for it to have a worker) before giving up."""

CLOSE_TIMEOUT = 10.0
"""Seconds to wait for a Dask client to close before leaving it behind."""


def check_timeout(timeout: Any, key: str = "timeout") -> float:
    """``timeout`` [s] as a float, or a ConfigError unless it is a positive finite number."""
    if isinstance(timeout, bool) or not isinstance(timeout, int | float):
        raise ConfigError(key, f"expected a positive number of seconds, got {timeout!r}")
    if not (math.isfinite(timeout) and timeout > 0):
        raise ConfigError(key, f"expected a positive finite number of seconds, got {timeout!r}")
    return float(timeout)


def connect_dask(address: str, timeout: float = CONNECT_TIMEOUT) -> Any:
    """A ``distributed.Client`` connected to ``address``; ConfigError if it cannot be reached."""
    try:
        import distributed
    except ImportError:
        raise ConfigError(
            "scheduler", "a Dask scheduler needs the dask extra: pip install 'torsio[dask]'"
        ) from None
    timeout = check_timeout(timeout)
    outcome: dict[str, Any] = {}

    def connect() -> None:  # in a thread: a peer that never answers must not block us
        try:
            client = distributed.Client(address, timeout=timeout, set_as_default=False)
            outcome["client"] = client
            client.wait_for_workers(1, timeout=timeout)
        except BaseException as exc:  # reported below, in the calling thread
            _discard_half_built(exc, distributed.Client)
            outcome["error"] = exc.with_traceback(None)

    import threading

    log_without_tracebacks()  # distributed is imported now: its handlers exist
    thread = threading.Thread(target=connect, name="torsio-dask-connect", daemon=True)
    thread.start()
    thread.join(timeout + 2.0)
    client = outcome.get("client")
    error = outcome.get("error")
    if thread.is_alive() or (error is not None and client is None):
        why = "no answer" if thread.is_alive() else f"{type(error).__name__}: {error}".rstrip(": ")
        if client is not None:
            close_dask(client)
        raise ConfigError(
            "scheduler",
            f"cannot reach the Dask scheduler at {address!r} within {timeout:g} s ({why}); "
            "is it a Dask scheduler address such as tcp://host:8786?",
        ) from None
    if error is not None:
        close_dask(client)
        raise ConfigError(
            "scheduler",
            f"the Dask scheduler at {address!r} has no worker after {timeout:g} s; "
            "start workers (dask worker ADDRESS) or raise --timeout",
        ) from None
    return client


def _discard_half_built(error: BaseException, client_class: Any) -> None:
    """Mark closed a client whose constructor raised ``error``.

    Otherwise the half-built client, kept alive by the traceback, tries to close
    itself when it is collected (at exit: a 20 s wait, then a traceback on stderr).
    """
    traceback = error.__traceback__
    while traceback is not None:
        candidate: Any = traceback.tb_frame.f_locals.get("self")
        if isinstance(candidate, client_class) and getattr(candidate, "status", None) != "closed":
            try:
                candidate.close(timeout=1.0)
            except Exception:  # unreachable scheduler: nothing to close on its side
                pass
            candidate.status = "closed"
        traceback = traceback.tb_next


def close_dask(client: Any, timeout: float = CLOSE_TIMEOUT) -> None:
    """Close a Dask client within ``timeout`` s; a client that does not close is left."""
    import threading

    def close() -> None:
        try:
            client.close(timeout=timeout)
        except Exception:  # a scheduler already gone: nothing left to close
            pass

    thread = threading.Thread(target=close, name="torsio-dask-close", daemon=True)
    thread.start()
    thread.join(timeout + 2.0)


class _WithoutTraceback:
    """A logging filter that keeps a record's message and drops its traceback."""

    def filter(self, record: Any) -> bool:
        record.exc_info = None
        record.exc_text = None
        record.stack_info = None
        return True


def log_without_tracebacks() -> None:
    """Let Dask's and the executors' log records reach stderr as one line, no traceback.

    Called on connecting: a lost scheduler is reported by torsio's own error; the
    tracebacks ``distributed`` and ``concurrent.futures`` log on the way are noise.
    """
    import logging

    handlers = [logging.lastResort]
    for name in ("distributed", "concurrent.futures", "tornado", "asyncio"):
        handlers += logging.getLogger(name).handlers
    for handler in handlers:
        if handler is not None and not any(
            isinstance(f, _WithoutTraceback) for f in handler.filters
        ):
            handler.addFilter(_WithoutTraceback())
