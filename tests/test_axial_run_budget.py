"""The axial engine refuses work beyond its budget before it allocates it (issue 36, case 4).

Budget: :func:`torsio.analysis.budget.most_fixed_steps` (2 000 000 steps and 5e10
node-steps, the wave runs' budget). The step counts that exceed it follow from the step
rule's closed form h = 2 pi / (omega_fast x steps_per_period), omega_fast the bit's contact
frequency sqrt(2 n zeta epsilon a / m_b) on the built-in 2-DOF file (about 557 rad/s for
m_b = 29 981.3 kg: h = 1.94 ms; 153 600 steps for its default run of 297.7 s).
"""

from __future__ import annotations

import re
from importlib import resources

import pytest

from torsio.analysis.budget import most_fixed_steps
from torsio.axial import rgd_example, rgd_two_dof_example, simulate_axial
from torsio.cli import main
from torsio.errors import ConfigError
from torsio.solvers import axial_run_setup as run_setup_module

EXAMPLE = resources.files("torsio").joinpath("data/rgd_2dof.toml").read_text(encoding="utf-8")


def _file(tmp_path, old, new):
    assert old in EXAMPLE
    path = tmp_path / "case.toml"
    path.write_text(EXAMPLE.replace(old, new, 1), encoding="utf-8")
    return str(path)


@pytest.fixture
def no_history(monkeypatch):
    """The history (the run's big array) must not be built: the refusal comes first."""

    def refuse(*args, **kwargs):
        raise AssertionError("the run's history was allocated before the budget check")

    monkeypatch.setattr(run_setup_module, "start_history", refuse)


CASES = [
    # (old text, new text, extra flags, key named)
    (
        'hook = "weight"',
        'hook = "weight"\nsteps_per_period = 1000000000',
        [],
        "axial.steps_per_period",
    ),
    (
        'hook = "weight"',
        'hook = "weight"\nsteps_per_period = 1000000',
        [],
        "axial.steps_per_period",
    ),
    ("perturbation = 1e-3", "perturbation = 1e-3\nstep = 1e-9", [], "simulation.step"),
    ("perturbation = 1e-3", "perturbation = 1e-3\nstep = 1e-6", [], "simulation.step"),
    ("masses = [29981.3]", "masses = [1e-6]", [], "bit_rock"),
    ("masses = [29981.3]", "masses = [1e-2]", [], "bit_rock"),
    ('intrinsic_specific_energy = "60 MPa"', "intrinsic_specific_energy = 1e300", [], "bit_rock"),
    ('intrinsic_specific_energy = "60 MPa"', "intrinsic_specific_energy = 1e16", [], "bit_rock"),
    ("rpm = 60", "rpm = 60", ["--duration", "1e7"], "simulation.duration"),
    ("rpm = 60", "rpm = 60", ["--duration", "1e5"], "simulation.duration"),
    ("rpm = 60", "rpm = 60", ["--duration", "1e-9"], "simulation.duration"),
    ("rpm = 60", "rpm = 60", ["--duration", "1e-4"], "simulation.duration"),
    ("rpm = 60", "rpm = 60", ["--rpm", "0.001"], "operation.rpm"),
    ("rpm = 60", "rpm = 60", ["--rpm", "0.005"], "operation.rpm"),
]


@pytest.mark.parametrize(("old", "new", "flags", "key"), CASES)
def test_work_beyond_the_budget_is_refused_by_key(
    capsys, tmp_path, no_history, old, new, flags, key
):
    status = main(["simulate", _file(tmp_path, old, new), *flags, "--json"])
    captured = capsys.readouterr()
    assert status == 2 and captured.out == ""
    assert key in captured.err and "Traceback" not in captured.err


def test_the_refusal_states_the_budget(capsys, tmp_path):
    # 1e7 s / 1.938 ms = 5.16e9 steps > 2e6 (the budget); at most 2e6 x 1.938 ms = 3876 s
    status = main(["simulate", _file(tmp_path, "rpm = 60", "rpm = 60"), "--duration", "1e7"])
    err = capsys.readouterr().err
    assert status == 2 and "5.16e+09 steps" in err
    longest = float(re.search(r"at most (\d+) s", err).group(1))
    assert longest == pytest.approx(most_fixed_steps(2) * 0.001938, rel=1e-3)


def test_a_run_within_the_budget_runs():
    # 2e6 steps x 1.938 ms (the step rule's h, module docstring) = 3876 s; 20 s is 10 320 steps
    run = simulate_axial(
        rgd_two_dof_example(), rgd_example(), 100e3, 60.0, duration=20.0, window=10.0,
        growth_rate=False,
    )  # fmt: skip
    assert run.duration == 20.0


def test_the_python_api_refuses_by_key_too(no_history):
    with pytest.raises(ConfigError, match="simulation.step"):
        simulate_axial(rgd_two_dof_example(), rgd_example(), 100e3, 60.0, step=1e-9)
