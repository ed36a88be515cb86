"""The Python API takes unit strings where a configuration file does (issue 36, case 13),
through the one converter of torsio.units (attrs fields and ``as_si`` at a function's entry).

Expected values are unit definitions: 1 kN = 1000 N, 1 g/cm^3 = 1000 kg/m^3 (SI brochure),
1 ft = 0.3048 m (NIST SP 811, B.8), 60 rpm = 2 pi rad/s; with strings a result equals the one
with the SI numbers exactly.
"""

from __future__ import annotations

import pytest

from torsio.analysis.axial_transient import simulate_axial
from torsio.axial.rgd import rgd_example
from torsio.errors import ConfigError
from torsio.examples import deviated_well_config
from torsio.model.axial_assembly import rgd_two_dof_example
from torsio.well.break_off import break_off
from torsio.well.torque_drag import torque_drag
from torsio.well.wellbore import HoleSection, Wellbore


def test_torque_drag_and_break_off_take_unit_strings():
    config = deviated_well_config()
    numbers = torque_drag(config.well, config.string, wob=100e3, bit_torque=2e3).to_dict()
    strings = torque_drag(config.well, config.string, wob="100 kN", bit_torque="2 kN*m").to_dict()
    assert strings == numbers
    held_numbers = break_off(config.well, config.string, wob=100e3)
    held_strings = break_off(config.well, config.string, wob="100 kN", cell_length="1 m")
    assert (held_strings.torque, held_strings.twist, held_strings.sliding_torque) == (
        held_numbers.torque,
        held_numbers.twist,
        held_numbers.sliding_torque,
    )


def test_wellbore_and_hole_section_take_unit_strings():
    survey = deviated_well_config().well.survey
    well = Wellbore(
        survey,
        mud_density="1.2 g/cm^3",
        threshold_speed="0.5 rad/s",
        hole=(HoleSection(to_md="3937 ft"),),
    )
    assert well.mud_density == pytest.approx(1200.0, rel=1e-15)
    assert well.hole[0].to_md == pytest.approx(3937 * 0.3048, rel=1e-15)
    assert HoleSection(to_md="1200 m").to_md == 1200.0


@pytest.mark.parametrize(
    ("call", "key", "text"),
    [
        (lambda s: Wellbore(s, mud_density="12 s"), "mud_density", "is not a density"),
        (lambda s: HoleSection(to_md="1200 kN"), "to_md", "is not a length"),
        (lambda s: HoleSection(to_md="9**9**9 m"), "to_md", "a power applies"),
    ],
)
def test_bad_unit_strings_name_the_field(call, key, text):
    survey = deviated_well_config().well.survey
    with pytest.raises(ConfigError) as info:
        call(survey)
    assert info.value.key == key and text in info.value.message


def test_torque_drag_refuses_a_force_for_a_torque():
    config = deviated_well_config()
    with pytest.raises(ConfigError, match="bit_torque: '2 kN' is not a torque"):
        torque_drag(config.well, config.string, bit_torque="2 kN")


def test_simulate_axial_takes_unit_strings():
    options = {"duration": 3.0, "window": 1.0, "growth_rate": False, "samples": 200}
    assembly, bit = rgd_two_dof_example(), rgd_example()
    numbers = simulate_axial(assembly, bit, 100e3, 60.0, **options)
    strings = simulate_axial(assembly, bit, "100 kN", "60 rpm", **options)
    assert strings.wob == 100e3 and strings.rpm == pytest.approx(60.0, rel=1e-15)
    assert strings.to_dict() == numbers.to_dict()


@pytest.mark.parametrize("samples", [0, -3, 2.5, True])
def test_severity_probability_refuses_no_samples(samples):
    from torsio.calibration.monte_carlo import severity_probability

    with pytest.raises(ConfigError) as info:  # before any map is built
        severity_probability(None, None, [0.0], [60.0], samples=samples)
    assert info.value.key == "samples" and repr(samples) in info.value.message


def test_fit_recordings_takes_one_name_as_a_string(tmp_path):
    """A string is one parameter name, not its letters ('unknown parameter 'f'')."""
    from torsio.calibration.fit import fit_recordings

    record = tmp_path / "rig.csv"
    record.write_text("time,top_rpm,surface_torque\n0,0,0\n1,30,5000\n2,60,8000\n", "utf-8")
    with pytest.raises(ConfigError) as info:
        fit_recordings(deviated_well_config(), [record], "friction_dinamic")
    assert "friction_dinamic" in info.value.message
    assert "'f'" not in info.value.message
