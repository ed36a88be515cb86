"""The steady drilling state of the RGD bit, in closed form.

Under a constant weight on bit W₀ and a constant bit speed Ω₀ the bit drills at a constant
rate of penetration V₀. Each blade then takes the same depth of cut, d₀ = 2π V₀ / Ω₀ per
revolution (d = n (U(t) − U(t − t_n)) with t_n = 2π / (n Ω₀)), and the axial balance
W₀ = ζ ε a d₀ + σ a l gives

    d₀ = (W₀ − σ a l) / (ζ ε a),     V₀ = Ω₀ d₀ / 2π,
    T₀ = ε a² d₀ / 2 + μ γ a² σ l / 2,
    MSE = W₀ / A + Ω₀ T₀ / (A V₀)    (Teale 1965; A = π a²),

the mechanical specific energy being the work done on the bit per unit volume of rock
drilled, (W₀ V₀ + T₀ Ω₀) / (A V₀). The bit cuts only when W₀ exceeds the weight σ a l the
wear flats carry.

Reference: R. Teale, "The concept of specific energy in rock drilling", Int. J. Rock
Mech. Min. Sci. 2 (1965) 57-73.

Examples
--------
>>> from torsio.axial.rgd import rgd_example
>>> state = steady_drilling(rgd_example(), wob=100e3, rpm=60.0)
>>> round(state.depth_of_cut * 1e3, 4)  # mm per revolution
7.3868
>>> round(state.rop * 3600, 3)  # m/h
26.593
>>> sorted(state.to_dict())
['bit_torque', 'depth_of_cut', 'mse', 'rop']
"""

from __future__ import annotations

import math
from typing import Any

import attrs

from torsio.axial.rgd import RGDBit
from torsio.errors import ConfigError
from torsio.units import RPM_TO_RAD_S


@attrs.frozen
class SteadyDrilling:
    """The steady drilling state: constant rate of penetration and bit speed.

    Attributes
    ----------
    wob : float
        W₀, the weight on bit [N].
    bit_speed : float
        Ω₀ [rad/s].
    depth_of_cut : float
        d₀ [m per revolution], the depth all n blades cut in one revolution.
    rop : float
        V₀ = Ω₀ d₀ / 2π [m/s], the rate of penetration.
    bit_torque : float
        T₀ [N m].
    mse : float
        The mechanical specific energy [Pa] (J per m³ of rock drilled).
    cutting_weight, friction_weight : float
        W₀ split into its cutting part ζ ε a d₀ and its wear-flat part σ a l [N].
    delay : float
        t_n0 = 2π / (n Ω₀) [s], the time between two blades.
    """

    wob: float
    bit_speed: float
    depth_of_cut: float
    rop: float
    bit_torque: float
    mse: float
    cutting_weight: float
    friction_weight: float
    delay: float

    def to_dict(self) -> dict[str, Any]:
        """The JSON keys of DESIGN.md's ``steady_state``: ``depth_of_cut`` (m per rev),
        ``rop`` (m/s), ``bit_torque`` (N m), ``mse`` (Pa)."""
        return {
            "depth_of_cut": self.depth_of_cut,
            "rop": self.rop,
            "bit_torque": self.bit_torque,
            "mse": self.mse,
        }

    def __repr__(self) -> str:
        return (
            f"SteadyDrilling(d0={self.depth_of_cut * 1e3:.4g} mm/rev, "
            f"rop={self.rop * 3600:.4g} m/h, torque={self.bit_torque:.5g} N m, "
            f"mse={self.mse / 1e6:.4g} MPa)"
        )


def _deepest_weight(bit: RGDBit) -> float:
    """The weight [N] at which the steady depth of cut per blade d0/n reaches the radius a."""
    return bit.friction_weight + bit.cutting_weight_per_depth * bit.blades * bit.radius


def steady_drilling(bit: RGDBit, wob: float, rpm: float) -> SteadyDrilling:
    """The steady drilling state of ``bit`` under weight ``wob`` [N] at ``rpm`` [rev/min].

    Raises
    ------
    ConfigError
        ``wob`` at most the wear flats' weight σ a l (the bit does not cut) or so large that
        the depth of cut per blade d0/n exceeds the bit's radius a, or ``rpm`` not positive.

    Examples
    --------
    >>> from torsio.axial.rgd import rgd_example
    >>> steady_drilling(rgd_example(), wob=50e3, rpm=60.0)
    Traceback (most recent call last):
    ...
    torsio.errors.ConfigError: wob: 50000.0 N is at most the weight the wear flats carry, ...
    """
    if not (math.isfinite(rpm) and rpm > 0):
        raise ConfigError("rpm", f"{rpm!r} must be > 0 rev/min for steady drilling")
    if not math.isfinite(wob):
        raise ConfigError("wob", f"{wob!r} is not finite; expected the weight on bit [N]")
    friction_weight = bit.friction_weight
    if wob <= friction_weight:
        raise ConfigError(
            "wob",
            f"{wob!r} N is at most the weight the wear flats carry, σ a l = "
            f"{friction_weight:.6g} N: the bit does not cut; expected a weight on bit above it",
        )
    speed = rpm * RPM_TO_RAD_S
    depth_of_cut = (wob - friction_weight) / bit.cutting_weight_per_depth
    if depth_of_cut / bit.blades > bit.radius:
        raise ConfigError(
            "wob",
            f"{wob!r} N gives a steady depth of cut d0 = (W0 - σ a l)/(ζ ε a) = "
            f"{depth_of_cut:.4g} m per revolution, {depth_of_cut / bit.blades:.3g} m per blade: "
            f"deeper than the bit's radius ({bit.radius:g} m), outside any bit's geometry; "
            f"expected a weight on bit below {_deepest_weight(bit):.4g} N for this bit",
        )
    rop = speed * depth_of_cut / (2 * math.pi)
    torque = bit.cutting_torque(depth_of_cut) + bit.friction_torque
    area = bit.hole_area
    mse = wob / area + speed * torque / (area * rop)
    return SteadyDrilling(
        wob=float(wob),
        bit_speed=speed,
        depth_of_cut=depth_of_cut,
        rop=rop,
        bit_torque=torque,
        mse=mse,
        cutting_weight=wob - friction_weight,
        friction_weight=friction_weight,
        delay=2 * math.pi / (bit.blades * speed),
    )
