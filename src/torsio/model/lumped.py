"""The lumped-parameter model: inertia and stiffness matrices of a chain fixed at the top.

Degrees of freedom are the rotation angles of the nodes below the surface; node 0
(the top drive) is prescribed and is not a degree of freedom. The last degree of
freedom carries the bit.

Examples
--------
A two-inertia chain built from its parameters:

>>> model = LumpedModel.from_chain(inertias=[2.0, 1.0], stiffnesses=[100.0, 50.0])
>>> model.stiffness
array([[150., -50.],
       [-50.,  50.]])
>>> model.equivalent_stiffness  # Eq. 9: 1 / (1/100 + 1/50)
33.33...
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, ClassVar

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.model.arrays import check_count, check_values, read_only, read_only_vector
from torsio.model.axial_rows import AxialRows
from torsio.model.protocol import ModelEngines
from torsio.model.tridiagonal import is_tridiagonal

LUMPED_ENGINES = ModelEngines(
    transient="torsio.analysis.transient:simulate_lumped",
    batch="torsio.solvers.batch:simulate_lumped_batch",
)
"""The engines of every lumped model: the integrators of the chain's description
(:mod:`torsio.physics.dynamics`) for one run and the batch engines for many."""


def exact_row_sums(matrix: np.ndarray) -> np.ndarray:
    """``matrix @ 1`` with sums inside their round-off bound (n eps sum |row|) set to 0."""
    sums = matrix.sum(axis=1)
    bound = matrix.shape[1] * np.finfo(float).eps * np.abs(matrix).sum(axis=1)
    sums[np.abs(sums) <= bound] = 0.0
    return sums


def chain_matrix(springs: np.ndarray) -> np.ndarray:
    """Matrix of a chain of springs (or dampers) whose first one is tied to the fixed top.

    ``springs[i]`` joins node ``i`` and node ``i+1`` (node 0 is the top), so the
    result is tridiagonal with ``k_i + k_(i+1)`` on the diagonal.

    >>> chain_matrix(np.array([3.0, 2.0]))
    array([[ 5., -2.],
           [-2.,  2.]])
    """
    springs = np.asarray(springs, dtype=float)
    n = springs.size
    matrix = np.zeros((n, n))
    idx = np.arange(n)
    matrix[idx, idx] = springs
    matrix[idx[:-1], idx[:-1]] += springs[1:]
    matrix[idx[:-1], idx[1:]] = -springs[1:]
    matrix[idx[1:], idx[:-1]] = -springs[1:]
    return matrix


@attrs.frozen(repr=False)
class LumpedModel:
    """Inertia and stiffness matrices of a torsional chain fixed at the top.

    A lumped model is a :class:`torsio.model.protocol.StructuralModel`: it is linearizable,
    has matrices, no time step of its own, and runs on :data:`LUMPED_ENGINES`.

    Parameters
    ----------
    inertia : ndarray, shape (n, n)
        Inertia matrix [I], in kg m^2 (diagonal for lumped mass, tridiagonal for
        consistent mass).
    stiffness : ndarray, shape (n, n)
        Stiffness matrix [K], in N m/rad. ``[K] @ 1`` is the coupling of each node
        to the prescribed top (``k_1`` on the first node for a chain).
    node_depths : ndarray, shape (n,)
        Measured depth of each degree of freedom [m] (for abstract models, any
        increasing coordinate).
    strategy : str
        Name of the discretizer that built the model.
    damping : ndarray or None
        Damping matrix [C], in N m s/rad when the model carries its own (e.g. a
        published lumped model); a System's Rayleigh damping replaces it.
    top_damping : ndarray or None
        Coupling of each node to the top through dampers [N m s/rad]
        (``c_1`` on the first node), used with ``damping``.
    details : dict
        What the discretizer chose (elements per section, ...), for reports.
    contacts : StringContacts or None
        Coulomb contacts of the nodes with the borehole (one capacity per node,
        :class:`torsio.model.contacts.StringContacts`; None: no contact); lumped mass only.
    axial : AxialRows or None
        The nodes' axial masses, springs and dampers and the hook
        (:class:`torsio.model.axial_rows.AxialRows`, :meth:`with_axial`; None: the chain
        turns only). A chain with axial rows runs on the axial engine
        (:func:`torsio.analysis.axial_transient.simulate_axial`); a System refuses it.
    top_spring : float or None
        The spring k_1 [N m/rad] that ties node 1 to the top, as given (:meth:`from_chain`;
        None: read from [K], :attr:`springs`). [K] holds k_1 only inside k_1 + k_2, which
        does not give it back to the last bit.
    """

    linearizable: ClassVar[bool] = True
    """The linear stability analysis applies (:mod:`torsio.analysis.stability`)."""
    has_matrices: ClassVar[bool] = True
    """[I] and [K]: :func:`torsio.model.modal.modal_analysis` applies."""
    engines: ClassVar[ModelEngines] = LUMPED_ENGINES
    """The engines that run a lumped model (:func:`torsio.model.protocol.resolve`)."""

    inertia: np.ndarray = attrs.field(converter=read_only)
    stiffness: np.ndarray = attrs.field(converter=read_only)
    node_depths: np.ndarray = attrs.field(converter=read_only_vector)
    strategy: str = "custom"
    damping: np.ndarray | None = attrs.field(
        default=None, converter=attrs.converters.optional(read_only)
    )
    top_damping: np.ndarray | None = attrs.field(
        default=None, converter=attrs.converters.optional(read_only_vector)
    )
    details: dict[str, Any] = attrs.field(factory=dict, eq=False)
    contacts: Any = attrs.field(default=None, eq=False)
    axial: AxialRows | None = attrs.field(default=None, eq=False)
    top_spring: float | None = attrs.field(default=None, eq=False)
    _memo: dict[str, Any] = attrs.field(factory=dict, init=False, eq=False, repr=False)
    """What analyses derived from the (never modified) matrices, e.g. omega_1, kept so that
    each is computed once per model (:func:`torsio.model.modal.first_natural_frequency`)."""

    def __repr__(self) -> str:  # short: no matrices
        depths = self.node_depths
        return (
            f"LumpedModel(strategy {self.strategy!r}, {self.dofs} DOFs at "
            f"{depths[0]:g}..{depths[-1]:g} m, total inertia {np.trace(self.inertia):.5g} kg m^2"
            + ("" if self.has_lumped_mass else ", consistent mass")
            + ("" if self.damping is None else ", own dampers")
            + ("" if self.axial is None else f", axial rows, hook {self.axial.hook}")
            + ")"
        )

    def __attrs_post_init__(self) -> None:
        n = self.inertia.shape[0]
        for key, matrix in (("inertia", self.inertia), ("stiffness", self.stiffness)):
            if matrix.shape != (n, n) or n == 0:
                raise ConfigError(
                    key, f"expected a non-empty square matrix of size {n}, got shape {matrix.shape}"
                )
            if not np.all(np.isfinite(matrix)):
                raise ConfigError(key, "matrix has non-finite entries")
            if not np.allclose(matrix, matrix.T, rtol=1e-12, atol=0.0):
                raise ConfigError(key, "matrix must be symmetric")
            try:
                np.linalg.cholesky(matrix)
            except np.linalg.LinAlgError:
                raise ConfigError(
                    key,
                    "matrix must be positive definite (is every node tied "
                    "to the top through springs, every inertia > 0?)",
                ) from None
        if self.node_depths.shape != (n,):
            raise ConfigError("node_depths", f"expected {n} depths, got {self.node_depths.size}")
        if self.damping is not None:
            if self.damping.shape != (n, n) or not np.allclose(self.damping, self.damping.T):
                raise ConfigError("damping", f"expected a symmetric {n}x{n} matrix")
            if self.top_damping is None or self.top_damping.shape != (n,):
                raise ConfigError("top_damping", f"expected {n} values with a damping matrix")
        if self.top_spring is not None:
            row = self.stiffness[0]
            bound = n * np.finfo(float).eps * np.abs(row).sum()
            if not abs(self.top_spring - row.sum()) <= bound:
                raise ConfigError(
                    "top_spring",
                    f"{self.top_spring!r} N m/rad is not the top coupling of [K], "
                    f"{row.sum()!r} (its first row's sum)",
                )

    def with_dampers(self, dampings: Any) -> LumpedModel:
        """The same chain with dampers c_1..c_n [N m s/rad] in parallel with its springs
        (replacing its own; c_1 to the top).

        >>> LumpedModel.from_chain([1.0, 1.0], [0.1, 0.2]).with_dampers([0.01, 0.02]).dampers
        array([0.01, 0.02])
        """
        dampers = read_only_vector(dampings)
        check_count("dampings", dampers, self.dofs)
        check_values("dampings", dampers, allow_zero=True)
        top = np.zeros(self.dofs)
        top[0] = dampers[0]
        return attrs.evolve(self, damping=chain_matrix(dampers), top_damping=top)

    def with_contacts(self, contacts: Any) -> LumpedModel:
        """The same chain with Coulomb contacts at its nodes (a
        :class:`torsio.model.contacts.StringContacts` with one capacity per node; None: none).

        Raises
        ------
        ConfigError
            On ``discretization.strategy`` for consistent mass (a contact holds one node's
            speed, which a mass matrix that couples nodes does not allow).
        """
        if contacts is not None and not self.has_lumped_mass:
            raise ConfigError(
                "discretization.strategy",
                f"friction along the string needs a lumped-mass model (A, B, C or wave); "
                f"{self.strategy!r} has consistent mass",
            )
        if contacts is not None and contacts.static.shape != (self.dofs,):
            raise ConfigError(
                "well", f"expected a capacity per node ({self.dofs}), got {contacts.static.size}"
            )
        return attrs.evolve(self, contacts=contacts)

    def with_axial(self, axial: AxialRows) -> LumpedModel:
        """The same chain whose nodes also move axially (:class:`AxialRows`, one mass per
        node).

        The axial engine steps a chain: lumped mass, each node tied to its neighbours (and
        node 1 to the top) by a spring and a damper, nothing else (its torsional rows are
        :attr:`node_inertias`, :attr:`springs` and :attr:`dampers`).

        Raises
        ------
        ConfigError
            On ``chain.masses`` for another number of masses than nodes; on
            ``discretization.strategy`` for consistent mass or a [K] that is not a chain
            tied to the top at node 1; on ``chain.drag`` for dampers that are not a chain's
            (drag to the borehole: the axial engine has none); on ``well`` for torsional
            contacts (the axial engine takes its own, ``AxialContacts``).
        """
        check_count("chain.masses", axial.masses, self.dofs)
        tied_once = not np.any(self.top_stiffness[1:]) and is_tridiagonal(self.stiffness)
        if not (self.has_lumped_mass and tied_once):
            raise ConfigError(
                "discretization.strategy",
                f"axial dynamics need a lumped-mass chain tied to the top at node 1; "
                f"{self.strategy!r} is not one",
            )
        if self.damping is not None and not np.array_equal(
            self.damping, chain_matrix(self.dampers)
        ):
            raise ConfigError(
                "chain.drag",
                "axial dynamics take dampers between the nodes only (no drag to the borehole)",
            )
        if self.contacts is not None:
            raise ConfigError(
                "well",
                "the axial engine takes its contacts along the string as AxialContacts "
                "(simulate_axial(contacts=...)), not the torsional model's",
            )
        return attrs.evolve(self, axial=axial)

    # --- constructors ---------------------------------------------------------------------
    @classmethod
    def from_chain(
        cls,
        inertias: Sequence[float],
        stiffnesses: Sequence[float],
        dampings: Sequence[float] | None = None,
        drag: Sequence[float] | None = None,
        node_depths: Sequence[float] | None = None,
        strategy: str = "custom",
    ) -> LumpedModel:
        """A chain of inertias joined by springs (and dampers), the first tied to the top.

        Parameters
        ----------
        inertias : sequence of float
            I_1..I_n [kg m^2]; the last carries the bit.
        stiffnesses : sequence of float
            k_1..k_n [N m/rad]; ``k_i`` joins node i-1 and node i (node 0 the top).
        dampings : sequence of float, optional
            c_1..c_n [N m s/rad], dampers in parallel with the springs.
        drag : sequence of float, optional
            Damping of each inertia to the (still) borehole [N m s/rad].
        node_depths : sequence of float, optional
            Depth of each node [m]; defaults to 1, 2, ..., n.

        Examples
        --------
        A 4-DOF chain with the structure of Navarro-Lopez and Cortes (2007): rotary
        table, two pipe inertias and the BHA, with inertias, springs and dampers of
        the size their model uses (check them against the paper before a study). Their
        rotary table is driven by a motor torque; here the prescribed top speed drives
        it through a very stiff first spring:

        >>> m = LumpedModel.from_chain(
        ...     inertias=[930.0, 2782.25, 750.0, 471.9698],
        ...     stiffnesses=[1.0e12, 698.063, 1080.0, 907.48],
        ...     dampings=[0.0, 139.6126, 190.0, 181.49], drag=[425.0, 0.0, 0.0, 50.0])
        >>> m.dofs
        4
        """
        inertia_values = np.asarray(inertias, dtype=float).reshape(-1)
        spring_values = np.asarray(stiffnesses, dtype=float).reshape(-1)
        n = inertia_values.size
        if spring_values.size != n:
            raise ConfigError(
                "stiffnesses", f"expected {n} values (one per inertia), got {spring_values.size}"
            )
        check_values("inertias", inertia_values, allow_zero=False)
        check_values("stiffnesses", spring_values, allow_zero=False)
        depths = np.arange(1.0, n + 1) if node_depths is None else node_depths
        damping = top_damping = None
        if dampings is not None or drag is not None:
            c = np.zeros(n) if dampings is None else np.asarray(dampings, float).reshape(-1)
            d = np.zeros(n) if drag is None else np.asarray(drag, float).reshape(-1)
            for key, values in (("dampings", c), ("drag", d)):
                if values.size != n:
                    raise ConfigError(key, f"expected {n} values, got {values.size}")
                check_values(key, values, allow_zero=True)
            damping = chain_matrix(c) + np.diag(d)
            top_damping = np.zeros(n)
            top_damping[0] = c[0]
        return cls(
            np.diag(inertia_values),
            chain_matrix(spring_values),
            depths,
            strategy=strategy,
            damping=damping,
            top_damping=top_damping,
            top_spring=float(spring_values[0]),
        )

    # --- derived quantities ---------------------------------------------------------------
    @property
    def dofs(self) -> int:
        """Number of degrees of freedom."""
        return int(self.inertia.shape[0])

    @property
    def top_stiffness(self) -> np.ndarray:
        """Coupling of each node to the prescribed top, ``[K] @ 1`` [N m/rad] (k_1 e_1).

        A row sum within its round-off bound, n eps sum_j |K_ij|, is zero: in a chain the
        rows below the first cancel exactly (-k_i + (k_i + k_i+1) - k_i+1), but in floating
        point they leave a few ulp where neighbouring springs differ (a section junction).

        >>> model = LumpedModel.from_chain([1.0, 1.0, 1.0], [1.0, 0.1, 0.2])
        >>> bool(model.stiffness.sum(axis=1)[1] == 0.0), model.top_stiffness
        (False, array([1., 0., 0.]))
        """
        return exact_row_sums(self.stiffness)

    @property
    def node_inertias(self) -> np.ndarray:
        """The inertia of each node [kg m^2]: the diagonal of [I] (a lumped-mass chain's)."""
        return np.diag(self.inertia).copy()

    @property
    def springs(self) -> np.ndarray:
        """The chain's springs k_1..k_n [N m/rad], k_i joining node i-1 to node i (node 0 the
        top): -[K]_(i-1,i), and k_1 as given (:attr:`top_spring`), else ([K] 1)_1
        (:attr:`top_stiffness`, to the rounding of k_1 + k_2).

        >>> LumpedModel.from_chain([1.0, 1.0], [0.1, 0.2]).springs
        array([0.1, 0.2])
        """
        top = self.top_stiffness[0] if self.top_spring is None else self.top_spring
        return np.concatenate([[top], 0.0 - np.diag(self.stiffness, 1)])

    @property
    def dampers(self) -> np.ndarray:
        """The chain's own dampers c_1..c_n [N m s/rad] in parallel with its springs
        (:attr:`damping`, :attr:`top_damping`; zeros without them)."""
        if self.damping is None or self.top_damping is None:
            return np.zeros(self.dofs)
        return np.concatenate([self.top_damping[:1], 0.0 - np.diag(self.damping, 1)])

    @property
    def equivalent_stiffness(self) -> float:
        """k_eq = 1 / [K^-1]_(N,N) (Eq. 9) [N m/rad]: the static stiffness seen at the bit."""
        unit_bit_torque = np.zeros(self.dofs)
        unit_bit_torque[-1] = 1.0
        return float(1.0 / np.linalg.solve(self.stiffness, unit_bit_torque)[-1])

    def first_frequency(self) -> float:
        """omega_1 [rad/s] of the first mode, top held, undamped: solved once per model (or
        taken from a modal analysis of it, :func:`torsio.model.modal.modal_analysis`)."""
        from torsio.model.modal import lowest_natural_frequency

        return lowest_natural_frequency(self)

    @property
    def bit_inertia(self) -> float:
        """Inertia of the bit's node, the last degree of freedom, [I]_(N,N) [kg m^2]."""
        return float(self.inertia[-1, -1])

    @property
    def time_step(self) -> None:
        """None: a lumped model has no step of its own (its integrators choose theirs)."""
        return None

    def describe(self) -> dict[str, Any]:
        """What the model is, for reports and JSON.

        >>> LumpedModel.from_chain(inertias=[2.0, 1.0], stiffnesses=[100.0, 50.0]).describe()
        {'strategy': 'custom', 'dofs': 2, 'lumped_mass': True, 'own_damping': False, \
'total_inertia_kg_m2': 3.0, 'equivalent_stiffness_N_m_rad': 33.33..., 'elements': {}}
        """
        return {
            "strategy": self.strategy,
            "dofs": self.dofs,
            "lumped_mass": self.has_lumped_mass,
            "own_damping": self.damping is not None,
            "total_inertia_kg_m2": self.total_inertia,
            "equivalent_stiffness_N_m_rad": self.equivalent_stiffness,
            "elements": dict(self.details.get("elements", {})),
            **({} if self.contacts is None else {"contacts": self.contacts.describe()}),
            **({} if self.axial is None else {"axial": self.axial.describe()}),
        }

    @property
    def total_inertia(self) -> float:
        """Sum of all inertia, ``1^T [I] 1`` [kg m^2]."""
        return float(self.inertia.sum())

    @property
    def has_lumped_mass(self) -> bool:
        """Whether [I] is diagonal."""
        return bool(np.count_nonzero(self.inertia - np.diag(np.diag(self.inertia))) == 0)
