"""The axial dynamics of a ``[[section]]`` string: its lumped chain or its distributed pipe.

A string has axial dynamics when its law declares ``needs_axial`` (``[bit_rock] law =
"rgd"``) or it has an ``[axial]`` table (then a law of the torque alone runs on its chain,
the bit resting on the rock). :func:`string_axial` builds the
:class:`~torsio.config.axial.AxialConfig`: the lumped chain of the file's discretizer with
axial rows (:func:`_lumped_chain`), or with ``[discretization] strategy = "wave"`` the
distributed pipe (:func:`_wave_pipe`, the RGD bit only).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import attrs

from torsio.axial.torque_law import TorqueLawBit
from torsio.axial.wave_assembly import PipeSection, WaveDrillingAssembly
from torsio.config.axial import (
    AxialConfig,
    axial_bit,
    axial_simulation_options,
    axial_table,
    damping_beta,
    needs_axial,
    refuse_axial_tables,
)
from torsio.config.configuration import COUNTING_WAYS, BitRockConfig, DiscretizationConfig
from torsio.errors import ConfigError
from torsio.model.drillstring import DrillString
from torsio.model.lumped import LumpedModel
from torsio.model.wave import DEFAULT_TRAVEL_TIME_TOLERANCE

__all__ = ["AxialSections", "axial_sections", "chain_discretization", "string_axial"]


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
    section, the BHA rigid; its lumped twin in elements of at most
    :data:`~torsio.axial.wave_assembly.DEFAULT_ELEMENT_LENGTH` for the linear stability);
    otherwise the lumped chain of the file's discretizer with axial rows
    (:func:`_lumped_chain`).
    """
    raw = table.get("bit_rock")
    law = raw.get("law", "tucker-wang") if isinstance(raw, Mapping) else None
    if not (isinstance(law, str) and needs_axial(law)) and "axial" not in table:
        refuse_axial_tables(
            table,
            "[bit_rock] law = 'rgd', or an [axial] table for a law of the torque alone, "
            "and [material] youngs_modulus",
        )
        return None
    options = axial_table(table)
    bit = axial_bit(table, bit_rock, "[axial]", string)
    run = {"steps_per_period": options["steps_per_period"], **axial_simulation_options(table)}
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


ELEMENT_COUNT_KEYS = tuple(sorted(set().union(*COUNTING_WAYS)))
"""``[discretization]`` keys that count a discretizer's elements."""


def chain_discretization(
    table: Mapping[str, Any], discretization: DiscretizationConfig
) -> DiscretizationConfig:
    """The discretization that lumps a string's axial chain: the file's ``discretization``
    where it counts the elements, else the same with ``max_element_length`` = ``[axial]
    element_length`` (both given: refused on ``axial.element_length``). It is the file's
    torsional model too (:meth:`~torsio.config.configuration.Config.model`)."""
    counted = [key for key in ELEMENT_COUNT_KEYS if key in discretization.options]
    if counted and "element_length" in table.get("axial", {}):
        raise ConfigError(
            "axial.element_length",
            f"{table['axial']['element_length']!r} given, and discretization.{counted[0]} "
            "counts the chain's elements too; give one of them",
        )
    if counted:
        return discretization
    length = axial_table(table)["element_length"]
    return DiscretizationConfig(
        discretization.strategy, {**discretization.options, "max_element_length": length}
    )


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
    lumping = chain_discretization(table, discretization)
    counted = lumping is discretization
    try:
        discretizer = lumping.build()
    except TypeError as exc:
        if counted:
            raise
        raise ConfigError(
            "discretization.strategy",
            f"{strategy!r} takes no max_element_length ({exc}), which counts the chain's "
            "elements by [axial] element_length when [discretization] counts none; give "
            "the strategy's own element counts in [discretization]",
        ) from None
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
    beta = damping_beta(table)
    if beta:
        chain = chain.with_dampers(beta * chain.springs)
    return chain.with_axial(attrs.evolve(rows, dampings=beta * rows.stiffnesses))
