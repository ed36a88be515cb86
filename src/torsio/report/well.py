"""The report's well section: the survey, torque and drag, and the break-off from rest.

Present when the configuration has a ``[well]`` table (:mod:`torsio.well`): the survey's
extent and its largest inclination and dogleg, the hookloads and surface torques of
soft-string torque and drag (on bottom at the operating weight on bit), and the torque
and twist at which the string lying in the hole breaks free from rest
(:func:`torsio.well.break_off.break_off`).

Examples
--------
>>> from torsio.examples import deviated_well_config
>>> from torsio.report.context import ReportContext
>>> section = well_section(ReportContext(deviated_well_config()))
>>> round(section.data["break_off_torque"] / 1e3, 2), round(section.data["break_off_twist"], 2)
(12.17, 19.26)
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from rich.table import Table
from rich.text import Text

from torsio.report.context import ReportContext, ReportSection

__all__ = ["well_section"]


def well_section(ctx: ReportContext) -> ReportSection | None:
    """The well: survey, torque and drag, break-off torque and twist (None without [well])."""
    well = getattr(ctx.config, "well", None)
    string = ctx.config.string
    if well is None or string is None:
        return None
    from torsio.config.bit_torque import law_bit_torque
    from torsio.errors import ConfigError
    from torsio.well.break_off import break_off
    from torsio.well.torque_drag import torque_drag

    survey = well.survey
    wob = float(ctx.config.operation.wob or 0.0)
    try:  # the law's torque on bit at the operating point, as torsio drag adds it
        bit_torque, source = law_bit_torque(ctx.config, wob)
    except ConfigError as exc:  # no law or no rotary speed: said beside the torque
        bit_torque, source = 0.0, f"none: no {exc.key}"
    drag = torque_drag(well, string, wob=wob, bit_torque=bit_torque)
    start = break_off(well, string)
    along = np.linspace(0.0, survey.depth, 2001)  # the arcs between stations, every 1/2000
    inclination = math.degrees(float(np.max(survey.inclination(along))))
    dogleg = float(np.max(survey.station_doglegs / np.maximum(np.diff(survey.md), 1e-300)))
    data = {
        "survey_depth_md": float(survey.depth),
        "survey_stations": int(survey.md.size),
        "max_inclination_deg": inclination,
        "max_dogleg_deg_per_30m": math.degrees(dogleg) * 30.0,
        "mud_density": float(well.mud_density),
        "normal_force": well.normal_force,
        "hookload_trip_out": drag.hookload_trip_out,
        "hookload_trip_in": drag.hookload_trip_in,
        "hookload_rotating": drag.hookload_rotating,
        "surface_torque_rotating": drag.surface_torque_rotating,
        "wob": wob,
        "hookload_on_bottom": drag.hookload_on_bottom,
        "surface_torque_on_bottom": drag.surface_torque_on_bottom,
        "bit_torque": bit_torque,
        "bit_torque_source": source,
        **start.to_dict(),
    }
    table = Table.grid(padding=(0, 2))
    table.add_column(style="dim")
    table.add_column()
    units = ctx.units
    rows = [
        (
            "survey",
            f"{data['survey_stations']} stations to md "
            f"{units.text('length', data['survey_depth_md'], 'g')}, "
            f"inclination up to {inclination:.1f}°, dogleg up to {_dogleg(data, units)}",
        ),
        (
            "mud, normal force",
            f"{units.text('density', well.mud_density, '.4g')}, {well.normal_force}",
        ),
        (
            "hookload",
            f"pick-up {units.text('force', drag.hookload_trip_out, '.1f')}, slack-off "
            f"{units.text('force', drag.hookload_trip_in, '.1f')}, "
            f"rotating {units.text('force', drag.hookload_rotating, '.1f')}",
        ),
        (
            "surface torque",
            f"off bottom {units.text('torque', drag.surface_torque_rotating, '.2f')}, on "
            f"bottom {units.text('torque', drag.surface_torque_on_bottom, '.2f')} (WOB "
            f"{units.text('force', wob, '.4g')}, bit {units.text('torque', bit_torque, '.3g')}: "
            f"{source})",
        ),
        (
            "break-off from rest",
            f"{units.text('torque', start.torque, '.2f')} after a twist of {start.twist:.2f} rad "
            f"({start.twist / (2.0 * math.pi):.2f} turns) stored before the bit turns",
        ),
    ]
    _ = ctx.system  # the dynamics with friction along the string, or why not
    if ctx.dynamics_note:
        data["dynamics"] = ctx.dynamics_note
        rows.append(("dynamics", ctx.dynamics_note))
    for label, value in rows:
        table.add_row(label, Text(value))
    return ReportSection("well", "Well: torque and drag", data, table)


def _dogleg(data: dict[str, Any], units: Any) -> str:
    """The largest dogleg severity per 30 m (SI) or per 100 ft (field: 30.48 m)."""
    per_30m = data["max_dogleg_deg_per_30m"]
    if units.system == "field":
        return f"{per_30m * 30.48 / 30.0:.2f}°/100 ft"
    return f"{per_30m:.2f}°/30 m"
