"""Linear stability of steady drilling with the RGD bit, and the rpm where it changes.

:func:`drilling_stability` linearizes the 2-DOF model about steady drilling
(:func:`torsio.axial.linearization.drilling_linearization`), finds the rightmost roots of
its characteristic equation (:func:`torsio.axial.delay_roots.rightmost_roots`, the
neutral root λ = 0 deflated) and reports the growth rate, the largest real part of the
others. :func:`crossing_rpm` finds where the growth rate changes sign over a range of rpm:
on a grid first, then by Brent's method between the grid points that bracket a change.

Examples
--------
>>> from torsio.axial.rgd import rgd_example
>>> result = drilling_stability(rgd_example(), 455.65, 324.857, 29981.3, 100e3, 60.0)
>>> result.stable
False
>>> sorted(result.to_dict())
['growth_rate', 'neutral_root', 'roots', 'stable', 'steady_state']
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.axial.delay_roots import DelayRoots, rightmost_roots
from torsio.axial.linearization import drilling_linearization
from torsio.axial.rgd import RGDBit
from torsio.axial.steady import SteadyDrilling, steady_drilling
from torsio.errors import ConfigError


@attrs.frozen(eq=False)
class DrillingStability:
    """Linear stability of steady drilling.

    Attributes
    ----------
    steady : SteadyDrilling
        The state linearized about.
    roots : ndarray of complex
        The rightmost characteristic roots λ = σ + iω [1/s, rad/s], Im >= 0, largest real
        part first, the neutral root left out.
    growth_rate : float
        max Re λ over ``roots`` [1/s] (DESIGN.md's JSON ``growth_rate``).
    stable : bool
        Whether the growth rate is negative (the neutral root does not count).
    neutral_root : complex
        The collocation eigenvalue that approximates the neutral root λ = 0 (a check: it is
        zero to round-off).
    details : DelayRoots
        Residuals, collocation starts and order of the root search.
    """

    steady: SteadyDrilling
    roots: NDArray[np.complex128]
    growth_rate: float
    stable: bool
    neutral_root: complex
    details: DelayRoots

    def to_dict(self) -> dict[str, Any]:
        """Plain data for JSON: roots as ``[real, imag]`` pairs."""
        return {
            "growth_rate": self.growth_rate,
            "stable": self.stable,
            "roots": [[r.real, r.imag] for r in self.roots],
            "neutral_root": [self.neutral_root.real, self.neutral_root.imag],
            "steady_state": self.steady.to_dict(),
        }

    def __repr__(self) -> str:
        word = "stable" if self.stable else "unstable"
        return f"DrillingStability({word}, growth_rate={self.growth_rate:.4g} 1/s)"


def drilling_stability(
    bit: RGDBit,
    inertia: float,
    stiffness: float,
    mass: float,
    wob: float,
    rpm: float,
    damping: float = 0.0,
    *,
    count: int = 6,
    order: int | None = None,
) -> DrillingStability:
    """Stability of steady drilling of the 2-DOF RGD model (units as in
    :func:`~torsio.axial.linearization.drilling_linearization`; ``rpm`` in rev/min).

    ``count`` rightmost roots are reported; ``order`` is the collocation order N (default
    :meth:`~torsio.axial.delay_roots.LinearDelaySystem.default_order`).
    """
    system = drilling_linearization(bit, inertia, stiffness, mass, wob, rpm, damping)
    if order is None:
        order = system.default_order()
    found = rightmost_roots(system, count, order=order, deflate=(0.0,))
    eigenvalues = system.collocation_eigenvalues(order)
    neutral = complex(eigenvalues[int(np.argmin(np.abs(eigenvalues)))])
    growth = float(found.roots[0].real)
    return DrillingStability(
        steady=steady_drilling(bit, wob, rpm),
        roots=found.roots,
        growth_rate=growth,
        stable=growth < 0,
        neutral_root=neutral,
        details=found,
    )


def growth_rate_crossings(
    growth_rate: Callable[[float], float],
    low: float,
    high: float,
    points: int = 41,
) -> list[float]:
    """Where ``growth_rate(rpm)`` changes sign on [low, high]: grid, then ``brentq``.

    Two crossings closer than the grid spacing can hide each other; give more ``points``.

    Examples
    --------
    >>> [round(r, 9) for r in growth_rate_crossings(lambda rpm: 100.0 - rpm, 20.0, 200.0)]
    [100.0]
    """
    if not (0 < low < high):
        raise ConfigError("rpm", f"range {low!r}..{high!r} must be increasing and positive")
    if points < 2:
        raise ConfigError("points", f"{points!r} must be >= 2 grid points")
    import scipy.optimize  # not at import: the torsional maps load this package too

    grid = np.linspace(low, high, points)
    values = [growth_rate(float(r)) for r in grid]
    crossings = []
    for i in range(points - 1):
        a, b, fa, fb = grid[i], grid[i + 1], values[i], values[i + 1]
        if fa == 0:
            crossings.append(float(a))
        elif fa * fb < 0:
            crossings.append(float(scipy.optimize.brentq(growth_rate, a, b, xtol=1e-10)))
    if values[-1] == 0:
        crossings.append(float(grid[-1]))
    return crossings


def crossing_rpm(
    bit: RGDBit,
    inertia: float,
    stiffness: float,
    mass: float,
    wob: float,
    rpm_range: tuple[float, float],
    damping: float = 0.0,
    *,
    points: int = 41,
    order: int | None = None,
) -> list[float]:
    """The rpm [rev/min] in ``rpm_range`` where the growth rate of steady drilling crosses 0.

    Examples
    --------
    With the damper β k = 0.06 s × 324.857 N m/rad of the built-in string's Rayleigh β,
    steady drilling turns stable above about 153 rpm, where the axial mode crosses:

    >>> from torsio.axial.rgd import rgd_example
    >>> crossings = crossing_rpm(rgd_example(), 455.65, 324.857, 29981.3, 100e3, (140.0, 170.0),
    ...                          damping=19.49, points=7)
    >>> [round(r, 1) for r in crossings]
    [153.3]
    """

    def growth(rpm: float) -> float:
        return drilling_stability(
            bit, inertia, stiffness, mass, wob, rpm, damping, count=1, order=order
        ).growth_rate

    low, high = rpm_range
    return growth_rate_crossings(growth, float(low), float(high), points)
