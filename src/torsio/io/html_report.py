"""The report as one standalone HTML page, its plots embedded (``torsio report --html``).

The page holds the same sections as the terminal report (rendered by rich with
inline styles), followed by figures embedded as base64 PNG images: the first
mode shapes against the exact continuum and, when the configuration has a
bit-rock law and an operating point, the transient response there. Nothing is
fetched when the page is opened. Without matplotlib (it comes with the ``[plot]``
extra) the page has the report without figures and a note saying how to get them.

Examples
--------
>>> from torsio.io.config import builtin_config
>>> page = html_report(builtin_config(), strategy="A")
>>> page.startswith("<!DOCTYPE html>") and page.count("data:image/png;base64,") == 2
True
"""

from __future__ import annotations

import base64
import html
import io
from typing import Any

from rich.console import Console
from rich.text import Text

from torsio.io.config import Config
from torsio.io.report import ReportContext, report_sections

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
</style>
</head>
<body>
<h1>torsio report: {title}</h1>
<p>Configuration: <code>{source}</code></p>
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
    """The report's figures (matplotlib Figures, no pyplot state) with their captions."""
    from matplotlib.figure import Figure

    from torsio.io.plotting import plot_mode_shapes

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
    results = ctx.transient
    if results is not None:
        figure = Figure(figsize=(8.0, 7.0))
        results.plot(axes=figure.subplots(3, 1, sharex=True))
        figures.append(
            (
                figure,
                f"Start-up from rest at {results.system.wob / 1e3:.4g} kN, "
                f"{results.system.rpm:.4g} rpm: S_SS = "
                f"{results.severity:.3f} over the shaded steady window.",
            )
        )
    return figures


def html_report(config: Config | ReportContext, **options: Any) -> str:
    """The report of ``config`` as a standalone HTML page.

    ``options`` as for :func:`torsio.io.report.report_data` (``strategy``,
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
    return PAGE.format(
        title=html.escape(config.name or "unnamed"),
        source=html.escape(config.source),
        report=report,
        figures=figures,
    )
