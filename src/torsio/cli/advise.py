"""``torsio advise``: the operating point that drills fastest without severe stick-slip.

Ranges are ``START:STOP:N`` as for ``torsio map``, N the coarse map's points (the search
refines from there): ``--wob 80kN:140kN:5 --rpm 60:180:5``. See docs/advise.md.
"""

from __future__ import annotations

import argparse
import math
import sys
from typing import Any

from torsio.cli import common


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``advise`` command to the ``torsio`` parser."""
    parser = common.add_command(
        subparsers,
        "advise",
        run,
        "operating window: the WOB, rpm and top drive that drill fastest without stick-slip",
        "The operating point of largest ROP (or least MSE) with S_SS below the paper's 0.8 "
        "and within the rig's limits: a coarse map, then bisection on the severity boundary "
        "and refinement near the optimum; its margin (Monte Carlo over --fit or --vary) and "
        "the top drives compared. Ranges are START:STOP:N (N: coarse points).",
    )
    parser.add_argument(
        "config",
        nargs="?",
        metavar="CONFIG",
        help="TOML configuration file with axial dynamics (default: the built-in RGD "
        "deviated well, rgd_deviated_well.toml)",
    )
    parser.add_argument(
        "--wob",
        metavar="START:STOP:N",
        help="weights on bit: N or with units (default 1.1 to 2 times the "
        "weight the wear flats carry, 5 points)",
    )
    parser.add_argument("--rpm", metavar="START:STOP:N", help="rotary speeds (default 40:180:5)")
    parser.add_argument(
        "--max-surface-torque",
        metavar="T",
        help="largest mean surface torque: N m or with units (default the file's "
        "top_drive.max_torque, if given)",
    )
    parser.add_argument("--max-wob", metavar="W", help="largest weight on bit: N or with units")
    common.add_discretization_arguments(parser)
    parser.add_argument(
        "--objective", default="rop", help="rop (largest mean ROP, default) or mse (least mean MSE)"
    )
    parser.add_argument(
        "--severity",
        type=common.finite_float,
        metavar="S",
        help="S_SS above which a point is severe (default 0.8, the paper's)",
    )
    parser.add_argument(
        "--fit",
        metavar="FILE",
        help="torsio fit --json output: the "
        "parameters drawn for the probability of severe stick-slip",
    )
    parser.add_argument(
        "--vary",
        metavar="NAME=LOW:HIGH",
        action="append",
        help="a parameter drawn uniformly (repeat; instead of --fit)",
    )
    parser.add_argument(
        "--level",
        type=common.finite_float,
        metavar="P",
        help="probability of severe stick-slip to stay below (default 0.1)",
    )
    parser.add_argument(
        "--samples", type=int, metavar="N", help="Monte Carlo samples per point (default 30)"
    )
    parser.add_argument("--seed", type=int, default=0, help="seed of the draws (default 0)")
    parser.add_argument(
        "--no-compare", action="store_true", help="the configured top drive only (no alternatives)"
    )
    common.add_run_time_arguments(parser, length="run length of every point", run="each run")
    common.add_executor_arguments(
        parser, "points side by side in this process (default: all cores)"
    )
    common.add_file_outputs(
        parser,
        csv="write one row per point run (configured top drive)",
        plot="write a PNG of the window",
    )
    common.add_json_argument(parser)


def _region(args: argparse.Namespace, config: Any) -> Any:
    """The region of --wob and --rpm, each defaulting to the advisor's
    (:func:`torsio.advice.region.default_region`)."""
    from torsio.advice import Region
    from torsio.advice.evaluate import AxialCase
    from torsio.advice.region import default_region
    from torsio.cli.map import _range_bounds

    case = AxialCase.from_config(config)  # a torsional configuration: an error by key
    default = default_region(case.bit)
    wob, wob_n = default.wob, default.wob_points
    if args.wob is not None:
        low, high, wob_n = _range_bounds(args.wob, "--wob", "wob")
        wob = (low, high)
    rpm, rpm_n = default.rpm, default.rpm_points
    if args.rpm is not None:
        low, high, rpm_n = _range_bounds(args.rpm, "--rpm", "rpm")
        rpm = (low, high)
    return Region(wob, rpm, wob_n, rpm_n)


def _torque(text: str | None, flag: str, dimension: str) -> float | None:
    from torsio.errors import ConfigError
    from torsio.units import to_si

    if text is None:
        return None
    value = float(to_si(text, dimension, key=flag))
    if not value > 0:
        raise ConfigError(flag, f"expected a positive value, got {text!r}")
    return value


def run(args: argparse.Namespace) -> int:
    """Run ``torsio advise``; returns the exit status."""
    import attrs

    from torsio.advice import AdviceInterrupted, Constraints, Uncertainty, advise
    from torsio.advice.advise import DEFAULT_LEVEL, DEFAULT_SAMPLES
    from torsio.errors import ConfigError
    from torsio.examples import rgd_deviated_well_config
    from torsio.solvers.run_chunks import count_progress

    if args.fit is not None and args.vary:
        raise ConfigError("--vary", "give either --fit or --vary, not both")
    executor = common.executor_choice(args)
    constraints = Constraints(
        max_surface_torque=_torque(args.max_surface_torque, "--max-surface-torque", "torque"),
        max_wob=_torque(args.max_wob, "--max-wob", "force"),
        objective=args.objective,
        **({"severity": args.severity} if args.severity is not None else {}),
    )
    outputs = common.check_outputs(args, ("csv", "plot"))
    common.require_plotting(args)
    config = common.load(args, default=rgd_deviated_well_config)
    if constraints.max_surface_torque is None:  # the rig's limit in the file, if any
        limit = config.top_drive.parameters.get("max_torque")
        if limit is not None and math.isfinite(limit):
            constraints = attrs.evolve(
                constraints, max_surface_torque=float(limit), torque_limit="top_drive.max_torque"
            )
    region = _region(args, config)
    uncertainty = None
    if args.fit is not None:
        uncertainty = Uncertainty.from_fit(args.fit)
    elif args.vary:
        uncertainty = Uncertainty.from_ranges(args.vary)
    threads = args.threads or _cores()
    if threads < 1:
        raise ConfigError("--threads", f"expected a number of threads >= 1, got {threads}")
    # the runs on stderr (the total is open: the search decides how many), --json or not
    shown = count_progress("advise")
    try:
        advice = advise(
            config,
            region,
            constraints,
            uncertainty=uncertainty,
            level=DEFAULT_LEVEL if args.level is None else args.level,
            samples=DEFAULT_SAMPLES if args.samples is None else args.samples,
            seed=args.seed,
            compare=not args.no_compare,
            threads=threads,
            executor=executor,
            progress=shown,
            duration=common.parse_time(args.duration, "--duration"),
            window=common.parse_time(args.window, "--window"),
        )
    except AdviceInterrupted as exc:
        shown.close()
        _show(args, exc.advice, {})
        raise KeyboardInterrupt from None
    finally:
        shown.close()
    written = _write(advice, outputs)
    _show(args, advice, written)
    return 0


def _cores() -> int:
    from torsio.solvers.compiled import numba

    return 1 if numba is None else int(numba.get_num_threads())


def _write(advice: Any, outputs: dict[str, str]) -> dict[str, str]:
    written = {}
    if "plot" in outputs:
        from torsio.advice.plot import plot_window

        plot_window(advice, outputs["plot"])
        written["plot"] = outputs["plot"]
    if "csv" in outputs:
        from torsio.advice.plot import write_points

        write_points(advice, outputs["csv"])
        written["csv"] = outputs["csv"]
    return written


def _show(args: argparse.Namespace, advice: Any, written: dict[str, str]) -> None:
    if args.json:
        common.print_json({**advice.to_dict(), **written})
        return
    from rich.console import Console
    from rich.markup import escape

    console = Console()
    console.print(advice.table())
    for line in advice.notes():
        console.print(escape(line))
    for key, path in written.items():
        console.print(escape(f"{key}: {path}"))
    if not advice.complete:
        print("torsio advise: interrupted; the advice above is incomplete", file=sys.stderr)
