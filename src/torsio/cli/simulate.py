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
    from torsio.analysis.transient import simulate_config
    from torsio.errors import ConfigError

    outputs = common.check_outputs(args, ("csv", "plot", "recording"))
    config = common.load(args)
    if config.axial is not None:  # [chain] masses or law = "rgd": the axial engine
        from torsio.cli import axial

        if args.recording is not None:
            raise ConfigError(
                "--recording", "a recording is of a torsional run (no axial channels)"
            )

        try:
            return axial.simulate(args, config)
        except ConfigError as exc:
            raise ConfigError(_option_name(exc.key), exc.message) from None
    if args.growth_rate is not None:
        raise ConfigError(
            "--growth-rate",
            "applies to axial runs (the RGD bit) only: a torsional run has no growth rate of "
            "steady drilling (torsio report gives its linear stability); remove it",
        )
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
    _refuse_integrator_options(config, args, overrides)
    common.require_plotting(args)
    common.warn_small_bare_wob(args.wob)
    try:  # a long run shows progress on stderr (simulate's default), never on stdout
        results = simulate_config(
            config,
            wob=args.wob,
            rpm=args.rpm,
            discretization=common.discretization_overrides(args),
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


def _refuse_integrator_options(config: Any, args: argparse.Namespace, given: dict) -> None:
    """The wave model has no integrator: --method/--rtol/--atol are errors, the file's a note."""
    import sys

    strategy = common.discretization_overrides(args).get("strategy")
    if (strategy or config.discretization.strategy) != "wave" or config.chain is not None:
        return
    # only now: importing the wave model's stepping compiles it (seconds, on a first run)
    from torsio.analysis.wave import INTEGRATOR_OPTIONS, integrator_note, refuse_integrator_options

    refuse_integrator_options(
        {_option_name(f"simulation.{k}"): given[k] for k in INTEGRATOR_OPTIONS}
    )
    unused = sorted(set(config.simulation.options) & set(INTEGRATOR_OPTIONS))
    if unused:
        print(f"torsio simulate: {integrator_note(unused)}", file=sys.stderr)


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

    units = DisplayUnits() if units is None else units
    system = results.system
    solver = results.solver
    table = Table(title=f"Transient response: {system.model.strategy}, {system.model.dofs} DOF")
    table.add_column("quantity")
    table.add_column("value", justify="right")
    window = results.window_mask
    rows = [
        ("weight on bit", units.text("force", system.wob, ".4g")),
        (
            "rotary speed",
            f"{results.rpm:.4g} rpm"
            + ("" if results.has_set_speed else "  (mean top-drive speed; none is set)"),
        ),
        ("bit-rock law", str(getattr(system.law, "name", type(system.law).__name__))),
        (
            "run / steady window",
            f"{results.duration:.4g} s / last {results.steady_window:.4g} s",
        ),
        (
            "bit speed in window",
            f"{results.bit_speed[window].min() * 30 / 3.141592653589793:.4g} .. "
            f"{results.bit_speed[window].max() * 30 / 3.141592653589793:.4g} rpm",
        ),
        (
            "S_SS (Eq. 12)",
            f"{results.severity:.4f}" + ("  severe (> 0.8)" if results.severe else ""),
        ),
        (
            "stick fraction",
            f"{results.stick_fraction:.3f}  (|bit speed| < {results.stick_threshold:g} Omega)",
        ),
        ("mean surface torque", units.text("torque", results.surface_torque[window].mean(), ".4g")),
        ("mean torque on bit", units.text("torque", results.bit_torque[window].mean(), ".4g")),
        (
            "solver",
            f"{solver['method']} ({solver.get('engine', 'scipy')} engine) "
            f"rtol={solver['rtol']:g} atol={solver['atol']:g}: "
            + (f"{solver['steps']} steps, " if solver.get("steps") is not None else "")
            + f"{solver['nfev']} f-evals, {solver['njev']} Jacobians, "
            f"{solver['wall_time_s']:.2f} s",
        ),
    ]
    rows.extend(_well_rows(results.well_summary, units))
    if "csv" in written:
        rows.append(("time series", written["csv"]))
    if "plot" in written:
        rows.append(("plot", written["plot"]))
    if "recording" in written:
        rows.append(("recording (torsio fit)", written["recording"]))
    for name, value in rows:
        table.add_row(escape(name), escape(value))
    Console().print(table)


def _well_rows(summary: Any, units: Any) -> list[tuple[str, str]]:
    """Rows of a run with friction along the string (a [well]); none without."""
    if summary is None:
        return []
    first = summary["bit_first_motion"]
    period = summary["stick_slip_period"]
    return [
        (
            "surface torque in window",
            f"{units.number('torque', summary['surface_torque_min'], '.4g')} .. "
            f"{units.text('torque', summary['surface_torque_max'], '.4g')}",
        ),
        ("peak surface torque", units.text("torque", summary["surface_torque_peak"], ".4g")),
        (
            "surface-torque swing in window",
            units.text("torque", summary["surface_torque_swing"], ".4g"),
        ),
        (
            "stick-slip period in window",
            f"none: {summary['stick_slip_period_reason']}" if period is None else f"{period:.4g} s",
        ),
        (
            f"bit first faster than {summary['threshold_speed']:g} rad/s",
            "never" if first is None else f"at {first:.4g} s",
        ),
        ("friction work along the string", units.energy(summary["friction_work"])),
    ]
