"""Soft-string torque and drag against closed forms (each to 1e-9 relative, as the
integrator is exact to round-off on them) and the physical sign of the normal force."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsio.errors import ConfigError
from torsio.model.components import Bit, DrillPipe, Material
from torsio.model.drillstring import DrillString
from torsio.well import Survey, Wellbore
from torsio.well.rotating_column import GRAVITY
from torsio.well.torque_drag import torque_drag

STEEL = Material(shear_modulus=80e9, density=7850.0)
MUD = 1300.0
DP = {"od": 0.127, "id": 0.1086}
BIT = {"od": 0.2159, "id": 0.05}
MU = 0.28


def string(length: float) -> DrillString:
    return DrillString(
        [
            DrillPipe(**DP, length=length - 0.3, material=STEEL),
            Bit(**BIT, length=0.3, material=STEEL),
        ]
    )


def weight(section: dict) -> float:
    """Buoyed weight per metre, w = g A (rho_steel - rho_mud) [N/m]."""
    return GRAVITY * math.pi / 4 * (section["od"] ** 2 - section["id"] ** 2) * (7850.0 - MUD)


W_DP, W_BIT = weight(DP), weight(BIT)
R_DP, R_BIT = DP["od"] / 2, BIT["od"] / 2


def well(survey: Survey, **options) -> Wellbore:
    options.setdefault("friction_static", 0.35)
    return Wellbore(survey, mud_density=MUD, friction_dynamic=MU, **options)


def test_vertical_well_has_no_friction():
    # closed form: no normal force in a vertical hole, so every hookload is the buoyed
    # weight sum w_i L_i, the surface torque is the torque on bit and off bottom none
    survey = Survey([0.0, 3000.0], [0.0, 0.0], [0.0, 0.0])
    results = torque_drag(well(survey), string(2500.0), wob=80e3, bit_torque=4e3)
    expected = W_DP * 2499.7 + W_BIT * 0.3
    for hookload in (results.hookload_trip_out, results.hookload_trip_in,
                     results.hookload_rotating):  # fmt: skip
        assert hookload == pytest.approx(expected, rel=1e-9)
    assert results.hookload_on_bottom == pytest.approx(expected - 80e3, rel=1e-9)
    assert results.surface_torque_rotating == 0.0
    assert results.surface_torque_on_bottom == pytest.approx(4e3, rel=1e-9)
    # the string hangs from the rig floor: top at md 0, bit at its length (500 m of open
    # hole below it carry nothing)
    assert results.string_top_md == 0.0 and results.md[0] == 0.0
    assert results.bit_md == 2500.0 and results.to_dict()["bit_md"] == 2500.0
    assert np.all(results.normal_force == 0.0)
    # the neutral point: WOB / w above the bit (closed form, buoyed weight)
    assert results.neutral_point_md == pytest.approx(2500.0 - 0.3 - (80e3 - W_BIT * 0.3) / W_DP)


@pytest.mark.parametrize("normal_force", ["soft-string", "gravity"])
def test_straight_inclined_hole(normal_force):
    # closed form (Johancsik et al. 1984, straight cell): F2 = F1 + w ds (cos inc +- mu
    # sin inc), torque mu w sin(inc) r_o ds, section by section; the same on bottom
    inc = math.radians(55.0)
    survey = Survey([0.0, 2000.0], [55.0, 55.0], [30.0, 30.0])
    results = torque_drag(
        well(survey, normal_force=normal_force), string(2000.0), wob=50e3, bit_torque=3e3
    )
    for column, sign in ((0, 1.0), (1, -1.0), (2, 0.0)):
        expected = (W_DP * 1999.7 + W_BIT * 0.3) * (math.cos(inc) + sign * MU * math.sin(inc))
        assert results.tension[0, column] == pytest.approx(expected, rel=1e-9)
    torque = MU * math.sin(inc) * (W_DP * R_DP * 1999.7 + W_BIT * R_BIT * 0.3)
    assert results.surface_torque_rotating == pytest.approx(torque, rel=1e-9)
    assert results.surface_torque_on_bottom == pytest.approx(torque + 3e3, rel=1e-9)
    np.testing.assert_allclose(results.normal_force[:-2, 2], W_DP * math.sin(inc), rtol=1e-12)


def _build_closed_form(t_bottom, w, radius, a1, a2, sigma):
    """Tension at the top of a circular build from a1 (top) to a2 (bottom) with the pipe on
    the high side (T > w R sin a): the solution of dT/da = -w R cos a - sigma mu (T - w R
    sin a), of the form of Aadnoy's closed forms for curved sections (Aadnoy & Andersen
    1998, SPE 39391; Aadnoy, Fazaelizadeh & Hareland 2010, JCPT 49(10)): a capstan factor
    exp(sigma mu theta) on the tension and a weight term w R in sin and cos."""

    def particular(a):
        return (
            -w * radius * ((1 - MU**2) * math.sin(a) + 2 * sigma * MU * math.cos(a)) / (1 + MU**2)
        )

    return particular(a1) + (t_bottom - particular(a2)) * math.exp(sigma * MU * (a2 - a1))


def test_circular_build_has_the_aadnoy_closed_form():
    # vertical to 500 m, a 3 deg/30 m build to 30 deg, a 1000 m tangent to the bit
    theta = math.radians(30.0)
    radius = 30.0 / math.radians(3.0)
    end_build = 500.0 + radius * theta
    survey = Survey([0.0, 500.0, end_build, end_build + 1000.0], [0, 0, 30, 30], [40] * 4)
    results = torque_drag(well(survey), string(end_build + 1000.0))
    top_of_tangent = np.isclose(results.md, end_build, rtol=0, atol=1e-9)
    for column, sigma in ((0, 1.0), (1, -1.0)):
        factor = math.cos(theta) + sigma * MU * math.sin(theta)
        t_bottom = (W_DP * 999.7 + W_BIT * 0.3) * factor  # straight tangent, closed form
        assert results.tension[top_of_tangent, column][0] == pytest.approx(t_bottom, rel=1e-9)
        t_top = _build_closed_form(t_bottom, W_DP, radius, 0.0, theta, sigma)
        assert results.tension[0, column] == pytest.approx(t_top + W_DP * 500.0, rel=1e-9)
    # rotating: T = T2 + w R (sin a2 - sin a), N = T / R - w sin a (high side) and
    # M = mu r [(T2 + w R sin a2) theta - 2 w R (1 - cos theta)] over the build
    t2 = (W_DP * 999.7 + W_BIT * 0.3) * math.cos(theta)
    tangent_torque = MU * math.sin(theta) * (W_DP * R_DP * 999.7 + W_BIT * R_BIT * 0.3)
    build_torque = (
        MU
        * R_DP
        * (
            (t2 + W_DP * radius * math.sin(theta)) * theta
            - 2 * W_DP * radius * (1 - math.cos(theta))
        )
    )
    assert results.surface_torque_rotating == pytest.approx(tangent_torque + build_torque, rel=1e-9)


def test_horizontal_turn_adds_tension_and_weight_as_vectors():
    # 3-D closed form: in a horizontal turn of radius R the tension's pull T/R and the
    # weight w are perpendicular, N = sqrt((T/R)^2 + w^2), and dT/dl = sigma mu N gives
    # T = w R sinh(asinh(T0 / (w R)) + sigma mu l / R); then 200 m straight: + sigma mu w l
    radius = 30.0 / math.radians(2.0)
    turn = radius * math.radians(60.0)
    survey = Survey([0.0, 200.0, 200.0 + turn], [90.0] * 3, [10.0, 10.0, 70.0])
    results = torque_drag(well(survey), string(200.0 + turn))
    for column, sigma in ((0, 1.0), (1, -1.0)):
        t = W_BIT * radius * math.sinh(sigma * MU * 0.3 / radius)
        t = (
            W_DP
            * radius
            * math.sinh(math.asinh(t / (W_DP * radius)) + sigma * MU * (turn - 0.3) / radius)
        )
        assert results.tension[0, column] == pytest.approx(t + sigma * MU * W_DP * 200.0, rel=1e-9)
    assert results.hookload_rotating == pytest.approx(0.0, abs=1e-6)
    torque = MU * (W_DP * R_DP * (200.0 + turn - 0.3) + W_BIT * R_BIT * 0.3)
    assert results.surface_torque_rotating == pytest.approx(torque, rel=1e-9)


def test_build_under_tension_pulls_the_pipe_to_the_high_side():
    # the physical sign: in a build the tension's pull T kappa (towards the centre, the
    # high side) opposes the weight (the low side), N = |T/R - w sin a|; the normal force
    # therefore vanishes where T = w R sin a, and is smaller than the sum of the two
    radius = 30.0 / math.radians(3.0)
    survey = Survey([0.0, 500.0, 500.0 + radius * math.radians(60.0), 3000.0], [0, 0, 60, 60],
                    [0] * 4)  # fmt: skip
    results = torque_drag(well(survey), string(3000.0))
    in_build = (results.md > 500.0) & (results.md < 500.0 + radius * math.radians(60.0) - 1)
    md = results.md[in_build]
    a = survey.inclination(md)
    t = results.tension[in_build, 2]
    np.testing.assert_allclose(
        results.normal_force[in_build, 2], np.abs(t / radius - W_DP * np.sin(a)), rtol=1e-12
    )
    assert np.all(results.normal_force[in_build, 2] < t / radius + W_DP * np.sin(a))


def test_errors_name_the_option():
    survey = Survey([0.0, 1000.0], [0.0, 0.0], [0.0, 0.0])
    with pytest.raises(ConfigError, match="the string is 1500 m long but the survey ends"):
        torque_drag(well(survey), string(1500.0))
    with pytest.raises(ConfigError, match="friction: expected a non-negative"):
        torque_drag(well(survey), string(900.0), friction=-0.1)
    with pytest.raises(ConfigError, match="wob: expected a non-negative"):
        torque_drag(well(survey), string(900.0), wob=math.nan)


def test_friction_override_replaces_every_hole_section():
    from torsio.well import HoleSection

    survey = Survey([0.0, 2000.0], [55.0, 55.0], [30.0, 30.0])
    cased = well(survey, hole=(HoleSection(to_md=1000.0, friction_dynamic=0.1),))
    same = torque_drag(well(survey), string(2000.0), friction=0.2)
    other = torque_drag(cased, string(2000.0), friction=0.2)
    assert other.hookload_trip_out == pytest.approx(same.hookload_trip_out, rel=1e-14)
    assert (
        torque_drag(cased, string(2000.0)).surface_torque_rotating
        < torque_drag(well(survey), string(2000.0)).surface_torque_rotating
    )


def test_published_buoyed_hookload_example():
    # worked example "how to calculate overpull on a drill pipe" (J. Whitehouse; the
    # textbook buoyancy factor BF = (65.5 - MW) / 65.5 with steel at 65.5 lb/gal, as in
    # Lyons et al., Formulas and Calculations for Drilling, Production and Workover):
    # 10,000 ft of 25 lb/ft pipe in 20 lb/gal mud, BF = 0.6947, hookload 173,675 lb. The
    # example rounds BF to four digits: exact 45.5/65.5 = 0.694656, 173,664 lbf; the test
    # allows the published rounding (half a unit of BF's fourth digit: 12.5 lbf)
    ppg, lbf, ft = 119.82642731689663, 4.4482216152605, 0.3048  # kg/m^3, N, m (exact)
    steel = Material(shear_modulus=80e9, density=65.5 * ppg)
    area = 25 * lbf / ft / (GRAVITY * steel.density)  # 25 lbf/ft in air
    od = 0.127
    inner = math.sqrt(od**2 - 4 * area / math.pi)
    length = 10_000 * ft
    pipe = DrillString([DrillPipe(od=od, id=inner, length=length - 0.3, material=steel),
                        Bit(od=od, id=inner, length=0.3, material=steel)])  # fmt: skip
    survey = Survey([0.0, length], [0.0, 0.0], [0.0, 0.0])
    hole = Wellbore(survey, mud_density=20 * ppg)
    results = torque_drag(hole, pipe)
    assert results.hookload_rotating / lbf == pytest.approx(250_000 * 45.5 / 65.5, rel=1e-12)
    assert results.hookload_rotating / lbf == pytest.approx(173_675, abs=12.5)
