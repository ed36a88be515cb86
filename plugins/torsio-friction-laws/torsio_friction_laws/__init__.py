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

    def _mu(self, w: np.ndarray) -> np.ndarray:
        return self.mu_coulomb + (self.mu_static - self.mu_coulomb) * np.exp(
            -np.abs(w) / self.stribeck_speed
        )

    def torque(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        w = np.asarray(speed, dtype=float)
        load = np.asarray(wob) * np.asarray(radius)
        return load * self._mu(w) * np.tanh(w / self.smoothing) + self.viscous * w

    def slope(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        """d torque / d speed [N m s/rad], analytic."""
        w = np.asarray(speed, dtype=float)
        load = np.asarray(wob) * np.asarray(radius)
        smooth_sign = np.tanh(w / self.smoothing)
        weakening = (self.mu_static - self.mu_coulomb) * np.exp(-np.abs(w) / self.stribeck_speed)
        d_mu = -weakening / self.stribeck_speed  # d mu / d|w|
        return (
            load
            * (d_mu * np.abs(smooth_sign) + self._mu(w) * (1.0 - smooth_sign**2) / self.smoothing)
            + self.viscous
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

    def _mu_and_derivative(self, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        ratio = np.abs(w) / self.stribeck_speed
        decay = (self.mu_static - self.mu_coulomb) * np.exp(-(ratio**self.exponent))
        derivative = -decay * self.exponent * ratio ** (self.exponent - 1.0) / self.stribeck_speed
        return self.mu_coulomb + decay, derivative

    def torque(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        w = np.asarray(speed, dtype=float)
        mu, _ = self._mu_and_derivative(w)
        return np.asarray(wob) * np.asarray(radius) * mu * np.tanh(w / self.smoothing) + (
            self.viscous * w
        )

    def slope(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        """d torque / d speed [N m s/rad], analytic."""
        w = np.asarray(speed, dtype=float)
        mu, d_mu = self._mu_and_derivative(w)
        smooth_sign = np.tanh(w / self.smoothing)
        load = np.asarray(wob) * np.asarray(radius)
        return (
            load * (d_mu * np.abs(smooth_sign) + mu * (1.0 - smooth_sign**2) / self.smoothing)
            + self.viscous
        )


LAWS: tuple[type[BitRockLaw], ...] = (CoulombStribeck, GeneralizedStribeck)


@hookimpl
def torsio_bit_laws() -> tuple[type[BitRockLaw], ...]:
    """The laws of this distribution (the torsio hook)."""
    return LAWS
