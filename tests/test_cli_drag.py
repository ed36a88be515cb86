"""``torsio drag``: the JSON contract of DESIGN.md, options, the table and the errors."""

from __future__ import annotations

import json
import math
import sys
from importlib import resources

import pytest

from torsio.cli import main
from torsio.examples import deviated_well_config
from torsio.well.torque_drag import torque_drag

CONTRACT = ("hookload_trip_out", "hookload_trip_in", "hookload_rotating",
            "surface_torque_rotating", "md", "tension_rotating", "torque_rotating")  # fmt: skip


def run_json(capsys, *argv: str) -> dict:
    assert main(["drag", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_json_contract_and_values(capsys):
    # keys: DESIGN.md, "More commands and keys"; values: the Python API on the same file
    data = run_json(capsys)
    assert set(CONTRACT) <= set(data)
    config = deviated_well_config()
    # [operation]: 80 kN, 100 rpm; on bottom the Tucker-Wang torque on bit there (Eq. 2)
    bit_torque = float(config.bit_law().torque(100 * math.pi / 30, 80e3, config.bit_radius))
    expected = torque_drag(config.well, config.string, wob=80e3, bit_torque=bit_torque).to_dict()
    for key in CONTRACT:
        assert data[key] == pytest.approx(expected[key], rel=1e-15)
    assert len(data["md"]) == len(data["tension_rotating"]) == len(data["torque_rotating"])
    assert data["md"][0] == 0.0 and data["md"][-1] == 2500.0
    assert data["tension_rotating"][0] == data["hookload_rotating"]
    assert data["hookload_trip_out"] > data["hookload_rotating"] > data["hookload_trip_in"]


def test_options_override(capsys, tmp_path):
    path = tmp_path / "well.toml"
    text = resources.files("torsio").joinpath("data/deviated_well.toml").read_text("utf-8")
    path.write_text(text, "utf-8")
    data = run_json(capsys, str(path), "--friction", "0", "--wob", "100 kN",
                    "--bit-torque", "6 kN*m")  # fmt: skip
    # no friction: every hookload is the rotating one, the surface torque the bit torque
    assert data["hookload_trip_out"] == pytest.approx(data["hookload_rotating"], rel=1e-12)
    assert data["hookload_trip_in"] == pytest.approx(data["hookload_rotating"], rel=1e-12)
    assert data["surface_torque_rotating"] == 0.0
    assert data["surface_torque_on_bottom"] == pytest.approx(6e3, rel=1e-12)
    assert data["wob"] == 100e3 and data["friction_override"] == 0.0


def test_table_and_plot(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    plot = tmp_path / "drag.png"
    assert main(["drag", "--plot", str(plot)]) == 0
    out = capsys.readouterr().out
    assert "tripping out" in out and "rotating on bottom" in out and "neutral point" in out
    assert plot.stat().st_size > 0


def test_no_well_is_an_error(capsys):
    path = str(resources.files("torsio").joinpath("data/ritto2017.toml"))
    assert main(["drag", path]) == 2
    err = capsys.readouterr().err
    assert "torsio drag: error: well:" in err and "has no [well] table" in err
    assert "add [well]" in err


@pytest.mark.parametrize(
    ("argv", "text"),
    [
        (["--friction", "-0.1"], "--friction: expected a friction factor from 0 to 1"),
        (["--wob", "-5 kN"], "--wob: expected a non-negative value"),
        (["--bit-torque", "5 kN"], "--bit-torque: '5 kN' is not a torque"),
    ],
)
def test_bad_options(capsys, argv, text):
    assert main(["drag", *argv]) == 2
    assert text in capsys.readouterr().err


def test_plot_without_matplotlib(tmp_path, monkeypatch, capsys):
    # --plot without matplotlib (as if not installed): a clear error before any work, exit 2
    for name in list(sys.modules):
        if name == "matplotlib" or name.startswith("matplotlib."):
            monkeypatch.setitem(sys.modules, name, None)
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    monkeypatch.chdir(tmp_path)
    assert main(["drag", "--plot", "x.png"]) == 2
    err = capsys.readouterr().err
    assert "--plot" in err and "torsio[plot]" in err and "Traceback" not in err
    assert not (tmp_path / "x.png").exists()


LBF = 4.4482216152605
"""1 lbf in N, exactly (NIST SP 811, appendix B.8); 1 ft = 0.3048 m exactly."""


def _row(out: str, label: str) -> list[str]:
    line = next(line for line in out.splitlines() if label in line)
    return [cell.strip() for cell in line.split("│") if cell.strip()]


def test_units_field_tables_give_ft_klbf_and_kft_lbf(capsys):
    """The table in field units is the SI JSON converted by the exact factors."""
    data = run_json(capsys)
    assert run_json(capsys, "--units", "field") == data  # JSON stays SI
    assert main(["drag", "--units", "field"]) == 0
    out = capsys.readouterr().out
    assert "hookload [klbf]" in out and "surface torque [kft·lbf]" in out
    assert _row(out, "tripping out")[1] == f"{data['hookload_trip_out'] / LBF / 1e3:.1f}"
    off_bottom = _row(out, "rotating off bottom")
    assert off_bottom[1] == f"{data['hookload_rotating'] / LBF / 1e3:.1f}"
    torque = data["surface_torque_rotating"] / (0.3048 * LBF) / 1e3
    assert off_bottom[2] == f"{torque:.2f}"
    assert f"bit at md {2500 / 0.3048:g} ft" in " ".join(out.split())  # the bit at md 2500 m
    assert "kN" not in out


def test_si_table_headers_carry_their_units(capsys):
    assert main(["drag"]) == 0
    out = capsys.readouterr().out
    assert "hookload [kN]" in out and "surface torque [kN m]" in out


def test_units_field_plot(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    from torsio.display_units import DisplayUnits

    config = deviated_well_config()
    results = torque_drag(config.well, config.string, wob=80e3)
    figure = results.plot(units=DisplayUnits("field"))
    axes = figure.axes
    assert axes[0].get_ylabel() == "measured depth [ft]"
    assert axes[0].get_xlabel() == "effective tension [klbf]"
    assert axes[1].get_xlabel() == "torque [kft·lbf]"
    line = axes[0].get_lines()[0]  # tripping out: tension at the top is the hookload
    assert line.get_xdata()[0] == pytest.approx(results.hookload_trip_out / LBF / 1e3, rel=1e-12)
    assert max(line.get_ydata()) == pytest.approx(2500 / 0.3048, rel=1e-12)
