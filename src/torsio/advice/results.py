"""What the advisor gives: :class:`Advice`, as JSON (:meth:`Advice.to_dict`, DESIGN.md's
``torsio advise --json`` keys), a terminal table (:meth:`Advice.table`) and a plot
(:func:`torsio.advice.plot.plot_window`)."""

from __future__ import annotations

import math
from typing import Any

import attrs

from torsio.advice.region import Constraints, Region
from torsio.advice.search import Window

__all__ = ["Advice", "Margin"]

BACK_OFF_TEXT = "the WOB steps down from it at its rpm"


@attrs.frozen
class Margin:
    """The recommended point's safety: its Monte Carlo probability of severe stick-slip
    and its distance to the severity boundary.

    Attributes
    ----------
    probability_severe : float or None
        Severe samples / samples (None: no uncertainty given).
    probability_upper : float or None
        The one-sided Clopper-Pearson upper bound of it (``confidence``).
    samples, severe : int
        Monte Carlo samples at the point, and how many were severe.
    level : float
        The probability the point's bound must stay below.
    confidence : float
        Of the bound.
    wob : float or None
        Critical WOB of the point's rpm minus its WOB [N] (None: no severe point there).
    rpm : float or None
        Distance in rpm to the boundary at the point's WOB (None: not in the region).
    backed_off : int
        WOB steps taken down from the window's best point to meet ``level``.
    """

    probability_severe: float | None = None
    probability_upper: float | None = None
    samples: int = 0
    severe: int = 0
    level: float = 0.1
    confidence: float = 0.95
    wob: float | None = None
    rpm: float | None = None
    backed_off: int = 0

    def to_dict(self) -> dict[str, Any]:
        """The margin in kN (``wob_kN``) and rpm, and the Monte Carlo's numbers."""
        return {
            "wob_kN": None if self.wob is None else self.wob / 1e3,
            "wob": self.wob,
            "rpm": self.rpm,
            "probability_severe": self.probability_severe,
            "probability_upper": self.probability_upper,
            "confidence": f"one-sided {self.confidence:.0%} Clopper-Pearson",
            "samples": self.samples,
            "severe_samples": self.severe,
            "level": self.level,
            "backed_off_steps": self.backed_off,
        }


@attrs.frozen(eq=False)
class Advice:
    """The operating window's advice.

    Attributes
    ----------
    recommended : dict or None
        ``wob`` [N], ``rpm``, ``rop`` [m/s], ``mse`` [Pa], ``severity``, ``surface_torque``
        (mean over the window) and ``surface_torque_max`` [N m] of the recommended point
        (None: no admissible point).
    margin : Margin
    window : Window
        The configured top drive's search.
    top_drives : tuple of Window
        Every top drive's search (the configured one first).
    tuning : dict
        The SoftTorque tunings tried: label to share of non-severe coarse points, and the
        ``chosen`` one.
    region, constraints : Region, Constraints
    uncertainty : dict or None
        What was drawn (:meth:`torsio.advice.margin.Uncertainty.to_dict`).
    monte_carlo_runs : int
    elapsed : float
        Seconds.
    complete : bool
        False: interrupted (Ctrl-C); what was run so far.
    model : str
    """

    recommended: dict[str, float] | None
    margin: Margin
    window: Window
    top_drives: tuple[Window, ...]
    tuning: dict[str, Any]
    region: Region
    constraints: Constraints
    uncertainty: dict[str, Any] | None
    monte_carlo_runs: int
    elapsed: float
    complete: bool
    model: str = ""

    @property
    def runs(self) -> int:
        """Every run made: the searches and the Monte Carlo's."""
        tuning_runs = int(self.tuning.get("runs", 0))
        return sum(w.runs for w in self.top_drives) + tuning_runs + self.monte_carlo_runs

    def to_dict(self) -> dict[str, Any]:
        """DESIGN.md's keys: ``recommended`` (with ``probability_severe``), ``constraints``,
        ``top_drives`` (each its ``recommended`` point), and ``margin``, ``region``,
        ``runs``, ``complete``, ``criterion``, ``uncertainty``, ``tuning``, ``elapsed_s``."""
        recommended = None
        if self.recommended is not None:
            recommended = {**self.recommended, "probability_severe": self.margin.probability_severe}
        drives = []
        for window in self.top_drives:
            point = window.point(window.best)
            drives.append(
                {
                    "top_drive": window.label,
                    "recommended": point,
                    "rop": None if point is None else point["rop"],
                    "runs": window.runs,
                    "coarse_runs": window.coarse_runs,
                    "critical_wob": {
                        "rpm": window.rows.tolist(),
                        "wob": [c if math.isfinite(c) else None for c in window.critical],
                    },
                }
            )
        constraints = self.constraints.to_dict()
        return {
            "model": self.model,
            "recommended": recommended,
            "margin": self.margin.to_dict(),
            "constraints": constraints,
            "criterion": constraints["criterion"],
            "region": self.region.to_dict(),
            "top_drives": drives,
            "tuning": self.tuning,
            "uncertainty": self.uncertainty,
            "runs": {
                "total": self.runs,
                "search": self.window.runs,
                "coarse": self.window.coarse_runs,
                "monte_carlo": self.monte_carlo_runs,
                "top_drives": sum(w.runs for w in self.top_drives[1:]),
                "tuning": int(self.tuning.get("runs", 0)),
            },
            "complete": self.complete,
            "elapsed_s": self.elapsed,
        }

    def table(self) -> Any:
        """A rich table: the top drives' recommended points (the configured first); T_s is
        the mean surface torque over the window."""
        from rich.table import Table
        from rich.text import Text

        title = f"Operating window: {self.model}" + ("" if self.complete else " (incomplete)")
        table = Table(title=Text(title))
        table.add_column(Text("top drive"), ratio=1)  # the label wraps, the numbers never
        for name in ("WOB kN", "rpm", "ROP m/h", "MSE MPa", "S_SS", "T_s kN m", "runs"):
            table.add_column(Text(name), justify="right", no_wrap=True, min_width=len(name) // 2)
        for window in self.top_drives:
            point = window.point(window.best)
            if point is None:
                table.add_row(window.label, *["-"] * 6, str(window.runs))
                continue
            table.add_row(
                window.label,
                f"{point['wob'] / 1e3:.4g}",
                f"{point['rpm']:.4g}",
                f"{point['rop'] * 3600:.4g}",
                f"{point['mse'] / 1e6:.4g}",
                f"{point['severity']:.3f}",
                f"{point['surface_torque'] / 1e3:.4g}",
                str(window.runs),
            )
        return table

    def notes(self) -> list[str]:
        """Lines under the table: the recommendation, its margin, the criterion, the runs."""
        lines = [f"criterion: {self.constraints.to_dict()['criterion']} (T_s: mean surface torque)"]
        point, m = self.recommended, self.margin
        if point is None and m.samples:
            lines.append(
                f"no recommended point: the best one and {BACK_OFF_TEXT} do not bring the "
                f"bound of P(severe) below {m.level:g} (last: {m.severe}/{m.samples} severe)"
            )
        elif point is None:
            lines.append("no admissible point in the region")
        else:
            lines.append(
                f"recommended ({self.window.label}): WOB {point['wob'] / 1e3:.4g} kN, "
                f"{point['rpm']:.4g} rpm, ROP {point['rop'] * 3600:.4g} m/h"
            )
            kn = "-" if m.wob is None else f"{m.wob / 1e3:.3g} kN"
            rpm = "-" if m.rpm is None else f"{m.rpm:.3g} rpm"
            lines.append(f"margin to S_SS = {self.constraints.severity:g}: {kn}, {rpm}")
            if m.probability_severe is not None:
                lines.append(
                    f"P(severe) = {m.severe}/{m.samples} = {m.probability_severe:.3g} "
                    f"(upper bound {m.probability_upper:.3g}, {m.confidence:.0%} Clopper-Pearson; "
                    f"level {m.level:g})"
                )
        lines.append(
            f"runs: {self.runs} ({self.window.coarse_runs} coarse, {self.window.runs} for the "
            f"configured top drive, {self.monte_carlo_runs} Monte Carlo); {self.elapsed:.1f} s"
            + ("" if self.complete else "; interrupted: incomplete")
        )
        return lines
