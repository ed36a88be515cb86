"""The top drive as a node with its controller in the lumped axial engine.

Each check against a reference computed another way: the held top against the results of
the engine before the top drive came in (recorded at commit f444b44), a PI top drive on
the closed-form steady state (RGD 2007; docs/axial.md), the run with the bit stuck against
the matrix exponential of the linear top drive and string, the SoftTorque tuning against
the held top where it stick-slips (a physical expectation), and the refusals.
"""

from __future__ import annotations

import json
import math
from importlib import resources

import numpy as np
import pytest
import scipy.linalg
from axial_files import STRING, pipe_chain, wave_pipe
from axial_growth import envelope_rate, perturbed_run

from torsio.analysis.axial_maps import axial_map
from torsio.analysis.axial_results import AxialChannels
from torsio.axial import (
    rgd_example,
    rgd_two_dof_example,
    simulate_axial,
    tube_section,
)
from torsio.axial.stability import drilling_stability
from torsio.cli import main
from torsio.errors import ConfigError
from torsio.physics.axial_top_drive import top_boundary, top_drive_matrix
from torsio.physics.top_drive_boundary import TopDriveBoundary
from torsio.physics.top_drives import (
    ConstantSpeedTop,
    PITopDrive,
    SoftTorqueTopDrive,
    ZTorqueTopDrive,
)
from torsio.solvers.axial_run_setup import BitRotation

BIT = rgd_example()
PI = PITopDrive(inertia=2900.0, kp=5000.0, ki=2067.6)  # ki ≈ ω₁² J, ω₁ = 0.8444 rad/s
CHAIN = pipe_chain(4, tube_section(1000.0, 2.0e11, 8.0e10, 7850.0, 3.4e-3, 1.5e-5), 3.0e4, 230.0)


def test_held_top_is_the_engine_before_the_top_drive():
    # reference: S_SS, mean ROP [m/s], mean MSE [Pa] of the same runs on the engine before
    # the top drive came in (commit f444b44), equal to the bit; the chain's to 1e-11: its
    # lumping is now strategy C's, whose masses and inertias equal the old ones to 2e-16
    # (measured), which the 10 s stick-slip run carries to 1e-13
    tolerance = {"two_dof": 0.0, "chain": 1e-11}
    first = {}
    before = {
        "two_dof": (1.0969508830625656, 0.007222174071044282, 104336205.60315032),
        "chain": (0.48715872373428387, 0.009488942412422076, 97425660.33640856),
    }
    for top in (None, ConstantSpeedTop()):
        runs = {
            "two_dof": simulate_axial(
                rgd_two_dof_example(), BIT, 100e3, 60.0, duration=20.0, window=10.0,
                growth_rate=False, top_drive=top,
            ),
            "chain": simulate_axial(
                CHAIN, BIT, 100e3, 60.0, duration=10.0, window=5.0, growth_rate=False,
                start="steady", top_drive=top,
            ),
        }  # fmt: skip
        for name, run in runs.items():
            outputs = (run.severity, run.axial.rop_mean, run.axial.mse_mean)
            assert outputs == pytest.approx(before[name], rel=tolerance[name], abs=0.0)
            assert first.setdefault(name, outputs) == outputs  # held: the same run to the bit
            speed = run.signal("top_speed")
            assert np.all(speed == run.axial.steady.bit_speed)
            assert np.array_equal(run.signal("motor_torque"), run.signal("surface_torque"))
            assert np.array_equal(run.signal("surface_torque"), run.signal("top_torque"))
    assert runs["chain"].axial.top_drive == "constant-speed"
    assert not runs["chain"].axial.stability_of_held_top


@pytest.mark.parametrize("assembly", [rgd_two_dof_example(), CHAIN], ids=["two_dof", "chain"])
def test_pi_top_drive_stays_on_the_steady_state(assembly):
    # reference: the closed form (docs/axial.md): V₀ = Ω₀ d₀/2π, T₀, the surface torque T₀
    # (the string carries the bit torque), the top at Ω₀; 180 rpm is above the 153 rpm
    # crossing (stable). Measured: 3e-13 relative (ROP, torques), S_SS 1e-12.
    run = simulate_axial(
        assembly, BIT, 100e3, 180.0, duration=6.0, window=3.0, start="steady",
        perturbation=0.0, top_drive=PI, growth_rate=False,
    )  # fmt: skip
    steady = run.axial.steady
    top = run.axial.top_drive_summary()
    assert run.axial.rop_mean == pytest.approx(steady.rop, rel=1e-10)
    assert run.axial.torque_mean == pytest.approx(steady.bit_torque, rel=1e-10)
    assert top["mean_surface_torque"] == pytest.approx(steady.bit_torque, rel=1e-10)
    assert top["mean_motor_torque"] == pytest.approx(steady.bit_torque, rel=1e-10)
    assert top["top_speed_mean"] == pytest.approx(steady.bit_speed, rel=1e-12)
    assert run.severity < 1e-10


def test_stuck_bit_against_the_matrix_exponential():
    # reference: with the bit stuck (from rest, 100 kN, 60 rpm: the string's torque stays
    # below T_c + T_f for 0.5 s) the top drive, its PI and the string's spring to the bit
    # are the linear system x' = A x + f of torsio.physics.axial_top_drive.top_drive_matrix, solved
    # by
    # scipy.linalg.expm. The scheme is first order: the error halves with the step
    # (measured 2.0007, 2.0003, 2.0002 for 256 .. 2048 steps per delay).
    assembly = rgd_two_dof_example()
    boundary = top_boundary(PI, assembly, 60.0)
    matrix = top_drive_matrix(boundary, assembly.springs[0], assembly.dampers[0])
    n = matrix.shape[0]
    affine = np.zeros((n + 1, n + 1))
    affine[:n, :n] = matrix
    affine[1, n] = boundary.d[0] * boundary.set_speed / boundary.inertia
    affine[2:n, n] = boundary.b[:, 0] * boundary.set_speed
    horizon = 0.5
    exact = scipy.linalg.expm(affine * horizon)[:, n]
    errors = []
    for per_delay in (512, 1024):
        h = 0.25 / per_delay  # the steady delay t_n0 = 0.25 s at 60 rpm
        run = simulate_axial(
            assembly, BIT, 100e3, 60.0, duration=horizon + 2 * h, window=2 * h, step=h,
            samples=10**9, top_drive=PI, growth_rate=False,
        )  # fmt: skip
        k = 2 * per_delay
        assert run.signal("time")[k] == pytest.approx(horizon, abs=1e-12)
        assert np.all(run.signal("bit_speed")[: k + 1] == 0.0)  # stuck throughout
        errors.append(abs(run.signal("top_speed")[k] - exact[1]))
        surface = assembly.springs[0] * exact[0] + assembly.dampers[0] * exact[1]
        assert run.signal("surface_torque")[k] == pytest.approx(surface, rel=2e-3)
    assert errors[1] < 1e-3 * abs(exact[1])
    assert errors[0] / errors[1] == pytest.approx(2.0, abs=0.05)


def test_soft_torque_lowers_stick_slip_against_the_held_top():
    # a physical expectation, not a closed form: at 100 kN, 60 rpm the held top stick-slips
    # (measured S_SS 1.144, the bit at rest 0.094 of the window over the last 50 of 100 s);
    # SoftTorque with kp the chain's impedance √(k I) = 384.7 N m s/rad and ki = ω₁² J (the
    # default) measured 1.059 and 0.036, Z-Torque (ζ = √(k I), the defaults) 0.423 and 0.
    # The time at rest is counted with a stick threshold of 1e-9 Ω₀ (the RGD bit rests at
    # Ω_b = 0 exactly); at the default 0.1 Ω₀ the slow creeps count too: 0.177 and 0.089
    assembly = rgd_two_dof_example()
    impedance = float(np.sqrt(assembly.springs[0] * assembly.bit_inertia))
    options = {"duration": 100.0, "window": 50.0, "growth_rate": False, "stick_threshold": 1e-9}
    held = simulate_axial(assembly, BIT, 100e3, 60.0, **options)
    soft = simulate_axial(
        assembly, BIT, 100e3, 60.0, top_drive=SoftTorqueTopDrive(inertia=2900.0, kp=impedance),
        **options,
    )  # fmt: skip
    z_torque = simulate_axial(
        assembly, BIT, 100e3, 60.0, top_drive=ZTorqueTopDrive(inertia=2900.0, zeta=impedance),
        **options,
    )  # fmt: skip
    assert held.stick_fraction > 0.05
    assert soft.severity < held.severity - 0.05
    assert soft.stick_fraction < 0.5 * held.stick_fraction
    assert z_torque.severity < 0.5 * held.severity


def test_refusals_name_their_key():
    wave = wave_pipe([tube_section(1000.0, 2.0e11, 8.0e10, 7850.0, 3.4e-3, 1.5e-5)], 3.0e4, 230.0)
    with pytest.raises(ConfigError) as info:
        simulate_axial(wave, BIT, 100e3, 60.0, duration=1.0, window=0.5, top_drive=PI)
    assert info.value.key == "top_drive" and "distributed pipe" in info.value.message
    with pytest.raises(ConfigError) as info:
        axial_map(wave, BIT, [100e3], [60.0], duration=1.0, window=0.5, top_drive=PI)
    assert info.value.key == "top_drive"
    # a stiff speed loop (kp/J = 3.4e4 1/s) on 3 steps per period: |λ| h = 2.1 > 1
    stiff = PITopDrive(inertia=2900.0, kp=1e8, ki=2067.6)
    with pytest.raises(ConfigError) as info:
        simulate_axial(
            rgd_two_dof_example(), BIT, 100e3, 60.0, duration=1.0, window=0.5,
            top_drive=stiff, steps_per_period=3,
        )  # fmt: skip
    assert info.value.key == "simulation.step" and "top drive" in info.value.message
    # the default rule resolves it: h |λ| = 2π/100
    run = simulate_axial(
        rgd_two_dof_example(), BIT, 100e3, 180.0, duration=0.5, window=0.25,
        top_drive=stiff, growth_rate=False, start="steady", perturbation=0.0,
    )  # fmt: skip
    assert run.axial.step < 2 * np.pi / (100 * 1e8 / 2900.0) * 1.0001
    with pytest.raises(ConfigError) as info:
        simulate_axial(
            rgd_two_dof_example(), BIT, 100e3, 60.0, duration=1.0, window=0.5, top_drive=PI,
            bit_rotation=BitRotation(),
        )  # fmt: skip
    assert info.value.key == "top_drive"


def test_pi_file_through_the_command_line(tmp_path, capsys):
    text = resources.files("torsio").joinpath("data/rgd_2dof.toml").read_text(encoding="utf-8")
    text += '\n[top_drive]\nkind = "pi"\ninertia = "2900 kg*m^2"\nkp = 5000.0\nki = 2067.6\n'
    path = tmp_path / "pi.toml"
    path.write_text(text, encoding="utf-8")
    status = main(["simulate", str(path), "--rpm", "180", "--duration", "20", "--window", "10",
                   "--json"])  # fmt: skip
    captured = capsys.readouterr()
    assert status == 0, captured.err
    data = json.loads(captured.out)
    for key in ("top_speed_mean", "surface_torque_min", "surface_torque_max",
                "surface_torque_peak", "mean_surface_torque", "mean_motor_torque"):  # fmt: skip
        assert isinstance(data[key], float), key
    assert data["top_drive"] == "pi" and data["stability_of_held_top"] is False  # PI: linearized
    assert data["severity"] >= 0.0
    text = text.replace('kind = "pi"', 'kind = "torque"\ntorque = 5000.0').replace(
        "kp = 5000.0\nki = 2067.6\n", ""
    )
    path.write_text(text, encoding="utf-8")
    assert main(["simulate", str(path), "--json"]) != 0
    assert "top_drive.kind" in capsys.readouterr().err


def test_section_string_gives_the_soft_torque_defaults():
    # reference: kp = ζ = J_p √(G ρ) of the top pipe (torsio.physics.top_drive_boundary),
    # ki = ω₁² J with ω₁ of the assembly's torsional chain, top held: the lowest root of
    # the dense generalized eigenproblem K x = ω² I x solved here (the package solves it
    # as a tridiagonal one, LumpedModel.first_frequency)
    from torsio.config.reading import parse_config
    from torsio.physics.top_drive_boundary import top_pipe_impedance

    data = {**STRING, "top_drive": {"kind": "soft-torque", "inertia": 2900.0}}
    axial = parse_config(data).axial
    boundary = top_boundary(axial.top_drive, axial.assembly, 60.0, axial.string)
    zeta = top_pipe_impedance(axial)
    assert boundary.kp == pytest.approx(zeta, rel=1e-15)
    assembly = axial.assembly
    stiffness, inertia = assembly.stiffness, assembly.inertia
    omega1 = math.sqrt(scipy.linalg.eigh(stiffness, inertia, eigvals_only=True)[0])
    assert assembly.first_frequency() == pytest.approx(omega1, rel=1e-12)
    assert boundary.c[0] == pytest.approx(omega1**2 * 2900.0, rel=1e-12)
    run = simulate_axial(
        axial.assembly, axial.bit, 100e3, 60.0, duration=2.0, window=1.0, growth_rate=False,
        **axial.run_options(),
    )  # fmt: skip
    assert run.axial.top_drive == "soft-torque" and np.isfinite(run.severity)


def test_wave_pipe_file_refuses_a_top_drive():
    from torsio.config.reading import parse_config_text

    text = resources.files("torsio").joinpath("data/rgd_wave_pipe.toml").read_text("utf-8")
    pi = '\n[top_drive]\nkind = "pi"\ninertia = 2900.0\nkp = 5000.0\nki = 2067.6\n'
    with pytest.raises(ConfigError) as info:
        parse_config_text(text + pi)
    assert info.value.key == "top_drive" and "'pi'" in info.value.message
    held = parse_config_text(text + '\n[top_drive]\nkind = "constant-speed"\n')
    assert held.axial.top_drive is None


def test_map_with_a_top_drive_is_its_runs():
    # reference: simulate_axial at each point with the same top drive (the map's own runs)
    grid = axial_map(
        rgd_two_dof_example(), BIT, [90e3, 110e3], [120.0], duration=10.0, window=5.0,
        top_drive=PI, threads=2,
    )  # fmt: skip
    for j, wob in enumerate((90e3, 110e3)):
        run = simulate_axial(
            rgd_two_dof_example(), BIT, wob, 120.0, duration=10.0, window=5.0, top_drive=PI,
            growth_rate=False,
        )  # fmt: skip
        assert grid.severity[0, j] == run.severity
        assert grid.rop[0, j] == run.axial.rop_mean


def test_pi_top_drive_in_the_linearization_against_the_transient():
    # reference: the decay of a small perturbation of steady drilling in the run (its
    # envelope, tests/axial_growth.py) against the rightmost root of the linearization with
    # the top node φ_top (J, kp + drag, ki: torsio.axial.linearization.speed_loop); 170 rpm,
    # above the axial crossing. Measured: root −0.055994 1/s, run −0.056024 1/s; the held
    # top's torsional root is −0.021482. A stiff loop (kp 1e7, ki 1e8) tends to the held top.
    assembly = rgd_two_dof_example()
    boundary = top_boundary(PI, assembly, 170.0)
    root = drilling_stability(assembly, BIT, 100e3, 170.0, count=1, top_drive=boundary).roots[0]
    held = drilling_stability(assembly, BIT, 100e3, 170.0, count=1).roots[0]
    assert root.real < held.real - 0.03
    run = perturbed_run(assembly, BIT, 100e3, 170.0, 60.0, 1e-6, top_drive=PI)
    assert not run.axial.stability_of_held_top
    assert run.axial.growth_rate == pytest.approx(root.real, rel=1e-9)
    rate = envelope_rate(run, "bit_speed", run.axial.steady.bit_speed, root.imag, 15.0, 60.0)
    assert rate == pytest.approx(root.real, rel=2e-3)
    stiff = top_boundary(PITopDrive(inertia=2900.0, kp=1e7, ki=1e8), assembly, 170.0)
    limit = drilling_stability(assembly, BIT, 100e3, 170.0, count=1, top_drive=stiff).roots[0]
    assert limit.real == pytest.approx(held.real, rel=1e-4)


def test_a_top_drive_short_of_its_torque_says_so():
    # reference: the steady bit torque T0 = eps a^2 d0 / 2 + mu gamma a^2 l sigma / 2
    # (torsio.axial.steady, RGD 2007): a motor limited to half of it cannot hold 180 rpm, so
    # the run says what the torsional runs say (torsio.analysis.limits.saturated_motor); a
    # PI without a limit holds it and says nothing
    from torsio.axial.steady import steady_drilling

    torque = steady_drilling(BIT, 100e3, 180.0).bit_torque
    weak = PITopDrive(inertia=2900.0, kp=5000.0, ki=2067.6, max_torque=0.5 * torque)
    run = {"duration": 10.0, "window": 5.0, "start": "steady", "growth_rate": False}
    limited = simulate_axial(rgd_two_dof_example(), BIT, 100e3, 180.0, top_drive=weak, **run)
    held = simulate_axial(rgd_two_dof_example(), BIT, 100e3, 180.0, top_drive=PI, **run)
    assert any("torque limit" in text for text in limited.warnings), limited.warnings
    assert limited.to_dict()["warnings"] == list(limited.warnings)
    assert held.warnings == ()


class _HeldAtTheSetSpeed:
    """A top drive written from the contract alone: a name of its own and a boundary with no
    inertia (held at the set speed), as ConstantSpeedTop's."""

    name = "held-plugin"

    def boundary(self, system):
        return TopDriveBoundary(inertia=0.0, set_speed=float(system.omega))


def test_a_held_top_has_no_node_whatever_its_name():
    # the run's facts read the boundary (held: no inertia), as a torsional run's do
    # (RunFacts.of_system), not the kind's name; a run saved before the channels kept it
    # reads the built-in kinds
    options = {"duration": 2.0, "window": 1.0, "samples": 50, "growth_rate": False}
    held = simulate_axial(rgd_two_dof_example(), BIT, 100e3, 60.0,
                          top_drive=_HeldAtTheSetSpeed(), **options)  # fmt: skip
    pi = simulate_axial(rgd_two_dof_example(), BIT, 100e3, 60.0, top_drive=PI, **options)
    assert held.facts.top_drive == "held-plugin" and not held.has_top_drive_node
    assert pi.has_top_drive_node
    for run, node in ((held, False), (pi, True)):
        data, samples = run.axial.saved()
        assert AxialChannels.from_saved(data, samples).facts().has_top_drive_node is node
    data, samples = pi.axial.saved()
    del data["has_top_drive_node"]  # saved before the channels kept it: PI has a node
    assert AxialChannels.from_saved(data, samples).facts().has_top_drive_node
    data = {**held.axial.saved()[0], "top_drive": "constant-speed"}
    del data["has_top_drive_node"]  # the held top's built-in kind: no node
    assert not AxialChannels.from_saved(data, samples).facts().has_top_drive_node
