"""Results of a torque-and-drag calculation: hookloads, surface torques, and tension,
torque and normal force along the string for each operation.

Tension is the effective (buoyed) tension [N], positive in tension, negative in
compression; at the surface it is the hookload. Torque [N m] is the torque in the string.

Examples
--------
>>> import numpy as np
>>> results = TorqueDragResults(
...     md=np.array([0.0, 1000.0]), tension=np.array([[2e5, 1e5, 1.5e5, 5e4], [0, 0, 0, -1e5]]),
...     torque=np.array([[8e3, 1.1e4], [0.0, 3e3]]), normal_force=np.zeros((2, 4)))
>>> results.hookload_trip_out, results.surface_torque_on_bottom, results.neutral_point_md
(200000.0, 11000.0, 333.3333333333333)
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import attrs
import numpy as np

__all__ = ["OPERATIONS", "TorqueDragResults"]

OPERATIONS = ("trip_out", "trip_in", "rotating", "on_bottom")
"""The columns of :attr:`TorqueDragResults.tension`: tripping out, tripping in, rotating
off bottom, rotating on bottom (with the weight and torque on bit)."""


@attrs.frozen(repr=False, eq=False)
class TorqueDragResults:
    """Tension, torque and normal force along a string in a well, four operations.

    Attributes
    ----------
    md : ndarray
        Measured depths [m] of the cell boundaries, from the string's top to the bit.
    tension : ndarray, shape (len(md), 4)
        Effective tension [N] for each of :data:`OPERATIONS`.
    torque : ndarray, shape (len(md), 2)
        Torque in the string [N m], rotating off bottom and on bottom.
    normal_force : ndarray, shape (len(md), 4)
        Contact force per metre string on borehole [N/m], each operation.
    wob, bit_torque : float
        Weight [N] and torque [N m] on bit of the on-bottom case.
    bit_torque_source : str
        Where ``bit_torque`` comes from (given, or the bit law's at the operating point).
    string_top_md : float
        Measured depth of the string's top [m]: 0, the string hangs from the rig floor.
    buoyed_weight : float
        Sum of the buoyed weight of the string [N] (its hookload in a vertical hole).
    normal_force_model : str
        ``soft-string`` or ``gravity``.
    friction : float or None
        The sliding friction factor that replaced the well's, if any.
    break_off : BreakOff or None
        The break-off torque and twist with the well's static friction
        (:func:`torsio.well.break_off.break_off`), when computed.
    """

    md: np.ndarray
    tension: np.ndarray
    torque: np.ndarray
    normal_force: np.ndarray
    wob: float = 0.0
    bit_torque: float = 0.0
    string_top_md: float = 0.0
    bit_torque_source: str = "given"
    buoyed_weight: float = float("nan")
    normal_force_model: str = "soft-string"
    friction: float | None = None
    break_off: Any = None

    def __repr__(self) -> str:
        return (
            f"TorqueDragResults(md {self.md[0]:g}-{self.md[-1]:g} m, hookloads "
            f"out {self.hookload_trip_out / 1e3:.1f} kN, in {self.hookload_trip_in / 1e3:.1f} kN, "
            f"rotating {self.hookload_rotating / 1e3:.1f} kN; surface torque "
            f"{self.surface_torque_rotating / 1e3:.2f} kN m)"
        )

    @property
    def hookload_trip_out(self) -> float:
        """Hookload tripping out (pick-up) [N]."""
        return float(self.tension[0, 0])

    @property
    def hookload_trip_in(self) -> float:
        """Hookload tripping in (slack-off) [N]."""
        return float(self.tension[0, 1])

    @property
    def hookload_rotating(self) -> float:
        """Hookload rotating off bottom [N]."""
        return float(self.tension[0, 2])

    @property
    def hookload_on_bottom(self) -> float:
        """Hookload rotating on bottom [N] (the off-bottom one less about the WOB)."""
        return float(self.tension[0, 3])

    @property
    def surface_torque_rotating(self) -> float:
        """Torque at the string's top rotating off bottom [N m]."""
        return float(self.torque[0, 0])

    @property
    def surface_torque_on_bottom(self) -> float:
        """Torque at the string's top rotating on bottom [N m]."""
        return float(self.torque[0, 1])

    @property
    def neutral_point_md(self) -> float | None:
        """Measured depth [m] where the on-bottom tension changes sign (compression below),
        the shallowest such point; None when the string is nowhere in compression."""
        t = self.tension[:, 3]
        below = np.nonzero((t[:-1] >= 0.0) & (t[1:] < 0.0))[0]
        if below.size == 0:
            return None
        j = int(below[0])
        return float(self.md[j] + (self.md[j + 1] - self.md[j]) * t[j] / (t[j] - t[j + 1]))

    @property
    def all_in_compression(self) -> bool:
        """Whether the whole string is in compression on bottom (the top too: the weight on
        bit exceeds what the string's weight and drag hold, a negative hookload)."""
        return bool(np.all(self.tension[:-1, 3] < 0.0))

    @property
    def warnings(self) -> tuple[str, ...]:
        """What limits the meaning of the result (JSON ``warnings``, and stderr)."""
        if not self.all_in_compression:
            return ()
        return (
            f"the whole string is in compression on bottom (hookload "
            f"{self.hookload_on_bottom / 1e3:.4g} kN, weight on bit {self.wob / 1e3:.4g} kN): "
            "a string pushed from the top buckles, which soft-string torque and drag does not "
            "model",
        )

    @property
    def bit_md(self) -> float:
        """Measured depth of the bit [m]: the string's length along the survey."""
        return float(self.md[-1])

    def to_dict(self) -> dict[str, Any]:
        """The keys of ``torsio drag --json`` (DESIGN.md), SI units, and more."""
        return {
            "hookload_trip_out": self.hookload_trip_out,
            "hookload_trip_in": self.hookload_trip_in,
            "hookload_rotating": self.hookload_rotating,
            "surface_torque_rotating": self.surface_torque_rotating,
            "hookload_on_bottom": self.hookload_on_bottom,
            "surface_torque_on_bottom": self.surface_torque_on_bottom,
            "wob": self.wob,
            "bit_torque": self.bit_torque,
            "bit_torque_source": self.bit_torque_source,
            "neutral_point_md": self.neutral_point_md,
            "all_in_compression": self.all_in_compression,
            "warnings": list(self.warnings),
            "string_top_md": self.string_top_md,
            "bit_md": self.bit_md,
            "buoyed_weight": self.buoyed_weight,
            "normal_force_model": self.normal_force_model,
            "friction_override": self.friction,
            "md": self.md.tolist(),
            "tension_rotating": self.tension[:, 2].tolist(),
            "torque_rotating": self.torque[:, 0].tolist(),
            "tension_trip_out": self.tension[:, 0].tolist(),
            "tension_trip_in": self.tension[:, 1].tolist(),
            "tension_on_bottom": self.tension[:, 3].tolist(),
            "torque_on_bottom": self.torque[:, 1].tolist(),
            "normal_force_rotating": self.normal_force[:, 2].tolist(),
            **({} if self.break_off is None else self.break_off.to_dict()),
        }

    def plot(self, path: str | Path | None = None, ax: Any = None, units: Any = None) -> Any:
        """Tension and torque against measured depth, depth increasing downward.

        ``ax``: two matplotlib axes (tension, torque) to draw into; ``path`` writes the
        figure (format by suffix); ``units``: a :class:`~torsio.display_units.DisplayUnits`
        (default SI: kN, kN m, m). Returns the figure. Needs matplotlib (``torsio[plot]``).
        """
        from torsio.display_units import DisplayUnits
        from torsio.errors import ConfigError
        from torsio.plotting.figures import pyplot, save_figure

        if ax is not None:
            if len(ax) != 2:
                raise ConfigError("ax", f"expected two matplotlib axes, got {len(ax)}")
            axes, figure = ax, ax[0].figure
        else:
            figure, axes = pyplot().subplots(1, 2, sharey=True, figsize=(9.0, 6.0))
        units = DisplayUnits() if units is None else units
        md = units.value("length", self.md)
        labels = ("tripping out", "tripping in", "rotating off bottom", "rotating on bottom")
        for column, label in enumerate(labels):
            axes[0].plot(units.value("force", self.tension[:, column]), md, label=label)
        axes[0].axvline(0.0, color="0.6", linewidth=0.8)
        axes[1].plot(units.value("torque", self.torque[:, 0]), md, label=labels[2], color="C2")
        axes[1].plot(units.value("torque", self.torque[:, 1]), md, label=labels[3], color="C3")
        axes[0].set_xlabel(units.header("effective tension", "force"))
        axes[1].set_xlabel(units.header("torque", "torque"))
        axes[0].set_ylabel(units.header("measured depth", "length"))
        if not axes[0].yaxis_inverted():
            axes[0].invert_yaxis()
        for axis in axes:
            axis.grid(True, alpha=0.3)
            axis.legend(fontsize="small")
        if path is not None:
            save_figure(figure, path)
        return figure
