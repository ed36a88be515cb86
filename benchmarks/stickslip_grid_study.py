"""How the wave grid moves the features of an off-bottom stick-slip cycle.

The built-in deviated well (``data/deviated_well.toml``: 2.5 km string, friction along the
string) off bottom at 60 rpm with one friction along the whole hole (mu_s 0.3, mu_d 0.195),
a PI top drive (J = 2900 kg m^2; kp = 300 N m s/rad and ki = 2067.6 N m/rad, or --kp, --ki)
and no distributed drag (alpha = 0: the slip fronts are not smeared by damping), 160 s from
rest, the last 60 s the window (the 8x grid's step budget allows about 170 s).
It runs the default grid and grids 2x, 4x (and 8x with --fine) finer in time step (the
cell length follows: c dt) and prints S_SS, the stick fraction, the surface-torque swing
and the stick-slip period of each, with their change from the 4x grid (docs/wave.md,
"How the grid moves a stick-slip cycle").

Usage: python benchmarks/stickslip_grid_study.py [--fine] [--kp KP] [--ki KI]
"""

from __future__ import annotations

import argparse
import time
from importlib import resources
from typing import Any

from torsio.analysis.transient import simulate
from torsio.config.reading import parse_config_text

RPM = 60.0
DURATION, WINDOW = 160.0, 60.0  # s
TOP_DRIVE = '[top_drive]\nkind = "pi"\ninertia = "2900 kg*m^2"\nkp = {kp!r}\nki = {ki!r}\n\n'


def case_text(kp: float = 300.0, ki: float = 2067.6) -> str:
    """The built-in deviated well with the study's friction, PI top drive (gains ``kp``
    [N m s/rad], ``ki`` [N m/rad]) and drag."""
    text = resources.files("torsio").joinpath("data/deviated_well.toml").read_text("utf-8")
    for old, new in (
        ("friction_static = 0.35", "friction_static = 0.3"),
        ("friction_dynamic = 0.3\n", "friction_dynamic = 0.195\n"),
        ("friction_static = 0.25", "friction_static = 0.3"),
        ("friction_dynamic = 0.2\n", "friction_dynamic = 0.195\n"),
        ("alpha = 0.35", "alpha = 0.0"),
        ("[bit_rock]", TOP_DRIVE.format(kp=kp, ki=ki) + "[bit_rock]"),
    ):
        assert old in text, old
        text = text.replace(old, new, 1)
    return text


def features(refinement: int, kp: float, ki: float) -> dict[str, Any]:
    """The cycle's features on the default grid refined ``refinement`` times in dt."""
    config = parse_config_text(case_text(kp, ki), source="stick-slip grid study")
    coarse = config.system().at(wob=0.0, rpm=RPM)
    dt = coarse.model.time_step if refinement > 1 else None
    system = config.system(time_step=dt / refinement) if dt else coarse
    started = time.perf_counter()
    result = simulate(system.at(wob=0.0, rpm=RPM), duration=DURATION, steady_window=WINDOW)
    summary = result.well_summary
    return {
        "dt_ms": result.solver["time_step"] * 1e3,
        "cells": sum(result.solver["cells"]),
        "S_SS": result.severity,
        "stick": result.stick_fraction,
        "swing_kNm": summary["surface_torque_swing"] / 1e3,
        "period_s": summary["stick_slip_period"],
        "wall_s": time.perf_counter() - started,
    }


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fine", action="store_true", help="also the 8x finer grid")
    parser.add_argument("--kp", type=float, default=300.0, help="PI gain [N m s/rad]")
    parser.add_argument("--ki", type=float, default=2067.6, help="PI gain [N m/rad]")
    args = parser.parse_args(argv)
    refinements = (1, 2, 4, 8) if args.fine else (1, 2, 4)
    rows = {k: features(k, args.kp, args.ki) for k in refinements}
    reference = rows[4]
    keys = ("S_SS", "stick", "swing_kNm", "period_s")
    print("refinement, dt [ms], cells, " + ", ".join(keys) + ", wall [s]; change from 4x")
    for k, row in rows.items():
        change = [
            f"{(row[key] - reference[key]) / reference[key]:+.3f}" if reference[key] else "-"
            for key in keys
        ]
        values = ", ".join(f"{row[key]:.4g}" for key in keys)
        print(f"{k}x, {row['dt_ms']:.4g}, {row['cells']}, {values}, {row['wall_s']:.1f}; ", change)


if __name__ == "__main__":
    main()
