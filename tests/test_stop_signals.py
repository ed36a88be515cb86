"""A stop signal whose KeyboardInterrupt Python discards still stops a run (issue 36,
case 6: every run stops within 2 s of SIGINT or SIGTERM). Python discards an exception
raised in a weakref callback: a SIGINT handled there was lost, and ``torsio simulate``
ran on to its end (1 of 120 SIGINTs sent during its start on a busy machine)."""

from __future__ import annotations

import signal
import sys
import weakref

import pytest

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


@pytest.mark.parametrize("name", ["SIGINT", "SIGTERM"])
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
        assert signal.getsignal(signal.SIGINT) is not before[0]
    after = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM), sys.unraisablehook
    assert after == before
