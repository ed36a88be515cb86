"""Characteristic roots followed over a parameter, and where each one crosses the
imaginary axis.

A family of delay systems ``system_at(p)`` (:class:`~torsio.axial.delay_roots.LinearDelaySystem`,
e.g. steady drilling linearized at the rpm p) has roots λ(p) that move continuously with
p. :func:`follow_roots` continues each of the ``count`` rightmost roots over an increasing
grid of p:

- by Newton on det Λ(λ) (:meth:`~torsio.axial.delay_roots.LinearDelaySystem.refine`,
  the neutral roots deflated) from its value at the previous point, linearly
  extrapolated from the two before. A step is accepted when one step and two half steps
  reach the same roots, each a root (relative residual at most 1e-8) and all distinct
  (a root that jumps to another in the long step does not pass); else the step is
  halved (at most :data:`MAX_HALVINGS` times, then it is taken as it is);
- at every grid point the ``count`` rightmost roots are also found afresh
  (:func:`~torsio.axial.delay_roots.rightmost_roots`); one that no branch reached starts a
  new branch there (a root that came from the left or from beyond the collocation's reach);
- a branch left of all the fresh roots is no longer among the rightmost and is not
  followed further (what it did until then is kept).

:func:`branch_crossings` gives where a branch's real part changes sign: between the two
samples that bracket it, Brent's method on Re λ(p) with λ(p) continued by Newton from the
bracket's left end. Unlike the sign changes of the growth rate (the rightmost root,
:func:`~torsio.axial.stability.growth_rate_crossings`) this finds the crossing of every
mode, also of one that crosses while another is already unstable.

Examples
--------
The delay oscillator x'' + 0.2 x' + 4 x + 2 (x − x(t − τ)) = 0 has a root λ = iω where
(k − ω² + d)² + c² ω² = d² (ω = 2.814 and 2.010 rad/s) and τ = (arg + 2πj)/ω, the first
at τ = 1.218 s (the tests derive it):

>>> from torsio.axial.delay_roots import LinearDelaySystem
>>> def system_at(tau):
...     return LinearDelaySystem([[1.0]], [[0.2]], [[4.0]], [[2.0]], delay=tau)
>>> branches = follow_roots(system_at, np.linspace(0.2, 2.0, 10), count=2)
>>> [(round(c.parameter, 4), round(c.frequency, 4), c.destabilizing)
...  for b in branches for c in branch_crossings(system_at, b)]
[(1.2178, 2.8141, True)]
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import attrs
import numpy as np
from numpy.typing import ArrayLike, NDArray

from torsio.axial.delay_roots import LinearDelaySystem, rightmost_roots
from torsio.errors import ConfigError, SolverError

__all__ = ["BranchCrossing", "RootBranch", "branch_crossings", "follow_roots", "unstable_roots"]

MAX_HALVINGS = 12
"""Halvings of a continuation step before it is taken as it is."""

ROOT_RESIDUAL = 1e-8
"""Largest relative residual of a continued root (as :func:`rightmost_roots` keeps)."""

SAME_ROOT = 1e-6
"""Two roots closer than this times max(1, |λ|) are one."""

SystemAt = Callable[[float], LinearDelaySystem]


@attrs.frozen(eq=False)
class RootBranch:
    """One characteristic root followed over the parameter.

    Attributes
    ----------
    parameters : ndarray of float
        The parameter values where the root was computed, increasing (the grid points and
        the steps between them).
    roots : ndarray of complex
        λ at each [1/s]; Im λ >= 0 (one of each conjugate pair).
    """

    parameters: NDArray[np.float64]
    roots: NDArray[np.complex128]


@attrs.frozen
class BranchCrossing:
    """Where a branch's root is on the imaginary axis.

    Attributes
    ----------
    parameter : float
        p of the crossing.
    frequency : float
        Im λ there [rad/s].
    destabilizing : bool
        Whether Re λ rises through 0 as p grows (the mode is unstable above p).
    """

    parameter: float
    frequency: float
    destabilizing: bool


def _upper(root: complex) -> complex:
    root = root.conjugate() if root.imag < 0 else root
    return complex(root.real, 0.0) if abs(root.imag) <= 1e-12 * max(1.0, abs(root)) else root


def _continued(system: LinearDelaySystem, starts: Sequence[complex]) -> list[complex] | None:
    """Newton from each start; None if one fails or is not a root."""
    found = []
    for start in starts:
        try:
            root = _upper(system.refine(start, system.neutral_roots))
        except SolverError:
            return None
        if system.relative_residual(root) > ROOT_RESIDUAL:
            return None
        found.append(root)
    return found


def _continued_to(
    system_at: SystemAt,
    position: float,
    target: float,
    roots: list[complex],
    slopes: list[complex],
    confirm: bool = True,
) -> list[complex] | None:
    """The roots at ``target`` by Newton from the linear prediction, or None.

    With ``confirm``, only if one step and two half steps reach the same distinct roots
    (a root that jumped to another one in the long step does not)."""
    guesses = [r + s * (target - position) for r, s in zip(roots, slopes, strict=True)]
    whole = _continued(system_at(target), guesses)
    if not confirm or whole is None:
        return whole
    middle = 0.5 * (position + target)
    half = _continued_to(system_at, position, middle, roots, slopes, confirm=False)
    if half is None:
        return None
    half_slopes = [(b - a) / (middle - position) for a, b in zip(roots, half, strict=True)]
    halves = _continued_to(system_at, middle, target, half, half_slopes, confirm=False)
    if halves is None or not all(_same(a, b) for a, b in zip(whole, halves, strict=True)):
        return None
    if any(_same(b, c) for i, b in enumerate(halves) for c in halves[i + 1 :]):
        return None
    return halves


def _step(
    system_at: SystemAt, start: float, end: float, roots: list[complex], slopes: list[complex]
) -> list[tuple[float, list[complex]]]:
    """The roots continued from ``start`` to ``end`` (either way): the accepted samples
    (p, roots), ``end`` last."""
    samples: list[tuple[float, list[complex]]] = []
    position, current, level = start, roots, 0
    while position != end:
        width = (end - start) / 2**level
        target = end if abs(end - position) <= abs(width) else position + width
        found = _continued_to(system_at, position, target, current, slopes)
        if found is None and level == MAX_HALVINGS:
            found = _continued_to(system_at, position, target, current, slopes, confirm=False)
        if found is not None:
            slopes = [(b - a) / (target - position) for a, b in zip(current, found, strict=True)]
            position, current, level = target, found, max(0, level - 1)
            samples.append((target, found))
        elif level < MAX_HALVINGS:
            level += 1
        else:
            raise SolverError(
                f"a characteristic root could not be followed from p = {position:g} "
                f"(Newton failed {MAX_HALVINGS} times halving the step)"
            )
    return samples


def unstable_roots(system: LinearDelaySystem, order: int | None = None) -> int:
    """How many roots of ``system`` have Re λ > 0 (Im λ >= 0: a pair counts once)."""
    roots = rightmost_roots(system, 1 << 30, order=order).roots
    return int(np.sum(roots.real > 0))


def _window(system: LinearDelaySystem, count: int, order: int | None) -> NDArray[np.complex128]:
    """The roots followed at a point: every unstable root and at least the ``count``
    rightmost."""
    roots = rightmost_roots(system, 1 << 30, order=order).roots  # all found, rightmost first
    threshold = min(0.0, float(roots[min(count, roots.size) - 1].real))
    return roots[roots.real >= threshold]


def follow_roots(
    system_at: SystemAt, grid: ArrayLike, count: int = 4, *, order: int | None = None
) -> list[RootBranch]:
    """The roots of ``system_at(p)`` followed over ``grid`` (increasing): at every point
    each unstable root and at least the ``count`` rightmost (the module docstring).

    ``order`` is the collocation order of :func:`rightmost_roots` (default the system's).

    Raises
    ------
    ConfigError
        If ``grid`` is not increasing with 2 or more points, or ``count`` < 1.
    SolverError
        If a root cannot be followed (Newton fails however small the step).
    """
    points = np.asarray(grid, dtype=float)
    if points.ndim != 1 or points.size < 2 or not np.all(np.diff(points) > 0):
        raise ConfigError("grid", f"expected 2 or more increasing values, got {grid!r}")
    if count < 1:
        raise ConfigError("count", f"{count!r} must be >= 1 root")
    first = _window(system_at(float(points[0])), count, order)
    branches = [([float(points[0])], [complex(r)]) for r in first]
    active = list(range(len(branches)))
    for start, end in zip(points[:-1].tolist(), points[1:].tolist(), strict=True):
        current = [branches[i][1][-1] for i in active]
        slopes = [_slope(branches[i]) for i in active]
        for p, found in _step(system_at, start, end, current, slopes):
            for i, root in zip(active, found, strict=True):
                branches[i][0].append(p)
                branches[i][1].append(root)
        window = _window(system_at(end), count, order)
        reached = [branches[i][1][-1] for i in active]
        joining = [r for r in window if not any(_same(r, other) for other in reached)]
        if joining:  # followed back over the interval: a crossing in it is seen
            back = _step(system_at, end, start, joining, [0j] * len(joining))
            for k, root in enumerate(joining):
                samples = [(p, found[k]) for p, found in reversed(back[:-1])]
                branches.append(
                    (
                        [start] + [p for p, _ in samples] + [end],
                        [back[-1][1][k]] + [r for _, r in samples] + [complex(root)],
                    )
                )
                active.append(len(branches) - 1)
        threshold = float(np.min(window.real))
        active = [i for i in active if _in(branches[i][1][-1], window, threshold)]
    return [RootBranch(np.array(p), np.array(r, dtype=complex)) for p, r in branches]


def _same(a: complex, b: complex) -> bool:
    return abs(a - b) <= SAME_ROOT * max(1.0, abs(a))


def _in(root: complex, window: NDArray[np.complex128], threshold: float) -> bool:
    """Whether a branch's root is still followed: one of the window's or right of it."""
    return root.real >= threshold or any(_same(root, other) for other in window)


def _slope(branch: tuple[list[float], list[complex]]) -> complex:
    """dλ/dp of the branch's last two samples (0 for a branch of one sample)."""
    p, r = branch
    return 0j if len(p) < 2 else (r[-1] - r[-2]) / (p[-1] - p[-2])


def branch_crossings(system_at: SystemAt, branch: RootBranch) -> list[BranchCrossing]:
    """Where ``branch``'s root crosses the imaginary axis, p to about 1e-12 relative
    (Brent's method on Re λ(p) between the samples that bracket a change of sign)."""
    import scipy.optimize  # not at import: the torsional maps load this package too

    def root_at(p: float, a: float, b: float, ra: complex, rb: complex) -> complex:
        guess = ra + (rb - ra) * (p - a) / (b - a)
        found = _continued(system_at(p), [guess])
        if found is None:
            raise SolverError(f"the root near {guess} at p = {p:g} was lost in its bracket")
        return found[0]

    crossings = []
    p, r = branch.parameters, branch.roots
    for a, b, ra, rb in zip(p[:-1], p[1:], r[:-1], r[1:], strict=True):
        if ra.real == 0 or ra.real * rb.real >= 0:
            continue
        at = float(
            scipy.optimize.brentq(
                lambda q, a=a, b=b, ra=ra, rb=rb: root_at(q, a, b, ra, rb).real,
                a,
                b,
                xtol=1e-13 * max(1.0, abs(b)),
                rtol=4 * np.finfo(float).eps,
            )
        )
        root = root_at(at, a, b, ra, rb)
        crossings.append(BranchCrossing(at, float(abs(root.imag)), bool(rb.real > 0)))
    return crossings
