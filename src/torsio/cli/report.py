"""``torsio report``: the whole picture of one configuration."""

from __future__ import annotations

import argparse

from torsio.cli import common


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``report`` command to the ``torsio`` parser."""
    parser = common.add_command(
        subparsers,
        "report",
        run,
        "report on a configuration (default: the built-in example)",
        "The string, its discretization, its first modes against the exact "
        "continuum, their damping ratios and the operating point.",
    )
    common.add_config_argument(parser)
    common.add_discretization_arguments(parser)
    parser.add_argument(
        "--modes", type=int, default=5, metavar="N", help="number of modes shown (default: 5)"
    )
    common.add_units_argument(parser)
    common.add_json_argument(parser)
    parser.add_argument(
        "--html",
        metavar="FILE",
        help="also write the report as a standalone HTML page with its plots "
        "(the plots need matplotlib: the [plot] extra)",
    )


def run(args: argparse.Namespace) -> int:
    """Print the report (rich, or JSON with ``--json``)."""
    from torsio.errors import ConfigError, OutputError
    from torsio.report.context import ReportContext
    from torsio.report.document import render, report_data

    if args.modes < 1:
        raise ConfigError("--modes", f"expected a whole number of modes >= 1, got {args.modes}")
    outputs = common.check_outputs(args, ("html",))
    config = common.load(args)
    # the overrides again: the model is already the file's read with them (common.load),
    # and the report says what they overrode
    options = {**common.discretization_overrides(args), "modes": args.modes, "units": args.units}
    ctx = ReportContext(config, **options)  # computed once, shared by every output
    failed: dict[str, OutputError] = {}
    if args.html:
        from torsio.output_files import write_text
        from torsio.report.html import NO_FIGURES_NOTE, have_matplotlib, html_report

        _, failed = common.write_files({"html": lambda p: write_text(p, html_report(ctx))}, outputs)
        if not have_matplotlib() and not failed:
            import sys

            print(f"torsio report: {args.html} has no figures. {NO_FIGURES_NOTE}", file=sys.stderr)
    if args.json:
        common.print_json(report_data(ctx))
    else:
        render(ctx)
    return common.report_failed_files(args, failed, "the report is on stdout") if failed else 0
