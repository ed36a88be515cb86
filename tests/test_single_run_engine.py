"""One engine for single runs and maps: ``simulate`` on the compiled RODAS4 kernel.

Sources of the expected values: the independent integrator, scipy's LSODA on the
right-hand side of torsio.physics.dynamics (``simulate(method="LSODA")``), and the map
engine (``simulate_batch``, the same kernel as severity maps). The tolerances:

* compiled ``simulate`` against the map engine at the same tolerances and run: the same
  steps from the same start, S_SS from the same in-step extremes, so to round-off (1e-12);
* compiled ``simulate`` against LSODA, both at rtol 1e-8, atol 1e-10, S_SS of the sampled
  bit speed on the same output grid (what LSODA reads): each solver's error in S_SS is of
  order 1e-7 at this tolerance (docs/performance.md: 2.9e-7 at rtol 1e-7 on 10 DOFs), so
  1e-6. The compiled run's own S_SS reads the extremes of its continuous solution, which
  bound the samples from outside; the default grid (200 samples per period) under-reads
  them by up to 9.1e-5 in these cases (measured: 5 DOFs, Tucker-Wang), so 2e-4.

Cases: the built-in Ritto et al. (2017) string with 1 DOF (strategy A), 5 DOF (strategy C)
and 40 DOF (strategy C, 40 drill-pipe elements), Tucker-Wang at 150 kN, 60 rpm; a law
written from the plugin contract alone (``torque`` only, no ``kernel()``: the regularized
Coulomb-Stribeck formula of the bundled plugin, Navarro-Lopez and Cortes 2007) at 100 kN,
30 rpm, compiled from its Python ``torque`` by numba; a 1-DOF run with a PI top drive
(controller state in the samples). All are stick-slip points (S_SS > 0.8, asserted).
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np
import pytest

from torsio.analysis.transient import simulate
from torsio.errors import ConfigError
from torsio.examples import builtin_config
from torsio.physics.dynamics import Dynamics
from torsio.physics.system import System
from torsio.plugins import top_drive_from_parameters
from torsio.solvers.batch import simulate_batch
from torsio.solvers.single_run import compiled_engine, integrate_compiled

RUN = {"duration": 60.0, "steady_window": 20.0, "rtol": 1e-8, "atol": 1e-10}
MODELS = {1: {"strategy": "A"}, 5: {"strategy": "C"}, 40: {"strategy": "C", "dp_elements": 40}}


class PlainStribeck:
    """T = W R [mu_c + (mu_s - mu_c) exp(-|w|/w_s)] tanh(w/eps): torque only, no kernel."""

    name = "plain-stribeck"

    def __init__(self, mu_static: float = 0.8, mu_coulomb: float = 0.5) -> None:
        self.mu_static = mu_static
        self.mu_coulomb = mu_coulomb
        self.stribeck_speed = 1.0 / 0.9
        self.smoothing = 0.01

    def torque(self, speed: Any, wob: Any, radius: Any) -> Any:
        weakening = (self.mu_static - self.mu_coulomb) * np.exp(
            -np.abs(speed) / self.stribeck_speed
        )
        return wob * radius * (self.mu_coulomb + weakening) * np.tanh(speed / self.smoothing)


class UncompilableStribeck(PlainStribeck):
    """The same law through ``np.asarray(..., dtype=float)``, which numba does not type."""

    name = "uncompilable-stribeck"

    def torque(self, speed: Any, wob: Any, radius: Any) -> Any:
        return super().torque(np.asarray(speed, dtype=float), wob, radius)


def _system(dofs: int, law: str = "tucker-wang", top: str = "constant-speed") -> System:
    system = builtin_config().system(**MODELS[dofs])
    assert system.model.dofs == dofs
    wob, rpm = 150e3, 60.0
    if law == "plain":
        system, wob, rpm = attrs.evolve(system, law=PlainStribeck()), 100e3, 30.0
    if top == "pi":
        pi = top_drive_from_parameters("pi", inertia=2900.0, kp=5000.0, ki=2900.0)
        system = system.with_top(pi)
    return system.at(wob=wob, rpm=rpm)


CASES = [
    pytest.param(1, "tucker-wang", "constant-speed"),
    pytest.param(5, "tucker-wang", "constant-speed"),
    pytest.param(40, "tucker-wang", "constant-speed"),
    pytest.param(1, "plain", "constant-speed"),
    pytest.param(5, "plain", "constant-speed"),
    pytest.param(1, "tucker-wang", "pi"),
]


@pytest.mark.parametrize(("dofs", "law", "top"), CASES)
def test_every_engine_gives_the_same_severity(dofs: int, law: str, top: str) -> None:
    system = _system(dofs, law, top)
    compiled = simulate(system, **RUN)
    lsoda = simulate(system, method="LSODA", **RUN)
    assert compiled.solver["engine"] == "compiled" and compiled.solver["method"] == "RODAS4"
    assert lsoda.solver["engine"] == "scipy" and lsoda.solver["method"] == "LSODA"
    assert compiled.severity > 0.8
    window = compiled.window_mask
    speeds = compiled.bit_speed[window]
    sampled = (speeds.max() - speeds.min()) / (2.0 * compiled.omega)
    assert abs(sampled - lsoda.severity) < 1e-6
    assert sampled <= compiled.severity + 1e-12 and compiled.severity - sampled < 2e-4
    rpm = None if top == "torque" else [system.rpm]
    batch = simulate_batch(system, [system.wob], rpm, steady_tolerance=0.0, **RUN)
    assert batch.engine == "compiled" and batch.ok.all()
    assert batch.severity[0] == pytest.approx(compiled.severity, abs=1e-12)
    # the same series as the scipy run: every state, the torques, the top speed
    assert compiled.states.shape == lsoda.states.shape
    scale = np.abs(lsoda.states).max(axis=0) + 1.0
    assert np.all(np.abs(compiled.states - lsoda.states).max(axis=0) < 1e-3 * scale)
    for name in ("bit_speed", "bit_angle", "surface_torque", "motor_torque", "top_speed"):
        ours, theirs = getattr(compiled, name), getattr(lsoda, name)
        assert np.abs(ours - theirs).max() <= 1e-3 * (np.abs(theirs).max() + 1.0), name


def test_chunks_do_not_change_a_step() -> None:
    # the run carried over one-sample chunks against the default chunks: bit for bit
    system = _system(1)
    dynamics = Dynamics.from_system(system)
    kernel, why = compiled_engine(system, dynamics)
    assert kernel is not None, why
    grid = np.linspace(0.0, 30.0, 801)
    y0 = dynamics.rest_state()
    seen: list[int] = []
    whole = integrate_compiled(system, dynamics, kernel, y0, grid, 10.0, 1e-6, 1e-9)
    tiny = integrate_compiled(
        system, dynamics, kernel, y0, grid, 10.0, 1e-6, 1e-9,
        progress=lambda done, total: seen.append(done), chunk_seconds=1e-9,
    )  # fmt: skip
    np.testing.assert_array_equal(tiny.states, whole.states)
    assert (tiny.steps, tiny.rejected) == (whole.steps, whole.rejected)
    assert len(seen) > 100 and seen == sorted(seen) and seen[-1] == grid.size


@pytest.mark.parametrize("method", ["auto", "LSODA"])
def test_progress_reports_the_samples_reached(method: str) -> None:
    seen: list[tuple[int, int]] = []
    results = simulate(
        _system(5), method=method, rtol=1e-10, atol=1e-12,
        progress=lambda done, total: seen.append((done, total)),
    )  # fmt: skip
    samples = results.time.size
    assert seen and all(total == samples for _, total in seen)
    assert [done for done, _ in seen] == sorted(done for done, _ in seen)
    if method == "auto":  # the compiled engine reports its last chunk: every sample
        assert seen[-1] == (samples, samples)


def test_a_law_numba_cannot_compile_runs_on_scipy_and_says_why() -> None:
    system = attrs.evolve(_system(1), law=UncompilableStribeck()).at(wob=100e3, rpm=30.0)
    results = simulate(system, duration=30.0, steady_window=10.0)
    assert results.solver["engine"] == "scipy" and results.solver["method"] == "LSODA"
    assert "numba cannot compile" in results.solver["fallback"]
    assert "uncompilable-stribeck" in results.solver["fallback"]
    with pytest.raises(ConfigError, match=r"simulation\.method.*RODAS4.*cannot run"):
        simulate(system, duration=30.0, steady_window=10.0, method="RODAS4")
    # the map engine: numba cannot compile it either, so the numpy engine runs it
    assert simulate_batch(system, [100e3], [30.0], duration=30.0).engine == "numpy"


def test_a_plain_law_runs_compiled_in_maps_too() -> None:
    system = _system(1, "plain")
    batch = simulate_batch(system, [100e3, 150e3], [30.0, 30.0], duration=30.0)
    assert batch.engine == "compiled" and batch.ok.all()
