"""The search of the operating window: a coarse map, then bisection near the boundary and
refinement in rpm near the optimum, every run counted.

1. **Coarse map**: the region's ``rpm_points`` x ``wob_points`` grid.
2. **Boundary** (the critical-WOB curve as guide): along each rpm, between the largest
   admissible weight on bit and the next one above it that is not, ``bisections`` halvings
   (:mod:`torsio.advice.region`: S_SS = criterion, or a constraint). Points below the
   critical WOB are not severe, those above are (the paper's maps): the best admissible
   point of a row, where ROP grows with WOB, lies at its boundary.
3. **Refinement in rpm**: ``refinements`` times, a new rpm halfway between the best row and
   each neighbouring row, its bracket guessed from the neighbours' boundaries, then bisected.

The recommended point is the best admissible point among all those run (a point the model
ran, not an interpolation). :class:`Ledger` keeps every run of one case.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.advice.evaluate import COLUMNS, AxialCase, Evaluation, PointsInterrupted, evaluate
from torsio.advice.region import Constraints, Region, objective_value

__all__ = ["Ledger", "SearchInterrupted", "Window", "critical_wob", "search_window", "window_of"]

DEFAULT_BISECTIONS = 5
"""Halvings of each row's boundary bracket (the coarse WOB step over 32)."""
DEFAULT_REFINEMENTS = 2
"""Rounds of new rpm rows around the best row."""


class Ledger:
    """Every point run for one case, in order, and the settings they run with
    (``threads``/``executor`` of :func:`~torsio.advice.evaluate.evaluate`; ``progress(n)``
    after n runs). A point asked again is not run again."""

    def __init__(
        self, case: AxialCase, run_on: dict[str, Any], progress: Callable[[int], None] | None = None
    ) -> None:
        self.case = case
        self.run_on = run_on
        self.progress = progress
        self.rows: dict[tuple[float, float], list[float]] = {}

    @property
    def runs(self) -> int:
        """How many runs so far."""
        return len(self.rows)

    def run(self, wob: Any, rpm: Any) -> None:
        """Run the points not yet run."""
        new = sorted({(float(w), float(r)) for w, r in zip(wob, rpm, strict=True)} - set(self.rows))
        if not new:
            return
        wobs, rpms = zip(*new, strict=True)
        try:
            done = evaluate(self.case, wobs, rpms, progress=self.progress, **self.run_on)
        except PointsInterrupted as exc:  # keep what finished
            for k, row in exc.finished.items():
                self.rows[new[k]] = row
            raise
        for k, key in enumerate(new):
            self.rows[key] = [float(getattr(done, name)[k]) for name in COLUMNS]

    def points(self) -> Evaluation:
        """Every point run so far, by rpm then WOB."""
        keys = sorted(self.rows, key=lambda key: (key[1], key[0]))
        values = np.array([self.rows[k] for k in keys], dtype=float).reshape(-1, len(COLUMNS))
        return Evaluation(
            wob=np.array([k[0] for k in keys], dtype=float),
            rpm=np.array([k[1] for k in keys], dtype=float),
            **{name: values[:, j] for j, name in enumerate(COLUMNS)},
        )


@attrs.frozen(eq=False)
class Window:
    """The search's outcome for one case.

    Attributes
    ----------
    label : str
        The case (its top drive).
    points : Evaluation
        Every point run, by rpm then WOB.
    admissible : ndarray of bool
        Which of them respect the constraints.
    best : int or None
        Index of the recommended point in ``points`` (None: no admissible point).
    rows : ndarray
        The rpm of every row searched [rev/min].
    critical : ndarray
        The critical WOB of each row [N] (S_SS = criterion, linear between the runs on
        either side; NaN where the row has no crossing: all severe or none).
    runs, coarse_runs : int
        Runs made in all, and those of the coarse map.
    complete : bool
        False when the search was interrupted.
    """

    label: str
    points: Evaluation
    admissible: NDArray[np.bool_]
    best: int | None
    rows: NDArray[np.float64]
    critical: NDArray[np.float64]
    runs: int
    coarse_runs: int
    complete: bool = True

    def point(self, index: int | None) -> dict[str, float] | None:
        """``wob``, ``rpm`` and the :data:`~torsio.advice.evaluate.COLUMNS` of a point."""
        if index is None:
            return None
        names = ("wob", "rpm", *COLUMNS)
        return {name: float(getattr(self.points, name)[index]) for name in names}


def _row_bracket(
    points: Evaluation, ok: NDArray[np.bool_], rpm: float
) -> tuple[float | None, float | None]:
    """The largest admissible WOB of the row at ``rpm`` and the least WOB above it that is
    not (None: none)."""
    row = points.rpm == rpm
    wobs, good = points.wob[row], ok[row]
    if not good.any():
        return None, (float(wobs.min()) if wobs.size else None)
    below = float(wobs[good].max())
    above = wobs[(wobs > below) & ~good]
    return below, (float(above.min()) if above.size else None)


def critical_wob(points: Evaluation, rpm: float, threshold: float) -> float:
    """The WOB [N] where S_SS crosses ``threshold`` along the row at ``rpm``: linear between
    the largest non-severe run and the next run above it (NaN: no such pair)."""
    row = points.rpm == rpm
    order = np.argsort(points.wob[row])
    wobs, severity = points.wob[row][order], points.severity[row][order]
    calm = np.flatnonzero(severity <= threshold)
    if calm.size == 0 or calm[-1] + 1 >= wobs.size:
        return float("nan")
    k = calm[-1]
    s0, s1 = severity[k], severity[k + 1]
    return float(wobs[k] + (threshold - s0) / (s1 - s0) * (wobs[k + 1] - wobs[k]))


def _bisect(
    ledger: Ledger, constraints: Constraints, rpms: list[float], steps: int, tolerance: float
) -> None:
    """Halve the boundary bracket of every row in ``rpms`` ``steps`` times, the rows side
    by side (one batch of runs per halving)."""
    for _ in range(steps):
        points = ledger.points()
        ok = constraints.admissible(points)
        wobs, rows = [], []
        for rpm in rpms:
            below, above = _row_bracket(points, ok, rpm)
            if below is not None and above is not None and above - below > tolerance:
                wobs.append(0.5 * (below + above))
                rows.append(rpm)
        if not rows:
            return
        ledger.run(wobs, rows)


def _best(points: Evaluation, ok: NDArray[np.bool_], objective: str) -> int | None:
    score = np.where(ok, objective_value(points, objective), -np.inf)
    if not ok.any() or not np.isfinite(score.max()):
        return None
    return int(np.argmax(score))


def _guess(
    ledger: Ledger, constraints: Constraints, region: Region, rpm: float, neighbours: list[float]
) -> None:
    """Run a new row's bracket guessed from its neighbours' boundaries (the region's ends
    where they have none), and the region's lowest WOB if the guess is not admissible."""
    points = ledger.points()
    ok = constraints.admissible(points)
    brackets = [_row_bracket(points, ok, r) for r in neighbours]
    belows = [b for b, _ in brackets if b is not None]
    aboves = [a for _, a in brackets if a is not None]
    low = min(belows) if belows else region.wob[0]
    high = max(aboves) if aboves else region.wob[1]
    ledger.run([low, high], [rpm, rpm])
    points = ledger.points()
    if not constraints.admissible(points)[(points.rpm == rpm) & (points.wob == low)].any():
        ledger.run([region.wob[0]], [rpm])


def search_window(
    ledger: Ledger,
    region: Region,
    constraints: Constraints,
    *,
    bisections: int = DEFAULT_BISECTIONS,
    refinements: int = DEFAULT_REFINEMENTS,
) -> Window:
    """Search the window of ``ledger``'s case over ``region`` (module documentation)."""
    wob, rpm = np.meshgrid(region.coarse_wob(), region.coarse_rpm())
    complete = False
    tolerance = 1e-3 * (region.wob[1] - region.wob[0])
    try:
        ledger.run(wob.ravel(), rpm.ravel())
        coarse = ledger.runs
        rows = [float(r) for r in region.coarse_rpm()]
        _bisect(ledger, constraints, rows, bisections, tolerance)
        for _ in range(refinements):
            points = ledger.points()
            best = _best(points, constraints.admissible(points), constraints.objective)
            if best is None:
                break
            at = rows.index(float(points.rpm[best]))
            new = []
            for side in (at - 1, at + 1):
                if 0 <= side < len(rows):
                    middle = 0.5 * (rows[at] + rows[side])
                    _guess(ledger, constraints, region, middle, [rows[at], rows[side]])
                    new.append(middle)
            rows = sorted(rows + new)
            _bisect(ledger, constraints, new, bisections, tolerance)
        complete = True
    except KeyboardInterrupt:
        coarse = min(ledger.runs, wob.size)  # the coarse map runs first
        rows = sorted({float(r) for r in ledger.points().rpm})
        if ledger.runs == 0:
            raise
        interrupted = window_of(ledger, constraints, rows, coarse, complete)
        raise SearchInterrupted(interrupted) from None
    return window_of(ledger, constraints, rows, coarse, complete)


class SearchInterrupted(KeyboardInterrupt):
    """Ctrl-C during a search: ``window`` holds the points run so far, marked incomplete."""

    def __init__(self, window: Window) -> None:
        super().__init__("interrupted")
        self.window = window


def window_of(
    ledger: Ledger, constraints: Constraints, rows: list[float], coarse: int, complete: bool
) -> Window:
    """The :class:`Window` of every point ``ledger`` has run: the ``rows`` [rev/min] searched,
    ``coarse`` runs of the coarse map, ``complete`` False when interrupted."""
    points = ledger.points()
    ok = constraints.admissible(points)
    return Window(
        label=ledger.case.label,
        points=points,
        admissible=ok,
        best=_best(points, ok, constraints.objective),
        rows=np.array(rows, dtype=float),
        critical=np.array([critical_wob(points, r, constraints.severity) for r in rows]),
        runs=ledger.runs,
        coarse_runs=coarse,
        complete=complete,
    )
