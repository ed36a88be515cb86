"""The axial channels of a run: :class:`AxialChannels`, and the run's results.

:func:`torsio.analysis.axial_transient.simulate_axial` returns the results every run has
(:class:`~torsio.analysis.transient_results.TransientResults`, made by
:func:`axial_results`) with these channels in its ``axial``: the window's outputs
(:class:`~torsio.analysis.axial_window.WindowSummary`), the steady state, the growth rate,
the signals by name (:data:`torsio.solvers.axial_layouts.SAMPLE_COLUMNS`), and the run's JSON
(:meth:`AxialChannels.to_dict`, DESIGN.md's keys beside every run's), CSV and terminal
table. The plot (:func:`torsio.plotting.transient_plot.plot_transient`) and the rig
recording (:meth:`torsio.calibration.recording.Recording.from_transient`) read the
common signals.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.analysis.axial_energy import EnergyBalance
from torsio.analysis.axial_window import WindowSummary
from torsio.analysis.run_facts import RunFacts
from torsio.analysis.transient_results import TransientResults
from torsio.axial.steady import SteadyDrilling
from torsio.model.axial_assembly import assembly_summary
from torsio.output_files import save_columns
from torsio.solvers import axial_layouts as slot
from torsio.units import RPM_TO_RAD_S

__all__ = ["SCHEME", "AxialChannels", "axial_results", "channels_of", "run_rows"]

_SUMMARY_NAMES = frozenset(attrs.fields_dict(WindowSummary))

SCHEME = "semi-implicit Euler, set-valued contacts at the velocity level (Moreau)"
"""The axial engine's fixed-step scheme (:mod:`torsio.solvers.axial_kernel`)."""


HELD_KINDS = ("constant-speed", "recorded")
"""The built-in top drives without a node, for a run saved before its channels kept
``has_top_drive_node``."""


@attrs.frozen(eq=False)
class AxialChannels:
    """The axial channels and outputs of one axial-torsional run
    (:attr:`TransientResults.axial <torsio.analysis.transient_results.TransientResults>`).

    Attributes
    ----------
    wob, rpm : float
        W₀ [N] and Ω₀ [rev/min].
    steady : SteadyDrilling
        The steady drilling state of (W₀, Ω₀).
    summary : WindowSummary
        The window's outputs (also as attributes: ``severity``, ``rop_mean`` ...).
    growth_rate : float or None
        The rightmost root's real part [1/s] of the linearization about the steady state
        (a distributed pipe's from its exact characteristic equation,
        :func:`torsio.axial.wave_stability.distributed_stability`; None with a prescribed
        bit rotation or when not asked).
    step, duration, window : float
        The step h, the run's length and its window [s].
    start : str
        ``"rest"`` or ``"steady"``.
    samples : ndarray (k, 13)
        The bit's and the top drive's signals, columns
        :data:`torsio.solvers.axial_layouts.SAMPLE_COLUMNS`.
    top_drive : str
        The top drive's kind (``"constant-speed"``: the top held at Ω₀).
    has_set_speed : bool
        Whether the top drive has a set speed (False: a torque-driven top; ``rpm`` is then
        the speed of the steady state the run was given, which S_SS is read against).
    has_top_drive_node : bool
        Whether the top drive is a node with inertia (its boundary not held), as every
        run's facts say it (:class:`~torsio.analysis.run_facts.RunFacts`).
    stability_of_held_top : bool
        Whether ``growth_rate`` is that of the top held at Ω₀ while the run's top drive is
        not held: a controller other than a PI speed loop, which the linearization does not
        take (:func:`torsio.axial.linearization.speed_loop`).
    energy : EnergyBalance or None
        The lumped chain's energy balance over the run
        (:mod:`torsio.analysis.axial_energy`; None for the distributed pipe and a prescribed
        rotation).
    contact_switches : int
        Stick ↔ slip switches of the string's contacts over the run (0 without them).
    string_friction_work : float
        The work of the friction along the string over the run [J] (0 without it).
    string_contacts, steady_friction : dict or None
        The contacts' totals (:meth:`~torsio.well.axial_contacts.AxialContacts.describe`)
        and what they take in steady drilling
        (:meth:`~torsio.axial.steady_friction.SteadyFriction.to_dict`); None without them.
    solver, model, bit : dict
        The engine (``engine``, ``method``, ``scheme``, ``step``), the assembly
        (:func:`~torsio.model.axial_assembly.assembly_description`) and the bit's law.
    stick_threshold : float
        The bit counted stuck while |Ω_b| < stick_threshold Ω₀ (0 in a run saved before
        the threshold: stuck at Ω_b = 0 exactly).

    Every column of :attr:`samples` is an attribute by name (``run.axial.bit_weight``,
    ``run.axial.depth_of_cut`` ...), and so is every entry of :attr:`summary`
    (``run.axial.rop_mean``).
    """

    wob: float
    rpm: float
    steady: SteadyDrilling
    summary: WindowSummary
    growth_rate: float | None
    step: float
    duration: float
    window: float
    start: str
    samples: NDArray[np.float64]
    top_drive: str = "constant-speed"
    has_set_speed: bool = True
    has_top_drive_node: bool = False
    stability_of_held_top: bool = False
    energy: EnergyBalance | None = None
    contact_switches: int = 0
    string_friction_work: float = 0.0
    string_contacts: dict[str, Any] | None = None
    steady_friction: dict[str, Any] | None = None
    solver: dict[str, Any] = attrs.field(factory=dict)
    model: dict[str, Any] = attrs.field(factory=dict)
    bit: dict[str, Any] = attrs.field(factory=dict)
    stick_threshold: float = 0.0

    def __getattr__(self, name: str) -> Any:
        """An entry of :attr:`summary` or a column of :attr:`samples` by name."""
        if name in _SUMMARY_NAMES:
            return getattr(self.summary, name)
        if name in slot.SAMPLE_COLUMNS:
            return self.signal(name)
        raise AttributeError(name)

    def signal(self, name: str) -> NDArray[np.float64]:
        """One column of :attr:`samples` by name (e.g. ``"bit_weight"``)."""
        if name not in slot.SAMPLE_COLUMNS:
            raise KeyError(f"{name!r}: an axial run's signals are {', '.join(slot.SAMPLE_COLUMNS)}")
        return self.samples[:, slot.SAMPLE_COLUMNS.index(name)]

    def facts(self) -> RunFacts:
        """The run's operating point, top drive and law, as every run's results read them
        (``rpm``: the set speed, or under a torque-driven top the steady state's; none under
        a recording, whose run reads its mean top speed as a torsional run does)."""
        return RunFacts(
            wob=self.wob,
            rpm=math.nan if self.top_drive == "recorded" else self.rpm,
            has_set_speed=self.has_set_speed,
            top_drive=self.top_drive,
            law=str(self.bit.get("law")),
            has_top_drive_node=self.has_top_drive_node,
        )

    def saved(self) -> tuple[dict[str, Any], NDArray[np.float64]]:
        """Plain data of every field but the samples, and the samples: what a saved run
        keeps (:meth:`~torsio.analysis.transient_results.TransientResults.save`,
        :meth:`from_saved`)."""
        return attrs.asdict(self, filter=lambda field, _: field.name != "samples"), self.samples

    @classmethod
    def from_saved(cls, data: dict[str, Any], samples: NDArray[np.float64]) -> AxialChannels:
        """The channels of :meth:`saved`'s ``data`` and ``samples``."""
        energy = data["energy"]
        if "has_top_drive_node" not in data:  # saved before runs kept it: the built-in kinds
            data = {**data, "has_top_drive_node": data["top_drive"] not in HELD_KINDS}
        return cls(**{
            **data,
            "steady": SteadyDrilling(**data["steady"]),
            "summary": WindowSummary(**data["summary"]),
            "energy": None if energy is None else EnergyBalance(**energy),
            "samples": samples,
        })  # fmt: skip

    def window_rows(self) -> NDArray[np.bool_]:
        """The sample rows inside the steady window."""
        return self.signal("time") >= self.duration - self.window - 0.5 * self.step

    def top_drive_summary(self) -> dict[str, float | None]:
        """The top drive over the window's samples: ``top_speed_mean`` [rad/s],
        ``surface_torque_min``, ``surface_torque_max``, ``mean_surface_torque``,
        ``mean_motor_torque`` [N m] (window), ``surface_torque_peak`` [N m] (whole run);
        null without samples."""
        keys = ("top_speed_mean", "surface_torque_min", "surface_torque_max",
                "mean_surface_torque", "mean_motor_torque", "surface_torque_peak")  # fmt: skip
        rows = self.window_rows() if self.samples.shape[0] else np.zeros(0, bool)
        if not rows.any():
            return dict.fromkeys(keys)
        surface = self.signal("surface_torque")
        values = (
            self.signal("top_speed")[rows].mean(),
            surface[rows].min(),
            surface[rows].max(),
            surface[rows].mean(),
            self.signal("motor_torque")[rows].mean(),
            surface.max(),
        )
        return {key: float(value) for key, value in zip(keys, values, strict=True)}

    def to_dict(self, series: bool = False) -> dict[str, Any]:
        """The axial run's own JSON keys, beside those of every run
        (:meth:`~torsio.analysis.transient_results.TransientResults.run_keys`), DESIGN.md's:
        ``rop_mean`` (m/s), ``mse_mean`` (Pa; null when the bit did not advance),
        ``off_bottom_fraction``, ``axial_severity``, ``steady_state``, ``growth_rate``, the
        top drive's (:meth:`top_drive_summary`, ``stability_of_held_top``), ``model``,
        ``bit`` and more (``mean_bit_torque``: ``torque_mean``, as every run names it);
        ``series=True`` adds the signals."""
        data: dict[str, Any] = {}
        for key, value in attrs.asdict(self.summary).items():
            data[key] = value if math.isfinite(value) else None
        data.update(self.top_drive_summary())
        data["mean_bit_torque"] = data["torque_mean"]  # under every run's name (run_keys)
        data.update(
            steady_state=self.steady.to_dict(),
            growth_rate=self.growth_rate,
            step=self.step,
            duration=self.duration,
            steady_window=self.window,
            start=self.start,
            stability_of_held_top=self.stability_of_held_top,
            string_friction_work=self.string_friction_work,
            contact_switches=self.contact_switches,
            string_contacts=self.string_contacts,
            steady_friction=self.steady_friction,
            energy_balance=self.energy.to_dict() if self.energy is not None else None,
            model=self.model,
            bit=self.bit,
        )
        if series:
            data["series"] = {name: self.signal(name).tolist() for name in slot.SAMPLE_COLUMNS}
        return data

    def to_csv(self, path: str | Path) -> Path:
        """Every signal as CSV, a column per :data:`torsio.solvers.axial_layouts.SAMPLE_COLUMNS`
        named with its unit (``time_s``, ``bit_speed_rad_s``, ``surface_torque_Nm`` ...)."""
        units = zip(slot.SAMPLE_COLUMNS, slot.SAMPLE_UNITS, strict=True)
        names = [f"{name}_{unit}" for name, unit in units]
        return save_columns(path, names, list(self.samples.T))

    def summary_rows(self, data: dict[str, Any], units: Any) -> tuple[str, list[tuple[str, str]]]:
        """The terminal table of the run from its JSON ``data`` (:func:`run_rows`)."""
        return run_rows(data, units)

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"AxialChannels(wob={self.wob:g} N, rpm={self.rpm:g}, S_SS={s.severity:.4g}, "
            f"stuck={s.stick_fraction:.3g}, rop={s.rop_mean * 3600:.4g} m/h)"
        )


def axial_results(channels: AxialChannels, warnings: tuple[str, ...]) -> TransientResults:
    """The results of an axial run: its ``channels``, the common signals read from their
    samples, S_SS and the stuck fraction from the window's every step (the bit stuck while
    |Ω_b| < ``stick_threshold`` Ω₀), and its ``warnings``."""
    column = channels.signal
    summary = channels.summary
    none = np.zeros((channels.samples.shape[0], 0))  # the samples keep the bit and the top
    return TransientResults(
        time=column("time"),
        bit_speed=column("bit_speed"),
        bit_angle=column("bit_angle"),
        node_speeds=none,
        node_twists=none,
        bit_torque=column("bit_torque"),
        surface_torque=column("surface_torque"),
        severity=summary.severity,
        stick_fraction=summary.stick_fraction,
        steady_window=channels.window,
        stick_threshold=channels.stick_threshold,
        solver=channels.solver,
        system=None,
        top_speed=column("top_speed"),
        motor_torque=column("motor_torque"),
        states=none,
        reference_speed=channels.rpm * RPM_TO_RAD_S,
        severity_speed=channels.steady.bit_speed,
        bit_speed_extremes=(summary.bit_speed_max, summary.bit_speed_min),
        warnings=warnings,
        axial=channels,
    )


def channels_of(run: TransientResults) -> AxialChannels:
    """The axial channels of ``run`` (:func:`torsio.analysis.axial_transient.simulate_axial`'s);
    a torsional run, which has none, is refused."""
    if run.axial is None:
        raise TypeError(f"{run!r} is a torsional run: it has no axial channels")
    return run.axial


NO_GROWTH_RATE = "not computed (--growth-rate asks for it)"
"""The growth-rate row of a run that did not find it (too large a chain, --no-growth-rate)."""

TORQUE_LAW_GROWTH_RATE = "none for a law of the torque alone (torsio report: the chain's)"
"""The growth-rate row of a law of the torque alone, whose axial motion rests on the rock."""


def run_rows(data: dict[str, Any], units: Any) -> tuple[str, list[tuple[str, str]]]:
    """The terminal table of an axial run (``torsio simulate``) from its JSON ``data``
    (:meth:`~torsio.analysis.transient_results.TransientResults.to_dict`): title and
    (quantity, value) rows, forces and torques in ``units`` (a
    :class:`~torsio.display_units.DisplayUnits`)."""
    steady = data["steady_state"]
    law = data["bit"]["law"]
    title = f"Axial-torsional run: {assembly_summary(data['model'])}, {law} bit"
    mse = data["mse_mean"]
    rate = data["growth_rate"]
    axial = data["axial_severity"]
    drilling = [  # the RGD bit's own; a law of the torque alone rests on the rock
        ("mean ROP", f"{data['rop_mean'] * 3600:.4g} m/h ({data['rop_mean']:.4g} m/s)"),
        ("mean MSE", "none (the bit did not advance)" if mse is None else f"{mse / 1e6:.4g} MPa"),
        ("steady depth of cut", f"{steady['depth_of_cut'] * 1e3:.4g} mm/rev"),
        ("steady ROP", f"{steady['rop'] * 3600:.4g} m/h ({steady['rop']:.4g} m/s)"),
    ]
    resting = [("axial motion", "at rest on the rock (a law of the torque alone)")]
    steady_mse = [("steady MSE", f"{steady['mse'] / 1e6:.4g} MPa")] if steady["rop"] > 0 else []
    rows = [
        ("weight on bit", units.text("force", data["wob"], ".4g")),
        ("rotary speed", f"{data['rpm']:.4g} rpm"),
        ("run / steady window", f"{data['duration']:.4g} s / last {data['steady_window']:.4g} s"),
        ("start", data["start"]),
        ("S_SS (Eq. 12)", f"{data['severity']:.4f}"),
        ("axial severity", "none (no rate of penetration)" if axial is None else f"{axial:.4f}"),
        (
            "stuck fraction",
            f"{data['stick_fraction']:.3f} (|Ω_b| < {data['stick_threshold']:g} Ω₀)",
        ),
        ("off-bottom fraction", f"{data['off_bottom_fraction']:.3f}"),
        *(drilling if steady["rop"] > 0 else resting),
        ("steady bit torque", units.text("torque", steady["bit_torque"], ".4g")),
        *steady_mse,
        (
            "growth rate (linear)",
            (NO_GROWTH_RATE if steady["rop"] > 0 else TORQUE_LAW_GROWTH_RATE)
            if rate is None
            else f"{rate:.4g} 1/s ({'unstable' if rate > 0 else 'stable'})",
        ),
        ("solver", f"axial engine, fixed step {data['solver']['step'] * 1e3:.4g} ms"),
        ("top drive", data["top_drive"]),
    ]
    if data["stability_of_held_top"]:
        rows.append(("growth rate is of", "the top held at the set speed"))
    contacts = data.get("string_contacts")
    if contacts is not None:
        rows += [
            ("string contacts", f"{contacts['count']} nodes, break-off "
             f"{units.text('torque', contacts['static_torque'], '.4g')}, sliding "
             f"{units.text('torque', contacts['sliding_torque'], '.4g')}"),
            ("string friction work", f"{units.energy(data['string_friction_work'])} "
             f"({data['contact_switches']} stick-slip switches)"),
        ]  # fmt: skip
    if data["top_speed_mean"] is not None:
        rows += [
            ("mean top speed", f"{data['top_speed_mean'] * 60 / (2 * 3.141592653589793):.4g} rpm"),
            ("surface torque (window)",
             f"{units.number('torque', data['surface_torque_min'], '.4g')} to "
             f"{units.text('torque', data['surface_torque_max'], '.4g')}"),
        ]  # fmt: skip
    return title, rows
