"""Report sections on the structure: the drill-string, its discretization, modes, damping."""

from __future__ import annotations

from typing import Any

import numpy as np
from rich.console import Group, RenderableType
from rich.table import Table
from rich.text import Text

from torsio.config.configuration import Config
from torsio.display_units import DisplayUnits
from torsio.errors import ConfigError
from torsio.model.continuum import ContinuumModes, continuum_modes
from torsio.model.drillstring import DrillString
from torsio.model.modal import ModalComparison
from torsio.physics.damping import RayleighDamping
from torsio.report.context import (
    ReportContext,
    ReportSection,
    _ByWidth,
    _diameter,
    _number,
    _table,
)


# --- the drill-string ---------------------------------------------------------------------
def string_table(
    string: DrillString | Config, wide: bool = True, units: DisplayUnits | None = None
) -> Table:
    """The drill-string as a table: geometry, J, inertia, stiffness, BHA membership.

    Parameters
    ----------
    string : DrillString or Config
        The string (or a configuration holding it).
    wide : bool
        ``False`` gives a layout that fits 80 columns (kind under the name,
        OD/ID in one column, units under the headers).
    units : DisplayUnits, optional
        Diameters and lengths in mm and m (default) or, ``DisplayUnits("field")``, in in
        and ft.

    Examples
    --------
    >>> from torsio import ritto2017_string
    >>> table = string_table(ritto2017_string(), wide=False)
    >>> table.row_count
    4
    """
    if isinstance(string, Config):
        if string.string is None:
            raise ConfigError("chain", "a [chain] model has no drill-string sections to show")
        string = string.string
    sections = string.sections
    units = DisplayUnits() if units is None else units
    diameter, length = units.label("diameter"), units.label("length")
    if wide:
        table = _table(
            "#",
            "section",
            "kind",
            f"OD\n[{diameter}]",
            f"ID\n[{diameter}]",
            f"length\n[{length}]",
            "J\n[m⁴]",
            "inertia\n[kg m²]",
            "stiffness\n[N m/rad]",
            "BHA",
            left=("section", "kind"),
        )
    else:
        table = _table(
            "#",
            "section",
            f"OD/ID\n[{diameter}]",
            f"L\n[{length}]",
            "J\n[m⁴]",
            "I\n[kg m²]",
            "k\n[N m/rad]",
            "BHA",
            left=("section",),
        )
    for i, s in enumerate(sections):
        stiffness = "rigid" if s.kind == "bit" else _number(s.stiffness)
        numbers = [
            units.number("length", s.length, ".5g"),
            _number(s.polar_moment, scientific=True),
            f"{s.inertia:.5g}",
            stiffness,
            "yes" if s.in_bha else "no",
        ]
        if wide:
            od, id_ = _diameter(s.od, units), _diameter(s.id, units)
            table.add_row(str(i), Text(s.name or "-"), s.kind, od, id_, *numbers)
        else:
            name = Text(s.name or s.kind)
            if s.name:
                name.append(f"\n{s.kind}", style="dim")
            od_id = f"{_diameter(s.od, units)}/{_diameter(s.id, units)}"
            table.add_row(str(i), name, od_id, *numbers)
    return table


def chain_section(ctx: ReportContext) -> ReportSection:
    """A ``[chain]`` model given directly: one row per node (inertia, spring, damper, drag)."""
    chain = ctx.config.chain
    assert chain is not None
    n = chain.dofs
    dampings = chain.dampings or (0.0,) * n
    drag = chain.drag or (0.0,) * n
    data = {
        "nodes": [
            {
                "index": i + 1,
                "inertia_kg_m2": chain.inertias[i],
                "stiffness_n_m_per_rad": chain.stiffnesses[i],
                "damping_n_m_s_per_rad": dampings[i],
                "drag_n_m_s_per_rad": drag[i],
            }
            for i in range(n)
        ],
        "continuum": None,
    }
    table = _table("node", "I\n[kg m²]", "k\n[N m/rad]", "c\n[N m s/rad]", "drag\n[N m s/rad]")
    for i in range(n):
        cells = (chain.inertias[i], chain.stiffnesses[i], dampings[i], drag[i])
        table.add_row(str(i + 1), *(f"{value:.6g}" for value in cells))
    note = Text(
        "k_i and c_i join node i-1 and node i (node 0: the top drive); node "
        f"{n} carries the bit. A lumped model given directly: no drill-string, "
        "so no exact continuum to compare with.",
        style="dim",
    )
    title = f"Lumped chain: {ctx.config.name or 'unnamed'}"
    return ReportSection("chain", title, data, Group(table, note))


def string_section(ctx: ReportContext) -> ReportSection:
    """The drill-string: one row per section, then the lumped totals of Eq. 5.

    For a ``[chain]`` configuration, the chain instead (:func:`chain_section`).
    """
    string = ctx.config.string
    if string is None:
        return chain_section(ctx)
    bottom = float(string.section_tops[-1] + string.bit.length)
    data = {
        "sections": [
            {
                "index": i,
                "name": s.name,
                "kind": s.kind,
                "od_m": s.od,
                "id_m": s.id,
                "length_m": s.length,
                "top_depth_m": float(string.section_tops[i]),
                "polar_moment_m4": s.polar_moment,
                "inertia_kg_m2": s.inertia,
                "stiffness_n_m_per_rad": None if s.kind == "bit" else s.stiffness,
                "shear_modulus_pa": s.material.shear_modulus,
                "density_kg_m3": s.material.density,
                "bha": s.in_bha,
            }
            for i, s in enumerate(string.sections)
        ],
        "bit_depth_m": bottom,
        "drill_pipe_inertia_kg_m2": string.drill_pipe_inertia,
        "bha_inertia_kg_m2": string.bha_inertia,
        "drill_pipe_stiffness_n_m_per_rad": string.drill_pipe_stiffness,
    }
    totals = Text(
        f"drill pipes: I_DP = {string.drill_pipe_inertia:.5g} kg m², "
        f"k_DP = {string.drill_pipe_stiffness:.5g} N m/rad\n"
        f"BHA (bit included): I_BHA = {string.bha_inertia:.5g} kg m²; "
        f"bit bottom at {ctx.units.text('length', bottom, '.6g')}",
        style="dim",
    )
    body = Group(
        _ByWidth(
            lambda: string_table(ctx.config, wide=False, units=ctx.units),
            lambda: string_table(ctx.config, wide=True, units=ctx.units),
        ),
        totals,
    )
    title = f"Drill-string: {ctx.config.name or 'unnamed'}"
    return ReportSection("string", title, data, body)


# --- the discretization -------------------------------------------------------------------
def discretization_section(ctx: ReportContext) -> ReportSection:
    """The strategy, its degrees of freedom and the elements of each section."""
    from torsio.plugins import get_discretizer

    model = ctx.model
    string = ctx.config.string
    if string is None:
        text = "none: the lumped model is given directly ([chain])"
        data_chain = {"strategy": model.strategy, "description": text, "dofs": model.dofs}
        data_chain.update({"elements": {}, "parts": [], "lumped_mass": model.has_lumped_mass})
        head = Text.assemble(("degrees of freedom ", "dim"), (str(model.dofs), "bold"))
        body = Group(Text(f"discretization {text}"), head)
        return ReportSection("discretization", "Discretization", data_chain, body)
    description = getattr(get_discretizer(model.strategy), "description", "")
    elements = dict(model.details.get("elements", {}))
    lengths = {s.name or s.kind: s.length for s in string.flexible_sections}
    table = _table("part", "elements", "element length [m]", left=("part",))
    rows = []
    for part, count in elements.items():
        length = lengths.get(part) if isinstance(count, int) else None
        element_length = None if length is None else length / count
        rows.append({"part": part, "elements": count, "element_length_m": element_length})
        length_text = "-" if element_length is None else f"{element_length:.4g}"
        table.add_row(Text(str(part)), str(count), length_text)
    data = {
        "strategy": model.strategy,
        "description": description,
        "dofs": model.dofs,
        "elements": elements,
        "parts": rows,
        "lumped_mass": model.has_lumped_mass,
    }
    head = Text.assemble(
        ("strategy ", "dim"),
        (model.strategy, "bold"),
        f" — {description}\n",
        ("degrees of freedom ", "dim"),
        (str(model.dofs), "bold"),
    )
    return ReportSection("discretization", "Discretization", data, Group(head, table))


# --- the modes ----------------------------------------------------------------------------
def modes_table(comparison: ModalComparison, flexible: ContinuumModes | None = None) -> Table:
    """Lumped frequencies against the exact continuum, mode by mode.

    The continuum of the string as given (flexible BHA) comes first; when the
    model keeps the BHA rigid (strategies A and C), the rigid-BHA continuum (the
    limit of its discretization) follows in two more columns.

    Parameters
    ----------
    comparison : ModalComparison
        The modes against their reference continuum.
    flexible : ContinuumModes, optional
        The continuum of the flexible string when the reference keeps the BHA rigid
        (default: ``comparison.flexible``).
    """
    rigid = comparison.reference.rigid_bha
    given = comparison.as_given if flexible is None or not rigid else flexible
    columns = ["mode", "lumped\n[Hz]", "continuum\n[Hz]", "error\n[%]"]
    if rigid:
        columns += ["rigid BHA\n[Hz]", "error\n[%]"]
    table = _table(*columns, "period\n[s]")
    for i, (mode, lumped, exact, error) in enumerate(comparison.rows()):
        cells = [str(mode), f"{lumped:.5f}"]
        if given is not None:
            full = float(given.frequencies_hz[i])
            cells += [f"{full:.5f}", f"{100 * (lumped / full - 1):+.3f}"]
        else:
            cells += ["-", "-"]
        if rigid:
            cells += [f"{exact:.5f}", f"{100 * error:+.3f}"]
        table.add_row(*cells, f"{1.0 / lumped:.4g}")
    return table


def modes_section(ctx: ReportContext) -> ReportSection:
    """The first natural frequencies against the exact stepped-shaft continuum.

    The reference is the continuum of the string as given (flexible BHA); when the
    model keeps the BHA rigid (strategies A and C) the rigid-BHA continuum, the
    limit of its discretization, is given as well.
    """
    comparison = ctx.comparison
    if comparison is None or ctx.config.string is None:
        return _chain_modes_section(ctx)
    given = comparison.as_given
    if given is None:
        given = continuum_modes(ctx.config.string, comparison.count)
    full_hz = given.frequencies_hz[: comparison.count]
    data = {
        "count": comparison.count,
        "frequencies_hz": comparison.frequencies_hz.tolist(),
        **comparison.to_dict(),
        "flexible_continuum_hz": full_hz.tolist(),
        "flexible_relative_error": (comparison.frequencies_hz / full_hz - 1.0).tolist(),
    }
    title = "Modes against the exact continuum (the string as given, flexible BHA)"
    body: RenderableType = modes_table(comparison, given)
    if comparison.reference.rigid_bha:
        note = Text(
            "rigid BHA: the exact continuum with the BHA rigid, this strategy's limit",
            style="dim",
        )
        body = Group(body, note)
    return ReportSection("modes", title, data, body)


NO_CONTINUUM = "none: the model is a [chain] given directly, with no drill-string behind it"
"""What reports and ``torsio modes`` say instead of a continuum reference for a chain."""


def _chain_modes_section(ctx: ReportContext) -> ReportSection:
    frequencies_hz = ctx.modal.frequencies_hz
    data = {
        "count": int(frequencies_hz.size),
        "frequencies_hz": frequencies_hz.tolist(),
        "continuum_hz": None,
        "relative_error": None,
        "continuum": NO_CONTINUUM,
    }
    table = _table("mode", "lumped\n[Hz]", "period\n[s]")
    for i, f in enumerate(frequencies_hz):
        table.add_row(str(i + 1), f"{f:.5f}", f"{1.0 / f:.4g}")
    note = Text(f"exact continuum: {NO_CONTINUUM}", style="dim")
    return ReportSection("modes", "Modes", data, Group(table, note))


# --- damping ------------------------------------------------------------------------------
def damping_section(ctx: ReportContext) -> ReportSection:
    """Rayleigh damping [C] = alpha [I] + beta [K] and the modal damping ratio of each mode."""
    damping = ctx.damping
    omega = ctx.modal.frequencies_rad
    if not isinstance(damping, RayleighDamping):  # a model carrying its own dampers
        data: dict[str, Any] = {"kind": "model"}
        return ReportSection("damping", "Damping", data, Text("damping carried by the model"))
    alpha, beta = damping.alpha, damping.beta
    ratios = np.asarray(damping.ratios(omega))
    configured = ctx.config.damping
    data = {
        "kind": "rayleigh",
        "alpha_per_s": alpha,
        "beta_s": beta,
        "target_ratios": None if configured.ratios is None else list(configured.ratios),
        "target_modes": None if configured.ratios is None else list(configured.modes),
        "modes": list(range(1, omega.size + 1)),
        "ratios": ratios.tolist(),
    }
    table = _table("mode", "ω [rad/s]", "α/(2ω) [%]", "βω/2 [%]", "ζ [%]")
    for i, (w, zeta) in enumerate(zip(omega, ratios, strict=True)):
        table.add_row(
            str(i + 1),
            f"{w:.3f}",
            f"{100 * alpha / (2 * w):.2f}",
            f"{100 * beta * w / 2:.2f}",
            f"{100 * zeta:.2f}",
        )
    if configured.ratios is None and configured.alpha is None and configured.beta is None:
        origin = "no [damping] in the file: undamped"
    elif configured.ratios is None:
        origin = "from the file"
    else:
        targets = ", ".join(f"{100 * r:g} %" for r in configured.ratios)
        origin = (
            f"set for ratios {targets} at modes {configured.modes[0]} and {configured.modes[1]}"
        )
    head = Text(f"α = {alpha:.4g} 1/s, β = {beta:.4g} s ({origin})\nζ = α/(2ω) + βω/2")
    title = "Rayleigh damping [C] = α[I] + β[K]"
    return ReportSection("damping", title, data, Group(head, table))
