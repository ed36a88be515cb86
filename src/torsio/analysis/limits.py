"""What limits the meaning of a result: the warnings a run or a map carries with it.

A result can be computed correctly and still say little. S_SS (Eq. 12) measures the
swing of the bit speed over the steady window, so it reads 0 for a bit that never
breaks free, and it misses a cycle longer than the window. Each function here returns
the warning text for one such case, or None where it does not apply; a results object
keeps the texts (``warnings``), its JSON lists them and the command line prints them on
stderr.

Examples
--------
>>> stuck_throughout(1.0, 0.1)
'the bit is stuck throughout the steady window (|bit speed| < 0.1 Omega at every sample): ...'
>>> stuck_throughout(0.4, 0.1) is None
True
>>> short_window(2.0, 7.65)
'the steady window (2 s) is shorter than one period of the first mode (7.65 s): ...'
>>> stuck_points(3, 100)
"at 3 of 100 points the bit is stuck throughout the steady window: ..."
"""

from __future__ import annotations

__all__ = ["short_window", "stuck_points", "stuck_throughout", "warning_list"]


def stuck_throughout(stick_fraction: float, stick_threshold: float) -> str | None:
    """The warning for a bit that sticks at every sample of the window, else None."""
    if stick_fraction < 1.0:
        return None
    return (
        f"the bit is stuck throughout the steady window (|bit speed| < {stick_threshold:g} "
        "Omega at every sample): the string never breaks it free, and S_SS, which measures "
        "the swing of the bit speed, does not measure stick-slip here; lower the weight on "
        "bit or raise the torque the top drive can give"
    )


def stuck_points(count: int, total: int) -> str | None:
    """The warning for a map with ``count`` of ``total`` points stuck throughout, else None."""
    if count <= 0:
        return None
    return (
        f"at {count} of {total} points the bit is stuck throughout the steady window: S_SS "
        "does not measure stick-slip there; they are classified 'stuck', not by S_SS"
    )


def short_window(steady_window: float, period: float) -> str | None:
    """The warning for a steady window [s] shorter than the first-mode ``period`` [s]."""
    if steady_window >= period:
        return None
    return (
        f"the steady window ({steady_window:.4g} s) is shorter than one period of the first "
        f"mode ({period:.4g} s): S_SS may miss the extremes of a stick-slip cycle; give a "
        "window of several periods (--window, simulation.steady_window)"
    )


def warning_list(*texts: str | None) -> tuple[str, ...]:
    """The texts that apply (not None), in order.

    >>> warning_list(None, "a", None, "b")
    ('a', 'b')
    """
    return tuple(text for text in texts if text is not None)
