"""``torsio laws``: every bit-rock law registered through the hook ``torsio_bit_laws()``
(built-in, the RGD bit of :mod:`torsio.axial.rgd` included, and plugins), its parameters and
what it declares it needs and gives (:func:`torsio.physics.laws.law_capabilities`)."""

from __future__ import annotations

import argparse
import inspect
from typing import Any

from torsio.cli import common
from torsio.physics.laws import law_capabilities


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
    """``name``, ``description``, ``parameters`` and ``class`` of a law class (any plugin's),
    what it declares (``needs_axial``, ``gives``) and the ``engine`` that takes it alone:
    ``"axial"`` for a law that needs axial dynamics, else ``"torsional"`` (such a law also
    runs on an axial chain, ``[chain] masses``)."""
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
    data.update(law_capabilities(cls))
    data["engine"] = "axial" if data["needs_axial"] else "torsional"
    return data


def _signature_parameters(cls: type[Any]) -> list[dict[str, Any]]:
    """The keyword parameters of a plain law class's constructor but ``speed_unit``:
    ``name`` and ``default`` (None where required, its text where not a number), ``unit``
    None (not declared)."""
    try:
        signature = inspect.signature(cls)
    except (TypeError, ValueError):  # a constructor Python cannot inspect
        return []
    named = (inspect.Parameter.POSITIONAL_OR_KEYWORD, inspect.Parameter.KEYWORD_ONLY)
    parameters = []
    for parameter in signature.parameters.values():
        if parameter.kind not in named or parameter.name == "speed_unit":
            continue  # speed_unit is the [bit_rock] table's reading, not a law parameter
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
    from torsio.plugins import bit_laws

    laws = [describe(cls) for _, cls in sorted(bit_laws().items())]
    if args.json:
        common.print_json({"laws": laws})
        return 0
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    table = Table(title="Bit-rock laws (parameters in the rad/s reading; speed_unit='rpm' also)")
    table.caption = escape(
        "needs axial: axial dynamics only ([chain] masses; docs/axial.md); the others run on "
        "every model, an axial chain included"
    )
    table.add_column("name")
    table.add_column("parameters")
    table.add_column("law")
    table.add_column("needs / gives")
    for law in laws:
        parameters = [_parameter_row(p) for p in law["parameters"]]
        needs = "axial" if law["needs_axial"] else "-"
        table.add_row(
            escape(law["name"]),
            escape("\n".join(parameters)),
            escape(law.get("description", "")),
            escape(f"{needs} / {', '.join(law['gives'])}"),
        )
    Console().print(table)
    return 0
