"""The distributed model (wave equation along characteristics) against exact results."""

from __future__ import annotations

import math
from types import SimpleNamespace

import attrs
import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from torsio.errors import ConfigError
from torsio.examples import builtin_config, ritto2017_string
from torsio.model.components import Bit, DrillCollar, DrillPipe
from torsio.model.continuum import continuum_modes
from torsio.model.drillstring import DrillString
from torsio.model.wave import WaveStrategy, choose_time_step, interface_factors
from torsio.physics.damping import RayleighDamping
from torsio.physics.laws import ConstantTorque
from torsio.physics.top_drives import PITopDrive, TorqueTopDrive
from torsio.solvers.characteristics import node_offsets, state_from_fields
from torsio.solvers.wave_march import march, string_energy
from torsio.solvers.wave_top import held_top, top_arrays

numba = pytest.importorskip("numba")
SIGNATURE = "float64(float64[::1], float64, float64, float64)"


@numba.njit(SIGNATURE, cache=True)
def _linear_torque(parameters, speed, wob, radius):  # type: ignore[no-untyped-def]
    return parameters[0] + parameters[1] * speed


@numba.njit(SIGNATURE, cache=True)
def _linear_slope(parameters, speed, wob, radius):  # type: ignore[no-untyped-def]
    return parameters[1]


def free_bit(torque: float = 0.0, damping: float = 0.0) -> tuple:
    """Kernel of a bit law T = torque + damping * speed (0: a free bit)."""
    return (_linear_torque, _linear_slope, np.array([torque, damping]))


NO_LAW = ConstantTorque(torque_on_bit=0.0)


def peak_frequency(time: np.ndarray, signal: np.ndarray, guess: float) -> float:
    """Frequency [Hz] of the Hann-windowed spectral peak nearest ``guess``, refined."""
    window = np.hanning(signal.size) * (signal - signal.mean())

    def minus_magnitude(f: float) -> float:
        return -abs(np.sum(window * np.exp(-2j * np.pi * f * time)))

    bin_width = 1.0 / (time[-1] - time[0])
    found = minimize_scalar(
        minus_magnitude, bounds=(guess - 2 * bin_width, guess + 2 * bin_width), method="bounded",
        options={"xatol": 1e-12},
    )  # fmt: skip
    return float(found.x)


def test_grid_rounding_is_within_tolerance_and_reported() -> None:
    # the grid string is the given one with each section rounded to whole cells
    grid = WaveStrategy(time_step=2e-3, travel_time_tolerance=1e-4).discretize(ritto2017_string())
    assert grid.time_step <= 2e-3
    assert grid.travel_time_errors.max() <= 1e-4
    lengths = np.array([s.length for s in grid.grid_string().flexible_sections])
    np.testing.assert_allclose(lengths, grid.grid_lengths, rtol=1e-15)
    dt, cells = choose_time_step(np.array([1.0, 0.25]), 0.1, 1e-9)
    assert (dt, cells.tolist()) == (1 / 12, [12, 3])  # the largest step <= 0.1 exact for both


def test_rings_at_the_exact_continuum_frequencies() -> None:
    # top held, no damping, no bit torque, released from a uniform static torque: the
    # free vibration holds only natural modes; reference: the exact continuum
    # (torsio.model.continuum, Wittrick-Williams), 0.13075 Hz first for the paper's string
    string = ritto2017_string()
    grid = WaveStrategy(time_step=2e-3, travel_time_tolerance=5e-5).discretize(string)
    top = held_top(0.0)
    size = int(node_offsets(grid)[-1])
    state = state_from_fields(grid, np.zeros(size), np.full(size, 1e3), top)
    steps = int(200.0 / grid.time_step)
    run = march(grid, top, NO_LAW, 0.0, 0.1, 0.0, steps, record_every=1, state=state,
                kernel=free_bit())  # fmt: skip
    exact_grid = continuum_modes(grid.grid_string(), count=3).frequencies_hz
    exact = continuum_modes(string, count=3).frequencies_hz
    assert round(float(exact[0]), 5) == 0.13075
    for f_grid, f_exact in zip(exact_grid, exact, strict=True):
        measured = peak_frequency(run.time, run.records[:, 0], f_grid)
        assert abs(measured - f_exact) / f_exact < 1e-4
        assert abs(measured - f_grid) / f_grid < 1e-6  # the grid string's own modes


def test_step_in_top_speed_arrives_after_the_travel_time() -> None:
    # d'Alembert: nothing moves at the bit before L/c = sum of the section travel times
    grid = WaveStrategy(time_step=2e-3, travel_time_tolerance=1e-4).discretize(ritto2017_string())
    steps = sum(grid.cells) + 5
    run = march(grid, held_top(1.0), NO_LAW, 0.0, 0.1, 0.0, steps, record_every=1,
                kernel=free_bit())  # fmt: skip
    moving = np.flatnonzero(run.records[:, 0] != 0.0)
    arrival = run.time[moving[0]]
    travel = grid.travel_times.sum()
    assert abs(arrival - travel) <= grid.time_step * (1 + 1e-9)
    assert moving[0] == sum(grid.cells)


def _two_section_string() -> DrillString:
    return DrillString(
        [DrillPipe(od=0.127, id=0.1086, length=1000.0),
         DrillCollar(od=0.2032, id=0.0714, length=500.0), Bit(od=0.2159, id=0.05, length=0.3)]
    )  # fmt: skip


def test_interface_splits_a_wave_exactly() -> None:
    # impedance junction: velocity transmitted 2 Z1/(Z1+Z2), reflected (Z1-Z2)/(Z1+Z2)
    # (torque: 2 Z2/(Z1+Z2), (Z2-Z1)/(Z1+Z2)); reference: continuity of speed and torque
    grid = WaveStrategy(time_step=1e-3).discretize(_two_section_string())
    z1, z2 = grid.impedances
    upper, lower = grid.cells
    steps = upper + lower // 2  # the front is halfway down the collars, nothing back yet
    run = march(grid, held_top(1.0), NO_LAW, 0.0, 0.1, 0.0, steps, field_every=steps,
                kernel=free_bit())  # fmt: skip
    speed = run.field[-1]
    factors = interface_factors(z1, z2)
    reflected_region = speed[upper - lower // 2 + 2 : upper]  # above the junction
    transmitted_region = speed[upper + 2 : upper + lower // 2 - 2]
    np.testing.assert_allclose(reflected_region, 1.0 + factors["velocity_reflected"], rtol=1e-14)
    np.testing.assert_allclose(transmitted_region, factors["velocity_transmitted"], rtol=1e-14)
    assert math.isclose(1 + factors["torque_reflected"], factors["torque_transmitted"])


def test_pi_top_drive_reflects_zeta_minus_kp_over_zeta_plus_kp() -> None:
    # a plateau of upgoing velocity hits a PI top drive (ki = 0): once its inertia has
    # settled (J/(Z+kp) = 3 dt), the reflection is R = (Z - kp)/(Z + kp) exactly
    # (small-signal impedance of the top drive: kp; torsio.physics.top_drives)
    string = DrillString([DrillPipe(od=0.127, id=0.1086, length=6000.0), Bit(od=0.2, id=0.05,
                          length=0.3)])  # fmt: skip
    grid = WaveStrategy(time_step=1e-3).discretize(string)
    zeta = float(grid.impedances[0])
    kp = 3.0 * zeta
    inertia = 3 * grid.time_step * (zeta + kp)
    boundary = PITopDrive(inertia=inertia, kp=kp, ki=0.0).boundary(SimpleNamespace(omega=0.0))
    top = top_arrays(boundary, zeta, grid.time_step, 0.0)
    size = int(node_offsets(grid)[-1])
    incoming = np.zeros(size)
    incoming[200:1200] = 1.0  # upgoing: torque = -Z * speed
    state = state_from_fields(grid, incoming, -zeta * incoming, top)
    steps = 1000  # the plateau's top part has been reflected and travelled down 800 cells
    run = march(grid, top, NO_LAW, 0.0, 0.1, 0.0, steps, field_every=steps, state=state,
                kernel=free_bit())  # fmt: skip
    reflected = run.field[-1][300:700]  # only the reflected wave is there now
    expected = (zeta - kp) / (zeta + kp)
    np.testing.assert_allclose(reflected, expected, rtol=1e-12)


def test_lossless_free_vibration_keeps_its_energy() -> None:
    # no damping, no bit torque, top held still: energy is conserved by exact transport and
    # junctions; only the bit's BDF2 step (inertia 0.4 kg m^2) can lose any
    grid = WaveStrategy(time_step=2e-3, travel_time_tolerance=1e-3).discretize(ritto2017_string())
    top = held_top(0.0)
    size = int(node_offsets(grid)[-1])
    state = state_from_fields(grid, np.zeros(size), np.full(size, 1e3), top)
    start = string_energy(grid, state)
    run = march(grid, top, NO_LAW, 0.0, 0.1, 0.0, 20000, state=state, kernel=free_bit())
    end = string_energy(grid, run.state) + 0.5 * grid.bit_inertia * run.state.bit[0] ** 2
    assert run.summary["work_in"] == 0.0
    assert abs(end - start) / start < 1e-3


def _energy_residual(dt: float, top_drive: str | None, alpha: float = 0.35) -> tuple:
    """Start-up from rest over 20 s of the paper's string on a grid of step ``dt`` with a
    bit law T = 500 w: (work in - stored - dissipated [J], work in [J], run, grid)."""
    # any grid near dt (a rounding is always within 1/2), then set to dt
    grid = WaveStrategy(time_step=dt, travel_time_tolerance=0.49).discretize(ritto2017_string())
    grid = attrs.evolve(grid, time_step=dt, cells=grid.cells)
    if top_drive is not None:
        drive = (
            PITopDrive(inertia=500.0, kp=3e3, ki=1e3)
            if top_drive == "pi"
            else TorqueTopDrive(inertia=500.0, torque=10e3)  # no controller state
        )
        boundary = drive.boundary(SimpleNamespace(omega=5.0))
        top = top_arrays(boundary, float(grid.impedances[0]), dt, 5.0)
    else:
        top = held_top(5.0)
    run = march(grid, top, NO_LAW, 0.0, 0.1, alpha, int(round(20.0 / dt)), record_every=1,
                kernel=free_bit(damping=500.0))  # fmt: skip
    s = run.summary
    stored = s["stored_final"] - s["stored_initial"]
    dissipated = sum(
        s[key] for key in ("bit_dissipation", "bit_drag_dissipation", "string_drag_dissipation",
                           "top_drag_dissipation")
    )  # fmt: skip
    return s["work_in"] - stored - dissipated, s["work_in"], run, grid


@pytest.mark.parametrize("top_drive", ["pi", "torque"])
def test_energy_balance_is_second_order_in_the_step(top_drive: str) -> None:
    # work in = stored + dissipated (reference: the energy balance of the wave equation with
    # drag, a PI top drive with inertia and a damped bit). Expected order 2 from the
    # scheme's analysis (characteristics module docstring): exact transport and junctions,
    # Strang-split drag, trapezoidal top drive, BDF2 bit, trapezoidal power quadrature,
    # the top speed continuous (the top drive's inertia)
    residuals = [_energy_residual(dt, top_drive) for dt in (4e-3, 2e-3, 1e-3)]
    relative = [r / work for r, work, _, _ in residuals]
    orders = [math.log2(relative[k] / relative[k + 1]) for k in range(2)]
    assert abs(relative[0]) < 1e-5
    for order in orders:
        assert order == pytest.approx(2.0, abs=0.1)


def test_step_start_loses_only_the_bit_jump_energy() -> None:
    # a held top started from rest sends a jump in speed down the string; at the stiff bit
    # (J_b / Z = 0.2 ms, far below dt) BDF2 loses J_b dw^2 / 2 at an isolated jump dw
    # (the analysis in the characteristics module docstring), which bounds the residual
    residual, work, run, grid = _energy_residual(4e-3, None)
    jump_loss = 0.5 * grid.bit_inertia * np.sum(np.diff(run.records[:, 0]) ** 2)
    assert 0.0 < residual <= jump_loss
    assert residual / work < 1e-5


def test_wave_strategy_refuses_what_it_cannot_represent() -> None:
    config = builtin_config()
    system = config.system(strategy="wave")  # the paper's beta = 0.06 s
    from torsio.analysis.wave import wave_response

    # the message names what to set: alpha + beta w1^2 keeps the first mode's damping ratio
    # (Rayleigh: zeta_1 = (alpha / w1 + beta w1) / 2, w1 = 0.8215 rad/s from the continuum)
    with pytest.raises(ConfigError, match=r"damping.beta.*beta = 0.*alpha = 0\.3905 1/s"):
        wave_response(system, duration=1.0)
    with pytest.raises(ConfigError, match="dp_elements"):
        WaveStrategy(dp_elements=5)
    with pytest.raises(ConfigError, match="time_step"):
        WaveStrategy(time_step=-1.0)
    assert attrs.evolve(system, damping=RayleighDamping(alpha=0.35)).model.strategy == "wave"


def test_cli_simulate_wave_on_the_builtin_config_says_what_to_set(capsys) -> None:  # type: ignore[no-untyped-def]
    # the built-in file has beta = 0.06 s: a usage error naming the key and the remedy
    from torsio.cli import main

    assert main(["simulate", "--strategy", "wave"]) == 2
    message = capsys.readouterr().err
    assert "damping.beta" in message and "beta = 0" in message
    assert "alpha = 0.3905 1/s" in message and "Kelvin-Voigt" in message


def _wave_config_text() -> str:
    from importlib import resources

    text = resources.files("torsio").joinpath("data/ritto2017.toml").read_text(encoding="utf-8")
    text = text.replace("beta = 0.06", "beta = 0.0").replace('strategy = "C"', 'strategy = "wave"')
    return text.replace("dp_elements = 5\n", "").replace("bha_elements = 1\n", "")


def test_wave_strategy_from_the_cli_simulate_and_map(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    # the same point through simulate and through a one-point map agree exactly (one
    # stepping); reference: the distributed model's own run
    import json

    from torsio.cli import main

    path = tmp_path / "wave.toml"
    path.write_text(_wave_config_text())
    options = ["--wob", "150 kN", "--rpm", "60", "--duration", "30", "--window", "10"]
    assert main(["simulate", str(path), *options, "--json"]) == 0
    simulated = json.loads(capsys.readouterr().out)
    assert simulated["strategy"] == "wave"
    grid = ["--wob", "150kN:150kN:1", "--rpm", "60:60:1", "--duration", "30", "--window", "10"]
    assert main(["map", str(path), *grid, "--json"]) == 0
    mapped = json.loads(capsys.readouterr().out)
    assert mapped["severity"][0][0] == pytest.approx(simulated["severity"], rel=1e-12)
    assert simulated["severity"] > 0.8  # stick-slip at the paper's low speed, high WOB


@pytest.mark.slow
def test_strategy_c_severity_converges_to_the_wave_model() -> None:
    # S_SS of strategy C (lumped mass, rigid BHA) approaches the distributed model's as
    # the drill pipes get more elements, at the paper's stick-slip point 150 kN, 60 rpm;
    # reference: the wave model on its default grid (default run length and window)
    from torsio.solvers.batch import simulate_batch

    damping = RayleighDamping(alpha=0.35)
    config = builtin_config()
    wave = attrs.evolve(config.system(strategy="wave"), damping=damping)
    reference = float(simulate_batch(wave, [150e3], [60.0]).severity[0])
    errors = []
    for elements in (2, 8, 32):
        lumped = attrs.evolve(config.system(strategy="C", dp_elements=elements), damping=damping)
        errors.append(abs(float(simulate_batch(lumped, [150e3], [60.0]).severity[0]) - reference))
    print("S_SS errors of C against the wave model:", errors)
    assert errors[-1] < errors[0]
    assert errors[-1] < 0.05


def test_soft_torque_top_drive_runs_on_the_wave_model() -> None:
    # SoftTorque's default gains need omega_1: for the wave model, the exact continuum of
    # its grid (torsio.analysis.wave.first_frequency); the energy balance closes
    # (reference: the energy balance of the wave equation with the top drive's inertia)
    from torsio.analysis.wave import first_frequency, wave_response
    from torsio.physics.top_drives import SoftTorqueTopDrive

    system = attrs.evolve(builtin_config().system(strategy="wave"), damping=RayleighDamping(0.35))
    system = system.with_top(SoftTorqueTopDrive(inertia=2900.0)).at(wob=150e3, rpm=60)
    kp, ki = system.top.gains(system)
    assert ki == pytest.approx(first_frequency(system.model) ** 2 * 2900.0, rel=1e-12)
    response = wave_response(system, duration=20.0, steady_window=5.0)
    energy = response.energy
    assert abs(energy["residual"]) < 1e-3 * energy["work_in"]
    assert response.run.records[-1, 3] > 0.0  # the top drive turns


def test_strategy_c_severity_converges_at_second_order_to_its_wave_limit() -> None:
    # strategy C keeps the BHA rigid: it converges to the wave model of the string with a
    # rigid BHA (rigid_bha = true), at 200 kN, 100 rpm (stick-slip in the paper's maps).
    # Expected order 2: lumped mass errs by -(kh)^2/24 in the frequencies (ConsistentMass
    # docstring; docs/strategies.md, Fig. 3 at second order). S_SS is an extreme of a
    # non-smooth limit cycle, so single refinements scatter (docs/wave.md: 1.4 to 2.8 at
    # the other points); the order over the two doublings 32 -> 128 is checked.
    from torsio.model.continuum import continuum_modes
    from torsio.solvers.batch import simulate_batch

    damping = RayleighDamping(alpha=0.35)
    config = builtin_config()
    period = 2.0 * math.pi / float(continuum_modes(ritto2017_string(), 1).frequencies_rad[0])
    times = {"duration": 40.0 * period, "steady_window": 15.0 * period}
    wave = config.system(strategy="wave", rigid_bha=True, time_step=1e-3)
    wave = attrs.evolve(wave, damping=damping)
    assert wave.model.cells == (wave.model.cells[0],)  # the drill pipes only
    reference = float(simulate_batch(wave, [200e3], [100.0], **times).severity[0])
    errors = []
    for elements in (32, 64, 128):
        lumped = attrs.evolve(config.system(strategy="C", dp_elements=elements), damping=damping)
        value = float(simulate_batch(lumped, [200e3], [100.0], **times).severity[0])
        errors.append(abs(value - reference))
    order = math.log(errors[0] / errors[2]) / math.log(4.0)
    print("S_SS errors of C against the rigid-BHA wave model:", errors, "order", order)
    assert order == pytest.approx(2.0, abs=0.25)
    assert max(errors) < 0.01  # the target: within 0.01 of the distributed model


def test_report_of_the_wave_model_shows_its_grid_and_severity(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    # torsio report --strategy wave end to end: the grid (cells per section, time step; the
    # default grid of the paper's string, docs/wave.md) and S_SS of the same run as simulate
    import json

    from torsio.cli import main

    path = tmp_path / "wave.toml"
    path.write_text(_wave_config_text().replace('strategy = "wave"', 'strategy = "C"'))
    assert main(["report", str(path), "--strategy", "wave", "--modes", "2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    grid = data["discretization"]
    assert grid["strategy"] == "wave"
    assert [part["cells"] for part in grid["parts"]] == [995, 36, 62]
    assert grid["time_step_s"] == pytest.approx(1.4386e-3, abs=1e-7)
    assert data["wave"]["cells"] == [995, 36, 62]
    assert data["wave"]["severity"] == data["response"]["severity"]
    assert data["modes"]["frequencies_hz"][0] == pytest.approx(0.13075, abs=1e-5)  # continuum
    assert data["damping"]["ratios"][0] == pytest.approx(0.35 / (2 * 0.8215), rel=1e-3)
