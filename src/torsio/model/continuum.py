"""Exact natural frequencies and mode shapes of the continuous stepped shaft.

Each flexible section obeys the torsional wave equation G J theta'' = rho J theta_tt
(wave speed c = sqrt(G/rho)); the top is fixed (the prescribed top drive has no
dynamic rotation), the bit is a rigid inertia at the bottom. This is the
reference the lumped models are measured against; it replaces the paper's
2430-element FEM, which only approximates it. :func:`bar_frequencies` gives the
frequencies of any stepped bar of the same form (the axial bar: E A, sqrt(E/rho) and
the BHA's mass in place of G J, sqrt(G/rho) and its inertia).

Root search
-----------
Frequencies come from the Wittrick-Williams algorithm: the number of natural
frequencies below omega is

    J(omega) = sum over members of floor(omega L_m / (c_m pi))   (clamped-member modes)
             + number of negative pivots of the dynamic stiffness matrix K(omega).

J is exact and monotone, so bisection on it isolates the n-th frequency with no
root skipped and none counted twice, whatever the spacing of the roots; each is
bisected to a relative width of 1e-14.

Mode shapes follow from the transfer matrix of each section, started at the
top with zero rotation and unit torque.

Examples
--------
>>> from torsio.examples import ritto2017_string
>>> modes = continuum_modes(ritto2017_string(), count=3)
>>> [round(float(f), 4) for f in modes.frequencies_hz]
[0.1307, 0.4165, 0.7319]
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.model.drillstring import DrillString
from torsio.model.shapes import normalize_shape

_RELATIVE_WIDTH = 1e-14


@attrs.frozen
class _Member:
    torsional_rigidity: float  # G J [N m^2/rad] (E A [N] in an axial bar, bar_frequencies)
    length: float  # [m]
    wave_speed: float  # [m/s]
    top_depth: float  # [m]


def _members(string: DrillString, rigid_bha: bool) -> tuple[list[_Member], float]:
    sections = string.drill_pipe_sections if rigid_bha else string.flexible_sections
    if not sections:
        raise ConfigError("section", "a continuum with a rigid BHA needs a drill-pipe section")
    members, top = [], 0.0
    for s in sections:
        members.append(
            _Member(s.material.shear_modulus * s.polar_moment, s.length, s.material.wave_speed, top)
        )
        top += s.length
    tip_inertia = string.bha_inertia if rigid_bha else string.bit.inertia
    return members, tip_inertia


def count_below(
    omega: float, members: Sequence[_Member], tip_inertia: float, free_top: bool = False
) -> int:
    """Number of natural frequencies strictly below ``omega`` [rad/s] (Wittrick-Williams).

    ``free_top``: the top end free instead of fixed (one more node, at the top); the
    rigid-body zero is then counted for every ``omega`` > 0.
    """
    if omega <= 0:
        return 0
    top_node = 1 if free_top else 0  # index of the first member's bottom node
    n = len(members) + top_node
    diagonal = np.zeros(n)
    off_diagonal = np.zeros(n - 1)
    clamped = 0
    for i, m in enumerate(members):
        phase = omega * m.length / m.wave_speed
        sin_phase = math.sin(phase)
        if sin_phase == 0.0:
            phase = math.nextafter(phase, math.inf)
            sin_phase = math.sin(phase)
        # clamped-member modes below omega; near a multiple of pi the floor and the sign of
        # sin() must agree (sin > 0 on even half-periods), else J would count a mode twice
        half_periods = math.floor(phase / math.pi)
        if (sin_phase > 0) != (half_periods % 2 == 0):
            half_periods += -1 if phase / math.pi - half_periods < 0.5 else 1
        clamped += half_periods
        factor = m.torsional_rigidity * omega / m.wave_speed / sin_phase
        bottom = i + top_node
        diagonal[bottom] += factor * math.cos(phase)
        if bottom > 0:  # the member's top end is a node (not the fixed top)
            diagonal[bottom - 1] += factor * math.cos(phase)
            off_diagonal[bottom - 1] = -factor
    diagonal[-1] -= omega**2 * tip_inertia
    negative = 0
    pivot = diagonal[0]
    for i in range(n):
        if i > 0:
            pivot = diagonal[i] - off_diagonal[i - 1] ** 2 / pivot
        if pivot == 0.0:
            pivot = -1e-300
        negative += pivot < 0
    return clamped + negative


def _bisect_mode(
    index: int,
    members: Sequence[_Member],
    tip_inertia: float,
    low: float,
    high: float,
    free_top: bool = False,
) -> float:
    """The ``index``-th (1-based) frequency, knowing J(low) < index <= J(high) (with
    ``free_top``, J less the rigid-body zero)."""
    while (high - low) > _RELATIVE_WIDTH * high:
        middle = 0.5 * (low + high)
        if count_below(middle, members, tip_inertia, free_top) - free_top >= index:
            high = middle
        else:
            low = middle
    return 0.5 * (low + high)


@attrs.frozen
class ContinuumModes:
    """Natural frequencies and mode shapes of the continuous stepped shaft.

    Attributes
    ----------
    string : DrillString
    rigid_bha : bool
        Whether the BHA is a rigid body on the drill pipes (the limit strategy C
        converges to) instead of flexible sections.
    frequencies_rad : ndarray
        Natural frequencies [rad/s], ascending.
    """

    string: DrillString
    rigid_bha: bool
    frequencies_rad: np.ndarray
    _members: list[_Member] = attrs.field(repr=False, eq=False)

    @property
    def frequencies_hz(self) -> np.ndarray:
        """Natural frequencies [Hz]."""
        return self.frequencies_rad / (2.0 * math.pi)

    def shape(self, mode: int, depths: Sequence[float] | np.ndarray) -> np.ndarray:
        """Rotation amplitude of mode ``mode`` (1-based) at ``depths`` [m].

        Depths below the last flexible section (in the rigid bit, or the rigid
        BHA) take the value at its bottom. Normalized like the lumped modes over the
        given samples: peak magnitude 1, positive near the surface
        (:func:`torsio.model.shapes.normalize_shape`).
        """
        return normalize_shape(self.raw_shape(mode, depths))

    def raw_shape(self, mode: int, depths: Sequence[float] | np.ndarray) -> np.ndarray:
        """Unnormalized amplitude (rotation for unit torque at the top) at ``depths`` [m]."""
        if not 1 <= mode <= self.frequencies_rad.size:
            raise ConfigError("mode", f"expected 1..{self.frequencies_rad.size}, got {mode}")
        omega = float(self.frequencies_rad[mode - 1])
        depths = np.asarray(depths, dtype=float)
        out = np.empty_like(depths)
        rotation, torque = 0.0, 1.0
        members = self._members
        bottom = members[-1].top_depth + members[-1].length
        for m in members:
            kappa = omega / m.wave_speed
            rigidity_kappa = m.torsional_rigidity * kappa
            inside = (depths >= m.top_depth) & (depths <= m.top_depth + m.length)
            x = depths[inside] - m.top_depth
            out[inside] = np.cos(kappa * x) * rotation + np.sin(kappa * x) / rigidity_kappa * torque
            phase = kappa * m.length
            rotation, torque = (
                math.cos(phase) * rotation + math.sin(phase) / rigidity_kappa * torque,
                -rigidity_kappa * math.sin(phase) * rotation + math.cos(phase) * torque,
            )
        out[depths > bottom] = rotation
        return out


def continuum_modes(
    string: DrillString, count: int = 10, rigid_bha: bool = False
) -> ContinuumModes:
    """The first ``count`` exact natural frequencies of the stepped shaft.

    Parameters
    ----------
    string : DrillString
    count : int
        How many modes, >= 1.
    rigid_bha : bool
        Treat the BHA as a rigid body on the drill pipes (strategy C's limit).
    """
    if isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise ConfigError("count", f"expected a whole number of modes >= 1, got {count!r}")
    members, tip_inertia = _members(string, rigid_bha)
    return ContinuumModes(string, rigid_bha, _frequencies(members, tip_inertia, count), members)


def _frequencies(
    members: Sequence[_Member], tip_inertia: float, count: int, free_top: bool = False
) -> np.ndarray:
    """The first ``count`` frequencies [rad/s] of the members, tip lumped, top fixed (or
    free: the nonzero ones, the rigid-body zero left out)."""
    # a lower bound on the spacing scale: the slowest member's first clamped frequency
    step = min(math.pi * m.wave_speed / m.length for m in members)
    frequencies = []
    low = 0.0
    for index in range(1, count + 1):
        high = max(low, step)
        while count_below(high, members, tip_inertia, free_top) - free_top < index:
            low, high = high, 2.0 * high
        frequencies.append(_bisect_mode(index, members, tip_inertia, low, high, free_top))
        low = frequencies[-1] * (1 - 4 * _RELATIVE_WIDTH)
    return np.array(frequencies)


def bar_frequencies(
    rigidities: Sequence[float] | np.ndarray,
    lengths: Sequence[float] | np.ndarray,
    wave_speeds: Sequence[float] | np.ndarray,
    tip: float,
    count: int = 10,
    *,
    free_top: bool = False,
) -> np.ndarray:
    """The first ``count`` exact natural frequencies [rad/s] of a stepped bar, top fixed
    (``free_top``: top free, the rigid-body zero left out).

    The mathematics of the torsional shaft for any wave line: sections from the top down
    with ``rigidities`` (G J [N m²] torsionally, E A [N] axially), ``lengths`` [m] and
    ``wave_speeds`` [m/s] (√(G/ρ), √(E/ρ)), and a lumped ``tip`` at the bottom (inertia
    [kg m²] or mass [kg]; 0: a free end). One uniform section with a tip mass m_b has
    κL tan(κL) = ρ A L / m_b, κ = ω/c; with the top free, sin κL + r κL cos κL = 0,
    r = m_b/(ρ A L).

    >>> omega = bar_frequencies([2.0e11 * 3.4e-3], [1000.0], [5047.0], 3.0e4, count=1)
    >>> x = float(omega[0]) * 1000.0 / 5047.0  # κL
    >>> round(x * math.tan(x) - 2.0e11 * 3.4e-3 * 1000.0 / 5047.0**2 / 3.0e4, 10)
    0.0
    """
    if isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise ConfigError("count", f"expected a whole number of modes >= 1, got {count!r}")
    members, top = [], 0.0
    for rigidity, length, speed in zip(rigidities, lengths, wave_speeds, strict=True):
        members.append(_Member(float(rigidity), float(length), float(speed), top))
        top += float(length)
    if not members:
        raise ConfigError("sections", "a bar needs at least one section")
    return _frequencies(members, float(tip), count, bool(free_top))
