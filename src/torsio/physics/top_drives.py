"""Top drives: the boundary at the surface, from a held speed to a tuned controller.

Every top drive is a small frozen class with a unique ``name``, built from keyword
parameters (validated, errors name ``top_drive.<key>``), whose
``boundary(system)`` returns a :class:`TopDriveBoundary`: the inertia and drag of
the top drive (node 0 of the chain) and a linear controller with optional
saturation (see ``docs/top_drives.md`` and :mod:`torsio.physics.dynamics`)::

    y      = [e, T_pipe],  e = Omega_set - Omega_0,  T_pipe = k_1 (phi_0 - phi_1) + c_1 (v_0 - v_1)
    u_free = u0 + c . z + d . y,   u = clip(u_free, -max_torque, max_torque)
    z'     = a z + b y + w (u - u_free)
    J Omega_0' = u - drag Omega_0 - T_pipe

Kinds (all start from rest, controller states zero):

* ``constant-speed``: Omega_0 = Omega_set (the paper's boundary); no node, no state.
* ``torque``: constant motor torque u = ``torque`` (Navarro-Lopez and Cortes 2007).
* ``pi``: speed loop u = kp e + ki int(e), optional ``max_torque`` with
  back-calculation anti-windup w = 1/kp (tracking time kp/ki; Astrom and Hagglund 2006).
* ``soft-torque``: ``pi`` tuned as a damper at the stick-slip frequency
  (Kyllingstad and Nessjoen 2009): ki = omega_1^2 J, kp = zeta = J_p sqrt(G rho)
  of the top drill-pipe section.
* ``z-torque``: impedance matching by torque feedback on a stiff speed loop
  (Dwars 2015): the speed set point is lowered by ``alpha / zeta`` times the
  high-passed pipe torque.

Top-drive inertia: there is no default; every kind with a node needs ``inertia``.
A typical value is J = 2900 kg m^2 (top drive with gearbox, the NORCE/OSDC
Simulator4nDOF default); Navarro-Lopez and Cortes (2007) use a rotary table of
930 kg m^2.

Examples
--------
>>> from torsio.plugins import top_drive_from_parameters
>>> pi = top_drive_from_parameters("pi", inertia=2900.0, kp=5000.0, ki=2900.0 * 0.8**2)
>>> round(abs(pi.impedance(0.8) - 5000.0), 9)   # ki = omega_s^2 J: a pure damper at omega_s
0.0
>>> round(pi.reflection_coefficient(zeta=5000.0), 12)
0.0
>>> top_drive_from_parameters("pi", inertia=-1.0, kp=1.0, ki=1.0)
Traceback (most recent call last):
...
torsio.errors.ConfigError: top_drive.inertia: expected a positive finite value in kg m^2, got -1.0
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.hookspecs import hookimpl
from torsio.physics.recorded_top import RecordedTopDrive
from torsio.physics.top_drive_boundary import TopDriveBoundary, top_pipe_impedance

__all__ = [
    "ConstantSpeedTop",
    "PITopDrive",
    "SoftTorqueTopDrive",
    "TorqueTopDrive",
    "ZTorqueTopDrive",
]

TYPICAL_INERTIA = 2900.0
"""A typical top-drive inertia with gearbox [kg m^2] (NORCE/OSDC Simulator4nDOF default)."""


def _number(key: str, value: Any, unit: str, *, positive: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise ConfigError(f"top_drive.{key}", f"expected a number in {unit}, got {value!r}")
    number = float(value)
    ok = math.isfinite(number) and (number > 0 if positive else number >= 0)
    if not ok:
        what = "positive" if positive else "non-negative"
        raise ConfigError(
            f"top_drive.{key}", f"expected a {what} finite value in {unit}, got {value!r}"
        )
    return number


def _validator(unit: str, positive: bool, optional: bool) -> Any:
    def check(instance: Any, attribute: attrs.Attribute[Any], value: Any) -> None:
        if (value is None and optional) or (attribute.name == "max_torque" and value == math.inf):
            return
        _number(attribute.name, value, unit, positive=positive)

    return check


def _parameter(unit: str, positive: bool = True, default: Any = attrs.NOTHING) -> Any:
    """A top-drive parameter: a finite number in ``unit``, > 0 (>= 0 unless ``positive``);
    None only where it is the default (a value resolved on the system, e.g. a tuning)."""
    validator = _validator(unit, positive, optional=default is None)
    return attrs.field(default=default, converter=_to_float, validator=validator)


def _max_torque_field() -> Any:
    """The motor torque limit [N m], > 0; none (inf) by default or when given as None."""
    validator = _validator("N m", positive=True, optional=False)
    return attrs.field(default=math.inf, converter=_max_torque, validator=validator)


PARAMETER_DIMENSIONS: dict[str, str] = {
    "inertia": "inertia",
    "torque": "torque",
    "max_torque": "torque",
    "drag": "rotational_damping",
    "kp": "rotational_damping",
    "zeta": "rotational_damping",
    "ki": "stiffness",
    "alpha": "dimensionless",
    "highpass_period": "time",
    "ramp": "time",
    "smoothing": "time",
}
"""Physical dimension of each parameter of the built-in top drives (for strings with units,
in Python as in a file: ``PITopDrive(inertia="2900 kg*m^2", ...)``)."""


def _convert(value: Any, field: attrs.Attribute[Any]) -> Any:
    if value is None or isinstance(value, bool):
        return value
    if isinstance(value, int | float | np.integer | np.floating):
        return float(value)
    if isinstance(value, str):
        from torsio.units import to_si

        dimension = PARAMETER_DIMENSIONS.get(field.name, "dimensionless")
        return to_si(value, dimension, key=f"top_drive.{field.name}")
    return value


_to_float = attrs.Converter(_convert, takes_field=True)


def _max_torque_value(value: Any, field: attrs.Attribute[Any]) -> Any:
    return math.inf if value is None else _convert(value, field)


_max_torque = attrs.Converter(_max_torque_value, takes_field=True)


@attrs.frozen
class ConstantSpeedTop:
    """Top drive held at the surface speed Omega of the operating point (paper Eq. 3)."""

    name: ClassVar[str] = "constant-speed"
    description: ClassVar[str] = "Omega_0 = Omega_set from t = 0 (the paper's boundary)"

    def boundary(self, system: Any) -> TopDriveBoundary:
        """No node and no state: the top turns at ``system.omega``."""
        return TopDriveBoundary(inertia=0.0, set_speed=float(system.omega))


@attrs.frozen
class TorqueTopDrive:
    """Constant motor torque on a top drive with inertia (Navarro-Lopez and Cortes 2007).

    J Omega_0' = torque - drag Omega_0 - T_pipe. There is no set speed: the speed
    follows from the torque balance, and S_SS is read relative to the mean
    top-drive speed over the steady window.

    Parameters
    ----------
    inertia : float
        J [kg m^2].
    torque : float
        Motor torque [N m].
    drag : float
        Viscous drag of the top drive [N m s/rad], default 0.
    """

    name: ClassVar[str] = "torque"
    description: ClassVar[str] = "J Omega' = torque - drag Omega - T_pipe"

    inertia: float = _parameter("kg m^2")
    torque: float = _parameter("N m")
    drag: float = _parameter("N m s/rad", positive=False, default=0.0)

    def boundary(self, system: Any) -> TopDriveBoundary:
        """Node 0 with a constant motor torque and no controller state."""
        return TopDriveBoundary(inertia=self.inertia, drag=self.drag, u0=self.torque)


def _ramp_field() -> Any:
    """Time [s] over which the set speed rises linearly from rest, >= 0 (0: a step)."""
    return _parameter("s", positive=False, default=0.0)


def _pi_boundary(drive: Any, kp: float, ki: float, set_speed: float) -> TopDriveBoundary:
    return TopDriveBoundary(
        inertia=drive.inertia,
        drag=drive.drag,
        set_speed=set_speed,
        a=np.zeros((1, 1)),
        b=np.array([[1.0, 0.0]]),
        c=np.array([ki]),
        d=np.array([kp, 0.0]),
        w=np.array([1.0 / kp if kp > 0 else 0.0]),
        max_torque=drive.max_torque,
        ramp=drive.ramp,
    )


def _pi_impedance(inertia: float, drag: float, kp: float, ki: float, omega: Any) -> Any:
    w = np.asarray(omega, dtype=float)
    return drag + kp + 1j * (w * inertia - ki / w)


@attrs.frozen
class PITopDrive:
    """Speed loop: T_m = kp e + ki int(e), e = Omega_set - Omega_0.

    With ``max_torque`` the motor torque is limited to +-max_torque and the
    integral is corrected by back-calculation, z' = e + (u - u_free)/kp (tracking
    time kp/ki; Astrom and Hagglund 2006, sec. 3.5), so it does not wind up.

    Parameters
    ----------
    inertia : float
        J [kg m^2].
    kp : float
        Proportional gain [N m s/rad], > 0.
    ki : float
        Integral gain [N m/rad], >= 0.
    drag : float
        Viscous drag of the top drive [N m s/rad], default 0.
    max_torque : float, optional
        Motor torque limit [N m]; none by default.
    ramp : float
        The set speed rises linearly from 0 over ``ramp`` [s] (a start-up); default 0, a step.
    """

    name: ClassVar[str] = "pi"
    description: ClassVar[str] = "J Omega' = kp e + ki int(e) - drag Omega - T_pipe"

    inertia: float = _parameter("kg m^2")
    kp: float = _parameter("N m s/rad")
    ki: float = _parameter("N m/rad", positive=False)
    drag: float = _parameter("N m s/rad", positive=False, default=0.0)
    max_torque: float = _max_torque_field()
    ramp: float = _ramp_field()

    def boundary(self, system: Any) -> TopDriveBoundary:
        """Node 0 with the PI integral as controller state."""
        return _pi_boundary(self, self.kp, self.ki, float(system.omega))

    def impedance(self, omega: Any) -> Any:
        """Z(i omega) = drag + kp + i (omega J - ki / omega) [N m s/rad] (unsaturated)."""
        return _pi_impedance(self.inertia, self.drag, self.kp, self.ki, omega)

    def reflection_coefficient(self, zeta: float) -> float:
        """R = (zeta - kp) / (zeta + kp) of a torsional wave of pipe impedance zeta [-]."""
        return (zeta - self.kp) / (zeta + self.kp)


@attrs.frozen
class _TunedSpeedLoop:
    """J [kg m^2] and the PI gains kp [N m s/rad], ki [N m/rad] of a speed loop whose
    gains default (None) to a tuning on the system."""

    inertia: float = _parameter("kg m^2")
    kp: float | None = _parameter("N m s/rad", default=None)
    ki: float | None = _parameter("N m/rad", positive=False, default=None)


@attrs.frozen
class SoftTorqueTopDrive(_TunedSpeedLoop):
    """The PI speed loop with the SoftTorque tuning (Kyllingstad and Nessjoen 2009).

    By default ki = omega_1^2 J (omega_1: first natural frequency of the model
    with the top held) and kp = zeta = J_p sqrt(G rho) of the top drill-pipe
    section, so that at omega_1 the top drive is the damper that absorbs a
    torsional wave coming up the pipe (reflection coefficient 0).

    Parameters
    ----------
    inertia : float
        J [kg m^2].
    kp, ki : float, optional
        Gains [N m s/rad], [N m/rad]; the defaults above when not given.
    drag, max_torque, ramp : float
        As for ``pi``.
    """

    name: ClassVar[str] = "soft-torque"
    description: ClassVar[str] = "pi with ki = omega_1^2 J, kp = zeta (SoftTorque tuning)"

    drag: float = _parameter("N m s/rad", positive=False, default=0.0)
    max_torque: float = _max_torque_field()
    ramp: float = _ramp_field()

    def gains(self, system: Any = None) -> tuple[float, float]:
        """(kp, ki) with the defaults resolved on ``system`` where not given."""
        if (self.kp is None or self.ki is None) and system is None:
            raise ConfigError(
                "top_drive.kp" if self.kp is None else "top_drive.ki",
                "the SoftTorque default tuning needs the system (omega_1, zeta); pass it",
            )
        kp = self.kp if self.kp is not None else top_pipe_impedance(system)
        if self.ki is not None:
            return kp, self.ki
        from torsio.model.modal import first_natural_frequency  # scipy: not for `torsio laws`

        return kp, first_natural_frequency(system.model) ** 2 * self.inertia

    def boundary(self, system: Any) -> TopDriveBoundary:
        """Node 0 with the PI integral as controller state, tuned on ``system``."""
        kp, ki = self.gains(system)
        return _pi_boundary(self, kp, ki, float(system.omega))

    def impedance(self, omega: Any, system: Any = None) -> Any:
        """Z(i omega) = drag + kp + i (omega J - ki / omega) [N m s/rad] (unsaturated)."""
        kp, ki = self.gains(system)
        return _pi_impedance(self.inertia, self.drag, kp, ki, omega)

    def reflection_coefficient(self, zeta: float, system: Any = None) -> float:
        """R = (zeta - kp) / (zeta + kp) [-]."""
        kp, _ = self.gains(system)
        return (zeta - kp) / (zeta + kp)


@attrs.frozen
class ZTorqueTopDrive(_TunedSpeedLoop):
    """Z-Torque: a stiff speed loop whose set point is lowered by the pipe torque.

    Impedance matching by torque feedback (Dwars 2015), as in NORCE/OSDC
    Simulator4nDOF: the speed error fed to the PI loop is

        e_z = Omega_set - Omega_0 - (alpha / zeta) HP(T_pipe)

    with HP a first-order high-pass of corner frequency 1/``highpass_period``
    (time constant highpass_period / (2 pi)), so that the steady torque does not
    move the speed. Written with the low-passed torque q (q' = (T_pipe - q)/tau):
    HP(T_pipe) = T_pipe - q. States: the PI integral of e_z and q.

    Parameters
    ----------
    inertia : float
        J [kg m^2].
    kp, ki : float, optional
        Speed-loop gains; default the stiff loop kp = 50 zeta, ki = 5 J
        (Simulator4nDOF).
    zeta : float, optional
        Pipe impedance [N m s/rad]; default J_p sqrt(G rho) of the top section.
    alpha : float
        Tuning factor in (0, 1], default 0.25 (Simulator4nDOF).
    highpass_period : float
        1 / corner frequency of the torque high-pass [s], default 20.
    drag, max_torque, ramp : float
        As for ``pi``.
    """

    name: ClassVar[str] = "z-torque"
    description: ClassVar[str] = "stiff PI on Omega_set - Omega - alpha HP(T_pipe) / zeta"

    zeta: float | None = _parameter("N m s/rad", default=None)
    alpha: float = _parameter("-", default=0.25)
    highpass_period: float = _parameter("s", default=20.0)
    drag: float = _parameter("N m s/rad", positive=False, default=0.0)
    max_torque: float = _max_torque_field()
    ramp: float = _ramp_field()

    def __attrs_post_init__(self) -> None:
        if self.alpha > 1.0:
            raise ConfigError("top_drive.alpha", f"expected a value in (0, 1], got {self.alpha!r}")

    def parameters(self, system: Any = None) -> tuple[float, float, float]:
        """(kp, ki, zeta) with the defaults resolved on ``system`` where not given."""
        zeta = self.zeta
        if zeta is None:
            if system is None:
                raise ConfigError("top_drive.zeta", "the default zeta needs the system; pass it")
            zeta = top_pipe_impedance(system)
        kp = self.kp if self.kp is not None else 50.0 * zeta
        ki = self.ki if self.ki is not None else 5.0 * self.inertia
        return kp, ki, zeta

    def boundary(self, system: Any) -> TopDriveBoundary:
        """Node 0 with two states: the PI integral and the low-passed pipe torque."""
        kp, ki, zeta = self.parameters(system)
        g = self.alpha / zeta
        rate = 2.0 * math.pi / self.highpass_period
        return TopDriveBoundary(
            inertia=self.inertia,
            drag=self.drag,
            set_speed=float(system.omega),
            a=np.array([[0.0, g], [0.0, -rate]]),
            b=np.array([[1.0, -g], [0.0, rate]]),
            c=np.array([ki, kp * g]),
            d=np.array([kp, -kp * g]),
            w=np.array([1.0 / kp, 0.0]),
            max_torque=self.max_torque,
            ramp=self.ramp,
        )


BUILTIN_TOP_DRIVES: tuple[type[Any], ...] = (
    ConstantSpeedTop,
    TorqueTopDrive,
    PITopDrive,
    SoftTorqueTopDrive,
    ZTorqueTopDrive,
    RecordedTopDrive,
)


@hookimpl
def torsio_top_drives() -> tuple[type[Any], ...]:
    """The built-in top drives, registered like any plugin's."""
    return BUILTIN_TOP_DRIVES
