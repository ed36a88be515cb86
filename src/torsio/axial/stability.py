"""Linear stability of steady drilling with the RGD bit, and the rpm where it changes.

:func:`drilling_stability` linearizes any lumped assembly about steady drilling
(:func:`torsio.axial.linearization.drilling_linearization`: the 2-DOF model or a chain,
either hook), finds the rightmost roots of its characteristic equation
(:func:`torsio.axial.delay_roots.rightmost_roots`, the neutral root λ = 0 of the weight
hook deflated) and reports the growth rate, the largest real part of the others, and how
axial each root's mode is (:func:`axial_share`). :func:`mode_crossings` finds where the
growth rate changes sign over a range of rpm (on a grid first, then by Brent's method
between the grid points that bracket a change) and the root that crosses there: its
frequency Im λ and axial share tell the axial from a torsional mode. A
:class:`DrillingCase` holds what these take but the rpm.

Examples
--------
>>> from torsio.model.axial_assembly import rgd_two_dof_example
>>> from torsio.axial.rgd import rgd_example
>>> result = drilling_stability(rgd_two_dof_example(), rgd_example(), 100e3, 60.0)
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

from torsio.axial.delay_roots import DelayRoots, LinearDelaySystem, rightmost_roots
from torsio.axial.linearization import drilling_linearization
from torsio.axial.rgd import RGDBit
from torsio.axial.steady import SteadyDrilling
from torsio.axial.steady_friction import drilling_state
from torsio.errors import ConfigError
from torsio.model.axial_assembly import require_axial
from torsio.model.lumped import LumpedModel

AXIAL_MODE_SHARE = 0.5
"""A mode whose axial share (:func:`axial_share`) is above this is called axial."""

MAX_AUTO_DOFS = 200
"""Degrees of freedom up to which a run finds its growth rate unless told not to. The
linearization's cost grows steeply with the chain (the collocation order with its fastest
frequency, then a Newton solve per candidate): the deviated-well chain of
``rgd_deviated_well.toml`` took 0.05 s at 48 DOF, 1.5 s at 188 DOF and 40 s at 376 DOF
(2026-12-05, 2-core AMD EPYC 2.0 GHz)."""


NO_PIPE_FRICTION_RATE = (
    "the distributed pipe's characteristic equation carries no friction along the string "
    "(its growth rate would be the frictionless pipe's); the lumped chain of the same "
    "[well] has it"
)
"""Why a run of the distributed pipe with contacts has no growth rate (refused if asked)."""


def growth_rate_skipped(assembly: Any, contacts: Any = None) -> str | None:
    """Why a run does not find the growth rate of ``assembly`` unless asked: a lumped chain
    of more than :data:`MAX_AUTO_DOFS` degrees of freedom, or a distributed pipe with
    ``contacts`` (:data:`NO_PIPE_FRICTION_RATE`); None when it does.

    Examples
    --------
    >>> from torsio.model.axial_assembly import rgd_two_dof_example
    >>> growth_rate_skipped(rgd_two_dof_example()) is None
    True
    """
    if not assembly.linearizable:  # the distributed pipe
        return None if contacts is None else f"growth rate not computed: {NO_PIPE_FRICTION_RATE}"
    dofs = assembly.dofs + require_axial(assembly).dofs
    if dofs <= MAX_AUTO_DOFS:
        return None
    return (
        f"growth rate not computed: the linearization of a {dofs}-DOF chain takes minutes "
        f"(found unasked up to {MAX_AUTO_DOFS} DOF); ask for it with growth_rate=True "
        "(torsio simulate --growth-rate), or take longer elements"
    )


@attrs.frozen(eq=False)
class DrillingCase:
    """Steady drilling of one assembly at every rpm: what its linearization takes but the
    rotary speed.

    ``wob`` [N]; ``top_drive`` and ``contacts`` as for :func:`drilling_stability`.
    :func:`mode_crossings` and :func:`each_mode_crossing` follow it over rpm.

    Examples
    --------
    >>> from torsio.model.axial_assembly import rgd_two_dof_example
    >>> from torsio.axial.rgd import rgd_example
    >>> case = DrillingCase(rgd_two_dof_example(), rgd_example(), 100e3)
    >>> case.stability(60.0).stable
    False
    """

    assembly: LumpedModel
    bit: RGDBit
    wob: float
    top_drive: Any = None
    contacts: Any = None

    def linearization(self, rpm: float) -> LinearDelaySystem:
        """:func:`~torsio.axial.linearization.drilling_linearization` at ``rpm`` [rev/min]."""
        return drilling_linearization(
            self.assembly, self.bit, self.wob, rpm, self.top_drive, self.contacts
        )

    def stability(
        self, rpm: float, *, count: int = 6, order: int | None = None
    ) -> DrillingStability:
        """:func:`drilling_stability` at ``rpm`` [rev/min]."""
        return drilling_stability(
            self.assembly,
            self.bit,
            self.wob,
            rpm,
            count=count,
            order=order,
            top_drive=self.top_drive,
            contacts=self.contacts,
        )


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
    axial_shares : ndarray of float
        :func:`axial_share` of each root's mode: 1 axial, 0 torsional.
    growth_rate : float
        max Re λ over ``roots`` [1/s] (DESIGN.md's JSON ``growth_rate``).
    stable : bool
        Whether the growth rate is negative (the neutral root does not count).
    neutral_root : complex or None
        The collocation eigenvalue that approximates the neutral root λ = 0 (a check: it is
        zero to round-off); None under the hook speed, which has none.
    details : DelayRoots
        Residuals, collocation starts and order of the root search.
    """

    steady: SteadyDrilling
    roots: NDArray[np.complex128]
    axial_shares: NDArray[np.float64]
    growth_rate: float
    stable: bool
    neutral_root: complex | None
    details: DelayRoots

    def to_dict(self) -> dict[str, Any]:
        """Plain data for JSON: roots as ``[real, imag]`` pairs (``neutral_root`` null
        when there is none)."""
        neutral = self.neutral_root
        return {
            "growth_rate": self.growth_rate,
            "stable": self.stable,
            "roots": [[r.real, r.imag] for r in self.roots],
            "neutral_root": None if neutral is None else [neutral.real, neutral.imag],
            "steady_state": self.steady.to_dict(),
        }

    def __repr__(self) -> str:
        word = "stable" if self.stable else "unstable"
        return f"DrillingStability({word}, growth_rate={self.growth_rate:.4g} 1/s)"


def axial_share(system: LinearDelaySystem, root: complex, axial_dofs: int) -> float:
    """The axial part of the kinetic energy of the mode x̂ e^{λt} at ``root``, in [0, 1].

    x̂ spans the null space of Λ(λ) (the right singular vector of its smallest singular
    value); the share is Σ_axial M_ii |x̂_i|² / Σ M_ii |x̂_i|², the first ``axial_dofs``
    entries being the axial ones (:func:`~torsio.axial.linearization.drilling_linearization`):
    1 for a purely axial mode, 0 for a purely torsional one.
    """
    _, _, right = np.linalg.svd(system.characteristic_matrix(root))
    energy = np.diag(system.mass) * np.abs(right[-1]) ** 2
    return float(energy[:axial_dofs].sum() / energy.sum())


def drilling_stability(
    assembly: LumpedModel,
    bit: RGDBit,
    wob: float,
    rpm: float,
    *,
    count: int = 6,
    order: int | None = None,
    top_drive: Any = None,
    contacts: Any = None,
) -> DrillingStability:
    """Stability of steady drilling of ``assembly`` (the arguments as in
    :func:`~torsio.axial.linearization.drilling_linearization`: any lumped assembly,
    either hook; ``wob`` [N], ``rpm`` in rev/min).

    ``count`` rightmost roots are reported; ``order`` is the collocation order N (default
    :meth:`~torsio.axial.delay_roots.LinearDelaySystem.default_order`). The cost grows
    with the DOFs and N (a dense eigenvalue problem of 2m + N rows, then Newton on an
    m × m determinant from each candidate). ``top_drive``: the top's boundary; a PI speed
    loop is linearized with the chain
    (:func:`~torsio.axial.linearization.speed_loop`), any other holds the top.
    ``contacts``: friction along the string, linearized with its damping (the steady state
    then that of the weight the friction leaves at the bit).
    """
    system = drilling_linearization(assembly, bit, wob, rpm, top_drive, contacts)
    if order is None:
        order = system.default_order()
    found = rightmost_roots(system, count, order=order)
    growth = float(found.roots[0].real)
    shares = [axial_share(system, root, require_axial(assembly).dofs) for root in found.roots]
    return DrillingStability(
        steady=drilling_state(bit, wob, rpm, contacts, require_axial(assembly).hook)[0],
        roots=found.roots,
        axial_shares=np.array(shares),
        growth_rate=growth,
        stable=growth < 0,
        neutral_root=found.dropped[0] if found.dropped else None,
        details=found,
    )


@attrs.frozen
class ModeCrossing:
    """Where the growth rate of steady drilling changes sign over rpm, and the root that
    crosses the imaginary axis there.

    Attributes
    ----------
    rpm : float
        The crossing [rev/min].
    frequency : float
        Im λ of the crossing root [rad/s].
    axial_share : float
        :func:`axial_share` of its mode (above :data:`AXIAL_MODE_SHARE`: axial).
    destabilizing : bool
        Whether the root's real part rises through 0 as the rpm grows (the mode is
        unstable above the crossing).
    """

    rpm: float
    frequency: float
    axial_share: float
    destabilizing: bool

    @property
    def mode(self) -> str:
        """``"axial"`` or ``"torsional"``, by the axial share of the kinetic energy."""
        return "axial" if self.axial_share > AXIAL_MODE_SHARE else "torsional"

    def to_dict(self) -> dict[str, Any]:
        """Plain data for JSON: ``rpm``, ``frequency`` [rad/s], ``axial_share``,
        ``destabilizing``, ``mode``."""
        return {**attrs.asdict(self), "mode": self.mode}


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


def mode_crossings(
    case: DrillingCase,
    rpm_range: tuple[float, float],
    *,
    points: int = 41,
    order: int | None = None,
) -> list[ModeCrossing]:
    """Where in ``rpm_range`` [rev/min] the growth rate of the steady drilling ``case``
    crosses 0 (:func:`growth_rate_crossings`), each with the root that crosses: the
    rightmost root there, whose real part is then 0.

    The modes are told apart at the crossings only (by Im λ and the axial share), not
    followed over rpm.

    Examples
    --------
    With the damper of :func:`~torsio.model.axial_assembly.rgd_two_dof_example` steady drilling
    turns stable above about 153 rpm, where the axial mode crosses at 32.1 rad/s (the
    axial equation alone crosses at √(2 n ζ ε a / M) = 32.2 rad/s, docs/axial.md):

    >>> from torsio.model.axial_assembly import rgd_two_dof_example
    >>> from torsio.axial.rgd import rgd_example
    >>> case = DrillingCase(rgd_two_dof_example(), rgd_example(), 100e3)
    >>> [crossing] = mode_crossings(case, (140.0, 170.0), points=7)
    >>> round(crossing.rpm, 1), round(crossing.frequency, 1), crossing.mode
    (153.3, 32.1, 'axial')
    """

    def stability(rpm: float) -> DrillingStability:
        return case.stability(rpm, count=1, order=order)

    low, high = rpm_range
    found = []
    for rpm in growth_rate_crossings(
        lambda r: stability(r).growth_rate, float(low), float(high), points
    ):
        at = stability(rpm)
        root = at.roots[0]
        system = case.linearization(rpm * (1 + 1e-6))
        rising = system.refine(root, system.neutral_roots).real > 0
        found.append(ModeCrossing(rpm, float(root.imag), float(at.axial_shares[0]), bool(rising)))
    return found


@attrs.frozen
class ModeCrossings:
    """Every mode's crossings over a range of rpm, and the check they pass.

    Attributes
    ----------
    crossings : tuple of ModeCrossing
        Sorted by rpm.
    rpm_range : tuple of float
        (low, high) [rev/min].
    unstable_at_low, unstable_at_high : int
        The unstable roots counted afresh at the two ends.
    """

    crossings: tuple[ModeCrossing, ...]
    rpm_range: tuple[float, float]
    unstable_at_low: int
    unstable_at_high: int

    @property
    def complete(self) -> bool:
        """Whether the unstable roots at ``low`` and the signed crossings (+1 for a mode
        that turns unstable) give those at ``high``; False if a grid too coarse lost a
        crossing."""
        signed = sum(1 if c.destabilizing else -1 for c in self.crossings)
        return self.unstable_at_low + signed == self.unstable_at_high

    def to_dict(self) -> dict[str, Any]:
        """Plain data for JSON."""
        return {
            "crossings": [c.to_dict() for c in self.crossings],
            "rpm_range": list(self.rpm_range),
            "unstable_at_low": self.unstable_at_low,
            "unstable_at_high": self.unstable_at_high,
            "complete": self.complete,
        }


def each_mode_crossing(
    case: DrillingCase,
    rpm_range: tuple[float, float],
    *,
    points: int = 41,
    count: int = 4,
    order: int | None = None,
) -> ModeCrossings:
    """Every crossing of the imaginary axis in ``rpm_range`` [rev/min] by each of the
    unstable roots and at least the ``count`` rightmost of the steady drilling ``case``,
    followed over rpm (:func:`torsio.axial.root_branches.follow_roots` on ``points`` rpm
    uniform in the delay t_n0 = 2π/(n Ω₀), the phase the roots turn with; the roots that
    join them on the way included).

    The growth rate (:func:`mode_crossings`) changes sign at some of them; the others are
    modes crossing while another is unstable (they set how many modes grow). A root that
    crosses twice between two grid points while it is left of all followed ones at both
    can hide: :attr:`ModeCrossings.complete` checks the count at the ends; give more
    ``points`` where it fails (an undamped chain, whose modes hover at Re λ ≈ 0, needs
    many).

    Examples
    --------
    The 2-DOF example's axial modes cross where the axial equation's do
    (ω t_n0 = (2j + 1) π, docs/axial.md), the lowest-rpm crossing a mode above the first:

    >>> from torsio.model.axial_assembly import rgd_two_dof_example
    >>> from torsio.axial.rgd import rgd_example
    >>> case = DrillingCase(rgd_two_dof_example(), rgd_example(), 100e3)
    >>> found = each_mode_crossing(case, (40.0, 170.0), points=14)
    >>> [(round(c.rpm, 1), c.mode, c.destabilizing) for c in found.crossings]
    [(51.1, 'axial', False), (153.3, 'axial', False)]
    >>> found.unstable_at_low, found.unstable_at_high, found.complete
    (2, 0, True)
    """
    from torsio.axial.root_branches import branch_crossings, follow_roots, unstable_roots

    system_at = case.linearization
    low, high = rpm_range
    if not (0 < low < high):
        raise ConfigError("rpm", f"range {low!r}..{high!r} must be increasing and positive")
    grid = 1.0 / np.linspace(1.0 / low, 1.0 / high, points)  # uniform in the delay t_n0
    found: list[ModeCrossing] = []
    for branch in follow_roots(system_at, grid, count, order=order):
        for crossing in branch_crossings(system_at, branch):
            root = 1j * crossing.frequency
            share = axial_share(
                system_at(crossing.parameter), root, require_axial(case.assembly).dofs
            )
            mode = ModeCrossing(
                crossing.parameter, crossing.frequency, share, crossing.destabilizing
            )
            if not any(_same_crossing(mode, other) for other in found):
                found.append(mode)
    return ModeCrossings(
        crossings=tuple(sorted(found, key=lambda c: c.rpm)),
        rpm_range=(float(low), float(high)),
        unstable_at_low=unstable_roots(system_at(float(low)), order),
        unstable_at_high=unstable_roots(system_at(float(high)), order),
    )


def _same_crossing(a: ModeCrossing, b: ModeCrossing) -> bool:
    """One root's crossing found on two branches (they met before it)."""
    return abs(a.rpm - b.rpm) <= 1e-9 * a.rpm and abs(a.frequency - b.frequency) <= 1e-6 * max(
        1.0, a.frequency
    )
