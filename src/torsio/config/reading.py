"""Reading a configuration: TOML text, a file or a dict into a validated :class:`Config`.

Bare numbers are SI; strings with units are accepted (``"5.5 in"``, ``"100 kN"``).
Unknown keys are errors. Every error names the key, e.g. ``section[2].od``.
See ``docs/configuration.md`` for every key, its unit and its default. The tables with
modules of their own: ``[[section]]`` and ``[material]`` (:mod:`torsio.config.tables`),
``[chain]``, ``[top_drive]`` and ``[well]``; the small ones are read here.

Examples
--------
>>> config = parse_config_text('''
... name = "one collar"
... [[section]]
... kind = "drill_collar"
... od = "8 in"
... id = "3 in"
... length = 100.0
... [[section]]
... kind = "bit"
... od = "8.5 in"
... id = 0.0
... length = 0.3
... [damping]
... alpha = 0.1
... ''')
>>> config.name, len(config.string.sections), config.damping.alpha
('one collar', 2, 0.1)
>>> parse_config({"section": []}, source="<dict>")
Traceback (most recent call last):
...
torsio.errors.ConfigError: section: a drill-string needs at least one section and a bit
"""

from __future__ import annotations

import copy
import tomllib
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import attrs

from torsio.config.axial import (
    AXIAL_SIMULATION_KEYS,
    axial_law_from_table,
    chain_axial,
    needs_axial,
)
from torsio.config.axial_string import ELEMENT_COUNT_KEYS, chain_discretization, string_axial
from torsio.config.axial_well import with_well
from torsio.config.chain import parse_chain
from torsio.config.configuration import (
    BitRockConfig,
    Config,
    DampingConfig,
    DiscretizationConfig,
    OperationConfig,
    SimulationConfig,
)
from torsio.config.tables import (
    _material,
    _option_error,
    _positive_number,
    _section,
    _string,
    _table,
    parse_rpm,
)
from torsio.config.top_drive import parse_top_drive
from torsio.config.well import well_table
from torsio.errors import ConfigError
from torsio.model.components import STEEL
from torsio.model.drillstring import DrillString
from torsio.units import to_si

__all__ = [
    "UndampedWarning",
    "load_config",
    "parse_config",
    "parse_config_text",
    "rediscretized",
]

TOP_LEVEL_KEYS = {
    "name",
    "material",
    "section",
    "chain",
    "bit_rock",
    "damping",
    "discretization",
    "operation",
    "simulation",
    "top_drive",
    "well",
    "axial",
}
DISCRETIZATION_KEYS = {
    "strategy",
    "dp_elements",
    "bha_elements",
    "section_elements",
    "max_element_length",
    "time_step",
    "travel_time_tolerance",
    "rigid_bha",
    "drag_spacing",
}
DAMPING_KEYS = {"alpha", "beta", "ratios", "modes"}
OPERATION_KEYS = {"wob", "rpm"}
SIMULATION_KEYS = {"duration", "steady_window", "method", "rtol", "atol", "output_step"}
SIMULATION_KEYS |= {"stick_threshold"} | AXIAL_SIMULATION_KEYS


def load_config(path: str | Path) -> Config:
    """Read and validate a TOML configuration file."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise ConfigError(
            "", f"cannot read configuration file {str(path)!r}: {exc.strerror or exc}"
        ) from None
    except UnicodeDecodeError as exc:
        line = path.read_bytes()[: exc.start].count(b"\n") + 1
        raise ConfigError(
            "",
            f"configuration file {str(path)!r} is not UTF-8 text (TOML files must be): "
            f"byte {exc.object[exc.start : exc.start + 1]!r} at line {line}; "
            "save it as UTF-8",
        ) from None
    return parse_config_text(text, source=str(path))


def parse_config_text(text: str, source: str = "<string>") -> Config:
    """Parse and validate TOML text."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError("", f"{source} is not valid TOML: {exc}") from None
    return parse_config(data, source=source)


def parse_config(data: Mapping[str, Any], source: str = "<dict>") -> Config:
    """Validate a configuration already read into a dict (as from ``tomllib``)."""
    table = _table(data, "", TOP_LEVEL_KEYS)
    name = _string(table.get("name", ""), "name")
    top_drive = parse_top_drive(table.get("top_drive", {}), source)
    config = (
        _chain_config(table, name, source)
        if "chain" in table
        else _string_config(table, name, source)
    )
    if config.axial is not None and "top_drive" in table:
        config = attrs.evolve(config, axial=_axial_top_drive(config.axial, top_drive))
    if not top_drive.has_set_speed and config.operation.rpm is not None:
        raise ConfigError(
            "operation.rpm",
            f"the top drive is {top_drive.kind!r}: its speed follows from the torque balance, "
            "so no rotary speed may be set; remove operation.rpm",
        )
    well = well_table(table, config.string, source)
    if config.axial is not None:
        config = attrs.evolve(config, axial=with_well(config.axial, table, well))
    return attrs.evolve(config, top_drive=top_drive, well=well, table=copy.deepcopy(table))


def rediscretized(config: Config, **overrides: Any) -> Config:
    """``config`` with ``overrides`` of its ``[discretization]`` (None: not given;
    :meth:`~torsio.config.configuration.DiscretizationConfig.overridden`): its torsional
    model and, with axial dynamics, its axial chain read again from the file's tables
    (:attr:`~torsio.config.configuration.Config.table`) with its ``[well]`` contacts and
    top drive. The rest of ``config`` is kept as it is.

    Element counts given here replace ``[axial] element_length`` on a chain the file
    counts by it; they must then count every part the strategy lumps (``dp_elements``, and
    ``bha_elements`` where the BHA is flexible). A ``[chain]`` is not discretized: an
    override is refused by its name.

    >>> from torsio.examples import rgd_wave_pipe_config
    >>> chain = rediscretized(rgd_wave_pipe_config(), strategy="B", dp_elements=4,
    ...                       bha_elements=1)
    >>> chain.discretization.strategy, chain.axial.assembly.node_depths.tolist()  # m
    ('B', [300.0, 600.0, 900.0, 1000.0, 1150.0])
    """
    given = {k: v for k, v in overrides.items() if v is not None}
    if not given:
        return config
    if config.chain is not None:
        config.model(**given)  # refused there: a [chain] is not discretized
    if config.axial is None:
        discretization = config.discretization.overridden(**given)
        checked = _discretization({"strategy": discretization.strategy, **discretization.options})
        assert config.string is not None  # not a [chain]
        _check_counts(checked, config.string)
        return attrs.evolve(config, discretization=checked)
    if not config.table:
        raise ConfigError(
            "discretization",
            "the axial chain is built from the file's tables, and this configuration was "
            "not read from one (parse_config, load_config); give the counts there",
        )
    # the file's own table: the chain's counts by [axial] element_length are not its options
    discretization = _discretization(config.table.get("discretization", {})).overridden(**given)
    data = {**config.table, "discretization": {"strategy": discretization.strategy}}
    data["discretization"].update(discretization.options)
    counts = set(given) & set(ELEMENT_COUNT_KEYS)
    if (
        counts
        and discretization.strategy != "wave"
        and not (set(discretization.options) - counts) & set(ELEMENT_COUNT_KEYS)
    ):  # the chain was counted by [axial] element_length
        _refuse_partial_counts(discretization.strategy, given, counts)
        axial = data.get("axial", {})
        data["axial"] = {k: v for k, v in axial.items() if k != "element_length"}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # what the file's reading says, it said once
        again = parse_config(data, config.source)
    return attrs.evolve(
        config, discretization=again.discretization, axial=again.axial, table=again.table
    )


def _refuse_partial_counts(strategy: str, given: Mapping[str, Any], counts: set[str]) -> None:
    """A ConfigError when ``counts`` (of ``given``) count only part of the elements of a
    built-in strategy's chain whose elements ``[axial] element_length`` counts otherwise
    (a part left uncounted would fall to one element)."""
    from torsio.plugins import get_discretizer

    rigid = getattr(get_discretizer(strategy), "rigid_bha", None)
    if rigid is None or counts & {"section_elements", "max_element_length"}:
        return  # a plugin's own counting, or every section counted at once
    needed = {"dp_elements"} if rigid else {"dp_elements", "bha_elements"}
    missing = sorted(needed - counts)
    if missing:
        name = sorted(counts)[0]
        raise ConfigError(
            name,
            f"{given[name]!r} counts part of the axial chain of strategy {strategy!r}, whose "
            "elements [axial] element_length counts otherwise (the part left would fall to "
            f"one element); give {' and '.join(missing)} too",
        )


def _check_counts(discretization: DiscretizationConfig, string: DrillString) -> None:
    """The discretizer's element counts checked against the sections of ``string``."""
    discretizer = discretization.build()
    if hasattr(discretizer, "element_counts"):
        try:
            discretizer.element_counts(string)
        except ConfigError as exc:
            raise ConfigError(f"discretization.{exc.key}", exc.message) from None


def _axial_top_drive(axial: Any, top_drive: Any) -> Any:
    """The axial dynamics with the ``[top_drive]`` of the file (every kind with a set speed:
    the axial engine's steady state, delay and step are those of the set rpm)."""
    if not top_drive.has_set_speed:
        raise ConfigError(
            "top_drive.kind",
            f"{top_drive.kind!r} has no set speed; the axial engine reads its steady state, "
            "delay and step at the set rpm: expected a kind with a set speed (constant-speed, "
            "recorded, pi, soft-torque, z-torque, plugins), or the torque kind from Python "
            "with an rpm",
        )
    if top_drive.kind == "constant-speed":
        return axial  # the held top, as without the table
    if not axial.assembly.has_matrices and top_drive.kind != "recorded":
        raise ConfigError(
            "top_drive",
            f"kind = {top_drive.kind!r} with [discretization] strategy = 'wave': the "
            "distributed axial pipe's top is held, at the set speed or a recorded one "
            "(expected no [top_drive], kind = 'constant-speed' or 'recorded', or a lumped "
            "chain: another strategy)",
        )
    return attrs.evolve(axial, top_drive=top_drive.build())


def _string_config(table: Mapping[str, Any], name: str, source: str) -> Config:
    """A configuration whose model is discretized from the ``[[section]]`` drill-string."""
    default_material = _material(table.get("material"), "material", STEEL)
    raw_sections = table.get("section", [])
    if not isinstance(raw_sections, list):
        raise ConfigError("section", "expected an array of tables [[section]]")
    sections = [
        _section(raw, f"section[{i}]", default_material) for i, raw in enumerate(raw_sections)
    ]
    string = DrillString(sections, name=name)
    discretization = _discretization(table.get("discretization", {}))
    bit_rock = _bit_rock(table["bit_rock"]) if "bit_rock" in table else None
    axial = string_axial(table, string, discretization, bit_rock)
    if axial is None:  # (with axial dynamics the chain is built at once: string_axial)
        _check_counts(discretization, string)
        _warn_if_undamped(table, source)
    elif axial.assembly.has_matrices:  # the chain's discretization, its torsional model too
        discretization = chain_discretization(table, discretization)
    return Config(
        name=name,
        string=string,
        bit_rock=bit_rock,
        damping=_damping(table.get("damping", {})),
        discretization=discretization,
        operation=_operation(table.get("operation", {})),
        simulation=_simulation(table.get("simulation", {})),
        source=source,
        axial=axial,
    )


def _chain_config(table: Mapping[str, Any], name: str, source: str) -> Config:
    """A configuration whose model is the ``[chain]`` table (no string, no discretization)."""
    for key in ("section", "material", "discretization"):
        if key in table:
            what = "[[section]]" if key == "section" else f"[{key}]"
            raise ConfigError(
                key, f"{what} goes with a drill-string; this file gives the model as [chain]"
            )
    chain = parse_chain(table["chain"])
    if "damping" in table and chain.carries_damping:
        given = "dampings" if chain.dampings is not None else "drag"
        raise ConfigError(
            "damping",
            f"damping is given twice: in [chain] ({given}) and in [damping]; give it in "
            "one place ([chain] dampings/drag for a published model's own dampers)",
        )
    bit_rock = None
    if "bit_rock" in table:
        bit_rock = _bit_rock(table["bit_rock"])
        if bit_rock.radius is None:
            raise ConfigError(
                "bit_rock.radius",
                "required with [chain]: a chain has no bit section to take the radius from",
            )
    return Config(
        name=name,
        string=None,
        bit_rock=bit_rock,
        damping=_damping(table.get("damping", {})),
        discretization=DiscretizationConfig("chain"),
        operation=_operation(table.get("operation", {})),
        simulation=_simulation(table.get("simulation", {})),
        source=source,
        chain=chain,
        axial=chain_axial(table, chain, bit_rock),
    )


def _bit_rock(raw: Any) -> BitRockConfig:
    if not isinstance(raw, Mapping):
        raise ConfigError("bit_rock", f"expected a table, got {raw!r}")
    law = _string(raw.get("law", "tucker-wang"), "bit_rock.law")
    radius = raw.get("radius")
    if radius is not None:
        radius = to_si(radius, "length", key="bit_rock.radius")
        if radius <= 0:
            raise ConfigError("bit_rock.radius", f"expected a positive radius, got {radius!r}")
    speed_unit = _string(raw.get("speed_unit", "rad/s"), "bit_rock.speed_unit")
    parameters = {k: v for k, v in raw.items() if k not in ("law", "radius", "speed_unit")}
    config = BitRockConfig(law, radius, speed_unit, parameters)
    if needs_axial(law):  # the RGD bit: built by config/axial.py
        if "speed_unit" in raw:
            raise ConfigError("bit_rock.speed_unit", f"the {law} law has no speed unit; remove it")
        axial_law_from_table(raw)
        return config
    config.build()  # validates the law name and its parameters now, naming the key
    return config


class UndampedWarning(UserWarning):
    """A configuration without damping: the model has no structural damping at all."""


def _warn_if_undamped(table: Mapping[str, Any], source: str) -> None:
    """Warn when neither ``[damping]`` nor a chain's own dampers give any damping."""
    chain = table.get("chain")
    if table.get("damping") or (isinstance(chain, Mapping) and ("dampings" in chain)):
        return
    where = f"{source}: " if source else ""
    warnings.warn(
        UndampedWarning(
            f"{where}no [damping] table: the model is undamped (no structural damping; "
            "stick-slip then never decays). Add [damping] with alpha (1/s) and beta (s) "
            "of Rayleigh damping, or ratios = [z1, z2] at modes = [1, 2]."
        ),
        stacklevel=3,
    )


def _damping(raw: Any) -> DampingConfig:
    table = _table(raw, "damping", DAMPING_KEYS)
    if not table:  # no damping given: alpha and beta stay None (undamped, warned)
        return DampingConfig()
    has_rayleigh = "alpha" in table or "beta" in table
    if has_rayleigh and "ratios" in table:
        raise ConfigError("damping.ratios", "give either alpha/beta or ratios, not both")
    if "modes" in table and "ratios" not in table:
        raise ConfigError("damping.modes", "modes goes with ratios")
    if "ratios" in table:
        ratios = table["ratios"]
        modes = table.get("modes", [1, 2])
        if not (isinstance(ratios, list) and len(ratios) == 2):
            raise ConfigError("damping.ratios", f"expected two damping ratios, got {ratios!r}")
        if not (
            isinstance(modes, list)
            and len(modes) == 2
            and all(isinstance(m, int) and not isinstance(m, bool) and m >= 1 for m in modes)
            and modes[0] != modes[1]
        ):
            raise ConfigError(
                "damping.modes", f"expected two different mode numbers >= 1, got {modes!r}"
            )
        values = tuple(
            _positive_number(r, f"damping.ratios[{i}]", "dimensionless")
            for i, r in enumerate(ratios)
        )
        return DampingConfig(ratios=(values[0], values[1]), modes=(modes[0], modes[1]))
    return DampingConfig(
        alpha=_positive_number(table.get("alpha", 0.0), "damping.alpha", "inverse_time"),
        beta=_positive_number(table.get("beta", 0.0), "damping.beta", "time"),
    )


def _discretization(raw: Any) -> DiscretizationConfig:
    table = _table(raw, "discretization", DISCRETIZATION_KEYS)
    strategy = _string(table.get("strategy", "C"), "discretization.strategy")
    options = {k: v for k, v in table.items() if k != "strategy"}
    if "max_element_length" in options:
        options["max_element_length"] = _positive_number(
            options["max_element_length"],
            "discretization.max_element_length",
            "length",
            allow_zero=False,
        )
    if "time_step" in options:
        options["time_step"] = _positive_number(
            options["time_step"], "discretization.time_step", "time", allow_zero=False
        )
    try:
        DiscretizationConfig(strategy, options).build()
    except ConfigError as exc:
        key = exc.key if exc.key.startswith("discretization") else f"discretization.{exc.key}"
        raise ConfigError(key, exc.message) from None
    except TypeError as exc:
        raise _option_error(strategy, exc) from None
    return DiscretizationConfig(strategy, options)


def _operation(raw: Any) -> OperationConfig:
    table = _table(raw, "operation", OPERATION_KEYS)
    wob = rpm = None
    if "wob" in table:
        wob = _positive_number(table["wob"], "operation.wob", "force")
    if "rpm" in table:
        rpm = parse_rpm(table["rpm"], "operation.rpm")
    return OperationConfig(wob, rpm)


def _simulation(raw: Any) -> SimulationConfig:
    table = _table(raw, "simulation", SIMULATION_KEYS)
    options: dict[str, Any] = {}
    for key in ("duration", "steady_window", "output_step"):
        if key in table:
            options[key] = _positive_number(
                table[key], f"simulation.{key}", "time", allow_zero=False
            )
    for key in ("rtol", "atol", "stick_threshold"):
        if key in table:
            options[key] = _positive_number(
                table[key], f"simulation.{key}", "dimensionless", allow_zero=False
            )
    if "method" in table:
        options["method"] = _string(table["method"], "simulation.method")
    return SimulationConfig(options)  # start, perturbation, step: config/axial.py
