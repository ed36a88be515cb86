"""The wave model's stepping engine: lumped drag, the bit's equation, runs that end early."""

from __future__ import annotations

import math

import attrs
import numpy as np
import pytest

from torsio.errors import ConfigError
from torsio.examples import builtin_config, ritto2017_string
from torsio.model.components import Bit, DrillPipe
from torsio.model.continuum import continuum_modes
from torsio.model.drillstring import DrillString
from torsio.model.wave import WaveStrategy
from torsio.model.wave_grid import drag_lumping
from torsio.physics.damping import RayleighDamping
from torsio.physics.laws import ConstantTorque
from torsio.solvers.batch import simulate_batch
from torsio.solvers.batch_results import DEFAULT_STEADY_TOLERANCE
from torsio.solvers.characteristics import kernel_layout, node_offsets, state_from_fields
from torsio.solvers.law_kernels import compile_law_function
from torsio.solvers.layouts import C_INNER, C_SPECIAL, INNER
from torsio.solvers.wave_bit import _solve_bit
from torsio.solvers.wave_march import march
from torsio.solvers.wave_top import held_top

pytest.importorskip("numba")
NO_LAW = ConstantTorque(torque_on_bit=0.0)


def _polynomial_torque(parameters, speed, wob, radius):  # type: ignore[no-untyped-def]
    return parameters[0] + speed * (parameters[1] + speed * (parameters[2] + speed * parameters[3]))


def _polynomial_slope(parameters, speed, wob, radius):  # type: ignore[no-untyped-def]
    return parameters[1] + speed * (2.0 * parameters[2] + 3.0 * speed * parameters[3])


TORQUE = compile_law_function(_polynomial_torque)
SLOPE = compile_law_function(_polynomial_slope)


def polynomial_law(*coefficients: float) -> tuple:
    """Kernel of a bit law T = c0 + c1 w + c2 w^2 + c3 w^3."""
    return (TORQUE, SLOPE, np.array(coefficients, dtype=float))


def test_drag_lumping_shares_add_up_to_the_section() -> None:
    # the trapezoidal rule on the nodes 0, k, 2k, ..., n: every cell's drag counted once
    for cells in (1, 3, 36, 62, 995):
        for spacing in (1, 4, 7, 8, 1000):
            nodes, shares = drag_lumping(cells, spacing)
            assert nodes[0] == 0 and nodes[-1] == cells
            assert math.isclose(shares.sum(), cells, rel_tol=1e-15)
            assert np.all(shares[1:-1][:-1] == spacing)  # the regular ones


def test_a_point_damper_splits_a_wave_exactly() -> None:
    # one inner damper c = alpha Z (n/2) dt at mid-length: a dashpot to the borehole on a
    # wave line transmits a velocity wave with 2Z/(2Z + c) and reflects -c/(2Z + c)
    # (speed continuous, torque jump c v); reference: that junction, solved by hand
    string = DrillString([DrillPipe(od=0.127, id=0.1086, length=3000.0), Bit(od=0.2, id=0.05,
                          length=0.3)])  # fmt: skip
    grid = WaveStrategy(time_step=1e-3).discretize(string)
    cells = grid.cells[0] - grid.cells[0] % 4
    grid = attrs.evolve(grid, cells=(cells,), drag_spacing=cells // 2)
    alpha = 0.35
    damper = alpha * float(grid.impedances[0]) * (cells // 2) * grid.time_step
    transmitted = 2.0 * grid.impedances[0] / (2.0 * grid.impedances[0] + damper)
    steps = cells // 2 + cells // 4  # the front three quarters down, nothing back yet
    run = march(grid, held_top(1.0), NO_LAW, 0.0, 0.1, alpha, steps, field_every=steps,
                kernel=polynomial_law(0.0, 0.0, 0.0, 0.0))  # fmt: skip
    speed = run.field[-1]
    above = speed[cells // 4 + 2 : cells // 2]  # the held top's wave and the reflection
    below = speed[cells // 2 + 1 : 3 * cells // 4 - 1]
    np.testing.assert_allclose(above, 1.0 - damper / (2.0 * grid.impedances[0] + damper),
                               rtol=1e-14)  # fmt: skip
    np.testing.assert_allclose(below, transmitted, rtol=1e-14)
    assert speed[cells // 2] == pytest.approx(transmitted, rel=1e-14)  # the damper node itself


def _first_mode_decay_rate(spacing: int, alpha: float) -> float:
    """Decay rate [1/s] of the first mode in a free vibration of the paper's string."""
    grid = WaveStrategy(time_step=2e-3, travel_time_tolerance=5e-5, drag_spacing=spacing)
    grid = grid.discretize(ritto2017_string())
    top = held_top(0.0)
    size = int(node_offsets(grid)[-1])
    state = state_from_fields(grid, np.zeros(size), np.full(size, 1e3), top, alpha=alpha)
    window = 60.0
    run = march(grid, top, NO_LAW, 0.0, 0.1, alpha, int(2 * window / grid.time_step),
                record_every=1, state=state, kernel=polynomial_law(0.0, 0.0, 0.0, 0.0))  # fmt: skip
    omega = float(continuum_modes(grid.grid_string(), count=1).frequencies_rad[0])
    damped = math.sqrt(omega**2 - alpha**2 / 4.0)

    def amplitude(start: float) -> float:  # Hann-windowed Fourier coefficient at mode 1
        inside = (run.time >= start) & (run.time < start + window)
        signal = run.records[inside, 0] * np.hanning(int(inside.sum()))
        return float(abs(np.sum(signal * np.exp(-1j * damped * run.time[inside]))))

    return math.log(amplitude(0.0) / amplitude(window)) / window


def test_lumped_drag_decays_the_first_mode_at_alpha_over_two() -> None:
    # distributed drag alpha rho J and alpha J_b on the bit is mass-proportional damping:
    # in the continuum every mode decays as exp(-alpha t / 2). Measured from the mode's
    # Fourier coefficient over two windows of 60 s (the estimate is biased by about 2e-4
    # by the other modes' leakage, the same for every spacing); the lumping into dampers
    # every k cells changes the rate at second order in k (spacing against wavelength)
    alpha = 0.35
    rates = {k: _first_mode_decay_rate(k, alpha) for k in (1, 4, 16, 64)}
    assert rates[1] == pytest.approx(alpha / 2.0, rel=5e-4)
    assert abs(rates[4] / rates[1] - 1.0) < 1e-6  # the default spacing
    order = math.log((rates[64] - rates[1]) / (rates[16] - rates[1])) / math.log(4.0)
    assert order == pytest.approx(2.0, abs=0.3)


def test_layout_lumps_every_cell_of_drag_once() -> None:
    # the dampers of a layout add up to alpha rho J L = alpha Z n dt per section
    grid = WaveStrategy(drag_spacing=8).discretize(ritto2017_string())
    layout = kernel_layout(grid, alpha=0.35)
    inner = layout.floats[:, C_INNER] * layout.integers[:, INNER] + layout.floats[:, C_SPECIAL]
    total = layout.end_dampers.sum() + inner.sum()
    expected = 0.35 * float(np.dot(grid.impedances, grid.cells)) * grid.time_step
    assert total == pytest.approx(expected, rel=1e-13)


@pytest.mark.parametrize(
    ("w_now", "guess", "expected"),
    [
        (-2.5, -2.4, -math.sqrt(3.0)),  # f < 0 below the lowest root: up to it
        (-2.5, 0.5, -math.sqrt(3.0)),  # a guess beyond two roots is not taken
        (2.5, 2.4, math.sqrt(3.0)),  # from above: down to the highest root
        (0.5, 0.6, math.sqrt(3.0)),  # f < 0: the net torque accelerates, up past w = 1
        (-0.5, -0.6, -math.sqrt(3.0)),  # f > 0: the net torque decelerates, down past -1
    ],
)
def test_bit_equation_takes_the_root_nearest_in_the_direction_of_motion(
    w_now: float, guess: float, expected: float
) -> None:
    # f(w) = k w + T(w) - r with k = 1 and T = -4 w + w^3: f = w^3 - 3 w, roots -sqrt 3,
    # 0, sqrt 3 (velocity weakening steeper than k); the sign of f at w_now is that of the
    # net decelerating torque, so the motion goes down where f > 0 and up where f < 0;
    # reference: the cubic's roots
    torque, slope, parameters = polynomial_law(0.0, -4.0, 0.0, 1.0)
    t_now = float(_polynomial_torque(parameters, w_now, 0.0, 0.0))
    root, t_root = _solve_bit(1.0, 0.0, w_now, t_now, guess, torque, slope, parameters, 0.0, 0.0)
    assert root == pytest.approx(expected, abs=1e-12)
    assert t_root == pytest.approx(_polynomial_torque(parameters, root, 0.0, 0.0), abs=1e-11)


def test_bit_equation_reports_a_law_without_a_root() -> None:
    # a torque on bit that is not a number has no root: NaN, which the run reports as the
    # failed step (a SolverError naming it), never a made-up speed
    torque, slope, parameters = polynomial_law(math.nan, 0.0, 0.0, 0.0)
    root, _ = _solve_bit(1.0, 0.0, 0.0, math.nan, 0.0, torque, slope, parameters, 0.0, 0.0)
    assert math.isnan(root)


def _wave_system(**options) -> object:  # type: ignore[no-untyped-def]
    system = builtin_config().system(strategy="wave", **options)
    return attrs.evolve(system, damping=RayleighDamping(alpha=0.35))


def test_runs_on_a_steady_cycle_end_early_within_the_tolerance() -> None:
    # the map's points end early only where S_SS cannot move by more than the tolerance
    # before the run's end (reference: the same runs taken to the end)
    system = _wave_system()
    wob, rpm = (a.ravel() for a in np.meshgrid([25e3, 75e3, 125e3, 175e3, 225e3],
                                               [40.0, 65.0, 90.0, 115.0, 140.0]))  # fmt: skip
    early = simulate_batch(system, wob, rpm)
    whole = simulate_batch(system, wob, rpm, steady_tolerance=0.0)
    assert early.engine == "wave" and early.steady_tolerance == DEFAULT_STEADY_TOLERANCE
    assert np.all(whole.ended == whole.duration) and np.all(whole.steps == whole.steps[0])
    ended = early.ended < early.duration
    assert ended.sum() >= 10  # the points in steady rotation, at least
    assert np.all(early.steps[ended] < whole.steps[ended])
    assert np.max(np.abs(early.severity - whole.severity)) <= DEFAULT_STEADY_TOLERANCE


def test_wave_strategy_refuses_a_drag_spacing_that_is_not_a_whole_number_of_cells() -> None:
    for bad in (0, -1, 2.5, True, "4"):
        with pytest.raises(ConfigError, match="drag_spacing"):
            WaveStrategy(drag_spacing=bad)
    assert _wave_system(drag_spacing=1).model.drag_spacing == 1


def test_drag_spacing_is_read_from_the_configuration(tmp_path) -> None:  # type: ignore[no-untyped-def]
    from importlib import resources

    from torsio.config.reading import load_config

    text = resources.files("torsio").joinpath("data/ritto2017.toml").read_text(encoding="utf-8")
    text = text.replace("beta = 0.06", "beta = 0.0").replace("dp_elements = 5\n", "")
    text = text.replace("bha_elements = 1\n", "")
    path = tmp_path / "wave.toml"
    path.write_text(text.replace('strategy = "C"', 'strategy = "wave"\ndrag_spacing = 8'))
    assert load_config(path).system().model.drag_spacing == 8
    path.write_text(text.replace('strategy = "C"', 'strategy = "wave"\ndrag_spacing = 0'))
    with pytest.raises(ConfigError, match="discretization.drag_spacing"):
        load_config(path)
    path.write_text(text.replace('strategy = "C"', 'strategy = "C"\ndrag_spacing = 4'))
    with pytest.raises(ConfigError, match="discretization.drag_spacing: strategy 'C' takes no"):
        load_config(path)


class _ContractLaw:
    """A bit-rock law written from the plugin contract alone: a name and torque(), no
    slope, no kernel, no base class (Tucker-Wang's formula, rad/s reading)."""

    name = "contract-tucker-wang"

    def torque(self, speed, wob, radius):  # type: ignore[no-untyped-def]
        w = np.asarray(speed, dtype=float)
        return wob * radius * 0.221 * (np.tanh(1.91 * w) + 8.5 * w / (1.0 + 5.47 * w * w))


def test_a_plugin_law_without_kernel_or_slope_runs_the_same_steps_in_python() -> None:
    # the plain-Python stepping (a law without a compiled kernel) against the compiled one
    # with the same law written as a kernel: the same algorithm, the same numbers up to
    # round-off and the slope's central difference (Newton converges to the same root)
    from torsio.analysis.wave import wave_response

    def kernel_torque(parameters, speed, wob, radius):  # type: ignore[no-untyped-def]
        return (
            wob
            * radius
            * 0.221
            * (math.tanh(1.91 * speed) + 8.5 * speed / (1.0 + 5.47 * speed * speed))
        )

    def kernel_slope(parameters, speed, wob, radius):  # type: ignore[no-untyped-def]
        sech = 1.0 / math.cosh(1.91 * speed)
        rational = 8.5 * (1.0 - 5.47 * speed * speed) / (1.0 + 5.47 * speed * speed) ** 2
        return wob * radius * 0.221 * (1.91 * sech * sech + rational)

    system = attrs.evolve(_wave_system(), law=_ContractLaw()).at(wob=150e3, rpm=60.0)
    python = wave_response(
        system, duration=2.0, steady_window=1.0, output_step=system.model.time_step
    )
    assert python.run.engine == "python"
    kernel = (compile_law_function(kernel_torque), compile_law_function(kernel_slope), np.zeros(1))
    grid = system.model
    from torsio.solvers.wave_top import top_boundary

    steps = python.run.records.shape[0] - 1
    compiled = march(grid, top_boundary(system, grid), system.law, system.wob, system.bit_radius,
                     0.35, steps, record_every=1, kernel=kernel)  # fmt: skip
    np.testing.assert_allclose(python.run.records, compiled.records, rtol=1e-9, atol=1e-9)
