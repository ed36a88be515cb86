"""The report of one configuration: the whole picture, for people (rich) and programs (JSON).

A report is a list of sections. Each section is one function of a
:class:`ReportContext` (the configuration and what has been computed from it,
computed once and shared) that returns a :class:`ReportSection`: a JSON key,
a title, plain data for ``--json`` and a rich renderable for the terminal,
built from the same numbers. To add a section, write one such function and
append it to :data:`SECTIONS`; :func:`report_data` and :func:`render` pick it up.

Sections now: the drill-string, the well (with a ``[well]``: survey, torque and drag,
break-off; :mod:`torsio.report.well`), its discretization, the first modes against
the exact continuum, the Rayleigh damping ratios of those modes, the operating
point, the top drive (gains, impedance at omega_1, reflection coefficient), the
dimensionless groups, the response there (S_SS, stick fraction) and its distance
to the critical weight on bit. For the distributed model (``strategy = "wave"``) the
discretization, modes and damping sections describe its grid, its exact continuum and
its distributed drag (:mod:`torsio.report.wave`), and a ``wave`` section follows the
response.

Examples
--------
>>> from torsio.examples import builtin_config
>>> data = report_data(builtin_config(), modes=3)
>>> list(data)
['name', 'source', 'string', 'discretization', 'modes', 'damping', 'operation',
 'top_drive', 'dimensionless', 'response', 'critical']
>>> data["discretization"]["strategy"], data["discretization"]["dofs"]
('C', 5)
>>> [round(f, 4) for f in data["modes"]["continuum_hz"]]  # the string as given
[0.1307, 0.4165, 0.7319]
>>> [round(f, 4) for f in data["modes"]["continuum_rigid_bha_hz"]]  # strategy C's limit
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

from collections.abc import Callable
from typing import Any

from rich.console import Console
from rich.text import Text

from torsio.config.configuration import Config
from torsio.report.context import ReportContext, ReportSection
from torsio.report.dynamics import (
    critical_section,
    dimensionless_section,
    operation_section,
    response_section,
)
from torsio.report.model import (
    damping_section,
    discretization_section,
    modes_section,
    string_section,
)
from torsio.report.top_drive import top_drive_section
from torsio.report.wave import (
    wave_damping_section,
    wave_discretization_section,
    wave_modes_section,
    wave_section,
)
from torsio.report.well import well_section

__all__ = ["SECTIONS", "WAVE_SECTIONS", "render", "report_data", "report_sections"]


SECTIONS: list[Callable[[ReportContext], ReportSection | None]] = [
    string_section,
    well_section,
    discretization_section,
    modes_section,
    damping_section,
    operation_section,
    top_drive_section,
    dimensionless_section,
    response_section,
    critical_section,
]
"""The sections of the report, in order; a function may return None to be left out."""


WAVE_SECTIONS: dict[Any, Callable[[ReportContext], ReportSection | None]] = {
    discretization_section: wave_discretization_section,
    modes_section: wave_modes_section,
    damping_section: wave_damping_section,
}
"""Sections the wave model replaces (same JSON keys); its own ``wave`` section follows
the response."""


def report_sections(ctx: ReportContext) -> list[ReportSection]:
    """The sections of the report of ``ctx``, in order, computed once per context.

    The modal analysis runs first: every later omega_1 of the model (run times, the
    dimensionless groups, the batch engine, a top drive's tuning) reads it. The wave
    model has no matrices: its sections describe the grid, its exact continuum and its
    distributed drag instead (:data:`WAVE_SECTIONS`).
    """
    if ctx.sections is None:
        functions = list(SECTIONS)
        if ctx.has_matrices:
            ctx.modal  # noqa: B018  (computed here, before anything that needs omega_1)
        else:
            functions = [WAVE_SECTIONS.get(function, function) for function in functions]
            functions.insert(functions.index(response_section) + 1, wave_section)
        sections = (function(ctx) for function in functions)
        ctx.sections = [section for section in sections if section is not None]
    return ctx.sections


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
