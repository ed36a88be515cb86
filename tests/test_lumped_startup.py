"""Start-ups on the lumped engines: a set speed that changes in time (docs/top_drives.md).

A controlled top drive's ``ramp = T`` raises its set speed linearly from 0 over T; a held top
may follow a table (a recorded top-drive speed). The compiled RODAS4 engine and scipy take
both from the one description (torsio.physics.dynamics), the table read by one function
(torsio.solvers.set_speed); maps refuse them by key.
"""

from __future__ import annotations

import json
import math
from importlib import resources
from typing import Any, ClassVar

import attrs
import numpy as np
import pytest

from torsio.analysis.energy import energy_balance
from torsio.analysis.transient import simulate, simulate_config
from torsio.calibration.recording import Recording
from torsio.cli import main
from torsio.config.reading import load_config
from torsio.errors import ConfigError
from torsio.examples import builtin_config, deviated_well_config
from torsio.model.lumped import LumpedModel
from torsio.physics.damping import RayleighDamping
from torsio.physics.recorded_top import RecordedTopDrive
from torsio.physics.system import System
from torsio.physics.top_drive_boundary import TopDriveBoundary
from torsio.physics.top_drives import PITopDrive
from torsio.solvers.batch import simulate_batch
from torsio.solvers.set_speed import table_at, twist_table

PI_RAMP = '\n[top_drive]\nkind = "pi"\ninertia = 2900.0\nkp = 5000.0\nki = 2067.6\nramp = 5.0\n'
"""A PI top drive (J of a top drive with gearbox, ki = 0.8^2 J... as in tests/test_axial_top_drive)
whose set speed ramps from 0 over 5 s."""


def _ritto_with(tmp_path: Any, extra: str, beta: float | None = None) -> Any:
    """The built-in ritto2017.toml with ``extra`` appended (and [damping] beta replaced)."""
    text = resources.files("torsio").joinpath("data/ritto2017.toml").read_text(encoding="utf-8")
    if beta is not None:
        text = text.replace("beta = 0.06", f"beta = {beta}")
    path = tmp_path / "ritto_startup.toml"
    path.write_text(text + extra, encoding="utf-8")
    return path


@attrs.frozen
class RampedHeldTop:
    """A top held at a set speed that ramps from 0 over ``ramp`` [s] (the top-drive
    contract: name, boundary); the built-in constant-speed top takes no ramp."""

    name: ClassVar[str] = "ramped-held"
    speed: float
    ramp: float

    def boundary(self, system: Any) -> TopDriveBoundary:
        return TopDriveBoundary(inertia=0.0, set_speed=self.speed, ramp=self.ramp)


def test_the_held_top_twist_is_the_integral_of_the_set_speed():
    # exact: psi(t) = int_0^t (Omega_set - Omega_ref) ds of a linear ramp 0 -> 6 rad/s over
    # 2 s, Omega_ref = 6: 1.5 t^2 - 6 t on the ramp, -6 rad (= -Omega T / 2) after it
    table = twist_table(np.array([[0.0, 2.0], [0.0, 6.0]]), 6.0)
    times = np.array([0.0, 0.5, 2.0, 7.0])
    speeds, twists = table_at(table, times, 6.0)
    assert speeds.tolist() == [0.0, 1.5, 6.0, 6.0]
    assert twists == pytest.approx([0.0, 1.5 * 0.25 - 3.0, -6.0, -6.0], abs=1e-15)
    # a table that starts after t = 0 holds its first speed before it (psi(0) = 0)
    late = twist_table(np.array([[1.0, 3.0], [2.0, 4.0]]), 4.0)
    assert table_at(late, 3.0, 4.0)[1] == pytest.approx(-2.0 * 1.0 - 1.0 * 2.0, abs=1e-15)


def _one_dof_ramp(method: str):
    """A 1-DOF chain (J = 1000 kg m^2, k = 2000 N m/rad, c = beta k, zeta = 0.1) whose top
    is held at a set speed ramping to 5 rad/s over 3 s, no torque on bit (wob = 0)."""
    inertia, stiffness, zeta = 1000.0, 2000.0, 0.1
    damper = 2.0 * zeta * math.sqrt(stiffness * inertia)
    base = builtin_config().system(strategy="A")
    system = System(
        model=LumpedModel.from_chain([inertia], [stiffness]),
        law=base.law,
        bit_radius=base.bit_radius,
        damping=RayleighDamping(beta=damper / stiffness),
        wob=0.0,
        top=RampedHeldTop(speed=5.0, ramp=3.0),
    )
    results = simulate(
        system, duration=20.0, steady_window=5.0, method=method, rtol=1e-9, atol=1e-11,
        output_step=0.01, progress=False,
    )  # fmt: skip
    return results, (inertia, stiffness, damper, 5.0, 3.0)


@pytest.mark.parametrize("method", ["RODAS4", "Radau"])
def test_a_held_top_ramp_on_one_dof_follows_the_closed_form(method):
    # exact: the twist x = theta_top - theta of J x'' + c x' + k x = J a(t), a = Omega/T on
    # (0, T), from rest, is the step response x_s(t) = (J a / k)(1 - e^(-zeta w t)(cos wd t +
    # zeta w / wd sin wd t)) less x_s(t - T) from T on; the surface torque is k x + c x' and
    # the bit speed Omega_set(t) - x'
    results, (inertia, k, c, speed, ramp) = _one_dof_ramp(method)
    t = results.time
    w = math.sqrt(k / inertia)
    zeta = c / (2.0 * math.sqrt(k * inertia))
    wd = w * math.sqrt(1.0 - zeta**2)
    scale = inertia * (speed / ramp) / k

    def step(s):
        s = np.maximum(s, 0.0)
        decay = np.exp(-zeta * w * s)
        x = scale * (1.0 - decay * (np.cos(wd * s) + zeta * w / wd * np.sin(wd * s)))
        return np.where(s > 0.0, x, 0.0), np.where(
            s > 0.0, scale * decay * w**2 / wd * np.sin(wd * s), 0.0
        )

    (x1, v1), (x2, v2) = step(t), step(t - ramp)
    twist, rate = x1 - x2, v1 - v2
    set_speed = speed * np.minimum(t / ramp, 1.0)
    torque = k * twist + c * rate
    # the integrators' tolerances (rtol 1e-9): 1e-7 of the scales, the bit speed's Omega and
    # the peak torque
    assert np.max(np.abs(results.bit_speed - (set_speed - rate))) < 1e-7 * speed
    assert np.max(np.abs(results.surface_torque - torque)) < 1e-7 * np.max(np.abs(torque))
    assert np.max(np.abs(results.top_speed - set_speed)) < 1e-12 * speed  # the table's own
    # after the ramp the twist decays to the static twist under no torque on bit, 0, and the
    # speed to the set speed: within the envelope of the free oscillation left at the ramp's
    # end, |x| <= 2 scale e^(-zeta w (t - T)) / sqrt(1 - zeta^2), |x'| <= that w
    envelope = 2.0 * scale * math.exp(-zeta * w * (t[-1] - ramp)) / math.sqrt(1.0 - zeta**2)
    assert abs(results.bit_speed[-1] - speed) <= envelope * w
    assert abs(results.surface_torque[-1]) <= (k + c * w) * envelope
    assert results.severity == pytest.approx(
        (
            results.bit_speed[results.window_mask].max()
            - results.bit_speed[results.window_mask].min()
        )
        / (2.0 * speed),
        rel=1e-3,
    )
    # conservation law: the top's work at Omega_set(t) = stored + dissipated
    assert energy_balance(results).relative_residual < 1e-6


def test_compiled_and_scipy_agree_on_a_pi_ramp_on_strategy_c(tmp_path):
    # independent engine: scipy's Radau on the same description (torsio.physics.dynamics)
    # against the compiled RODAS4 kernel, both at rtol 1e-8, on the Ritto et al. (2017)
    # string (built-in ritto2017.toml, strategy C) with a PI top drive ramped over 5 s
    config = load_config(_ritto_with(tmp_path, PI_RAMP))
    system = config.system(strategy="C").at(wob=100e3, rpm=100)
    runs = {
        method: simulate(
            system,
            duration=30.0,
            steady_window=10.0,
            method=method,
            rtol=1e-8,
            atol=1e-10,
            output_step=0.01,
            progress=False,
        )  # fmt: skip
        for method in ("RODAS4", "Radau")
    }
    compiled, reference = runs["RODAS4"], runs["Radau"]
    assert compiled.solver["engine"] == "compiled" and reference.solver["engine"] == "scipy"
    scale = np.max(np.abs(reference.surface_torque))
    assert np.max(np.abs(compiled.surface_torque - reference.surface_torque)) < 1e-6 * scale
    assert np.max(np.abs(compiled.bit_speed - reference.bit_speed)) < 1e-6 * system.omega
    assert np.max(np.abs(compiled.top_speed - reference.top_speed)) < 1e-6 * system.omega
    # the top drive trails its ramp (its inertia and the string load it), then holds the
    # set speed in the window
    early = compiled.time <= 2.0
    ramp = system.omega * compiled.time[early] / 5.0
    assert (
        np.all(compiled.top_speed[early] <= ramp) and compiled.top_speed[early][-1] > 0.5 * ramp[-1]
    )
    assert compiled.top_speed_mean == pytest.approx(system.omega, rel=1e-3)  # PI: no offset
    # conservation law: the motor's work = stored + dissipated, on both engines
    for run in runs.values():
        assert energy_balance(run).relative_residual < 1e-5


@pytest.mark.parametrize(("wob", "rpm", "stick_slip"), [(100e3, 100.0, False), (175e3, 60.0, True)])
def test_a_lumped_start_up_agrees_with_the_wave_model(tmp_path, wob, rpm, stick_slip):
    # independent model: the wave model of the continuum (characteristics) of the same
    # string, top drive and ramp (beta = 0: the wave model carries alpha only). The lumped
    # models differ from it by their discretization: strategy C with 5 drill-pipe elements
    # reads the surface torque at the end of the ramp within 2 %, with 20 closer still, and
    # both find the same outcome (stick-slip or none) and S_SS within 3 %.
    config = load_config(_ritto_with(tmp_path, PI_RAMP, beta=0.0))
    runs = {
        name: simulate_config(
            config,
            wob=wob,
            rpm=rpm,
            discretization=discretization,
            duration=60.0,
            steady_window=20.0,
            progress=False,
        )  # fmt: skip
        for name, discretization in (
            ("wave", {"strategy": "wave"}),
            ("C", {"strategy": "C"}),
            ("C20", {"strategy": "C", "dp_elements": 20}),
        )
    }

    def at_ramp_end(run):
        return float(np.interp(5.0, run.time, run.surface_torque))

    wave = at_ramp_end(runs["wave"])
    errors = {name: abs(at_ramp_end(runs[name]) / wave - 1.0) for name in ("C", "C20")}
    assert errors["C"] < 0.02 and errors["C20"] < errors["C"]
    for name in ("C", "C20"):
        assert (
            (runs[name].stick_fraction > 0.1) == (runs["wave"].stick_fraction > 0.1) == stick_slip
        )
        assert runs[name].severity == pytest.approx(runs["wave"].severity, rel=0.03, abs=1e-3)


def test_simulate_on_strategy_c_with_a_pi_ramp_gives_json(tmp_path, capsys):
    # the acceptance: a PI top drive with ramp = 5 on strategy C of ritto2017.toml
    path = _ritto_with(tmp_path, PI_RAMP)
    status = main(["simulate", str(path), "--strategy", "C", "--duration", "30", "--json"])
    captured = capsys.readouterr()
    assert status == 0, captured.err
    data = json.loads(captured.out)
    assert data["top_drive"] == "pi" and data["solver"]["engine"] == "compiled"
    assert data["top_speed_mean"] == pytest.approx(100 * math.pi / 30, rel=1e-3)  # 100 rpm


def _recording_file(tmp_path: Any) -> Any:
    """A rig record: the top ramped to 100 rpm over 10 s, then held (the torque column is
    read only by torsio fit)."""
    time = np.arange(0.0, 40.5, 0.5)
    rpm = 100.0 * np.minimum(time / 10.0, 1.0)
    rows = "".join(f"{t:g},{r:g},{5000.0:g}\n" for t, r in zip(time, rpm, strict=True))
    path = tmp_path / "rig.csv"
    path.write_text("time,top_rpm,surface_torque\n" + rows, encoding="utf-8")
    return path


@pytest.mark.parametrize("strategy", ["A", "C"])
def test_a_recorded_top_runs_on_the_lumped_strategies(tmp_path, capsys, strategy):
    # the held top turns at the record's speed (the table itself, linear between samples)
    _recording_file(tmp_path)
    extra = '\n[top_drive]\nkind = "recorded"\nrecording = "rig.csv"\n'
    path = _ritto_with(tmp_path, extra)
    status = main(["simulate", str(path), "--strategy", strategy, "--duration", "40", "--json"])
    captured = capsys.readouterr()
    assert status == 0, captured.err
    data = json.loads(captured.out)
    assert data["rpm_source"] == "top_speed_mean"
    assert data["rpm"] == pytest.approx(100.0, rel=1e-12)  # held at the last sample's speed
    config = load_config(path)
    results = simulate_config(config, discretization={"strategy": strategy}, duration=40.0,
                              progress=False)  # fmt: skip
    expected = 100.0 * math.pi / 30.0 * np.minimum(results.time / 10.0, 1.0)
    assert np.max(np.abs(results.top_speed - expected)) < 1e-12
    # conservation law: the top's work at the recorded speed = stored + dissipated
    assert energy_balance(results).relative_residual < 1e-5


def test_a_recorded_top_is_held_past_the_record_and_says_so():
    record = Recording(time=[0.0, 4.0], top_speed=[0.0, 6.0], surface_torque=[0.0, 0.0],
                       name="short.csv")  # fmt: skip
    system = builtin_config().system(strategy="A").with_top(RecordedTopDrive(recording=record))
    results = simulate(system.at(wob=50e3), duration=20.0, progress=False)
    assert any("outlasts the recording short.csv" in text for text in results.warnings)


def test_a_map_of_ramped_start_ups_agrees_with_scipy_and_single_runs(tmp_path):
    # independent engine: the scipy batch engine (Radau from rest, the same description)
    # against the compiled batch kernel, each point ramped to its own set speed over 5 s;
    # and the compiled single run of a point (the same kernel, sampled): S_SS within the
    # integrators' tolerance (rtol 1e-8), the single run to 1e-9
    config = load_config(_ritto_with(tmp_path, PI_RAMP))
    system = config.system(strategy="C")
    points = {"wob": [100e3, 175e3], "rpm": [100.0, 60.0]}
    options = {"duration": 40.0, "steady_window": 15.0, "rtol": 1e-8, "atol": 1e-10}
    compiled = simulate_batch(system, **points, engine="compiled", steady_tolerance=0.0,
                              **options)  # fmt: skip
    reference = simulate_batch(system, **points, engine="scipy", **options)
    assert compiled.ok.all() and reference.ok.all()
    assert np.max(np.abs(compiled.severity - reference.severity)) < 1e-4
    single = simulate(system.at(wob=175e3, rpm=60.0), method="RODAS4", progress=False, **options)
    assert single.severity == pytest.approx(compiled.severity[1], rel=1e-9)
    assert compiled.severity[1] > 1.0 > 0.01 > compiled.severity[0]  # stick-slip, and none
    # the early end on a steady cycle waits for the ramp's end, then reads S_SS to its
    # tolerance (torsio.solvers.cycles: 1e-3 S_SS units by default)
    early = simulate_batch(system, **points, engine="compiled", **options)
    assert np.all(early.ended > 5.0)
    assert np.max(np.abs(early.severity - compiled.severity)) < 1e-3


def test_a_small_batch_takes_the_batch_kernels_steps(tmp_path, monkeypatch):
    # a batch of fewer than SMALL_BATCH points runs each point through the single run's
    # kernel (rodas_kernels.run_points), a larger one through the batch loop: the same
    # compiled steps from the same start, so the rows agree bitwise (ramped PI start-ups
    # from rest, strategy C of the built-in Ritto et al. 2017 string)
    from torsio.solvers import rodas_kernels

    system = load_config(_ritto_with(tmp_path, PI_RAMP)).system(strategy="C")
    points = {"wob": [100e3, 175e3, 60e3], "rpm": [100.0, 60.0, 140.0]}
    options = {"duration": 30.0, "steady_window": 10.0, "engine": "compiled", "threads": 1}
    small = simulate_batch(system, **points, **options)
    monkeypatch.setattr(rodas_kernels, "SMALL_BATCH", 0)  # every batch through the loop
    loop = simulate_batch(system, **points, **options)
    assert small.ok.all()
    for field in ("severity", "bit_speed_max", "bit_speed_min", "top_speed_mean", "steps"):
        np.testing.assert_array_equal(getattr(small, field), getattr(loop, field), err_msg=field)


def test_a_map_refuses_a_recorded_top_and_numpy_a_ramp_by_key():
    record = Recording(time=[0.0, 4.0], top_speed=[0.0, 6.0], surface_torque=[0.0, 0.0],
                       name="rig.csv")  # fmt: skip
    for strategy in ("A", "wave"):
        system = builtin_config().system(strategy=strategy)
        system = attrs.evolve(system, damping=RayleighDamping(alpha=0.35))  # wave: alpha only
        recorded = system.with_top(RecordedTopDrive(recording=record))
        with pytest.raises(ConfigError, match=r"top_drive\.kind: .*follows a table"):
            simulate_batch(recorded, wob=[100e3], rpm=[60.0])
    ramped = (
        builtin_config()
        .system(strategy="A")
        .with_top(PITopDrive(inertia=2900.0, kp=5000.0, ki=1000.0, ramp=10.0))
    )
    with pytest.raises(ConfigError, match=r"top_drive\.ramp: the numpy batch engine"):
        simulate_batch(ramped, wob=[100e3], rpm=[60.0], engine="numpy")


def test_a_held_top_that_changes_speed_needs_lumped_mass():
    system = builtin_config().system(strategy="consistent").with_top(RampedHeldTop(6.0, 2.0))
    with pytest.raises(ConfigError, match=r"discretization\.strategy: the top's acceleration"):
        system.dynamics()


@pytest.mark.parametrize("strategy", ["A", "C"])
def test_a_recorded_start_up_with_friction_along_the_string_agrees_with_scipy(strategy):
    # what torsio fit runs, on the lumped strategies: the built-in deviated well (friction
    # along the string), the top held at a recorded speed ramped to 60 rpm over 10 s, bit off
    # bottom. Independent engine: scipy's Radau between the contacts' switches
    # (torsio.solvers.contact_events) against the compiled kernel's located switches, both
    # at rtol 1e-7: the surface torque within 1e-6 of its peak, the bit breaking free at the
    # same time; conservation law: the top's work = stored + dissipated + friction's work
    time = np.arange(0.0, 30.5, 0.5)
    record = Recording(time=time, top_speed=2.0 * np.pi * np.minimum(time / 10.0, 1.0),
                       surface_torque=np.zeros_like(time), name="rig.csv")  # fmt: skip
    system = deviated_well_config().system(strategy=strategy)
    system = system.with_top(RecordedTopDrive(recording=record)).at(wob=0.0)
    runs = [
        simulate(
            system,
            duration=30.0,
            steady_window=5.0,
            method=method,
            rtol=1e-7,
            atol=1e-9,
            progress=False,
        )  # fmt: skip
        for method in ("RODAS4", "Radau")
    ]
    compiled, reference = runs
    assert compiled.solver["engine"] == "compiled" and compiled.solver["contact_switches"] > 0
    scale = np.max(np.abs(reference.surface_torque))
    assert np.max(np.abs(compiled.surface_torque - reference.surface_torque)) < 1e-6 * scale
    moved = [run.well_summary["bit_first_motion"] for run in runs]
    assert 0.0 < moved[0] < 10.0 and moved[0] == pytest.approx(moved[1], abs=0.05)  # on the ramp
    for run in runs:
        assert energy_balance(run).relative_residual < 1e-5
