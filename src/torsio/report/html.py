"""The report as one standalone HTML page, its plots embedded (``torsio report --html``).

The page starts with the torsio version, the date (UTC) and the configuration as
TOML text; then the same sections as the terminal report (rendered by rich with
inline styles), followed by figures embedded as base64 PNG images: the first
mode shapes against the exact continuum and, when the configuration has a
bit-rock law and an operating point, the transient response there and a severity
map around it (:data:`MAP_GRID`). Nothing is fetched when the page is opened. Without
matplotlib (it comes with the ``[plot]`` extra) the page has the report without figures
and a note saying how to get them.

Examples
--------
>>> from torsio.examples import builtin_config
>>> page = html_report(builtin_config(), strategy="A")
>>> page.startswith("<!DOCTYPE html>") and page.count("data:image/png;base64,") == 3
True
>>> "[[section]]" in page and "Severity map" in page
True
"""

from __future__ import annotations

import base64
import html
import io
from datetime import UTC
from typing import Any

from rich.console import Console
from rich.text import Text

from torsio.config.configuration import Config
from torsio.report.context import ReportContext
from torsio.report.document import report_sections

PAGE = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>torsio report: {title}</title>
<style>
body {{ font-family: system-ui, sans-serif; margin: 2em auto; max-width: 70em;
       color: #222; background: #fff; }}
pre.report {{ font-family: ui-monospace, Menlo, Consolas, monospace; font-size: 13px;
             line-height: 1.3; background: #fafafa; padding: 1em; border: 1px solid #ddd;
             overflow-x: auto; }}
figure {{ margin: 1.5em 0; }}
figure img {{ max-width: 100%; border: 1px solid #ddd; }}
figcaption {{ color: #555; font-size: 0.9em; }}
p.note {{ color: #555; border-left: 3px solid #ccc; padding-left: 0.8em; }}
details pre {{ font-size: 13px; background: #fafafa; padding: 1em; border: 1px solid #ddd;
              overflow-x: auto; }}
</style>
</head>
<body>
<h1>torsio report: {title}</h1>
<p>torsio {version}, {date}. Configuration: <code>{source}</code>{overrides}</p>
{configuration}
<pre class="report">{report}</pre>
{figures}
</body>
</html>
"""


#: Shown in place of the figures when matplotlib is not installed.
NO_FIGURES_NOTE = (
    "Figures need matplotlib, which is not installed: "
    "pip install 'torsio[plot]' (or pip install matplotlib) and run the report again."
)


def have_matplotlib() -> bool:
    """Whether matplotlib can be imported (the ``[plot]`` extra), without importing it."""
    import importlib.util

    return importlib.util.find_spec("matplotlib") is not None


def _png(figure: Any) -> str:
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=90, bbox_inches="tight")
    return base64.b64encode(buffer.getvalue()).decode("ascii")


def _figure_html(figure: Any, caption: str) -> str:
    return (
        f'<figure><img alt="{html.escape(caption)}" src="data:image/png;base64,'
        f'{_png(figure)}"><figcaption>{html.escape(caption)}</figcaption></figure>'
    )


def report_figures(ctx: ReportContext) -> list[tuple[Any, str]]:
    """The report's figures (matplotlib Figures, no pyplot state) with their captions; for
    a configuration with axial dynamics (its section is a table) the operating window of
    :func:`torsio.advice.plot.report_figures`."""
    from matplotlib.figure import Figure

    if ctx.config.axial is not None:  # the operating window (torsio advise's, quick)
        from torsio.advice.plot import report_figures as window_figures

        return window_figures(ctx.config)

    from torsio.plotting import plot_mode_shapes

    figures = []
    modes = tuple(range(1, min(3, ctx.modal.frequencies_rad.size) + 1))
    figure = Figure(figsize=(6.0, 6.5))
    plot_mode_shapes(ctx.modal, modes, ax=figure.add_subplot())
    figures.append(
        (
            figure,
            f"Mode shapes {', '.join(map(str, modes))} of the "
            f"{ctx.model.dofs}-DOF model (markers) against the exact "
            "continuum (lines).",
        )
    )
    severity_map = map_figure(ctx)
    if severity_map is not None:
        figures.append(severity_map)
    results = ctx.transient
    if results is not None:
        figure = Figure(figsize=(8.0, 7.0))
        results.plot(ax=figure.subplots(3, 1, sharex=True))
        figures.append(
            (
                figure,
                f"Start-up from rest at {results.system.wob / 1e3:.4g} kN, "
                f"{results.rpm:.4g} rpm"
                + ("" if results.has_set_speed else " (mean top-drive speed)")
                + ": S_SS = "
                f"{results.severity:.3f} over the shaded steady window.",
            )
        )
    return figures


MAP_GRID = ((0.25, 2.25, 9), (0.4, 1.4, 9), 2)
"""Severity map of the HTML report: (weight on bit, rotary speed) ranges as multiples of the
operating point with their point counts, and bisection steps of the critical curve
(the paper's 25-225 kN x 40-140 rpm around 100 kN, 100 rpm)."""


def map_figure(ctx: ReportContext) -> tuple[Any, str] | None:
    """The severity map around the operating point, or None without a bit law or point.

    The grid is :data:`MAP_GRID`; every point starts from rest
    (:func:`torsio.analysis.maps.severity_map`). The operating point is marked.
    """
    system = ctx.system
    op = ctx.config.operation
    if system is None or op.wob is None or op.rpm is None or op.wob <= 0:
        return None
    import numpy as np
    from matplotlib.figure import Figure

    from torsio.analysis.maps import severity_map

    (w0, w1, wn), (r0, r1, rn), refine = MAP_GRID
    result = severity_map(
        system,
        wob=np.linspace(w0 * op.wob, w1 * op.wob, wn),
        rpm=np.linspace(r0 * op.rpm, r1 * op.rpm, rn),
        refine=refine,
    )
    figure = Figure(figsize=(7.0, 5.0), constrained_layout=True)
    ax = result.plot(ax=figure.add_subplot())
    ax.plot([op.rpm], [op.wob / 1e3], "r*", ms=14, mec="white", label="operating point")
    ax.legend(loc="upper left", fontsize=8, framealpha=0.8)
    info = result.info
    caption = (
        f"Severity map: S_SS over {rn} rotary speeds x {wn} weights on bit around the "
        f"operating point (star), each run from rest for {info['duration']:.4g} s, S_SS over "
        f"the last {info['steady_window']:.4g} s (rtol {info['rtol']:g}); the critical "
        f"weight on bit (S_SS > {result.threshold:g} above it) bisected {refine} times; "
        "triangles: critical weight on bit off the grid."
    )
    return figure, caption


def configuration_text(config: Config) -> str | None:
    """The TOML text of the configuration: its file, or the built-in example; None otherwise.

    The file is read again when the page is written.
    """
    from importlib import resources
    from pathlib import Path

    source = config.source
    if source.startswith("built-in "):
        name = source.removeprefix("built-in ")
        resource = resources.files("torsio").joinpath(f"data/{name}")
        return resource.read_text(encoding="utf-8") if resource.is_file() else None
    path = Path(source)
    try:
        return path.read_text(encoding="utf-8") if path.is_file() else None
    except OSError:
        return None


def html_report(config: Config | ReportContext, **options: Any) -> str:
    """The report of ``config`` as a standalone HTML page.

    ``options`` as for :func:`torsio.report.document.report_data` (``strategy``,
    ``dp_elements``, ``bha_elements``, ``modes``); a :class:`ReportContext` may be
    passed instead, to reuse what it has computed. Without matplotlib the page has
    no figures and says so (:data:`NO_FIGURES_NOTE`).
    """
    ctx = config if isinstance(config, ReportContext) else ReportContext(config, **options)
    config = ctx.config
    console = Console(record=True, width=110, file=io.StringIO(), color_system="truecolor")
    for section in report_sections(ctx):
        console.print(section)
    console.print(Text(""))
    report = console.export_html(inline_styles=True, code_format="{code}")
    if have_matplotlib():
        figures = "\n".join(
            _figure_html(figure, caption) for figure, caption in report_figures(ctx)
        )
    else:
        figures = f'<p class="note">{html.escape(NO_FIGURES_NOTE)}</p>'
    from datetime import datetime

    from torsio import __version__

    text = configuration_text(config)
    configuration = (
        "<p>(the configuration was given in Python: no TOML text)</p>"
        if text is None
        else "<details open><summary>Configuration (TOML)</summary>"
        f"<pre>{html.escape(text)}</pre></details>"
    )
    given = {k: v for k, v in ctx.overrides.items() if v is not None}
    overrides = (
        ", overridden by " + html.escape(", ".join(f"{k} = {v}" for k, v in given.items()))
        if given
        else ""
    )
    return PAGE.format(
        title=html.escape(config.name or "unnamed"),
        version=html.escape(__version__),
        date=datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"),
        source=html.escape(config.source),
        overrides=overrides,
        configuration=configuration,
        report=report,
        figures=figures,
    )
