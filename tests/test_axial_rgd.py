"""The RGD bit law (torsio.axial.rgd) and its steady drilling state (torsio.axial.steady).

Expected values are the closed forms of Richard, Germay and Detournay (2007) and Teale's
(1965) mechanical specific energy, computed here by hand from the parameters."""

from __future__ import annotations

import math

import pytest

from torsio.axial.rgd import RGDBit, rgd_example, rgd_from_table
from torsio.axial.steady import steady_drilling
from torsio.errors import ConfigError

# DESIGN.md's [bit_rock] law = "rgd" table
A, N, EPS, ZETA, SIGMA, L, MU, GAMMA = 0.108, 4, 60e6, 0.6, 60e6, 0.011, 0.6, 1.0
TABLE = {
    "law": "rgd",
    "radius": A,
    "blades": N,
    "intrinsic_specific_energy": EPS,
    "cutting_force_ratio": ZETA,
    "contact_stress": SIGMA,
    "wear_flat_length": L,
    "contact_friction": MU,
    "bit_geometry": GAMMA,
}


def test_the_example_is_designs_table():
    assert rgd_from_table(TABLE) == rgd_example()


def test_forces_are_cutting_plus_wear_flat_friction():
    # W = ζ ε a d + σ a l, T = ε a² d / 2 + μ γ a (σ a l) / 2 (RGD 2007)
    bit = rgd_example()
    d = 3.7e-3
    weight, torque = bit.forces(d)
    assert weight == pytest.approx(ZETA * EPS * A * d + SIGMA * A * L, rel=1e-12)
    friction_torque = MU * GAMMA * A * (SIGMA * A * L) / 2
    assert torque == pytest.approx(EPS * A**2 * d / 2 + friction_torque, rel=1e-12)
    assert bit.friction_weight == pytest.approx(SIGMA * A * L, rel=1e-12)
    assert bit.hole_area == pytest.approx(math.pi * A**2, rel=1e-12)


@pytest.mark.parametrize(("wob", "rpm"), [(100e3, 60.0), (150e3, 120.0), (71.3e3, 30.0)])
def test_steady_state_against_the_closed_forms(wob, rpm):
    state = steady_drilling(rgd_example(), wob, rpm)
    omega = rpm * math.pi / 30
    d0 = (wob - SIGMA * A * L) / (ZETA * EPS * A)
    v0 = omega * d0 / (2 * math.pi)
    t0 = EPS * A**2 * d0 / 2 + MU * GAMMA * A**2 * L * SIGMA / 2
    area = math.pi * A**2
    assert state.depth_of_cut == pytest.approx(d0, rel=1e-9)
    assert state.rop == pytest.approx(v0, rel=1e-9)
    assert state.bit_torque == pytest.approx(t0, rel=1e-9)
    assert state.mse == pytest.approx(wob / area + omega * t0 / (area * v0), rel=1e-9)
    assert state.delay == pytest.approx(2 * math.pi / (N * omega), rel=1e-12)


def test_mse_is_the_work_per_unit_volume_drilled():
    # Teale (1965): power (W V + T Ω) over the volume drilled per second A V
    state = steady_drilling(rgd_example(), 120e3, 80.0)
    power = state.wob * state.rop + state.bit_torque * state.bit_speed
    assert state.mse == pytest.approx(power / (math.pi * A**2 * state.rop), rel=1e-9)


def test_the_steady_state_balances_the_bit_law():
    # the bit law at d0 returns the applied weight: the axial balance M U'' = 0
    bit = rgd_example()
    state = steady_drilling(bit, 100e3, 60.0)
    weight, torque = bit.forces(state.depth_of_cut)
    assert weight == pytest.approx(100e3, rel=1e-12)
    assert torque == pytest.approx(state.bit_torque, rel=1e-12)
    # each blade cuts d0/n in the time t_n0 between blades: d0 = n V0 t_n0
    assert N * state.rop * state.delay == pytest.approx(state.depth_of_cut, rel=1e-12)


def test_to_dict_has_exactly_designs_keys():
    keys = set(steady_drilling(rgd_example(), 100e3, 60.0).to_dict())
    assert keys == {"depth_of_cut", "rop", "bit_torque", "mse"}


@pytest.mark.parametrize("wob", [71280.0, 50e3, 0.0])
def test_a_bit_that_does_not_cut_is_refused_naming_the_weight(wob):
    with pytest.raises(ConfigError, match=r"wob: .* the bit does not cut") as info:
        steady_drilling(rgd_example(), wob, 60.0)
    assert info.value.key == "wob"
    assert "71280" in str(info.value)


def test_rpm_must_be_positive():
    with pytest.raises(ConfigError, match="rpm"):
        steady_drilling(rgd_example(), 100e3, 0.0)


def test_units_in_the_table():
    table = {**TABLE, "intrinsic_specific_energy": "60 MPa", "wear_flat_length": "11 mm"}
    assert rgd_from_table(table) == rgd_example()


def test_bit_geometry_defaults_to_one():
    table = {k: v for k, v in TABLE.items() if k != "bit_geometry"}
    assert rgd_from_table(table).bit_geometry == 1.0


@pytest.mark.parametrize(
    ("key", "value", "expected"),
    [
        ("radius", 0.0, r"bit_rock.radius: 0.0 must be > 0"),
        ("radius", "3 kN", r"bit_rock.radius"),
        ("blades", 2.5, r"bit_rock.blades: 2.5 is not a whole number"),
        ("blades", 0, r"bit_rock.blades: 0 must be >= 1"),
        ("intrinsic_specific_energy", -1.0, r"intrinsic_specific_energy: -1.0 must be > 0"),
        ("cutting_force_ratio", 0.0, r"cutting_force_ratio: 0.0 must be > 0"),
        ("contact_stress", -5.0, r"contact_stress: -5.0 must be >= 0"),
        ("wear_flat_length", -1e-3, r"wear_flat_length: -0.001 must be >= 0"),
        ("contact_friction", float("nan"), r"contact_friction: expected a finite value, got nan"),
        ("bit_geometry", 0.0, r"bit_geometry: 0.0 must be > 0"),
    ],
)
def test_errors_name_the_key_the_value_and_what_was_expected(key, value, expected):
    with pytest.raises(ConfigError, match=expected):
        rgd_from_table({**TABLE, key: value})


def test_missing_unknown_and_wrong_law_keys():
    with pytest.raises(ConfigError, match=r"bit_rock.contact_stress: missing"):
        rgd_from_table({k: v for k, v in TABLE.items() if k != "contact_stress"})
    with pytest.raises(ConfigError, match=r"bit_rock.wear_flat: unknown key"):
        rgd_from_table({**TABLE, "wear_flat": 0.01})
    with pytest.raises(ConfigError, match=r"bit_rock.law: 'tucker-wang' is not 'rgd'"):
        rgd_from_table({**TABLE, "law": "tucker-wang"})


def test_the_constructor_validates_too():
    with pytest.raises(ConfigError, match=r"bit_rock.contact_friction: nan is not finite"):
        RGDBit(A, N, EPS, ZETA, SIGMA, L, float("nan"), GAMMA)


def test_the_bit_is_frozen():
    bit = rgd_example()
    with pytest.raises(AttributeError):
        bit.radius = 0.2  # type: ignore[misc]
    assert isinstance(bit, RGDBit)
