"""``torsio report --units field`` (issue 37, item 6): the string, the well, the operating point
and the critical weight on bit in oilfield units, the JSON in SI whatever ``--units`` says.

Expected values: the SI numbers of the same report converted by the exact definitions
(NIST SP 811, appendix B.8): 1 in = 0.0254 m, 1 ft = 0.3048 m, 1 lbf = 4.4482216152605 N,
1 lb = 0.45359237 kg, 1 US gal = 3.785411784e-3 m^3.
"""

from __future__ import annotations

import json
from importlib import resources

import pytest

from torsio.cli import main

LBF, FOOT, INCH = 4.4482216152605, 0.3048, 0.0254
PPG = 0.45359237 / 3.785411784e-3  # kg/m^3 per lb/US gal


@pytest.fixture(scope="module")
def path() -> str:
    return str(resources.files("torsio").joinpath("data/deviated_well.toml"))


def _report(capsys, path: str, *argv: str) -> str:
    assert main(["report", path, "--modes", "1", *argv]) == 0
    return " ".join(capsys.readouterr().out.split())  # the lines as read, wraps removed


def test_field_units_in_the_report(capsys, path):
    assert main(["report", path, "--modes", "1", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    text = _report(capsys, path, "--units", "field")
    well, operation = data["well"], data["operation"]
    assert f"md {data['string']['bit_depth_m'] / FOOT:.6g} ft" in text  # 8202.1 ft
    assert f"{well['mud_density'] / PPG:.4g} ppg" in text  # 1200 kg/m^3: 10.01 ppg
    assert f"pick-up {well['hookload_trip_out'] / LBF / 1e3:.1f} klbf" in text
    torque = well["surface_torque_on_bottom"] / (FOOT * LBF) / 1e3
    assert f"on bottom {torque:.2f} kft·lbf" in text
    assert f"weight on bit {operation['wob_n'] / LBF / 1e3:.4g} klbf" in text  # 80 kN
    assert f"bit radius {operation['bit_radius_m'] / INCH:.4g} in" in text  # 4.25 in
    assert "[in]" in text and "[ft]" in text  # the string table's headers
    assert " kN" not in text and "[mm]" not in text


def test_json_stays_si_whatever_units_say(capsys, path):
    si = _report(capsys, path, "--json")
    field = _report(capsys, path, "--json", "--units", "field")
    assert json.loads(si) == json.loads(field)


def test_the_dogleg_and_the_axial_section_in_field_units(capsys, path):
    # the dogleg per 100 ft (30.48 m) from the report's own per-30 m figure
    assert main(["report", path, "--modes", "1", "--json"]) == 0
    per_30m = json.loads(capsys.readouterr().out)["well"]["max_dogleg_deg_per_30m"]
    assert f"dogleg up to {per_30m * 30.48 / 30.0:.2f}°/100 ft" in _report(
        capsys, path, "--units", "field"
    )
    rgd = str(resources.files("torsio").joinpath("data/rgd_deviated_well.toml"))
    assert main(["report", rgd, "--json"]) == 0
    axial = json.loads(capsys.readouterr().out)["axial"]
    text = _report(capsys, rgd, "--units", "field")
    assert f"operating point {axial['wob_n'] / LBF / 1e3:.4g} klbf" in text
    torque = axial["steady_state"]["bit_torque"] / (FOOT * LBF) / 1e3
    assert f"steady bit torque {torque:.4g} kft·lbf" in text
