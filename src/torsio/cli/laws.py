"""``torsio laws``: the registered bit-rock laws and their parameters (plugins included),
and the RGD bit of the axial engine (a law with memory, :mod:`torsio.axial.rgd`)."""

from __future__ import annotations

import argparse
import inspect
from typing import Any

from torsio.cli import common


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``laws`` command to the ``torsio`` parser."""
    parser = common.add_command(
        subparsers,
        "laws",
        run,
        "registered bit-rock laws (built-in and plugins) and their parameters",
        "List every registered bit-rock law, built-in or from a plugin.",
    )
    common.add_json_argument(parser)


def describe(cls: type[Any]) -> dict[str, Any]:
    """``name``, ``description`` and ``parameters`` of a law class (any plugin's)."""
    if hasattr(cls, "describe"):
        data = dict(cls.describe())
    else:  # a law that does not subclass BitRockLaw: its keyword parameters, units unknown
        doc = (cls.__doc__ or "").strip().splitlines()
        data = {
            "name": cls.name,
            "description": doc[0] if doc else "",
            "parameters": _signature_parameters(cls),
        }
    data.setdefault("parameters", [])
    data["class"] = f"{cls.__module__}.{cls.__qualname__}"
    return data


def _signature_parameters(cls: type[Any]) -> list[dict[str, Any]]:
    """The keyword parameters of a plain law class's constructor: ``name`` and ``default``
    (None where required, its text where not a number), ``unit`` None (not declared)."""
    try:
        signature = inspect.signature(cls)
    except (TypeError, ValueError):  # a constructor Python cannot inspect
        return []
    named = (inspect.Parameter.POSITIONAL_OR_KEYWORD, inspect.Parameter.KEYWORD_ONLY)
    parameters = []
    for parameter in signature.parameters.values():
        if parameter.kind not in named:
            continue
        default = None if parameter.default is inspect.Parameter.empty else parameter.default
        if not (default is None or isinstance(default, int | float)):
            default = str(default)
        parameters.append({"name": parameter.name, "unit": None, "default": default})
    return parameters


def _parameter_row(parameter: dict[str, Any]) -> str:
    """``name [unit] = default`` (``required`` without one; no brackets without a unit)."""
    default = parameter.get("default")
    if default is None:
        default = "required"
    elif isinstance(default, int | float) and not isinstance(default, bool):
        default = f"{default:g}"
    unit = parameter.get("unit")
    return f"{parameter['name']}{'' if unit is None else f' [{unit}]'} = {default}"


def run(args: argparse.Namespace) -> int:
    """Run ``torsio laws`` with parsed arguments; return the exit status."""
    from torsio.axial.rgd import law_description
    from torsio.plugins import bit_laws

    laws = [{**describe(cls), "engine": "torsional"} for _, cls in sorted(bit_laws().items())]
    laws.append(law_description())
    if args.json:
        common.print_json({"laws": laws})
        return 0
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    table = Table(title="Bit-rock laws (parameters in the rad/s reading; speed_unit='rpm' also)")
    table.caption = "rgd: the axial engine's law (axial dynamics only; docs/axial.md)"
    table.add_column("name")
    table.add_column("parameters")
    table.add_column("law")
    for law in laws:
        parameters = [_parameter_row(p) for p in law["parameters"]]
        table.add_row(
            escape(law["name"]), escape("\n".join(parameters)), escape(law.get("description", ""))
        )
    Console().print(table)
    return 0
