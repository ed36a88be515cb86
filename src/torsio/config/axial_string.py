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
from typing import Any, cast

import attrs

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
from torsio.model.axial_assembly import axial_model, check_axial_discretizer, lumped_twin
from torsio.model.drillstring import DrillString
from torsio.model.lumped import LumpedModel
from torsio.model.wave import WaveModel, WaveStrategy
from torsio.physics.torque_law_bit import TorqueLawBit

__all__ = ["chain_discretization", "string_axial"]


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
    table: Mapping[str, Any], string: DrillString, discretization: DiscretizationConfig, hook: str
) -> WaveModel:
    """The distributed pipe of ``[discretization] strategy = "wave"``: the wave model of
    the string's drill pipes with their axial lines, the BHA rigid
    (:func:`~torsio.model.axial_assembly.axial_model`)."""
    if "element_length" in table.get("axial", {}):
        raise ConfigError(
            "axial.element_length",
            f"{table['axial']['element_length']!r} given, but [discretization] strategy = "
            "'wave' builds the distributed pipe, which has no elements (its grid follows the "
            "wave speeds within discretization.travel_time_tolerance); remove it, or choose "
            "the lumped chain (another strategy)",
        )
    options = discretization.options
    for key, why in WAVE_REFUSED_DISCRETIZATION.items():
        if key in options:
            raise ConfigError(f"discretization.{key}", f"{options[key]!r}: {why}")
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
    if not string.drill_pipe_sections:
        raise ConfigError(
            "section", "the distributed axial pipe needs a drill pipe above the BHA; none given"
        )
    strategy = WaveStrategy(**discretization.of_axial_pipe().options)
    return cast(WaveModel, axial_model(string, strategy, hook))


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
    (a :class:`~torsio.model.wave.WaveModel` with axial rows, the BHA rigid; its lumped
    twin, :func:`~torsio.model.axial_assembly.lumped_twin`, for the linear stability);
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
        pipe = _wave_pipe(table, string, discretization, options["hook"])
        return AxialConfig(pipe, bit, lumped_twin=lumped_twin(pipe), string=string, **run)
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
    check_axial_discretizer(discretization.build())
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
        chain = axial_model(string, discretizer, options["hook"])
    except ConfigError as exc:
        if exc.key == "discretization" and not counted:  # too many elements of [axial]'s
            length = table.get("axial", {}).get("element_length", options["element_length"])
            raise ConfigError("axial.element_length", f"{length!r}: {exc.message}") from None
        if exc.key.split("[")[0] not in ELEMENT_COUNT_KEYS:
            raise
        raise ConfigError(f"discretization.{exc.key}", exc.message) from None
    chain = cast(LumpedModel, chain)
    rows = chain.axial
    assert rows is not None
    beta = damping_beta(table)
    if beta:
        chain = chain.with_dampers(beta * chain.springs)
    return chain.with_axial(attrs.evolve(rows, dampings=beta * rows.stiffnesses))
