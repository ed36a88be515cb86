"""``torsio modes``: natural frequencies of the discretized string against the continuum."""

from __future__ import annotations

import argparse

from torsio.cli.common import (
    add_config_argument,
    add_discretization_arguments,
    discretization_overrides,
    load,
    print_json,
)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``modes`` command to the ``torsio`` parser."""
    parser = subparsers.add_parser(
        "modes",
        help="natural frequencies and their error against the exact continuum",
        description="Natural frequencies of the lumped model against the exact continuum.",
    )
    add_config_argument(parser)
    add_discretization_arguments(parser)
    parser.add_argument(
        "--count",
        type=int,
        default=None,
        metavar="N",
        help="number of modes (default: all, at most 10)",
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """Run ``torsio modes`` with parsed arguments; return the exit status."""
    from rich.console import Console

    from torsio.errors import ConfigError
    from torsio.io.report import modes_table
    from torsio.model.modal import modal_analysis

    config = load(args)
    model = config.model(**discretization_overrides(args))
    if args.count is not None and args.count < 1:
        raise ConfigError("--count", f"expected a whole number of modes >= 1, got {args.count}")
    count = args.count if args.count is not None else min(model.dofs, 10)
    results = modal_analysis(model, count, string=config.string)
    comparison = results.compare()
    if args.json:
        data = results.to_dict()
        data.update(comparison.to_dict())
        data["count"] = int(results.frequencies_rad.size)
        print_json(data)
        return 0
    Console().print(modes_table(comparison))
    return 0
