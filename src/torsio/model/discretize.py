"""Discretizers: from a DrillString to a LumpedModel (strategies A, B, C and consistent mass).

A discretizer is built from keyword options and is a pure function of the string:
``StrategyC(dp_elements=5).discretize(string)``. The built-in ones register through
the plugin hook ``torsio_discretizers`` exactly as third-party ones do.

Element counts
--------------
Strategies B, C and ``consistent`` split sections into elements. Give one of

* ``dp_elements`` and ``bha_elements``: totals for the drill pipes and the BHA
  (the paper's "DP 120 DOFs, BHA 30 DOFs"). A total is split over the sections of
  its part in proportion to each section's wave travel time L/sqrt(G/rho) (its
  length, for one material) by largest remainders, with at least one element per
  section; so a total smaller than the number of sections is an error.
* ``section_elements``: one count per flexible section (per drill-pipe section
  for strategy C, whose BHA is rigid).
* ``max_element_length`` [m]: each section gets ceil(L / max_element_length).

With lumped mass each element is a spring G J L_e^-1 with half its inertia
rho J L_e on each end node (Eq. 6); the node at the top is prescribed, so the
model has one degree of freedom per element. The bit's inertia (and in strategy
C the whole rigid BHA's) is added to the last node (Eq. 7). The same elements carry a
string's axial rows (``axial_rows``: springs E A L_e^-1, masses rho A L_e halved onto
the end nodes) for axial dynamics.

Examples
--------
>>> from torsio.examples import ritto2017_string
>>> model = StrategyA().discretize(ritto2017_string())
>>> model.dofs, round(float(model.inertia[0, 0]), 2), round(float(model.stiffness[0, 0]), 2)
(1, 455.65, 324.86)
>>> StrategyB(dp_elements=120, bha_elements=30).discretize(ritto2017_string()).dofs
150
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, ClassVar

import numpy as np

from torsio.errors import ConfigError
from torsio.model.axial_rows import AxialRows, youngs_modulus
from torsio.model.components import Section
from torsio.model.drillstring import DrillString
from torsio.model.lumped import LumpedModel, chain_matrix

MAX_DOFS = 5000
"""Largest model a discretizer builds (dense n x n matrices: 200 MB each at the limit)."""


def split_count(total: int, sections: Sequence[Section], key: str) -> list[int]:
    """Split ``total`` elements over ``sections`` in proportion to wave travel time.

    Largest-remainder rounding, at least one element per section.

    >>> from torsio.examples import ritto2017_string
    >>> split_count(30, ritto2017_string().bha_sections, "bha_elements")
    [11, 19]
    """
    _check_count(key, total)
    n = len(sections)
    if n == 0:
        return []
    if total < n:
        raise ConfigError(
            key,
            f"{total} elements cannot cover {n} sections; give at least {n} "
            "(one element per section)",
        )
    times = np.array([s.wave_travel_time for s in sections])
    spare = total - n
    share = spare * times / times.sum()
    counts = np.floor(share).astype(int)
    order = np.argsort(-(share - counts), kind="stable")
    counts[order[: spare - counts.sum()]] += 1
    return [int(c) + 1 for c in counts]


def element_count(length: float, max_element_length: float) -> int:
    """Elements of at most ``max_element_length`` [m] in a section of ``length`` [m]:
    ceil(L / max_element_length), at least one (a length within 1e-9 of a whole number of
    elements takes that number).

    >>> element_count(900.0, 100.0), element_count(150.0, 100.0), element_count(0.3, 100.0)
    (9, 2, 1)
    """
    return max(1, math.ceil(length / max_element_length - 1e-9))


def lumped_halves(element_values: np.ndarray) -> np.ndarray:
    """Half of each element's inertia (or mass) on each of its end nodes, the top node
    removed: node i carries halves of elements i and i + 1, the last node half of the
    last element (Eq. 6). The one lumping rule of every chain: the torsional
    discretizers' and the axial rows' (:func:`element_axial_rows`).

    >>> lumped_halves(np.array([6.0, 6.0, 4.0]))
    array([6., 5., 2.])
    """
    halves = np.asarray(element_values, dtype=float) / 2.0
    nodes = halves.copy()
    nodes[:-1] += halves[1:]
    return nodes


def element_axial_rows(
    springs: Any, element_masses: Sequence[float], below: float, hook: str
) -> AxialRows:
    """The axial rows of a chain of elements, their springs E A / Δ [N/m] and masses ρ A Δ
    [kg] from the top down: each element's mass halved onto its end nodes
    (:func:`lumped_halves`), the mass ``below`` [kg] the last element on the last node.
    Under the weight hook the top of the pipe is free, so the top element's upper half
    rides on node 0 as well; under the speed hook it moves with the hook
    (:mod:`torsio.model.axial_rows`).

    >>> element_axial_rows([4.0, 4.0], [2.0, 2.0], 10.0, "weight").masses
    array([ 3., 11.])
    """
    masses = lumped_halves(np.asarray(element_masses, dtype=float))
    masses[-1] += below
    if hook == "weight":
        masses[0] += element_masses[0] / 2
    return AxialRows(masses, springs, hook=hook)


def _check_count(key: str, value: Any) -> None:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
        raise ConfigError(key, f"expected a whole number of elements >= 1, got {value!r}")


class Discretizer:
    """Base class of discretizers: subclasses set ``name`` and implement ``discretize`` (and,
    to lump strings for axial dynamics, ``axial_rows``: :meth:`StrategyC.axial_rows`)."""

    name: ClassVar[str] = ""
    description: ClassVar[str] = ""

    def discretize(self, string: DrillString) -> LumpedModel:  # pragma: no cover - abstract
        """The lumped model of ``string`` (inertia [kg m^2], stiffness [N m/rad])."""
        raise NotImplementedError


class StrategyA(Discretizer):
    """Strategy A (Eq. 5): one degree of freedom, rigid BHA.

    I = I_DP/3 + I_BHA, k = G J_DP / L_DP (series stiffness of the drill pipes).
    The bit inertia is part of I_BHA. Takes no options.
    """

    name = "A"
    description = "1 DOF, rigid BHA, I = I_DP/3 + I_BHA (Eq. 5)"

    def __init__(self, **options: Any) -> None:
        _reject_options(self.name, options, allowed={"dp_elements": 1, "bha_elements": 1})

    def discretize(self, string: DrillString) -> LumpedModel:
        """The 1-DOF model of Eq. 5 (inertia [kg m^2], stiffness [N m/rad])."""
        _require_drill_pipe(string, self.name)
        inertia = string.drill_pipe_inertia / 3.0 + string.bha_inertia
        depth = sum(s.length for s in string.drill_pipe_sections)
        return LumpedModel(
            [[inertia]],
            [[string.drill_pipe_stiffness]],
            [depth],
            strategy=self.name,
            details={"elements": {"drill pipe": 1, "BHA": "rigid"}},
        )


class _ElementDiscretizer(Discretizer):
    """Shared element-splitting logic of strategies B, C and consistent mass."""

    rigid_bha: ClassVar[bool] = False
    consistent_mass: ClassVar[float] = 0.0

    def __init__(
        self,
        dp_elements: int | None = None,
        bha_elements: int | None = None,
        section_elements: Sequence[int] | None = None,
        max_element_length: float | None = None,
    ) -> None:
        given = [
            k
            for k, v in (
                ("dp_elements/bha_elements", dp_elements if bha_elements is None else bha_elements),
                ("section_elements", section_elements),
                ("max_element_length", max_element_length),
            )
            if v is not None
        ]
        if len(given) > 1:
            raise ConfigError(
                "discretization",
                f"give only one way of counting elements, got {' and '.join(given)}",
            )
        if dp_elements is not None:
            _check_count("dp_elements", dp_elements)
        if bha_elements is not None:
            _check_count("bha_elements", bha_elements)
            if self.rigid_bha and bha_elements != 1:
                raise ConfigError(
                    "bha_elements",
                    f"strategy {self.name} keeps the BHA rigid (one "
                    f"body); bha_elements must be 1, got {bha_elements}",
                )
        if max_element_length is not None and not (
            isinstance(max_element_length, int | float)
            and not isinstance(max_element_length, bool)
            and math.isfinite(max_element_length)
            and max_element_length > 0
        ):
            raise ConfigError(
                "max_element_length", f"expected a positive length in m, got {max_element_length!r}"
            )
        if section_elements is not None:
            for i, count in enumerate(section_elements):
                _check_count(f"section_elements[{i}]", count)
        self.dp_elements = dp_elements
        self.bha_elements = bha_elements
        self.section_elements = None if section_elements is None else list(section_elements)
        self.max_element_length = max_element_length

    def element_counts(self, string: DrillString) -> list[int]:
        """Elements in each split section (drill pipes only when the BHA is rigid)."""
        sections = string.drill_pipe_sections if self.rigid_bha else string.flexible_sections
        if self.section_elements is not None:
            if len(self.section_elements) != len(sections):
                what = "drill-pipe" if self.rigid_bha else "flexible (non-bit)"
                raise ConfigError(
                    "section_elements",
                    f"expected one count per {what} section "
                    f"({len(sections)}), got {len(self.section_elements)}",
                )
            return list(self.section_elements)
        if self.max_element_length is not None:
            return [element_count(s.length, self.max_element_length) for s in sections]
        dp = split_count(self.dp_elements or 1, string.drill_pipe_sections, "dp_elements")
        if self.rigid_bha:
            return dp
        bha_sections = string.bha_sections
        if not bha_sections:
            if self.bha_elements is not None:
                raise ConfigError(
                    "bha_elements",
                    "the string has no flexible BHA section (only the rigid bit) to split",
                )
            return dp
        bha_total = self.bha_elements if self.bha_elements is not None else len(bha_sections)
        return dp + split_count(bha_total, bha_sections, "bha_elements")

    def _split(self, string: DrillString) -> tuple[tuple[Section, ...], list[int]]:
        """The sections split into elements (drill pipes only when the BHA is rigid) and
        the count of each: the one partition of :meth:`discretize` and :meth:`axial_rows`."""
        if self.rigid_bha:
            _require_drill_pipe(string, self.name)
        sections = string.drill_pipe_sections if self.rigid_bha else string.flexible_sections
        counts = self.element_counts(string)
        if sum(counts) > MAX_DOFS:
            raise ConfigError(
                "discretization",
                f"{sum(counts)} elements (degrees of freedom) "
                f"exceed the limit of {MAX_DOFS}: the model's matrices are dense "
                f"({sum(counts) ** 2 * 8 / 1e9:.1f} GB each)",
            )
        return sections, counts

    def discretize(self, string: DrillString) -> LumpedModel:
        sections, counts = self._split(string)
        springs, inertias, depths = [], [], []
        top = 0.0
        for section, count in zip(sections, counts, strict=True):
            element_length = section.length / count
            springs += [section.stiffness * count] * count
            inertias += [section.inertia / count] * count
            depths += list(top + element_length * np.arange(1, count + 1))
            top += section.length
        tip = string.bha_inertia if self.rigid_bha else string.bit.inertia
        stiffness = chain_matrix(np.array(springs))
        inertia = element_inertia_matrix(np.array(inertias), consistent=self.consistent_mass)
        inertia[-1, -1] += tip
        elements: dict[str, Any] = {}
        for section, count in zip(sections, counts, strict=True):
            name = base = section.name or section.kind
            while name in elements:  # two sections of one name: number the later ones
                name = f"{base} #{sum(k.startswith(base) for k in elements) + 1}"
            elements[name] = count
        if self.rigid_bha:
            elements["BHA"] = "rigid"
        return LumpedModel(
            inertia,
            stiffness,
            depths,
            strategy=self.name,
            details={"elements": elements},
            top_spring=springs[0],
        )

    def axial_rows(self, string: DrillString, hook: str) -> AxialRows:
        """The axial rows of :meth:`discretize`'s chain, on its elements
        (:meth:`~torsio.model.lumped.LumpedModel.with_axial`).

        Each element of length Δ is a spring E A / Δ [N/m] with half its mass ρ A Δ [kg]
        on each end node (A the body's cross-section, :attr:`Section.area`); what lies
        below the last element (the rigid BHA, or the bit) rides on the last node
        (:func:`element_axial_rows`). No dampers: give them with
        ``attrs.evolve(rows, dampings=...)``.

        Raises
        ------
        ConfigError
            On ``material.youngs_modulus`` for a section without E.
        """
        sections, counts = self._split(string)
        springs, element_masses = [], []
        for section, count in zip(sections, counts, strict=True):
            length = section.length / count
            springs += [youngs_modulus(section) * section.area / length] * count
            element_masses += [section.material.density * section.area * length] * count
        rigid = string.sections[len(sections) :]  # below the chain: on its last node
        below = sum(s.material.density * s.area * s.length for s in rigid)
        return element_axial_rows(springs, element_masses, below, hook)


def element_inertia_matrix(element_inertias: np.ndarray, consistent: bool | float) -> np.ndarray:
    """Inertia matrix of a chain of shaft elements, the top node removed.

    Lumped (``consistent=False``): half of each element's rho J L on each end
    node (Eq. 6). Consistent (``True``): each element contributes
    rho J L / 6 [[2, 1], [1, 2]]. A number between 0 and 1 blends the two.

    >>> element_inertia_matrix(np.array([6.0, 6.0]), consistent=False)
    array([[6., 0.],
           [0., 3.]])
    >>> element_inertia_matrix(np.array([6.0, 6.0]), consistent=True)
    array([[4., 1.],
           [1., 2.]])
    """
    m = np.asarray(element_inertias, dtype=float)
    weight = float(consistent)
    matrix = np.diag(lumped_halves(m))
    if weight:
        idx = np.arange(m.size - 1)
        coupling = weight * m[1:] / 6.0
        matrix[idx, idx + 1] = coupling
        matrix[idx + 1, idx] = coupling
        # each element end keeps m/3 instead of the lumped m/2 (less weight * m/6)
        matrix[np.diag_indices(m.size)] -= weight * m / 6.0
        matrix[idx, idx] -= coupling
    return matrix


class StrategyB(_ElementDiscretizer):
    """Strategy B (Eq. 6): every section flexible, half of each element's inertia on each node."""

    name = "B"
    description = "all sections flexible, lumped half-inertias (Eq. 6)"


class StrategyC(_ElementDiscretizer):
    """Strategy C (Eqs. 7-8): drill pipes as in B, the BHA rigid and added to the last node."""

    name = "C"
    description = "drill pipes as B, rigid BHA on the last node (Eq. 7)"
    rigid_bha = True


class ConsistentMass(_ElementDiscretizer):
    """Finite elements with the consistent mass matrix rho J L/6 [[2,1],[1,2]], all flexible.

    Not in the paper: linear shape functions for inertia as for stiffness. Its
    frequencies converge from above where lumped mass converges from below, at
    the same second order and with an error of about the same size (for a
    uniform shaft +(kh)^2/24 against -(kh)^2/24, k the wavenumber, h the element
    length); see :class:`MixedMass` for the faster one.
    """

    name = "consistent"
    description = "finite elements with consistent mass, all sections flexible"
    consistent_mass = 1.0


class MixedMass(_ElementDiscretizer):
    """Finite elements with the average of the lumped and consistent mass matrices.

    Not in the paper: rho J L/12 [[5, 1], [1, 5]] per element. In a uniform
    shaft the second-order dispersion errors of lumped and consistent mass cancel
    (omega_h = omega (1 - (kh)^4/480)); the bit and section junctions leave an
    O(h^2) term with a small constant, so the observed order falls from 4 to 2
    as elements shrink, the error staying 20-100 times below lumped mass.
    """

    name = "mixed"
    description = "finite elements with averaged lumped/consistent mass (4th order)"
    consistent_mass = 0.5


def _reject_options(strategy: str, options: dict[str, Any], allowed: dict[str, Any]) -> None:
    for key, value in options.items():
        if key in allowed and (value is None or value == allowed[key]):
            continue
        if key in allowed:
            raise ConfigError(
                key,
                f"strategy {strategy} has one degree of freedom; {key} "
                f"must be {allowed[key]}, got {value!r}",
            )
        raise ConfigError(key, f"strategy {strategy} takes no option {key!r}")


def _require_drill_pipe(string: DrillString, strategy: str) -> None:
    if not string.drill_pipe_sections:
        raise ConfigError(
            "section",
            f"strategy {strategy} needs at least one drill-pipe "
            "(non-BHA) section above the rigid BHA",
        )


BUILTIN_DISCRETIZERS: tuple[type[Discretizer], ...] = (
    StrategyA,
    StrategyB,
    StrategyC,
    ConsistentMass,
    MixedMass,
)


from torsio.hookspecs import hookimpl  # noqa: E402  (after the classes it registers)


@hookimpl
def torsio_discretizers() -> tuple[type[Discretizer], ...]:
    """The built-in discretizers, registered like any plugin's."""
    return BUILTIN_DISCRETIZERS
