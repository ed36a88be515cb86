"""A stop signal whose KeyboardInterrupt Python discards still stops a run (issue 36,
case 6: every run stops within 2 s of SIGINT or SIGTERM). Python discards an exception
raised in a weakref callback: a SIGINT handled there was lost, and ``torsio simulate``
ran on to its end (1 of 120 SIGINTs sent during its start on a busy machine)."""

from __future__ import annotations

import signal
import sys
import time
import weakref
from concurrent.futures import ThreadPoolExecutor

import pytest

from torsio.analysis.sweep import EXECUTOR_POLL, SweepInterrupted, run_tasks
from torsio.solvers.run_chunks import run_in_chunks
from torsio.stop_signals import raise_if_stopped, stop_signals


class _Referent:
    pass


def _lose_a_signal(name: str) -> None:
    """Send ``name`` to this process inside a weakref callback (its handler runs there)."""
    referent = _Referent()
    reference = weakref.ref(referent, lambda _: signal.raise_signal(getattr(signal, name)))
    del referent  # the callback runs now, and Python discards what it raises
    assert reference() is None


SIGINT_IGNORED = pytest.mark.skipif(
    signal.getsignal(signal.SIGINT) is signal.SIG_IGN,
    reason="SIGINT is ignored in this process (a background job), and stays ignored",
)


@pytest.mark.parametrize("name", [pytest.param("SIGINT", marks=SIGINT_IGNORED), "SIGTERM"])
def test_a_lost_interrupt_stops_the_next_chunk(name: str, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    discarded: list[type[BaseException] | None] = []
    monkeypatch.setattr(sys, "unraisablehook", lambda u: discarded.append(u.exc_type))
    chunks: list[int] = []
    with stop_signals() as received:
        _lose_a_signal(name)
        assert received == [getattr(signal, name)]  # handled, and then discarded by Python
        assert discarded == []  # no "Exception ignored" traceback on stderr
        with pytest.raises(KeyboardInterrupt):
            run_in_chunks(10, chunks.append, first=4)
    assert chunks == [4]  # stopped after the chunk that was running
    raise_if_stopped()  # outside the block, no signal is pending


def test_other_discarded_exceptions_are_still_shown(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    discarded: list[type[BaseException] | None] = []
    monkeypatch.setattr(sys, "unraisablehook", lambda u: discarded.append(u.exc_type))
    referent = _Referent()
    reference = weakref.ref(referent, lambda _: 1 / 0)
    with stop_signals():
        del referent
    assert reference() is None
    assert discarded == [ZeroDivisionError]


def test_the_handlers_are_restored() -> None:
    before = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM), sys.unraisablehook
    with stop_signals():
        assert signal.getsignal(signal.SIGTERM) is not before[1]
    after = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM), sys.unraisablehook
    assert after == before


def test_an_ignored_sigint_stays_ignored_and_sigterm_is_handled() -> None:
    # a background job inherits SIGINT ignored (Python leaves it so); SIGTERM stops a
    # command whatever the parent did, as before stop_signals
    previous = (
        signal.signal(signal.SIGINT, signal.SIG_IGN),
        signal.signal(signal.SIGTERM, signal.SIG_IGN),
    )
    try:
        with stop_signals():
            assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN
            assert signal.getsignal(signal.SIGTERM) not in (signal.SIG_IGN, signal.SIG_DFL)
        assert signal.getsignal(signal.SIGTERM) is signal.SIG_IGN
    finally:
        signal.signal(signal.SIGINT, previous[0])
        signal.signal(signal.SIGTERM, previous[1])


def test_a_lost_interrupt_stops_a_sweep_waiting_on_its_workers(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    # the sweep's poll of its executor (every EXECUTOR_POLL s) raises it again: the tasks
    # left are cancelled and SweepInterrupted keeps what finished
    monkeypatch.setattr(sys, "unraisablehook", lambda u: None)
    started = time.monotonic()
    with stop_signals(), pytest.raises(SweepInterrupted) as interrupted:
        _lose_a_signal("SIGTERM")
        run_tasks(time.sleep, [(0.2,)] * 40, executor=ThreadPoolExecutor(max_workers=2))
    assert interrupted.value.done < 40
    assert time.monotonic() - started < 2.0 + EXECUTOR_POLL
