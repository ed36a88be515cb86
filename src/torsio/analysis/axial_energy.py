"""The energy balance of a lumped axial-torsional run (:mod:`torsio.solvers.axial_kernel`).

Over the run the work put into the string at the top (surface torque × top speed) and at the
hook (the weight × the top node's velocity, or the speed hook's force × its speed) goes into
the chain's kinetic and spring energy, the dampers, the bit and the friction along the
string:

    W_top + W_hook = Δ(Σ m V²/2 + Σ I ω²/2 + Σ k Δθ²/2 + Σ k_a ΔU²/2)
                     + D_dampers + W_bit + W_friction.

The kernel sums the works over the steps on each step's new velocities (the scheme's own
power), so the residual is the scheme's O(h) (docs/axial.md, "Friction along the string").

Examples
--------
>>> from torsio.model.axial_assembly import rgd_two_dof_example
>>> from torsio.axial.rgd import rgd_example
>>> from torsio.analysis.axial_transient import simulate_axial
>>> run = simulate_axial(rgd_two_dof_example(), rgd_example(), 100e3, 60.0, duration=2.0,
...                      window=1.0, growth_rate=False)
>>> abs(run.axial.energy.residual) < 0.01 * run.axial.energy.input_work
True
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.solvers import axial_layouts as slot
from torsio.solvers.set_speed import table_twist

__all__ = ["RESIDUAL_TOLERANCE", "EnergyBalance", "chain_energy", "energy_balance", "stored_energy"]


def chain_energy(
    torsional: NDArray, axial: NDArray, theta: NDArray, omega: NDArray, u: NDArray,
    v: NDArray, top_angle: float, hook_position: float | None,
) -> float:  # fmt: skip
    """Kinetic and spring energy [J] of the chain (the kernel's rows 1/I, k, c and 1/m,
    k_a, c_a; the top spring from ``top_angle`` [rad]; the hook's spring from
    ``hook_position`` [m] under the speed hook, None under the weight hook)."""
    kinetic = 0.5 * np.sum(omega**2 / torsional[0]) + 0.5 * np.sum(v**2 / axial[0])
    twist = np.diff(np.concatenate([[top_angle], theta]))
    spring = 0.5 * np.sum(torsional[1] * twist**2)
    if u.size > 1:
        spring += 0.5 * np.sum(axial[1, 1:] * np.diff(u) ** 2)
    if hook_position is not None:
        spring += 0.5 * axial[1, 0] * (hook_position - u[0]) ** 2
    return float(kinetic + spring)


@attrs.frozen
class EnergyBalance:
    """The terms of a run's energy balance [J] (see the module docstring); ``residual``
    is what the balance leaves, input − (Δ stored + dampers + bit + friction)."""

    top_work: float
    hook_work: float
    stored_change: float
    damper_work: float
    bit_work: float
    string_friction_work: float

    @property
    def input_work(self) -> float:
        """W_top + W_hook [J]."""
        return self.top_work + self.hook_work

    @property
    def residual(self) -> float:
        """input − (Δ stored + dampers + bit + friction) [J]."""
        spent = self.stored_change + self.damper_work + self.bit_work
        return self.input_work - spent - self.string_friction_work

    @property
    def relative_residual(self) -> float:
        """|residual| over the larger of |input| and |bit work| (inf when both are 0 and
        the residual is not)."""
        scale = max(abs(self.input_work), abs(self.bit_work))
        if scale > 0:
            return abs(self.residual) / scale
        return 0.0 if self.residual == 0 else math.inf

    def warning(self) -> str | None:
        """The warning for a residual above :data:`RESIDUAL_TOLERANCE`, else None."""
        if self.relative_residual <= RESIDUAL_TOLERANCE:
            return None
        return (
            f"the energy balance does not close: its residual is {self.residual:.4g} J, "
            f"{self.relative_residual:.3g} of the work put in (tolerance "
            f"{RESIDUAL_TOLERANCE:g}): the fixed step does not resolve the motion and the "
            "results are not reliable; give more steps per period (axial.steps_per_period) "
            "or check the bit's and the string's parameters"
        )

    def to_dict(self) -> dict[str, Any]:
        """The terms, the ``residual`` [J] and the ``relative_residual``."""
        return {
            **attrs.asdict(self),
            "residual": self.residual,
            "relative_residual": self.relative_residual,
        }


RESIDUAL_TOLERANCE = 1e-2
"""Largest relative residual of a run's energy balance without a warning: the first-order
scheme leaves 1.6e-4 on the default run of the RGD 2-DOF file and 3e-5 on that of the
deviated well (measured, 2026-12-05)."""


def energy_balance(stats: NDArray, start: float, end: float) -> EnergyBalance:
    """The balance of a lumped run's ``stats`` (:data:`torsio.solvers.axial_layouts.STATS`) with
    the chain's energy at the ``start`` and the ``end`` [J] (:func:`chain_energy`)."""
    return EnergyBalance(
        top_work=float(stats[slot.TOP_WORK]),
        hook_work=float(stats[slot.HOOK_WORK]),
        stored_change=end - start,
        damper_work=float(stats[slot.DAMPER_WORK]),
        bit_work=float(stats[slot.BIT_WORK]),
        string_friction_work=float(stats[slot.FRICTION_WORK]),
    )


def stored_energy(setup: Any, time: float) -> float | None:
    """The lumped chain's kinetic and spring energy [J] at ``time`` [s] of its state (None:
    the distributed pipe, or a prescribed bit rotation)."""
    from torsio.solvers.axial_run_setup import RunSetup

    if not isinstance(setup, RunSetup) or setup.settings[slot.PRESCRIBED]:
        return None
    settings = setup.settings
    held = setup.top.top[slot.TOP_HELD] != 0.0
    table = setup.top.speed_table
    top_angle = (
        table_twist(table, time, 0.0) if held else float(setup.top_state[slot.TOP_NODE_ANGLE])
    )
    hook = None
    if settings[slot.SPEED_HOOK]:
        hook = settings[slot.HOOK_START] + settings[slot.HOOK_SPEED] * time
    return chain_energy(
        setup.torsional, setup.axial, setup.theta, setup.omega, setup.u, setup.v, top_angle, hook
    )
