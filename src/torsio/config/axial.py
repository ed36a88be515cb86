"""Axial dynamics from a configuration: the assembly, the RGD bit and the run options.

A configuration has axial dynamics when ``[chain]`` gives ``masses`` (each node also moves
axially) or a ``[[section]]`` string has a law that declares ``needs_axial``, ``[bit_rock]
law = "rgd"``, or an ``[axial]`` table (its axial data from E, ρ and the sections). Any
registered law runs on a chain: the RGD bit, or a law of the torque alone (Tucker-Wang, a
plugin's), whose axial motion rests on the rock under the weight on bit
(:class:`~torsio.axial.torque_law.TorqueLawBit`).
:func:`chain_axial` and :func:`string_axial` build an :class:`AxialConfig` that
:func:`torsio.axial.transient.simulate_axial` and :func:`torsio.axial.maps.axial_map` run:
a lumped chain (the file's discretizer with axial rows, elements of at most
``[axial] element_length``), or
with ``[discretization] strategy = "wave"`` the distributed pipe
(:class:`~torsio.axial.wave_assembly.WaveDrillingAssembly`), which takes no element
length and no damping (both refused by key).

Examples
--------
>>> from torsio.examples import rgd_two_dof_config
>>> axial = rgd_two_dof_config().axial
>>> axial.assembly.dofs, axial.hook, axial.bit.blades
(1, 'weight', 4)
>>> sorted(axial.run_options().items())  # doctest: +NORMALIZE_WHITESPACE
[('perturbation', 0.001), ('start', 'rest'), ('step', None), ('steps_per_period', 100),
 ('string', None), ('top_drive', None)]
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import attrs
import numpy as np

from torsio.axial.assembly import is_two_dof, require_axial
from torsio.axial.rgd import RGDBit, rgd_from_table
from torsio.axial.torque_law import AxialBit, TorqueLawBit
from torsio.axial.wave_assembly import DEFAULT_ELEMENT_LENGTH, PipeSection, WaveDrillingAssembly
from torsio.config.chain import ChainConfig, _values
from torsio.config.configuration import BitRockConfig, DiscretizationConfig, bit_radius
from torsio.config.tables import _positive_number, _string, _table
from torsio.errors import ConfigError
from torsio.model.axial_rows import AxialRows
from torsio.model.drillstring import DrillString
from torsio.model.lumped import LumpedModel
from torsio.model.wave import DEFAULT_TRAVEL_TIME_TOLERANCE

__all__ = [
    "AXIAL_SIMULATION_KEYS",
    "AxialConfig",
    "AxialSections",
    "axial_law_from_table",
    "axial_sections",
    "chain_axial",
    "string_axial",
]

AXIAL_KEYS = {"hook", "steps_per_period", "element_length"}
"""Keys of the ``[axial]`` table."""
AXIAL_SIMULATION_KEYS = {"start", "perturbation", "step"}
"""``[simulation]`` keys of the axial engine only."""
TORSIONAL_ONLY_SIMULATION_KEYS = ("method", "rtol", "atol", "output_step", "stick_threshold")
"""``[simulation]`` keys the fixed-step axial engine has no use for (refused)."""


@attrs.frozen(eq=False)
class AxialConfig:
    """The axial dynamics of a configuration, validated.

    Attributes
    ----------
    assembly : LumpedModel or WaveDrillingAssembly
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

    assembly: LumpedModel | WaveDrillingAssembly
    bit: AxialBit
    start: str = "rest"
    perturbation: float = 1e-3
    step: float | None = None
    steps_per_period: int = 100
    lumped_twin: LumpedModel | None = None
    top_drive: Any = None
    string: Any = None
    contacts: Any = None

    def run_options(self) -> dict[str, Any]:
        """Keywords of :func:`~torsio.axial.transient.simulate_axial` from the file."""
        return {
            "start": self.start,
            "perturbation": self.perturbation,
            "step": self.step,
            "steps_per_period": self.steps_per_period,
            "top_drive": self.top_drive,
            "string": self.string,
            **({"contacts": self.contacts} if self.contacts is not None else {}),
        }

    @property
    def hook(self) -> str:
        """The hook's boundary, ``"weight"`` or ``"speed"`` (:mod:`torsio.model.axial_rows`)."""
        if isinstance(self.assembly, WaveDrillingAssembly):
            return self.assembly.hook
        return require_axial(self.assembly).hook

    @property
    def stability_assembly(self) -> LumpedModel:
        """The lumped chain whose linearization gives the growth rate and crossings: the
        assembly itself, or the distributed pipe's :attr:`lumped_twin`."""
        if not isinstance(self.assembly, WaveDrillingAssembly):
            return self.assembly
        assert self.lumped_twin is not None
        return self.lumped_twin

    @property
    def stability_model(self) -> str:
        """What :attr:`stability_assembly` is, for reports: ``"the assembly"`` or
        ``"lumped twin, N nodes (elements of at most 100 m)"``."""
        if not isinstance(self.assembly, WaveDrillingAssembly):
            return "the assembly"
        return (
            f"lumped twin, {self.stability_assembly.dofs} nodes (elements of at most "
            f"{DEFAULT_ELEMENT_LENGTH:g} m)"
        )

    @property
    def is_two_dof(self) -> bool:
        """One node under the weight hook: RGD (2007)'s model
        (:func:`torsio.axial.assembly.is_two_dof`)."""
        return is_two_dof(self.assembly)


def _axial_table(table: Mapping[str, Any]) -> dict[str, Any]:
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


def _simulation_options(table: Mapping[str, Any]) -> dict[str, Any]:
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


def _bit(
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


def _damping_beta(table: Mapping[str, Any]) -> float:
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
        _refuse_axial_tables(table, "[chain] masses")
        return None
    if chain.drag is not None:
        raise ConfigError("chain.drag", "the axial engine has no damping to the borehole")
    options = _axial_table(table)
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
        model = model.with_dampers(_damping_beta(table) * model.springs)
    if not dampers and springs:
        dampers = tuple(_damping_beta(table) * np.asarray(springs))
    assembly = model.with_axial(AxialRows(masses, springs, dampers or None, options["hook"]))
    return AxialConfig(
        assembly, _bit(table, bit_rock, "[chain] masses"),
        steps_per_period=options["steps_per_period"],
        **_simulation_options(table),
    )  # fmt: skip


def _optional(raw: Mapping[str, Any], key: str, dimension: str, positive: bool) -> tuple:
    if key not in raw or raw[key] == []:
        return ()
    return _values(raw[key], f"chain.{key}", dimension, positive)


def _refuse_axial_tables(table: Mapping[str, Any], needed: str) -> None:
    if "axial" in table:
        raise ConfigError("axial", f"[axial] goes with axial dynamics: give {needed}")
    simulation = table.get("simulation", {})
    for key in sorted(AXIAL_SIMULATION_KEYS & set(simulation)):
        raise ConfigError(f"simulation.{key}", f"applies to axial dynamics only: give {needed}")


@attrs.frozen
class AxialSections:
    """A ``[[section]]`` string read for the distributed axial pipe (:func:`axial_sections`).

    Attributes
    ----------
    pipe : tuple of PipeSection
        The sections above the BHA, from the top down: L [m], E, G [Pa], ρ [kg/m³],
        A = π (od² − id²)/4 [m²], J [m⁴].
    bha_mass : float
        Σ ρ A L of the BHA's sections and the bit [kg].
    bha_inertia : float
        Σ ρ J L of the same [kg m²].
    """

    pipe: tuple[PipeSection, ...]
    bha_mass: float
    bha_inertia: float


def axial_sections(string: DrillString) -> AxialSections:
    """The pipe sections (with E of their material, ``[material]`` or the section's own)
    and the rigid BHA's sums: what the distributed pipe is built from (the lumped chain is
    its discretizer's, :func:`_lumped_chain`)."""
    pipe: list[PipeSection] = []
    bha_mass = bha_inertia = 0.0
    for i, section in enumerate(string.sections):
        e = section.material.youngs_modulus
        area = section.area
        if section.in_bha:
            bha_mass += section.material.density * area * section.length
            bha_inertia += section.inertia
            continue
        if e is None:
            raise ConfigError(
                "material.youngs_modulus",
                f"missing: the rgd law needs axial dynamics, whose springs E A / L need "
                f"Young's modulus E of section[{i}] ({section.describe()}) "
                "(e.g. youngs_modulus = '207 GPa')",
            )
        material = section.material
        pipe.append(
            PipeSection(
                section.length, e, material.shear_modulus, material.density, area,
                section.polar_moment,
            )
        )  # fmt: skip
    if not pipe:
        raise ConfigError("section", "axial dynamics need a flexible pipe above the BHA")
    return AxialSections(tuple(pipe), bha_mass, bha_inertia)


WAVE_REFUSED_DISCRETIZATION = {
    "time_step": "the axial engine's largest step is simulation.step (the distributed "
    "pipe's step rule: axial.steps_per_period and discretization.travel_time_tolerance); "
    "give it there",
    "drag_spacing": "the distributed axial pipe carries no distributed drag (no contacts "
    "along it and no damping); remove it",
}
"""``[discretization]`` keys of the torsional wave strategy that the distributed axial pipe
refuses, and why."""


def _wave_pipe(
    table: Mapping[str, Any], sections: AxialSections, hook: str
) -> WaveDrillingAssembly:
    """The distributed pipe of ``[discretization] strategy = "wave"``: one
    :class:`~torsio.axial.wave_assembly.PipeSection` per section above the BHA."""
    if "element_length" in table.get("axial", {}):
        raise ConfigError(
            "axial.element_length",
            f"{table['axial']['element_length']!r} given, but [discretization] strategy = "
            "'wave' builds the distributed pipe, which has no elements (its grid follows the "
            "wave speeds within discretization.travel_time_tolerance); remove it, or choose "
            "the lumped chain (another strategy)",
        )
    discretization = table.get("discretization", {})
    for key, why in WAVE_REFUSED_DISCRETIZATION.items():
        if key in discretization:
            raise ConfigError(f"discretization.{key}", f"{discretization[key]!r}: {why}")
    if discretization.get("rigid_bha", True) is not True:
        raise ConfigError(
            "discretization.rigid_bha",
            f"{discretization['rigid_bha']!r}: the distributed axial pipe's BHA is one rigid "
            "body with the bit (expected true, or leave it out)",
        )
    damping = table.get("damping", {})
    damping = damping if isinstance(damping, Mapping) else {}
    for key in ("alpha", "beta", "ratios"):
        if key in damping and damping[key] not in (0, 0.0):
            raise ConfigError(
                f"damping.{key}",
                f"{damping[key]!r}: the distributed axial pipe has no damping yet (its lines "
                "carry no dampers); remove it, or choose the lumped chain (a [discretization] "
                "strategy other than 'wave') for stiffness-proportional dampers",
            )
    tolerance = discretization.get("travel_time_tolerance", DEFAULT_TRAVEL_TIME_TOLERANCE)
    return WaveDrillingAssembly(
        sections.pipe,
        bha_mass=sections.bha_mass,
        bha_inertia=sections.bha_inertia,
        hook=hook,
        travel_time_tolerance=tolerance,
    )


def string_axial(
    table: Mapping[str, Any],
    string: DrillString,
    discretization: DiscretizationConfig,
    bit_rock: BitRockConfig | None,
) -> AxialConfig | None:
    """The axial dynamics of a ``[[section]]`` file (None unless its law declares
    ``needs_axial``, ``law = "rgd"``, or it has an ``[axial]`` table: then a law of the
    torque alone, ``bit_rock``, runs on the axial chain, its bit resting on the rock).

    With ``[discretization] strategy = "wave"`` the distributed pipe
    (:class:`~torsio.axial.wave_assembly.WaveDrillingAssembly`, one section per pipe
    section, the BHA rigid; its lumped twin at :data:`DEFAULT_ELEMENT_LENGTH` for the linear
    stability); otherwise the lumped chain of the file's discretizer with axial rows
    (:func:`_lumped_chain`).
    """
    raw = table.get("bit_rock")
    law = raw.get("law", "tucker-wang") if isinstance(raw, Mapping) else None
    if not (isinstance(law, str) and needs_axial(law)) and "axial" not in table:
        _refuse_axial_tables(
            table,
            "[bit_rock] law = 'rgd', or an [axial] table for a law of the torque alone, "
            "and [material] youngs_modulus",
        )
        return None
    options = _axial_table(table)
    bit = _bit(table, bit_rock, "[axial]", string)
    run = {"steps_per_period": options["steps_per_period"], **_simulation_options(table)}
    if discretization.strategy == "wave":
        if isinstance(bit, TorqueLawBit):
            raise ConfigError(
                "discretization.strategy",
                f"'wave' builds the distributed axial pipe, which takes the RGD bit only; "
                f"{bit.name!r} is a law of the torque alone: choose 'B' or 'C' (the lumped "
                "chain), or remove [axial] for the torsional wave model",
            )
        pipe = _wave_pipe(table, axial_sections(string), options["hook"])
        return AxialConfig(pipe, bit, lumped_twin=pipe.lumped_twin(), string=string, **run)
    chain = _lumped_chain(table, string, discretization, options)
    return AxialConfig(chain, bit, string=string, **run)


ELEMENT_COUNT_KEYS = ("dp_elements", "bha_elements", "section_elements", "max_element_length")
"""``[discretization]`` keys that count a discretizer's elements."""


def _lumped_chain(
    table: Mapping[str, Any],
    string: DrillString,
    discretization: DiscretizationConfig,
    options: Mapping[str, Any],
) -> LumpedModel:
    """The lumped chain of a ``[[section]]`` string with axial rows: the file's discretizer
    (strategy C by default) builds its torsional and axial rows on the same elements
    (:meth:`~torsio.model.discretize.StrategyC.axial_rows`), of at most ``[axial]
    element_length`` unless ``[discretization]`` counts them; dampers β k on every spring
    (``[damping] beta``)."""
    strategy = discretization.strategy
    if not callable(getattr(discretization.build(), "axial_rows", None)):
        raise ConfigError(
            "discretization.strategy",
            f"{strategy!r} builds no axial rows (springs E A / L and masses on its "
            "elements); axial dynamics take a discretizer with axial_rows ('B', 'C', the "
            "default, or a plugin's) or 'wave'",
        )
    counted = [key for key in ELEMENT_COUNT_KEYS if key in discretization.options]
    if counted and "element_length" in table.get("axial", {}):
        raise ConfigError(
            "axial.element_length",
            f"{table['axial']['element_length']!r} given, and discretization.{counted[0]} "
            "counts the chain's elements too; give one of them",
        )
    counting = {} if counted else {"max_element_length": options["element_length"]}
    discretizer = DiscretizationConfig(strategy, {**discretization.options, **counting}).build()
    try:
        chain = discretizer.discretize(string)
        rows = discretizer.axial_rows(string, options["hook"])
    except ConfigError as exc:
        if exc.key == "discretization" and not counted:  # too many elements of [axial]'s
            length = table.get("axial", {}).get("element_length", options["element_length"])
            raise ConfigError("axial.element_length", f"{length!r}: {exc.message}") from None
        if exc.key.split("[")[0] not in ELEMENT_COUNT_KEYS:
            raise
        raise ConfigError(f"discretization.{exc.key}", exc.message) from None
    beta = _damping_beta(table)
    if beta:
        chain = chain.with_dampers(beta * chain.springs)
    return chain.with_axial(attrs.evolve(rows, dampings=beta * rows.stiffnesses))
