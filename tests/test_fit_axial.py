"""A fit of a file with axial dynamics: its torsional model, the bit off bottom
(Config.off_bottom; docs/calibration.md, "A file with axial dynamics").

The recordings: the built-in RGD deviated well (torsio.examples.rgd_deviated_well_config)
with open-hole friction mu_s 0.33, mu_d 0.27 (the truth; the file says 0.35/0.3), 40 s
start-ups off bottom to 120 and 150 rpm by a SoftTorque top drive (J = 2900 kg m^2, set
speed ramped over 5 s), made by the wave model on a grid other than the fit's: a time step
of 2.5e-4 s (the fit's default for this string: 3.9e-3 s; contacts on every node in both),
sampled every 0.01 s, with 1.5 % Gaussian noise on the torque and 1 % on the speed.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from torsio.analysis.wave import wave_response
from torsio.calibration.fit import fit_recordings
from torsio.calibration.parameters import SystemFamily
from torsio.calibration.recording import Recording
from torsio.cli import main
from torsio.errors import ConfigError
from torsio.examples import data_text, deviated_well_config, rgd_deviated_well_config
from torsio.model.wave import equivalent_alpha
from torsio.physics.top_drives import SoftTorqueTopDrive

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

TRUTH = {"friction_static": 0.33, "friction_dynamic": 0.27}
NAMES = ["friction_static", "friction_dynamic"]


def _startup(rpm: float) -> Recording:
    family = SystemFamily(rgd_deviated_well_config().off_bottom(), time_step=2.5e-4, drag_spacing=1)
    system = family.system(TRUTH).with_top(SoftTorqueTopDrive(inertia=2900.0, ramp=5.0))
    run = wave_response(
        system.at(wob=0.0, rpm=rpm),
        duration=40.0,
        steady_window=4.0,
        output_step=0.01,
        progress=False,
    ).transient
    return Recording.from_transient(
        run, torque_noise=0.015, speed_noise=0.01, seed=2 + int(rpm), name=f"{rpm:g}rpm.csv"
    )


@pytest.fixture(scope="module")
def recordings():
    return [_startup(rpm) for rpm in (120.0, 150.0)]


def test_off_bottom_the_torsional_model_is_the_axial_chain_with_its_contacts():
    # the exactness off_bottom rests on: the same chain (inertias, springs) and, at wob 0,
    # every node's Coulomb capacity equal to the axial contacts' F r (the cone's whole
    # capacity turns the string when it does not slide axially)
    config = rgd_deviated_well_config()
    system = config.off_bottom().system().at(wob=0.0)
    chain = config.axial.assembly
    np.testing.assert_allclose(system.model.inertia, chain.inertia, rtol=1e-14)
    np.testing.assert_allclose(system.model.springs, chain.springs, rtol=1e-14)
    contacts = config.axial.contacts.at_wob(0.0)
    for torsional, axial in (
        (system.model.contacts.static, contacts.static_force),
        (system.model.contacts.dynamic, contacts.sliding_force),
    ):
        np.testing.assert_allclose(torsional, axial * contacts.radius, rtol=1e-13, atol=1e-9)
    assert float(system.law.torque(5.0, 0.0, system.bit_radius)) == 0.0  # off bottom


def test_the_fit_reads_the_truth_of_recordings_made_on_another_grid(recordings):
    counted: list[int] = []
    results = fit_recordings(rgd_deviated_well_config(), recordings, NAMES, progress=counted.append)
    assert sum(counted) == results.runs  # every run of the fit and its twins counted once
    assert "the bit off bottom" in results.model
    fitted = results.parameters
    # the acceptance of tests/test_fit_independent.py (issue 38): mu_d within 0.01, mu_s
    # within 0.05, and every stated two-sigma interval holds the truth
    assert abs(fitted["friction_dynamic"] - TRUTH["friction_dynamic"]) < 0.01
    assert abs(fitted["friction_static"] - TRUTH["friction_static"]) < 0.05
    for name, spread in zip(results.names, results.uncertainty, strict=True):
        low, high = spread.interval
        assert low <= TRUTH[name] <= high, (name, spread)


def test_the_wave_model_carries_beta_as_the_alpha_of_its_first_mode_damping_ratio():
    # Rayleigh damping gives mode 1 the ratio (alpha / w1 + beta w1) / 2; alpha + beta w1^2
    # alone gives it the same (model.wave.equivalent_alpha); the file's beta is 0.01 s
    family = SystemFamily(rgd_deviated_well_config(), axial_off_bottom=True)
    omega = family.base.model.first_frequency()
    damping = family.system({"alpha": 0.1}).damping
    assert damping.beta == 0.0
    assert damping.alpha == pytest.approx(0.1 + 0.01 * omega**2, rel=1e-12)
    assert family.beta_alpha == equivalent_alpha(0.0, 0.01, omega)
    assert "beta 0.01 s as alpha" in family.description
    # a lumped strategy keeps beta; its continuum twin (the wave model) carries it as alpha
    lumped = SystemFamily(rgd_deviated_well_config(), axial_off_bottom=True, strategy="C")
    assert lumped.system({}).damping.beta == 0.01
    assert lumped.continuum().system({}).damping.beta == 0.0


def test_a_file_without_beta_runs_the_wave_model_as_before():
    family = SystemFamily(deviated_well_config())  # [damping] alpha only
    assert family.beta_alpha == 0.0
    assert family.system({}).damping == family.base.damping
    assert "as alpha" not in family.description


def test_on_bottom_is_refused_by_key_on_a_file_with_axial_dynamics(recordings):
    with pytest.raises(ConfigError, match="wob: 10000 N on a configuration with axial"):
        fit_recordings(rgd_deviated_well_config(), recordings, NAMES, wob=1e4)
    # the systems at a weight on bit (severity maps of a fit's draws) refuse such a file
    with pytest.raises(ConfigError, match="bit_rock.law: these systems are torsional"):
        SystemFamily(rgd_deviated_well_config())


def test_torsio_fit_on_the_built_in_rgd_deviated_well(recordings, tmp_path, capsys):
    source = tmp_path / "rgd_deviated_well.toml"
    source.write_text(data_text("rgd_deviated_well"))
    paths = []
    for record in recordings:
        record.save(tmp_path / record.name)
        paths += ["--recording", str(tmp_path / record.name)]
    argv = ["fit", str(source), *paths, "--fit", "friction_dynamic", "--no-profile", "--json"]
    assert main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["parameters"]["friction_dynamic"] == pytest.approx(0.27, abs=0.01)  # TRUTH
    assert data["model"].startswith("wave model")
