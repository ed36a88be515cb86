"""The survey and its minimum-curvature trajectory: a published worked example, a peer
library, closed forms along the arc, and the errors of bad surveys."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsio.errors import ConfigError
from torsio.well.survey import Survey
from torsio.well.survey_csv import read_survey_csv

FT = 0.3048  # m, exact

# The 3-D S-shaped survey of src/torsio/data/deviated_well.toml
MD = [0.0, 500.0, 800.0, 1100.0, 1700.0, 2000.0, 2300.0, 2500.0]
INC = [0.0, 0.0, 15.0, 35.0, 35.0, 25.0, 20.0, 20.0]
AZI = [0.0, 0.0, 20.0, 45.0, 45.0, 60.0, 60.0, 60.0]

# wellpathpy 0.5.2 (Zabamund/wellpathpy, LGPL), mincurve.minimum_curvature(MD, INC, AZI),
# run in a throw-away virtualenv; printed with 17 digits: tvd, northing, easting, dls (deg/30 m)
WELLPATHPY_TVD = [0.0, 500.0, 796.5847788396107, 1067.751490134451, 1559.242716707846,
                  1819.0821110455283, 2096.1580323581425, 2284.096556515324]  # fmt: skip
WELLPATHPY_NORTH = [0.0, 0.0, 36.69135730000789, 135.24744271546967, 378.595315319053,
                    471.49347501987216, 528.8777772272248, 563.0797915597916]  # fmt: skip
WELLPATHPY_EAST = [0.0, 0.0, 13.354561912028803, 88.41222549886328, 331.7600981024466,
                   447.9530923232369, 547.3456193032584, 606.5852458484632]  # fmt: skip
WELLPATHPY_DLS = [0.0, 0.0, 1.5, 2.221315983053111, 0.0, 1.2433105506910376,
                  0.5000000000000003, 0.0]  # fmt: skip


def test_published_worked_example_lyons():
    # Lyons, Carter & Lapeyrouse, "Formulas and Calculations for Drilling, Production and
    # Workover", 2nd ed. (Gulf Professional, 2002), directional survey calculations, the
    # minimum curvature method (also at drillingformulas.com/minimum-curvature-method):
    # 3500 ft, 15 deg, 20 deg to 3600 ft, 25 deg, 45 deg gives dogleg 0.22605 rad
    # (12.95 deg), North 27.22 ft, East 19.45 ft, TVD 94.01 ft. Tolerances are
    # half a unit of the last published digit.
    survey = Survey([0.0, 3500 * FT, 3600 * FT], [15.0, 15.0, 25.0], [20.0, 20.0, 45.0])
    beta = survey.station_doglegs[1]
    assert beta == pytest.approx(0.22605, abs=5e-6)
    assert math.degrees(beta) == pytest.approx(12.95, abs=5e-3)
    # the example prints RF = 1.00408, a misprint: (2 / 0.22605) tan(0.22605 / 2) = 1.00428,
    # and its North, East and TVD follow from 1.00428 (with 1.00408 the TVD would be 93.99 ft)
    assert 2.0 / beta * math.tan(beta / 2.0) == pytest.approx(1.00428, abs=5e-6)
    north, east, tvd = (survey.station_positions[2] - survey.station_positions[1]) / FT
    assert north == pytest.approx(27.22, abs=5e-3)
    assert east == pytest.approx(19.45, abs=5e-3)
    assert tvd == pytest.approx(94.01, abs=5e-3)


def test_against_wellpathpy_recorded():
    # wellpathpy 0.5.2 numbers recorded above: the same method, so agreement to round-off
    survey = Survey(MD, INC, AZI)
    north, east, tvd = survey.station_positions.T
    np.testing.assert_allclose(tvd, WELLPATHPY_TVD, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(north, WELLPATHPY_NORTH, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(east, WELLPATHPY_EAST, rtol=1e-12, atol=1e-9)
    dls = np.degrees(survey.dogleg_severity(np.array(MD[:-1]))) * 30.0
    np.testing.assert_allclose(dls, WELLPATHPY_DLS[1:], rtol=1e-12, atol=1e-12)


def test_against_wellpathpy_live():
    # the same comparison with wellpathpy itself, where it is installed (not a dependency)
    mincurve = pytest.importorskip("wellpathpy.mincurve")
    tvd, north, east, _ = mincurve.minimum_curvature(np.array(MD), np.array(INC), np.array(AZI))
    np.testing.assert_allclose(Survey(MD, INC, AZI).station_positions, np.c_[north, east, tvd],
                               rtol=1e-12, atol=1e-9)  # fmt: skip


def test_circular_build_along_the_arc():
    # closed form of a circular arc in the vertical plane of azimuth 90 deg: radius
    # R = L / beta, east = R (1 - cos a), tvd = kop + R sin a at the inclination a reached
    survey = Survey([0.0, 500.0, 800.0], [0.0, 0.0, 30.0], [90.0, 90.0, 90.0])
    radius = 300.0 / math.radians(30.0)
    md = np.linspace(500.0, 800.0, 7)
    a = (md - 500.0) / radius
    np.testing.assert_allclose(
        survey.position(md), np.c_[0 * md, radius * (1 - np.cos(a)), 500 + radius * np.sin(a)],
        rtol=1e-12, atol=1e-9,
    )  # fmt: skip
    np.testing.assert_allclose(survey.inclination(md), a, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(survey.dogleg_severity(md), 1.0 / radius, rtol=1e-12)
    np.testing.assert_allclose(survey.build_rate(md), 1.0 / radius, rtol=1e-12)
    np.testing.assert_allclose(survey.turn_rate(md[1:]), 0.0, atol=1e-15)
    # the curvature vector points to the centre of the arc: up and back (the high side)
    np.testing.assert_allclose(
        survey.curvature(650.0), np.array([0.0, math.cos(a[3]), -math.sin(a[3])]) / radius,
        rtol=1e-12, atol=1e-18,
    )  # fmt: skip


def test_tangent_and_curvature_are_derivatives():
    # dp/ds = t and dt/ds = curvature along a 3-D arc (central differences, error h^2)
    survey = Survey(MD, INC, AZI)
    h = 1e-3
    for md in (650.0, 900.0, 1850.0, 2150.0):
        dp = (survey.position(md + h) - survey.position(md - h)) / (2 * h)
        dt = (survey.tangent(md + h) - survey.tangent(md - h)) / (2 * h)
        np.testing.assert_allclose(dp, survey.tangent(md), atol=1e-9)
        np.testing.assert_allclose(dt, survey.curvature(md), atol=1e-10)
        assert np.linalg.norm(survey.tangent(md)) == pytest.approx(1.0, abs=1e-15)


def test_turn_rate_of_a_horizontal_turn():
    # a horizontal hole turning at constant rate: d azi/ds = delta azi / L, no build
    survey = Survey([0.0, 100.0, 400.0], [90.0, 90.0, 90.0], [0.0, 0.0, 30.0])
    assert survey.turn_rate(250.0) == pytest.approx(math.radians(30.0) / 300.0, rel=1e-12)
    assert survey.build_rate(250.0) == pytest.approx(0.0, abs=1e-15)
    assert math.degrees(survey.azimuth(250.0)) == pytest.approx(15.0, rel=1e-12)


@pytest.mark.parametrize(
    ("md", "inc", "azi", "key", "text"),
    [
        ([0, 800, 500], [0, 0, 0], [0, 0, 0], "md[2]", "stations out of order: 500 m after 800"),
        ([0, 800, 800], [0, 0, 0], [0, 0, 0], "md[2]", "strictly increasing"),
        ([0, 800], [0, 181], [0, 0], "inclination[1]", "from 0 to 180 degrees, got 181"),
        ([0, 800], [0, -1], [0, 0], "inclination[1]", "got -1"),
        ([0, 800], [0, 10], [0, math.inf], "azimuth[1]", "finite number, got inf"),
        ([0, 800], [0, 10, 20], [0, 0], "inclination", "got 2, 3 and 2 values"),
        ([100, 800], [0, 10], [0, 0], "md[0]", "md 0"),
        ([0], [0], [0], "md", "at least two"),
        ([0, 800], [0, "ten"], [0, 0], "inclination[1]", "expected a number, got 'ten'"),
        ([0, 100], [0, 180], [0, 0], "inclination[1]", "opposite directions"),
    ],
)
def test_bad_surveys_are_errors_naming_the_station(md, inc, azi, key, text):
    with pytest.raises(ConfigError) as info:
        Survey(md, inc, azi)
    assert info.value.key == key
    assert text in info.value.message


def test_outside_the_survey_is_an_error():
    with pytest.raises(ConfigError, match="2600 m is outside the survey"):
        Survey(MD, INC, AZI).tangent(2600.0)


def test_csv_survey(tmp_path):
    path = tmp_path / "s.csv"
    rows = "\n".join(f"{m},{i},{a},9.9" for m, i, a in zip(MD, INC, AZI, strict=True))
    path.write_text("# exported\nMD, Inclination ,azimuth,tvd\n" + rows + "\n\n", "utf-8")
    survey = read_survey_csv(path)
    np.testing.assert_array_equal(survey.md, MD)
    np.testing.assert_array_equal(survey.azimuth_deg, AZI)


FT = 0.3048
"""1 ft in m, exactly (NIST SP 811, appendix B.8)."""


@pytest.mark.parametrize(
    "header",
    ["md [ft],inclination,azimuth", "MD (ft),Inc (deg),Azi (deg)", "md[ft],Incl,Azim",
     "Measured Depth (ft),Inclination [deg],AZIMUTH", "Azi,md (FT),inc (°)"],
)  # fmt: skip
def test_csv_survey_in_feet_with_unit_headers(tmp_path, header):
    """The same stations in ft (md / 0.3048) read back as the metric survey."""
    order = [c.strip().split()[0].split("[")[0].lower()[:2] for c in header.split(",")]
    feet = [m / FT for m in MD]
    values = {"md": feet, "me": feet, "in": INC, "az": AZI}
    rows = "\n".join(",".join(repr(values[c][k]) for c in order) for k in range(len(MD)))
    path = tmp_path / "ft.csv"
    path.write_text(header + "\n" + rows + "\n", "utf-8")
    survey = read_survey_csv(path)
    np.testing.assert_allclose(survey.md, MD, rtol=1e-15, atol=1e-12)
    np.testing.assert_array_equal(survey.inclination_deg, INC)
    np.testing.assert_array_equal(survey.azimuth_deg, AZI)


def test_csv_survey_in_radians(tmp_path):
    """pi rad = 180 deg (definition of the radian)."""
    path = tmp_path / "rad.csv"
    rows = "\n".join(
        f"{m},{float(np.radians(i))!r},{float(np.radians(a))!r}"
        for m, i, a in zip(MD, INC, AZI, strict=True)
    )
    path.write_text("md (m),inc (rad),azi (rad)\n" + rows + "\n", "utf-8")
    survey = read_survey_csv(path)
    np.testing.assert_allclose(survey.inclination_deg, INC, rtol=1e-14, atol=1e-12)
    np.testing.assert_allclose(survey.azimuth_deg, AZI, rtol=1e-14, atol=1e-12)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            "md,dip,azimuth\n0,0,0\n",
            "s.csv, line 1: the header 'md,dip,azimuth' has no column 'inclination'",
        ),  # fmt: skip
        ("md [yd],inc,azi\n0,0,0\n", "line 1: column 'md [yd]': unknown unit 'yd'; expected"),
        ("md,MD (ft),inc,azi\n0,0,0,0\n", "line 1: column md is given twice"),
        (
            "md,inclination,azimuth\n0,0,0\n10,5\n",
            "s.csv, line 3: 2 fields, no value for column azimuth",
        ),  # fmt: skip
        (
            "md,inclination,azimuth\n0,0,0\n10,x,0\n",
            "line 3: column inclination: 'x' is not a number",
        ),  # fmt: skip
        ("md,inclination,azimuth\n0,0,0\n10,5,nan\n", "line 3: column azimuth: expected a finite"),
        (
            "md,inclination,azimuth\n0,0,0\n900,5,0\n800,5,0\n",
            "s.csv, line 4: column md: stations out of order: 800 m after 900 m",
        ),  # fmt: skip
        (
            "md,inclination,azimuth\n0,0,0\n900,200,0\n",
            "line 3: column inclination: expected an inclination from 0 to 180 degrees, got 200",
        ),  # fmt: skip
        ("", "the file is empty"),
    ],
)
def test_bad_csv_lines_are_errors_naming_file_and_line(tmp_path, text, message):
    path = tmp_path / "s.csv"
    path.write_text(text, "utf-8")
    with pytest.raises(ConfigError) as info:
        read_survey_csv(path, key="well.survey")
    assert info.value.key == "well.survey"
    assert message in info.value.message


def test_missing_csv_file(tmp_path):
    with pytest.raises(ConfigError, match="cannot read survey file"):
        read_survey_csv(tmp_path / "none.csv")
