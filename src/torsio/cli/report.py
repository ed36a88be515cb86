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
    common.add_json_argument(parser)
    parser.add_argument(
        "--html",
        metavar="FILE",
        help="also write the report as a standalone HTML page with its plots "
        "(the plots need matplotlib: the [plot] extra)",
    )


def run(args: argparse.Namespace) -> int:
    """Print the report (rich, or JSON with ``--json``)."""
    from torsio.errors import ConfigError
    from torsio.report.context import ReportContext
    from torsio.report.document import render, report_data

    if args.modes < 1:
        raise ConfigError("--modes", f"expected a whole number of modes >= 1, got {args.modes}")
    common.check_outputs(args, ("html",))
    config = common.load(args)
    options = {**common.discretization_overrides(args), "modes": args.modes}
    ctx = ReportContext(config, **options)  # computed once, shared by every output
    if args.html:
        from pathlib import Path

        from torsio.report.html import NO_FIGURES_NOTE, have_matplotlib, html_report

        path = Path(args.html)
        try:
            path.write_text(html_report(ctx), encoding="utf-8")
        except OSError as exc:
            raise ConfigError("--html", f"cannot write {args.html!r}: {exc.strerror}") from None
        if not have_matplotlib():
            import sys

            print(f"torsio report: {args.html} has no figures. {NO_FIGURES_NOTE}", file=sys.stderr)
    if args.json:
        common.print_json(report_data(ctx))
    else:
        render(ctx)
    return 0
