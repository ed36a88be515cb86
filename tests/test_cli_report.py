"""``torsio report``: the built-in example, JSON sections, a modal-only configuration."""

from __future__ import annotations

import json

import pytest

from torsio.analysis.transient import simulate_config
from torsio.cli import main
from torsio.examples import builtin_config


def report_json(capsys, *argv: str) -> dict:
    assert main(["report", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_report_json_of_the_builtin_example(capsys):
    data = report_json(capsys)
    assert {
        "string",
        "discretization",
        "modes",
        "damping",
        "operation",
        "dimensionless",
        "response",
    } <= set(data)
    # Source: ERRATA 1 (I_BHA with the bit) and the paper's FEM value for the continuum
    assert data["string"]["bha_inertia_kg_m2"] == pytest.approx(233.78, abs=0.005)
    assert round(data["modes"]["flexible_continuum_hz"][0], 4) == 0.1307
    # the response is the transient analyzer's own at the file's operating point
    expected = simulate_config(builtin_config()).severity
    assert data["response"]["severity"] == pytest.approx(expected, abs=1e-12)
    # Pi_2 = W R / k_eq (ERRATA 3) with strategy C's k_eq = k_DP (rigid BHA)
    assert data["dimensionless"]["pi2"] == pytest.approx(100e3 * 0.108 / 324.857, rel=1e-4)


def test_report_terminal_output(capsys):
    assert main(["report", "--strategy", "A"]) == 0
    out = capsys.readouterr().out
    assert "Ritto et al. (2017)" in out and "S_SS" in out and "0.13438" in out


def test_report_bit_speed_in_rpm(capsys):
    """The response's bit speed is printed in rpm (1 rad/s = 30/pi rpm), as the rotary speed."""
    import math
    import re

    data = report_json(capsys, "--strategy", "A")["response"]
    assert main(["report", "--strategy", "A"]) == 0
    line = next(line for line in capsys.readouterr().out.splitlines() if "bit speed" in line)
    low, high = (data[f"bit_speed_{k}_rad_s"] * 30 / math.pi for k in ("min", "max"))
    assert re.search(rf"{low:.4g} to {high:.4g} rpm", line), line


def test_report_of_a_modal_only_configuration(tmp_path, capsys):
    path = tmp_path / "modal.toml"
    path.write_text(
        '[[section]]\nkind = "drill_pipe"\nod = "5 in"\nid = "4.276 in"\n'
        'length = "3000 m"\n[[section]]\nkind = "bit"\nod = "8.5 in"\nid = 0.05\n'
        'length = 0.3\n[discretization]\nstrategy = "B"\ndp_elements = 10\n'
    )
    data = report_json(capsys, str(path))
    assert "response" not in data and "dimensionless" not in data
    assert data["discretization"]["dofs"] == 10


def test_report_html_is_standalone_with_embedded_figures(tmp_path, capsys):
    path = tmp_path / "report.html"
    assert main(["report", "--strategy", "A", "--html", str(path)]) == 0
    assert "S_SS" in capsys.readouterr().out  # the terminal report is still printed
    page = path.read_text(encoding="utf-8")
    assert page.startswith("<!DOCTYPE html>")
    assert page.count("data:image/png;base64,") == 3  # mode shapes, severity map, transient
    assert "http://" not in page and "https://" not in page  # nothing fetched on opening
    assert "Dimensionless groups" in page and "0.13438" in page
    # version, date and the configuration as TOML text (the built-in file, HTML-escaped)
    import re

    from torsio import __version__

    assert f"torsio {__version__}, " in page
    assert re.search(r"\d{4}-\d\d-\d\d \d\d:\d\d UTC", page)
    assert "Configuration (TOML)" in page and "kind = &quot;drill_pipe&quot;" in page
    assert "overridden by strategy = A" in page
    assert "Severity map: S_SS over 9 rotary speeds x 9 weights on bit" in page


def test_report_html_unwritable_path_is_a_clear_error(capsys):
    assert main(["report", "--html", "/nonexistent/dir/report.html"]) == 2
    assert "--html" in capsys.readouterr().err


def test_report_critical_wob_is_bracketed_by_single_runs(capsys):
    # Source: the transient analyzer (LSODA), independent of the batch engine of the maps:
    # below the reported bracket the start-up from rest is not severe, above it it is.
    from torsio.analysis.severity import SEVERE_THRESHOLD

    critical = report_json(capsys)["critical"]
    low, high = critical["bracket_n"]
    assert low < critical["critical_wob_n"] < high and high - low < 0.01 * critical["wob_n"]
    system = builtin_config().system()
    from torsio.analysis.transient import simulate

    assert simulate(system.at(wob=low), method="LSODA", rtol=1e-8).severity < SEVERE_THRESHOLD
    assert simulate(system.at(wob=high), method="LSODA", rtol=1e-8).severity > SEVERE_THRESHOLD
    assert critical["margin_n"] == critical["critical_wob_n"] - 100e3
