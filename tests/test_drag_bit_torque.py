"""The bit in torque and drag (issue 37, item 4) and ``--friction`` applied to every
torque of ``torsio drag`` (issue 36, case 10).

On bottom the surface torque is the string's friction torque plus the torque on bit: the
configured law's at the operating point, or ``--bit-torque``. In a vertical hole without
friction the string carries none, so the surface torque on bottom is the torque on bit.
"""

from __future__ import annotations

import json
import math
import re
from importlib import resources

import pytest

from torsio.axial.steady import steady_drilling
from torsio.cli import main
from torsio.examples import rgd_deviated_well_config


def _drag(capsys, *argv: str) -> dict:
    assert main(["drag", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def _vertical(tmp_path) -> str:
    text = resources.files("torsio").joinpath("data/deviated_well.toml").read_text("utf-8")
    text = re.sub(r"inclination = \[[^\]]*\]", "inclination = [" + ", ".join(["0.0"] * 8) + "]",
                  text)  # fmt: skip
    path = tmp_path / "vertical.toml"
    path.write_text(text, "utf-8")
    return str(path)


def _tucker_wang(wob: float, rpm: float) -> float:
    """Tucker and Wang (1997), the paper's Eq. 2, T = W R a0 (tanh(a1 w) + a2 w / (1 + a3 w^2)),
    with the built-in deviated well's parameters (speed in rpm, R = 4.25 in)."""
    a0, a1, a2, a3, radius = 0.221, 0.2, 0.89, 0.06, 4.25 * 0.0254
    return wob * radius * a0 * (math.tanh(a1 * rpm) + a2 * rpm / (1 + a3 * rpm**2))


@pytest.mark.parametrize("rpm", [None, "60"])
def test_vertical_frictionless_surface_torque_is_the_law_torque_on_bit(capsys, tmp_path, rpm):
    extra = () if rpm is None else ("--rpm", rpm)
    data = _drag(capsys, _vertical(tmp_path), "--friction", "0", "--wob", "80kN", *extra)
    speed = 100.0 if rpm is None else 60.0  # [operation] rpm = 100
    expected = _tucker_wang(80e3, speed)
    assert data["surface_torque_on_bottom"] == pytest.approx(expected, rel=1e-6)
    assert data["bit_torque"] == pytest.approx(expected, rel=1e-12)
    assert data["bit_torque_source"] == f"tucker-wang at {speed:g} rpm"
    assert data["surface_torque_rotating"] == 0.0


def test_given_bit_torque_and_off_bottom(capsys, tmp_path):
    path = _vertical(tmp_path)
    data = _drag(capsys, path, "--friction", "0", "--bit-torque", "3 kN*m")
    assert data["surface_torque_on_bottom"] == pytest.approx(3e3, rel=1e-12)
    assert data["bit_torque_source"] == "given (--bit-torque)"
    data = _drag(capsys, path, "--wob", "0")  # the bit off bottom: no torque on it
    assert data["bit_torque"] == 0.0 and data["bit_torque_source"] == "off bottom"


def test_table_says_where_the_bit_torque_comes_from(capsys):
    assert main(["drag"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "tucker-wang at 100 rpm" in out


def test_rgd_bit_takes_its_steady_drilling_torque(capsys):
    # the RGD bit's torque on bit on bottom is its steady state's T0 (Detournay and
    # Defourny 1992 as in axial/steady.py): the closed form, not a run
    path = resources.files("torsio").joinpath("data/rgd_deviated_well.toml")
    config = rgd_deviated_well_config()
    data = _drag(capsys, str(path), "--wob", "100kN", "--rpm", "60")
    expected = steady_drilling(config.axial.bit, 100e3, 60.0).bit_torque
    assert data["bit_torque"] == pytest.approx(expected, rel=1e-12)
    assert data["bit_torque_source"] == "rgd steady drilling at 60 rpm"


def test_friction_override_applies_to_break_off_and_sliding(capsys):
    # one factor for static and sliding: the break-off torque (all static, from rest) and
    # the sliding torque are the rotating off-bottom torque (the same integral of mu N r)
    data = _drag(capsys, "--friction", "0.5")
    rotating = data["surface_torque_rotating"]
    assert data["break_off_torque"] == pytest.approx(rotating, rel=1e-9)
    assert data["sliding_torque"] == pytest.approx(rotating, rel=1e-9)
    plain = _drag(capsys)  # without the override, the well's factors: 12.2 and 10.2 kN m
    assert plain["break_off_torque"] < 0.7 * data["break_off_torque"]


def test_the_report_adds_the_same_torque_on_bit_as_drag(capsys, tmp_path):
    # one torque on bit on bottom: the report's well section and torsio drag agree (in a
    # vertical hole without friction both are the Tucker-Wang torque at [operation] rpm)
    path = _vertical(tmp_path)
    drag = _drag(capsys, path, "--wob", "80kN")
    assert main(["report", path, "--json"]) == 0
    well = json.loads(capsys.readouterr().out)["well"]
    assert well["wob"] == 80e3  # deviated_well.toml's [operation] wob
    assert well["bit_torque"] == pytest.approx(_tucker_wang(80e3, 100.0), rel=1e-12)
    assert well["bit_torque_source"] == drag["bit_torque_source"] == "tucker-wang at 100 rpm"
    assert well["surface_torque_on_bottom"] == drag["surface_torque_on_bottom"]


def test_rpm_with_a_given_bit_torque_is_an_error(capsys):
    # --rpm sets where the law's torque is taken; with --bit-torque it would be ignored
    assert main(["drag", "--rpm", "60", "--bit-torque", "1000"]) == 2
    assert "--rpm" in capsys.readouterr().err
