"""Tool joints and adjusted weight on drill pipe and HWDP (issue 37, item 5).

``adjusted_weight`` (mass per length in air with the tool joints) sets the buoyed weight
and so the normal force; ``tool_joint_od`` the contact radius of the friction torque.
Expected values are closed forms of the soft-string model (Johancsik et al. 1984): a
vertical hole's hookload is the buoyed weight, sum of g m (1 - rho_mud/rho_steel) L; a
straight inclined hole's rotating torque is mu w_b sin(inc) L r_contact, section by section.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsio.config.tables import _section
from torsio.errors import ConfigError
from torsio.model.components import STEEL, Bit, DrillPipe, HeavyWeightDrillPipe
from torsio.model.drillstring import DrillString
from torsio.well import Survey, Wellbore
from torsio.well.rotating_column import GRAVITY
from torsio.well.string_contacts import node_contacts
from torsio.well.torque_drag import torque_drag

LB_FT = 0.45359237 / 0.3048  # kg/m per lb/ft (exact: 1 lb = 0.45359237 kg, 1 ft = 0.3048 m)
ADJUSTED = 22.3 * LB_FT  # 5 in 19.5 lb/ft pipe with tool joints (issue 37's example)
JOINT_OD = 6.625 * 0.0254
MUD, MU = 1300.0, 0.28
L_DP, L_BIT = 2499.7, 0.3


def _string() -> DrillString:
    pipe = DrillPipe(od="5 in", id="4.276 in", length=L_DP, adjusted_weight="22.3 lb/ft",
                     tool_joint_od="6.625 in")  # fmt: skip
    return DrillString([pipe, Bit(od="8.5 in", id="2 in", length=L_BIT)])


def _buoyed(mass_per_length: float) -> float:
    return GRAVITY * mass_per_length * (1.0 - MUD / STEEL.density)


def _bit_mass() -> float:
    return STEEL.density * math.pi / 4 * ((8.5 * 0.0254) ** 2 - (2 * 0.0254) ** 2)


def test_vertical_hookload_is_the_buoyed_adjusted_weight():
    survey = Survey([0.0, 2500.0], [0.0, 0.0], [0.0, 0.0])
    results = torque_drag(Wellbore(survey, mud_density=MUD), _string())
    expected = _buoyed(ADJUSTED) * L_DP + _buoyed(_bit_mass()) * L_BIT
    assert results.hookload_rotating == pytest.approx(expected, rel=1e-9)
    assert results.buoyed_weight == pytest.approx(expected, rel=1e-9)
    # 22.3 lb/ft against the body's 26.5 kg/m (17.8 lb/ft): the weight is the adjusted one
    assert ADJUSTED > _string().sections[0].body_mass_per_length * 1.2


def test_straight_inclined_torque_takes_the_tool_joint_radius():
    inc = math.radians(45.0)
    survey = Survey([0.0, 2500.0], [45.0, 45.0], [0.0, 0.0])
    well = Wellbore(survey, mud_density=MUD, friction_static=MU, friction_dynamic=MU)
    results = torque_drag(well, _string())
    expected = (
        MU
        * math.sin(inc)
        * (
            _buoyed(ADJUSTED) * L_DP * JOINT_OD / 2
            + _buoyed(_bit_mass()) * L_BIT * 8.5 * 0.0254 / 2
        )
    )
    assert results.surface_torque_rotating == pytest.approx(expected, rel=1e-6)
    # the friction capacities along the string add up to the same torque (mu_s = mu_d)
    string = _string()
    contacts = node_contacts(_Nodes(np.linspace(0.0, 2500.0, 11)[1:]), well, string)
    assert contacts.static_total == pytest.approx(expected, rel=1e-6)


class _Nodes:
    """A chain's node depths below the string's top [m] (what node_contacts reads)."""

    def __init__(self, depths: np.ndarray) -> None:
        self.node_depths = depths


def test_section_keys_in_a_configuration():
    section = _section({"kind": "hwdp", "od": "5 in", "id": "3 in", "length": 140.0,
                        "adjusted_weight": "49.3 lb/ft", "tool_joint_od": "6.5 in"},
                       "section[1]", STEEL)  # fmt: skip
    assert isinstance(section, HeavyWeightDrillPipe)
    assert section.mass_per_length == pytest.approx(49.3 * LB_FT, rel=1e-12)
    assert section.contact_radius == pytest.approx(6.5 * 0.0254 / 2, rel=1e-12)
    plain = _section({"kind": "drill_pipe", "od": 0.127, "id": 0.1, "length": 9.0}, "s", STEEL)
    assert plain.mass_per_length == plain.body_mass_per_length and plain.contact_radius == 0.127 / 2


@pytest.mark.parametrize(
    ("extra", "key", "text"),
    [
        ({"kind": "drill_collar", "tool_joint_od": "7 in"}, "section[0].tool_joint_od",
         "no tool joints"),
        ({"adjusted_weight": "10 lb/ft"}, "section[0].adjusted_weight", "between the body's"),
        ({"adjusted_weight": "1e6 kg/m"}, "section[0].adjusted_weight", "a solid bar's"),
        ({"tool_joint_od": "4 in"}, "section[0].tool_joint_od", "at least as wide"),
        ({"adjusted_weight": "22 N"}, "section[0].adjusted_weight", "not a linear density"),
    ],
)  # fmt: skip
def test_bad_values_name_the_key(extra, key, text):
    table = {"kind": "drill_pipe", "od": "5 in", "id": "4.276 in", "length": 100.0, **extra}
    with pytest.raises(ConfigError, match=text) as caught:
        _section(table, "section[0]", STEEL)
    assert caught.value.key == key
