"""Maps over (weight on bit, rpm) of axial-torsional runs (torsio.axial.maps).

Reference: every point of a map is the single run of torsio.axial.transient.simulate_axial
with the same options (the same engine, so equal to round-off), and its growth rate the
rightmost root of torsio.axial.stability."""

from __future__ import annotations

import json
import time

import numpy as np
import pytest

from torsio.axial.assembly import pipe_assembly, rgd_two_dof_example
from torsio.axial.maps import axial_map
from torsio.axial.rgd import rgd_example
from torsio.axial.stability import drilling_stability
from torsio.axial.transient import simulate_axial
from torsio.errors import ConfigError

ASSEMBLY = rgd_two_dof_example()
BIT = rgd_example()
WOBS, RPMS = [90e3, 130e3, 170e3], [50.0, 120.0]


def test_every_point_of_the_map_is_the_single_run():
    grid = axial_map(ASSEMBLY, BIT, WOBS, RPMS, duration=30.0, window=15.0, growth_rate=True)
    assert grid.severity.shape == (len(RPMS), len(WOBS))  # severity[i][j] at rpm[i], wob[j]
    for i, rpm in enumerate(RPMS):
        for j, wob in enumerate(WOBS):
            run = simulate_axial(ASSEMBLY, BIT, wob, rpm, duration=30.0, window=15.0, samples=0)
            assert grid.severity[i, j] == pytest.approx(run.severity, rel=1e-12)
            assert grid.stick_fraction[i, j] == run.stick_fraction
            assert grid.off_bottom_fraction[i, j] == run.off_bottom_fraction
            assert grid.rop[i, j] == pytest.approx(run.rop_mean, rel=1e-12)
            assert grid.mse[i, j] == pytest.approx(run.mse_mean, rel=1e-12)
            assert grid.axial_severity[i, j] == pytest.approx(run.axial_severity, rel=1e-12)
            assert grid.growth_rate is not None
            rate = drilling_stability(ASSEMBLY, BIT, wob, rpm).growth_rate
            assert grid.growth_rate[i, j] == pytest.approx(rate, rel=1e-12)


def test_the_map_gives_design_keys_as_plain_json():
    grid = axial_map(ASSEMBLY, BIT, WOBS[:2], RPMS[:1], duration=10.0, window=5.0)
    data = json.loads(json.dumps(grid.to_dict()))
    for key in ("wob", "rpm", "severity", "rop", "mse", "stick_fraction", "off_bottom_fraction"):
        assert key in data
    assert np.shape(data["rop"]) == (1, 2)
    assert data["growth_rate"] is None


def test_the_growth_rate_is_refused_for_a_chain():
    chain = pipe_assembly(2, 900.0, 2.1e11, 8.1e10, 7850.0, 3.4e-3, 1.5e-5, 29981.3, 230.0)
    with pytest.raises(ConfigError, match="growth_rate"):
        axial_map(chain, BIT, WOBS[:1], RPMS[:1], duration=2.0, window=1.0, growth_rate=True)


@pytest.mark.slow
def test_a_21_by_21_map_of_the_2dof_model_takes_under_a_minute():
    axial_map(ASSEMBLY, BIT, [100e3], [60.0], duration=2.0, window=1.0)  # compiled, cached
    start = time.perf_counter()
    axial_map(ASSEMBLY, BIT, np.linspace(80e3, 200e3, 21), np.linspace(30.0, 200.0, 21))
    assert time.perf_counter() - start < 60.0
