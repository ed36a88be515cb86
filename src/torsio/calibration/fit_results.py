"""The results of a fit to recordings: values, uncertainties, residual, record and model.

Examples
--------
>>> import numpy as np
>>> from torsio.calibration.uncertainty import ParameterSpread
>>> spread = ParameterSpread(0.002, 0.002, 0.002, (0.296, 0.304), "jacobian", True)
>>> record = RecordingFit("rig.csv", np.array([0.0, 1.0]), np.array([1.0, 2.0]),
...                       np.array([1.0, 2.0]), 0.0)
>>> results = FitResults(("friction_dynamic",), (0.3,), (0.31,), (0.25,), (spread,), 0.0,
...                      (record,), "torque", "recorded", 12, 1.5, "converged")
>>> results.to_dict()["parameters"], results.to_dict()["uncertainty"]
({'friction_dynamic': 0.3}, {'friction_dynamic': 0.002})
>>> results.parameters["friction_dynamic"]
0.3
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import attrs
import numpy as np

from torsio.calibration.uncertainty import ParameterSpread

__all__ = ["NEARLY_AS_GOOD", "Alternative", "FitResults", "RecordingFit"]

NEARLY_AS_GOOD = 4.0
"""An alternative minimum whose misfit exceeds the fit's by at most this chi^2 (two sigma)
is nearly as good: the data do not choose between them."""


@attrs.frozen
class Alternative:
    """Another minimum of the misfit the global stage found: its values (the fit's
    ``names`` order) and how much worse it fits, in chi^2 (the misfit's rise over s^2 tau,
    :mod:`torsio.calibration.uncertainty`)."""

    values: tuple[float, ...]
    delta_chi2: float


@attrs.frozen(eq=False)
class RecordingFit:
    """One recording against the fitted model.

    Attributes
    ----------
    name : str
        The recording's name (its file).
    time, surface_torque, model_torque : ndarray
        Sample times [s], the recorded and the model's surface torque there [N m].
    residual : float
        RMS of model minus record [N m].
    """

    name: str
    time: np.ndarray
    surface_torque: np.ndarray
    model_torque: np.ndarray
    residual: float


@attrs.frozen(eq=False)
class FitResults:
    """A fit of configuration parameters to recordings (``fit_recordings``).

    Attributes
    ----------
    names : tuple of str
        The fitted configuration keys.
    values, start, configured : tuple of float
        Fitted values, the closed-form starting values, the configuration's values.
    uncertainty : tuple of ParameterSpread
        Per parameter: sigma, the two-sigma interval, how it was found, identifiability.
    residual : float
        RMS of model minus record over every sample of every recording [N m].
    recordings : tuple of RecordingFit
    objective, top : str
        What was compared (``torque``, ``features``) and what drove the top.
    model : str
        The model the fit ran, in words
        (:attr:`~torsio.calibration.parameters.SystemFamily.description`).
    runs : int
        Model runs the fit took; ``seconds`` its wall-clock time [s].
    message : str
        The optimizer's word on its convergence.
    correlation : ndarray or None
        Correlation of the fitted parameters from the Jacobian (``names`` order), which
        the Monte Carlo draws carry (:mod:`torsio.calibration.monte_carlo`).
    warnings : tuple of str
        What limits the meaning of the fit (spikes left out, a record that cannot inform a
        parameter); the command line prints each on stderr.
    alternatives : tuple of Alternative
        The other minima the global stage found (:mod:`torsio.calibration.global_stage`).
    """

    names: tuple[str, ...]
    values: tuple[float, ...]
    start: tuple[float, ...]
    configured: tuple[float, ...]
    uncertainty: tuple[ParameterSpread, ...]
    residual: float
    recordings: tuple[RecordingFit, ...]
    objective: str
    top: str
    runs: int
    seconds: float
    message: str
    correlation: np.ndarray | None = None
    warnings: tuple[str, ...] = ()
    alternatives: tuple[Alternative, ...] = ()
    model: str = ""

    def __repr__(self) -> str:
        fitted = ", ".join(
            f"{n} {v:.4g} +- {s.sigma:.2g}"
            for n, v, s in zip(self.names, self.values, self.uncertainty, strict=True)
        )
        return f"FitResults({fitted}; residual {self.residual:.4g} N m)"

    @property
    def parameters(self) -> dict[str, float]:
        """Fitted value by name."""
        return dict(zip(self.names, self.values, strict=True))

    @property
    def weak(self) -> tuple[str, ...]:
        """The parameters the data do not pin down (weakly identifiable)."""
        return tuple(
            n for n, s in zip(self.names, self.uncertainty, strict=True) if not s.identifiable
        )

    def notes(self) -> list[str]:
        """Plain sentences: where the fit started, what the data do not pin down."""
        started = ", ".join(f"{n} {v:.4g}" for n, v in zip(self.names, self.start, strict=True))
        notes = [
            f"started from the closed forms (break-over and sliding torque of the record): "
            f"{started}"
        ]
        for name, spread in zip(self.names, self.uncertainty, strict=True):
            low, high = spread.interval
            if not spread.identifiable:
                notes.append(
                    f"{name} is weakly identifiable from these recordings: the data allow "
                    f"{low:.4g} to {high:.4g} (two sigma)"
                )
            elif spread.method == "profile":
                notes.append(f"{name}: the misfit is not smooth there; its sigma is the profile's")
            if spread.profile is not None:
                notes.append(
                    f"{name}: sigma {spread.sigma:.2g} = statistical "
                    f"{spread.sigma_statistical:.2g}, between recordings "
                    f"{spread.sigma_recordings:.2g}, grid {spread.sigma_grid:.2g}, speed record "
                    f"{spread.sigma_speed_record:.2g} (in quadrature)"
                )
        for other in self.alternatives:
            if other.delta_chi2 <= NEARLY_AS_GOOD:
                values = ", ".join(
                    f"{n} {v:.4g}" for n, v in zip(self.names, other.values, strict=True)
                )
                notes.append(
                    f"a second minimum nearly as good (chi^2 {other.delta_chi2:.2g} above): "
                    f"{values}; the data do not choose between them"
                )
        return notes

    def to_dict(self) -> dict[str, Any]:
        """Plain data for JSON: ``parameters``, ``uncertainty`` (one sigma), ``residual``
        (RMS surface torque, N m), ``recordings``, and ``start``, ``interval``,
        ``identifiable``, ``uncertainty_method``, ``interval_method`` (how each two-sigma
        interval was found), ``uncertainty_parts`` (the statistical, between-recordings
        and grid parts of each sigma, and each recording's own value), ``alternatives``
        (other minima: values and chi^2 above the fit), ``objective``, ``top``, ``model``
        (what the fit ran, in words), ``notes``,
        ``correlation`` (name to name, from the Jacobian; None if not computed) and
        ``warnings``."""
        spreads = dict(zip(self.names, self.uncertainty, strict=True))
        return {
            "parameters": self.parameters,
            "uncertainty": {n: s.sigma for n, s in spreads.items()},
            "residual": self.residual,
            "recordings": [
                {
                    "name": r.name,
                    "samples": int(r.time.size),
                    "duration": float(r.time[-1] - r.time[0]),
                    "residual": r.residual,
                }
                for r in self.recordings
            ],
            "start": dict(zip(self.names, self.start, strict=True)),
            "configured": dict(zip(self.names, self.configured, strict=True)),
            "interval": {n: list(s.interval) for n, s in spreads.items()},
            "identifiable": {n: s.identifiable for n, s in spreads.items()},
            "uncertainty_method": {n: s.method for n, s in spreads.items()},
            "interval_method": {n: s.interval_method for n, s in spreads.items()},
            "uncertainty_parts": {
                n: {
                    "statistical": s.sigma_statistical,
                    "recordings": s.sigma_recordings,
                    "grid": s.sigma_grid,
                    "speed_record": s.sigma_speed_record,
                    "recording_values": list(s.recording_values),
                }
                for n, s in spreads.items()
            },
            "alternatives": [
                {
                    "parameters": dict(zip(self.names, a.values, strict=True)),
                    "delta_chi2": a.delta_chi2,
                }
                for a in self.alternatives
            ],
            "objective": self.objective,
            "top": self.top,
            "model": self.model,
            "runs": self.runs,
            "seconds": self.seconds,
            "notes": self.notes(),
            "correlation": None
            if self.correlation is None
            else {
                a: {b: float(self.correlation[i, j]) for j, b in enumerate(self.names)}
                for i, a in enumerate(self.names)
            },
            "warnings": list(self.warnings),
        }

    def rows(self) -> list[tuple[str, str, str, str, str]]:
        """Table rows: name, fitted, one sigma, two-sigma interval, start."""
        return [
            (
                n,
                f"{v:.5g}",
                f"{s.sigma:.2g}",
                f"{s.interval[0]:.4g} .. {s.interval[1]:.4g}",
                f"{st:.4g}",
            )
            for n, v, s, st in zip(
                self.names, self.values, self.uncertainty, self.start, strict=True
            )
        ]

    def plot(self, path: str | Path | None = None, ax: Any = None) -> Any:
        """Record against model, surface torque [kN m] against time with each break-over
        marked, one panel per recording, and below them each parameter's profile with its
        interval (:mod:`torsio.plotting.fit_plots`); on ``ax``, the torques alone. ``path``
        writes the figure (format by suffix). Returns the figure. Needs matplotlib
        (``pip install 'torsio[plot]'``)."""
        from torsio.plotting.fit_plots import plot_fit

        return plot_fit(self, path, ax)
