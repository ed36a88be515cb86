"""``torsio modes``: natural frequencies of the discretized string against the continuum."""

from __future__ import annotations

import argparse
from typing import Any

from torsio.cli import common


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``modes`` command to the ``torsio`` parser."""
    parser = common.add_command(
        subparsers,
        "modes",
        run,
        "natural frequencies and their error against the exact continuum",
        "Natural frequencies of the lumped model against the exact continuum.",
    )
    common.add_config_argument(parser)
    common.add_discretization_arguments(parser)
    parser.add_argument(
        "--count",
        type=int,
        default=None,
        metavar="N",
        help="number of modes (default: all, at most 10)",
    )
    common.add_json_argument(parser)


def run(args: argparse.Namespace) -> int:
    """Run ``torsio modes`` with parsed arguments; return the exit status."""
    from rich.console import Console
    from rich.markup import escape

    from torsio.errors import ConfigError
    from torsio.model.modal import modal_analysis
    from torsio.report.axial import axial_modes
    from torsio.report.model import modes_table

    config = common.load(args)
    model = config.model()
    if args.count is not None and args.count < 1:
        raise ConfigError("--count", f"expected a whole number of modes >= 1, got {args.count}")
    axial = axial_modes(config, args.count)  # empty without axial dynamics
    if not model.has_matrices:  # the distributed model: the exact continuum of its grid
        return _wave_modes(model, args.count or 10, args.json, axial)
    count = args.count if args.count is not None else min(model.dofs, 10)
    results = modal_analysis(model, count, string=config.string)
    if config.string is None:  # a [chain]: no continuum reference
        return _print_chain_modes(results, args.json, axial)
    comparison = results.compare()
    shown = int(results.frequencies_rad.size)
    cut = None
    if args.count is not None and shown < args.count:
        cut = (
            f"{shown} mode{'s' if shown != 1 else ''} shown of the {args.count} asked: "
            f"strategy {model.strategy} has {model.dofs} "
            f"degree{'s' if model.dofs != 1 else ''} of freedom"
        )
    if args.json:
        data = results.to_dict()
        data.update(comparison.to_dict())
        data["count"] = shown
        if args.count is not None:
            data["count_requested"] = args.count
        common.print_json({**data, **axial})
        return 0
    console = Console()
    rigid = comparison.reference.rigid_bha
    console.print(
        escape(
            f"strategy {model.strategy}, {model.dofs} DOF{'s' if model.dofs != 1 else ''}"
            f" ({config.string.name if config.string is not None else 'model'}); "
            "continuum: the exact solution of the string as given (flexible BHA)"
            + ("; rigid BHA: the same with the BHA rigid, this strategy's limit" if rigid else "")
        )
    )
    console.print(modes_table(comparison))
    if cut is not None:
        console.print(escape(f"note: {cut}"))
    _print_axial(console, axial)
    return 0


def _print_axial(console: Any, axial: dict[str, Any]) -> None:
    """The axial frequencies of :func:`~torsio.report.axial.axial_modes`, if any."""
    if axial:
        values = ", ".join(f"{f:.5g}" for f in axial["axial_frequencies_hz"])
        values = values or "none (axially rigid)"
        console.print(f"axial frequencies [Hz] ({axial['axial_boundaries']}): {values}")


def _print_chain_modes(results: Any, as_json: bool, axial: dict[str, Any]) -> int:
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    from torsio.report.model import NO_CONTINUUM

    if as_json:
        data = results.to_dict()
        data.update({"continuum_hz": None, "relative_error": None, "continuum": NO_CONTINUUM})
        data["count"] = int(results.frequencies_rad.size)
        common.print_json({**data, **axial})
        return 0
    table = Table(title=f"Modes of the {results.model.dofs}-DOF chain")
    table.add_column("mode", justify="right")
    table.add_column("frequency [Hz]", justify="right")
    table.add_column("period [s]", justify="right")
    for i, f in enumerate(results.frequencies_hz):
        table.add_row(str(i + 1), f"{f:.5f}", f"{1.0 / f:.4g}")
    console = Console()
    console.print(table)
    console.print(escape(f"exact continuum: {NO_CONTINUUM}"), soft_wrap=True)
    _print_axial(console, axial)
    return 0


def _wave_modes(model: Any, count: int, as_json: bool, axial: dict[str, Any]) -> int:
    """The wave model rings at the exact continuum of its grid string (section lengths
    rounded to whole cells); ``continuum_hz`` is the string as given."""
    from rich.console import Console
    from rich.table import Table

    from torsio.model.continuum import continuum_modes

    grid = continuum_modes(model.grid_string(), count).frequencies_hz
    exact = continuum_modes(model.string, count).frequencies_hz
    if as_json:
        common.print_json(
            {
                "strategy": "wave",
                "dofs": model.dofs,
                "frequencies_hz": grid.tolist(),
                "continuum_hz": exact.tolist(),
                "count": count,
                "time_step_s": model.time_step,
                "travel_time_errors": model.travel_time_errors.tolist(),
                **axial,
            }
        )
        return 0
    table = Table(title=f"Wave model (dt = {model.time_step * 1e3:.4g} ms, cells {model.cells})")
    for name in ("mode", "wave model [Hz]", "continuum [Hz]", "error [%]"):
        table.add_column(name, justify="right")
    for i, (f, e) in enumerate(zip(grid, exact, strict=True), start=1):
        table.add_row(str(i), f"{f:.6g}", f"{e:.6g}", f"{100 * (f - e) / e:+.2e}")
    console = Console()
    console.print(table)
    _print_axial(console, axial)
    return 0
