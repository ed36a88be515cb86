"""The ``[well]`` table: reading, defaults, the string's placement and every error."""

from __future__ import annotations

import textwrap

import pytest

from torsio.config.reading import load_config, parse_config_text
from torsio.errors import ConfigError

STRING = """
[[section]]
kind = "drill_pipe"
od = 0.127
id = 0.1086
length = 1500.0
[[section]]
kind = "bit"
od = 0.2159
id = 0.05
length = 0.3
"""

WELL = """
[well]
mud_density = 1200.0
md = [0.0, 1000.0, 1600.0]
inclination = [0.0, 0.0, 60.0]
azimuth = [0.0, 0.0, 30.0]
"""


def config(well: str = WELL, string: str = STRING):
    return parse_config_text(textwrap.dedent(string + well), source="<test>")


def test_well_is_read_and_the_string_placed():
    well = config().well
    assert well is not None
    assert well.mud_density == 1200.0 and well.survey.depth == 1600.0
    # defaults of DESIGN.md's [well] table
    assert (well.friction_static, well.friction_dynamic) == (0.3, 0.25)
    assert well.normal_force == "soft-string" and well.hole == ()


def test_no_well_is_none():
    assert config(well="").well is None


def test_hole_sections_and_units():
    well = config(
        WELL.replace("mud_density = 1200.0", 'mud_density = "1.2 g/cm^3"')
        + """
friction_static = 0.35
friction_dynamic = 0.3
threshold_speed = "5 rpm"
normal_force = "gravity"
[[well.hole]]
to_md = "3000 ft"
friction_static = 0.2
friction_dynamic = 0.15
name = "casing"
[[well.hole]]
to_md = 1300
friction_dynamic = 0.28
"""
    ).well
    assert well is not None
    assert well.mud_density == pytest.approx(1200.0, rel=1e-15)
    assert well.threshold_speed == pytest.approx(5 * 3.141592653589793 / 30, rel=1e-15)
    assert well.hole[0].to_md == pytest.approx(914.4, rel=1e-15)  # 3000 ft, exact
    assert well.friction_dynamic_at([100.0, 1000.0, 1500.0]).tolist() == [0.15, 0.28, 0.3]
    assert well.friction_static_at([100.0, 1000.0, 1500.0]).tolist() == [0.2, 0.35, 0.35]


def test_survey_file_relative_to_the_configuration(tmp_path):
    (tmp_path / "data").mkdir()
    (tmp_path / "data" / "s.csv").write_text(
        "md,inclination,azimuth\n0,0,0\n1000,0,0\n1600,60,30\n", "utf-8"
    )
    path = tmp_path / "c.toml"
    path.write_text(STRING + '[well]\nsurvey = "data/s.csv"\n', "utf-8")
    well = load_config(path).well
    assert well is not None and well.survey.depth == 1600.0


@pytest.mark.parametrize(
    ("well", "key", "text"),
    [
        (
            "[well]\nmd=[0, 1400]\ninclination=[0, 0]\nazimuth=[0, 0]\n",
            "well.md",
            "the string is 1500.3 m long but the survey ends at md 1400 m",
        ),  # fmt: skip
        (WELL + "frction = 0.2\n", "well.frction", "unknown key; expected one of azimuth"),
        (
            WELL + "friction_static = 0.2\nfriction_dynamic = 0.3\n",
            "well.friction_dynamic",
            "<= the static one (0.2), got 0.3",
        ),  # fmt: skip
        (WELL + "friction_dynamic = -0.1\n", "well.friction_dynamic", "non-negative"),
        (WELL + 'normal_force = "stiff"\n', "well.normal_force", "expected one of soft-string"),
        (WELL.replace("1200.0", '"12 s"'), "well.mud_density", "is not a density"),
        (
            WELL.replace("[0.0, 0.0, 60.0]", "[0.0, 0.0, 190.0]"),
            "well.inclination[2]",
            "from 0 to 180 degrees, got 190",
        ),  # fmt: skip
        (  # a string that is not a number: the key once, not well.well.inclination[2]
            WELL.replace("[0.0, 0.0, 60.0]", '[0.0, 0.0, "sixty"]'),
            "well.inclination[2]",
            "expected a number of degrees, got 'sixty'",
        ),  # fmt: skip
        (WELL.replace("[0.0, 0.0, 30.0]", '[0.0, "x", 30.0]'), "well.azimuth[1]", "'x'"),
        (
            WELL.replace("[0.0, 1000.0, 1600.0]", "[0.0, 1700.0, 1600.0]"),
            "well.md[2]",
            "out of order: 1600 m after 1700 m",
        ),  # fmt: skip
        (WELL.replace("[0.0, 0.0, 30.0]", "[0.0, 30.0]"), "well.azimuth", "got 3, 3 and 2"),
        (WELL.replace("azimuth = [0.0, 0.0, 30.0]", ""), "well.azimuth", "missing"),
        (WELL + 'survey = "s.csv"\n', "well.md", "the survey is given twice"),
        ("[well]\nmud_density = 1000\n", "well", "no survey"),
        ('[well]\nsurvey = "missing.csv"\n', "well.survey", "cannot read survey file"),
        (
            WELL + "[[well.hole]]\nto_md = 1200\n[[well.hole]]\nto_md = 1100\n",
            "well.hole[1].to_md",
            "expected a measured depth below 1200 m",
        ),  # fmt: skip
        (WELL + "[[well.hole]]\nto_md = 1700\n", "well.hole[0].to_md", "below the survey's last"),
        (WELL + "[[well.hole]]\nfriction_static = 0.1\n", "well.hole[0].to_md", "missing"),
        (
            WELL + "[[well.hole]]\nto_md = 900\nfriction_static = 0.1\n",
            "well.hole[0].friction_dynamic",
            "<= the static one (0.1), got 0.25",
        ),  # fmt: skip
        (WELL + "[[well.hole]]\nto_md = 900\nmu = 0.1\n", "well.hole[0].mu", "unknown key"),
    ],
)
def test_errors_name_the_key(well, key, text):
    with pytest.raises(ConfigError) as info:
        config(well=well)
    assert info.value.key == key
    assert text in info.value.message


def test_well_with_a_chain_is_an_error():
    text = "[chain]\ninertias = [1.0]\nstiffnesses = [1.0]\n" + WELL
    with pytest.raises(ConfigError, match="well: \\[well\\] needs a drill-string"):
        parse_config_text(text)
