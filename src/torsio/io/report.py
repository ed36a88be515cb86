"""The report of one configuration: the whole picture, for people (rich) and programs (JSON).

A report is a list of sections. Each section is one function of a
:class:`ReportContext` (the configuration and what has been computed from it,
computed once and shared) that returns a :class:`ReportSection`: a JSON key,
a title, plain data for ``--json`` and a rich renderable for the terminal,
built from the same numbers. To add a section, write one such function and
append it to :data:`SECTIONS`; :func:`report_data` and :func:`render` pick it up.

Sections now: the drill-string, its discretization, the first modes against
the exact continuum, the Rayleigh damping ratios of those modes, the operating
point, the dimensionless groups, the response there (S_SS, stick fraction) and
its distance to the critical weight on bit.

Examples
--------
>>> from torsio.io.config import builtin_config
>>> data = report_data(builtin_config(), modes=3)
>>> list(data)
['name', 'source', 'string', 'discretization', 'modes', 'damping', 'operation',
 'dimensionless', 'response', 'critical']
>>> data["discretization"]["strategy"], data["discretization"]["dofs"]
('C', 5)
>>> [round(f, 4) for f in data["modes"]["continuum_hz"]]  # rigid-BHA continuum, strategy C
[0.131, 0.421, 0.7434]
>>> import json
>>> len(json.dumps(data)) > 0  # plain data all the way down
True

The terminal layout fits 80 columns:

>>> import io
>>> from rich.console import Console
>>> console = Console(width=80, record=True, file=io.StringIO())
>>> render(builtin_config(), console)
>>> max(len(line.rstrip()) for line in console.export_text().splitlines()) <= 80
True
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterator
from typing import Any

import attrs
import numpy as np
from rich import box
from rich.console import Console, ConsoleOptions, Group, RenderableType, RenderResult
from rich.table import Table
from rich.text import Text

from torsio.errors import ConfigError
from torsio.io.config import Config
from torsio.model.continuum import ContinuumModes, continuum_modes
from torsio.model.drillstring import DrillString
from torsio.model.lumped import LumpedModel
from torsio.model.modal import ModalComparison, ModalResults, modal_analysis
from torsio.physics.damping import ModelDamping, RayleighDamping
from torsio.physics.system import System

__all__ = [
    "SECTIONS",
    "ReportContext",
    "ReportSection",
    "damping_section",
    "discretization_section",
    "modes_section",
    "modes_table",
    "operation_section",
    "render",
    "report_data",
    "report_sections",
    "string_section",
    "string_table",
]

DEFAULT_MODES = 5
"""Modes shown by default (fewer if the model has fewer degrees of freedom)."""

WIDE = 100
"""Console width [columns] from which tables use their wide layout."""


class ReportContext:
    """A configuration and what the report computes from it, each computed once on demand.

    Parameters
    ----------
    config : Config
        The validated configuration.
    strategy : str, optional
        Discretizer name overriding the file's ``[discretization] strategy``.
    dp_elements, bha_elements : int, optional
        Element counts overriding the file's (see :mod:`torsio.model.discretize`).
    modes : int
        How many modes to show (at most the model's degrees of freedom).
    """

    def __init__(
        self,
        config: Config,
        *,
        strategy: str | None = None,
        dp_elements: int | None = None,
        bha_elements: int | None = None,
        modes: int = DEFAULT_MODES,
    ) -> None:
        if isinstance(modes, bool) or not isinstance(modes, int) or modes < 1:
            raise ConfigError("modes", f"expected a whole number of modes >= 1, got {modes!r}")
        self.config = config
        self.overrides: dict[str, Any] = {
            "strategy": strategy,
            "dp_elements": dp_elements,
            "bha_elements": bha_elements,
        }
        self.requested_modes = modes

    @functools.cached_property
    def system(self) -> System | None:
        """The System of the configuration (model, damping, bit-rock law, operating point).

        None when the configuration has no ``[bit_rock]`` table (modal analyses only).
        """
        if self.config.bit_rock is None:
            return None
        return System.from_config(self.config, **self.overrides)

    @functools.cached_property
    def model(self) -> LumpedModel:
        """The discretized string."""
        if self.system is not None:
            return self.system.model
        return self.config.model(**self.overrides)

    @functools.cached_property
    def damping(self) -> RayleighDamping | ModelDamping:
        """The damping of the model, as :meth:`System.from_config` sets it."""
        if self.system is not None:
            return self.system.damping
        d = self.config.damping
        if d.ratios is not None:
            return RayleighDamping.from_modal_ratios(self.model, d.ratios, d.modes)
        return RayleighDamping(d.alpha or 0.0, d.beta or 0.0)

    @functools.cached_property
    def modal(self) -> ModalResults:
        """The first modes of the model."""
        count = min(self.requested_modes, self.model.dofs)
        return modal_analysis(self.model, count, string=self.config.string)

    @functools.cached_property
    def transient(self) -> Any:
        """The transient response at the operating point (None without law or operating point)."""
        op = self.config.operation
        if self.system is None or op.wob is None or op.rpm is None:
            return None
        from torsio.analysis.transient import simulate_config

        discretization = {k: v for k, v in self.overrides.items() if v is not None}
        return simulate_config(self.config, discretization=discretization)

    @functools.cached_property
    def comparison(self) -> ModalComparison:
        """The modes against the exact continuum (rigid BHA if the model keeps it rigid)."""
        return self.modal.compare()


@attrs.frozen
class ReportSection:
    """One part of the report: the same content as data and as a rich renderable.

    Attributes
    ----------
    key : str
        Key of the section in :func:`report_data`.
    title : str
        Heading in the terminal.
    data : dict
        JSON-ready plain data (numbers in SI units unless the key names another).
    body : rich renderable
        What the terminal shows under the title.
    """

    key: str
    title: str
    data: dict[str, Any]
    body: RenderableType

    def __rich__(self) -> RenderableType:
        return Group(Text(self.title, style="bold cyan"), self.body, Text(""))


class _ByWidth:
    """A renderable that picks a narrow or a wide layout from the console width."""

    def __init__(
        self,
        narrow: Callable[[], RenderableType],
        wide: Callable[[], RenderableType],
        min_wide: int = WIDE,
    ) -> None:
        self.narrow, self.wide, self.min_wide = narrow, wide, min_wide

    def __rich_console__(self, console: Console, options: ConsoleOptions) -> RenderResult:
        yield (self.wide if options.max_width >= self.min_wide else self.narrow)()


def _table(*columns: str, left: tuple[str, ...] = ()) -> Table:
    table = Table(
        box=box.SIMPLE_HEAD,
        pad_edge=False,
        show_edge=False,
        collapse_padding=True,
        header_style="bold",
    )
    for column in columns:  # Text: "[m]" in a header is a unit, not rich markup
        table.add_column(Text(column), justify="left" if column in left else "right")
    return table


def _mm(value: float) -> str:
    return f"{1000.0 * value:.4g}"


def _number(value: float, digits: int = 4, scientific: bool = False) -> str:
    """``value`` to ``digits`` significant digits, exponents written short (1.715e4)."""
    text = f"{value:.{digits - 1}e}" if scientific else f"{value:.{digits}g}"
    if "e" in text:
        mantissa, exponent = text.split("e")
        text = f"{mantissa}e{int(exponent)}"
    return text


# --- the drill-string ---------------------------------------------------------------------
def string_table(string: DrillString | Config, wide: bool = True) -> Table:
    """The drill-string as a table: geometry, J, inertia, stiffness, BHA membership.

    Parameters
    ----------
    string : DrillString or Config
        The string (or a configuration holding it).
    wide : bool
        ``False`` gives a layout that fits 80 columns (kind under the name,
        OD/ID in one column, units under the headers).

    Examples
    --------
    >>> from torsio import ritto2017_string
    >>> table = string_table(ritto2017_string(), wide=False)
    >>> table.row_count
    4
    """
    if isinstance(string, Config):
        string = string.string
    sections = string.sections
    if wide:
        table = _table(
            "#",
            "section",
            "kind",
            "OD\n[mm]",
            "ID\n[mm]",
            "length\n[m]",
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
            "OD/ID\n[mm]",
            "L\n[m]",
            "J\n[m⁴]",
            "I\n[kg m²]",
            "k\n[N m/rad]",
            "BHA",
            left=("section",),
        )
    for i, s in enumerate(sections):
        stiffness = "rigid" if s.kind == "bit" else _number(s.stiffness)
        numbers = [
            f"{s.length:.5g}",
            _number(s.polar_moment, scientific=True),
            f"{s.inertia:.5g}",
            stiffness,
            "yes" if s.in_bha else "no",
        ]
        if wide:
            table.add_row(str(i), Text(s.name or "-"), s.kind, _mm(s.od), _mm(s.id), *numbers)
        else:
            name = Text(s.name or s.kind)
            if s.name:
                name.append(f"\n{s.kind}", style="dim")
            table.add_row(str(i), name, f"{_mm(s.od)}/{_mm(s.id)}", *numbers)
    return table


def string_section(ctx: ReportContext) -> ReportSection:
    """The drill-string: one row per section, then the lumped totals of Eq. 5."""
    string = ctx.config.string
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
        f"bit bottom at {bottom:.6g} m",
        style="dim",
    )
    body = Group(
        _ByWidth(
            lambda: string_table(ctx.config, wide=False),
            lambda: string_table(ctx.config, wide=True),
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
    description = getattr(get_discretizer(model.strategy), "description", "")
    elements = dict(model.details.get("elements", {}))
    lengths = {s.name or s.kind: s.length for s in ctx.config.string.flexible_sections}
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

    Parameters
    ----------
    comparison : ModalComparison
        The modes against their reference continuum.
    flexible : ContinuumModes, optional
        When the reference keeps the BHA rigid: the continuum of the whole
        flexible string, shown in two more columns (the error of the model
        itself, not only of its discretization).
    """
    columns = ["mode", "lumped\n[Hz]", "continuum\n[Hz]", "error\n[%]"]
    if flexible is not None:
        columns = ["mode", "lumped\n[Hz]", "rigid BHA\n[Hz]", "error\n[%]"]
        columns += ["flexible\n[Hz]", "error\n[%]"]
    table = _table(*columns, "period\n[s]")
    for i, (mode, lumped, exact, error) in enumerate(comparison.rows()):
        cells = [str(mode), f"{lumped:.5f}", f"{exact:.5f}", f"{100 * error:+.3f}"]
        if flexible is not None:
            full = float(flexible.frequencies_hz[i])
            cells += [f"{full:.5f}", f"{100 * (lumped / full - 1):+.3f}"]
        table.add_row(*cells, f"{1.0 / lumped:.4g}")
    return table


def modes_section(ctx: ReportContext) -> ReportSection:
    """The first natural frequencies against the exact stepped-shaft continuum.

    The reference keeps the BHA rigid when the model does (strategies A and
    C); the continuum of the whole flexible string is then given as well.
    """
    comparison = ctx.comparison
    flexible = None
    if comparison.reference.rigid_bha:
        flexible = continuum_modes(ctx.config.string, comparison.count)
    full = flexible if flexible is not None else comparison.reference
    full_hz = full.frequencies_hz[: comparison.count]
    data = {
        "count": comparison.count,
        "frequencies_hz": comparison.frequencies_hz.tolist(),
        **comparison.to_dict(),
        "flexible_continuum_hz": full_hz.tolist(),
        "flexible_relative_error": (comparison.frequencies_hz / full_hz - 1.0).tolist(),
    }
    title = "Modes against the exact continuum"
    if flexible is None:
        title += " (flexible BHA)"
    body: RenderableType = modes_table(comparison, flexible)
    if flexible is not None:
        note = Text(
            "exact continuum with the BHA rigid (this strategy's limit) and flexible",
            style="dim",
        )
        body = Group(body, note)
    return ReportSection("modes", title, data, body)


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
    if configured.ratios is None:
        origin = "from the file"
    else:
        targets = ", ".join(f"{100 * r:g} %" for r in configured.ratios)
        origin = (
            f"set for ratios {targets} at modes {configured.modes[0]} and {configured.modes[1]}"
        )
    head = Text(f"α = {alpha:.4g} 1/s, β = {beta:.4g} s ({origin})\nζ = α/(2ω) + βω/2")
    title = "Rayleigh damping [C] = α[I] + β[K]"
    return ReportSection("damping", title, data, Group(head, table))


# --- operating point ----------------------------------------------------------------------
def operation_section(ctx: ReportContext) -> ReportSection:
    """Weight on bit, rotary speed, bit radius and the bit-rock law with its parameters."""
    op = ctx.config.operation
    radius = ctx.config.bit_radius
    law = None if ctx.config.bit_rock is None else ctx.config.bit_law()
    law_data: dict[str, Any] | None = None
    steady_torque = None
    if law is not None:
        law_data = {
            "name": str(getattr(law, "name", type(law).__name__)),
            "speed_unit": str(getattr(law, "speed_unit", "rad/s")),
            "given": dict(getattr(law, "given", {})),
            "parameters_rad_s": law.values() if hasattr(law, "values") else {},
        }
        if op.wob is not None and op.omega is not None:
            steady_torque = float(law.torque(op.omega, op.wob, radius))
    data = {
        "wob_n": op.wob,
        "rpm": op.rpm,
        "omega_rad_s": op.omega,
        "bit_radius_m": radius,
        "bit_rock_law": law_data,
        "bit_torque_steady_n_m": steady_torque,
    }
    table = Table.grid(padding=(0, 2))
    table.add_column(style="dim")
    table.add_column()
    wob = "not set" if op.wob is None else f"{op.wob / 1000:.4g} kN"
    rpm = "not set" if op.omega is None else f"{op.rpm:.4g} rpm (Ω = {op.omega:.4g} rad/s)"
    rows = [("weight on bit", wob), ("surface speed", rpm)]
    rows.append(("bit radius", f"{radius * 1000:.4g} mm"))
    if law_data is None:
        rows.append(("bit-rock law", "none: no [bit_rock] table (modal analyses only)"))
    else:
        given = ", ".join(f"{k} = {v:g}" for k, v in law_data["given"].items())
        unit = law_data["speed_unit"]
        rows.append(("bit-rock law", f"{law_data['name']} ({given}; bit speed in {unit})"))
        values = law_data["parameters_rad_s"]
        if values and unit != "rad/s":
            rows.append(("in rad/s", ", ".join(f"{k} = {v:.4g}" for k, v in values.items())))
    if steady_torque is not None:
        rows.append(("torque on bit", f"{steady_torque:.5g} N m at steady rotation (bit at Ω)"))
    for label, value in rows:
        table.add_row(label, Text(value))
    return ReportSection("operation", "Operating point", data, table)


# --- dimensionless groups -------------------------------------------------------------------
def dimensionless_section(ctx: ReportContext) -> ReportSection | None:
    """k_eq, omega_1, I_eq, Pi_1, Pi_2 and Tucker-Wang b0..b3 (Eqs. 9-11, ERRATA 2 and 3)."""
    if ctx.system is None:
        return None
    from torsio.physics.dimensionless import dimensionless_groups

    groups = dimensionless_groups(ctx.system)
    data = groups.to_dict()
    table = Table.grid(padding=(0, 2))
    table.add_column(style="dim")
    table.add_column()
    rows = [
        ("k_eq = 1/[K⁻¹]_NN", f"{groups.k_eq:.5g} N m/rad (Eq. 9)"),
        ("ω₁", f"{groups.omega1:.5g} rad/s"),
        ("I_eq = k_eq/ω₁²", f"{groups.i_eq:.5g} kg m² (Eq. 10)"),
        ("Π₁ = Ω/ω₁", f"{groups.pi1:.5g}"),
        ("Π₂ = W_ob R_bit/k_eq", f"{groups.pi2:.5g}"),
    ]
    if groups.tucker_wang is not None:
        b = ", ".join(f"b{i} = {v:.4g}" for i, v in enumerate(groups.tucker_wang))
        rows.append(("Tucker-Wang", f"{b} (b2 = ω₁ a2)"))
    for label, value in rows:
        table.add_row(label, Text(value))
    return ReportSection("dimensionless", "Dimensionless groups (Eq. 11)", data, table)


# --- response at the operating point ------------------------------------------------------------
def response_section(ctx: ReportContext) -> ReportSection | None:
    """S_SS (Eq. 12) and the stick fraction of a start-up from rest at the operating point."""
    results = ctx.transient
    if results is None:
        return None
    start, end = results.window_start, results.duration
    solver = results.solver
    data = {
        "severity": results.severity,
        "stick_fraction": results.stick_fraction,
        "stick_threshold": results.stick_threshold,
        "steady_window_s": [start, end],
        "bit_speed_min_rad_s": float(results.bit_speed[results.window_mask].min()),
        "bit_speed_max_rad_s": float(results.bit_speed[results.window_mask].max()),
        "solver": {k: solver[k] for k in ("method", "rtol", "atol", "nfev") if k in solver},
    }
    from torsio.analysis.severity import SEVERE_THRESHOLD

    if results.severity > SEVERE_THRESHOLD:
        verdict = Text("severe stick-slip", style="bold red")
    elif results.severity > 1e-3:
        verdict = Text("torsional oscillation", style="yellow")
    else:
        verdict = Text("steady rotation", style="green")
    table = Table.grid(padding=(0, 2))
    table.add_column(style="dim")
    table.add_column()
    table.add_row("S_SS", Text.assemble(f"{results.severity:.4f}  ", verdict))
    table.add_row(
        "stick fraction",
        Text(
            f"{results.stick_fraction:.3f} of the window (bit below {results.stick_threshold:g} Ω)"
        ),
    )
    table.add_row(
        "bit speed",
        Text(f"{data['bit_speed_min_rad_s']:.4g} to {data['bit_speed_max_rad_s']:.4g} rad/s"),
    )
    table.add_row("window", Text(f"{start:.4g} to {end:.4g} s of a start-up from rest"))
    table.add_row(
        "integrator",
        Text(
            f"{solver.get('method')} (rtol {solver.get('rtol'):g}, "
            f"atol {solver.get('atol'):g}), {solver.get('nfev')} "
            "evaluations"
        ),
    )
    return ReportSection("response", "Response at the operating point (Eq. 12)", data, table)


# --- distance to the critical weight on bit -----------------------------------------------
CRITICAL_SEARCH = (0.25, 4.0, 9, 6)
"""Critical-WOB search of the report: (lowest, highest) weight on bit as multiples of the
operating one, grid points, bisection steps (final bracket 3.75/8/2^6 = 0.7 % of W_ob)."""


def critical_section(ctx: ReportContext) -> ReportSection | None:
    """Critical weight on bit at the operating speed, and the operating point's distance to it.

    One row of a severity map at the operating rpm (:func:`torsio.analysis.maps.severity_map`,
    every point started from rest) over :data:`CRITICAL_SEARCH`, bisected between grid
    points, with the linear stability limit of steady rotation at the same speed.
    """
    op = ctx.config.operation
    if ctx.system is None or op.wob is None or op.rpm is None or op.wob <= 0:
        return None
    from torsio.analysis.maps import severity_map

    low, high, points, refine = CRITICAL_SEARCH
    grid = np.linspace(low * op.wob, high * op.wob, points)
    row = severity_map(ctx.system, wob=grid, rpm=[op.rpm], refine=refine)
    critical = float(row.critical_wob[0])
    status = row.critical_status[0]
    linear = float(row.stability_wob[0])
    margin = critical - op.wob if np.isfinite(critical) else None
    data = {
        "rpm": op.rpm,
        "wob_n": op.wob,
        "critical_wob_n": critical if np.isfinite(critical) else None,
        "status": status,
        "margin_n": margin,
        "margin_fraction": None if margin is None else margin / op.wob,
        "search_wob_n": [float(grid[0]), float(grid[-1])],
        "bracket_n": [float(w) for w in row.critical_bracket[0]],
        "linear_stability_wob_n": linear if np.isfinite(linear) else None,
    }
    table = Table.grid(padding=(0, 2))
    table.add_column(style="dim")
    table.add_column()
    if status == "none":
        text = f"none up to {grid[-1] / 1e3:.4g} kN (no severe point in the search)"
    elif status == "below_range":
        text = f"at or below {grid[0] / 1e3:.4g} kN (severe over the whole search)"
    else:
        text = f"{critical / 1e3:.4g} kN (S_SS > 0.8 above it, from rest)"
    table.add_row(f"critical WOB at {op.rpm:.4g} rpm", Text(text))
    if margin is not None and status not in ("below_range",):
        side = "below" if margin > 0 else "above"
        style = "green" if margin > 0 else "bold red"
        table.add_row(
            "operating point",
            Text(f"{abs(margin) / 1e3:.4g} kN ({abs(margin) / op.wob:.0%}) {side} it", style=style),
        )
    if np.isfinite(linear):
        table.add_row(
            "linear stability", Text(f"steady rotation unstable above {linear / 1e3:.4g} kN")
        )
    return ReportSection("critical", "Distance to the critical weight on bit", data, table)


SECTIONS: list[Callable[[ReportContext], ReportSection | None]] = [
    string_section,
    discretization_section,
    modes_section,
    damping_section,
    operation_section,
    dimensionless_section,
    response_section,
    critical_section,
]
"""The sections of the report, in order; a function may return None to be left out."""


def report_sections(ctx: ReportContext) -> Iterator[ReportSection]:
    """The sections of the report of ``ctx``, in order."""
    for function in SECTIONS:
        section = function(ctx)
        if section is not None:
            yield section


def report_data(config: Config | ReportContext, **options: Any) -> dict[str, Any]:
    """The report as plain data (what ``torsio report --json`` prints).

    Parameters
    ----------
    config : Config
    **options
        ``strategy``, ``dp_elements``, ``bha_elements``, ``modes``: see
        :class:`ReportContext`.

    Returns
    -------
    dict
        ``name``, ``source`` and one key per section (``string``,
        ``discretization``, ``modes``, ``damping``, ``operation``, ...).
    """
    ctx = config if isinstance(config, ReportContext) else ReportContext(config, **options)
    config = ctx.config
    data: dict[str, Any] = {"name": config.name, "source": config.source}
    for section in report_sections(ctx):
        data[section.key] = section.data
    return data


def render(config: Config | ReportContext, console: Console | None = None, **options: Any) -> None:
    """Print the report of ``config`` on a rich console (a new one by default).

    ``options`` as for :func:`report_data`. A :class:`ReportContext` may be passed
    instead of a configuration, to reuse what it has already computed.
    """
    console = console or Console()
    ctx = config if isinstance(config, ReportContext) else ReportContext(config, **options)
    config = ctx.config
    sections = list(report_sections(ctx))  # compute everything before printing
    title = Text.assemble(("torsio report", "bold"), f" — {config.name or 'unnamed'}")
    console.print(title, Text(f"configuration: {config.source}", style="dim"), "", sep="\n")
    for section in sections:
        console.print(section)
