"""Components and the drill-string: geometry, validation, BHA membership."""

from __future__ import annotations

import math

import attrs
import pytest

from torsio import (
    LWD,
    MWD,
    Bit,
    DrillCollar,
    DrillPipe,
    DrillString,
    HeavyWeightDrillPipe,
    Material,
    Stabilizer,
)
from torsio.errors import ConfigError


def test_section_properties_match_errata_numbers(ritto):
    # Source: ERRATA 1: k_DP = 324.86 N m/rad, I_DP = 665.61 kg m^2, I_BHA = 233.78 kg m^2.
    dp = ritto.sections[0]
    assert dp.polar_moment == pytest.approx(math.pi / 32 * (0.140**4 - 0.119**4), rel=1e-15)
    assert dp.stiffness == pytest.approx(324.86, abs=0.005)
    assert dp.inertia == pytest.approx(665.61, abs=0.005)
    assert ritto.bha_inertia == pytest.approx(233.78, abs=0.005)  # HWDP + collars + bit


def test_default_bha_membership_and_override():
    # Paper Table 1: HWDP is "BHA 1"; everything below it is BHA; drill pipe is not.
    assert not DrillPipe(od=0.1, id=0.05, length=1.0).in_bha
    for cls in (HeavyWeightDrillPipe, DrillCollar, MWD, LWD, Stabilizer, Bit):
        assert cls(od=0.1, id=0.05, length=1.0).in_bha
    assert not HeavyWeightDrillPipe(od=0.1, id=0.05, length=1.0, bha=False).in_bha


@pytest.mark.parametrize(
    ("kwargs", "key"),
    [
        ({"od": 0.1, "id": 0.1, "length": 1.0}, "id"),
        ({"od": 0.1, "id": 0.2, "length": 1.0}, "id"),
        ({"od": -0.1, "id": 0.0, "length": 1.0}, "od"),
        ({"od": 0.1, "id": -0.01, "length": 1.0}, "id"),
        ({"od": 0.1, "id": 0.05, "length": 0.0}, "length"),
        ({"od": 0.1, "id": 0.05, "length": math.inf}, "length"),
        ({"od": math.nan, "id": 0.05, "length": 1.0}, "od"),
    ],
)
def test_bad_geometry_names_the_field(kwargs, key):
    with pytest.raises(ConfigError) as info:
        DrillCollar(**kwargs)
    assert info.value.key == key
    assert repr(kwargs[key]) in str(info.value)


def test_bad_material():
    with pytest.raises(ConfigError, match="shear_modulus"):
        Material(shear_modulus=0.0, density=7800.0)
    with pytest.raises(ConfigError, match="density"):
        Material(shear_modulus=80e9, density=-1.0)


def test_components_are_immutable():
    dp = DrillPipe(od=0.1, id=0.05, length=1.0)
    with pytest.raises(AttributeError):
        dp.length = 2.0  # type: ignore[misc]


def test_string_needs_one_bit_last():
    dp = DrillPipe(od=0.1, id=0.05, length=10.0)
    bit = Bit(od=0.2, id=0.05, length=0.3)
    with pytest.raises(ConfigError, match="no bit"):
        DrillString([dp])
    with pytest.raises(ConfigError, match="last section"):
        DrillString([bit, dp])
    with pytest.raises(ConfigError, match="one bit"):
        DrillString([dp, bit, bit])
    with pytest.raises(ConfigError, match="flexible section"):
        DrillString([bit])
    with pytest.raises(ConfigError, match="expected a Section"):
        DrillString([dp, "collar", bit])
    with pytest.raises(ConfigError, match="bha = false"):
        DrillString([dp, Bit(od=0.2, id=0.05, length=0.3, bha=False)])


def test_drill_pipe_below_bha_rejected():
    with pytest.raises(ConfigError, match="one block above the bit"):
        DrillString(
            [
                DrillCollar(od=0.2, id=0.07, length=100.0),
                DrillPipe(od=0.1, id=0.05, length=10.0),
                Bit(od=0.2, id=0.05, length=0.3),
            ]
        )


def test_series_stiffness_of_two_pipe_grades():
    # Source: springs in series: 1/k = sum(L / (G J)).
    a = DrillPipe(od=0.127, id=0.108, length=2000.0)
    b = DrillPipe(od=0.140, id=0.119, length=1500.0)
    string = DrillString([a, b, Bit(od=0.2, id=0.05, length=0.3)])
    assert string.drill_pipe_stiffness == pytest.approx(1 / (1 / a.stiffness + 1 / b.stiffness))
    assert string.flexible_length == 3500.0


def test_constructors_take_unit_strings_like_the_toml():
    # Exact factors: 1 in = 0.0254 m, 1 ft = 0.3048 m (international inch/foot); G in GPa.
    steel = Material(shear_modulus="79.3 GPa", density="7800 kg/m^3")
    assert steel.shear_modulus == pytest.approx(79.3e9, rel=1e-15)
    pipe = DrillPipe(od="5 in", id="4.276 in", length="31 ft", material=steel)
    assert pipe.od == pytest.approx(0.127, rel=1e-15)
    assert pipe.id == pytest.approx(4.276 * 0.0254, rel=1e-15)
    assert pipe.length == pytest.approx(31 * 0.3048, rel=1e-15)
    assert DrillPipe(od=0.127, id=0.1086, length=9.4488).od == 0.127  # bare numbers: SI
    with pytest.raises(ConfigError, match="od") as info:
        DrillPipe(od="5 kg", id=0.1, length=10.0)
    assert "'5 kg' is not a length" in str(info.value)
    with pytest.raises(ConfigError, match="must be smaller than the outer diameter"):
        DrillPipe(od="4 in", id="5 in", length=10.0)


def test_system_and_damping_take_unit_strings(one_dof):
    from torsio.physics.damping import RayleighDamping

    # 1 rpm = pi/30 rad/s; 1 in = 0.0254 m
    system = one_dof.at(wob="100 kN", rpm="120 rpm")
    assert system.wob == 100e3 and system.rpm == pytest.approx(120.0, rel=1e-15)
    assert one_dof.at(rpm=f"{4 * math.pi} rad/s").rpm == pytest.approx(120.0, rel=1e-15)
    assert attrs.evolve(one_dof, bit_radius="4.25 in").bit_radius == pytest.approx(0.10795)
    damping = RayleighDamping(alpha="0.35 1/s", beta="60 ms")
    assert (damping.alpha, damping.beta) == (pytest.approx(0.35), pytest.approx(0.06))
