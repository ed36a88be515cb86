"""The report section of a configuration with axial dynamics (the RGD bit).

The assembly's natural frequencies (torsional, top held; axial, bit free, the top free
under the weight hook or held by k_a,0 under the speed hook), the steady drilling state at
the operating point (depth of cut, ROP, bit torque, MSE) and its linear stability: the
growth rate and the rpm where it crosses zero, each with the frequency and the kind (axial
or torsional) of the mode that crosses there (:func:`torsio.axial.stability.mode_crossings`
over :data:`CROSSING_RANGE`).

A distributed pipe (a :class:`~torsio.model.wave.WaveModel` with axial rows) has the
exact continuum frequencies of its stepped bar with the same boundaries; its stability is
that of its lumped twin (:attr:`torsio.config.axial.AxialConfig.lumped_twin`), and the
data's ``stability.stability_model`` says so.

Examples
--------
>>> from torsio.examples import rgd_two_dof_config
>>> from torsio.report.context import ReportContext
>>> section = axial_section(ReportContext(rgd_two_dof_config()))
>>> round(section.data["steady_state"]["depth_of_cut"] * 1e3, 4)  # mm per revolution
7.3868
>>> [round(r, 1) for r in section.data["stability"]["crossing_rpm"]]
[153.3]
>>> [c["mode"] for c in section.data["stability"]["crossings"]]
['axial']
"""

from __future__ import annotations

import functools
import math
from typing import Any, cast

import scipy.linalg
from rich.table import Table

from torsio.axial.linearization import axial_matrices
from torsio.display_units import DisplayUnits
from torsio.model.axial_assembly import (
    assembly_description,
    assembly_summary,
    pipe_rows,
    require_axial,
)
from torsio.model.continuum import bar_frequencies, continuum_modes
from torsio.model.lumped import LumpedModel
from torsio.model.modal import natural_frequencies
from torsio.model.wave import WaveModel
from torsio.physics.torque_law_bit import TorqueLawBit
from torsio.report.context import ReportContext, ReportSection

__all__ = [
    "CROSSING_RANGE",
    "axial_frequencies",
    "axial_modes",
    "axial_section",
    "torsional_frequencies",
]

CROSSING_RANGE = (20.0, 300.0)
"""The rpm range [rev/min] searched for a change of sign of the growth rate (15 points)."""
MODE_CROSSINGS_SHOWN = 6
"""How many of every mode's crossings the table lists (the data has them all)."""
DISTRIBUTED_MODES = 10
"""How many frequencies of a distributed pipe :func:`axial_frequencies` and
:func:`torsional_frequencies` give by default (a chain gives all of its own)."""


def axial_frequencies(
    assembly: LumpedModel | WaveModel, count: int = DISTRIBUTED_MODES
) -> list[float]:
    """The axial natural frequencies [Hz] of the assembly with the bit free, undamped:
    the top free under the weight hook (its rigid-body zero left out) or held by k_a,0
    (the distributed pipe: held) under the speed hook; none for an axially rigid
    assembly. A chain gives all of its own; a distributed pipe the first ``count`` of its
    exact continuum (:func:`torsio.model.continuum.bar_frequencies`: E A, √(E/ρ), m_b).

    >>> from torsio.model.axial_assembly import axial_model, pipe_string, tube_section
    >>> from torsio.model.discretize import StrategyC
    >>> from torsio.model.wave import WaveStrategy
    >>> string = pipe_string([tube_section(1000.0, 2.0e11, 8.0e10, 7850.0, 3.4e-3, 1.5e-5)],
    ...                      3.0e4, 230.0)
    >>> chain = axial_model(string, StrategyC(dp_elements=4))
    >>> [round(f, 3) for f in axial_frequencies(chain)][:2]
    [1.596, 3.867]
    >>> pipe = axial_model(string, WaveStrategy(rigid_bha=True))
    >>> [round(f, 3) for f in axial_frequencies(pipe, 2)]  # the continuum of the same pipe
    [1.599, 3.93]
    """
    if not assembly.has_matrices:  # the distributed pipe: its continuum
        pipe = cast(WaveModel, assembly)
        rows = pipe_rows(pipe)
        omega = bar_frequencies(rows.rigidities, pipe.lengths, rows.wave_speeds, rows.bha_mass,
                                count, free_top=rows.hook == "weight")  # fmt: skip
        return [float(w) / (2 * math.pi) for w in omega]
    chain = cast(LumpedModel, assembly)
    if not require_axial(chain).stiffnesses.size:
        return []
    mass, _, stiffness = axial_matrices(chain)
    values = scipy.linalg.eigh(stiffness, mass, eigvals_only=True)
    if require_axial(chain).hook == "weight":
        values = values[1:]
    return [math.sqrt(max(v, 0.0)) / (2 * math.pi) for v in values]


def axial_modes(config: Any, count: int | None = None) -> dict[str, Any]:
    """What ``torsio modes`` adds for a configuration with axial dynamics (none without):
    ``axial_frequencies_hz``, the first ``count`` of :func:`axial_frequencies` (default
    all of a chain's, :data:`DISTRIBUTED_MODES` of a distributed pipe's) and
    ``axial_boundaries``, the ends they are of."""
    if config.axial is None:
        return {}
    assembly = config.axial.assembly
    values = axial_frequencies(assembly, count or DISTRIBUTED_MODES)[:count]
    top = "top free" if config.axial.hook == "weight" else "top held"
    return {"axial_frequencies_hz": values, "axial_boundaries": f"bit free, {top}"}


def torsional_frequencies(
    assembly: LumpedModel | WaveModel, count: int = DISTRIBUTED_MODES
) -> list[float]:
    """The torsional natural frequencies [Hz], the top drive held and the bit free,
    undamped (a chain: all of its own; a distributed pipe: the first ``count`` of its
    string's exact continuum, the BHA rigid)."""
    if not assembly.has_matrices:
        modes = continuum_modes(cast(WaveModel, assembly).string, count, rigid_bha=True)
        return [float(w) / (2 * math.pi) for w in modes.frequencies_rad]
    return [float(w) / (2 * math.pi) for w in natural_frequencies(cast(LumpedModel, assembly))]


def _stability(axial: Any, wob: float, rpm: float) -> dict[str, Any]:
    from torsio.axial.linearization import drilling_linearization, speed_loop
    from torsio.axial.root_branches import unstable_roots
    from torsio.axial.stability import (
        DrillingCase,
        drilling_stability,
        each_mode_crossing,
        mode_crossings,
    )
    from torsio.axial.steady import steady_drilling
    from torsio.physics.axial_top_drive import top_boundary

    chain = axial.stability_assembly  # a distributed pipe's lumped twin
    top = None
    if axial.top_drive is not None:
        top = top_boundary(axial.top_drive, chain, rpm, axial.string)
    contacts = axial.contacts
    result = drilling_stability(
        chain, axial.bit, wob, rpm, count=1, top_drive=top, contacts=contacts
    )
    case = DrillingCase(chain, axial.bit, wob, top, contacts)
    crossings = mode_crossings(case, CROSSING_RANGE, points=15)
    each = each_mode_crossing(case, CROSSING_RANGE, points=15)
    steady = steady_drilling(axial.bit, wob, rpm)
    held = top is not None and not top.held
    held = held and speed_loop(top, steady.bit_torque, steady.bit_speed) is None
    growth = {"growth_rate": result.growth_rate, "stable": result.stable, "twin_growth_rate": None}
    model = axial.stability_model
    if not axial.assembly.has_matrices and contacts is None:  # its own equation
        from torsio.axial.wave_stability import distributed_stability

        exact = distributed_stability(axial.assembly, axial.bit, wob, rpm, twin=chain)
        growth = {"growth_rate": exact.growth_rate, "stable": exact.stable,
                  "twin_growth_rate": result.growth_rate}  # fmt: skip
        model = "the distributed pipe's exact characteristic equation, from the twin's roots"
    return {
        "contacts": None
        if contacts is None
        else "each sliding contact's damping F_d/|s0| (I - s s^T) at the steady state with "
        "friction (every node sliding at V0, Omega0)",
        "held_top": held,
        "stability_model": axial.stability_model,
        "growth_rate_model": model,
        **growth,
        "crossing_rpm": [c.rpm for c in crossings],
        "crossings": [c.to_dict() for c in crossings],
        "unstable_modes": unstable_roots(
            drilling_linearization(chain, axial.bit, wob, rpm, top, contacts)
        ),
        "mode_crossings": each.to_dict(),
        "crossing_range_rpm": list(CROSSING_RANGE),
    }


def _friction(steady: Any, friction: Any, contacts: Any) -> dict[str, Any]:
    """The contacts' totals and what they take in steady drilling (``steady``,
    ``friction`` of :func:`~torsio.axial.steady_friction.drilling_state`)."""
    return {
        "string_contacts": contacts.describe(),
        "steady_friction": {**friction.to_dict(), "bit_weight": steady.wob},
    }


def _modes_crossing(stability: dict[str, Any]) -> str:
    """The row of every mode's crossings: how many turn unstable and stable, the first few."""
    each = stability["mode_crossings"]
    crossings = each["crossings"]
    low, high = each["rpm_range"]
    rising = sum(c["destabilizing"] for c in crossings)
    shown = ", ".join(
        f"{c['rpm']:.4g} ({c['mode']}, {'unstable' if c['destabilizing'] else 'stable'} above)"
        for c in crossings[:MODE_CROSSINGS_SHOWN]
    )
    if len(crossings) > MODE_CROSSINGS_SHOWN:
        shown += f", {len(crossings) - MODE_CROSSINGS_SHOWN} more"
    text = (
        f"{len(crossings)} in {low:g}..{high:g} rpm ({rising} turn unstable, "
        f"{len(crossings) - rising} stable as the rpm rises){': ' + shown if crossings else ''}; "
        f"{stability['unstable_modes']} unstable at the operating point"
    )
    if not each["complete"]:
        text += (
            f" (some crossings are missed: {each['unstable_at_low']} unstable at {low:g} "
            f"rpm and the crossings do not give the {each['unstable_at_high']} at {high:g})"
        )
    return text


def axial_section(ctx: ReportContext) -> ReportSection | None:
    """The ``axial`` section: frequencies, steady drilling state, stability."""
    from torsio.axial.steady_friction import drilling_state

    axial = ctx.config.axial
    if axial is None:
        return None
    op = ctx.config.operation
    assembly = axial.assembly
    count = ctx.requested_modes
    data: dict[str, Any] = {
        "model": assembly_description(assembly),
        "bit": axial.bit.to_dict(),
        "torsional_frequencies_hz": torsional_frequencies(assembly, count)[:count],
        "axial_frequencies_hz": axial_frequencies(assembly, count)[:count],
        "wob_n": op.wob,
        "rpm": op.rpm,
        "steady_state": None,
        "stability": None,
        "note": "",
        "top_drive": getattr(axial.top_drive, "name", "constant-speed"),
        "stability_of_held_top": False,
    }
    if op.wob is None or op.rpm is None:
        data["note"] = "no [operation] wob and rpm: no steady state"
    elif isinstance(axial.bit, TorqueLawBit):  # a law of the torque alone
        data["steady_state"] = axial.bit.steady(op.wob, op.rpm).to_dict()
        data["note"] = (
            f"the {axial.bit.name} law is a law of the torque alone: the bit rests on the rock "
            "under the weight on bit (no rate of penetration); no growth rate of drilling"
        )
    elif op.wob <= axial.bit.friction_weight:
        data["note"] = (
            f"the weight on bit is at most sigma a l = {axial.bit.friction_weight:.6g} N: "
            "the bit does not cut"
        )
    else:
        steady, friction = drilling_state(axial.bit, op.wob, op.rpm, axial.contacts, axial.hook)
        if friction is not None:
            data.update(_friction(steady, friction, axial.contacts.at_wob(op.wob)))
        data["steady_state"] = steady.to_dict()
        data["stability"] = _stability(axial, op.wob, op.rpm)
        data["stability_of_held_top"] = data["stability"]["held_top"]
    title = f"Axial dynamics ({'RGD' if axial.bit.needs_axial else axial.bit.name} bit)"
    return ReportSection("axial", title, data, _body(data, ctx.units))


def _hz(values: list[float], boundaries: str) -> str:
    if not values:
        return "none (axially rigid)"
    return ", ".join(f"{f:.4g}" for f in values) + f" Hz ({boundaries})"


def _body(data: dict[str, Any], units: DisplayUnits) -> Table:
    force, torque = (functools.partial(units.text, q) for q in ("force", "torque"))
    model = data["model"]
    table = Table.grid(padding=(0, 2))
    table.add_column(style="dim")
    table.add_column()
    top = "top free" if model["hook"] == "weight" else "top held"
    rows = [
        ("assembly", assembly_summary(model)),
        ("torsional frequencies", _hz(data["torsional_frequencies_hz"], "top held")),
        ("axial frequencies", _hz(data["axial_frequencies_hz"], f"bit free, {top}")),
        ("top drive", data["top_drive"]),
    ]
    steady = data["steady_state"]
    if steady is not None:
        rows += [
            ("operating point", f"{force(data['wob_n'], '.4g')}, {data['rpm']:.4g} rpm"),
        ]
        if steady["rop"] > 0:
            rows += [
                ("steady depth of cut", f"{steady['depth_of_cut'] * 1e3:.4g} mm/rev"),
                ("steady ROP", f"{steady['rop'] * 3600:.4g} m/h ({steady['rop']:.4g} m/s)"),
            ]
        rows.append(("steady bit torque", torque(steady["bit_torque"], ".4g")))
        if steady["rop"] > 0:
            rows.append(("steady MSE", f"{steady['mse'] / 1e6:.4g} MPa"))
    contacts, friction = data.get("string_contacts"), data.get("steady_friction")
    if contacts is not None and friction is not None:
        rows += [
            ("string contacts", f"{contacts['count']} nodes ({contacts['normal_force']}), "
             f"F_s {force(contacts['static_force'], '.4g')}, F_d "
             f"{force(contacts['sliding_force'], '.4g')}, break-off "
             f"{torque(contacts['static_torque'], '.4g')}, sliding "
             f"{torque(contacts['sliding_torque'], '.4g')}"),
            ("steady bit weight", f"{force(friction['bit_weight'], '.5g')} (hook "
             f"{force(friction['hook_force'], '.5g')}, axial friction "
             f"{force(friction['axial_friction'], '.4g')})"),
            ("steady surface torque", f"{torque(friction['surface_torque'], '.4g')} (friction "
             f"{torque(friction['friction_torque'], '.4g')})"),
        ]  # fmt: skip
    stability = data["stability"]
    if stability is not None:
        if stability.get("contacts"):
            rows.append(("contacts in stability", stability["contacts"]))
        rate = stability["growth_rate"]
        crossings = stability["crossings"]
        low, high = stability["crossing_range_rpm"]
        rows += [
            (
                "stability computed on"
                if stability["twin_growth_rate"] is None
                else "crossings computed on",
                stability["stability_model"],
            ),
            (
                "growth rate",
                f"{rate:.4g} 1/s ({'stable' if rate < 0 else 'unstable'})"
                + (
                    " with the top held at the set speed, not with the top drive"
                    if data["stability_of_held_top"]
                    else ""
                ),
            ),
        ]
        if stability["twin_growth_rate"] is not None:
            rows += [
                ("growth rate from", stability["growth_rate_model"]),
                ("growth rate of the twin", f"{stability['twin_growth_rate']:.4g} 1/s"),
            ]
        rows += [
            (
                "crossing rpm",
                ", ".join(
                    f"{c['rpm']:.4g} rpm ({c['mode']}, {c['frequency'] / (2 * math.pi):.4g} Hz)"
                    for c in crossings
                )
                if crossings
                else f"none in {low:g}..{high:g} rpm",
            ),
            ("modes crossing", _modes_crossing(stability)),
        ]
    if data["note"]:
        rows.append(("note", data["note"]))
    for label, value in rows:
        table.add_row(label, value)
    return table
