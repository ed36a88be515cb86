"""Torque-and-drag plausibility (issue 36, case 10): inputs that cannot be physical are
refused naming the key; a string entirely in compression says so."""

from __future__ import annotations

import json
import math
import re
from importlib import resources

import attrs
import pytest

from torsio.cli import main
from torsio.errors import ConfigError
from torsio.examples import deviated_well_config
from torsio.well import Survey, Wellbore
from torsio.well.survey import MAX_DOGLEG_SEVERITY
from torsio.well.torque_drag import torque_drag


def _config(tmp_path, old: str, new: str) -> str:
    text = resources.files("torsio").joinpath("data/deviated_well.toml").read_text("utf-8")
    assert old in text
    path = tmp_path / "well.toml"
    path.write_text(text.replace(old, new, 1), "utf-8")
    return str(path)


def test_whole_string_in_compression_says_where_the_neutral_point_is(capsys):
    # rotating on bottom there is no axial friction: the hookload on bottom is the
    # off-bottom one less the weight on bit (701.1 kN - 800 kN < 0, DESIGN's drag table)
    assert main(["drag", "--wob", "800 kN", "--json"]) == 0
    captured = capsys.readouterr()
    data = json.loads(captured.out)
    assert data["hookload_on_bottom"] == pytest.approx(data["hookload_rotating"] - 800e3)
    assert data["hookload_on_bottom"] < 0.0 and data["all_in_compression"] is True
    assert data["neutral_point_md"] is None
    assert "whole string is in compression" in data["warnings"][0]
    assert "whole string is in compression" in captured.err
    assert main(["drag", "--wob", "800 kN"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "neutral point on bottom: above the top: the whole string is in compression" in out
    assert "none (no compression)" not in out


@pytest.mark.parametrize(
    ("old", "new", "key", "text"),
    [
        ("mud_density = 1200.0", "mud_density = 8000.0", "well.mud_density",
         "the string would float"),
        ("mud_density = 1200.0", "mud_density = 1e300", "well.mud_density", "no denser than"),
        ("friction_static = 0.35", "friction_static = 10.0", "well.friction_static", "from 0 to 1"),
        ("friction_dynamic = 0.2", "friction_dynamic = 10.0", "well.hole[0].friction_dynamic",
         "from 0 to 1"),
    ],
)  # fmt: skip
def test_out_of_range_inputs_are_refused_naming_the_key(capsys, tmp_path, old, new, key, text):
    path = _config(tmp_path, old, new)
    assert main(["drag", path]) == 2
    err = capsys.readouterr().err
    assert f"error: {key}:" in err and text in err and "Traceback" not in err


def test_mud_as_dense_as_the_steel_is_allowed():
    # buoyed weight g A (rho_steel - rho_mud) = 0: a vertical hookload of 0 (issue 36 case 1)
    config = deviated_well_config()

    densest = min(s.material.density for s in config.string.sections)
    survey = Survey([0.0, 2500.0], [0.0, 0.0], [0.0, 0.0])
    results = torque_drag(
        attrs.evolve(config.well, survey=survey, mud_density=densest), config.string
    )
    assert results.hookload_rotating == pytest.approx(0.0, abs=1e-6)


def test_a_dogleg_taking_the_well_above_the_surface_is_refused():
    # 179.99 deg over 0.01 m: 314 rad/m, beyond MAX_DOGLEG_SEVERITY (a radius of 1 m)
    with pytest.raises(ConfigError, match=r"179.99 deg over 0.01 m .* at 314.1 rad/m") as caught:
        Survey([0.0, 500.0, 500.01, 2500.0], [0.0, 0.0, 179.99, 179.99], [0.0] * 4)
    assert caught.value.key == "inclination[2]"
    assert 179.99 * math.pi / 180 / 0.01 > MAX_DOGLEG_SEVERITY
    # a gentle turn back up (0 to 170 deg over 300 m: radius 101 m, within the bound)
    # then 1000 m straight up: TVD 300 + 101 sin(170 deg) + 1000 cos(170 deg) = -667 m
    with pytest.raises(ConfigError, match="above the surface at station 3") as caught:
        Survey([0.0, 300.0, 600.0, 1600.0], [0.0, 0.0, 170.0, 170.0], [0.0] * 4)
    assert caught.value.key == "inclination[3]"


def test_dogleg_in_a_configuration_names_the_station(capsys, tmp_path):
    path = _config(
        tmp_path,
        "md = [0.0, 500.0, 800.0, 1100.0, 1700.0, 2000.0, 2300.0, 2500.0]",
        "md = [0.0, 500.0, 500.01, 1100.0, 1700.0, 2000.0, 2300.0, 2500.0]",
    )
    text = open(path).read()
    turned = "inclination = [0.0, 0.0" + ", 179.99" * 6 + "]"
    text = re.sub(r"inclination = \[[^\]]*\]", turned, text)
    open(path, "w").write(text)
    assert main(["drag", path]) == 2
    assert "error: well.inclination[2]:" in capsys.readouterr().err


def test_friction_factor_bound_in_the_api():
    survey = Survey([0.0, 1000.0], [0.0, 0.0], [0.0, 0.0])
    with pytest.raises(ConfigError, match="from 0 to 1") as caught:
        Wellbore(survey, friction_static=10.0, friction_dynamic=0.3)
    assert caught.value.key == "friction_static"
