"""``torsio report``: the whole picture of one configuration."""

from __future__ import annotations

import argparse

from torsio.cli.common import add_config_argument, load


def register(subparsers: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    parser = subparsers.add_parser(
        "report", help="report on a configuration (default: the built-in example)",
        description="The string, its discretization and its modes against the continuum.")
    add_config_argument(parser)
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from rich.console import Console

    from torsio.report import render

    render(load(args), Console())
    return 0
