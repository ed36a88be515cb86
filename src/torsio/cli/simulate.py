"""``torsio simulate``: transient response at one operating point, S_SS (Eq. 12)."""

from __future__ import annotations

import argparse
from typing import Any

from torsio.cli.common import (
    add_config_argument,
    add_discretization_arguments,
    check_outputs,
    discretization_overrides,
    finite_float,
    load,
    parse_time,
    print_json,
    warn_small_bare_wob,
)


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``simulate`` command to the ``torsio`` parser."""
    parser = subparsers.add_parser(
        "simulate",
        help="start-up transient at one operating point and its stick-slip severity S_SS",
        description=(
            "Integrate the equations of motion from rest at a weight on bit and rotary "
            "speed, and report the stick-slip severity S_SS (Eq. 12) over the steady window. "
            "Options override the configuration file."
        ),
    )
    add_config_argument(parser)
    parser.add_argument(
        "--wob", metavar="W", help="weight on bit: N, or with units ('100 kN', '22 klbf')"
    )
    parser.add_argument(
        "--rpm", metavar="R", help="surface rotary speed: rpm, or with units ('10 rad/s')"
    )
    add_discretization_arguments(parser)
    parser.add_argument(
        "--duration", metavar="T", help="run length: s or with units (default: 40 periods)"
    )
    parser.add_argument(
        "--window",
        metavar="T",
        help="steady-state window at the end of the run: s or with units (default: 15 periods)",
    )
    parser.add_argument(
        "--method", help="solve_ivp integrator: LSODA (default), Radau, BDF, RK45, DOP853, RK23"
    )
    parser.add_argument("--rtol", type=finite_float, help="relative tolerance (default 1e-6)")
    parser.add_argument("--atol", type=finite_float, help="absolute tolerance (default 1e-9)")
    parser.add_argument("--output-step", metavar="T", help="output sampling step: s or with units")
    parser.add_argument("--csv", metavar="FILE", help="write the time series to a CSV file")
    parser.add_argument(
        "--plot",
        metavar="FILE",
        help="write a PNG of bit speed, surface torque and torque on bit (needs matplotlib)",
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """Run ``torsio simulate`` with parsed arguments; return the exit status."""
    from torsio.analysis.transient import simulate_config
    from torsio.errors import ConfigError

    outputs = check_outputs(args, ("csv", "plot"))
    config = load(args)
    if args.rpm is not None and not config.top_drive.has_set_speed:
        raise ConfigError(
            "--rpm",
            f"the top drive is {config.top_drive.kind!r} (top_drive.kind): its speed follows "
            "from the torque balance; remove --rpm, or change top_drive.torque",
        )
    overrides: dict[str, Any] = {
        "duration": parse_time(args.duration, "--duration"),
        "steady_window": parse_time(args.window, "--window"),
        "output_step": parse_time(args.output_step, "--output-step"),
        "method": args.method,
        "rtol": args.rtol,
        "atol": args.atol,
    }
    if args.plot is not None:
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            raise ConfigError(
                "--plot", "needs matplotlib, which is not installed; pip install 'torsio[plot]'"
            ) from None
    warn_small_bare_wob(args.wob)
    try:
        results = simulate_config(
            config,
            wob=args.wob,
            rpm=args.rpm,
            discretization=discretization_overrides(args),
            **overrides,
        )
    except ConfigError as exc:
        raise ConfigError(_option_name(exc.key), exc.message) from None
    if "csv" in outputs:
        results.to_csv(outputs["csv"])
    if "plot" in outputs:
        results.plot(outputs["plot"])
    if args.json:
        data = results.to_dict()
        data.update(outputs)
        print_json(data)
        return 0
    _print_summary(results, args)
    return 0


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


def _print_summary(results: Any, args: argparse.Namespace) -> None:
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    system = results.system
    solver = results.solver
    table = Table(title=f"Transient response: {system.model.strategy}, {system.model.dofs} DOF")
    table.add_column("quantity")
    table.add_column("value", justify="right")
    window = results.window_mask
    rows = [
        ("weight on bit", f"{system.wob / 1e3:.4g} kN"),
        ("rotary speed", f"{system.rpm:.4g} rpm"),
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
        ("mean surface torque", f"{results.surface_torque[window].mean() / 1e3:.4g} kN m"),
        ("mean torque on bit", f"{results.bit_torque[window].mean() / 1e3:.4g} kN m"),
        (
            "solver",
            f"{solver['method']} rtol={solver['rtol']:g} atol={solver['atol']:g}: "
            f"{solver['nfev']} f-evals, {solver['njev']} Jacobians, "
            f"{solver['wall_time_s']:.2f} s",
        ),
    ]
    if args.csv is not None:
        rows.append(("time series", args.csv))
    if args.plot is not None:
        rows.append(("plot", check_outputs(args, ("plot",))["plot"]))
    for name, value in rows:
        table.add_row(escape(name), escape(value))
    Console().print(table)
