"""Maps over (weight on bit, rpm) of axial-torsional runs with the RGD bit.

:func:`axial_map` runs :mod:`torsio.axial.kernel` at every point of the grid, one after
the other, with the options of :func:`torsio.axial.transient.simulate_axial` (no signals
kept), and returns :class:`AxialMap`: S_SS, axial severity, stuck and off-bottom
fractions, mean ROP [m/s] and mean MSE [Pa], each of shape (rpm, wob) like torsio's
severity maps (``severity[i][j]`` at ``rpm[i]``, ``wob[j]``), and optionally the linear
growth rate of the 2-DOF model.

Examples
--------
>>> from torsio.axial.assembly import rgd_two_dof_example
>>> from torsio.axial.rgd import rgd_example
>>> grid = axial_map(rgd_two_dof_example(), rgd_example(), [90e3, 110e3], [60.0, 120.0],
...                  duration=20.0, window=10.0)
>>> grid.severity.shape
(2, 2)
>>> sorted(grid.to_dict())[:4]
['axial_severity', 'duration', 'growth_rate', 'mse']
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.axial.assembly import DrillingAssembly
from torsio.axial.rgd import RGDBit
from torsio.axial.transient import run_times, simulate_axial
from torsio.axial.wave_assembly import WaveDrillingAssembly
from torsio.errors import ConfigError

__all__ = ["AxialMap", "axial_map"]

_FIELDS = (
    "severity",
    "axial_severity",
    "stick_fraction",
    "off_bottom_fraction",
    "rop_mean",
    "mse_mean",
)


@attrs.frozen(eq=False)
class AxialMap:
    """Window outputs over a (rpm, wob) grid; every array has shape (len(rpm), len(wob)).

    Attributes
    ----------
    wob, rpm : ndarray
        The grid [N], [rev/min].
    severity, axial_severity, stick_fraction, off_bottom_fraction : ndarray
        As in :class:`torsio.axial.run_setup.WindowSummary`.
    rop, mse : ndarray
        Mean ROP [m/s] and mean MSE [Pa] over the window (MSE inf where the bit did not
        advance).
    growth_rate : ndarray or None
        The linear growth rate [1/s] of steady drilling (2-DOF model, when asked).
    duration, window : float
        Run length and window [s].
    """

    wob: NDArray[np.float64]
    rpm: NDArray[np.float64]
    severity: NDArray[np.float64]
    axial_severity: NDArray[np.float64]
    stick_fraction: NDArray[np.float64]
    off_bottom_fraction: NDArray[np.float64]
    rop: NDArray[np.float64]
    mse: NDArray[np.float64]
    growth_rate: NDArray[np.float64] | None
    duration: float
    window: float

    def to_dict(self) -> dict[str, Any]:
        """DESIGN.md's keys for ``torsio map --json`` with axial dynamics: ``wob``, ``rpm``,
        ``severity``, ``rop``, ``mse`` (null where not finite) and the other fractions."""

        def plain(array: NDArray[np.float64] | None) -> Any:
            if array is None:
                return None
            return [[float(x) if np.isfinite(x) else None for x in row] for row in array]

        return {
            "wob": self.wob.tolist(),
            "rpm": self.rpm.tolist(),
            "severity": plain(self.severity),
            "axial_severity": plain(self.axial_severity),
            "stick_fraction": plain(self.stick_fraction),
            "off_bottom_fraction": plain(self.off_bottom_fraction),
            "rop": plain(self.rop),
            "mse": plain(self.mse),
            "growth_rate": plain(self.growth_rate),
            "duration": self.duration,
            "steady_window": self.window,
        }


def axial_map(
    assembly: DrillingAssembly | WaveDrillingAssembly,
    bit: RGDBit,
    wobs: Sequence[float],
    rpms: Sequence[float],
    *,
    growth_rate: bool = False,
    **options: Any,
) -> AxialMap:
    """Run :func:`~torsio.axial.transient.simulate_axial` at every (rpm, wob) of the grid,
    no signals kept.

    ``options`` are its run options (``duration``, ``window``, ``start``,
    ``perturbation``, ``step``, ``steps_per_period``); ``growth_rate`` adds the linear
    growth rate of the 2-DOF model at each point.
    """
    wob_grid = np.asarray(wobs, dtype=float).reshape(-1)
    rpm_grid = np.asarray(rpms, dtype=float).reshape(-1)
    duration, window = run_times(
        assembly, options.pop("duration", None), options.pop("window", None)
    )
    shape = (rpm_grid.size, wob_grid.size)
    out = {name: np.zeros(shape) for name in _FIELDS}
    rates = np.zeros(shape) if growth_rate else None
    if growth_rate and not (assembly.is_two_dof and options.get("bit_rotation") is None):
        raise ConfigError(
            "growth_rate", "the linear growth rate is of the 2-DOF model (its chain turning) only"
        )
    for i, rpm in enumerate(rpm_grid):
        for j, wob in enumerate(wob_grid):
            run = simulate_axial(
                assembly,
                bit,
                float(wob),
                float(rpm),
                duration=duration,
                window=window,
                samples=0,
                growth_rate=growth_rate,
                **options,
            )
            for name in _FIELDS:
                out[name][i, j] = getattr(run.summary, name)
            if rates is not None:
                rates[i, j] = run.growth_rate
    return AxialMap(
        wob=wob_grid,
        rpm=rpm_grid,
        severity=out["severity"],
        axial_severity=out["axial_severity"],
        stick_fraction=out["stick_fraction"],
        off_bottom_fraction=out["off_bottom_fraction"],
        rop=out["rop_mean"],
        mse=out["mse_mean"],
        growth_rate=rates,
        duration=duration,
        window=window,
    )
