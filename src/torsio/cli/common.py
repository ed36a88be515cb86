"""Helpers shared by the CLI commands: the configuration argument and JSON output."""

from __future__ import annotations

import argparse
import json
import math
import sys
from typing import TYPE_CHECKING, Any

from torsio.errors import ConfigError

if TYPE_CHECKING:
    from torsio.io.config import Config


def add_config_argument(parser: argparse.ArgumentParser) -> None:
    """The optional CONFIG positional (default: the built-in Ritto 2017 string)."""
    parser.add_argument(
        "config",
        nargs="?",
        metavar="CONFIG",
        help="TOML configuration file (default: the built-in Ritto et al. 2017 example)",
    )


def add_discretization_arguments(parser: argparse.ArgumentParser) -> None:
    """--strategy, --dp-elements, --bha-elements (override the file)."""
    parser.add_argument("--strategy", help="discretizer name (A, B, C, consistent, mixed, ...)")
    parser.add_argument(
        "--dp-elements", type=int, metavar="N", help="elements (DOFs) in the drill pipes"
    )
    parser.add_argument("--bha-elements", type=int, metavar="N", help="elements (DOFs) in the BHA")


def discretization_overrides(args: argparse.Namespace) -> dict[str, Any]:
    """The discretization options given on the command line."""
    return {
        "strategy": args.strategy,
        "dp_elements": args.dp_elements,
        "bha_elements": args.bha_elements,
    }


def parse_time(value: str | None, key: str) -> float | None:
    """A time option: a bare number in s, or a string with units ("5 min"); None stays None."""
    from torsio.units import to_si

    if value is None:
        return None
    try:
        number = float(value)
    except ValueError:
        number = to_si(value, "time", key=key)
    if not (math.isfinite(number) and number > 0):
        raise ConfigError(key, f"expected a positive finite time, got {value!r}")
    return number


def finite_float(text: str) -> float:
    """argparse type of a number option: a finite float (``nan`` and ``inf`` are refused)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return value


def load(args: argparse.Namespace) -> Config:
    """The configuration named on the command line, or the built-in one."""
    from torsio.io.config import builtin_config, load_config

    return builtin_config() if args.config is None else load_config(args.config)


def _clean(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_clean(v) for v in value]
    return value


def print_json(data: dict[str, Any]) -> None:
    """One JSON object on stdout (non-finite numbers become null)."""
    json.dump(_clean(data), sys.stdout, indent=2)
    sys.stdout.write("\n")
