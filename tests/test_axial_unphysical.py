"""Axial runs whose results cannot be physical are refused up front or carry warnings
(issue 36, case 3), on the built-in RGD 2-DOF file.

Sources: the steady depth of cut d0 = (W0 - σ a l)/(ζ ε a) (RGD 2007, docs/axial.md) with
ζ = 0.6, ε = 60 MPa, a = 0.108 m, σ a l = 71 280 N: d0/n reaches the radius a at
W = σ a l + ζ ε a n a = 1.751e6 N; the energy balance W_top + W_hook = Δstored + dampers +
W_bit (a conservation law; the first-order scheme leaves 1.6e-4 of it on the default run).
"""

from __future__ import annotations

import json
from importlib import resources

import pytest

from torsio.analysis.axial_energy import RESIDUAL_TOLERANCE, EnergyBalance
from torsio.analysis.axial_warnings import depth_beyond_geometry
from torsio.axial import rgd_example, rgd_two_dof_example, simulate_axial
from torsio.axial.steady import steady_drilling
from torsio.cli import main
from torsio.errors import ConfigError

EXAMPLE = resources.files("torsio").joinpath("data/rgd_2dof.toml").read_text(encoding="utf-8")
TIMES = ["--duration", "40", "--window", "20"]


def _run(capsys, tmp_path, old, new, *flags):
    assert old in EXAMPLE
    path = tmp_path / "case.toml"
    path.write_text(EXAMPLE.replace(old, new, 1), encoding="utf-8")
    status = main(["simulate", str(path), *flags, "--json"])
    captured = capsys.readouterr()
    return status, captured


@pytest.mark.parametrize("wob", ["1 GN", "2 MN", "1.8 MN"])
def test_a_steady_cut_deeper_than_the_bit_is_refused(capsys, wob):
    # d0/n > a above W = 1.751e6 N (module docstring)
    path = str(resources.files("torsio").joinpath("data/rgd_2dof.toml"))
    status = main(["simulate", path, "--wob", wob, *TIMES])
    err = capsys.readouterr().err
    assert status == 2 and "--wob" in err and "radius" in err and "Traceback" not in err


def test_the_deepest_weight_is_the_closed_form():
    bit = rgd_example()
    deepest = bit.friction_weight + bit.cutting_weight_per_depth * bit.blades * bit.radius
    assert deepest == pytest.approx(1.751e6, rel=1e-3)  # module docstring
    steady_drilling(bit, 0.999 * deepest, 60.0)
    with pytest.raises(ConfigError, match="wob"):
        steady_drilling(bit, 1.001 * deepest, 60.0)


@pytest.mark.parametrize("perturbation", ["1e6", "1.0", "5"])
def test_a_perturbation_that_is_no_perturbation_is_refused(capsys, tmp_path, perturbation):
    # 1e6 gave a mean bit torque of -2.3e9 N m (issue 36); p >= 1 at least doubles Ω0
    old = 'start = "rest"'
    new = f'start = "steady"\nperturbation = {perturbation}'
    text = EXAMPLE.replace("perturbation = 1e-3\n", "")
    path = tmp_path / "case.toml"
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    status = main(["simulate", str(path), *TIMES])
    err = capsys.readouterr().err
    assert status == 2 and "simulation.perturbation" in err


@pytest.mark.parametrize(
    ("old", "new"),
    [
        ('wear_flat_length = "11 mm"', "wear_flat_length = 0"),
        ('contact_stress = "60 MPa"', "contact_stress = 0"),
        ('contact_stress = "60 MPa"', 'contact_stress = "1 kPa"'),
    ],
)
def test_no_wear_flat_contact_runs_with_warnings(capsys, tmp_path, old, new):
    # σ a l = 0: the bit bounces (issue 36: MSE -6.4 MPa, d = 2 m/rev, 3.5 MJ residual)
    status, captured = _run(capsys, tmp_path, old, new, *TIMES)
    assert status == 0
    data = json.loads(captured.out)
    assert data["warnings"]
    text = " ".join(data["warnings"])
    if data["depth_of_cut_max"] / 4 > 0.108:  # d/n beyond the radius: said
        assert "radius" in text
    if data["mse_mean"] is not None and data["mse_mean"] < 0:
        assert "MSE is negative" in text
    if data["rop_mean"] < 0:
        assert "moved up" in text
    if data["energy_balance"]["relative_residual"] > RESIDUAL_TOLERANCE:
        assert "energy balance" in text
    for warning in data["warnings"]:
        assert f"warning: {warning}" in captured.err


def test_the_default_run_carries_no_warning_and_its_balance_closes():
    run = simulate_axial(
        rgd_two_dof_example(), rgd_example(), 100e3, 60.0, duration=40.0, window=20.0,
        growth_rate=False,
    )  # fmt: skip
    assert run.warnings == ()
    assert run.axial.energy.relative_residual < RESIDUAL_TOLERANCE  # conservation law, O(h)


def test_the_residual_warning_states_the_tolerance():
    # input 100 J, spent 50 J: residual 50 J, half of the work put in
    balance = EnergyBalance(100.0, 0.0, 0.0, 10.0, 40.0, 0.0)
    assert balance.relative_residual == pytest.approx(0.5)
    assert "0.5 of the work put in" in balance.warning()
    closed = EnergyBalance(100.0, 0.0, 50.0, 10.0, 40.0, 0.0)
    assert closed.residual == 0.0 and closed.warning() is None


def test_the_depth_bound_is_per_blade():
    # d/n against a: 0.43 m/rev on 4 blades is 0.1075 m per blade, below a = 0.108 m
    assert depth_beyond_geometry(0.43, 4, 0.108) is None
    assert depth_beyond_geometry(0.44, 4, 0.108) is not None


def test_a_bit_stuck_throughout_the_window_is_said():
    # the axial bit is stuck below 0.1 Ω₀ (torsio.axial.bit_step.record_step); a run
    # started from rest whose window ends before the string's torque T = k Ω0 t reaches the
    # bit's torque at rest (T_c + T_f >= μ γ a² σ l / 2 = 2309 N m: t >= 2309 / (324.857 x
    # 2π) = 1.13 s) never turns the bit over the window
    run = simulate_axial(
        rgd_two_dof_example(), rgd_example(), 100e3, 60.0, duration=1.0, window=0.5,
        growth_rate=False,
    )  # fmt: skip
    assert run.stick_fraction == 1.0
    assert any("stuck throughout" in text for text in run.warnings)
