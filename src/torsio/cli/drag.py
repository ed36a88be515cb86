"""``torsio drag``: soft-string torque and drag of the string in its ``[well]``."""

from __future__ import annotations

import argparse
from typing import Any

from torsio.cli import common


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``drag`` command to the ``torsio`` parser."""
    parser = common.add_command(
        subparsers,
        "drag",
        run,
        "soft-string torque and drag: hookloads, surface torque, tension and torque vs depth",
        "Soft-string torque and drag (Johancsik et al. 1984) of the string in the well of "
        "[well]: hookloads tripping out, tripping in, rotating off and on bottom, the "
        "surface torque, and tension and torque against depth. Without CONFIG: the "
        "built-in deviated well (src/torsio/data/deviated_well.toml).",
    )
    parser.add_argument(
        "config",
        nargs="?",
        metavar="CONFIG",
        help="TOML configuration file with [well] (default: the built-in deviated well)",
    )
    parser.add_argument(
        "--friction",
        type=common.finite_float,
        metavar="MU",
        help="friction factor for every hole section, static and sliding (instead of the "
        "well's): the table, the break-off and the sliding torques",
    )
    parser.add_argument(
        "--wob", metavar="W", help="weight on bit on bottom: N or with units (default [operation])"
    )
    parser.add_argument(
        "--rpm",
        metavar="N",
        help="rotary speed on bottom: rpm or with units (default [operation]); the bit law's "
        "torque on bit is taken there",
    )
    parser.add_argument(
        "--bit-torque",
        metavar="T",
        help="torque on bit on bottom: N m or with units (default: the [bit_rock] law's at "
        "the weight on bit and rotary speed; RGD: its steady drilling state)",
    )
    parser.add_argument(
        "--plot", metavar="FILE", help="tension and torque against depth (needs matplotlib)"
    )
    common.add_units_argument(parser)
    common.add_json_argument(parser)


def _load(args: argparse.Namespace) -> Any:
    from torsio.config.reading import load_config
    from torsio.errors import ConfigError
    from torsio.examples import deviated_well_config

    config = deviated_well_config() if args.config is None else load_config(args.config)
    if config.well is None:
        raise ConfigError(
            "well",
            f"{args.config} has no [well] table; torque and drag needs the hole: add [well] "
            'with md, inclination and azimuth (or survey = "file.csv"), see '
            "docs/configuration.md; `torsio drag` alone runs the built-in deviated well",
        )
    return config


def _option(value: str | None, dimension: str, key: str, default: float) -> float:
    from torsio.errors import ConfigError
    from torsio.units import to_si

    if value is None:
        return default
    number = to_si(value, dimension, key=key)
    if number < 0.0:
        raise ConfigError(key, f"expected a non-negative value, got {value!r}")
    return number


def _with_friction(well: Any, friction: float | None) -> Any:
    """``well`` with ``friction`` as its static and sliding factor in every hole section
    (``--friction``: the break-off and sliding torques take it as the table does)."""
    import attrs

    if friction is None:
        return well
    return attrs.evolve(
        well,
        friction_static=friction,
        friction_dynamic=friction,
        hole=tuple(attrs.evolve(h, friction_static=None, friction_dynamic=None) for h in well.hole),
    )


def run(args: argparse.Namespace) -> int:
    """Run ``torsio drag`` with parsed arguments; return the exit status."""
    import functools

    import attrs

    from torsio.config.bit_torque import law_bit_torque
    from torsio.display_units import DisplayUnits
    from torsio.errors import ConfigError
    from torsio.well.break_off import break_off
    from torsio.well.torque_drag import torque_drag
    from torsio.well.wellbore import MAX_FRICTION_FACTOR

    outputs = common.check_outputs(args, ["plot"])
    common.require_plotting(args)
    if args.friction is not None and not 0.0 <= args.friction <= MAX_FRICTION_FACTOR:
        raise ConfigError(
            "--friction",
            f"expected a friction factor from 0 to {MAX_FRICTION_FACTOR:g} (measured factors "
            f"in mud are 0.1 to 0.5), got {args.friction:g}",
        )
    common.warn_small_bare_wob(args.wob)
    config = _load(args)
    wob = _option(args.wob, "force", "--wob", config.operation.wob or 0.0)
    if args.bit_torque is not None:
        if args.rpm is not None:
            raise ConfigError(
                "--rpm",
                "sets where the bit law's torque on bit is taken, and --bit-torque gives that "
                "torque: give one of them",
            )
        bit_torque = _option(args.bit_torque, "torque", "--bit-torque", 0.0)
        source = "given (--bit-torque)"
    else:
        bit_torque, source = law_bit_torque(config, wob, args.rpm)
    results = torque_drag(
        config.well, config.string, friction=args.friction, wob=wob, bit_torque=bit_torque
    )
    results = attrs.evolve(
        results,
        bit_torque_source=source,
        break_off=break_off(_with_friction(config.well, args.friction), config.string),
    )
    units = DisplayUnits(args.units)
    writers: dict[str, Any] = {"plot": functools.partial(results.plot, units=units)}
    return common.write_and_print(
        args, results, outputs, functools.partial(_print_table, units=units), writers
    )


def _print_table(results: Any, written: dict[str, str], units: Any) -> None:
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    force, torque = units.label("force"), units.label("torque")
    table = Table(title="Soft-string torque and drag")
    for name in (
        "operation",
        units.header("hookload", "force"),
        units.header("surface torque", "torque"),
    ):
        table.add_column(escape(name), justify="left" if name == "operation" else "right")
    table.add_row(
        "tripping out (pick-up)", units.number("force", results.hookload_trip_out, ".1f"), "-"
    )
    table.add_row(
        "tripping in (slack-off)", units.number("force", results.hookload_trip_in, ".1f"), "-"
    )
    table.add_row(
        "rotating off bottom",
        units.number("force", results.hookload_rotating, ".1f"),
        units.number("torque", results.surface_torque_rotating, ".2f"),
    )
    table.add_row(
        f"rotating on bottom (WOB {units.number('force', results.wob, '.4g')} {force}, "
        f"bit {units.number('torque', results.bit_torque, '.3g')} {torque}: "
        f"{results.bit_torque_source})",
        units.number("force", results.hookload_on_bottom, ".1f"),
        units.number("torque", results.surface_torque_on_bottom, ".2f"),
    )
    console = Console()
    console.print(table)
    neutral = results.neutral_point_md
    lines = [
        f"buoyed weight of the string {units.text('force', results.buoyed_weight, '.1f')}; "
        f"string top at md {units.text('length', results.string_top_md, 'g')}, "
        f"bit at md {units.text('length', results.md[-1], 'g')}",
        "neutral point on bottom: " + _neutral_point(results, neutral, units),
        f"normal force: {results.normal_force_model}"
        + (
            ""
            if results.friction is None
            else f"; friction factor {results.friction:g} everywhere (static and sliding)"
        ),
    ]
    if results.break_off is not None:
        lines.append(
            "break-off from rest (static friction): "
            f"{units.text('torque', results.break_off.torque, '.2f')} "
            f"at the top after a twist of {results.break_off.twist:.2f} rad "
            f"({results.break_off.twist / (2 * 3.141592653589793):.2f} turns); sliding "
            f"{units.text('torque', results.break_off.sliding_torque, '.2f')}"
        )
    if "plot" in written:
        lines.append(f"wrote {written['plot']}")
    for line in lines:
        console.print(line, highlight=False)


def _neutral_point(results: Any, neutral: float | None, units: Any) -> str:
    """Where the on-bottom tension changes sign, or why there is no such point."""
    if neutral is not None:
        return f"md {units.text('length', neutral, '.0f')}"
    if results.all_in_compression:
        return (
            f"above the top: the whole string is in compression (hookload on bottom "
            f"{units.text('force', results.hookload_on_bottom, '.1f')}: the weight on bit "
            "exceeds what the "
            "string's weight holds)"
        )
    return "none (the string is nowhere in compression)"
