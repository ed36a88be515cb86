"""The System: what the dynamic analyzers take.

A lumped model with damping, a bit-rock law and bit radius, a top boundary
condition and an operating point (weight on bit, surface rotary speed).

Equations of motion (paper Eq. 3), with theta the absolute node rotations:

    [I] theta'' + [C] theta' + [K] theta = k_t (Omega t) + c_t Omega - T_bit(theta_N') e_N

where k_t = [K] 1 and c_t are the couplings of the nodes to the top drive
(k_1 e_1 and c_1 e_1 for a chain). Written in the twist phi = theta - Omega t 1
(``phi = 0`` is rigid rotation with the top) they become autonomous:

    [I] phi'' + [C] phi' + [K] phi = (c_t - [C] 1) Omega - T_bit(Omega + phi_N') e_N

which is how the transient analyzer integrates them.

Examples
--------
>>> system = System.from_config(builtin_config())
>>> system.model.dofs, round(system.omega, 4), system.wob
(5, 10.472, 100000.0)
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.io.config import Config, builtin_config
from torsio.model.lumped import LumpedModel
from torsio.physics.damping import ModelDamping, RayleighDamping
from torsio.units import RPM_TO_RAD_S

__all__ = ["ConstantSpeedTop", "System", "builtin_config"]


@attrs.frozen
class ConstantSpeedTop:
    """Top drive held at the constant surface speed Omega of the operating point (Eq. 3).

    An object rather than a flag so that a speed-controlled top drive can take its
    place later.
    """

    name: str = "constant speed"


def _check_operating_value(key: str, value: float, positive: bool) -> None:
    import math

    ok = math.isfinite(value) and (value > 0 if positive else value >= 0)
    if not ok:
        what = "positive" if positive else "non-negative"
        raise ConfigError(key, f"expected a {what} finite value, got {value!r}")


@attrs.frozen
class System:
    """A damped lumped model with a bit-rock law, top drive and operating point.

    Parameters
    ----------
    model : LumpedModel
    law : BitRockLaw
        Any object with ``torque(speed, wob, radius)``.
    bit_radius : float
        R_bit [m].
    damping : RayleighDamping | ModelDamping
    wob : float
        Weight on bit W_ob [N], >= 0.
    rpm : float
        Surface rotary speed [rpm], > 0.
    top : ConstantSpeedTop
    string : DrillString | None
        The string the model came from (for reports and the continuum).
    """

    model: LumpedModel
    law: Any
    bit_radius: float = attrs.field(converter=float)
    damping: RayleighDamping | ModelDamping = attrs.field(factory=RayleighDamping)
    wob: float = attrs.field(default=0.0, converter=float)
    rpm: float = attrs.field(default=60.0, converter=float)
    top: ConstantSpeedTop = attrs.field(factory=ConstantSpeedTop)
    string: Any = attrs.field(default=None, eq=False)

    def __attrs_post_init__(self) -> None:
        _check_operating_value("operation.wob", self.wob, positive=False)
        _check_operating_value("operation.rpm", self.rpm, positive=True)
        _check_operating_value("bit_rock.radius", self.bit_radius, positive=True)

    @classmethod
    def from_config(cls, config: Config, **discretization: Any) -> System:
        """The System a configuration describes; ``discretization`` overrides its options."""
        model = config.model(**discretization)
        d = config.damping
        damping = (
            RayleighDamping.from_modal_ratios(model, d.ratios, d.modes)
            if d.ratios is not None
            else RayleighDamping(d.alpha or 0.0, d.beta or 0.0)
        )
        op = config.operation
        return cls(
            model=model,
            law=config.bit_law(),
            bit_radius=config.bit_radius,
            damping=damping,
            wob=op.wob if op.wob is not None else 0.0,
            rpm=op.rpm if op.rpm is not None else 60.0,
            string=config.string,
        )

    def at(self, wob: float | None = None, rpm: float | None = None) -> System:
        """The same system at another operating point."""
        return attrs.evolve(
            self, wob=self.wob if wob is None else wob, rpm=self.rpm if rpm is None else rpm
        )

    # --- matrices -------------------------------------------------------------------------
    @property
    def omega(self) -> float:
        """Surface rotary speed Omega [rad/s]."""
        return self.rpm * RPM_TO_RAD_S

    @property
    def damping_matrix(self) -> np.ndarray:
        """[C], in N m s/rad."""
        return self.damping.matrix(self.model)

    @property
    def top_damping(self) -> np.ndarray:
        """c_t: damping coupling of each node to the top drive [N m s/rad]."""
        return self.damping.top_coupling(self.model)

    @property
    def drag_per_speed(self) -> np.ndarray:
        """[C] 1 - c_t: torque on each node per unit rigid rotation speed [N m s/rad].

        Rigid rotation at Omega costs a steady torque ``Omega * drag_per_speed`` (the
        alpha [I] part of Rayleigh damping); zero for purely relative damping.
        """
        return self.damping_matrix.sum(axis=1) - self.top_damping

    def bit_torque(self, bit_speed: Any) -> np.ndarray:
        """Torque on bit [N m] at bit speed [rad/s] for this operating point."""
        return np.asarray(self.law.torque(bit_speed, self.wob, self.bit_radius))
