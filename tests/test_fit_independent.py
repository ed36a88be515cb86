"""A fit on recordings that the fitted model did not make (issue 38; docs/calibration.md).

The recordings: the built-in deviated well (torsio.examples.deviated_well_config) with open
hole friction mu_s 0.33, mu_d 0.22 (the truth), 60 s start-ups to 120 and 150 rpm by a
SoftTorque top drive (J = 2900 kg m^2, set speed ramped over 5 s), made by the wave model
on a grid other than the fit's: a time step of 2.5e-4 s (the fit's 6.9e-4 s; contacts on
every node), sampled
every 0.01 s, with 1.5 % Gaussian noise on the torque and 1 % on the speed. The fit holds
the top at the recorded speed (its own model of the top, not the SoftTorque that made the
records) and starts from three different configurations.
"""

from __future__ import annotations

import attrs
import numpy as np
import pytest
from startups import wave_startup

from torsio.calibration.fit import fit_recordings
from torsio.calibration.parameters import SystemFamily
from torsio.calibration.recording import Recording
from torsio.examples import deviated_well_config

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

TRUTH = {"friction_static": 0.33, "friction_dynamic": 0.22}
NAMES = ["friction_static", "friction_dynamic"]
STARTS = ((0.2, 0.15), (0.4, 0.3), (0.25, 0.12))  # the three starts (mu_s, mu_d)


def _startup(rpm: float) -> Recording:
    family = SystemFamily(deviated_well_config(), time_step=2.5e-4, drag_spacing=1)
    return wave_startup(
        family.system(TRUTH), rpm, 60.0, 2 + int(rpm), f"{rpm:g}rpm.csv", (0.015, 0.01)
    )


@pytest.fixture(scope="module")
def recordings():
    return [_startup(rpm) for rpm in (120.0, 150.0)]


def _fit(recordings, start):
    config = deviated_well_config()
    well = attrs.evolve(config.well, friction_static=start[0], friction_dynamic=start[1])
    return fit_recordings(attrs.evolve(config, well=well), recordings, NAMES)


@pytest.fixture(scope="module")
def first_fit(recordings):
    return _fit(recordings, STARTS[0])


def _holds_the_truth(results):
    fitted = results.parameters
    assert abs(fitted["friction_dynamic"] - TRUTH["friction_dynamic"]) < 0.01  # issue 38
    assert abs(fitted["friction_static"] - TRUTH["friction_static"]) < 0.05
    for name, spread in zip(results.names, results.uncertainty, strict=True):
        low, high = spread.interval  # the stated two sigma
        assert low <= TRUTH[name] <= high, (name, spread)
        assert spread.identifiable


def test_the_intervals_hold_the_truth_of_recordings_made_on_another_grid(first_fit):
    _holds_the_truth(first_fit)
    assert first_fit.warnings == ()  # no rough misfit said where the intervals hold


@pytest.mark.slow  # two more fits of the same recordings (about 3.5 min on 2 cores)
def test_three_starts_agree_within_their_stated_sigma(recordings, first_fit):
    fits = [first_fit, *(_fit(recordings, start) for start in STARTS[1:])]
    for results in fits[1:]:
        _holds_the_truth(results)
    for k, name in enumerate(NAMES):
        values = np.array([r.values[k] for r in fits])
        sigma = min(r.uncertainty[k].sigma for r in fits)
        assert np.ptp(values) <= sigma, (name, values, sigma)


def test_the_sigma_says_what_it_is_made_of(first_fit):
    spread = first_fit.uncertainty[0]
    parts = first_fit.to_dict()["uncertainty_parts"]["friction_static"]
    assert set(parts) == {"statistical", "recordings", "grid", "speed_record", "recording_values"}
    # the stated sigma is its parts in quadrature (docs/calibration.md)
    total = np.hypot.reduce([parts["statistical"], parts["recordings"], parts["grid"],
                             parts["speed_record"]])  # fmt: skip
    assert spread.sigma == pytest.approx(total, rel=1e-9)
    assert len(parts["recording_values"]) == 2
