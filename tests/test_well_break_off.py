"""Break-off torque, twist and sliding torque of a string in a well (torsio.well.break_off).

References: closed forms of a straight inclined hole, where the normal force per metre is
the buoyed weight's normal component w sin(inc) for both normal-force models (no
curvature), and the sliding torque of the torque-and-drag calculation (the same integral
with mu_d, integrated by torque_drag's own Runge-Kutta steps).
"""

from __future__ import annotations

import math

import pytest

from torsio.examples import deviated_well_config
from torsio.model.components import Bit, DrillCollar, DrillPipe, Material
from torsio.model.drillstring import DrillString
from torsio.well.break_off import break_off
from torsio.well.rotating_column import GRAVITY
from torsio.well.survey import Survey
from torsio.well.torque_drag import torque_drag
from torsio.well.wellbore import HoleSection, Wellbore

STEEL = Material(shear_modulus=80e9, density=7850.0)
MUD = 1200.0
INCLINATION = math.radians(50.0)


def _weight(section) -> float:
    """Buoyed weight per metre g A (rho_steel - rho_mud) [N/m]."""
    return GRAVITY * math.pi / 4 * (section.od**2 - section.id**2) * (7850.0 - MUD)


@pytest.fixture(scope="module")
def straight():
    pipe = DrillPipe(od=0.127, id=0.1086, length=1500.0, material=STEEL)
    collar = DrillCollar(od=0.1715, id=0.0714, length=199.0, material=STEEL)
    bit = Bit(od=0.1715, id=0.0714, length=1.0, material=STEEL)  # a collar-like stub
    string = DrillString([pipe, collar, bit])
    well = Wellbore(
        Survey([0.0, 1700.0], [50.0, 50.0], [30.0, 30.0]),
        mud_density=MUD,
        friction_static=0.4,
        friction_dynamic=0.3,
        hole=(HoleSection(to_md=800.0, friction_static=0.25, friction_dynamic=0.2),),
    )
    return well, string


def _closed_form(well, string, static: bool) -> tuple[float, float]:
    """(torque at the top, twist) of a straight inclined hole, integrated piece by piece:
    on each piece of constant mu, w, r_o and G J, tau is linear in depth."""
    marks = [0.0, 800.0, 1500.0, 1699.0, 1700.0]  # hole-section and string-section ends
    pieces = []
    for a, b in zip(marks[:-1], marks[1:], strict=True):
        mu = (0.25 if static else 0.2) if b <= 800.0 else (0.4 if static else 0.3)
        section = string.sections[0 if b <= 1500.0 else (1 if b <= 1699.0 else 2)]
        load = mu * _weight(section) * math.sin(INCLINATION) * section.od / 2  # N m per m
        rigidity = STEEL.shear_modulus * section.polar_moment
        pieces.append((a, b, load, rigidity))
    below = 0.0
    twist = 0.0
    for a, b, load, rigidity in reversed(pieces):
        top = below + load * (b - a)
        twist += 0.5 * (top + below) * (b - a) / rigidity  # tau linear on the piece: exact
        below = top
    return below, twist


@pytest.mark.parametrize("model", ["soft-string", "gravity"])
def test_straight_inclined_hole_closed_forms(straight, model):
    well, string = straight
    well = Wellbore(
        well.survey,
        mud_density=MUD,
        friction_static=0.4,
        friction_dynamic=0.3,
        hole=well.hole,
        normal_force=model,
    )
    result = break_off(well, string, cell_length=50.0)
    torque, twist = _closed_form(well, string, static=True)
    sliding, _ = _closed_form(well, string, static=False)
    assert result.torque == pytest.approx(torque, rel=1e-9)
    assert result.sliding_torque == pytest.approx(sliding, rel=1e-9)
    assert result.twist == pytest.approx(twist, rel=1e-9)  # tau linear per cell: exact
    assert result.static_torque[-1] == 0.0 and result.static_torque[0] == result.torque


def test_sliding_torque_is_the_torque_and_drag_surface_torque():
    config = deviated_well_config()
    result = break_off(config.well, config.string)
    drag = torque_drag(config.well, config.string, cell_length=1.0)
    # the same integral of mu_d N r_o, per cell here and by Runge-Kutta there
    assert result.sliding_torque == pytest.approx(drag.surface_torque_rotating, rel=1e-9)
    assert result.torque > result.sliding_torque  # mu_s > mu_d in both hole sections


def test_twist_converges_in_the_cell_length():
    config = deviated_well_config()
    coarse = break_off(config.well, config.string, cell_length=8.0).twist
    fine = break_off(config.well, config.string, cell_length=4.0).twist
    finest = break_off(config.well, config.string, cell_length=1.0).twist
    # the trapezoidal rule is second order: the change shrinks about 4x per halving
    assert abs(fine - finest) < 0.5 * abs(coarse - finest) + 1e-12
    assert abs(fine - finest) / finest < 1e-6


def test_bad_cell_length_is_named():
    config = deviated_well_config()
    with pytest.raises(Exception, match="cell_length"):
        break_off(config.well, config.string, cell_length=0.0)


def test_report_well_section_gives_the_same_numbers():
    from torsio.config.bit_torque import law_bit_torque
    from torsio.report.document import report_data

    config = deviated_well_config()
    data = report_data(config, modes=1)["well"]
    start = break_off(config.well, config.string)
    wob = config.operation.wob
    bit_torque, _ = law_bit_torque(config, wob)  # on bottom, as torsio drag adds it
    drag = torque_drag(config.well, config.string, wob=wob, bit_torque=bit_torque)
    # the report computes nothing of its own: the same functions, the same numbers
    assert data["break_off_torque"] == start.torque
    assert data["break_off_twist"] == start.twist
    assert data["surface_torque_on_bottom"] == drag.surface_torque_on_bottom
    assert data["max_inclination_deg"] == pytest.approx(35.0, abs=1e-9)  # the tangent's
