"""Helpers shared by the CLI commands: the parser of a command, the arguments several
commands take (configuration, discretization, run times, output files, JSON) and JSON
output."""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from torsio.errors import ConfigError, OutputError

if TYPE_CHECKING:
    from torsio.config.configuration import Config


OPTION_FLAGS: dict[str, tuple[argparse.ArgumentParser, Callable[[], type]]] = {}
"""Commands whose flags come from an options class: the parser and how to get the class
(imported only when that command runs: ``torsio --help`` loads no engine)."""


def add_command(
    subparsers: argparse._SubParsersAction,
    name: str,
    run: Callable[[argparse.Namespace], int],
    summary: str,
    description: str,
    options: Callable[[], type] | None = None,
) -> argparse.ArgumentParser:
    """The parser of the command ``torsio NAME``: ``summary`` for ``torsio --help``,
    ``description`` for its own help, ``run(args)`` returns the exit status; ``options()``
    gives the options class whose flags it takes (:func:`add_option_flags`)."""
    parser: argparse.ArgumentParser = subparsers.add_parser(
        name, help=summary, description=description
    )
    parser.set_defaults(run=run)
    if options is not None:
        OPTION_FLAGS[name] = (parser, options)
    return parser


def add_option_flags(parser: argparse.ArgumentParser, options: type) -> None:
    """The flags of an options class (attrs fields whose metadata name a ``flag`` and its
    ``help``; :class:`torsio.analysis.map_options.MapOptions`), typed by their defaults
    (finite numbers, whole numbers, words; ``choices`` where given), default None (the
    options class holds the default, and checks every value). Fields whose flag has no
    help are added elsewhere (the run length and window: :func:`add_run_time_arguments`)."""
    import attrs

    for field in attrs.fields(options):
        flag, help_text = field.metadata.get("flag"), field.metadata.get("help")
        if not (flag and help_text):
            continue
        default = field.default
        annotation = str(field.type)  # "float | None", "int", "str" (postponed annotations)
        kind: Callable[[str], Any] = str
        metavar = "NAME"
        if annotation.startswith("float"):
            kind, metavar = finite_float, "X"
        elif annotation.startswith("int"):
            kind, metavar = int, "N"
        shown = "" if default is None or "default" in help_text else f" (default {default})"
        parser.add_argument(
            flag,
            dest=flag[2:].replace("-", "_"),
            type=kind,
            default=None,
            choices=field.metadata.get("choices"),
            metavar=None if field.metadata.get("choices") else metavar,
            help=help_text + shown,
        )


def add_json_argument(parser: argparse.ArgumentParser) -> None:
    """--json: print one JSON object instead of the terminal layout."""
    parser.add_argument("--json", action="store_true", help="print one JSON object")


def add_units_argument(parser: argparse.ArgumentParser) -> None:
    """--units: the units of tables and plots (torsio.display_units); JSON stays SI."""
    parser.add_argument(
        "--units",
        choices=("si", "field"),
        default="si",
        help="units of the printed tables (and of torsio drag's plot): si (kN, kN m, m; "
        "default) or field (klbf, kft·lbf, ft, ppg); JSON stays SI",
    )


def add_run_time_arguments(
    parser: argparse.ArgumentParser, length: str = "run length", run: str = "the run"
) -> None:
    """--duration (``length``) and --window (the steady-state window at the end of ``run``)."""
    parser.add_argument(
        "--duration", metavar="T", help=f"{length}: s or with units (default: 40 periods)"
    )
    parser.add_argument(
        "--window",
        metavar="T",
        help=f"steady-state window at the end of {run}: s or with units (default: 15 periods)",
    )


def add_file_outputs(parser: argparse.ArgumentParser, csv: str, plot: str) -> None:
    """--csv FILE (``csv``: what its rows are) and --plot FILE (``plot``: what the PNG shows)."""
    parser.add_argument("--csv", metavar="FILE", help=csv)
    parser.add_argument("--plot", metavar="FILE", help=f"{plot} (needs matplotlib)")


def require_plotting(args: argparse.Namespace) -> None:
    """A clear error before any work if ``--plot`` is given and matplotlib is missing."""
    if getattr(args, "plot", None) is None:
        return
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        raise ConfigError(
            "--plot", "needs matplotlib, which is not installed; pip install 'torsio[plot]'"
        ) from None


def refuse_rpm_without_set_speed(config: Config, rpm: Any, consequence: str) -> None:
    """A clear error if a rotary speed is given for a top drive that takes none (torque
    driven, or following a recording)."""
    follows = config.top_drive.speed_follows
    if rpm is not None and follows is not None:
        if config.top_drive.kind == "recorded":
            consequence = "; remove --rpm, or use another top_drive.kind"
        raise ConfigError(
            "--rpm",
            f"the top drive is {config.top_drive.kind!r} (top_drive.kind): {follows}{consequence}",
        )


def write_and_print(
    args: argparse.Namespace,
    results: Any,
    outputs: dict[str, str],
    summary: Callable[[Any, dict[str, str]], None],
    writers: dict[str, Callable[[str], object]] | None = None,
    everything: Callable[[], dict[str, Any]] | None = None,
) -> int:
    """Write the files ``outputs`` names (``out``: ``results.save``, ``csv``:
    ``results.to_csv``, ``plot``: ``results.plot``, others: ``writers[option](path)``),
    then print ``results.to_dict()`` with the paths written as one JSON object
    (``--json``) or ``summary(results, written)``. Each of ``results.warnings`` (what
    limits the meaning of the result) goes to stderr as ``torsio COMMAND: warning: ...``.

    A file that cannot be written (a full disk) loses nothing computed: the other files
    are written, the results are printed as JSON on stdout (``everything()``, default
    ``results.to_dict()``: all a file would have held) whatever ``--json`` says, and each
    failure is named on stderr. Returns the exit status: 0, or 2 if a file failed.
    """
    for text in getattr(results, "warnings", ()):
        print(f"torsio {args.command}: warning: {text}", file=sys.stderr)
    methods = {"out": "save", "csv": "to_csv", "plot": "plot"}
    chosen = {k: (writers or {}).get(k) or getattr(results, methods[k]) for k in outputs}
    written, failed = write_files(chosen, outputs)
    if failed:
        data = everything() if everything is not None else results.to_dict()
        data.update(written)
        print_json(data)
        return report_failed_files(args, failed, "the results are on stdout as JSON")
    if args.json:
        data = results.to_dict()
        data.update(written)
        print_json(data)
    else:
        summary(results, written)
    return 0


def write_files(
    writers: dict[str, Callable[[str], object]], outputs: dict[str, str]
) -> tuple[dict[str, str], dict[str, OutputError]]:
    """Call ``writers[option](path)`` for each output file (by option, ``outputs``); a file
    that cannot be written (:class:`~torsio.errors.OutputError`) does not stop the others.
    Returns the paths written and the failures, by option."""
    written: dict[str, str] = {}
    failed: dict[str, OutputError] = {}
    for option, write in writers.items():
        try:
            write(outputs[option])
        except OutputError as exc:
            failed[option] = exc
        else:
            written[option] = outputs[option]
    return written, failed


def report_failed_files(args: argparse.Namespace, failed: dict[str, OutputError], kept: str) -> int:
    """Each file that could not be written on stderr as ``torsio COMMAND: error: --OPTION:
    cannot write 'PATH': REASON; KEPT`` (``kept``: where the results went instead);
    returns the exit status, 2."""
    for option, exc in failed.items():
        print(f"torsio {args.command}: error: --{option}: {exc}; {kept}", file=sys.stderr)
    return 2


def add_config_argument(parser: argparse.ArgumentParser) -> None:
    """The optional CONFIG positional (default: the built-in Ritto 2017 string)."""
    parser.add_argument(
        "config",
        nargs="?",
        metavar="CONFIG",
        help="TOML configuration file (default: the built-in Ritto et al. 2017 example)",
    )


def add_executor_arguments(parser: argparse.ArgumentParser, threads: str) -> None:
    """--threads (``threads`` its help), --workers, --scheduler: where a command's points run."""
    parser.add_argument("--threads", type=int, metavar="N", help=threads)
    parser.add_argument("--workers", type=int, metavar="N", help="run on N local worker processes")
    parser.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="run on a Dask scheduler (e.g. tcp://host:8786; needs the dask extra)",
    )


def executor_choice(args: argparse.Namespace) -> Any:
    """The executor of --workers or --scheduler (None: this process), checked."""
    if args.workers is not None and args.scheduler is not None:
        raise ConfigError("--workers", "give either --workers or --scheduler, not both")
    if args.workers is not None and args.workers < 1:
        raise ConfigError("--workers", f"expected a number of processes >= 1, got {args.workers}")
    return args.workers if args.workers is not None else args.scheduler


def add_discretization_arguments(parser: argparse.ArgumentParser) -> None:
    """--strategy, --dp-elements, --bha-elements (override the file)."""
    parser.add_argument("--strategy", help="discretizer name (A, B, C, consistent, mixed, ...)")
    parser.add_argument(
        "--dp-elements", type=int, metavar="N", help="elements (DOFs) in the drill pipes"
    )
    parser.add_argument("--bha-elements", type=int, metavar="N", help="elements (DOFs) in the BHA")


def discretization_overrides(args: argparse.Namespace) -> dict[str, Any]:
    """The discretization options given on the command line (:func:`load` applies them to
    the configuration; ``torsio fit`` reads its strategy from them too)."""
    return {name: getattr(args, name) for name in DISCRETIZATION_FLAGS}


def parse_time(value: str | None, key: str, *, allow_zero: bool = False) -> float | None:
    """A time option: a bare number in s, or a string with units ("5 min"); None stays None.

    ``allow_zero`` admits 0 (an option whose 0 means "none", such as a smoothing window).
    """
    from torsio.units import to_si

    if value is None:
        return None
    try:
        number = float(value)
    except ValueError:
        number = to_si(value, "time", key=key)
    if not (math.isfinite(number) and (number > 0 or (allow_zero and number == 0))):
        expected = "a finite time >= 0" if allow_zero else "a positive finite time"
        raise ConfigError(key, f"expected {expected}, got {value!r}")
    return number


def finite_float(text: str) -> float:
    """argparse type of a number option: a finite float (``nan`` and ``inf`` are refused)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return value


def check_outputs(args: argparse.Namespace, options: Sequence[str]) -> dict[str, str]:
    """Check, before any work, that every output file named by ``options`` can be written.

    ``options`` are attribute names of ``args`` (``"out"``, ``"csv"``, ``"plot"``,
    ``"html"``). Each given path must lie in an existing folder where a file can be
    created, must not be a folder, the configuration file or another output. A plot
    without a suffix gets ``.png`` (as matplotlib would write it); a suffix that
    matplotlib cannot write is an error. Returns the paths to write, by option.
    """
    paths: dict[str, str] = {}
    seen: dict[Path, str] = {}
    if getattr(args, "config", None) is not None:
        seen[Path(args.config).resolve()] = "the configuration file"
    for name in options:
        value = getattr(args, name, None)
        if value is None:
            continue
        option = f"--{name}"
        if name == "plot":
            value = _plot_path(value, option)
        path = Path(value)
        resolved = path.resolve()
        if resolved in seen:
            raise ConfigError(option, f"{value!r} is also {seen[resolved]}; name another file")
        seen[resolved] = f"the file of --{name}"
        if resolved.is_dir():
            raise ConfigError(option, f"{value!r} is a folder; expected a file name")
        folder = resolved.parent
        if not folder.is_dir():
            raise ConfigError(option, f"directory of {value!r} does not exist")
        if resolved.exists() and not resolved.is_file():
            raise ConfigError(option, f"{value!r} exists and is not a regular file")
        _try_create(folder, value, option)
        if resolved.exists() and not os.access(resolved, os.W_OK):
            raise ConfigError(option, f"{value!r} exists and cannot be overwritten")
        paths[name] = value
    return paths


def _try_create(folder: Path, value: str, option: str) -> None:
    """Create and remove a file in ``folder``: the only test that holds for every user."""
    import tempfile

    try:
        with tempfile.NamedTemporaryFile(dir=folder, prefix=".torsio-check-"):
            pass
    except OSError as exc:
        raise ConfigError(
            option, f"cannot write {value!r}: {exc.strerror or exc} in folder {str(folder)!r}"
        ) from None


def _plot_path(value: str, option: str) -> str:
    suffix = Path(value).suffix.lower().lstrip(".")
    if not suffix:
        return value + ".png"
    try:
        from matplotlib.figure import Figure
    except ImportError:
        return value  # the command reports the missing matplotlib itself
    supported = Figure().canvas.get_supported_filetypes()
    if suffix not in supported:
        raise ConfigError(
            option,
            f"matplotlib cannot write .{suffix} files; expected one of "
            f"{', '.join('.' + k for k in sorted(supported))}",
        )
    return value


SMALL_BARE_WOB = 1000.0
"""A bare ``--wob`` below this many newtons gets a warning: drilling loads are kN."""


def warn_small_bare_wob(text: str | None, option: str = "--wob") -> None:
    """Warn on stderr when a bare number for a weight on bit is implausibly small.

    Bare numbers are newtons (SI), so ``--wob 150`` is 150 N, not 150 kN; below
    :data:`SMALL_BARE_WOB` the warning asks whether kN was meant. Strings with units
    and zero are never warned about.

    Examples
    --------
    >>> import contextlib, io
    >>> stream = io.StringIO()
    >>> with contextlib.redirect_stderr(stream):
    ...     warn_small_bare_wob("150")
    >>> print(stream.getvalue().strip())
    warning: --wob 150 is 150 N (bare numbers are N); did you mean '150 kN'?
    """
    if text is None:
        return
    try:
        value = float(text)
    except (TypeError, ValueError):
        return  # a string with units says what it means
    if 0.0 < value < SMALL_BARE_WOB:
        print(
            f"warning: {option} {text} is {value:g} N (bare numbers are N); "
            f"did you mean '{text} kN'?",
            file=sys.stderr,
        )


DISCRETIZATION_FLAGS = {
    "strategy": "--strategy",
    "dp_elements": "--dp-elements",
    "bha_elements": "--bha-elements",
}
"""The ``[discretization]`` options a command line may override, by flag."""


def load(args: argparse.Namespace, default: Callable[[], Config] | None = None) -> Config:
    """The configuration named on the command line, or ``default()`` (the built-in
    example, ``ritto2017.toml``, where None), discretized as
    --strategy, --dp-elements and --bha-elements say where the command takes them
    (:func:`torsio.config.reading.rediscretized`: the axial chain too); an error in one of
    them names its flag."""
    from torsio.config.reading import load_config, rediscretized
    from torsio.examples import builtin_config

    if args.config is not None:
        config = load_config(args.config)
    else:
        config = (default or builtin_config)()
    overrides = {name: getattr(args, name, None) for name in DISCRETIZATION_FLAGS}
    try:
        return rediscretized(config, **overrides)
    except ConfigError as exc:
        name = exc.key.removeprefix("discretization.")
        if overrides.get(name) is not None:
            flag = DISCRETIZATION_FLAGS[name]
            key = flag if name == exc.key else f"{flag} ({exc.key})"
        else:  # a key of the file that the flags made wrong
            given = [
                f"{DISCRETIZATION_FLAGS[k]} {v}" for k, v in overrides.items() if v is not None
            ]
            key = f"{exc.key} (with {', '.join(given)})"
        raise ConfigError(key, exc.message) from None


def _clean(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_clean(v) for v in value]
    return value


def print_json(data: dict[str, Any]) -> None:
    """One JSON object on stdout (non-finite numbers become null)."""
    json.dump(_clean(data), sys.stdout, indent=2)
    sys.stdout.write("\n")
