"""Bit-rock friction laws for torsio, registered through the ``torsio`` entry point.

Two laws of the stick-slip literature, both with a smooth (tanh) sign so that
the equations of motion stay ordinary differential equations:

* ``coulomb-stribeck``: :class:`CoulombStribeck`, the bit friction of
  Navarro-López and Cortés (2007).
* ``generalized-stribeck``: :class:`GeneralizedStribeck`, the exponential
  Stribeck curve with an exponent (Armstrong-Hélouvry, Dupont and Canudas de Wit
  1994).

Speeds are in rad/s, weight on bit in N, bit radius in m, torque in N m. Like
every :class:`torsio.physics.laws.BitRockLaw`, the parameters can be given for a bit
speed in rpm with ``speed_unit="rpm"``.

Examples
--------
>>> law = CoulombStribeck()          # Navarro-López and Cortés (2007) values
>>> round(float(law.torque(0.5, 97347.0, 0.155575)), 1)   # N m
10469.4
>>> round(float(law.torque(-0.5, 97347.0, 0.155575)), 1)  # odd in the speed
-10469.4
"""

from __future__ import annotations

from typing import Any

import numpy as np

from torsio.errors import ConfigError
from torsio.hookspecs import hookimpl
from torsio.physics.laws import BitRockLaw, Parameter

__all__ = ["CoulombStribeck", "GeneralizedStribeck", "torsio_bit_laws"]
__version__ = "0.1.0"


def _check_order(law: BitRockLaw) -> None:
    mu_static = law.values()["mu_static"]
    mu_coulomb = law.values()["mu_coulomb"]
    if mu_coulomb > mu_static:
        raise ConfigError(
            "bit_rock.mu_coulomb",
            f"law {law.name!r}: the Coulomb (sliding) coefficient must not exceed the static "
            f"one for velocity weakening; got mu_coulomb={mu_coulomb!r} > "
            f"mu_static={mu_static!r}",
        )


# --- the formulas, written once with numpy ufuncs: they take arrays (the laws' torque and
# slope) and numba scalars (the compiled kernels of torsio's batch engine).
# p = (mu_s, mu_c, w_s, eps, c_v[, delta]); speed w [rad/s], wob [N], radius [m].
def _arrays(speed: Any, wob: Any, radius: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return np.asarray(speed, dtype=float), np.asarray(wob), np.asarray(radius)


def coulomb_stribeck_torque(p: Any, w: Any, wob: Any, radius: Any) -> Any:
    """W R [mu_c + (mu_s - mu_c) exp(-|w|/w_s)] tanh(w/eps) + c_b w [N m]."""
    mu = p[1] + (p[0] - p[1]) * np.exp(-np.abs(w) / p[2])
    return wob * radius * mu * np.tanh(w / p[3]) + p[4] * w


def coulomb_stribeck_slope(p: Any, w: Any, wob: Any, radius: Any) -> Any:
    """d torque / d speed of :func:`coulomb_stribeck_torque` [N m s/rad]."""
    weakening = (p[0] - p[1]) * np.exp(-np.abs(w) / p[2])
    smooth_sign = np.tanh(w / p[3])
    d_mu = -weakening / p[2]  # d mu / d|w|
    mu = p[1] + weakening
    return wob * radius * (d_mu * np.abs(smooth_sign) + mu * (1.0 - smooth_sign**2) / p[3]) + p[4]


def generalized_stribeck_torque(p: Any, w: Any, wob: Any, radius: Any) -> Any:
    """W R [mu_c + (mu_s - mu_c) exp(-|w/w_s|^delta)] tanh(w/eps) + c_v w [N m]."""
    mu = p[1] + (p[0] - p[1]) * np.exp(-((np.abs(w) / p[2]) ** p[5]))
    return wob * radius * mu * np.tanh(w / p[3]) + p[4] * w


def generalized_stribeck_slope(p: Any, w: Any, wob: Any, radius: Any) -> Any:
    """d torque / d speed of :func:`generalized_stribeck_torque` [N m s/rad]."""
    ratio = np.abs(w) / p[2]
    decay = (p[0] - p[1]) * np.exp(-(ratio ** p[5]))
    d_mu = -decay * p[5] * ratio ** (p[5] - 1.0) / p[2]  # d mu / d|w|
    smooth_sign = np.tanh(w / p[3])
    return (
        wob * radius * (d_mu * np.abs(smooth_sign) + (p[1] + decay) * (1.0 - smooth_sign**2) / p[3])
        + p[4]
    )


class CoulombStribeck(BitRockLaw):
    """Regularized Coulomb friction with Stribeck weakening (Navarro-López and Cortés 2007).

    Navarro-López and Cortés (2007), "Sliding-mode control of a multi-DOF oilwell
    drillstring with stick-slip oscillations", Proc. American Control
    Conference, pp. 3837-3842 (the same bit model as Navarro-López and Suárez
    2004), give the friction torque on the bit

        T_fb(w) = W_ob R_b mu_b(w) sign(w),
        mu_b(w) = mu_cb + (mu_sb - mu_cb) exp(-gamma_b |w| / v_f),

    with mu_sb = 0.8, mu_cb = 0.5, gamma_b = 0.9, v_f = 1 rad/s, and a viscous
    bit torque c_b w (c_b = 50 N m s/rad) besides. Here the sign is regularized,
    sign(w) ~ tanh(w / eps), and the speed scale is w_s = v_f / gamma_b:

        T(w) = W R [mu_c + (mu_s - mu_c) exp(-|w| / w_s)] tanh(w / eps) + c_b w.

    Defaults are the values above, except c_b = 0: in a lumped model the bit's
    viscous damping usually belongs to the damping matrix (as in
    ``LumpedModel.from_chain(..., drag=[..., 50.0])``).

    Parameters
    ----------
    mu_static : float
        Static friction coefficient mu_s [-].
    mu_coulomb : float
        Coulomb (sliding) friction coefficient mu_c <= mu_s [-].
    stribeck_speed : float
        Stribeck speed w_s = v_f / gamma_b [rad/s].
    smoothing : float
        Regularization speed eps of the smooth sign [rad/s].
    viscous : float
        Viscous coefficient c_b [N m s/rad].
    """

    name = "coulomb-stribeck"
    description = (
        "W R [mu_c + (mu_s - mu_c) exp(-|w|/w_s)] tanh(w/eps) + c_b w "
        "(Navarro-Lopez and Cortes 2007, smooth sign)"
    )
    parameters = {
        "mu_static": Parameter("-", "static friction coefficient mu_s", default=0.8),
        "mu_coulomb": Parameter("-", "Coulomb friction coefficient mu_c <= mu_s", default=0.5),
        "stribeck_speed": Parameter(
            "rad/s",
            "Stribeck speed w_s = v_f/gamma_b of the exponential weakening",
            default=1.0 / 0.9,
            strict=True,
            speed_power=-1,
        ),
        "smoothing": Parameter(
            "rad/s",
            "regularization speed eps of tanh(w/eps)",
            default=0.01,
            strict=True,
            speed_power=-1,
        ),
        "viscous": Parameter("N m s/rad", "viscous coefficient c_b", default=0.0, speed_power=1),
    }
    mu_static: float
    mu_coulomb: float
    stribeck_speed: float
    smoothing: float
    viscous: float

    def __init__(self, **values: Any) -> None:
        super().__init__(**values)
        _check_order(self)

    def torque(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        return coulomb_stribeck_torque(self._vector(), *_arrays(speed, wob, radius))

    def slope(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        """d torque / d speed [N m s/rad], analytic."""
        return coulomb_stribeck_slope(self._vector(), *_arrays(speed, wob, radius))

    def _vector(self) -> np.ndarray:
        return np.array(
            [self.mu_static, self.mu_coulomb, self.stribeck_speed, self.smoothing, self.viscous]
        )

    def kernel(self) -> tuple[Any, Any, np.ndarray]:
        """Compiled torque and slope for torsio's batch engine (the same formulas)."""
        from torsio.solvers.law_kernels import compile_law_function

        return (
            compile_law_function(coulomb_stribeck_torque),
            compile_law_function(coulomb_stribeck_slope),
            self._vector(),
        )


class GeneralizedStribeck(BitRockLaw):
    """Exponential Stribeck curve with an exponent (Armstrong-Hélouvry et al. 1994).

    Armstrong-Hélouvry, Dupont and Canudas de Wit (1994), "A survey of models,
    analysis tools and compensation methods for the control of machines with
    friction", Automatica 30(7), 1083-1138, give the steady friction

        F(v) = F_C + (F_S - F_C) exp(-|v / v_s|^delta) + F_v v   (times sign(v)),

    (delta = 2: the Gaussian Stribeck curve; delta = 1: the exponential decay of
    :class:`CoulombStribeck`). A drill-string test rig was modelled with this form
    by Mihajlović et al. (2004). As a bit-rock law, with friction coefficients
    scaled by W_ob R_bit and a smooth sign:

        T(w) = W R [mu_c + (mu_s - mu_c) exp(-|w / w_s|^delta)] tanh(w / eps) + c_v w.

    Parameters
    ----------
    mu_static, mu_coulomb : float
        Static and Coulomb friction coefficients, mu_c <= mu_s [-] (required).
    stribeck_speed : float
        Stribeck speed w_s [rad/s] (required).
    exponent : float
        delta >= 1 (default 2) [-]; below 1 the law has an infinite slope at w = 0.
    smoothing : float
        Regularization speed eps of the smooth sign [rad/s].
    viscous : float
        Viscous coefficient c_v [N m s/rad].
    """

    name = "generalized-stribeck"
    description = (
        "W R [mu_c + (mu_s - mu_c) exp(-|w/w_s|^delta)] tanh(w/eps) + c_v w "
        "(Armstrong-Helouvry et al. 1994, smooth sign)"
    )
    parameters = {
        "mu_static": Parameter("-", "static friction coefficient mu_s"),
        "mu_coulomb": Parameter("-", "Coulomb friction coefficient mu_c <= mu_s"),
        "stribeck_speed": Parameter("rad/s", "Stribeck speed w_s", strict=True, speed_power=-1),
        "exponent": Parameter("-", "Stribeck exponent delta >= 1", default=2.0, minimum=1.0),
        "smoothing": Parameter(
            "rad/s",
            "regularization speed eps of tanh(w/eps)",
            default=0.01,
            strict=True,
            speed_power=-1,
        ),
        "viscous": Parameter("N m s/rad", "viscous coefficient c_v", default=0.0, speed_power=1),
    }
    mu_static: float
    mu_coulomb: float
    stribeck_speed: float
    exponent: float
    smoothing: float
    viscous: float

    def __init__(self, **values: Any) -> None:
        super().__init__(**values)
        _check_order(self)

    def torque(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        return generalized_stribeck_torque(self._vector(), *_arrays(speed, wob, radius))

    def slope(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        """d torque / d speed [N m s/rad], analytic."""
        return generalized_stribeck_slope(self._vector(), *_arrays(speed, wob, radius))

    def _vector(self) -> np.ndarray:
        return np.array(
            [
                self.mu_static,
                self.mu_coulomb,
                self.stribeck_speed,
                self.smoothing,
                self.viscous,
                self.exponent,
            ]
        )

    def kernel(self) -> tuple[Any, Any, np.ndarray]:
        """Compiled torque and slope for torsio's batch engine (the same formulas)."""
        from torsio.solvers.law_kernels import compile_law_function

        return (
            compile_law_function(generalized_stribeck_torque),
            compile_law_function(generalized_stribeck_slope),
            self._vector(),
        )


LAWS: tuple[type[BitRockLaw], ...] = (CoulombStribeck, GeneralizedStribeck)


@hookimpl
def torsio_bit_laws() -> tuple[type[BitRockLaw], ...]:
    """The laws of this distribution (the torsio hook)."""
    return LAWS
