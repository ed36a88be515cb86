"""``torsio report`` computes each analysis once from one System.

Counted through the command-line entry point with every output at once (terminal-free
JSON and the HTML page, whose figures reuse the report's analyses): spies on the
discretizers' ``discretize``, on the bit-rock law's construction, on the eigen-solve of
the modal analysis (``scipy.linalg.eigh`` and ``eigh_tridiagonal``, wherever called), on
the transient ``simulate`` and on ``severity_map``. Expected counts: one of each, plus
the one severity map the HTML page draws over its own grid (``MAP_GRID``).
"""

from __future__ import annotations

import collections
import functools
import json

import pytest
import scipy.linalg

import torsio.analysis.maps
import torsio.analysis.transient
from torsio.cli import main
from torsio.physics.laws import BitRockLaw
from torsio.plugins import discretizers
from torsio.report.html import MAP_GRID, have_matplotlib


def _spy(monkeypatch, calls, owner, name, key):
    original = getattr(owner, name)

    @functools.wraps(original)
    def counted(*args, **kwargs):
        calls[key].append((args, kwargs))
        return original(*args, **kwargs)

    monkeypatch.setattr(owner, name, counted)


@pytest.fixture
def calls(monkeypatch):
    counts: dict[str, list] = collections.defaultdict(list)
    for cls in set(discretizers().values()):
        for klass in cls.__mro__:  # the class that defines discretize, once
            if "discretize" in vars(klass):
                if not getattr(vars(klass)["discretize"], "__wrapped__", None):
                    _spy(monkeypatch, counts, klass, "discretize", "discretize")
                break
    _spy(monkeypatch, counts, BitRockLaw, "__init__", "law")
    _spy(monkeypatch, counts, scipy.linalg, "eigh", "eigen-solve")
    _spy(monkeypatch, counts, scipy.linalg, "eigh_tridiagonal", "eigen-solve")
    _spy(monkeypatch, counts, torsio.analysis.transient, "simulate", "simulate")
    _spy(monkeypatch, counts, torsio.analysis.maps, "severity_map", "severity_map")
    return counts


@pytest.mark.parametrize("strategy", ["A", "C"])
def test_report_computes_each_analysis_once(calls, tmp_path, capsys, strategy):
    page = tmp_path / "report.html"
    assert main(["report", "--strategy", strategy, "--json", "--html", str(page)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert {"modes", "dimensionless", "response", "critical"} <= set(data)  # all analyses ran
    assert len(calls["discretize"]) == 1
    assert len(calls["law"]) == 1
    assert len(calls["eigen-solve"]) == 1  # the modal analysis; omega_1 everywhere else
    assert len(calls["simulate"]) == 1
    grids = [len(kwargs["rpm"]) for _, kwargs in calls["severity_map"]]
    expected = [1, MAP_GRID[1][2]] if have_matplotlib() else [1]  # critical row, HTML map
    assert grids == expected


def test_each_output_reuses_the_sections(calls, capsys):
    # terminal and JSON of one context: the sections are computed once, not per output
    from rich.console import Console

    from torsio.examples import builtin_config
    from torsio.report.context import ReportContext
    from torsio.report.document import render, report_data

    ctx = ReportContext(builtin_config(), strategy="A")
    first = report_data(ctx)
    render(ctx, Console(file=None, width=100, record=True))
    assert report_data(ctx) == first
    assert len(calls["severity_map"]) == 1 and len(calls["simulate"]) == 1
