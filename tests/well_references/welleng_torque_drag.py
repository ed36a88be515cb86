"""Torque and drag of the built-in deviated well by welleng (jonnymaserati/welleng), the
peer-library reference of tests/test_well_peer.py. Not run by the test suite: welleng is
not a dependency of torsio (its requirements include pandas, pyproj, pydantic, openpyxl).

Reproduce in a throw-away virtualenv::

    python -m venv /tmp/venv-welleng && /tmp/venv-welleng/bin/pip install welleng==0.30.0
    PYTHONPATH=src python tests/well_references/welleng_torque_drag.py stations /tmp/s.csv
    /tmp/venv-welleng/bin/python tests/well_references/welleng_torque_drag.py run /tmp/s.csv

The first step writes the survey of ``data/deviated_well.toml`` resampled every metre along
torsio's minimum-curvature arcs (so that welleng's one-cell-per-interval scheme and
torsio's integration see the same hole); the second prints welleng's hookloads and
surface torque for one uniform pipe (the 5 in drill pipe over the whole string) in mud.
"""

from __future__ import annotations

import json
import math
import sys

OD, ID = 0.127, 0.1086144  # m: 5 in x 4.276 in
STEEL_SG, MUD_SG = 7.85, 1.2
MU = 0.3
GRAVITY = 9.80665
LENGTH = 2500.0
STEP = 1.0  # m, the resampling of the survey


def stations(path: str) -> None:
    import numpy as np

    from torsio.examples import deviated_well_config

    survey = deviated_well_config().well.survey
    md = np.linspace(0.0, LENGTH, int(LENGTH / STEP) + 1)
    inc, azi = np.degrees(survey.inclination(md)), np.degrees(np.nan_to_num(survey.azimuth(md)))
    with open(path, "w", encoding="utf-8") as file:
        file.write("md,inclination,azimuth\n")
        for row in zip(md, inc, azi, strict=True):
            file.write(",".join(repr(float(x)) for x in row) + "\n")


def run(path: str) -> None:
    import numpy as np
    from welleng.architecture import BHA, WellBore
    from welleng.survey import Survey, SurveyHeader
    from welleng.torque_drag import TorqueDrag

    md, inc, azi = np.loadtxt(path, delimiter=",", skiprows=1, unpack=True)
    survey = Survey(md=md, inc=inc, azi=azi, header=SurveyHeader(azi_reference="grid"))
    hole = WellBore("hole", 0.0, LENGTH, method="bottom_up")
    hole.add_section(id=0.2159, coeff_friction_sliding=MU, length=LENGTH)
    pipe = BHA("pipe", 0.0, LENGTH, method="bottom_up")
    weight = GRAVITY * STEEL_SG * 1000.0 * math.pi / 4.0 * (OD**2 - ID**2)  # N/m in air
    pipe.add_section(od=OD, id=ID, unit_weight=weight, density=STEEL_SG, length=LENGTH)
    td = TorqueDrag(survey, hole, pipe, fluid_density=MUD_SG)
    print(json.dumps({
        "hookload_trip_out": float(td.tension["pickup"][0]),
        "hookload_trip_in": float(td.tension["slackoff"][0]),
        "hookload_rotating": float(td.tension["rotating"][0]),
        "surface_torque_rotating": float(td.torque["rotating"][0]),
    }, indent=1))  # fmt: skip


if __name__ == "__main__":
    {"stations": stations, "run": run}[sys.argv[1]](sys.argv[2])
