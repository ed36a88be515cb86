"""The rotating soft-string state at any weight on bit (torsio.well.rotating_column)
against closed forms: a horizontal hole turning on a circular arc, where the tension is
-W everywhere (t_z = 0: no weight along the hole) and the normal force is the vector sum
of the tension's pull, W / R towards the centre, and the buoyed weight w_b, down."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsio.model.components import Bit, DrillPipe
from torsio.model.drillstring import DrillString
from torsio.well.rotating_column import GRAVITY, RotatingColumn
from torsio.well.survey import Survey
from torsio.well.wellbore import Wellbore

OD, ID, LENGTH, TURN = 0.127, 0.1086, 600.0, 30.0  # m, m, m, deg of azimuth over the arc


def _column(normal_force: str = "soft-string") -> RotatingColumn:
    survey = Survey([0.0, LENGTH], [90.0, 90.0], [0.0, TURN])
    string = DrillString(
        [DrillPipe(od=OD, id=ID, length=LENGTH - 0.3), Bit(od=OD, id=ID, length=0.3)]
    )
    return RotatingColumn(Wellbore(survey, normal_force=normal_force), string)


def _buoyed_weight() -> float:
    density = DrillPipe(od=OD, id=ID, length=1.0).material.density  # the default steel
    return GRAVITY * math.pi / 4 * (OD**2 - ID**2) * density  # N/m, no mud


@pytest.mark.parametrize("wob", [0.0, 5e4, 2e5])
def test_horizontal_arc_friction_is_the_closed_form_at_every_weight(wob: float) -> None:
    # N = sqrt((W / R)^2 + w_b^2) with R = L / beta, so int N r_o dl = r_o L N
    radius = LENGTH / math.radians(TURN)
    normal = math.hypot(wob / radius, _buoyed_weight())
    column = _column()
    assert column.friction_per_cell(wob).sum() == pytest.approx(OD / 2 * LENGTH * normal, rel=1e-9)
    assert column.normal_force(wob) == pytest.approx(np.full(column.md.size, normal), rel=1e-9)
    assert column.tension(wob) == pytest.approx(np.full(column.md.size, -wob), abs=1e-6)


def test_many_weights_at_once_equal_each_weight_alone() -> None:
    # the same quadrature, broadcast over the weights: equal to round-off
    column = _column()
    weights = np.array([0.0, 3e4, 1.2e5])
    together = column.friction_per_cell(weights)
    for row, wob in zip(together, weights, strict=True):
        assert row == pytest.approx(column.friction_per_cell(float(wob)), rel=1e-14)


def test_gravity_model_ignores_the_weight_on_bit() -> None:
    # the gravity model's N = w_b sin(inc) = w_b here, whatever the tension
    column = _column("gravity")
    expected = OD / 2 * LENGTH * _buoyed_weight()
    for wob in (0.0, 2e5):
        assert column.friction_per_cell(wob).sum() == pytest.approx(expected, rel=1e-12)
