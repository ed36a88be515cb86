"""The ``torsio`` command line.

Each command lives in its own module of this package with a ``register(subparsers)``
function. ``--json`` prints one JSON object on stdout and nothing else. Errors go
to stderr, name the offending key or value, and exit with status 2.
"""

from __future__ import annotations

import argparse
import contextlib
import gc
import signal
import sys
import warnings
from collections.abc import Iterator, Sequence
from typing import Any

from torsio.errors import TorsioError
from torsio.stop_signals import stop_signals

COMMANDS = ("report", "modes", "simulate", "map", "advise", "drag", "fit", "laws", "init")


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The argument parser with every command registered; the flags a command takes from
    its options class (``torsio map``'s MapOptions) are added for ``command`` (None: all)."""
    import importlib

    from torsio import __version__
    from torsio.cli.common import OPTION_FLAGS, add_option_flags

    parser = argparse.ArgumentParser(
        prog="torsio",
        description="Torsional dynamics of drill-strings: modes, stick-slip, severity maps.",
    )
    parser.add_argument("--version", action="version", version=f"torsio {__version__}")
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND")
    subparsers.required = True
    for name in COMMANDS:
        try:
            module = importlib.import_module(f"torsio.cli.{name}")
        except ModuleNotFoundError as exc:
            if exc.name == f"torsio.cli.{name}":
                continue  # command not available in this build
            raise
        module.register(subparsers)
    for name, (command_parser, options) in OPTION_FLAGS.items():
        if command in (None, name):
            add_option_flags(command_parser, options())
    return parser


@contextlib.contextmanager
def _warning_format(command: str) -> Iterator[None]:
    """Warnings printed as one line on stderr: ``torsio COMMAND: warning: message``."""
    original = warnings.formatwarning

    def one_line(message: Warning | str, category: type[Warning], *args: Any, **kw: Any) -> str:
        return f"torsio {command}: warning: {message}\n"

    warnings.formatwarning = one_line
    try:
        yield
    finally:
        warnings.formatwarning = original


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``torsio`` console script; returns the exit status."""
    words = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser(next((w for w in words if not w.startswith("-")), ""))
    args = parser.parse_args(words)
    stdout = sys.stdout
    sys.stdout = _Stdout(stdout)
    with stop_signals() as received:
        try:
            with warnings.catch_warnings(), _warning_format(args.command):
                warnings.simplefilter("default")
                status = args.run(args)
            sys.stdout.flush()  # a full stdout fails here, not at the exit
        except _StdoutFailed as exc:  # stdout on a full disk, /dev/full, an I/O error
            _discard_stdout(stdout)
            print(f"torsio {args.command}: error: cannot write to stdout: {exc}", file=sys.stderr)
            return 2
        except TorsioError as exc:
            print(f"torsio {args.command}: error: {exc}", file=sys.stderr)
            return 2
        except KeyboardInterrupt:  # SIGINT or SIGTERM (partial results kept, workers stopped)
            terminated = signal.SIGTERM in received
            what = "terminated (SIGTERM)" if terminated else "interrupted"
            print(f"torsio {args.command}: {what}", file=sys.stderr)
            return 143 if terminated else 130
        except BrokenPipeError:  # output piped into a program that stopped reading (| head)
            _discard_stdout(stdout)
            return 0
        finally:
            sys.stdout = stdout
    return int(status or 0)


class _StdoutFailed(Exception):
    """stdout could not be written (not a closed pipe); the OS's reason."""


class _Stdout:
    """sys.stdout whose failures (other than a closed pipe) are :class:`_StdoutFailed`, told
    apart from those of the files a command reads or writes."""

    def __init__(self, stream: Any) -> None:
        self._stream = stream

    def write(self, text: str) -> int:
        try:
            return int(self._stream.write(text))
        except BrokenPipeError:
            raise
        except OSError as exc:
            raise _StdoutFailed(exc.strerror or str(exc)) from None

    def flush(self) -> None:
        try:
            self._stream.flush()
        except BrokenPipeError:
            raise
        except OSError as exc:
            raise _StdoutFailed(exc.strerror or str(exc)) from None

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)


def _discard_stdout(stdout: Any) -> None:
    """Point stdout's descriptor at the null device: what is still buffered for it is
    dropped at the exit instead of failing again there."""
    import os

    try:
        descriptor = stdout.fileno()
    except (OSError, ValueError, AttributeError):
        return  # not a file (captured output)
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, descriptor)
    os.close(null)


def console_main() -> int:
    """The ``torsio`` console script and ``python -m torsio``: :func:`main`, then every
    object the garbage collector tracks frozen (:func:`gc.freeze`), so that the process's
    exit does not scan them again. numba's type registries make that scan about 0.2 s of
    every command that runs a kernel; what :func:`main` opened it has closed, and
    ``atexit`` handlers and the flush of stdout and stderr run as before."""
    status = main()
    gc.freeze()
    return status


if __name__ == "__main__":  # pragma: no cover
    sys.exit(console_main())
