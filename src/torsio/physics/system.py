"""The System: what the dynamic analyzers take.

A lumped model with damping, a bit-rock law and bit radius, a top boundary
condition and an operating point (weight on bit, surface rotary speed).

Equations of motion (paper Eq. 3), with theta the absolute node rotations:

    [I] theta'' + [C] theta' + [K] theta = k_t (Omega t) + c_t Omega - T_bit(theta_N') e_N

where k_t = [K] 1 and c_t are the couplings of the nodes to the top drive
(k_1 e_1 and c_1 e_1 for a chain). Written in the twist phi = theta - Omega t 1
(``phi = 0`` is rigid rotation with the top) they become autonomous:

    [I] phi'' + [C] phi' + [K] phi = (c_t - [C] 1) Omega - T_bit(Omega + phi_N') e_N

which is how the transient analyzer integrates them. A top drive with inertia
(:mod:`torsio.physics.top_drives`) adds a node and controller states; the one
description of the dynamics of either is :mod:`torsio.physics.dynamics`.

The physics does not import the configuration layer: a configuration builds its
System (:meth:`torsio.config.configuration.Config.system`).

Examples
--------
>>> from torsio.examples import builtin_config
>>> system = builtin_config().system()
>>> system.model.dofs, round(system.omega, 4), system.wob
(5, 10.472, 100000.0)
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.model.lumped import LumpedModel
from torsio.physics.damping import ModelDamping, RayleighDamping
from torsio.physics.top_drives import ConstantSpeedTop
from torsio.units import RPM_TO_RAD_S, as_rpm, si_field

__all__ = ["System"]


def _check_top(instance: Any, attribute: Any, value: Any) -> None:
    if not callable(getattr(value, "boundary", None)):
        raise ConfigError(
            "top_drive",
            f"expected a top drive with a boundary(system) method (see torsio.physics."
            f"top_drives), got {value!r}",
        )


def _check_model(instance: Any, attribute: Any, value: Any) -> None:
    from torsio.model.protocol import StructuralModel

    if not isinstance(value, StructuralModel):
        raise ConfigError(
            "model",
            "expected a structural model (torsio.model.protocol.StructuralModel: a "
            "LumpedModel from a discretizer or a chain, or the wave strategy's grid), got "
            f"{value!r}",
        )
    if getattr(value, "axial", None) is not None:
        raise ConfigError(
            "model",
            "a model with axial rows moves axially too, which the torsional engines do not "
            "step: run it with torsio.analysis.axial_transient.simulate_axial (or give the chain "
            "without them)",
        )


def _check_law(instance: Any, attribute: Any, value: Any) -> None:
    if not callable(getattr(value, "torque", None)):
        raise ConfigError(
            "law",
            "expected a bit-rock law with a torque(speed, wob, radius) method (see "
            f"torsio.physics.laws), got {value!r}",
        )


def _check_operating_value(key: str, value: float, positive: bool) -> None:
    import math

    ok = math.isfinite(value) and (value > 0 if positive else value >= 0)
    if not ok:
        what = "positive" if positive else "non-negative"
        raise ConfigError(key, f"expected a {what} finite value, got {value!r}")


@attrs.frozen(repr=False)
class System:
    """A damped lumped model with a bit-rock law, top drive and operating point.

    Parameters
    ----------
    model : LumpedModel
    law : BitRockLaw
        Any object with ``torque(speed, wob, radius)``.
    bit_radius : float or str
        R_bit [m] (or e.g. ``"4.25 in"``).
    damping : RayleighDamping | ModelDamping
    wob : float or str
        Weight on bit W_ob [N], >= 0 (or e.g. ``"100 kN"``).
    rpm : float or str
        Surface rotary speed [rpm], > 0 (or e.g. ``"120 rpm"``, ``"12 rad/s"``).
    top : top drive
        Any registered top drive (:mod:`torsio.physics.top_drives`); default
        :class:`ConstantSpeedTop`.
    string : DrillString | None
        The string the model came from (for reports and the continuum).
    """

    model: LumpedModel = attrs.field(validator=_check_model)
    law: Any = attrs.field(validator=_check_law)
    bit_radius: float = si_field("length", "bit_radius")
    damping: RayleighDamping | ModelDamping = attrs.field(factory=RayleighDamping)
    wob: float = si_field("force", "wob", default=0.0)
    rpm: float = attrs.field(default=60.0, converter=as_rpm)
    top: Any = attrs.field(factory=ConstantSpeedTop, validator=_check_top)
    string: Any = attrs.field(default=None, eq=False)

    def __repr__(self) -> str:  # short: no matrices (the model has its own repr)
        name = getattr(self.string, "name", "") or "model"
        return (
            f"System({name!r}, strategy {self.model.strategy}, {self.model.dofs} DOFs; "
            f"{self.law!r}, R_bit {self.bit_radius:g} m; {self.damping!r}; {self.top!r}; "
            f"wob {self.wob / 1e3:g} kN, {self.rpm:g} rpm)"
        )

    def __attrs_post_init__(self) -> None:
        _check_operating_value("operation.wob", self.wob, positive=False)
        _check_operating_value("operation.rpm", self.rpm, positive=True)
        _check_operating_value("bit_rock.radius", self.bit_radius, positive=True)

    def with_top(self, top: Any) -> System:
        """The same system with another top drive."""
        return attrs.evolve(self, top=top)

    def dynamics(self) -> Any:
        """The one description of its dynamics (:class:`torsio.physics.dynamics.Dynamics`)."""
        from torsio.physics.dynamics import Dynamics

        return Dynamics.from_system(self)

    def at(self, wob: float | None = None, rpm: float | None = None) -> System:
        """The same system at another operating point; contacts along the string whose
        normal force depends on the weight on bit follow it
        (:meth:`torsio.model.contacts.StringContacts.at_wob`)."""
        system = attrs.evolve(
            self, wob=self.wob if wob is None else wob, rpm=self.rpm if rpm is None else rpm
        )
        contacts = getattr(self.model, "contacts", None)
        if contacts is not None and contacts.depends_on_wob:
            moved = contacts.at_wob(float(system.wob))
            if moved is not contacts:
                system = attrs.evolve(system, model=self.model.with_contacts(moved))
        return system

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
