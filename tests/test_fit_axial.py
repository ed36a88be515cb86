"""A fit of a file with axial dynamics: its torsional model, the bit off bottom
(Config.off_bottom; docs/calibration.md, "A file with axial dynamics").

Two sets of recordings of the built-in RGD deviated well (torsio.examples.
rgd_deviated_well_config), 40 s start-ups off bottom to 120 and 150 rpm by a SoftTorque top
drive (J = 2900 kg m^2, set speed ramped over 5 s), sampled every 0.01 s, with 1.5 %
Gaussian noise on the torque and 1 % on the speed:

* made by the wave model on a grid other than the fit's (a time step of 2.5e-4 s against
  the fit's 3.9e-3 s; contacts on every node in both), open hole mu_s 0.33, mu_d 0.27;
* made by another model, the file's own axial chain (strategy C, 24 nodes of at most 100 m,
  its [damping] beta 0.01 s dampers, compiled RODAS4), open hole mu_s 0.35 (the file's),
  mu_d 0.27.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from startups import soft_torque_top, wave_startup

from torsio.analysis.transient import simulate
from torsio.calibration.fit import fit_recordings
from torsio.calibration.parameters import SystemFamily
from torsio.calibration.recording import Recording
from torsio.cli import main
from torsio.errors import ConfigError
from torsio.examples import data_text, rgd_deviated_well_config, rgd_wave_pipe_config

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

TRUTH = {"friction_static": 0.33, "friction_dynamic": 0.27}
NAMES = ["friction_static", "friction_dynamic"]
SPEEDS = (120.0, 150.0)  # rpm


NOISE = (0.015, 0.01)  # relative, on the torque and on the speed


def _record(run, rpm: float) -> Recording:
    torque_noise, speed_noise = NOISE
    return Recording.from_transient(
        run, torque_noise=torque_noise, speed_noise=speed_noise, seed=2 + int(rpm),
        name=f"{rpm:g}rpm.csv",
    )  # fmt: skip


@pytest.fixture(scope="module")
def recordings():
    family = SystemFamily(rgd_deviated_well_config(), fit=True, time_step=2.5e-4, drag_spacing=1)
    system = family.system(TRUTH)
    return [
        wave_startup(system, rpm, 40.0, 2 + int(rpm), f"{rpm:g}rpm.csv", NOISE) for rpm in SPEEDS
    ]


def test_off_bottom_the_torsional_model_is_the_axial_chain_with_its_contacts():
    # on the file's discretization: the same chain (inertias, springs, beta dampers) and, at
    # wob 0, every node's Coulomb capacity equal to the axial contacts' F r (the cone's
    # whole capacity turns the string when it does not slide axially)
    config = rgd_deviated_well_config()
    system = config.off_bottom().system()
    assert system.wob == 0.0
    chain = config.axial.assembly
    np.testing.assert_allclose(system.model.inertia, chain.inertia, rtol=1e-14)
    np.testing.assert_allclose(system.model.springs, chain.springs, rtol=1e-14)
    np.testing.assert_allclose(system.model.springs * 0.01, chain.dampers, rtol=1e-14)
    contacts = config.axial.contacts.at_wob(0.0)
    for torsional, axial in (
        (system.model.contacts.static, contacts.static_force),
        (system.model.contacts.dynamic, contacts.sliding_force),
    ):
        np.testing.assert_allclose(torsional, axial * contacts.radius, rtol=1e-13, atol=1e-9)
    assert float(system.law.torque(5.0, 0.0, system.bit_radius)) == 0.0  # off bottom


def test_a_distributed_pipe_keeps_its_rigid_bha_off_bottom():
    # the axial pipe's BHA is rigid (config/axial_string.py); its torsional model's too
    config = rgd_wave_pipe_config()
    assert config.off_bottom().model().rigid_bha
    assert config.off_bottom().model().bit_inertia == config.axial.assembly.bit_inertia


def test_the_fit_reads_the_truth_of_recordings_made_on_another_grid(recordings):
    counted: list[int] = []
    results = fit_recordings(rgd_deviated_well_config(), recordings, NAMES, progress=counted.append)
    assert sum(counted) == results.runs  # every run of the fit and its twins counted once
    assert "the bit off bottom" in results.model
    fitted = results.parameters
    # the acceptance of tests/test_fit_independent.py (issue 38): mu_d within 0.01 and its
    # stated two-sigma interval holding the truth, mu_s within 0.05. On this string's
    # default grid (3.9e-3 s) mu_s reads 0.319 for 0.33 and its stated interval (+-0.003)
    # misses the truth: the grid twins do not see that bias (docs/calibration.md, "A file
    # with axial dynamics"); on a grid of 2e-3 s it holds (the next test)
    assert abs(fitted["friction_dynamic"] - TRUTH["friction_dynamic"]) < 0.01
    assert abs(fitted["friction_static"] - TRUTH["friction_static"]) < 0.05
    low, high = results.uncertainty[1].interval
    assert low <= TRUTH["friction_dynamic"] <= high
    # and the fit says so: its own profile of mu_s is least 0.002 from the fitted value,
    # more than the stated sigma (0.0014), where the interval misses the truth
    rough = [w for w in results.warnings if w.startswith("friction_static: its profile")]
    assert rough and "fit on a finer grid" in rough[0]


def test_on_a_finer_grid_the_intervals_hold_the_truth(recordings):
    # half the default step (1.97e-3 s): its coarser twin is the default grid, which reads
    # mu_s 0.005 lower, and the discretization part widens the interval to hold 0.33
    results = fit_recordings(rgd_deviated_well_config(), recordings, NAMES, time_step=2e-3)
    assert results.uncertainty[0].sigma_grid > 0.003
    assert not any("its profile is least" in w for w in results.warnings)
    for name, spread in zip(results.names, results.uncertainty, strict=True):
        low, high = spread.interval
        assert low <= TRUTH[name] <= high, (name, spread)


def test_the_sliding_factor_of_recordings_made_by_the_axial_chain():
    # the chain the axial engine runs (its beta dampers included) makes the records; the
    # fit (the wave model, without beta) reads mu_d from the sliding torque, which neither
    # the lumping (node capacities that add up to the well's) nor Kelvin-Voigt damping
    # (no torque in steady rotation) moves. mu_s is the file's 0.35 in both and not
    # fitted: the chain's break-over peak is its lumping's (docs/calibration.md)
    config = rgd_deviated_well_config()
    truth = {"friction_dynamic": 0.27}
    chain = SystemFamily(config, fit=True, strategy="C").system(truth).with_top(soft_torque_top())
    assert chain.damping.beta == 0.01  # a lumped strategy keeps the file's dampers
    records = [
        _record(simulate(chain.at(wob=0.0, rpm=rpm), duration=40.0, output_step=0.01), rpm)
        for rpm in SPEEDS
    ]
    results = fit_recordings(config, records, ["friction_dynamic"], profile=False)
    assert results.parameters["friction_dynamic"] == pytest.approx(0.27, abs=0.005)


def test_the_fit_leaves_beta_out_of_the_wave_model_and_says_so():
    family = SystemFamily(rgd_deviated_well_config(), fit=True)  # [damping] beta = 0.01 s
    assert family.beta_left_out == 0.01
    assert family.system({}).damping.beta == 0.0
    assert "without [damping] beta 0.01 s" in family.description
    # a lumped fit keeps beta; its continuum twin (the wave model) leaves it out
    lumped = SystemFamily(rgd_deviated_well_config(), fit=True, strategy="C")
    assert lumped.system({}).damping.beta == 0.01
    assert lumped.continuum().system({}).damping.beta == 0.0


def test_alpha_is_not_fittable_on_a_file_with_axial_dynamics():
    family = SystemFamily(rgd_deviated_well_config(), fit=True)
    assert "alpha" not in family.names
    with pytest.raises(ConfigError, match="fit: alpha: a file with axial dynamics takes"):
        family.check(["friction_dynamic", "alpha"])


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
    assert main([*argv, "--time-step", "2ms"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["parameters"]["friction_dynamic"] == pytest.approx(0.27, abs=0.01)  # TRUTH
    assert data["model"].startswith("wave model, time step 0.00197 s")  # 2 ms fitted to L/c
