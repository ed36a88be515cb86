"""The well as drilled: the survey (minimum curvature), hole sections and mud, and the
soft-string torque and drag of a drill-string in it, and the closed forms of its
break-off (the torque and twist at which a string lying in the hole breaks free).

Examples
--------
>>> from torsio.well import Survey, Wellbore
>>> well = Wellbore(Survey([0.0, 1000.0], [0.0, 0.0], [0.0, 0.0]), mud_density=1200.0)
>>> well.survey.depth
1000.0
"""

from __future__ import annotations

from torsio.well.break_off import BreakOff, break_off
from torsio.well.survey import Survey, tangent_vector
from torsio.well.survey_csv import read_survey_csv
from torsio.well.torque_drag import torque_drag
from torsio.well.torque_drag_results import TorqueDragResults
from torsio.well.wellbore import NORMAL_FORCE_MODELS, HoleSection, Wellbore, string_top_md

__all__ = [
    "NORMAL_FORCE_MODELS",
    "BreakOff",
    "HoleSection",
    "Survey",
    "TorqueDragResults",
    "Wellbore",
    "break_off",
    "read_survey_csv",
    "string_top_md",
    "tangent_vector",
    "torque_drag",
]
