"""A bit-rock law of the torque alone on an axial chain: Tucker-Wang, a plugin's, any law.

A law with ``torque(speed, wob, radius)`` and no axial force of its own (it does not declare
``needs_axial``: :func:`torsio.physics.laws.law_capabilities`) gives the torque on bit for a
weight on bit; it says nothing of how the rock gives way under that weight. On an axial
chain (``[chain] masses``) torsio reads it as a drilling engineer sets a weight on bit on
such a law:

- the rock does not yield: the bit rests on it, and its axial reaction is whatever the
  string pushes down with (a unilateral contact: the bit lifts off if the string pulls it
  up). The chain starts at its static equilibrium under the hook weight W₀ (each axial
  spring carrying W₀), so the reaction, the **weight of the law**, is the weight on bit W₀
  of the operating point, and the chain rests there: no rate of penetration, no axial
  motion (the hook speed V₀ of ``hook = "speed"`` is the steady rate of penetration, 0);
- the torque on bit is ``torque(Ω_b, W, a)`` at that weight, taken linearly implicit in the
  bit speed over each step (:func:`torsio.axial.bit_step.law_rotation`), so that a stiff
  smooth sign (a small regularization speed) does not bound the step.

The torsional motion is then that of the torsional chain under the law at W₀, which the
torsional engines compute too (tests/test_axial_torque_law.py compares them).

Examples
--------
>>> from torsio.physics.laws import TuckerWang
>>> bit = TorqueLawBit(TuckerWang(a0=0.221, a1=0.2, a2=0.89, a3=0.06, speed_unit="rpm"), 0.108)
>>> state = bit.steady(100e3, 60.0)
>>> round(state.bit_torque, 1), state.rop, state.mse  # Eq. 2 at 2π rad/s: W R a0 (1 + 0.2461)
(2974.2, 0.0, inf)
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.analysis.budget import law_slope_at_rest
from torsio.axial.rgd import RGDBit
from torsio.axial.steady import SteadyDrilling, steady_drilling
from torsio.errors import ConfigError
from torsio.solvers import axial_layouts as slot
from torsio.units import RPM_TO_RAD_S

__all__ = ["AxialBit", "TorqueLawBit", "law_functions", "steady_state"]


@attrs.frozen(eq=False)
class TorqueLawBit:
    """A law of the torque alone (``torque(speed, wob, radius)``) on a bit of ``radius`` a
    [m], the rock rigid under it (see the module docstring).

    Attributes
    ----------
    law : bit-rock law
        Any registered law that does not declare ``needs_axial``.
    radius : float
        The bit radius a [m] the law's torque takes.
    """

    law: Any
    radius: float = attrs.field(converter=float)

    needs_axial = False
    blades = 1
    """One revolution between two passes over the same rock (the history's span)."""
    cutting_weight_per_depth = 0.0
    """ζ ε a [N/m]: none, the rock does not yield (no axial contact frequency in the step
    rule, :func:`torsio.solvers.axial_step_rule.contact_frequency`)."""

    NO_GROWTH_RATE = (
        "a law of the torque alone has no growth rate of drilling (its axial motion rests; "
        "the linear stability is the torsional chain's, torsio report); expected None or False"
    )
    """Why :func:`~torsio.analysis.axial_transient.simulate_axial` refuses ``growth_rate=True``."""

    def __attrs_post_init__(self) -> None:
        if not (math.isfinite(self.radius) and self.radius > 0):
            raise ConfigError("bit_rock.radius", f"{self.radius!r}: expected a positive radius")

    @property
    def name(self) -> str:
        """The law's registered name."""
        return str(getattr(self.law, "name", type(self.law).__name__))

    @property
    def hole_area(self) -> float:
        """A = π a² [m²]."""
        return math.pi * self.radius**2

    def torque(self, speed: float, wob: float) -> float:
        """The law's torque on bit [N m] at ``speed`` [rad/s] under ``wob`` [N]."""
        return float(np.asarray(self.law.torque(speed, wob, self.radius), dtype=float))

    def rate(self, wob: float, inertia: float) -> float:
        """The law's rate at rest [1/s]: its slope at zero speed under ``wob`` [N]
        (:func:`torsio.analysis.budget.law_slope_at_rest`) over the bit's ``inertia``
        [kg m²], the time scale on which the bit leaves or enters a stick."""
        return law_slope_at_rest(self.law, wob, self.radius) / inertia

    def steady(self, wob: float, rpm: float) -> SteadyDrilling:
        """The steady state at ``wob`` [N] and ``rpm`` [rev/min]: the bit turning at Ω₀ under
        T = torque(Ω₀, W₀, a), resting axially (no depth of cut, no rate of penetration, MSE
        inf); its ``delay`` is one revolution 2π/Ω₀, the span of the (unused) history."""
        if not (math.isfinite(rpm) and rpm > 0):
            raise ConfigError("rpm", f"{rpm!r} must be > 0 rev/min")
        if not (math.isfinite(wob) and wob >= 0):
            raise ConfigError("wob", f"{wob!r}: expected a weight on bit >= 0 N")
        speed = rpm * RPM_TO_RAD_S
        return SteadyDrilling(
            wob=float(wob),
            bit_speed=speed,
            depth_of_cut=0.0,
            rop=0.0,
            bit_torque=self.torque(speed, wob),
            mse=math.inf,
            cutting_weight=0.0,
            friction_weight=float(wob),
            delay=2 * math.pi / speed,
        )

    def row(self) -> NDArray[np.float64]:
        """The kernels' bit row (:data:`torsio.solvers.axial_layouts.BIT_ROW`): no cutting, a rock
        that carries any weight (σ a l = inf), the law's torque (``LAW_TORQUE`` 1) on the
        radius a, one blade."""
        row = np.zeros(len(slot.BIT_ROW))
        row[slot.FRICTION_WEIGHT] = math.inf
        row[slot.ANGLE_PER_BLADE] = 2 * math.pi
        row[slot.BLADES] = 1.0
        row[slot.LAW_TORQUE] = 1.0
        row[slot.BIT_RADIUS] = self.radius
        return row

    def to_dict(self) -> dict[str, Any]:
        """The law's name, its parameters (rad/s reading, when it lists them) and the radius."""
        values = getattr(self.law, "values", None)
        parameters = values() if callable(values) else {}
        return {"law": self.name, "radius": self.radius, **parameters}


def steady_state(bit: RGDBit | TorqueLawBit, wob: float, rpm: float) -> SteadyDrilling:
    """The steady state of either bit at ``wob`` [N] and ``rpm`` [rev/min]: the RGD bit's
    drilling (:func:`torsio.axial.steady.steady_drilling`) or a law of the torque alone
    resting on the rock (:meth:`TorqueLawBit.steady`)."""
    if isinstance(bit, TorqueLawBit):
        return bit.steady(wob, rpm)
    return steady_drilling(bit, wob, rpm)


AxialBit = RGDBit | TorqueLawBit
"""The bits the axial engine runs: the RGD bit, or a law of the torque alone."""


def law_functions(bit: AxialBit) -> Any:
    """The compiled torque and slope the lumped kernel calls
    (:class:`~torsio.solvers.law_kernels.LawKernel`): the law's own ``kernel()``, or one
    numba compiles from its Python ``torque`` (a ConfigError naming ``bit_rock.law`` when it
    cannot); for the RGD bit, whose torque is its cutting and wear flats, a zero torque the
    kernel never calls."""
    from torsio.physics.laws import ConstantTorque
    from torsio.solvers.law_kernels import law_kernel, python_law_kernel

    law = bit.law if isinstance(bit, TorqueLawBit) else ConstantTorque(torque_on_bit=0.0)
    return law_kernel(law) or python_law_kernel(law)
