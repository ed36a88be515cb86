"""Axial dynamics from a configuration: the assembly, the RGD bit and the run options.

A configuration has axial dynamics when ``[chain]`` gives ``masses`` (each node also moves
axially) or a ``[[section]]`` string has a law that declares ``needs_axial``, ``[bit_rock]
law = "rgd"``, or an ``[axial]`` table (its axial data from E, ρ and the sections). Any
registered law runs on a chain: the RGD bit, or a law of the torque alone (Tucker-Wang, a
plugin's), whose axial motion rests on the rock under the weight on bit
(:class:`~torsio.physics.torque_law_bit.TorqueLawBit`).
:func:`chain_axial` and :func:`torsio.config.axial_string.string_axial` build an
:class:`AxialConfig` that
:func:`torsio.analysis.axial_transient.simulate_axial` and
:func:`torsio.analysis.axial_maps.axial_map` run:
a lumped chain (the file's discretizer with axial rows, elements of at most
``[axial] element_length``), or
with ``[discretization] strategy = "wave"`` the distributed pipe
(a :class:`~torsio.model.wave.WaveModel` with axial rows), which takes no element
length and no damping (both refused by key).

Examples
--------
>>> from torsio.examples import rgd_two_dof_config
>>> axial = rgd_two_dof_config().axial
>>> axial.assembly.dofs, axial.hook, axial.bit.blades
(1, 'weight', 4)
>>> sorted(axial.run_options().items())  # doctest: +NORMALIZE_WHITESPACE
[('perturbation', 0.001), ('start', 'rest'), ('step', None), ('steps_per_period', 100),
 ('stick_threshold', 0.1), ('string', None), ('top_drive', None)]
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, cast

import attrs
import numpy as np

from torsio.analysis.severity import DEFAULT_STICK_THRESHOLD
from torsio.axial.rgd import RGDBit, rgd_from_table
from torsio.config.chain import ChainConfig, _values
from torsio.config.configuration import BitRockConfig, bit_radius
from torsio.config.tables import _positive_number, _string, _table
from torsio.errors import ConfigError
from torsio.model.axial_assembly import DEFAULT_ELEMENT_LENGTH, hook_of, is_two_dof
from torsio.model.axial_rows import AxialRows
from torsio.model.drillstring import DrillString
from torsio.model.lumped import LumpedModel
from torsio.model.wave import WaveModel
from torsio.physics.torque_law_bit import AxialBit, TorqueLawBit

__all__ = [
    "AXIAL_SIMULATION_KEYS",
    "AxialConfig",
    "axial_law_from_table",
    "chain_axial",
]

AXIAL_KEYS = {"hook", "steps_per_period", "element_length"}
"""Keys of the ``[axial]`` table."""
AXIAL_SIMULATION_KEYS = {"start", "perturbation", "step"}
"""``[simulation]`` keys of the axial engine only."""
TORSIONAL_ONLY_SIMULATION_KEYS = ("method", "rtol", "atol", "output_step")
"""``[simulation]`` keys the fixed-step axial engine has no use for (refused)."""


@attrs.frozen(eq=False)
class AxialConfig:
    """The axial dynamics of a configuration, validated.

    Attributes
    ----------
    assembly : LumpedModel or WaveModel
        The lumped nodes that turn and move axially, the bit on the last one (a chain with
        axial rows); or the distributed pipe above the rigid BHA (``[discretization]
        strategy = "wave"``).
    bit : RGDBit or TorqueLawBit
        The RGD bit of ``[bit_rock]``, or a law of the torque alone on the bit's radius
        (``[chain] masses``, or a string with ``[axial]``).
    start : str
        ``"rest"`` or ``"steady"`` (``[simulation] start``).
    perturbation : float
        Relative raise of the bit speed on a steady start (``[simulation] perturbation``).
    step : float or None
        Largest time step [s] (``[simulation] step``; None: the engine's rule).
    steps_per_period : int
        Steps per period of the fastest node frequency (``[axial] steps_per_period``).
    stick_threshold : float
        The bit stuck while |Ω_b| < stick_threshold Ω₀ (``[simulation] stick_threshold``).
    top_drive : top drive or None
        The ``[top_drive]`` (None: absent, the top held at Ω₀).
    string : DrillString or None
        The ``[[section]]`` string the assembly was built from (None for ``[chain]``).
    lumped_twin : LumpedModel or None
        With the distributed pipe: the lumped chain of the same sections in elements of at
        most :data:`DEFAULT_ELEMENT_LENGTH`, on which its linear stability is computed
        (the distributed pipe has no linearization yet); None with a lumped assembly.
    contacts : AxialContacts or None
        The string's contacts with the ``[well]`` (:mod:`torsio.config.axial_well`).
    """

    assembly: LumpedModel | WaveModel
    bit: AxialBit
    start: str = "rest"
    perturbation: float = 1e-3
    step: float | None = None
    steps_per_period: int = 100
    stick_threshold: float = DEFAULT_STICK_THRESHOLD
    lumped_twin: LumpedModel | None = None
    top_drive: Any = None
    string: Any = None
    contacts: Any = None

    def run_options(self) -> dict[str, Any]:
        """Keywords of :func:`~torsio.analysis.axial_transient.simulate_axial` from the file."""
        return {
            "start": self.start,
            "perturbation": self.perturbation,
            "step": self.step,
            "steps_per_period": self.steps_per_period,
            "stick_threshold": self.stick_threshold,
            "top_drive": self.top_drive,
            "string": self.string,
            **({"contacts": self.contacts} if self.contacts is not None else {}),
        }

    @property
    def hook(self) -> str:
        """The hook's boundary, ``"weight"`` or ``"speed"`` (:mod:`torsio.model.axial_rows`)."""
        return hook_of(self.assembly)

    @property
    def stability_assembly(self) -> LumpedModel:
        """The lumped chain whose linearization gives the growth rate and crossings: the
        assembly itself, or the distributed pipe's :attr:`lumped_twin`."""
        if self.assembly.has_matrices:
            return cast(LumpedModel, self.assembly)
        assert self.lumped_twin is not None
        return self.lumped_twin

    @property
    def stability_model(self) -> str:
        """What :attr:`stability_assembly` is, for reports: ``"the assembly"`` or
        ``"lumped twin, N nodes (elements of at most 100 m)"``."""
        if self.assembly.has_matrices:
            return "the assembly"
        return (
            f"lumped twin, {self.stability_assembly.dofs} nodes (elements of at most "
            f"{DEFAULT_ELEMENT_LENGTH:g} m)"
        )

    @property
    def is_two_dof(self) -> bool:
        """One node under the weight hook: RGD (2007)'s model
        (:func:`torsio.model.axial_assembly.is_two_dof`)."""
        return is_two_dof(self.assembly)


def axial_table(table: Mapping[str, Any]) -> dict[str, Any]:
    """The ``[axial]`` table of ``table``, checked: ``hook``, ``steps_per_period`` (a whole
    number >= 10) and ``element_length`` [m] (default :data:`DEFAULT_ELEMENT_LENGTH`)."""
    raw = _table(table.get("axial", {}), "axial", AXIAL_KEYS)
    options: dict[str, Any] = {"hook": _string(raw.get("hook", "weight"), "axial.hook")}
    # its value is checked by the model it builds (torsio.model.axial_rows.check_hook)
    spp = raw.get("steps_per_period", 100)
    if isinstance(spp, bool) or not isinstance(spp, int) or spp < 10:
        raise ConfigError(
            "axial.steps_per_period", f"{spp!r} must be a whole number >= 10 (steps per period)"
        )
    options["steps_per_period"] = spp
    options["element_length"] = _positive_number(
        raw.get("element_length", DEFAULT_ELEMENT_LENGTH),
        "axial.element_length",
        "length",
        allow_zero=False,
    )
    return options


def axial_simulation_options(table: Mapping[str, Any]) -> dict[str, Any]:
    """The axial run's options of ``[simulation]``: ``start``, ``perturbation``, ``step``
    [s] and ``stick_threshold`` when given; the torsional integrator's keys refused."""
    raw = table.get("simulation", {})
    raw = raw if isinstance(raw, Mapping) else {}
    for key in TORSIONAL_ONLY_SIMULATION_KEYS:
        if key in raw:
            raise ConfigError(
                f"simulation.{key}",
                "the axial engine integrates with a fixed step (no integrator, tolerances or "
                "output step); remove it, or set simulation.step",
            )
    options: dict[str, Any] = {"start": _string(raw.get("start", "rest"), "simulation.start")}
    if options["start"] not in ("rest", "steady"):
        raise ConfigError("simulation.start", f"{options['start']!r} is not one of rest, steady")
    options["perturbation"] = _positive_number(
        raw.get("perturbation", 1e-3), "simulation.perturbation", "dimensionless"
    )
    step = raw.get("step")
    options["step"] = (
        None if step is None else _positive_number(step, "simulation.step", "time", False)
    )
    if "stick_threshold" in raw:
        options["stick_threshold"] = _positive_number(
            raw["stick_threshold"], "simulation.stick_threshold", "dimensionless", False
        )
    return options


def needs_axial(law: str) -> bool:
    """Whether the registered law ``law`` declares ``needs_axial`` (an unknown name is a
    ConfigError naming ``bit_rock.law`` and the registered laws)."""
    from torsio.physics.laws import law_capabilities
    from torsio.plugins import get_bit_law

    return bool(law_capabilities(get_bit_law(law))["needs_axial"])


def axial_law_from_table(raw: Mapping[str, Any]) -> RGDBit:
    """The bit of a ``[bit_rock]`` table whose law declares ``needs_axial``: the RGD bit
    (:func:`torsio.axial.rgd.rgd_from_table`), the one such law the axial engine runs."""
    law = raw.get("law")
    if law != RGDBit.name:
        raise ConfigError(
            "bit_rock.law",
            f"{law!r} declares needs_axial, but the axial engine runs the cutting and wear "
            f"flats of the RGD bit only; expected law = 'rgd' or a law of the torque alone",
        )
    return rgd_from_table(raw)


def axial_bit(
    table: Mapping[str, Any],
    bit_rock: BitRockConfig | None,
    given: str,
    string: DrillString | None = None,
) -> AxialBit:
    """The bit of axial dynamics (``given`` says what gave them): the RGD bit, or any other
    law as a law of the torque alone on its radius (:func:`bit_radius` of ``string``)."""
    raw = table.get("bit_rock")
    if bit_rock is None or not isinstance(raw, Mapping):
        raise ConfigError(
            "bit_rock",
            f"missing: axial dynamics ({given}) need a bit-rock law (e.g. law = 'rgd', or "
            "'tucker-wang' with its parameters and radius)",
        )
    if needs_axial(bit_rock.law):
        return axial_law_from_table(raw)
    return TorqueLawBit(bit_rock.build(), bit_radius(bit_rock, string))


def damping_beta(table: Mapping[str, Any]) -> float:
    """β [s] of ``[damping]`` (default 0); alpha and ratios refused."""
    raw = table.get("damping", {})
    raw = raw if isinstance(raw, Mapping) else {}
    for key in ("alpha", "ratios"):
        if key in raw and raw[key] not in (0, 0.0):
            raise ConfigError(
                f"damping.{key}",
                "the axial engine's dampers join nodes: only stiffness-proportional damping "
                "(damping.beta, c = beta k) applies; remove it",
            )
    return _positive_number(raw.get("beta", 0.0), "damping.beta", "time")


def chain_axial(
    table: Mapping[str, Any], chain: ChainConfig, bit_rock: BitRockConfig | None = None
) -> AxialConfig | None:
    """The axial dynamics of a ``[chain]`` file (None without ``masses``), with the bit of
    its ``bit_rock`` (the parsed ``[bit_rock]``)."""
    raw = table["chain"]
    if "masses" not in raw:
        for key in ("axial_stiffnesses", "axial_dampings"):
            if key in raw:
                raise ConfigError(f"chain.{key}", "goes with chain.masses (axial dynamics)")
        refuse_axial_tables(table, "[chain] masses")
        return None
    if chain.drag is not None:
        raise ConfigError("chain.drag", "the axial engine has no damping to the borehole")
    options = axial_table(table)
    if "element_length" in table.get("axial", {}):
        raise ConfigError("axial.element_length", "goes with a [[section]] string, not [chain]")
    masses = _values(raw["masses"], "chain.masses", "mass", True)
    springs = _optional(raw, "axial_stiffnesses", "axial_stiffness", True)
    dampers = _optional(raw, "axial_dampings", "axial_damping", False)
    if dampers and not springs:
        raise ConfigError(
            "chain.axial_dampings", "goes with chain.axial_stiffnesses (dampers join nodes)"
        )
    model = chain.model()
    if chain.dampings is None:
        model = model.with_dampers(damping_beta(table) * model.springs)
    if not dampers and springs:
        dampers = tuple(damping_beta(table) * np.asarray(springs))
    assembly = model.with_axial(AxialRows(masses, springs, dampers or None, options["hook"]))
    return AxialConfig(
        assembly, axial_bit(table, bit_rock, "[chain] masses"),
        steps_per_period=options["steps_per_period"],
        **axial_simulation_options(table),
    )  # fmt: skip


def _optional(raw: Mapping[str, Any], key: str, dimension: str, positive: bool) -> tuple:
    if key not in raw or raw[key] == []:
        return ()
    return _values(raw[key], f"chain.{key}", dimension, positive)


def refuse_axial_tables(table: Mapping[str, Any], needed: str) -> None:
    """A ConfigError on ``[axial]`` or an axial ``[simulation]`` key in a file without axial
    dynamics, saying what would give them (``needed``)."""
    if "axial" in table:
        raise ConfigError("axial", f"[axial] goes with axial dynamics: give {needed}")
    simulation = table.get("simulation", {})
    for key in sorted(AXIAL_SIMULATION_KEYS & set(simulation)):
        raise ConfigError(f"simulation.{key}", f"applies to axial dynamics only: give {needed}")
