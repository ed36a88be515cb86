"""The string hangs from the rig floor (issue 37, item 1): top at md 0, bit at its length.

A survey deeper than the string adds open hole below the bit, which carries nothing: the
break-off torque and twist and the torque-and-drag table are those of the survey ending at
the bit (the same hole above it; minimum curvature between the same stations). A survey
shorter than the string is an error naming ``md``.
"""

from __future__ import annotations

import attrs
import numpy as np
import pytest

from torsio.errors import ConfigError
from torsio.examples import deviated_well_config
from torsio.well import Survey
from torsio.well.break_off import break_off
from torsio.well.torque_drag import torque_drag


def _deeper(survey: Survey, extra: float) -> Survey:
    """The same stations and one more ``extra`` m below, straight on (the last tangent)."""
    md = np.append(survey.md, survey.md[-1] + extra)
    inc = np.append(survey.inclination_deg, survey.inclination_deg[-1])
    azi = np.append(survey.azimuth_deg, survey.azimuth_deg[-1])
    return Survey(md, inc, azi)


def test_a_deeper_survey_changes_nothing_above_the_bit():
    config = deviated_well_config()  # a 2500 m string, its survey ending at 2500 m
    well, string = config.well, config.string
    deeper = attrs.evolve(well, survey=_deeper(well.survey, 100.0))
    for wob in (0.0, 80e3):
        a, b = break_off(well, string, 10.0, wob), break_off(deeper, string, 10.0, wob)
        assert b.torque == pytest.approx(a.torque, rel=1e-3)
        assert b.twist == pytest.approx(a.twist, rel=1e-3)
    a = torque_drag(well, string, wob=80e3, bit_torque=4e3)
    b = torque_drag(deeper, string, wob=80e3, bit_torque=4e3)
    assert a.bit_md == b.bit_md == 2500.0 and b.string_top_md == 0.0
    np.testing.assert_allclose(b.md, a.md, rtol=1e-12)
    scale_t = np.abs(a.tension).max()
    scale_q = np.abs(a.torque).max()
    assert np.abs(b.tension - a.tension).max() < 1e-3 * scale_t
    assert np.abs(b.torque - a.torque).max() < 1e-3 * scale_q


def test_a_survey_shorter_than_the_string_names_md():
    config = deviated_well_config()
    survey = config.well.survey
    short = Survey(
        survey.md[:-1], survey.inclination_deg[:-1], survey.azimuth_deg[:-1]
    )  # to 2300 m
    with pytest.raises(ConfigError, match=r"^md: the string is 2500 m long but the survey"):
        torque_drag(attrs.evolve(config.well, survey=short), config.string)
