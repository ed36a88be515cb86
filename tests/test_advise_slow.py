"""``-m slow``: the advice on the built-in RGD deviated well over its default region and with
the default runs (40 periods, the last 15 the window) against a fine brute-force map.

The reference is a 33 x 15 map (495 runs, WOB every 2 kN, rpm every 10) of the same region
with the same model, run by :func:`torsio.analysis.axial_maps.axial_map` (the engine of
``torsio map``); "not severe" is S_SS <= 0.8 (the paper's severe stick-slip, Eq. 12), read
from a run of the recommended point on its own.
"""

from __future__ import annotations

import numpy as np
import pytest

from torsio.advice import advise
from torsio.advice.region import default_region
from torsio.analysis.axial_maps import axial_map
from torsio.analysis.axial_transient import simulate_axial
from torsio.examples import rgd_deviated_well_config

THRESHOLD = 0.8


@pytest.mark.slow
def test_default_advice_against_a_fine_brute_force_map():
    config = rgd_deviated_well_config()
    axial = config.axial
    region = default_region(axial.bit)
    advice = advise(config, region, compare=False, threads=2)
    point = advice.recommended
    assert point is not None
    run = simulate_axial(
        axial.assembly,
        axial.bit,
        point["wob"],
        point["rpm"],
        samples=0,
        growth_rate=False,
        **axial.run_options(),
    )
    assert run.severity <= THRESHOLD
    fine = axial_map(
        axial.assembly,
        axial.bit,
        np.linspace(*region.wob, 33),
        np.linspace(*region.rpm, 15),
        threads=2,
        **axial.run_options(),
    )
    best = fine.rop[fine.severity <= THRESHOLD].max()
    assert point["rop"] >= 0.95 * best
    # measured: the search's 54 runs against the map's 495
    assert advice.window.runs < fine.severity.size / 5
