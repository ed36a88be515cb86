"""Steady drilling of a lumped assembly linearized about its steady state, with its delay.

The 2-DOF model of Richard, Germay and Detournay (2007) first: the bit assembly, of axial
mass M and torsional inertia I, is pushed down by the constant weight W₀ (the axial
stiffness of the string neglected) and turned through a torsional spring k (and a damper c
in parallel) whose top turns at Ω₀:

    M U'' = W₀ − W(d),
    I Φ'' = k (Ω₀ t − Φ) + c (Ω₀ − Φ') − T(d),
    d = n (U(t) − U(t − t_n)),   Φ(t) − Φ(t − t_n) = 2π / n.

While it drills, W = ζ ε a d + σ a l and T = ε a² d / 2 + μ γ a² σ l / 2. Perturbing the
steady motion U = V₀ t + u, Φ = Ω₀ t − T₀/k + φ, t_n = t_n0 + δt_n (t_n0 = 2π/(n Ω₀)),
the delay's own equation gives Ω₀ δt_n + φ(t) − φ(t − t_n0) = 0 to first order, and the
depth of cut

    δd = n [u(t) − u(t − t_n0) + V₀ δt_n]
       = n [(u(t) − u(t − t_n0)) − (V₀/Ω₀) (φ(t) − φ(t − t_n0))]

(the second term is the state-dependent delay: a bit that turns faster takes less time
per blade, so cuts less). With x = (u, φ) this is M x'' + C x' + K x + D (x − x(t − τ))
= 0 for :class:`~torsio.axial.delay_roots.LinearDelaySystem`:

    M = diag(M, I),  C = diag(0, c),  K = diag(0, k),  τ = t_n0,
    D = n [[ζ ε a, −ζ ε a V₀/Ω₀], [ε a² / 2, −(ε a² / 2) V₀/Ω₀]],

and the characteristic equation, with E(λ) = 1 − e^{−λ t_n0}, is

    Δ(λ) = (M λ² + n ζ ε a E)(I λ² + c λ + k) − n (ε a² / 2)(V₀/Ω₀) M λ² E = 0.

**A chain** (:func:`~torsio.model.axial_assembly.axial_chain`, n nodes, m axial DOFs) is
linearized the same way about its steady state (every node at Ω₀ and V₀, every spring
carrying T₀ and W₀): x = (u_0 .. u_m−1, φ_0 .. φ_n−1), M = diag(m_i, I_i), C and K block
diagonal with the chain's tridiagonal matrices (:func:`chain_matrices`), and D the 2 × 2
block above on the bit's entries (u_m−1, φ_n−1). The 2-DOF model is the chain of one node.

**Friction along the string** (:mod:`torsio.axial.steady_friction`): about the steady
state with contacts, each contact's sliding friction adds its damping matrix
F_d/|s₀| (I − ŝ₀ŝ₀ᵀ) in the (V, r ω) metric to C on its node's (u_i, φ_i), as
[[D₁₁, r D₁₂], [r D₂₁, r² D₂₂]] in (u, φ); the steady state is that of the bit's weight
left by the friction (:func:`~torsio.axial.steady_friction.steady_with_friction`). A
contact stuck in steady drilling does not occur (every node slides at V₀, Ω₀ > 0).

**The neutral root.** Under the hook weight, λ = 0 is a root for every parameter
(E(0) = 0 and K has no axial spring to the ground): a shift of the whole string's axial
position, u_i = const, is a steady motion too, since the depth of cut reads only
differences of U and the hook's force is constant. It is neutral, not a mode: the
system's ``neutral_roots`` = (0,). Under the hook speed the spring k_a,0 pins the axial
position (det K ≠ 0): no neutral root.

References: Richard, Germay and Detournay, J. Sound Vib. 305 (2007) 432-456; the
linearized state-dependent delay as in X. Liu, N. Vlajic, X. Long, G. Meng and
B. Balachandran, "Coupled axial-torsional dynamics in rotary drilling with
state-dependent delay: stability and control", Nonlinear Dyn. 78 (2014) 1891-1906, and
U. J. F. Aarsnes and N. van de Wouw, "Axial and torsional self-excited vibrations of a
distributed drill-string", J. Sound Vib. 444 (2019) 127-151.

Examples
--------
>>> from torsio.model.axial_assembly import axial_model, pipe_string, tube_section
>>> from torsio.model.axial_assembly import rgd_two_dof_example
>>> from torsio.axial.rgd import rgd_example
>>> from torsio.model.discretize import StrategyC
>>> system = drilling_linearization(rgd_two_dof_example(), rgd_example(), 100e3, 60.0)
>>> round(system.delay, 6)  # t_n0 = 2π/(n Ω₀), s
0.25
>>> abs(system.characteristic(0.0)), system.neutral_roots  # the neutral root
(0.0, (0j,))
>>> string = pipe_string([tube_section(900.0, 2.1e11, 8.1e10, 7850.0, 3.4e-3, 1.5e-5)], 3e4, 230.0)
>>> chain = axial_model(string, StrategyC(dp_elements=3), hook="speed")
>>> system = drilling_linearization(chain, rgd_example(), 100e3, 60.0)
>>> system.dofs, system.neutral_roots  # 3 axial and 3 torsional DOFs, the hook pins u
(6, ())
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from torsio.axial.delay_roots import LinearDelaySystem
from torsio.axial.rgd import RGDBit
from torsio.axial.steady import SteadyDrilling, steady_drilling
from torsio.axial.steady_friction import drilling_state, friction_damping
from torsio.errors import ConfigError
from torsio.model.axial_assembly import is_two_dof, require_axial
from torsio.model.lumped import LumpedModel, chain_matrix


def _positive(key: str, value: float, what: str) -> float:
    if not (math.isfinite(value) and value > 0):
        raise ConfigError(key, f"{value!r} must be > 0 ({what})")
    return float(value)


def delayed_matrix(bit: RGDBit, steady: SteadyDrilling) -> np.ndarray:
    """D of the linearized bit forces: (δW, δT) = D (x_b(t) − x_b(t − t_n0)), x_b = (u_b, φ_b)
    the bit's axial displacement and angle.

    Rows: weight [N] and torque [N m]; columns: per metre of u_b and per radian of φ_b.
    """
    ratio = steady.rop / steady.bit_speed  # V₀ / Ω₀ = d₀ / 2π, m/rad
    n = bit.blades
    weight, torque = bit.cutting_weight_per_depth, bit.cutting_torque_per_depth
    return n * np.array([[weight, -weight * ratio], [torque, -torque * ratio]])


def two_dof_parameters(assembly: LumpedModel) -> tuple[float, float, float, float]:
    """(I [kg m²], k [N m/rad], M [kg], c [N m s/rad]) of a 2-DOF assembly
    (:func:`~torsio.model.axial_assembly.two_dof_assembly`: one node under the weight hook), for
    the characteristic equation written out (:func:`characteristic_function`).

    Raises
    ------
    ConfigError
        An assembly of more than one node, or with the speed hook.
    """
    axial = require_axial(assembly)
    if not is_two_dof(assembly):
        raise ConfigError(
            "assembly",
            f"{assembly.dofs} node(s) with the {axial.hook!r} hook: Δ(λ) is written out "
            "for the 2-DOF model only (one node under the weight hook); "
            "drilling_linearization(...).characteristic is that of any assembly",
        )
    return (
        assembly.bit_inertia,
        float(assembly.springs[0]),
        axial.bit_mass,
        float(assembly.dampers[0]),
    )


def axial_matrices(assembly: LumpedModel) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(M [kg], C [N s/m], K [N/m]) of the axial DOFs u_0 .. u_m−1 about steady drilling.

    Spring and damper i join node i − 1 to node i (:mod:`torsio.model.axial_assembly`): under
    the hook speed k_a,0 and c_a,0 join node 0 to the hook (the ground of the
    perturbation); under the hook weight node 0 has none (the weight is constant); with no
    axial springs the string is one rigid body of mass Σ m_i (K = C = 0).
    """
    axial = require_axial(assembly)
    if not axial.stiffnesses.size:
        return np.array([[axial.bit_mass]]), np.zeros((1, 1)), np.zeros((1, 1))
    springs = np.array(axial.stiffnesses, dtype=float)
    dampers = np.array(axial.dampings, dtype=float)
    if axial.hook == "weight":
        springs[0] = dampers[0] = 0.0
    return np.diag(axial.masses), chain_matrix(dampers), chain_matrix(springs)


def chain_matrices(assembly: LumpedModel) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(M, C, K) of x = (u_0 .. u_m−1 [m], φ_0 .. φ_n−1 [rad]) about steady drilling: the
    axial block of :func:`axial_matrices`, then the torsional chain, its spring and damper 0
    to the top drive (held at Ω₀ t: the ground of the perturbation). SI units of the DOFs.

    Examples
    --------
    >>> from torsio.model.axial_assembly import two_dof_assembly
    >>> mass, damping, stiffness = chain_matrices(two_dof_assembly(455.65, 324.857, 3e4, 19.49))
    >>> np.diag(mass).tolist(), np.diag(damping).tolist(), np.diag(stiffness).tolist()
    ([30000.0, 455.65], [0.0, 19.49], [0.0, 324.857])
    """
    axial_mass, axial_damping, axial_stiffness = axial_matrices(assembly)
    damping = np.zeros_like(assembly.stiffness) if assembly.damping is None else assembly.damping
    return (
        _block_diagonal(axial_mass, assembly.inertia),
        _block_diagonal(axial_damping, damping),
        _block_diagonal(axial_stiffness, assembly.stiffness),
    )


def _block_diagonal(first: np.ndarray, second: np.ndarray) -> np.ndarray:
    size = first.shape[0]
    matrix = np.zeros((size + second.shape[0],) * 2)
    matrix[:size, :size] = first
    matrix[size:, size:] = second
    return matrix


def speed_loop(boundary: Any, torque: float, speed: float) -> tuple[float, float, float] | None:
    """(J [kg m²], kp + drag [N m s/rad], ki [N m/rad]) of a top drive whose small motions
    about steady drilling are a node of its own: a PI speed loop (``pi``, ``soft-torque``:
    one state z = ∫e dt, so δz = −φ_top and J φ_top'' = −(kp + drag) φ_top' − ki φ_top −
    δT_pipe) with ki > 0, unsaturated at the steady motor torque ``torque`` + drag ``speed``
    [N m]. None for a held top (no node) and for any other controller (its states are not
    of this second-order form: the linearization then holds the top)."""
    if boundary is None or boundary.held or boundary.states != 1:
        return None
    a, b = np.asarray(boundary.a, float).ravel(), np.asarray(boundary.b, float).ravel()
    d, ki = np.asarray(boundary.d, float).ravel(), float(np.asarray(boundary.c).ravel()[0])
    pi_form = a[0] == 0.0 and b[0] == 1.0 and b[1] == 0.0 and d[1] == 0.0 and ki > 0.0
    unsaturated = abs(torque + boundary.drag * speed) < boundary.max_torque
    if not (pi_form and unsaturated):
        return None
    return float(boundary.inertia), float(d[0] + boundary.drag), ki


def friction_damping_matrix(
    assembly: LumpedModel, contacts: Any, rop: float, speed: float, angles_from: int
) -> np.ndarray:
    """The contacts' damping in x = (u .., φ ..) [SI of the DOFs]: each node's
    :func:`~torsio.axial.steady_friction.friction_damping` at V₀ = ``rop`` [m/s] and
    Ω₀ = ``speed`` [rad/s] on (u_i, φ_i), φ_i at ``angles_from`` + i."""
    size = angles_from + assembly.dofs
    matrix = np.zeros((size, size))
    blocks = friction_damping(contacts, rop, speed)
    for i in range(assembly.dofs):
        r = contacts.radius[i]
        dofs = [i, angles_from + i]
        scale = np.array([1.0, r])
        matrix[np.ix_(dofs, dofs)] += blocks[i] * np.outer(scale, scale)
    return matrix


def drilling_linearization(
    assembly: LumpedModel,
    bit: RGDBit,
    wob: float,
    rpm: float,
    top_drive: Any = None,
    contacts: Any = None,
) -> LinearDelaySystem:
    """Steady drilling of ``assembly`` linearized about its steady state (module docstring).

    x = (u_0 .. u_m−1 [m], φ_0 .. φ_n−1 [rad]): the m axial DOFs
    (:attr:`~torsio.model.axial_rows.AxialRows.dofs`), then the n angles; the
    bit's are the last of each. For the 2-DOF model x = (u, φ).

    Parameters
    ----------
    assembly : LumpedModel
        Any lumped chain with axial rows, both hooks (:mod:`torsio.model.axial_assembly`).
    bit : RGDBit
        The bit law.
    wob : float
        W₀ [N], the weight on bit of steady drilling (the hook weight, or what the hook
        speed V₀ gives).
    rpm : float
        Ω₀ [rev/min], the speed of the top drive and, steadily, of every node.
    top_drive : TopDriveBoundary, optional
        The top's boundary (:func:`torsio.physics.axial_top_drive.top_boundary`): a PI speed loop
        (:func:`speed_loop`) adds the top node φ_top first among the angles, x = (u ..,
        φ_top, φ_0 ..); any other (or None) holds the top at Ω₀.

    Raises
    ------
    ConfigError
        A weight on bit at which the bit does not cut.
    """
    axial = require_axial(assembly)
    steady, friction = drilling_state(bit, wob, rpm, contacts, axial.hook)
    surface = steady.bit_torque if friction is None else friction.surface_torque
    mass, damping, stiffness = chain_matrices(assembly)
    loop = speed_loop(top_drive, surface, steady.bit_speed)
    if loop is not None:  # the top node φ_top first among the angles
        inertia, loop_damping, loop_stiffness = loop
        axial_mass, axial_damping, axial_stiffness = axial_matrices(assembly)
        mass = _block_diagonal(axial_mass, np.diag([inertia, *assembly.node_inertias]))
        damping = _block_diagonal(
            axial_damping, chain_matrix(np.array([loop_damping, *assembly.dampers]))
        )
        stiffness = _block_diagonal(
            axial_stiffness, chain_matrix(np.array([loop_stiffness, *assembly.springs]))
        )
    if contacts is not None:
        angles_from = mass.shape[0] - assembly.dofs
        damping = damping + friction_damping_matrix(
            assembly, contacts.at_wob(wob), steady.rop, steady.bit_speed, angles_from
        )
    bit_dofs = [axial.dofs - 1, mass.shape[0] - 1]
    delayed = np.zeros_like(mass)
    delayed[np.ix_(bit_dofs, bit_dofs)] = delayed_matrix(bit, steady)
    return LinearDelaySystem(
        mass=mass,
        damping=damping,
        stiffness=stiffness,
        delayed=delayed,
        delay=steady.delay,
        neutral_roots=(0.0,) if axial.hook == "weight" else (),
    )


def characteristic_function(
    assembly: LumpedModel, bit: RGDBit, wob: float, rpm: float
) -> Callable[[complex], complex]:
    """Δ(λ) of the module docstring, written out (a check on the matrix form).

    Examples
    --------
    >>> from torsio.model.axial_assembly import rgd_two_dof_example
    >>> from torsio.axial.rgd import rgd_example
    >>> delta = characteristic_function(rgd_two_dof_example(), rgd_example(), 100e3, 60.0)
    >>> delta(0.0)
    0j
    """
    inertia, stiffness, mass, damping = two_dof_parameters(assembly)
    steady = steady_drilling(bit, wob, rpm)
    ratio = steady.rop / steady.bit_speed
    n, tau = bit.blades, steady.delay
    axial = n * bit.cutting_weight_per_depth
    coupling = n * bit.cutting_torque_per_depth * ratio * mass

    def delta(root: complex) -> complex:
        lam = complex(root)
        e = 1 - np.exp(-lam * tau)
        torsional = inertia * lam**2 + damping * lam + stiffness
        return complex((mass * lam**2 + axial * e) * torsional - coupling * lam**2 * e)

    return delta


def axial_linearization(bit: RGDBit, mass: float, wob: float, rpm: float) -> LinearDelaySystem:
    """The axial equation alone, the bit turning at exactly Ω₀ (the limit k → ∞).

    M u'' + n ζ ε a (u(t) − u(t − t_n0)) = 0, characteristic M λ² + n ζ ε a E(λ) = 0
    (Richard et al. 2004): on the imaginary axis λ = iω only where ω t_n0 = (2j + 1) π and
    M ω² = 2 n ζ ε a.

    Examples
    --------
    >>> from torsio.axial.rgd import rgd_example
    >>> axial_linearization(rgd_example(), 29981.3, 100e3, 60.0).dofs
    1
    """
    mass = _positive("mass", mass, "the axial mass M [kg]")
    steady = steady_drilling(bit, wob, rpm)
    return LinearDelaySystem(
        mass=[[mass]],
        damping=[[0.0]],
        stiffness=[[0.0]],
        delayed=[[bit.blades * bit.cutting_weight_per_depth]],
        delay=steady.delay,
        neutral_roots=(0.0,),
    )
