"""``torsio init``: write a commented template configuration that runs as it is."""

from __future__ import annotations

import argparse
from pathlib import Path

from torsio.cli import common

DEFAULT_PATH = "torsio.toml"


def template_text() -> str:
    """The template (``src/torsio/data/template.toml``): every table and key, commented."""
    from importlib import resources

    return resources.files("torsio").joinpath("data/template.toml").read_text(encoding="utf-8")


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``init`` command to the ``torsio`` parser."""
    parser = common.add_command(
        subparsers,
        "init",
        run,
        "write a commented template configuration (default: torsio.toml)",
        "Write a template configuration file with every table and key "
        "explained; it runs as it is (torsio report PATH, torsio simulate PATH ...).",
    )
    parser.add_argument(
        "path", nargs="?", default=DEFAULT_PATH, metavar="PATH", help=f"default {DEFAULT_PATH}"
    )
    parser.add_argument("--force", action="store_true", help="overwrite PATH if it exists")


def run(args: argparse.Namespace) -> int:
    """Write the template; an existing file is kept unless ``--force``."""
    from torsio.errors import ConfigError, OutputError
    from torsio.output_files import write_text

    path = Path(args.path)
    if path.exists() and not args.force:
        raise ConfigError("PATH", f"{args.path!r} exists; give another path or --force")
    try:
        write_text(path, template_text())
    except OutputError as exc:
        raise ConfigError("PATH", str(exc)) from None
    print(
        f"wrote {path}; try: torsio report {path}   or   "
        f'torsio simulate {path} --wob "100 kN" --rpm 60'
    )
    return 0
