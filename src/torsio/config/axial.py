"""Axial dynamics from a configuration: the assembly, the RGD bit and the run options.

A configuration has axial dynamics when ``[chain]`` gives ``masses`` (each node also moves
axially) or a ``[[section]]`` string has ``[bit_rock] law = "rgd"`` (its axial data from
E, ρ and the sections). Either needs the RGD bit. :func:`chain_axial` and
:func:`string_axial` build an :class:`AxialConfig` that
:func:`torsio.axial.transient.simulate_axial` and :func:`torsio.axial.maps.axial_map` run.

Examples
--------
>>> from torsio.examples import rgd_two_dof_config
>>> axial = rgd_two_dof_config().axial
>>> axial.assembly.nodes, axial.assembly.hook, axial.bit.blades
(1, 'weight', 4)
>>> sorted(axial.run_options().items())  # doctest: +NORMALIZE_WHITESPACE
[('perturbation', 0.001), ('start', 'rest'), ('step', None), ('steps_per_period', 100),
 ('string', None), ('top_drive', None)]
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import attrs
import numpy as np

from torsio.axial.assembly import HOOKS, DrillingAssembly
from torsio.axial.rgd import RGDBit, rgd_from_table
from torsio.config.chain import ChainConfig, _values
from torsio.config.tables import _positive_number, _string, _table
from torsio.errors import ConfigError
from torsio.model.drillstring import DrillString
from torsio.units import to_si

__all__ = ["AXIAL_SIMULATION_KEYS", "AxialConfig", "chain_axial", "string_axial"]

AXIAL_KEYS = {"hook", "steps_per_period", "element_length"}
"""Keys of the ``[axial]`` table."""
AXIAL_SIMULATION_KEYS = {"start", "perturbation", "step"}
"""``[simulation]`` keys of the axial engine only."""
TORSIONAL_ONLY_SIMULATION_KEYS = ("method", "rtol", "atol", "output_step", "stick_threshold")
"""``[simulation]`` keys the fixed-step axial engine has no use for (refused)."""
DEFAULT_ELEMENT_LENGTH = 100.0
"""Longest element [m] of a ``[[section]]`` string's pipe in its axial-torsional chain."""

RGD_REFUSAL = (
    "the rgd law needs axial dynamics: give [chain] masses (or, for a [[section]] string, "
    "[material] youngs_modulus); the torsional engines take a law with "
    "torque(speed, wob, radius)"
)
"""Why the torsional engines refuse ``law = "rgd"`` (the message of ``bit_rock.law``)."""


@attrs.frozen(eq=False)
class AxialConfig:
    """The axial dynamics of a configuration, validated.

    Attributes
    ----------
    assembly : DrillingAssembly
        The nodes that turn and move axially, the bit on the last one.
    bit : RGDBit
        The RGD bit of ``[bit_rock]``.
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
    """

    assembly: DrillingAssembly
    bit: RGDBit
    start: str = "rest"
    perturbation: float = 1e-3
    step: float | None = None
    steps_per_period: int = 100
    top_drive: Any = None
    string: Any = None

    def run_options(self) -> dict[str, Any]:
        """Keywords of :func:`~torsio.axial.transient.simulate_axial` from the file."""
        return {
            "start": self.start,
            "perturbation": self.perturbation,
            "step": self.step,
            "steps_per_period": self.steps_per_period,
            "top_drive": self.top_drive,
            "string": self.string,
        }

    @property
    def is_two_dof(self) -> bool:
        """One node under the weight hook: RGD (2007)'s model
        (:attr:`torsio.axial.assembly.DrillingAssembly.is_two_dof`)."""
        return self.assembly.is_two_dof


def _axial_table(table: Mapping[str, Any]) -> dict[str, Any]:
    raw = _table(table.get("axial", {}), "axial", AXIAL_KEYS)
    options: dict[str, Any] = {"hook": _string(raw.get("hook", "weight"), "axial.hook")}
    if options["hook"] not in HOOKS:
        raise ConfigError("axial.hook", f"{options['hook']!r} is not one of {', '.join(HOOKS)}")
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


def _bit(table: Mapping[str, Any], given: str) -> RGDBit:
    raw = table.get("bit_rock")
    law = raw.get("law") if isinstance(raw, Mapping) else None
    if law != "rgd":
        raise ConfigError(
            "bit_rock.law",
            f"axial dynamics ({given}) need the RGD bit: law = 'rgd', got {law!r}",
        )
    assert isinstance(raw, Mapping)
    return rgd_from_table(raw)


def _dampers(table: Mapping[str, Any], springs: np.ndarray) -> np.ndarray:
    """Dampers β k [N m s/rad or N s/m] from ``[damping] beta``; alpha and ratios refused."""
    raw = table.get("damping", {})
    raw = raw if isinstance(raw, Mapping) else {}
    for key in ("alpha", "ratios"):
        if key in raw and raw[key] not in (0, 0.0):
            raise ConfigError(
                f"damping.{key}",
                "the axial engine's dampers join nodes: only stiffness-proportional damping "
                "(damping.beta, c = beta k) applies; remove it",
            )
    beta = _positive_number(raw.get("beta", 0.0), "damping.beta", "time")
    return beta * springs


def chain_axial(table: Mapping[str, Any], chain: ChainConfig) -> AxialConfig | None:
    """The axial dynamics of a ``[chain]`` file (None without ``masses``)."""
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
    torsional = np.asarray(chain.stiffnesses)
    damping = (
        np.asarray(chain.dampings) if chain.dampings is not None else _dampers(table, torsional)
    )
    if not dampers and springs:
        dampers = tuple(_dampers(table, np.asarray(springs)))
    assembly = _assembly(
        inertias=chain.inertias,
        stiffnesses=chain.stiffnesses,
        masses=masses,
        axial_stiffnesses=springs,
        damping=damping,
        axial_damping=dampers or None,
        hook=options["hook"],
    )
    return AxialConfig(
        assembly, _bit(table, "[chain] masses"), steps_per_period=options["steps_per_period"],
        **_simulation_options(table),
    )  # fmt: skip


def _optional(raw: Mapping[str, Any], key: str, dimension: str, positive: bool) -> tuple:
    if key not in raw or raw[key] == []:
        return ()
    return _values(raw[key], f"chain.{key}", dimension, positive)


def _assembly(**kwargs: Any) -> DrillingAssembly:
    try:
        return DrillingAssembly(**kwargs)
    except ConfigError as exc:  # the assembly names its arrays; the file's key is plural
        key = exc.key.replace("chain.axial_damping", "chain.axial_dampings")
        raise ConfigError(key, exc.message) from None


def _refuse_axial_tables(table: Mapping[str, Any], needed: str) -> None:
    if "axial" in table:
        raise ConfigError("axial", f"[axial] goes with axial dynamics: give {needed}")
    simulation = table.get("simulation", {})
    for key in sorted(AXIAL_SIMULATION_KEYS & set(simulation)):
        raise ConfigError(f"simulation.{key}", f"applies to axial dynamics only: give {needed}")


def _youngs_modulus(raw: Any, key: str, default: float | None) -> float | None:
    if not isinstance(raw, Mapping) or "youngs_modulus" not in raw:
        return default
    value = to_si(raw["youngs_modulus"], "pressure", key=f"{key}.youngs_modulus")
    if not (math.isfinite(value) and value > 0):
        raise ConfigError(f"{key}.youngs_modulus", f"expected a positive modulus, got {value!r}")
    return value


def string_axial(table: Mapping[str, Any], string: DrillString) -> AxialConfig | None:
    """The axial dynamics of a ``[[section]]`` file (None unless ``law = "rgd"``).

    The pipe sections above the BHA are split into elements of at most
    ``[axial] element_length`` [m], each with springs E A / Δ [N/m] and G J / Δ [N m/rad]
    and its mass ρ A Δ and inertia ρ J Δ shared by its two end nodes (the top half at the
    hook); the BHA (with the bit) is rigid on the last node.
    """
    raw = table.get("bit_rock")
    law = raw.get("law") if isinstance(raw, Mapping) else None
    if law != "rgd":
        _refuse_axial_tables(table, "[bit_rock] law = 'rgd' and [material] youngs_modulus")
        return None
    options = _axial_table(table)
    default_e = _youngs_modulus(table.get("material"), "material", None)
    inertias: list[float] = []
    stiffnesses: list[float] = []
    masses: list[float] = []
    springs: list[float] = []
    carry_i = carry_m = 0.0  # the lower half of the element above
    bha_i = bha_m = 0.0
    for i, (section, raw_section) in enumerate(zip(string.sections, table["section"], strict=True)):
        key = f"section[{i}].material"
        e = _youngs_modulus(raw_section.get("material"), key, default_e)
        rho, g = section.material.density, section.material.shear_modulus
        area = math.pi * (section.od**2 - section.id**2) / 4
        if section.in_bha:
            bha_i += section.inertia
            bha_m += rho * area * section.length
            continue
        if e is None:
            raise ConfigError(
                "material.youngs_modulus",
                f"missing: the rgd law needs axial dynamics, whose springs E A / L need "
                f"Young's modulus E of section[{i}] ({section.describe()}) "
                "(e.g. youngs_modulus = '207 GPa')",
            )
        count = math.ceil(section.length / options["element_length"] - 1e-9)
        spacing = section.length / count
        for _ in range(count):
            element_i = rho * section.polar_moment * spacing
            element_m = rho * area * spacing
            if stiffnesses:
                inertias.append(carry_i + element_i / 2)
                masses.append(carry_m + element_m / 2)
            stiffnesses.append(g * section.polar_moment / spacing)
            springs.append(e * area / spacing)
            carry_i, carry_m = element_i / 2, element_m / 2
    if not stiffnesses:
        raise ConfigError("section", "axial dynamics need a flexible pipe above the BHA")
    inertias.append(carry_i + bha_i)
    masses.append(carry_m + bha_m)
    torsional = np.array(stiffnesses)
    axial = np.array(springs)
    assembly = _assembly(
        inertias=inertias,
        stiffnesses=torsional,
        masses=masses,
        axial_stiffnesses=axial,
        damping=_dampers(table, torsional),
        axial_damping=_dampers(table, axial),
        hook=options["hook"],
    )
    return AxialConfig(
        assembly, _bit(table, "law = 'rgd'"), steps_per_period=options["steps_per_period"],
        string=string, **_simulation_options(table),
    )  # fmt: skip
