"""Ending a run on its steady cycle (torsio.solvers.cycles) gives the S_SS of the whole run.

The reference of every check here is the same compiled integrator run to the end
(``steady_tolerance=0``): the early end must not move S_SS by more than the tolerance,
over a grid that crosses the stick-slip boundary, for 1 and 5 DOFs.
"""

from __future__ import annotations

import numpy as np
import pytest

from torsio.errors import ConfigError
from torsio.examples import builtin_config
from torsio.plugins import top_drive_from_parameters
from torsio.solvers import cycles
from torsio.solvers.batch import simulate_batch
from torsio.solvers.batch_results import DEFAULT_STEADY_TOLERANCE

DURATION, WINDOW = 300.0, 100.0  # s: the benchmark's runs (40 first-mode periods)


def _grid(points: int) -> tuple[np.ndarray, np.ndarray]:
    wob, rpm = np.meshgrid(np.linspace(25e3, 225e3, points), np.linspace(40.0, 140.0, points))
    return wob.ravel(), rpm.ravel()


@pytest.mark.parametrize("strategy", [{"strategy": "A"}, {"strategy": "C", "dp_elements": 5}])
def test_ending_on_the_cycle_keeps_the_severity_of_the_whole_run(strategy: dict) -> None:
    system = builtin_config().system(**strategy)
    wob, rpm = _grid(9)
    whole = simulate_batch(
        system, wob, rpm, duration=DURATION, steady_window=WINDOW, steady_tolerance=0.0
    )
    early = simulate_batch(system, wob, rpm, duration=DURATION, steady_window=WINDOW)
    assert whole.ok.all() and early.ok.all()
    assert (whole.ended == DURATION).all()
    assert np.max(np.abs(early.severity - whole.severity)) <= DEFAULT_STEADY_TOLERANCE
    stick_slip = whole.severity > 0.8
    assert stick_slip.sum() >= 10  # the grid crosses the boundary: both kinds are checked
    # most stick-slip cycles are found within a few periods (7.4 s) of the start
    assert np.median(early.ended[stick_slip]) < 0.25 * DURATION
    assert early.steps.sum() < 0.5 * whole.steps.sum()


@pytest.mark.parametrize(
    ("strategy", "wob", "rpm"),
    [
        # the motion lingers on a stick-slip cycle for ten cycles, then leaves it for steady
        # rotation (a saddle cycle): the early end must not stop on it
        ({"strategy": "A"}, 95e3, 67.5),
        # a slowly converging cycle (the change shrinks by ~0.85 a cycle, 10 DOFs)
        ({"strategy": "C", "dp_elements": 10}, 90e3, 60.0),
    ],
)
def test_hard_points_keep_the_severity_of_the_whole_run(strategy: dict, wob: float, rpm: float):
    system = builtin_config().system(**strategy)
    whole = simulate_batch(
        system, [wob], [rpm], duration=DURATION, steady_window=WINDOW, steady_tolerance=0.0
    )
    early = simulate_batch(system, [wob], [rpm], duration=DURATION, steady_window=WINDOW)
    assert abs(early.severity[0] - whole.severity[0]) <= DEFAULT_STEADY_TOLERANCE


def test_a_torque_driven_top_runs_to_the_end() -> None:
    # its S_SS is relative to the mean top speed over the whole window
    system = builtin_config().system(strategy="A")
    top = top_drive_from_parameters("torque", inertia=930.0, torque=10e3, drag=425.0)
    result = simulate_batch(system.with_top(top), [60e3], None, duration=120.0, steady_window=40.0)
    assert result.steady_tolerance == 0.0
    assert (result.ended == 120.0).all()


@pytest.mark.parametrize("value", [-1e-3, 0.5, float("nan"), True])
def test_steady_tolerance_is_checked(value: float) -> None:
    system = builtin_config().system(strategy="A")
    with pytest.raises(ConfigError, match="steady_tolerance"):
        simulate_batch(system, [1e5], [60.0], steady_tolerance=value)


def test_the_crossing_of_a_cubic_is_found_to_round_off() -> None:
    # u(x) = (x - 0.3)(x + 1)(x + 2) = x^3 + 2.7 x^2 + 1.1 x - 0.6: u(0) = -0.6, u(1) = 4.2,
    # u'(0) = 1.1, u'(1) = 3 + 5.4 + 1.1 = 9.5; the one root in (0, 1) is x = 0.3
    u0, u1, d0, d1 = -0.6, 4.2, 1.1, 9.5
    assert cycles.upward_root(u0, u1, d0, d1) == pytest.approx(0.3, abs=1e-12)
    assert cycles.hermite(u0, u1, d0, d1, 0.5) == pytest.approx(0.125 + 0.675 + 0.55 - 0.6)
    # concave: Newton's iterates approach the root from one side only, the bracket's other
    # end stays put. u(x) = -x^2 + 2 x - 0.75: u(0) = -0.75, u(1) = 0.25, u'(0) = 2,
    # u'(1) = 0; root x = 0.5
    assert cycles.upward_root(-0.75, 0.25, 2.0, 0.0) == pytest.approx(0.5, abs=1e-12)
    # convex, the mirror case: u(x) = x^2 + x - 0.75, u'(0) = 1, u'(1) = 3; root x = 0.5
    assert cycles.upward_root(-0.75, 1.25, 1.0, 3.0) == pytest.approx(0.5, abs=1e-12)
