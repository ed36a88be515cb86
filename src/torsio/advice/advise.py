"""``advise``: the operating point that drills best without severe stick-slip, its margin
and the top drives compared (docs/advise.md).

1. The configured top drive's window is searched (:func:`torsio.advice.search.search_window`).
2. With an :class:`~torsio.advice.margin.Uncertainty`, the best point's probability of
   severe stick-slip is found by Monte Carlo; while its upper bound is not below ``level``
   the point steps down in WOB (a quarter of the coarse WOB step) at the same rpm.
3. The alternatives (:mod:`torsio.advice.top_drives`) are searched the same way; the
   SoftTorque tunings on a 3 x 3 grid of the region first, the widest safe window then
   searched whole.

Ctrl-C raises :class:`AdviceInterrupted` carrying the advice so far, marked incomplete.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

import attrs
import numpy as np

from torsio.advice.evaluate import AxialCase, case_with, evaluate
from torsio.advice.margin import (
    CONFIDENCE,
    Uncertainty,
    case_with_values,
    rpm_margin,
    severe_count,
    upper_bound,
)
from torsio.advice.region import Constraints, Region
from torsio.advice.results import Advice, Margin
from torsio.advice.search import (
    DEFAULT_BISECTIONS,
    DEFAULT_REFINEMENTS,
    Ledger,
    SearchInterrupted,
    Window,
    search_window,
    window_of,
)
from torsio.advice.top_drives import alternatives, safe_share, soft_torque_tunings
from torsio.errors import ConfigError

__all__ = ["DEFAULT_LEVEL", "DEFAULT_SAMPLES", "AdviceInterrupted", "advise"]

DEFAULT_LEVEL = 0.1
"""The probability of severe stick-slip the recommended point stays below."""
DEFAULT_SAMPLES = 30
"""Monte Carlo samples per point (none severe in 30: upper bound 9.5 % < 10 %)."""
BACK_OFF_STEPS = 8
"""Most WOB steps down from the best point to meet the level."""


class AdviceInterrupted(KeyboardInterrupt):
    """Ctrl-C: ``advice`` holds what was run, ``complete`` False."""

    def __init__(self, advice: Advice) -> None:
        super().__init__("interrupted")
        self.advice = advice


def _effective_critical(window: Window, threshold: float) -> np.ndarray:
    """Each row's critical WOB; a row with no crossing: +inf (nothing severe) or -inf
    (everything severe)."""
    out = window.critical.copy()
    for k, rpm in enumerate(window.rows):
        if np.isnan(out[k]):
            row = window.points.rpm == rpm
            calm = window.points.severity[row] <= threshold
            out[k] = np.inf if calm.all() else -np.inf
    return out


class _Advisor:
    """One advice in the making; :meth:`advice` builds it from what has run."""

    def __init__(
        self,
        config: Any,
        region: Region,
        constraints: Constraints,
        run_on: dict,
        progress: Callable[[int], None] | None,
        case: AxialCase,
        search: dict[str, int],
    ) -> None:
        self.config, self.region, self.constraints = config, region, constraints
        self.options = search
        self.run_on, self.progress, self.case = run_on, progress, case
        self.start = time.perf_counter()
        self.ledger = Ledger(case, run_on, progress)
        self.window: Window | None = None
        self.best: int | None = None
        self.margin = Margin()
        self.others: list[Window] = []
        self.tuning: dict[str, Any] = {}
        self.mc_runs = 0
        self.uncertainty: dict[str, Any] | None = None

    def search(self, ledger: Ledger) -> Window:
        try:
            return search_window(ledger, self.region, self.constraints, **self.options)
        except SearchInterrupted as exc:
            if ledger is self.ledger:
                self.window = exc.window
                self.best = exc.window.best
            else:
                self.others.append(exc.window)
            raise

    def secure(self, uncertainty: Uncertainty, level: float, samples: int, seed: int) -> None:
        """Step the best point down in WOB until its probability bound is below ``level``."""
        assert self.window is not None
        self.uncertainty = {**uncertainty.to_dict(), "seed": seed}
        if self.best is None:
            return
        draws = uncertainty.draws(samples, seed)
        cases = [case_with_values(self.config, self.case, d, uncertainty.flag) for d in draws]
        wob, rpm = (
            float(self.window.points.wob[self.best]),
            float(self.window.points.rpm[self.best]),
        )
        step = 0.25 * (self.region.wob[1] - self.region.wob[0]) / (self.region.wob_points - 1)
        for k in range(BACK_OFF_STEPS + 1):
            trial = wob - k * step
            if trial < self.region.wob[0]:
                break
            self.ledger.run([trial], [rpm])
            points = self.ledger.points()
            index = int(np.flatnonzero((points.wob == trial) & (points.rpm == rpm))[0])
            if not self.constraints.admissible(points)[index]:
                continue
            result = evaluate(
                cases, [trial] * samples, [rpm] * samples, progress=self.progress, **self.run_on
            )
            self.mc_runs += samples
            severe, valid = severe_count(result.severity, self.constraints.severity)
            bound = upper_bound(severe, valid)
            self.margin = Margin(
                probability_severe=severe / max(valid, 1),
                probability_upper=bound,
                samples=valid,
                severe=severe,
                level=level,
                confidence=CONFIDENCE,
                backed_off=k,
            )
            if bound < level:
                self.window = _with_points(self.window, self.ledger, self.constraints)
                self.best = int(
                    np.flatnonzero(
                        (self.window.points.wob == trial) & (self.window.points.rpm == rpm)
                    )[0]
                )
                return
        self.best = None  # no point of the row meets the level

    def compare(self) -> None:
        """The alternatives' windows, and the SoftTorque tuning with the widest safe one."""
        for label, top_drive in alternatives(self.config).items():
            ledger = Ledger(
                case_with(self.case, top_drive=top_drive, label=label), self.run_on, self.progress
            )
            self.others.append(self.search(ledger))
        shares, ledgers = {}, {}
        for label, top_drive in soft_torque_tunings(self.config).items():
            ledger = Ledger(
                case_with(self.case, top_drive=top_drive, label=label), self.run_on, self.progress
            )
            ledgers[label] = ledger
            ledger.run(*_tuning_grid(self.region))
            shares[label] = safe_share(ledger.points().severity, self.constraints.severity)
        chosen = max(shares, key=lambda label: shares[label])
        self.tuning = {
            "parameter": "kp = k zeta (SoftTorque damping gain; ki = omega_1^2 J kept)",
            "safe_share": shares,
            "chosen": chosen,
            "runs": sum(ledger.runs for label, ledger in ledgers.items() if label != chosen),
        }
        self.others.append(self.search(ledgers[chosen]))

    def advice(self, complete: bool) -> Advice:
        window = self.window or _with_points(None, self.ledger, self.constraints)
        if self.window is not None:  # the recommended point: the margin's, not the best
            window = attrs.evolve(window, best=self.best)
        margin = self.margin
        recommended = window.point(window.best) if self.window is not None else None
        if recommended is not None:
            critical = _effective_critical(window, self.constraints.severity)
            at = np.flatnonzero(window.rows == recommended["rpm"])
            wob_margin = float(critical[at[0]] - recommended["wob"]) if at.size else None
            if wob_margin is not None and not np.isfinite(wob_margin):
                wob_margin = None
            rpm = rpm_margin(window.rows, critical, recommended["wob"], recommended["rpm"])
            margin = attrs.evolve(margin, wob=wob_margin, rpm=rpm)
        return Advice(
            recommended=recommended,
            margin=margin,
            window=window,
            top_drives=(window, *self.others),
            tuning=self.tuning,
            region=self.region,
            constraints=self.constraints,
            uncertainty=self.uncertainty,
            monte_carlo_runs=self.mc_runs,
            elapsed=time.perf_counter() - self.start,
            complete=complete,
            model=str(getattr(self.config, "name", "")),
        )


def _tuning_grid(region: Region) -> tuple[np.ndarray, np.ndarray]:
    """The points a SoftTorque tuning's safe window is measured on: the region's corners,
    edge midpoints and centre (3 x 3), a subset of the coarse map when its counts are odd."""
    wob, rpm = np.meshgrid(np.linspace(*region.wob, 3), np.linspace(*region.rpm, 3))
    return wob.ravel(), rpm.ravel()


def _with_points(window: Window | None, ledger: Ledger, constraints: Constraints) -> Window:
    """``window`` with every point the ledger has run since (the Monte Carlo's nominal)."""
    rows = [] if window is None else window.rows.tolist()
    rows = sorted(
        set(rows) | ({float(r) for r in ledger.points().rpm} if window is None else set())
    )
    coarse = 0 if window is None else window.coarse_runs
    complete = window is not None and window.complete
    return window_of(ledger, constraints, rows, coarse, complete)


def advise(
    config: Any,
    region: Region,
    constraints: Constraints | None = None,
    *,
    uncertainty: Uncertainty | None = None,
    level: float = DEFAULT_LEVEL,
    samples: int = DEFAULT_SAMPLES,
    seed: int = 0,
    compare: bool = True,
    threads: int = 1,
    executor: Any = None,
    progress: Callable[[int], None] | None = None,
    duration: float | None = None,
    window: float | None = None,
    bisections: int = DEFAULT_BISECTIONS,
    refinements: int = DEFAULT_REFINEMENTS,
) -> Advice:
    """The advice on ``config`` over ``region`` (module documentation).

    ``uncertainty``: the parameters drawn for the margin (None: no Monte Carlo);
    ``level``: the probability of severe stick-slip the point's bound stays below;
    ``samples`` and ``seed`` of the Monte Carlo; ``compare``: search the alternative top
    drives too; ``threads``/``executor``: where the runs go (as the maps);
    ``progress(n)`` after every n runs; ``duration``/``window`` of every run [s];
    ``bisections`` and ``refinements`` of the search
    (:func:`~torsio.advice.search.search_window`)."""
    if not (0.0 < level < 1.0):
        raise ConfigError("--level", f"expected a probability between 0 and 1, got {level!r}")
    if isinstance(samples, bool) or not isinstance(samples, int) or samples < 1:
        raise ConfigError("--samples", f"expected a whole number >= 1, got {samples!r}")
    least = upper_bound(0, samples)
    if uncertainty is not None and least >= level:
        raise ConfigError(
            "--samples",
            f"{samples} samples cannot show a probability below {level:g}: even none severe "
            f"leaves its upper bound at {least:.3g} ({CONFIDENCE:.0%} Clopper-Pearson); "
            f"expected at least {math.ceil(math.log(1 - CONFIDENCE) / math.log(1 - level))}",
        )
    constraints = constraints or Constraints()
    case = AxialCase.from_config(config, duration, window)
    if uncertainty is not None:  # a bad name is an error before any run
        nominal = dict(zip(uncertainty.names, uncertainty.values, strict=True))
        case_with_values(config, case, nominal, uncertainty.flag)
    if compare:
        alternatives(config)  # a [chain] without a drill pipe: an error before any run
    run_on = {"threads": threads, "executor": executor}
    search = {"bisections": bisections, "refinements": refinements}
    advisor = _Advisor(config, region, constraints, run_on, progress, case, search)
    try:
        advisor.window = advisor.search(advisor.ledger)
        advisor.best = advisor.window.best
        if uncertainty is not None:
            advisor.secure(uncertainty, level, samples, seed)
        if compare:
            advisor.compare()
    except KeyboardInterrupt:
        raise AdviceInterrupted(advisor.advice(complete=False)) from None
    return advisor.advice(complete=True)
