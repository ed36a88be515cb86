"""Report section on the top drive: its kind, gains, impedance and what it reflects.

The top drive's impedance at the first natural frequency ω₁ (top held) is
Z(iω₁) = (J iω₁ + drag + H_e)/(1 − H_T) (:meth:`TopDriveBoundary.impedance`), and a
torsional wave of the drill pipe's impedance ζ = J_p √(G ρ) is reflected with
R = (ζ − Z)/(ζ + Z): −1 at a held top, 0 at a matched one. For the PI kinds the report
also gives R = (ζ − kp)/(ζ + kp), the top drive's own ``reflection_coefficient``. See
``docs/top_drives.md``.
"""

from __future__ import annotations

import inspect
import math
from typing import Any

import attrs
import numpy as np
from rich.table import Table
from rich.text import Text

from torsio.report.context import ReportContext, ReportSection


def _complex(value: complex | None) -> dict[str, float] | None:
    if value is None:
        return None
    return {"real": float(value.real), "imag": float(value.imag), "abs": float(abs(value))}


def _parameters(top: Any) -> dict[str, Any]:
    if not attrs.has(type(top)):
        return {}
    values = attrs.asdict(top, recurse=False)
    return {
        k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in values.items()
    }


def pipe_impedance(system: Any, top: Any) -> float | None:
    """ζ [N m s/rad]: the top drive's own ``zeta`` if it has one, else J_p √(G ρ) of the top
    drill-pipe section; None for a ``[chain]`` model without either."""
    given = getattr(top, "zeta", None)
    if given is not None:
        return float(given)
    if system.string is None:
        return None
    from torsio.physics.top_drive_boundary import top_pipe_impedance

    return float(top_pipe_impedance(system))


def _pi_reflection(top: Any, zeta: float | None, system: Any) -> float | None:
    method = getattr(top, "reflection_coefficient", None)
    if method is None or zeta is None:
        return None
    if "system" in inspect.signature(method).parameters:
        return float(method(zeta, system=system))
    return float(method(zeta))


def top_drive_data(ctx: ReportContext) -> dict[str, Any] | None:
    """The top drive of the configuration as plain data (None without a System)."""
    system = ctx.system
    if system is None:
        return None
    top = system.top
    boundary = top.boundary(system)
    omega1 = ctx.first_frequency
    i_eq = float(ctx.model.equivalent_stiffness) / omega1**2
    zeta = pipe_impedance(system, top)
    pi_like = boundary.states >= 1
    kp = float(boundary.d[0]) if pi_like else None
    ki = float(boundary.c[0]) if pi_like else None
    impedance: complex | None = None
    reflection: complex | None = None
    if boundary.held:
        reflection = complex(-1.0)  # Z -> infinity: total reflection
    else:
        impedance = complex(boundary.impedance(omega1))
        if zeta is not None:
            reflection = (zeta - impedance) / (zeta + impedance)
    inertia = float(boundary.inertia)
    tuning = math.sqrt(ki / inertia) if ki is not None and inertia > 0 else None
    groups: dict[str, float | None] = {
        "inertia_ratio": inertia / i_eq if inertia > 0 else None,
        "kp_over_zeta": kp / zeta if kp is not None and zeta is not None else None,
        "kp_over_i_eq_omega1": kp / (i_eq * omega1) if kp is not None else None,
        "tuning_over_omega1": tuning / omega1 if tuning is not None else None,
    }
    return {
        "kind": str(top.name),
        "description": str(getattr(top, "description", "")),
        "parameters": _parameters(top),
        "held": bool(boundary.held),
        "inertia_kg_m2": inertia,
        "drag_n_m_s_per_rad": float(boundary.drag),
        "set_speed_rad_s": float(boundary.set_speed) if math.isfinite(boundary.set_speed) else None,
        "motor_torque_n_m": float(boundary.u0),
        "controller_states": int(boundary.states),
        "kp_n_m_s_per_rad": kp,
        "ki_n_m_per_rad": ki,
        "tuning_frequency_rad_s": tuning,
        "max_torque_n_m": float(boundary.max_torque) if np.isfinite(boundary.max_torque) else None,
        "omega1_rad_s": omega1,
        "pipe_impedance_n_m_s_per_rad": zeta,
        "impedance_at_omega1_n_m_s_per_rad": _complex(impedance),
        "reflection_coefficient": _pi_reflection(top, zeta, system),
        "reflection_at_omega1": _complex(reflection),
        "groups": groups,
    }


def _format_complex(value: dict[str, float]) -> str:
    sign = "+" if value["imag"] >= 0 else "−"
    return f"{value['real']:.4g} {sign} {abs(value['imag']):.4g}i (|·| = {value['abs']:.4g})"


def top_drive_section(ctx: ReportContext) -> ReportSection | None:
    """The top drive: kind, gains, impedance at ω₁ and reflection coefficients."""
    data = top_drive_data(ctx)
    if data is None:
        return None
    table = Table.grid(padding=(0, 2))
    table.add_column(style="dim")
    table.add_column()
    rows = [("kind", f"{data['kind']}: {data['description']}")]
    if data["held"]:
        rows.append(("boundary", "held at the set speed (no inertia, no controller)"))
    else:
        rows.append(("inertia J", f"{data['inertia_kg_m2']:.5g} kg m²"))
        rows.append(("drag", f"{data['drag_n_m_s_per_rad']:.5g} N m s/rad"))
        if data["set_speed_rad_s"] is None:
            rows.append(("motor torque", f"{data['motor_torque_n_m']:.5g} N m (no set speed)"))
    if data["kp_n_m_s_per_rad"] is not None:
        kp, ki = data["kp_n_m_s_per_rad"], data["ki_n_m_per_rad"]
        gains = f"kp = {kp:.5g} N m s/rad, ki = {ki:.5g} N m/rad"
        rows.append(("gains", gains))
        if data["tuning_frequency_rad_s"] is not None:
            ratio = data["groups"]["tuning_over_omega1"]
            rows.append(("√(ki/J)", f"{data['tuning_frequency_rad_s']:.4g} rad/s ({ratio:.3g} ω₁)"))
    if data["max_torque_n_m"] is not None:
        rows.append(("torque limit", f"{data['max_torque_n_m']:.5g} N m (anti-windup)"))
    zeta = data["pipe_impedance_n_m_s_per_rad"]
    rows.append(("pipe impedance ζ", "none (a chain)" if zeta is None else f"{zeta:.5g} N m s/rad"))
    rows.append(("ω₁ (top held)", f"{data['omega1_rad_s']:.5g} rad/s"))
    impedance = data["impedance_at_omega1_n_m_s_per_rad"]
    if impedance is not None:
        rows.append(("Z(iω₁)", f"{_format_complex(impedance)} N m s/rad"))
    if data["reflection_coefficient"] is not None:
        rows.append(("R = (ζ−kp)/(ζ+kp)", f"{data['reflection_coefficient']:+.4f}"))
    reflection = data["reflection_at_omega1"]
    if reflection is not None:
        text = "−1 (total reflection)" if data["held"] else _format_complex(reflection)
        rows.append(("R at ω₁", text))
    for label, value in rows:
        table.add_row(label, Text(value))
    return ReportSection("top_drive", "Top drive", data, table)
