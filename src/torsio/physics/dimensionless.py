"""The dimensionless formulation (paper Eqs. 9-11, with ERRATA 2 and 3).

Scales, from the lumped model:

* k_eq = 1 / [K^-1]_(N,N)         equivalent stiffness seen at the bit (Eq. 9) [N m/rad]
* omega_1                          first natural frequency [rad/s]
* I_eq = k_eq / omega_1^2         equivalent inertia (Eq. 10) [kg m^2]
* tau = omega_1 t                 dimensionless time

Dividing Eq. 3 by k_eq with tau as time gives Eq. 11 with
[I]/I_eq, [C] omega_1/k_eq, [K]/k_eq and the groups

* Pi_1 = Omega / omega_1
* Pi_2 = W_ob R_bit / k_eq        (ERRATA 3: the paper's "k" is k_eq)

The dimensionless torque on bit is the law itself rescaled,
T(omega_1 theta', W_ob, R_bit) / k_eq with theta' = d theta / d tau, so every
bit-rock law (built-in or plugin) works dimensionless. For Tucker-Wang (Eq. 2)
this is Pi_2 b0 (tanh(b1 theta') + b2 theta' / (1 + b3 theta'^2)) with
b0 = a0, b1 = omega_1 a1, **b2 = omega_1 a2** (ERRATA 2; the paper prints
b2 = a2, which is not dimensionless) and b3 = omega_1^2 a3.

A top drive with inertia (:mod:`torsio.physics.top_drives`) adds its own groups
(:func:`top_drive_groups`): J / I_eq (its inertia against the string's),
kp / (omega_1 I_eq) (its damping; kp / zeta compares it with the pipe impedance,
the reflection coefficient R = (zeta - kp)/(zeta + kp)), ki / k_eq (its integral
stiffness against the string's), and drag omega_1 / k_eq. Its controller is
rescaled exactly (:class:`torsio.physics.top_drives.ScaledTopDrive`), so a
dimensionless run with a top drive is the dimensional run in tau.

A dimensionless system is an ordinary :class:`torsio.physics.system.System` whose model
matrices are the dimensionless ones, whose surface speed is Pi_1 (its ``omega``),
whose ``wob * bit_radius`` is Pi_2 (``wob = Pi_2``, ``bit_radius = 1``) and whose
law is the rescaled one; :func:`torsio.analysis.transient.simulate` runs it unchanged, in
tau. Its first natural frequency and its k_eq are 1.

Examples
--------
>>> from torsio.examples import builtin_config
>>> system = builtin_config().system(strategy="A").at(wob=100e3, rpm=60)
>>> groups = dimensionless_groups(system)
>>> round(groups.k_eq, 2), round(groups.omega1, 4), round(groups.pi1, 4), round(groups.pi2, 2)
(324.86, 0.8444, 7.4413, 33.25)
>>> [round(b, 4) for b in groups.tucker_wang]  # b0..b3, rpm reading of a1..a3
[0.221, 1.6126, 7.1762, 3.9008]
>>> scaled = dimensionless_system(system)
>>> round(scaled.omega, 4), round(scaled.model.equivalent_stiffness, 12)
(7.4413, 1.0)
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.model.lumped import LumpedModel
from torsio.model.modal import first_natural_frequency
from torsio.physics.damping import ModelDamping, RayleighDamping
from torsio.physics.law_slope import bit_slope
from torsio.physics.laws import TuckerWang
from torsio.physics.system import System
from torsio.physics.top_drive_boundary import ScaledTopDrive
from torsio.physics.top_drives import ConstantSpeedTop
from torsio.units import RPM_TO_RAD_S

__all__ = [
    "DimensionlessGroups",
    "DimensionlessLaw",
    "dimensional_system",
    "dimensionless_groups",
    "dimensionless_system",
    "top_drive_groups",
]


@attrs.frozen
class DimensionlessGroups:
    """The scales and groups of Eqs. 9-11 for a System at its operating point.

    Attributes
    ----------
    k_eq : float
        Equivalent stiffness 1/[K^-1]_(N,N) (Eq. 9) [N m/rad].
    omega1 : float
        First natural frequency [rad/s].
    i_eq : float
        Equivalent inertia k_eq / omega1^2 (Eq. 10) [kg m^2].
    pi1 : float
        Omega / omega1 [-].
    pi2 : float
        W_ob R_bit / k_eq [-] (ERRATA 3).
    bit_radius : float
        R_bit [m], kept to convert Pi_2 back to a weight on bit.
    tucker_wang : tuple of float or None
        (b0, b1, b2, b3) when the law is Tucker-Wang (b2 = omega1 a2, ERRATA 2).
    """

    k_eq: float
    omega1: float
    i_eq: float
    pi1: float
    pi2: float
    bit_radius: float
    tucker_wang: tuple[float, float, float, float] | None = None

    @property
    def b0(self) -> float | None:
        """Tucker-Wang b0 = a0 [-] (None for another law)."""
        return None if self.tucker_wang is None else self.tucker_wang[0]

    @property
    def b1(self) -> float | None:
        """Tucker-Wang b1 = omega1 a1 [-]."""
        return None if self.tucker_wang is None else self.tucker_wang[1]

    @property
    def b2(self) -> float | None:
        """Tucker-Wang b2 = omega1 a2 [-] (ERRATA 2)."""
        return None if self.tucker_wang is None else self.tucker_wang[2]

    @property
    def b3(self) -> float | None:
        """Tucker-Wang b3 = omega1^2 a3 [-]."""
        return None if self.tucker_wang is None else self.tucker_wang[3]

    @property
    def time_scale(self) -> float:
        """1 / omega1 [s]: t = tau / omega1."""
        return 1.0 / self.omega1

    def operating_point(self, pi1: float, pi2: float) -> tuple[float, float]:
        """(weight on bit [N], rotary speed [rpm]) of the groups (Pi_1, Pi_2)."""
        return pi2 * self.k_eq / self.bit_radius, pi1 * self.omega1 / RPM_TO_RAD_S

    def to_dict(self) -> dict[str, Any]:
        """Plain data for JSON."""
        data: dict[str, Any] = {
            "k_eq": self.k_eq,
            "omega1": self.omega1,
            "i_eq": self.i_eq,
            "pi1": self.pi1,
            "pi2": self.pi2,
        }
        if self.tucker_wang is not None:
            data.update(zip(("b0", "b1", "b2", "b3"), self.tucker_wang, strict=True))
        return data


def dimensionless_groups(system: System) -> DimensionlessGroups:
    """k_eq, omega_1, I_eq, Pi_1, Pi_2 (and Tucker-Wang b0..b3) of a System."""
    k_eq = system.model.equivalent_stiffness
    omega1 = first_natural_frequency(system.model)
    law = system.law
    tucker = None
    if isinstance(law, TuckerWang):
        tucker = (law.a0, omega1 * law.a1, omega1 * law.a2, omega1**2 * law.a3)
    return DimensionlessGroups(
        k_eq=k_eq,
        omega1=omega1,
        i_eq=k_eq / omega1**2,
        pi1=system.omega / omega1,
        pi2=system.wob * system.bit_radius / k_eq,
        bit_radius=system.bit_radius,
        tucker_wang=tucker,
    )


class DimensionlessLaw:
    """A bit-rock law rescaled to the dimensionless formulation.

    torque(theta', wob, radius) = T(omega1 theta', wob radius k_eq / R_bit, R_bit) / k_eq,

    with ``wob * radius`` = Pi_2 (a dimensionless System has ``wob = Pi_2`` and
    ``bit_radius = 1``) and theta' = d theta / d tau. Broadcasts like the law.

    Parameters
    ----------
    law : object
        Dimensional law with ``torque(speed, wob, radius)`` (and ``slope``).
    omega1 : float
        First natural frequency [rad/s].
    k_eq : float
        Equivalent stiffness [N m/rad].
    bit_radius : float
        R_bit [m] at which the law is evaluated.
    """

    dimensionless = True

    def __init__(self, law: Any, omega1: float, k_eq: float, bit_radius: float) -> None:
        for key, value in (("omega1", omega1), ("k_eq", k_eq), ("bit_radius", bit_radius)):
            if not (math.isfinite(value) and value > 0):
                raise ConfigError(key, f"expected a positive finite value, got {value!r}")
        self.law = law
        self.omega1 = float(omega1)
        self.k_eq = float(k_eq)
        self.bit_radius = float(bit_radius)
        self.name = f"{getattr(law, 'name', type(law).__name__)} (dimensionless)"

    def _wob(self, wob: Any, radius: Any) -> Any:
        return np.asarray(wob) * np.asarray(radius) * self.k_eq / self.bit_radius

    def torque(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        """Dimensionless torque on bit T / k_eq at dimensionless bit speed theta'."""
        w = self.omega1 * np.asarray(speed, dtype=float)
        return np.asarray(self.law.torque(w, self._wob(wob, radius), self.bit_radius)) / self.k_eq

    def slope(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        """d torque / d theta' (dimensionless)."""
        w = self.omega1 * np.asarray(speed, dtype=float)
        wob_si = self._wob(wob, radius)
        dimensional = bit_slope(self.law, w, wob_si, self.bit_radius)
        return dimensional * self.omega1 / self.k_eq

    def __repr__(self) -> str:
        return (
            f"DimensionlessLaw({self.law!r}, omega1={self.omega1!r}, k_eq={self.k_eq!r}, "
            f"bit_radius={self.bit_radius!r})"
        )


class DimensionlessTuckerWang(TuckerWang):
    """Tucker-Wang in Eq. 11 form: Pi_2 b0 (tanh(b1 s) + b2 s / (1 + b3 s^2)).

    The parameters a0..a3 of this object are b0..b3 (dimensionless), and
    ``wob * radius`` is Pi_2.
    """

    dimensionless = True


def top_drive_groups(system: System) -> dict[str, float]:
    """The dimensionless groups a top drive with inertia adds (empty for a held top).

    ``inertia_ratio`` J / I_eq, ``damping_ratio`` kp / (omega_1 I_eq) (= kp omega_1 / k_eq),
    ``integral_ratio`` ki / k_eq, ``drag_ratio`` drag omega_1 / k_eq, for a PI-type
    controller (kp, ki: the speed-error gains d_e and c_e of its boundary).
    """
    boundary = system.top.boundary(system)
    if boundary.held:
        return {}
    groups = dimensionless_groups(system)
    omega1, k_eq, i_eq = groups.omega1, groups.k_eq, groups.i_eq
    data = {
        "inertia_ratio": boundary.inertia / i_eq,
        "drag_ratio": boundary.drag * omega1 / k_eq,
    }
    if boundary.d[0]:
        data["damping_ratio"] = float(boundary.d[0]) / (omega1 * i_eq)
    if boundary.states and np.asarray(boundary.b)[0, 0]:
        data["integral_ratio"] = float(np.asarray(boundary.c)[0]) / k_eq
    return data


def dimensionless_system(
    system: System, pi1: float | None = None, pi2: float | None = None
) -> System:
    """The dimensionless System of Eq. 11 at (Pi_1, Pi_2); default: the system's own groups.

    Tucker-Wang becomes Eq. 11's b0..b3 form; any other law is wrapped in a
    :class:`DimensionlessLaw`. Damping: Rayleigh alpha, beta become alpha/omega_1
    and beta omega_1 (the same [C] omega_1/k_eq); a model's own damping matrix is
    scaled by omega_1/k_eq.
    """
    groups = dimensionless_groups(system)
    pi1 = groups.pi1 if pi1 is None else _check_group("pi1", pi1, positive=True)
    pi2 = groups.pi2 if pi2 is None else _check_group("pi2", pi2, positive=False)
    model = system.model
    omega1, k_eq, i_eq = groups.omega1, groups.k_eq, groups.i_eq
    damping: RayleighDamping | ModelDamping
    model_damping = top_damping = None
    if isinstance(system.damping, RayleighDamping):
        damping = RayleighDamping(system.damping.alpha / omega1, system.damping.beta * omega1)
    else:
        damping = ModelDamping()
        model_damping = system.damping_matrix * omega1 / k_eq
        top_damping = system.top_damping * omega1 / k_eq
    scaled = LumpedModel(
        np.asarray(model.inertia) / i_eq,
        np.asarray(model.stiffness) / k_eq,
        model.node_depths,
        strategy=model.strategy,
        damping=model_damping,
        top_damping=top_damping,
        details={**model.details, "dimensionless": True},
    )
    top: Any = system.top
    boundary = system.top.boundary(system)
    if not boundary.held:
        name = getattr(system.top, "name", type(system.top).__name__)
        top = ScaledTopDrive.from_boundary(name, boundary, omega1, k_eq)
    elif not isinstance(top, ConstantSpeedTop):
        top = ConstantSpeedTop()
    law: Any
    if groups.tucker_wang is not None:
        b0, b1, b2, b3 = groups.tucker_wang
        law = DimensionlessTuckerWang(a0=b0, a1=b1, a2=b2, a3=b3)
    else:
        law = DimensionlessLaw(system.law, omega1, k_eq, system.bit_radius)
    return System(
        model=scaled,
        law=law,
        bit_radius=1.0,
        damping=damping,
        wob=pi2,
        rpm=pi1 / RPM_TO_RAD_S,
        top=top,
        string=system.string,
    )


def dimensional_system(system: System, pi1: float, pi2: float) -> System:
    """The (dimensional) system at the operating point of groups (Pi_1, Pi_2).

    W_ob = Pi_2 k_eq / R_bit and Omega = Pi_1 omega_1.
    """
    groups = dimensionless_groups(system)
    wob, rpm = groups.operating_point(
        _check_group("pi1", pi1, positive=True), _check_group("pi2", pi2, positive=False)
    )
    return system.at(wob=wob, rpm=rpm)


def _check_group(key: str, value: Any, positive: bool) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ConfigError(key, f"expected a number, got {value!r}") from None
    ok = math.isfinite(number) and (number > 0 if positive else number >= 0)
    if not ok:
        what = "positive" if positive else "non-negative"
        raise ConfigError(key, f"expected a {what} finite value, got {value!r}")
    return number
