"""Results that say what limits their meaning (issue 21, case 7 and the short window).

A bit stuck throughout the steady window gives S_SS near 0 (the bit speed does not
swing), which the classification by S_SS would call "stable". At 1e9 N on the Ritto
et al. (2017) string the Tucker-Wang torque to break the bit free is of order
R W a0 = 0.108 m x 1e9 N x 0.221 = 2.4e7 N m, while the 1-DOF string (strategy A,
k = 324.9 N m/rad) turned at 60 rpm for the default 298 s stores at most
k Omega t = 324.9 x 6.283 x 298 = 6.1e5 N m: the bit cannot break free in the run, so the
stick fraction must be exactly 1.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from torsio.analysis.limits import short_window, stuck_throughout
from torsio.analysis.map_results import load_map
from torsio.analysis.maps import severity_map
from torsio.analysis.severity import first_natural_frequency
from torsio.analysis.transient import simulate
from torsio.cli import main
from torsio.examples import builtin_config


@pytest.fixture(scope="module")
def one_dof():
    return builtin_config().system(strategy="A")


def test_stuck_bit_is_said_in_results_and_json(one_dof):
    results = simulate(one_dof.at(wob=1e9, rpm=60))
    assert results.stick_fraction == 1.0  # the bound in the module docstring
    assert results.warnings == (stuck_throughout(1.0, results.stick_threshold),)
    assert results.to_dict()["warnings"] == list(results.warnings)


def test_stuck_bit_through_the_cli(capsys):
    status = main(["simulate", "--strategy", "A", "--wob", "1e9", "--rpm", "60", "--json"])
    captured = capsys.readouterr()
    assert status == 0
    data = json.loads(captured.out)  # stdout stays one JSON object
    assert data["stick_fraction"] == 1.0
    assert "stuck throughout the steady window" in data["warnings"][0]
    assert "torsio simulate: warning: the bit is stuck throughout" in captured.err


def test_a_steady_point_carries_no_warning(one_dof):
    results = simulate(one_dof.at(wob=100e3, rpm=100))
    assert results.warnings == ()


def test_window_shorter_than_a_period_is_said(one_dof):
    # the 1-DOF model's first period 2 pi / omega_1 = 2 pi sqrt(J / k) = 7.44 s
    results = simulate(one_dof.at(wob=100e3, rpm=100), duration=30.0, steady_window=2.0)
    period = 2 * np.pi / first_natural_frequency(one_dof)
    assert period == pytest.approx(7.4413, abs=1e-4)
    assert results.warnings == (short_window(2.0, period),)


def test_map_classifies_stuck_points_and_warns(one_dof):
    result = severity_map(one_dof, wob=[100e3, 1e9], rpm=[60.0], refine=0)
    assert result.stuck.tolist() == [[False, True]]
    assert result.classification()[0, 1] == "stuck"
    assert result.counts()["stuck"] == 1
    assert len(result.warnings) == 1 and "1 of 2 points" in result.warnings[0]
    data = result.to_dict()
    assert data["stuck"] == [[False, True]] and data["warnings"] == list(result.warnings)


@pytest.mark.parametrize("suffix", [".json", ".npz"])
def test_stuck_flags_survive_save_and_load(one_dof, tmp_path, suffix):
    result = severity_map(one_dof, wob=[100e3, 1e9], rpm=[60.0], refine=0)
    loaded = load_map(result.save(tmp_path / f"map{suffix}"))
    assert loaded.stuck.tolist() == result.stuck.tolist()
    assert loaded.classification().tolist() == result.classification().tolist()


@pytest.mark.parametrize(
    ("flag", "named", "shortest"),
    # 10 samples of the default step, 1/200 of the 7.4413 s period: 0.372 s (a run: twice)
    [
        ("--window", "--window (simulation.steady_window)", "0.372066 s"),
        ("--duration", "--duration (simulation.duration)", "0.744131 s"),
    ],
)
def test_too_short_a_window_names_what_was_given(capsys, flag, named, shortest):
    status = main(["simulate", "--strategy", "A", "--wob", "100kN", "--rpm", "60", flag, "1e-6"])
    err = capsys.readouterr().err
    assert status == 2
    assert f"error: {named}:" in err and shortest in err and "Traceback" not in err
