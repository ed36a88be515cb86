"""S_SS, ω₁ and the run-time defaults: one definition read by every engine.

References: S_SS = (max Ω_b − min Ω_b) / (2 Ω) is Eq. 12 of the paper; ω₁ of one node on a
spring to a held top is √(k/I) (exact); the default run is 40 and the window 15 periods
2π/ω₁ (torsio.analysis.severity, the paper gives neither).
"""

from __future__ import annotations

import math

import pytest

from torsio.analysis.severity import (
    DEFAULT_DURATION_PERIODS,
    DEFAULT_WINDOW_PERIODS,
    run_times,
    severity_of_extremes,
)
from torsio.axial.assembly import rgd_two_dof_example
from torsio.axial.rgd import rgd_example
from torsio.axial.transient import simulate_axial
from torsio.errors import ConfigError

# the RGD 2-DOF example (docs/axial.md): I = 455.65 kg m², k = 324.857 N m/rad
INERTIA, STIFFNESS = 455.65, 324.857


def test_s_ss_is_eq_12_for_floats_and_arrays():
    # Eq. 12 of the paper: half the bit speed's range over the surface speed
    import numpy as np

    assert severity_of_extremes(15.0, 5.0, 10.0) == 0.5
    values = severity_of_extremes(np.array([12.0, 20.0]), np.array([8.0, 0.0]), 10.0)
    assert values.tolist() == [0.2, 1.0]


def test_an_axial_run_reads_s_ss_with_eq_12_from_its_own_extremes():
    # Eq. 12 of the paper on the run's reported extremes, Ω the set speed of 60 rpm
    run = simulate_axial(rgd_two_dof_example(), rgd_example(), 100e3, 60.0, duration=40.0)
    data = run.to_dict()
    omega = 60.0 * 2.0 * math.pi / 60.0
    expected = (data["bit_speed_max"] - data["bit_speed_min"]) / (2.0 * omega)
    assert run.severity == pytest.approx(expected, rel=1e-12)


def test_an_axial_assembly_has_the_first_frequency_and_run_times_of_every_model():
    # one node on a spring to the held top: ω₁ = √(k/I) exactly; the defaults 40 and 15
    # periods of it, the window at most half a given run (torsio.analysis.severity)
    assembly = rgd_two_dof_example()
    omega1 = math.sqrt(STIFFNESS / INERTIA)
    assert assembly.first_frequency() == pytest.approx(omega1, rel=1e-12)
    period = 2.0 * math.pi / omega1
    expected = (DEFAULT_DURATION_PERIODS * period, DEFAULT_WINDOW_PERIODS * period)
    assert run_times(assembly) == pytest.approx(expected, rel=1e-12)
    assert run_times(assembly, 60.0) == (60.0, 30.0)


@pytest.mark.parametrize(
    ("duration", "window", "key"),
    [(2.0, 3.0, "simulation.steady_window"), (-2.0, 1.0, "simulation.duration")],
)
def test_an_axial_run_checks_its_times_as_every_run(duration, window, key):
    # the axial engine checked 0 < window <= duration on its own and named the window for a
    # bad duration; the one check names the key that is wrong
    with pytest.raises(ConfigError) as info:
        simulate_axial(
            rgd_two_dof_example(), rgd_example(), 100e3, 60.0, duration=duration, window=window
        )
    assert info.value.key == key
