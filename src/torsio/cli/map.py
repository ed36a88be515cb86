"""``torsio map``: stick-slip severity S_SS over a grid of weight on bit x rotary speed.

Ranges are ``START:STOP:N`` (N evenly spaced values, both ends included):
``--wob 25kN:225kN:21`` (a bare number is N), ``--rpm 40:140:21`` (a bare number
is rpm; units such as ``rad/s`` are accepted). ``--pi1``/``--pi2`` give the grid
in the dimensionless groups of Eq. 11 instead.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Any

from torsio.cli import common

DEFAULT_WOB = "25kN:225kN:21"
DEFAULT_RPM = "40:140:21"


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``map`` command to the ``torsio`` parser."""
    parser = common.add_command(
        subparsers,
        "map",
        run,
        "severity map S_SS over weight on bit x rotary speed, critical WOB",
        "Stick-slip severity S_SS (Eq. 12) over a grid of weight on bit and rotary "
        "speed, each point started from rest; classification, the critical weight on bit "
        "per rotary speed (bisected between grid points) and the linear stability "
        "boundary. Ranges are START:STOP:N.",
        options=_options_class,
    )
    common.add_config_argument(parser)
    parser.add_argument(
        "--wob",
        metavar="START:STOP:N",
        help=f"weights on bit: N or with units (default {DEFAULT_WOB})",
    )
    parser.add_argument(
        "--rpm",
        metavar="START:STOP:N",
        help=f"rotary speeds: rpm or with units (default {DEFAULT_RPM})",
    )
    parser.add_argument(
        "--pi1",
        metavar="START:STOP:N",
        help="dimensionless speeds Pi_1 = Omega/omega_1 (instead of --rpm)",
    )
    parser.add_argument(
        "--pi2",
        metavar="START:STOP:N",
        help="dimensionless loads Pi_2 = W_ob R_bit/k_eq (instead of --wob)",
    )
    common.add_discretization_arguments(parser)
    common.add_run_time_arguments(parser, length="run length of every point", run="each run")
    common.add_executor_arguments(
        parser, "threads of the compiled engine in this process (default: all cores)"
    )
    parser.add_argument(
        "--out",
        metavar="FILE",
        help="save the map (.json, or .npz); an interrupted map goes to "
        "FILE.partial.json/.npz, marked incomplete",
    )
    common.add_file_outputs(
        parser,
        csv="write one row per grid point",
        plot="write a PNG heat map with the critical curve",
    )
    common.add_json_argument(parser)


# --- ranges ---------------------------------------------------------------------------------
def _split_range(text: str, option: str) -> tuple[str, str, int]:
    parts = text.split(":")
    if len(parts) != 3:
        from torsio.errors import ConfigError

        raise ConfigError(option, f"expected START:STOP:N, got {text!r}")
    start, stop, count_text = (p.strip() for p in parts)
    from torsio.errors import ConfigError

    try:
        count = int(count_text)
    except ValueError:
        raise ConfigError(
            option, f"N in START:STOP:N must be a whole number of points, got {count_text!r}"
        ) from None
    if count < 1:
        raise ConfigError(option, f"empty range {text!r}: N must be at least 1, got {count}")
    return start, stop, count


def _range_bounds(text: str, option: str, kind: str) -> tuple[float, float, int]:
    """(start, stop, count) of a START:STOP:N range, in SI (N), rpm or dimensionless."""
    from torsio.config.tables import parse_rpm
    from torsio.errors import ConfigError
    from torsio.units import to_si

    start_text, stop_text, count = _split_range(text, option)
    values = []
    for part in (start_text, stop_text):
        if not part:
            raise ConfigError(option, f"expected START:STOP:N, got {text!r}")
        if kind == "wob":
            common.warn_small_bare_wob(part, option)
            value = to_si(part, "force", key=option)
            if value < 0:
                raise ConfigError(option, f"expected non-negative weights on bit, got {part!r}")
        elif kind == "rpm":
            value = parse_rpm(part, option)
        else:
            try:
                value = float(part)
            except ValueError:
                raise ConfigError(option, f"expected a number, got {part!r}") from None
            if not math.isfinite(value) or value < 0 or (kind == "pi1" and value == 0):
                what = "positive" if kind == "pi1" else "non-negative"
                raise ConfigError(option, f"expected a {what} number, got {part!r}")
        values.append(value)
    start, stop = values
    if start > stop:
        raise ConfigError(option, f"reversed range {text!r}: START must not exceed STOP")
    if count == 1 and start != stop:
        raise ConfigError(
            option, f"range {text!r} has one point but START != STOP; give N >= 2 or START = STOP"
        )
    if count > 1 and start == stop:
        raise ConfigError(option, f"empty range {text!r}: START = STOP with {count} points")
    return start, stop, count


_ENGINE_FLAGS = ("pi1", "pi2")
"""Flags that are not map options and that an engine may not take."""
_RUN_ARGUMENTS = ("wob", "rpm", "pi1", "pi2", "workers", "scheduler", "out")
_ARGUMENTS = {"grid": "--wob/--rpm", **{name: f"--{name}" for name in _RUN_ARGUMENTS}}
"""Flags of the map's arguments that are not options, for errors (options name themselves:
MapOptions.flag)."""


def run(args: argparse.Namespace) -> int:
    """Run ``torsio map`` with parsed arguments; return the exit status."""
    from torsio.errors import ConfigError

    try:
        return _run(args)
    except ConfigError as exc:
        from torsio.analysis.map_options import MapOptions

        raise ConfigError(
            _ARGUMENTS.get(exc.key) or MapOptions.flag(exc.key), exc.message
        ) from None


def _run(args: argparse.Namespace) -> int:
    import attrs
    import numpy as np

    from torsio.analysis.config_runs import config_map, default_wob_range, run_capabilities
    from torsio.analysis.map_options import MapOptions
    from torsio.analysis.map_results import MapInterrupted
    from torsio.analysis.map_runs import MapFailed, check_grid_size
    from torsio.errors import ConfigError
    from torsio.solvers.run_chunks import stderr_progress

    if args.wob is not None and args.pi2 is not None:
        raise ConfigError("--pi2", "give either --wob or --pi2, not both")
    if args.rpm is not None and args.pi1 is not None:
        raise ConfigError("--pi1", "give either --rpm or --pi1, not both")
    dimensionless = args.pi1 is not None or args.pi2 is not None
    if dimensionless and (args.pi1 is None or args.pi2 is None):
        raise ConfigError(
            "--pi1" if args.pi1 is None else "--pi2",
            "a dimensionless map needs both --pi1 and --pi2",
        )
    executor = common.executor_choice(args)
    if args.threads is not None:
        if args.workers is not None or args.scheduler is not None:
            raise ConfigError(
                "--threads", "applies to this process; worker processes run one thread each"
            )
        _use_threads(args.threads)
    if dimensionless:
        x_start, x_stop, x_count = _range_bounds(args.pi1, "--pi1", "pi1")
        y_start, y_stop, y_count = _range_bounds(args.pi2, "--pi2", "pi2")
    else:
        x_start, x_stop, x_count = _range_bounds(args.rpm or DEFAULT_RPM, "--rpm", "rpm")
        y_start, y_stop, y_count = _range_bounds(args.wob or DEFAULT_WOB, "--wob", "wob")
    check_grid_size(x_count, y_count)  # before building the axes
    outputs = common.check_outputs(args, ("out", "csv", "plot"))  # before the work, not after it
    common.require_plotting(args)

    config = common.load(args)
    capabilities = run_capabilities(config)
    flags = {field.name: field.metadata["flag"] for field in attrs.fields(MapOptions)}
    given = {name: (flag, getattr(args, flag[2:].replace("-", "_"))) for name, flag in flags.items()
             if flag}  # fmt: skip
    given.update({name: (f"--{name.replace('_', '-')}", getattr(args, name))
                  for name in _ENGINE_FLAGS})  # fmt: skip
    capabilities.refuse(given)  # what the model's engine cannot take, by flag
    if args.wob is None and not dimensionless:  # the model's own default range
        y_start, y_stop, y_count = _range_bounds(
            default_wob_range(config, DEFAULT_WOB), "--wob", "wob"
        )
    common.refuse_rpm_without_set_speed(config, args.rpm, ", there is no rotary speed to set")
    options = _map_options(args, dict(config.simulation.options))
    x = np.linspace(x_start, x_stop, x_count)
    y = np.linspace(y_start, y_stop, y_count)
    shown = stderr_progress("map", unit="points")  # --json or not: stdout keeps the JSON
    try:
        result = config_map(
            config,
            y,
            x,
            options,
            dimensionless=dimensionless,
            executor=executor,
            progress=shown,
            rtol=args.rtol,
            note=lambda text: print(f"torsio map: {text}", file=sys.stderr),
        )
    except MapInterrupted as exc:
        shown.close()
        if args.out is not None:
            print(f"torsio map: {exc}; {_save_partial(exc.partial, args.out)}", file=sys.stderr)
        raise KeyboardInterrupt from None
    except MapFailed as exc:  # the executor failed: keep what finished, then the error
        if args.out is not None:
            exc.args = (f"{exc}; {_save_partial(exc.partial, args.out)}",)
        raise
    finally:
        shown.close()
    return common.write_and_print(args, result, outputs, _print_summary)


def _save_partial(partial: Any, out: str) -> str:
    """Write the points done beside ``out`` (``NAME.partial.SUFFIX``, marked incomplete);
    says where they went: on stdout as JSON where the file cannot be written (a full
    disk)."""
    from torsio.errors import OutputError

    path = _partial_path(Path(out))
    try:
        partial.save(path)
    except OutputError as exc:
        common.print_json(partial.to_dict())
        return f"{exc}; the partial results are on stdout as JSON (marked incomplete)"
    return f"partial results written to {path} (marked incomplete)"


def _options_class() -> type:
    """The options whose flags ``torsio map`` takes (--threshold, --refine, --rtol, ...)."""
    from torsio.analysis.map_options import MapOptions

    return MapOptions


def _map_options(args: argparse.Namespace, simulation: dict[str, Any]) -> Any:
    """The map's options from its flags, each read where the option says (its flag, else
    its ``[simulation]`` key): :class:`torsio.analysis.map_options.MapOptions`."""
    import attrs

    from torsio.analysis.map_options import MapOptions

    values: dict[str, Any] = {}
    for field in attrs.fields(MapOptions):
        flag, key = field.metadata["flag"], field.metadata["key"]
        value = getattr(args, flag[2:].replace("-", "_")) if flag else None
        if value is not None and field.name in ("duration", "steady_window"):
            value = common.parse_time(value, flag)
        if value is None and key:
            value = simulation.get(key.removeprefix("simulation."))
        if value is not None:
            values[field.name] = value
    return MapOptions(**values)


def _use_threads(count: int) -> None:
    """Threads of the compiled engine (numba's pool) for this process: 1 .. all cores."""
    from torsio.errors import ConfigError

    try:
        import numba
    except ImportError:  # pragma: no cover - the numpy engine has no threads
        raise ConfigError("--threads", "needs numba (pip install numba)") from None
    most = int(getattr(numba.config, "NUMBA_NUM_THREADS", 1))
    if not 1 <= count <= most:
        raise ConfigError("--threads", f"expected 1 to {most} threads (the cores), got {count}")
    numba.set_num_threads(count)


def _partial_path(path: Path) -> Path:
    suffix = path.suffix if path.suffix == ".npz" else ".json"
    return path.with_name(f"{path.stem}.partial{suffix}")


def _print_summary(result: Any, written: dict[str, str]) -> None:
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    info = result.info
    model = info.get("model", {})
    label = info.get("label") or (
        f"{model.get('name', '')} ({model.get('strategy')}, {model.get('dofs')} DOF)"
    )
    table = Table(
        title=escape(f"Severity map: {label}, {result.rpm.size} x {result.wob.size} points")
    )
    for name in ("rpm", "Pi_1", "critical WOB [kN]", "critical Pi_2", "linear stability WOB [kN]"):
        table.add_column(escape(name), justify="right")
    # off the grid: "> largest" / "≤ smallest" (no value invented), the status otherwise
    wob_texts = result.critical_wob_texts(1e3)
    pi_texts = result.critical_wob_texts(result.k_eq / result.bit_radius)
    for (rpm, _, _, linear), pi1, wob_text, pi_text in zip(
        result.critical_rows(), result.pi1, wob_texts, pi_texts, strict=True
    ):
        table.add_row(
            f"{rpm:.4g}",
            f"{pi1:.4g}",
            wob_text,
            pi_text,
            "-" if linear is None else f"{linear / 1e3:.4g}",
        )
    console = Console()
    console.print(table)
    if any(result.critical_wob_bound):
        console.print(
            escape(
                f"critical WOB off the grid: '> {result.wob[-1] / 1e3:.4g}' = not severe at the "
                f"largest weight on bit; '≤ {result.wob[0] / 1e3:.4g}' = severe over the whole row"
            )
        )
    counts = ", ".join(f"{n} {name}" for name, n in result.counts().items())
    console.print(
        escape(
            f"points: {counts} (severe: S_SS > {result.threshold:g}; stick-slip: "
            f"S_SS > {result.stick_slip_threshold:g})"
        )
    )
    console.print(
        escape(
            f"runs of {info.get('duration', 0):.4g} s from rest, S_SS over the last "
            f"{info.get('steady_window', 0):.4g} s; {info.get('extra_runs', 0)} "
            f"extra runs for the critical curve; {info.get('elapsed_s', 0):.2f} s "
            f"on {info.get('executor')}, {result.engine} engine"
        )
    )
    if result.rop is not None:  # the layers of a bit that drills
        console.print(_layers_table(result))
    for key, path in written.items():
        console.print(escape(f"{key}: {path}"))


def _layers_table(result: Any) -> Any:
    """Every point's layers: S_SS, stuck and off-bottom fractions, ROP, MSE."""
    import numpy as np
    from rich.table import Table
    from rich.text import Text

    table = Table(title="Layers")
    for name in ("rpm", "WOB [kN]", "S_SS", "stuck", "off bottom", "ROP [m/h]", "MSE [MPa]"):
        table.add_column(Text(name), justify="right")  # Text: "[kN]" is a unit, not markup
    for i, rpm in enumerate(result.rpm):
        for j, wob in enumerate(result.wob):
            mse = result.mse[i, j]
            table.add_row(
                f"{rpm:.4g}",
                f"{wob / 1e3:.4g}",
                f"{result.severity[i, j]:.3f}",
                f"{result.stick_fraction[i, j]:.3f}",
                f"{result.off_bottom_fraction[i, j]:.3f}",
                f"{result.rop[i, j] * 3600:.4g}",
                "-" if not np.isfinite(mse) else f"{mse / 1e6:.4g}",
            )
    return table
