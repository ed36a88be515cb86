"""``torsio init``: write a commented template configuration that runs as it is, or one of
the built-in examples (:func:`torsio.examples.example_names`)."""

from __future__ import annotations

import argparse
from pathlib import Path

from torsio.cli import common

DEFAULT_PATH = "torsio.toml"


def template_text() -> str:
    """The template (``src/torsio/data/template.toml``): every table and key, commented."""
    from torsio.examples import TEMPLATE, data_text

    return data_text(TEMPLATE)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``init`` command to the ``torsio`` parser."""
    parser = common.add_command(
        subparsers,
        "init",
        run,
        "write a commented template configuration (default: torsio.toml), or a built-in example",
        "Write a template configuration file with every table and key "
        "explained; it runs as it is (torsio report PATH, torsio simulate PATH ...). "
        "--example NAME writes a built-in example instead (--list names them).",
    )
    parser.add_argument(
        "path",
        nargs="?",
        metavar="PATH",
        help=f"default {DEFAULT_PATH}, or NAME.toml with --example",
    )
    parser.add_argument("--force", action="store_true", help="overwrite PATH if it exists")
    parser.add_argument(
        "--example", metavar="NAME", help="a built-in example (rgd_2dof, ritto2017, ...)"
    )
    parser.add_argument("--list", action="store_true", help="list the built-in examples")


def run(args: argparse.Namespace) -> int:
    """Write the template or the example; an existing file is kept unless ``--force``."""
    from torsio.errors import ConfigError, OutputError
    from torsio.examples import example_names, example_summary, example_text
    from torsio.output_files import write_text

    if args.list:
        if args.example is not None or args.path is not None:
            raise ConfigError("--list", "lists the examples; it takes no PATH or --example")
        for name in example_names():
            print(f"{name:<28} {example_summary(name)}")
        return 0
    text = template_text() if args.example is None else example_text(args.example)
    default = DEFAULT_PATH if args.example is None else f"{args.example}.toml"
    path = Path(args.path if args.path is not None else default)
    if path.exists() and not args.force:
        raise ConfigError("PATH", f"{str(path)!r} exists; give another path or --force")
    try:
        write_text(path, text)
    except OutputError as exc:
        raise ConfigError("PATH", str(exc)) from None
    print(f"wrote {path}; try: {'   or   '.join(_commands(text, path, args.example))}")
    return 0


def _commands(text: str, path: Path, example: str | None) -> list[str]:
    """The first two commands on the file that its opening comment suggests (``#   torsio
    ... this.toml``, a remark in parentheses after it left out), run on ``path``."""
    names = ["this.toml"] + ([f"{example}.toml"] if example is not None else [])
    found = []
    for line in text.splitlines():
        if line.startswith("#   torsio "):
            command = line.lstrip("# ").partition("  (")[0].strip()
            if any(name in command for name in names):  # a command on this file
                for name in names:
                    command = command.replace(name, str(path))
                found.append(command)
    return found[:2]
