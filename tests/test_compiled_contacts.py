"""Coulomb friction along the string on the compiled RODAS4 engine (solvers/contact_kernel.py):
single runs and maps against the scipy path between located switches
(torsio.solvers.contact_events), the closed forms of torsio.well.break_off, and a one-node
chain with a closed-form stick-slip cycle.

The deviated-well runs are the built-in deviated well (torsio.examples.deviated_well_config:
2.5 km string, mu_s 0.25/0.35, mu_d 0.2/0.3, threshold 0.5 rad/s) on strategy B with 10
drill-pipe and 4 BHA elements, as in tests/test_lumped_friction.py.
"""

from __future__ import annotations

import math

import attrs
import numpy as np
import pytest

from torsio.analysis.energy import energy_balance
from torsio.analysis.transient import simulate
from torsio.errors import ConfigError
from torsio.examples import deviated_well_config
from torsio.model.contacts import StringContacts
from torsio.model.lumped import LumpedModel
from torsio.physics.damping import RayleighDamping
from torsio.physics.laws import TuckerWang
from torsio.physics.system import System
from torsio.solvers.batch import simulate_batch
from torsio.solvers.batch_results import STATUS_CHATTER, STATUS_MESSAGES
from torsio.well.break_off import break_off

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

TIGHT = {"rtol": 1e-8, "atol": 1e-10}


def _deviated(alpha: float, wob: float, rpm: float, **discretization) -> System:
    config = deviated_well_config()
    options = {"strategy": "B", "dp_elements": 10, "bha_elements": 4, **discretization}
    system = config.system(**options)
    return attrs.evolve(system, damping=RayleighDamping(alpha=alpha)).at(wob=wob, rpm=rpm)


# --- the test double: one node on a spring, driven by the held top at Omega --------------
INERTIA, STIFFNESS, STATIC, DYNAMIC = 10.0, 1000.0, 300.0, 200.0  # kg m^2, N m/rad, N m
OMEGA = 2.0 * math.pi  # 60 rpm [rad/s]
NATURAL = math.sqrt(STIFFNESS / INERTIA)  # omega = 10 rad/s
AMPLITUDE = (STATIC - DYNAMIC) / STIFFNESS  # A [rad]: the spring's stretch above C_d / k
BREAK = STATIC / (STIFFNESS * OMEGA)  # stuck from rest until k Omega t = C_s [s]
SLIP = 2.0 * (math.pi - math.atan(AMPLITUDE * NATURAL / OMEGA)) / NATURAL  # [s]
STICK = 2.0 * (STATIC - DYNAMIC) / (STIFFNESS * OMEGA)  # from k x = 2 C_d - C_s to C_s [s]
PEAK = OMEGA + math.hypot(AMPLITUDE * NATURAL, OMEGA)  # the slip's fastest speed [rad/s]


def _slip_speed(tau: np.ndarray) -> np.ndarray:
    """The node's speed tau after it breaks free (I theta'' = k (Omega t - theta) - C_d, from
    k x = C_s, theta' = 0): Omega + A omega sin(omega tau) - Omega cos(omega tau)."""
    wt = NATURAL * tau
    return OMEGA + AMPLITUDE * NATURAL * np.sin(wt) - OMEGA * np.cos(wt)


@pytest.fixture(scope="module")
def coulomb_node() -> System:
    contacts = StringContacts(static=[STATIC], dynamic=[DYNAMIC], threshold_speed=0.0)
    model = LumpedModel([[INERTIA]], [[STIFFNESS]], [1.0]).with_contacts(contacts)
    law = TuckerWang(a0=0.221, a1=0.2, a2=0.89, a3=0.06, speed_unit="rpm")  # 0 at wob = 0
    return System(model=model, law=law, bit_radius=0.108, wob=0.0, rpm=60.0)


def test_the_double_is_the_closed_form_stick_slip_cycle(coulomb_node: System) -> None:
    # reference: the closed form above. Stuck (speed exactly 0) until t = C_s/(k Omega); the
    # slip follows the sinusoid; it sticks again after SLIP, for STICK; two switches a cycle.
    step = 1e-3
    results = simulate(coulomb_node, duration=5.0, output_step=step, progress=False, **TIGHT)
    assert results.solver["engine"] == "compiled" and results.solver["fallback"] is None
    t, speed = results.time, results.bit_speed
    moved = int(np.flatnonzero(speed != 0.0)[0])
    assert t[moved - 1] <= BREAK < t[moved]
    slipping = (t > BREAK) & (t < BREAK + SLIP)
    exact = _slip_speed(t[slipping] - BREAK)
    assert np.max(np.abs(speed[slipping] - exact)) < 1e-6 * PEAK  # rtol 1e-8: measured 2e-9
    again = (t > BREAK + SLIP + 1e-6) & (t < BREAK + SLIP + STICK - 1e-6)
    assert again.sum() > 25 and np.all(speed[again] == 0.0)  # stuck again: exactly at rest
    cycles = np.arange(10) * (SLIP + STICK) + BREAK  # each cycle breaks free, then sticks
    switches = np.sum(cycles < 5.0) + np.sum(cycles + SLIP < 5.0)
    assert results.solver["contact_switches"] == switches
    # S_SS over the window from the in-step extremes: (PEAK - 0)/(2 Omega)
    assert results.severity == pytest.approx(PEAK / (2.0 * OMEGA), rel=1e-7)


def test_the_double_on_the_batch_engine(coulomb_node: System) -> None:
    # reference: the closed form S_SS = PEAK / (2 Omega) (the bit's least speed 0, stuck),
    # and the single run of the same kernel (steady_tolerance 0: the same steps)
    batch = simulate_batch(coulomb_node, [0.0], [60.0], duration=5.0, steady_window=2.5,
                           steady_tolerance=0.0, **TIGHT)  # fmt: skip
    assert batch.engine == "compiled" and batch.ok.all()
    # the least speed: 0, to the location's tolerance (contact_law.TOLERANCE (1 + Omega):
    # the cubic of the step that ends where the node sticks; measured -7.0e-10 rad/s)
    assert abs(batch.bit_speed_min[0]) < 1e-9 * (1.0 + OMEGA)
    assert batch.severity[0] == pytest.approx(PEAK / (2.0 * OMEGA), rel=1e-7)
    single = simulate(coulomb_node, duration=5.0, steady_window=2.5, output_step=1e-2,
                      progress=False, **TIGHT)  # fmt: skip
    assert batch.severity[0] == pytest.approx(single.severity, abs=1e-12)
    assert single.well_summary["friction_work"] > 0.0


def test_a_sliding_contact_does_exact_work(coulomb_node: System) -> None:
    # conservation law: the held top's work = stored energy + C |d theta| of the friction
    # (no damping); the engine's exact sum against the sampled power C_d |theta'|
    results = simulate(coulomb_node, duration=5.0, output_step=1e-4, progress=False, **TIGHT)
    balance = energy_balance(results)
    assert balance.relative_residual < 1e-5
    exact = results.well_summary["friction_work"]
    assert balance.dissipated_friction[-1] == pytest.approx(exact, rel=1e-5)


def test_a_run_that_chatters_ends_with_its_status(coulomb_node: System) -> None:
    # the kernel counts the switches: past the allowed number the point fails, never silently
    from torsio.solvers.batch import BatchModel, _run_compiled
    from torsio.solvers.batch_options import DEFAULT_MAX_STEPS
    from torsio.solvers.law_kernels import law_kernel
    from torsio.solvers.layouts import OUT_COLUMNS, OUT_STATUS
    from torsio.solvers.lumped_inputs import run_settings, step_limits

    model = BatchModel.from_system(coulomb_node)
    kernel = law_kernel(coulomb_node.law)
    settings = run_settings(5.0, 2.5, 1e-8, 1e-10, step_limits(model.first_frequency),
                            DEFAULT_MAX_STEPS, 0.108, 0.0, model.first_frequency, 3)  # fmt: skip
    out = np.zeros((1, OUT_COLUMNS))
    law = (kernel.torque, kernel.slope, kernel.parameters)
    points = (settings, np.zeros(1), np.full(1, OMEGA), np.full(1, OMEGA))
    _run_compiled((model.chain, model.top, *law, *points, out), 1)
    assert out[0, OUT_STATUS] == STATUS_CHATTER
    assert "chatter" in STATUS_MESSAGES[STATUS_CHATTER]


# --- the deviated well: against contact_events and the closed forms ---------------------
@pytest.fixture(scope="module")
def reference():
    config = deviated_well_config()
    return break_off(config.well, config.string)


def test_slow_start_up_breaks_free_at_the_break_off_torque_and_twist(reference) -> None:
    # reference: break_off (int mu_s N r_o dx = 12.174 kN m, twist 19.255 rad), with the
    # quadrature error of the 10-element chain (tests/test_lumped_friction.py: 1.3e-3)
    system = _deviated(alpha=0.0, wob=0.0, rpm=1.0)
    duration = 1.1 * reference.twist / system.omega
    results = simulate(
        system, duration=duration, steady_window=0.1 * duration, output_step=0.05, progress=False
    )
    assert results.solver["engine"] == "compiled" and results.solver["fallback"] is None
    moved = int(np.flatnonzero(results.bit_speed != 0.0)[0])
    assert np.all(results.node_speeds[:moved, -1] == 0.0)  # stuck: exactly at rest
    assert results.surface_torque[moved - 1] == pytest.approx(reference.torque, rel=5e-3)
    assert system.omega * results.time[moved - 1] == pytest.approx(reference.twist, rel=5e-3)
    scipy_run = simulate(system, duration=duration, steady_window=0.1 * duration,
                         output_step=0.05, method="LSODA", progress=False)  # fmt: skip
    assert int(np.flatnonzero(scipy_run.bit_speed != 0.0)[0]) == moved  # the same sample


@pytest.fixture(scope="module")
def stick_slip_pair():
    """One stick-slip point (50 kN, 60 rpm, 60 s) on both engines at rtol 1e-10.

    Its sampled S_SS is sensitive to the switch times: from rtol 1e-8 to 1e-10 it moves by
    5e-3 (compiled) and 1.1e-2 (scipy), to agree at 1e-10 within 6.4e-6 (measured with
    the contacts at the run's 50 kN)."""
    system = _deviated(alpha=0.35, wob=50e3, rpm=60.0)
    run = {"duration": 60.0, "output_step": 0.02, "progress": False, "rtol": 1e-10,
           "atol": 1e-12}  # fmt: skip
    return system, simulate(system, **run), simulate(system, method="LSODA", **run)


def test_stick_slip_agrees_with_the_scipy_engine(stick_slip_pair) -> None:
    # reference: contact_events (LSODA between located switches) at rtol 1e-10 (the
    # fixture): the sampled S_SS to 6.4e-6, the switch counts within 1 %, the bit at rest
    # in the same samples, the sampled bit speeds within 0.05 rad/s (of 15 rad/s peaks).
    system, compiled, scipy_run = stick_slip_pair
    assert compiled.solver["engine"] == "compiled" and scipy_run.solver["engine"] == "scipy"
    window = compiled.time >= compiled.time[-1] - compiled.steady_window
    sampled = [np.ptp(r.bit_speed[window]) / (2.0 * system.omega) for r in (compiled, scipy_run)]
    assert sampled[0] == pytest.approx(sampled[1], rel=1e-4)
    assert np.sum(compiled.bit_speed == 0.0) == np.sum(scipy_run.bit_speed == 0.0)
    switches = compiled.solver["contact_switches"], scipy_run.solver["contact_switches"]
    assert abs(switches[0] - switches[1]) <= 0.01 * switches[1]
    assert np.max(np.abs(compiled.bit_speed - scipy_run.bit_speed)) < 0.05
    # the in-step extremes read the peaks between samples: at least the sampled range
    assert compiled.severity >= sampled[0]


def test_the_energy_balance_closes_with_the_friction(stick_slip_pair) -> None:
    # conservation law: the held top's work = stored + drag + bit + friction; the sampled
    # friction power sum C |theta'| integrated against the engine's exact sum C |d theta|
    _, compiled, scipy_run = stick_slip_pair
    balance = energy_balance(compiled)
    assert balance.relative_residual < 1e-3
    exact = compiled.well_summary["friction_work"]
    assert balance.dissipated_friction[-1] == pytest.approx(exact, rel=1e-3)
    assert exact == pytest.approx(scipy_run.well_summary["friction_work"], rel=1e-4)


def test_a_map_with_contacts_is_its_single_runs(reference) -> None:
    # reference: each point run alone (simulate_batch) and as a single run (simulate, the
    # same kernel and steps with steady_tolerance 0). The map and a batch of one differ by
    # round-off in how the map packs its points, contacts or not (measured without
    # contacts: 2e-12; with them: 6.5e-12)
    from torsio.analysis.maps import severity_map

    system = _deviated(alpha=0.35, wob=0.0, rpm=60.0)
    wob, rpm = [0.0, 40e3], [60.0, 120.0]
    tolerances = {"rtol": 1e-6, "atol": 1e-6}
    run = {"duration": 30.0, "steady_window": 10.0, "steady_tolerance": 0.0, **tolerances}
    grid = severity_map(system, wob, rpm, **run)
    assert grid.severity.shape == (2, 2) and np.all(np.isfinite(grid.severity))
    for i, w in enumerate(wob):
        for j, r in enumerate(rpm):
            alone = simulate_batch(system, [w], [r], **run)
            assert alone.engine == "compiled"
            assert grid.severity[j, i] == pytest.approx(alone.severity[0], abs=1e-10)
    single = simulate(system.at(wob=40e3, rpm=120.0), duration=30.0, steady_window=10.0,
                      output_step=0.02, progress=False, **tolerances)  # fmt: skip
    assert grid.severity[1, 1] == pytest.approx(single.severity, abs=1e-12)


def test_the_scipy_batch_engine_refuses_contacts() -> None:
    system = _deviated(alpha=0.35, wob=0.0, rpm=60.0)
    with pytest.raises(ConfigError, match=r"^engine: .*takes no contacts"):
        simulate_batch(system, [0.0], [60.0], engine="scipy")


def test_the_numpy_and_compiled_batch_engines_agree_with_contacts() -> None:
    # reference: the two implementations of one method (RODAS4, contacts switched at their
    # located margins, torsio.solvers.contact_kernel and numpy_contacts), each with its own
    # steps: S_SS the same to the tolerance's order (rtol 1e-8; measured 5.9e-10 over 4 s,
    # S_SS 0.60 and 0.95)
    system = _deviated(alpha=0.35, wob=0.0, rpm=60.0)
    points = ([0.0, 40e3], [60.0, 100.0])
    run = {"duration": 4.0, "steady_window": 2.0, "rtol": 1e-8, "atol": 1e-10}
    compiled = simulate_batch(system, *points, engine="compiled", **run)
    numpy = simulate_batch(system, *points, engine="numpy", **run)
    assert compiled.engine == "compiled" and numpy.engine == "numpy"
    assert (compiled.status == 0).all() and (numpy.status == 0).all()
    np.testing.assert_allclose(numpy.severity, compiled.severity, atol=1e-7)


def test_contacts_behind_a_pi_top_drive_agree_with_the_scipy_engine() -> None:
    # reference: contact_events (LSODA between located switches) at rtol 1e-8, the top drive
    # a node without a contact (its speed loop eliminated into rows 0 and 1 of the step
    # matrix). Measured over 20 s: the same 792 switches, the bit at rest in the same 163
    # samples, the sampled bit speeds to 9.0e-5 rad/s, the top speed to 1.8e-6 rad/s, the
    # friction's work to 2.1e-8 (over 60 s: 3899 switches, 9.7e-5, 2.8e-7, 2e-9)
    from torsio.plugins import top_drive_from_parameters

    top = top_drive_from_parameters("pi", inertia=2900.0, kp=5000.0, ki=2900.0 * 0.8**2)
    system = attrs.evolve(_deviated(alpha=0.35, wob=50e3, rpm=60.0), top=top)
    run = {"duration": 20.0, "output_step": 0.02, "progress": False, **TIGHT}
    compiled = simulate(system, **run)
    scipy_run = simulate(system, method="LSODA", **run)
    assert compiled.solver["engine"] == "compiled"
    assert compiled.solver["contact_switches"] == scipy_run.solver["contact_switches"] > 100
    assert np.max(np.abs(compiled.bit_speed - scipy_run.bit_speed)) < 1e-3
    assert np.max(np.abs(compiled.top_speed - scipy_run.top_speed)) < 1e-5
    work = compiled.well_summary["friction_work"], scipy_run.well_summary["friction_work"]
    assert work[0] == pytest.approx(work[1], rel=1e-6)
    assert np.array_equal(compiled.bit_speed == 0.0, scipy_run.bit_speed == 0.0)


def test_chunks_do_not_change_a_step_with_contacts() -> None:
    # the run carried over one-sample chunks against the default chunks: bit for bit, the
    # contacts' states, switches and work carried in the work space
    from torsio.physics.dynamics import Dynamics
    from torsio.solvers.single_run import compiled_engine, integrate_compiled

    system = _deviated(alpha=0.35, wob=50e3, rpm=60.0)
    dynamics = Dynamics.from_system(system)
    kernel, why = compiled_engine(system, dynamics)
    assert kernel is not None, why
    grid = np.linspace(0.0, 20.0, 1001)
    y0 = dynamics.rest_state()
    whole = integrate_compiled(system, dynamics, kernel, y0, grid, 10.0, 1e-6, 1e-9)
    tiny = integrate_compiled(system, dynamics, kernel, y0, grid, 10.0, 1e-6, 1e-9,
                              chunk_seconds=1e-9)  # fmt: skip
    np.testing.assert_array_equal(tiny.states, whole.states)
    assert (tiny.steps, tiny.rejected, tiny.switches) == (
        whole.steps,
        whole.rejected,
        whole.switches,
    )
    assert tiny.friction_work == whole.friction_work > 0.0 and whole.contacts


def test_weights_in_pieces_on_two_threads_give_the_serial_batch() -> None:
    # reference: every point runs alone from rest, so the pieces a weight's points are cut
    # into for two threads (and their order, heaviest weight first) change nothing, bit for
    # bit; each point with its own weight's contacts
    system = _deviated(alpha=0.35, wob=0.0, rpm=60.0)
    wob = np.repeat([0.0, 40e3, 80e3], 3)
    rpm = np.tile([60.0, 90.0, 120.0], 3)
    run = {"duration": 3.0, "steady_window": 1.5}
    serial = simulate_batch(system, wob, rpm, threads=1, **run)
    threaded = simulate_batch(system, wob, rpm, threads=2, **run)
    assert np.array_equal(serial.severity, threaded.severity, equal_nan=True)
    assert np.array_equal(serial.steps, threaded.steps)
    alone = simulate_batch(system.at(wob=80e3), [80e3], [90.0], threads=1, **run)
    assert threaded.severity[7] == alone.severity[0]


def test_the_holding_torque_rate_is_the_chain_force_law_differentiated() -> None:
    # reference: the model's dense [K] and [C] (Dynamics.stiffness_matrix, damping_matrix):
    # a node's force without friction is applied - drag Omega - ([K] phi + [C] v)_i, so its
    # rate is -([K] v + [C] a)_i (contact_kernel.holding_rate, which locates the release of a
    # stuck node on the step's cubic)
    from torsio.solvers.contact_kernel import holding_rate
    from torsio.solvers.lumped_inputs import pack_chain

    dynamics = _deviated(alpha=0.35, wob=40e3, rpm=60.0).dynamics()
    chain = pack_chain(dynamics)
    rng = np.random.default_rng(7)
    speeds, accelerations = rng.normal(size=(2, chain.shape[1]))
    expected = -(dynamics.stiffness_matrix @ speeds + dynamics.damping_matrix @ accelerations)
    padded = np.concatenate([[0.0], accelerations, [0.0]])
    rates = [
        holding_rate(chain, speeds, i, padded[i], padded[i + 1], padded[i + 2])
        for i in range(chain.shape[1])
    ]
    np.testing.assert_allclose(rates, expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())


def test_a_switch_is_located_on_the_cubic_of_the_speed() -> None:
    # reference: a node whose speed is exactly a cubic over the step (the cubic Hermite
    # interpolant of its end values and slopes is that cubic): w(x) = 1 - 3x + x^3, whose
    # root in (0, 1) is 2 cos(4 pi / 9) = 0.347296...; contact_kernel.cubic_crossing aims at
    # half the tolerance below 0 and stops within a quarter of it
    from torsio.solvers.contact_kernel import cubic_crossing
    from torsio.solvers.contact_law import TOLERANCE
    from torsio.solvers.layouts import CHAIN_CONTACT_STATIC, CHAIN_CONTACT_THRESHOLD, CHAIN_ROWS

    chain = np.zeros((CHAIN_ROWS, 1))
    chain[CHAIN_CONTACT_STATIC], chain[CHAIN_CONTACT_THRESHOLD] = 100.0, 0.0
    state = np.array([2.0])  # fast, turning forward: margin 0 is the speed itself
    tolerance = TOLERANCE * 2.0
    speed0, speed1, slope0, slope1 = 1.0, -1.0, -3.0, 0.0  # w, w' at x = 0 and 1
    x = cubic_crossing(
        chain, state, 0.0, 0, 0, speed0, speed1, slope0, slope1, speed0, speed1, tolerance
    )
    root = 2.0 * math.cos(4.0 * math.pi / 9.0)
    speed = 1.0 - 3.0 * x + x**3
    assert abs(speed + 0.5 * tolerance) <= 0.25 * tolerance
    assert x == pytest.approx(root, abs=2.0 * tolerance)
