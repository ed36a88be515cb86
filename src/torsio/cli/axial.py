"""``torsio simulate`` and ``torsio map`` on a configuration with axial dynamics.

The runs go to :func:`torsio.axial.transient.simulate_axial` and
:func:`torsio.axial.maps.axial_map` (fixed step, the RGD bit); the flags of the torsional
engines that have no meaning there are refused by name.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from torsio.cli import common
from torsio.errors import ConfigError

SCHEME = "semi-implicit Euler, set-valued contacts at the velocity level (Moreau)"
"""The axial engine's fixed-step scheme (:mod:`torsio.axial.kernel`)."""

NO_GROWTH_RATE = "not computed (--growth-rate asks for it)"
"""The growth-rate row of a run that did not find it (too large a chain, --no-growth-rate)."""

_SIMULATE_REFUSED = {
    "strategy": "--strategy",
    "dp_elements": "--dp-elements",
    "bha_elements": "--bha-elements",
    "method": "--method",
    "rtol": "--rtol",
    "atol": "--atol",
    "output_step": "--output-step",
    "csv": "--csv",
    "plot": "--plot",
}
_MAP_REFUSED = {
    "strategy": "--strategy",
    "dp_elements": "--dp-elements",
    "bha_elements": "--bha-elements",
    "pi1": "--pi1",
    "pi2": "--pi2",
    "threshold": "--threshold",
    "refine": "--refine",
    "rtol": "--rtol",
    "steady_tol": "--steady-tol",
    "on_failure": "--on-failure",
    "out": "--out",
    "csv": "--csv",
    "plot": "--plot",
}


TORQUE_LAW_GROWTH_RATE = "none for a law of the torque alone (torsio report: the chain's)"
"""The growth-rate row of a law of the torque alone, whose axial motion rests on the rock."""


def _refuse(args: argparse.Namespace, flags: dict[str, str]) -> None:
    for name, flag in flags.items():
        if getattr(args, name, None) is not None:
            raise ConfigError(
                flag,
                "does not apply to axial dynamics: the axial engine runs the file's assembly "
                "with a fixed step (simulation.step) and the RGD bit; remove it",
            )


def _times(args: argparse.Namespace, config: Any) -> dict[str, Any]:
    options = config.simulation.options
    duration = common.parse_time(args.duration, "--duration") or options.get("duration")
    window = common.parse_time(args.window, "--window") or options.get("steady_window")
    return {"duration": duration, "window": window}


def solver_info(run: Any) -> dict[str, Any]:
    """The ``solver`` entry of a run's JSON: the engine, its step [s] and its scheme."""
    return {"engine": "axial", "method": "fixed-step", "scheme": SCHEME, "step": run.step}


def simulate(args: argparse.Namespace, config: Any) -> int:
    """``torsio simulate`` on an axial configuration; returns the exit status."""
    from torsio.axial.transient import simulate_axial
    from torsio.display_units import DisplayUnits

    _refuse(args, _SIMULATE_REFUSED)
    axial = config.axial
    if args.growth_rate and not axial.bit.needs_axial:
        raise ConfigError(
            "--growth-rate",
            f"the {axial.bit.name} law is a law of the torque alone: its axial motion rests on "
            "the rock, and the linear stability is the torsional chain's (torsio report); "
            "remove it",
        )
    point = config.operating_point(args.wob, args.rpm)
    common.warn_small_bare_wob(args.wob)
    run = simulate_axial(
        axial.assembly,
        axial.bit,
        point["wob"],
        point["rpm"],
        **_times(args, config),
        **axial.run_options(),
        growth_rate=args.growth_rate,
    )
    for text in run.warnings:
        print(f"torsio {args.command}: warning: {text}", file=sys.stderr)
    data = run.to_dict()
    data["solver"] = solver_info(run)
    data["model"] = axial.assembly.describe()
    data["bit"] = axial.bit.to_dict()
    if args.json:
        common.print_json(data)
    else:
        _print_run(data, DisplayUnits(args.units))
    return 0


def _print_run(data: dict[str, Any], units: Any) -> None:
    from rich.console import Console
    from rich.table import Table

    from torsio.report.axial import assembly_summary

    steady = data["steady_state"]
    law = data["bit"]["law"]
    table = Table(title=f"Axial-torsional run: {assembly_summary(data['model'])}, {law} bit")
    table.add_column("quantity")
    table.add_column("value", justify="right")
    mse = data["mse_mean"]
    rate = data["growth_rate"]
    axial = data["axial_severity"]
    drilling = [  # the RGD bit's own; a law of the torque alone rests on the rock
        ("mean ROP", f"{data['rop_mean'] * 3600:.4g} m/h ({data['rop_mean']:.4g} m/s)"),
        ("mean MSE", "none (the bit did not advance)" if mse is None else f"{mse / 1e6:.4g} MPa"),
        ("steady depth of cut", f"{steady['depth_of_cut'] * 1e3:.4g} mm/rev"),
        ("steady ROP", f"{steady['rop'] * 3600:.4g} m/h ({steady['rop']:.4g} m/s)"),
    ]
    resting = [("axial motion", "at rest on the rock (a law of the torque alone)")]
    steady_mse = [("steady MSE", f"{steady['mse'] / 1e6:.4g} MPa")] if steady["rop"] > 0 else []
    rows = [
        ("weight on bit", units.text("force", data["wob"], ".4g")),
        ("rotary speed", f"{data['rpm']:.4g} rpm"),
        ("run / steady window", f"{data['duration']:.4g} s / last {data['steady_window']:.4g} s"),
        ("start", data["start"]),
        ("S_SS (Eq. 12)", f"{data['severity']:.4f}"),
        ("axial severity", "none (no rate of penetration)" if axial is None else f"{axial:.4f}"),
        ("stuck fraction", f"{data['stick_fraction']:.3f}"),
        ("off-bottom fraction", f"{data['off_bottom_fraction']:.3f}"),
        *(drilling if steady["rop"] > 0 else resting),
        ("steady bit torque", units.text("torque", steady["bit_torque"], ".4g")),
        *steady_mse,
        (
            "growth rate (linear)",
            (NO_GROWTH_RATE if steady["rop"] > 0 else TORQUE_LAW_GROWTH_RATE)
            if rate is None
            else f"{rate:.4g} 1/s ({'unstable' if rate > 0 else 'stable'})",
        ),
        ("solver", f"axial engine, fixed step {data['solver']['step'] * 1e3:.4g} ms"),
        ("top drive", data["top_drive"]),
    ]
    if data["stability_of_held_top"]:
        rows.append(("growth rate is of", "the top held at the set speed"))
    contacts = data.get("string_contacts")
    if contacts is not None:
        rows += [
            ("string contacts", f"{contacts['count']} nodes, break-off "
             f"{units.text('torque', contacts['static_torque'], '.4g')}, sliding "
             f"{units.text('torque', contacts['sliding_torque'], '.4g')}"),
            ("string friction work", f"{units.energy(data['string_friction_work'])} "
             f"({data['contact_switches']} stick-slip switches)"),
        ]  # fmt: skip
    if data["top_speed_mean"] is not None:
        rows += [
            ("mean top speed", f"{data['top_speed_mean'] * 60 / (2 * 3.141592653589793):.4g} rpm"),
            ("surface torque (window)",
             f"{units.number('torque', data['surface_torque_min'], '.4g')} to "
             f"{units.text('torque', data['surface_torque_max'], '.4g')}"),
        ]  # fmt: skip
    for name, value in rows:
        table.add_row(name, value)
    Console().print(table)


def run_map(args: argparse.Namespace, config: Any, wob: Any, rpm: Any) -> int:
    """``torsio map`` on an axial configuration over the grids ``wob`` [N] and ``rpm``:
    in this process on ``--threads`` threads (default all cores), or on ``--workers``
    processes or a Dask ``--scheduler`` (the flags of the torsional maps)."""
    import time

    from torsio.axial.maps import axial_map
    from torsio.axial.stability import growth_rate_skipped

    _refuse(args, _MAP_REFUSED)
    if args.engine not in (None, "auto", "numba"):
        raise ConfigError("--engine", f"{args.engine!r}: the axial engine is compiled (numba)")
    axial = config.axial
    skipped = growth_rate_skipped(axial.assembly, axial.contacts) if axial.bit.needs_axial else None
    if skipped is not None:  # the same at every point: said once
        print(f"torsio map: warning: {skipped}", file=sys.stderr)
    start = time.perf_counter()
    grid = axial_map(
        axial.assembly,
        axial.bit,
        wob,
        rpm,
        **_times(args, config),
        **axial.run_options(),
        growth_rate=skipped is None and axial.bit.needs_axial,
        threads=args.threads,
        executor=args.workers if args.workers is not None else args.scheduler,
        timeout=args.timeout,
        progress=(not args.json) and sys.stdout.isatty() or None,
    )
    data = grid.to_dict()
    data["info"] = {
        "engine": "axial",
        "scheme": SCHEME,
        "start": axial.start,
        "elapsed_s": time.perf_counter() - start,
        "executor": grid.executor,
        "model": axial.assembly.describe(),
    }
    if args.json:
        common.print_json(data)
    else:
        _print_map(data)
    return 0


def _print_map(data: dict[str, Any]) -> None:
    from rich.console import Console
    from rich.table import Table
    from rich.text import Text

    table = Table(title=f"Axial map: {len(data['rpm'])} x {len(data['wob'])} points")
    for name in ("rpm", "WOB [kN]", "S_SS", "stuck", "off bottom", "ROP [m/h]", "MSE [MPa]"):
        table.add_column(Text(name), justify="right")  # Text: "[kN]" is a unit, not markup
    for i, rpm in enumerate(data["rpm"]):
        for j, wob in enumerate(data["wob"]):
            mse = data["mse"][i][j]
            table.add_row(
                f"{rpm:.4g}",
                f"{wob / 1e3:.4g}",
                f"{data['severity'][i][j]:.3f}",
                f"{data['stick_fraction'][i][j]:.3f}",
                f"{data['off_bottom_fraction'][i][j]:.3f}",
                f"{data['rop'][i][j] * 3600:.4g}",
                "-" if mse is None else f"{mse / 1e6:.4g}",
            )
    console = Console()
    console.print(table)
    console.print(
        f"runs of {data['duration']:.4g} s, window {data['steady_window']:.4g} s, axial engine"
    )
