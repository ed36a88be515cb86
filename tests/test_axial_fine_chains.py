"""Fine axial chains with dampers run, and their growth rate is found only when asked (issue 36,
case 5).

The chain of ``rgd_deviated_well.toml`` cut into 4 m elements with its β = 0.01 s dampers
failed with "the bit's history did not hold the delay at step 1647 (t = 0.0569 s):
non-finite state": the step rule resolved the node frequencies but not the dampers, whose
rate δ = β ω² outgrows ω on short elements. Semi-implicit Euler keeps a damped mode
x'' + δ x' + ω² x = 0 stable only for h δ < 2 − (h ω)²/2 (its step matrix
[[1 − h δ, −h ω²], [h (1 − h δ), 1 − (h ω)²]] has determinant 1 − h δ and trace
2 − h δ − (h ω)²; Jury's conditions). The growth rate of a 1176-DOF chain took minutes in
the linearization that every run computed.
"""

from __future__ import annotations

import json
from importlib import resources

import numpy as np
import pytest

from torsio.axial.stability import MAX_AUTO_DOFS
from torsio.cli import main
from torsio.config.reading import load_config
from torsio.model.axial_assembly import axial_chain, fastest_damping_rate
from torsio.solvers.axial_step_rule import DAMPER_STEP

SKIPPED = "growth rate not computed"


def _deviated(tmp_path, element_length: str, steps_per_period: int = 100) -> str:
    text = resources.files("torsio").joinpath("data/rgd_deviated_well.toml").read_text("utf-8")
    old = 'element_length = "100 m"'
    assert old in text
    new = f'element_length = "{element_length}"\nsteps_per_period = {steps_per_period}'
    path = tmp_path / f"fine_{steps_per_period}.toml"
    path.write_text(text.replace(old, new), "utf-8")
    return str(path)


@pytest.mark.parametrize(("h_delta", "stable"), [(1.0, True), (1.9, True), (2.1, False)])
def test_the_damper_bound_of_semi_implicit_euler(h_delta, stable):
    # the step matrix of the module docstring at h omega = 0.1: stable iff its spectral
    # radius is below 1, which Jury's conditions put at h delta < 2 - (h omega)^2 / 2 = 1.995
    h_omega = 0.1
    step = np.array(
        [[1 - h_delta, -(h_omega**2)], [1 - h_delta, 1 - h_omega**2]]
    )  # (h v, x) scaled: the same eigenvalues
    radius = np.abs(np.linalg.eigvals(step)).max()
    assert bool(radius < 1.0) is stable
    assert DAMPER_STEP == 0.5 * 2.0  # half the bound at h omega -> 0


def test_the_damping_bound_holds_the_eigenvalues_of_the_dampers():
    # a uniform chain, C = beta K: the eigenvalues of M^-1 C lie under the Gershgorin bound
    # 2 (c_i + c_i+1) / m, and the largest of a fine chain comes close to it
    nodes, beta, k, m = 200, 0.01, 1e8, 50.0
    springs = np.full(nodes, k)
    assembly = axial_chain(
        inertias=np.full(nodes, 1.0), stiffnesses=springs, dampings=beta * springs,
        masses=np.full(nodes, m), axial_stiffnesses=springs, axial_dampings=beta * springs,
    )  # fmt: skip
    stiffness = np.diag(springs + np.r_[springs[1:], 0.0])
    stiffness -= np.diag(springs[1:], 1) + np.diag(springs[1:], -1)
    largest = np.linalg.eigvalsh(beta * stiffness / 1.0).max()  # the torsional inertias: 1
    bound = fastest_damping_rate(assembly)
    assert largest <= bound * (1 + 1e-12)
    assert largest > 0.99 * bound


def test_a_four_metre_chain_with_dampers_runs_and_converges(tmp_path, capsys):
    runs = []
    for steps_per_period in (100, 400):
        path = _deviated(tmp_path, "4 m", steps_per_period)
        argv = ["simulate", path, "--duration", "0.2", "--window", "0.1", "--json"]
        assert main(argv) == 0
        captured = capsys.readouterr()
        runs.append((json.loads(captured.out), captured.err))
    (coarse, err), (fine, _) = runs
    assembly = load_config(path).axial.assembly
    # the step keeps h delta at most DAMPER_STEP (it diverged at step 1647 before, its
    # energy residual 2.6e12 times the work put in)
    h_coarse, h_fine = coarse["solver"]["step"], fine["solver"]["step"]
    assert h_coarse * fastest_damping_rate(assembly) <= DAMPER_STEP * (1 + 1e-9)
    assert np.isfinite(coarse["severity"]) and np.isfinite(coarse["surface_torque_max"])
    # semi-implicit Euler with Moreau's contacts is first order: the energy residual of
    # the start-up falls in proportion to the step (80.6 J at 15.1 us, 46.2 J at 8.6 us)
    ratio = coarse["energy_balance"]["residual"] / fine["energy_balance"]["residual"]
    assert ratio == pytest.approx(h_coarse / h_fine, rel=0.2)
    # 1176 DOF: the growth rate is not computed, and the run says so
    assert assembly.dofs + assembly.axial.dofs > MAX_AUTO_DOFS
    assert coarse["growth_rate"] is None
    assert any(SKIPPED in text for text in coarse["warnings"])
    assert SKIPPED in err


def test_the_growth_rate_is_found_or_skipped_on_request(capsys):
    two_dof = str(resources.files("torsio").joinpath("data/rgd_2dof.toml"))
    argv = ["simulate", two_dof, "--duration", "5", "--window", "2", "--json"]
    assert main(argv) == 0
    assert json.loads(capsys.readouterr().out)["growth_rate"] is not None  # 2 DOF: found
    assert main([*argv, "--no-growth-rate"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["growth_rate"] is None
    assert not any(SKIPPED in text for text in data["warnings"])  # asked: no warning


def test_growth_rate_flag_on_a_torsional_run_is_an_error(capsys):
    assert main(["simulate", "--duration", "1", "--growth-rate"]) == 2
    err = capsys.readouterr().err
    assert "--growth-rate" in err and "axial runs" in err
