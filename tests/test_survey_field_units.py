"""A survey in feet with unit headers gives the same torque and drag as in metres (issue 37,
item 6). 1 ft = 0.3048 m exactly (NIST SP 811, appendix B.8): the feet file holds md / 0.3048,
so both files describe the same hole and every result agrees to rounding (1e-9)."""

from __future__ import annotations

import re
from importlib import resources

import numpy as np
import pytest

from torsio.config.reading import load_config
from torsio.well.torque_drag import torque_drag

FT = 0.3048


def _config_with_survey(tmp_path, name: str, header: str, md_factor: float):
    text = resources.files("torsio").joinpath("data/deviated_well.toml").read_text("utf-8")
    md = [float(v) for v in re.search(r"^md = \[(.*?)\]", text, re.M)[1].split(",")]
    inc = [float(v) for v in re.search(r"^inclination = \[(.*?)\]", text, re.M)[1].split(",")]
    azi = [float(v) for v in re.search(r"^azimuth = \[(.*?)\]", text, re.M)[1].split(",")]
    rows = "\n".join(f"{m * md_factor!r},{i},{a}" for m, i, a in zip(md, inc, azi, strict=True))
    (tmp_path / f"{name}.csv").write_text(f"{header}\n{rows}\n", "utf-8")
    text = re.sub(r"^(md|inclination|azimuth) = .*$", "", text, flags=re.M)
    text = text.replace("[well]\n", f'[well]\nsurvey = "{name}.csv"\n', 1)
    path = tmp_path / f"{name}.toml"
    path.write_text(text, "utf-8")
    return load_config(path)


@pytest.mark.parametrize("header", ["MD (ft),Inc (deg),Azi (deg)", "md[ft],Incl,Azim"])
def test_feet_survey_gives_the_metric_results(tmp_path, header):
    metric = _config_with_survey(tmp_path, "metres", "md,inclination,azimuth", 1.0)
    field = _config_with_survey(tmp_path, "feet", header, 1.0 / FT)
    expected = torque_drag(metric.well, metric.string, wob=80e3).to_dict()
    got = torque_drag(field.well, field.string, wob=80e3).to_dict()
    compared = 0
    for key, value in expected.items():
        if isinstance(value, float | list) and key != "source":
            np.testing.assert_allclose(got[key], value, rtol=1e-9, atol=1e-9, err_msg=key)
            compared += 1
    assert compared >= 7  # the DESIGN.md contract keys at least
    assert expected["hookload_rotating"] > 0.0
