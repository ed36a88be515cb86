"""``torsio simulate``: transient response at one operating point, S_SS (Eq. 12)."""

from __future__ import annotations

import argparse
import functools
import sys
from pathlib import Path
from typing import Any

from torsio.cli import common
from torsio.display_units import DisplayUnits


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``simulate`` command to the ``torsio`` parser."""
    parser = common.add_command(
        subparsers,
        "simulate",
        run,
        "start-up transient at one operating point and its stick-slip severity S_SS",
        "Integrate the equations of motion from rest at a weight on bit and rotary "
        "speed, and report the stick-slip severity S_SS (Eq. 12) over the steady window. "
        "Options override the configuration file.",
    )
    common.add_config_argument(parser)
    parser.add_argument(
        "--wob", metavar="W", help="weight on bit: N, or with units ('100 kN', '22 klbf')"
    )
    parser.add_argument(
        "--rpm", metavar="R", help="surface rotary speed: rpm, or with units ('10 rad/s')"
    )
    common.add_discretization_arguments(parser)
    common.add_run_time_arguments(parser)
    parser.add_argument(
        "--method",
        help="integrator: auto (default: RODAS4 on the compiled engine where it can run the "
        "model, else LSODA), RODAS4, or a solve_ivp method: LSODA, Radau, BDF, RK45, DOP853, "
        "RK23",
    )
    tolerance = common.finite_float
    parser.add_argument("--rtol", type=tolerance, help="relative tolerance (default 1e-6)")
    parser.add_argument("--atol", type=tolerance, help="absolute tolerance (default 1e-9)")
    parser.add_argument("--output-step", metavar="T", help="output sampling step: s or with units")
    common.add_file_outputs(
        parser,
        csv="write the time series to a CSV file",
        plot="write a PNG of bit speed, surface torque and torque on bit",
    )
    parser.add_argument(
        "--out",
        metavar="FILE",
        help="save the run (.npz: every signal and state, S_SS, the solver's statistics), "
        "which torsio.load_run reads back",
    )
    parser.add_argument(
        "--recording",
        metavar="FILE",
        help="write what a rig records of the run (time, top_rpm, surface_torque, bit_rpm): "
        "the CSV torsio fit reads",
    )
    parser.add_argument(
        "--growth-rate",
        action=argparse.BooleanOptionalAction,
        help="axial runs (the RGD bit): find the linear growth rate of steady drilling, or "
        "not (default: on chains of up to 200 DOF; a larger one takes minutes)",
    )
    common.add_units_argument(parser)
    common.add_json_argument(parser)


def run(args: argparse.Namespace) -> int:
    """Run ``torsio simulate`` with parsed arguments; return the exit status."""
    from torsio.analysis.config_runs import run_capabilities
    from torsio.analysis.transient import simulate_config
    from torsio.analysis.transient_results import run_file_path
    from torsio.errors import ConfigError

    outputs = common.check_outputs(args, ("out", "csv", "plot", "recording"))
    if "out" in outputs:  # before the run, not after it
        run_file_path(outputs["out"], "--out")
    config = common.load(args)
    given = {
        "growth_rate": ("--growth-rate", args.growth_rate),
        **{name: (f"--{name.replace('_', '-')}", getattr(args, name)) for name in _ENGINE_FLAGS},
    }
    run_capabilities(config).refuse(given)  # what the model's engine cannot take, by flag
    common.refuse_rpm_without_set_speed(
        config, args.rpm, "; remove --rpm, or change top_drive.torque"
    )
    overrides: dict[str, Any] = {
        "duration": common.parse_time(args.duration, "--duration"),
        "steady_window": common.parse_time(args.window, "--window"),
        "output_step": common.parse_time(args.output_step, "--output-step"),
        "method": args.method,
        "rtol": args.rtol,
        "atol": args.atol,
    }
    common.require_plotting(args)
    common.warn_small_bare_wob(args.wob)
    if args.growth_rate is not None:
        overrides["growth_rate"] = args.growth_rate
    try:  # a long run shows progress on stderr (simulate's default), never on stdout
        results = simulate_config(
            config,
            wob=args.wob,
            rpm=args.rpm,
            **overrides,
        )
    except ConfigError as exc:
        raise ConfigError(_option_name(exc.key), exc.message) from None
    fallback = results.solver.get("fallback")
    if fallback:
        print(
            f"torsio simulate: integrated with scipy {results.solver['method']}: the compiled "
            f"engine cannot run this model ({fallback})",
            file=sys.stderr,
        )
    writers: dict[str, Any] = {}
    if "recording" in outputs:
        from torsio.calibration.recording import Recording

        name = Path(outputs["recording"]).name
        recording = Recording.from_transient(results, bit_speed=True, name=name)
        writers["recording"] = recording.save
    summary = functools.partial(_print_summary, units=DisplayUnits(args.units))
    return common.write_and_print(
        args, results, outputs, summary, writers, lambda: results.to_dict(series=True)
    )


_ENGINE_FLAGS = ("method", "rtol", "atol", "output_step")
"""Options that an engine may not take (:mod:`torsio.analysis.config_runs`)."""

_OPTIONS = {
    "wob": "--wob",
    "rpm": "--rpm",
    "simulation.duration": "--duration (simulation.duration)",
    "simulation.steady_window": "--window (simulation.steady_window)",
    "simulation.method": "--method (simulation.method)",
    "simulation.rtol": "--rtol (simulation.rtol)",
    "simulation.atol": "--atol (simulation.atol)",
    "simulation.output_step": "--output-step (simulation.output_step)",
}


def _option_name(key: str) -> str:
    return _OPTIONS.get(key, key)


def _print_summary(results: Any, written: dict[str, str], units: Any = None) -> None:
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    title, rows = results.summary_rows(DisplayUnits() if units is None else units)
    table = Table(title=escape(title))
    table.add_column("quantity")
    table.add_column("value", justify="right")
    files = {"csv": "time series", "plot": "plot", "recording": "recording (torsio fit)"}
    rows += [(files[key], path) for key, path in written.items() if key in files]
    for name, value in rows:
        table.add_row(escape(name), escape(value))
    Console().print(table)
