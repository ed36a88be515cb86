"""The work an axial run may take, checked before anything is allocated.

A run of either axial kernel takes ``duration / h`` fixed steps on ``nodes`` nodes and
keeps the bit's history of every step and of 1.5 steady delays before t = 0
(:func:`torsio.solvers.axial_run_setup.past_times`). :func:`check_run_work` holds it to the
budget of the wave model's runs (:func:`torsio.analysis.budget.most_fixed_steps`: at most
2 000 000 steps and 5e10 node-steps; the default run of the RGD 2-DOF file takes 153 600
steps, that of the deviated well 201 459 steps of 24 nodes) and names the key that makes
the work: a given step, the steps per period, the run's length, the rotary speed (the
delay the history spans), or the model whose fastest frequency sets the step (the bit's
contact frequency √(2 n ζ ε a / m_b), the chain's node frequencies, or the rate at rest of
a law of the torque alone).

Examples
--------
>>> from torsio.axial.rgd import rgd_example
>>> from torsio.solvers.axial_run_setup import RunOptions
>>> options = RunOptions(1e7, 10.0, default_duration=300.0)
>>> check_run_work(options, 1.9e-3, 0.25, 1, rgd_example(), 3e4, 1.0, "chain")
Traceback (most recent call last):
...
torsio.errors.ConfigError: simulation.duration: a run of 1e+07 s is 5.26e+09 steps of ...
"""

from __future__ import annotations

import math
from typing import Any

from torsio.analysis.budget import MAX_WAVE_STEPS, MAX_WAVE_WORK, most_fixed_steps
from torsio.errors import ConfigError
from torsio.solvers.axial_step_rule import DEFAULT_STEPS_PER_PERIOD, contact_frequency

__all__ = ["check_run_work"]

LIMITS = (
    f"more than a run may take ({MAX_WAVE_STEPS:,} steps and {MAX_WAVE_WORK:g} node-steps, "
    "the budget of the torsional wave runs)"
)


def _model_key(bit: Any, mass: float, fastest: float, model_key: str) -> tuple:
    """(key, why) of the model's fastest frequency that sets the step rule."""
    contact = contact_frequency(bit, mass)
    if contact >= fastest:
        return "bit_rock", (
            f"the bit's axial contact frequency sqrt(2 n zeta epsilon a / m_b) = {contact:.3g} "
            f"rad/s (n = {bit.blades}, zeta = {bit.cutting_force_ratio:g}, epsilon = "
            f"{bit.intrinsic_specific_energy:.3g} Pa, a = {bit.radius:g} m, bit mass m_b = "
            f"{mass:.3g} kg) sets the step; check bit_rock.intrinsic_specific_energy and the "
            "bit's mass (chain.masses, or the BHA's)"
        )
    if model_key == "bit_rock":  # a law of the torque alone (torsio.physics.torque_law_bit)
        return model_key, (
            f"the bit-rock law's rate at rest (its slope at zero speed over the bit's "
            f"inertia), {fastest:.3g} 1/s, sets the step; check the law's parameters (a "
            "smooth sign's regularization speed), or expected fewer axial.steps_per_period "
            "(at least 10) or a shorter simulation.duration"
        )
    return model_key, (
        f"the fastest node frequency of the model, {fastest:.3g} rad/s, sets the step; check "
        f"its masses, inertias, stiffnesses and dampers ({model_key})"
    )


def check_run_work(
    options: Any,
    step: float,
    delay: float,
    nodes: int,
    bit: Any,
    mass: float,
    fastest: float,
    model_key: str,
) -> int:
    """The steps of a run of ``options`` on the step h = ``step`` [s]; ConfigError naming the
    key that makes a run too short or too long (see the module documentation).

    ``delay`` is the steady delay t_n0 [s], ``nodes`` the kernel's nodes, ``mass`` the bit's
    axial mass [kg] and ``fastest`` the model's fastest frequency [rad/s] beside the bit's
    (``model_key`` names where it comes from).
    """
    duration = float(options.duration)
    steps = duration / step
    if not steps >= 1.0 - 1e-9 or options.window < step * (1.0 - 1e-9):
        raise ConfigError(
            "simulation.duration" if steps < 1.0 - 1e-9 else "simulation.steady_window",
            f"a run of {duration:g} s with a steady window of {options.window:g} s is shorter "
            f"than one step of the axial engine ({step:.4g} s); expected a run and a window "
            f"of at least {step:.4g} s",
        )
    most = most_fixed_steps(nodes)
    past = 1.5 * delay / step
    if steps + past <= most:
        return int(math.ceil(steps - 1e-9))
    rule_fastest = max(contact_frequency(bit, mass), fastest)
    rule_step = 2 * math.pi / (rule_fastest * options.steps_per_period)
    default_step = min(2 * math.pi / (rule_fastest * DEFAULT_STEPS_PER_PERIOD), delay)
    work = (
        f"a run of {duration:g} s is {steps:.3g} steps of {step:.4g} s ({nodes:,} nodes) and "
        f"its history {past:.3g} steps before t = 0, {LIMITS}"
    )
    fits = (most - 1.5 * delay / default_step) * default_step
    typical = options.default_duration
    if options.step is not None and options.step < rule_step * (1 - 1e-9):
        raise ConfigError(
            "simulation.step",
            f"{work}; expected a step of at least {duration / most:.3g} s for this run, or the "
            "step rule's own (no simulation.step)",
        )
    if options.steps_per_period > DEFAULT_STEPS_PER_PERIOD and duration <= fits:
        raise ConfigError(
            "axial.steps_per_period",
            f"{options.steps_per_period:g} steps per period: {work}; expected at most about "
            f"{options.steps_per_period * most / steps:.3g} steps per period for this run "
            f"(default {DEFAULT_STEPS_PER_PERIOD})",
        )
    if typical is not None and typical / default_step > most:
        key, why = _model_key(bit, mass, fastest, model_key)
        raise ConfigError(key, f"{work}: {why}")
    if 1.5 * delay / default_step > most:
        raise ConfigError(
            "operation.rpm",
            f"the bit's history spans 1.5 steady delays t_n0 = 2 pi / (n Omega_0) = {delay:.4g} "
            f"s, {1.5 * delay / default_step:.3g} steps of the step rule's {default_step:.4g} s, "
            f"{LIMITS}: the rotary speed is too low for the axial engine; expected a higher "
            "rotary speed (--rpm)",
        )
    raise ConfigError(
        "simulation.duration",
        f"{work}; expected a run of at most {max(most - past, 0.0) * step:.4g} s with this model",
    )
