"""Coulomb friction along the string on the lumped axial-torsional chain (docs/axial.md,
"Friction along the string"): one contact's set-valued step against its closed forms
(torsio.solvers.contact_law.cone_step), steady drilling with friction
(torsio.axial.steady_friction), the energy balance (torsio.analysis.axial_energy), the
break-off of torsio.well.break_off, and the built-in rgd_deviated_well.toml through the
command line.

Every run is rgd_deviated_well.toml (torsio.examples.rgd_deviated_well_config: the stepped
RGD string, 2.5 km, in the deviated well's survey; 24 nodes of at most 100 m), short.
"""

from __future__ import annotations

import json
import math
from importlib import resources

import numpy as np
import pytest
import scipy.optimize

from torsio.analysis.axial_transient import simulate_axial
from torsio.axial.steady_friction import friction_damping, friction_split, steady_with_friction
from torsio.cli import main
from torsio.config.reading import parse_config_text
from torsio.errors import ConfigError
from torsio.examples import rgd_deviated_well_config
from torsio.solvers.axial_run_setup import BitRotation
from torsio.solvers.contact_law import cone_step, sliding_speed

TEXT = resources.files("torsio").joinpath("data/rgd_deviated_well.toml").read_text(encoding="utf-8")


def _config(text: str = TEXT):
    return parse_config_text(text, source="test")


def _run(axial, wob=100e3, rpm=60.0, **options):
    run_options = {**axial.run_options(), **options}
    return simulate_axial(axial.assembly, axial.bit, wob, rpm, growth_rate=False, **run_options)


# --- one contact -------------------------------------------------------------------------


@pytest.mark.parametrize("free", [(0.01, 0.127), (-0.3, 0.002), (1e-4, -2.0)])
def test_sliding_step_against_the_closed_form_of_equal_metrics(free):
    # closed form (m = I/r²): s = s*(1 − h F_d/(m |s*|)); measured error 0 to 2e-16
    mass, radius, step, force = 500.0, 0.0635, 1e-3, 3000.0
    velocity, tangential = free
    inertia = mass * radius**2
    new_v, new_w, stuck = cone_step(
        velocity, tangential / radius, radius, 1 / mass, 1 / inertia, 4000.0, force, step, False
    )
    factor = 1.0 - step * force / (mass * math.hypot(velocity, tangential))
    assert not stuck
    assert new_v == pytest.approx(velocity * factor, rel=1e-12, abs=0)
    assert new_w * radius == pytest.approx(tangential * factor, rel=1e-12, abs=0)


def test_sliding_speed_is_the_root_with_unequal_metrics():
    # reference: the root of phi(rho) by brentq to 1e-15, m = 500 kg, I/r² = 20 kg (the
    # Newton steps from the lower bound reach it to round-off)
    m, j, p = 500.0, 20.0, 3.0
    a, b = 0.01, 0.127

    def phi(rho):
        return (m * a / (m * rho + p)) ** 2 + (j * b / (j * rho + p)) ** 2 - 1.0

    reference = scipy.optimize.brentq(phi, 0.0, math.hypot(a, b), xtol=1e-16, rtol=1e-15)
    assert sliding_speed(a, b, m, j, p) == pytest.approx(reference, rel=1e-13)


def test_contact_sticks_when_the_stopping_impulse_is_within_the_cone():
    # the impulse that stops the node, |(m V*, (I/r²) r Ω*)|, against h F_s (slow: static
    # cone) or h F_d (fast: sliding cone)
    m, r, inertia, h = 500.0, 0.0635, 2.0, 1e-3
    j = inertia / r**2
    velocity, speed = 0.004, 0.05
    stop = math.hypot(m * velocity, j * r * speed)
    just_above, just_below = stop / h * (1 + 1e-9), stop / h * (1 - 1e-9)
    assert cone_step(velocity, speed, r, 1 / m, 1 / inertia, just_above, 0.5 * just_above,
                         h, True) == (0.0, 0.0, True)  # fmt: skip
    assert not cone_step(velocity, speed, r, 1 / m, 1 / inertia, just_below, 0.5 * just_below,
                             h, True)[2]  # fmt: skip
    # on the sliding branch the cone is F_d: the same F_s does not hold the node
    assert not cone_step(velocity, speed, r, 1 / m, 1 / inertia, just_above, 0.5 * just_above,
                             h, False)[2]  # fmt: skip


def test_damping_matrix_against_finite_differences_of_the_friction_force():
    # reference: central differences (step 1e-7 relative) of f(s) = −F_d s/|s|, s = (V, r ω)
    config = rgd_deviated_well_config()
    contacts = config.axial.contacts.at_wob(100e3)
    rop, speed = 0.0074, 2 * math.pi
    matrices = friction_damping(contacts, rop, speed)
    for i in np.flatnonzero(contacts.sliding_force > 0)[:5]:
        r, f = contacts.radius[i], contacts.sliding_force[i]
        s0 = np.array([rop, r * speed])

        def force(s, f=f):
            return -f * s / np.linalg.norm(s)

        jac = np.zeros((2, 2))
        for k in range(2):
            delta = np.zeros(2)
            delta[k] = 1e-7 * np.linalg.norm(s0)
            jac[:, k] = (force(s0 + delta) - force(s0 - delta)) / (2 * delta[k])
        assert np.allclose(matrices[i], -jac, rtol=1e-6, atol=1e-9 * f / np.linalg.norm(s0))
        assert np.all(np.linalg.eigvalsh(matrices[i]) >= -1e-9 * f)  # positive semi-definite


# --- runs ----------------------------------------------------------------------------------


def test_vertical_well_is_bit_identical_to_the_run_without_well():
    # a vertical survey: zero normal force at every node, so no contact
    vertical = TEXT.replace(
        "inclination = [0.0, 0.0, 15.0, 35.0, 35.0, 25.0, 20.0, 20.0]",
        "inclination = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]",
    )
    start = vertical.index("[well]")
    without = vertical[:start] + vertical[vertical.index("[bit_rock]") :]
    with_well, no_well = _config(vertical).axial, _config(without).axial
    assert with_well.contacts.count == 0 and no_well.contacts is None
    a = _run(with_well, duration=4.0, window=2.0)
    b = _run(no_well, duration=4.0, window=2.0)
    assert np.array_equal(a.axial.samples, b.axial.samples)
    assert a.axial.summary == b.axial.summary
    assert a.axial.string_friction_work == 0.0 and a.axial.contact_switches == 0


@pytest.mark.parametrize("hook", ["weight", "speed"])
def test_steady_start_stays_on_the_closed_form(hook):
    # closed form (torsio.axial.steady_friction): bit weight W_b (weight hook: W_h − Σ F_a),
    # ROP, MSE and surface torque T₀ + Σ F_d r² Ω₀/|s₀|; measured relative errors <= 3e-12
    text = TEXT.replace('hook = "weight"', f'hook = "{hook}"')
    axial = _config(text).axial
    run = _run(axial, start="steady", perturbation=0.0, duration=3.0, window=2.0)
    contacts = axial.contacts.at_wob(100e3)
    steady, friction = steady_with_friction(axial.bit, 100e3, 60.0, contacts, hook)
    assert run.axial.contact_switches == 0
    assert run.axial.rop_mean == pytest.approx(steady.rop, rel=1e-9)
    assert run.axial.mse_mean == pytest.approx(steady.mse, rel=1e-9)
    assert run.axial.weight_mean == pytest.approx(steady.wob, rel=1e-9)
    assert run.axial.torque_mean == pytest.approx(steady.bit_torque, rel=1e-9)
    surface = run.signal("surface_torque")
    assert np.max(np.abs(surface / friction.surface_torque - 1.0)) < 1e-9
    assert abs(run.axial.energy.residual) < 1e-9 * run.axial.energy.top_work  # measured 2.4e-13
    if hook == "weight":
        assert steady.wob == pytest.approx(100e3 - friction.axial_friction, rel=1e-12)
    else:
        assert friction.hook_force == pytest.approx(100e3 + friction.axial_friction, rel=1e-12)


def test_energy_residual_halves_with_the_step():
    # the scheme's works summed on each step's new velocities: residual / top work of first
    # order in h. A stick-slip run from rest, 20 s: measured 2.17e-5, 1.32e-5, 7.17e-6 at
    # 100/200/400 steps per period (orders 0.72, 0.88, tending to 1)
    ratios = []
    for steps in (100, 200, 400):
        run = _run(rgd_deviated_well_config().axial, duration=20.0, window=5.0,
                   steps_per_period=steps, samples=0)  # fmt: skip
        ratios.append(abs(run.axial.energy.residual) / run.axial.energy.top_work)
    assert run.axial.energy.string_friction_work > 0.1 * run.axial.energy.top_work
    orders = [math.log2(ratios[k] / ratios[k + 1]) for k in range(2)]
    assert ratios[0] < 1e-4
    assert all(0.6 < order < 1.3 for order in orders), (ratios, orders)


def test_perturbed_steady_start_settles_on_the_bit_torque_plus_the_sliding_torque():
    # closed form: surface torque T₀ + Σ F_d r² Ω₀/|s₀| at a linearly stable point (80 kN,
    # 200 rpm, growth rates −0.0097 1/s speed hook, −0.0065 weight hook); the bit speed
    # raised 1 %: measured window mean − closed form 2.5e-4 (speed), 1.5e-4 (weight)
    for hook in ("speed", "weight"):
        axial = _config(TEXT.replace('hook = "weight"', f'hook = "{hook}"')).axial
        steady, friction = steady_with_friction(
            axial.bit, 80e3, 200.0, axial.contacts.at_wob(80e3), hook
        )
        run = _run(axial, wob=80e3, rpm=200.0, start="steady", perturbation=1e-2,
                   duration=30.0, window=10.0)  # fmt: skip
        top = run.axial.top_drive_summary()
        sliding = float(np.sum(friction_split(axial.contacts.at_wob(80e3), steady.rop,
                                              steady.bit_speed)[1]))  # fmt: skip
        assert friction.surface_torque == pytest.approx(steady.bit_torque + sliding, rel=1e-15)
        assert top["mean_surface_torque"] == pytest.approx(friction.surface_torque, rel=1e-3)
        assert run.axial.torque_mean == pytest.approx(steady.bit_torque, rel=1e-4)
        assert run.axial.contact_switches == 0


def _first_motion(hook: str, wob: float):
    """A top held at 1 rpm twisting the string from rest until the bit turns: (the config,
    break_off at ``wob``, the surface torque less the bit law's own T_c + T_f at the last
    step before the bit moved, the top's angle then, that bit torque)."""
    from torsio.well.break_off import break_off

    config = _config(TEXT.replace('hook = "weight"', f'hook = "{hook}"'))
    axial, bit = config.axial, config.axial.bit
    reference = break_off(config.well, config.string, 10.0, wob)
    omega = 2 * math.pi / 60
    duration = 1.6 * reference.twist / omega
    run = _run(axial, wob=wob, rpm=1.0, duration=duration, window=0.1 * duration,
               samples=40000)  # fmt: skip
    moved = int(np.flatnonzero(run.signal("bit_speed") > 0.0)[0])
    depth = max(run.signal("depth_of_cut")[moved - 1], 0.0)
    cutting = bit.cutting_weight_per_depth * depth
    wear_flat = run.signal("bit_weight")[moved - 1] - cutting
    own = bit.cutting_torque_per_depth * depth + bit.contact_friction * bit.bit_geometry * (
        bit.radius / 2 * wear_flat
    )
    held = run.signal("surface_torque")[moved - 1] - own
    angle = omega * run.signal("time")[moved - 1]
    return config, reference, held, angle, own, run.signal("bit_weight")[moved - 1]


@pytest.mark.parametrize("hook", ["speed", "weight"])
def test_slow_start_up_breaks_free_at_the_break_off_torque(hook):
    # reference: torsio.well.break_off at 72 kN, just above σ a l = 71.28 kN (Σ C_s =
    # Σ F_s r, the torsional closed form, 1e-12). The top held at 1 rpm twists the string
    # from rest; the bit turns once the torque overcomes every contact's static capacity
    # and the bit law's own T_c + T_f. Measured: torque 1.4e-4 (speed hook), 9e-5 (weight
    # hook) below Σ C_s; the top's angle against break_off's twist plus the bit torque
    # over the chain's compliance Σ 1/k: −1.3e-3 (a quadrature of ∫ τ/(G J) dx)
    config, reference, held, angle, own, _ = _first_motion(hook, 72e3)
    contacts = config.axial.contacts.at_wob(72e3)
    assert contacts.static_torque == pytest.approx(reference.torque, rel=1e-12)
    assert held == pytest.approx(reference.torque, rel=5e-3)
    compliance = float(np.sum(1.0 / config.axial.assembly.springs))
    assert angle == pytest.approx(reference.twist + own * compliance, rel=5e-3)


@pytest.mark.parametrize("hook", ["speed", "weight"])
def test_axial_load_at_rest_takes_part_of_the_bha_contact_cone(hook):
    # At 100 kN the bit on its flat bottom takes σ a l and a shallow cut; the BHA node's
    # contact, at rest, carries the rest of the weight axially (F_a = W₀ − W_b = 25.9 kN,
    # its whole F_s = 25.6 kN: it creeps down), so only √(F_s² − F_a²) r of its cone is
    # left for the torque. Weight hook: the torque at first motion is Σ C_s − F_s r +
    # √(F_s² − F_a²) r (the BHA's) to 2e-5, 21.4 % below Σ C_s (3.2 % at 85 kN, 0.01 % at
    # 72 kN). Speed hook: 21.4 % below Σ C_s too, but not by the BHA alone: the hook
    # advancing at V₀ loads the other contacts axially as well (its break is 15.3 % below
    # the BHA-only prediction; 5.5 % below Σ C_s at 85 kN).
    config, reference, held, _, _, bit_weight = _first_motion(hook, 100e3)
    assert held / reference.torque - 1 == pytest.approx(-0.214, abs=2e-3)
    if hook == "weight":
        contacts = config.axial.contacts.at_wob(100e3)
        f_s, r = contacts.static_force[-1], contacts.radius[-1]
        axial_load = 100e3 - bit_weight
        left = math.sqrt(max(f_s**2 - axial_load**2, 0.0)) * r
        assert held == pytest.approx(contacts.static_torque - f_s * r + left, rel=1e-3)


def test_cli_simulate_and_map_give_the_string_friction(tmp_path, capsys):
    # the built-in file through the command line; a map point is the single run
    path = str(resources.files("torsio").joinpath("data/rgd_deviated_well.toml"))
    common = ["--duration", "6", "--window", "3"]

    def cli(*args):
        assert main([*args, "--json"]) == 0
        return json.loads(capsys.readouterr().out)

    run = cli("simulate", path, "--wob", "100kN", "--rpm", "60", *common)
    assert run["string_friction_work"] > 0.0 and run["contact_switches"] >= 0
    assert run["string_contacts"]["count"] == 20
    assert run["growth_rate"] is not None
    assert run["steady_friction"]["surface_torque"] > run["steady_state"]["bit_torque"]
    grid = cli("map", path, "--wob", "90kN:100kN:2", "--rpm", "60:60:1", *common)
    assert grid["string_friction_work"][0][1] == run["string_friction_work"]
    assert grid["severity"][0][1] == run["severity"]
    small = tmp_path / "small.toml"  # 5 nodes: the report follows every mode over rpm
    small.write_text(TEXT.replace('element_length = "100 m"', 'element_length = "600 m"'))
    report = cli("report", str(small))["axial"]
    assert report["string_contacts"]["static_torque"] == pytest.approx(
        run["string_contacts"]["static_torque"], rel=1e-12
    )
    assert report["steady_friction"]["bit_weight"] < 100e3  # the axial friction's share
    assert report["stability"]["contacts"].startswith("each sliding contact's damping")


def test_refusals_name_the_key():
    with pytest.raises(ConfigError, match=r"well\.friction_dynamic"):
        _config(TEXT.replace("friction_dynamic = 0.3\n", "friction_dynamic = 0.5\n"))
    with pytest.raises(ConfigError, match=r"well\.threshold_speed"):
        _config(TEXT.replace("threshold_speed = 0.5", "threshold_speed = -1.0"))
    with pytest.raises(ConfigError, match=r"well.*grip"):
        _config(TEXT.replace("threshold_speed = 0.5", "threshold_speed = 0.5\ngrip = 1"))
    chain = resources.files("torsio").joinpath("data/rgd_2dof.toml").read_text(encoding="utf-8")
    well = TEXT[TEXT.index("[well]") : TEXT.index("[bit_rock]")]
    with pytest.raises(ConfigError, match=r"well: .*not a \[chain\]"):  # no diameters
        _config(chain + "\n" + well)
    axial = rgd_deviated_well_config().axial
    with pytest.raises(ConfigError, match="well"):  # the bit turning as prescribed
        simulate_axial(axial.assembly, axial.bit, 100e3, 60.0, duration=1.0, window=0.5,
                       bit_rotation=BitRotation(), contacts=axial.contacts,
                       growth_rate=False)  # fmt: skip


def test_growth_of_a_small_perturbation_is_the_linearization_with_the_contacts_damping():
    # reference: the rightmost root of drilling_linearization with the contacts (2.535 1/s at
    # 100 kN, 60 rpm; 2.828 without them). The envelope of |V_b − V₀| from a steady start
    # raised 1e-7 grows at 2.540 1/s (log of its peaks over 0.8..2.8 s), within 0.2 %
    from torsio.axial.stability import drilling_stability

    axial = rgd_deviated_well_config().axial
    run = _run(axial, start="steady", perturbation=1e-7, duration=3.0, window=1.0,
               samples=10**6)  # fmt: skip
    with_contacts = drilling_stability(
        axial.assembly, axial.bit, 100e3, 60.0, count=1, contacts=axial.contacts
    ).growth_rate
    without = drilling_stability(axial.assembly, axial.bit, 100e3, 60.0, count=1).growth_rate
    time, deviation = run.signal("time"), np.abs(run.signal("bit_velocity") - run.axial.steady.rop)
    peaks = np.flatnonzero((deviation[1:-1] >= deviation[:-2]) & (deviation[1:-1] > deviation[2:]))
    peaks = peaks[(time[peaks + 1] > 0.8) & (time[peaks + 1] < 2.8)] + 1
    fitted = np.polyfit(time[peaks], np.log(deviation[peaks]), 1)[0]
    assert fitted == pytest.approx(with_contacts, rel=1e-2)
    assert abs(fitted / without - 1) > 0.08
