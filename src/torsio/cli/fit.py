"""``torsio fit``: friction and damping of a configuration fitted to rig recordings."""

from __future__ import annotations

import argparse
from typing import Any

from torsio.cli import common


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``fit`` command to the ``torsio`` parser."""
    parser = common.add_command(
        subparsers,
        "fit",
        run,
        "fit friction factors, threshold speed or damping to recorded surface torque",
        "Fit parameters of CONFIG (its keys: friction_static, friction_dynamic, "
        "hole[i].friction_static, hole[i].friction_dynamic, threshold_speed, alpha) to "
        "recordings of top-drive speed and surface torque (CSV: time,top_rpm,surface_torque), "
        "on the wave model (or the lumped strategy --strategy names; a file with axial "
        "dynamics on its torsional model, the bit off bottom): a global stage over "
        "the admissible range, then least squares (docs/calibration.md).",
    )
    parser.add_argument("config", metavar="CONFIG", help="TOML configuration file with [well]")
    parser.add_argument(
        "--recording",
        action="append",
        required=True,
        metavar="FILE",
        help="a recording (CSV; repeat for more)",
    )
    parser.add_argument(
        "--fit",
        required=True,
        metavar="NAMES",
        help="comma-separated configuration keys to fit, e.g. friction_static,friction_dynamic",
    )
    parser.add_argument(
        "--top",
        choices=("recorded", "configured"),
        default="recorded",
        help="what drives the top: the recorded speed (default) or the configured top drive",
    )
    parser.add_argument(
        "--objective",
        choices=("torque", "features"),
        default="torque",
        help="every torque sample (default), or the sliding and break-over torques",
    )
    parser.add_argument(
        "--wob",
        metavar="W",
        help="weight on bit: N or with units (default 0: off bottom; the only weight a file "
        "with axial dynamics takes)",
    )
    parser.add_argument(
        "--no-profile",
        action="store_true",
        help="uncertainty from the Jacobian only (no profile of the misfit)",
    )
    parser.add_argument(
        "--speed-smoothing",
        metavar="T",
        help="smooth the recorded speed over a centred window (s or with units) before it "
        "drives the top (default 0.2 s; 0: as recorded); against noise on the speed record",
    )
    common.add_discretization_arguments(parser)
    parser.add_argument(
        "--time-step",
        metavar="T",
        help="the wave model's largest time step (s or with units; default its grid's: 5 ms "
        "made to fit the sections' travel times); a finer grid reads the break-over closer",
    )
    parser.add_argument(
        "--plot",
        metavar="FILE",
        help="record against model with the break-overs, and each parameter's profile "
        "with its interval (needs matplotlib)",
    )
    common.add_json_argument(parser)


def run(args: argparse.Namespace) -> int:
    """Run ``torsio fit`` with parsed arguments; return the exit status."""
    from torsio.calibration.fit import SPEED_SMOOTHING, check_wob, fit_recordings
    from torsio.calibration.recording import read_recording
    from torsio.config.reading import load_config
    from torsio.errors import ConfigError
    from torsio.solvers.run_chunks import count_progress
    from torsio.units import to_si

    outputs = common.check_outputs(args, ["plot"])
    common.require_plotting(args)
    names = [name.strip() for name in args.fit.split(",") if name.strip()]
    config = load_config(args.config)
    if config.well is None:
        raise ConfigError("well", f"{args.config} has no [well] table: nothing to fit friction to")
    given = 0.0 if args.wob is None else to_si(args.wob, "force", key="--wob")
    wob = check_wob(given, "--wob", config.axial is not None)
    recordings = [read_recording(path) for path in args.recording]
    window = common.parse_time(args.speed_smoothing, "--speed-smoothing", allow_zero=True)
    grid = {k: v for k, v in common.discretization_overrides(args).items() if v is not None}
    time_step = common.parse_time(args.time_step, "--time-step")
    if time_step is not None:
        if grid.get("strategy", "wave") != "wave":
            raise ConfigError("--time-step", "sets the wave model's grid: drop --strategy")
        grid["time_step"] = time_step
    if window is not None and args.top != "recorded":
        raise ConfigError("--speed-smoothing", "smooths the recorded speed: needs --top recorded")
    shown = count_progress("fit", "model runs")
    try:
        results = fit_recordings(
            config,
            recordings,
            names,
            top=args.top,
            objective=args.objective,
            wob=wob,
            profile=not args.no_profile,
            speed_smoothing=SPEED_SMOOTHING if window is None else window,
            progress=shown,
            **grid,
        )
    finally:
        shown.close()
    return common.write_and_print(args, results, outputs, _print_table)


def _print_table(results: Any, written: dict[str, str]) -> None:
    from rich.console import Console
    from rich.table import Table

    table = Table(title=f"Fit to {len(results.recordings)} recordings ({results.objective})")
    for name in ("parameter", "fitted", "sigma", "2-sigma interval", "closed-form start"):
        table.add_column(name, justify="left" if name == "parameter" else "right")
    for row in results.rows():
        table.add_row(*row)
    console = Console()
    console.print(table)
    lines = [
        f"residual (RMS surface torque) {results.residual:.4g} N m; "
        + "; ".join(f"{r.name} {r.residual:.4g} N m" for r in results.recordings),
        f"{results.runs} model runs in {results.seconds:.1f} s (top: {results.top}; "
        f"model: {results.model})",
        *results.notes(),
    ]
    if "plot" in written:
        lines.append(f"wrote {written['plot']}")
    for line in lines:
        console.print(line, highlight=False, markup=False)
