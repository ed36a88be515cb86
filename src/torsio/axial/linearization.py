"""The 2-DOF RGD drilling model linearized about steady drilling, with its delay.

The model of Richard, Germay and Detournay (2007): the bit assembly, of axial mass M and
torsional inertia I, is pushed down by the constant weight W₀ (the axial stiffness of the
string neglected) and turned through a torsional spring k (and a damper c in parallel)
whose top turns at Ω₀:

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

λ = 0 is always a root (E(0) = 0): a shift of the bit's axial position, u = const, is a
steady motion too, since the depth of cut reads only differences of U. It is neutral, not
a mode.

References: Richard, Germay and Detournay, J. Sound Vib. 305 (2007) 432-456; the
linearized state-dependent delay as in X. Liu, N. Vlajic, X. Long, G. Meng and
B. Balachandran, "Coupled axial-torsional dynamics in rotary drilling with
state-dependent delay: stability and control", Nonlinear Dyn. 78 (2014) 1891-1906, and
U. J. F. Aarsnes and N. van de Wouw, "Axial and torsional self-excited vibrations of a
distributed drill-string", J. Sound Vib. 444 (2019) 127-151.

Examples
--------
>>> from torsio.axial.assembly import rgd_two_dof_example
>>> from torsio.axial.rgd import rgd_example
>>> system = drilling_linearization(rgd_two_dof_example(), rgd_example(), 100e3, 60.0)
>>> round(system.delay, 6)  # t_n0 = 2π/(n Ω₀), s
0.25
>>> abs(system.characteristic(0.0))  # the neutral root
0.0
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from torsio.axial.assembly import DrillingAssembly
from torsio.axial.delay_roots import LinearDelaySystem
from torsio.axial.rgd import RGDBit
from torsio.axial.steady import SteadyDrilling, steady_drilling
from torsio.errors import ConfigError


def _positive(key: str, value: float, what: str) -> float:
    if not (math.isfinite(value) and value > 0):
        raise ConfigError(key, f"{value!r} must be > 0 ({what})")
    return float(value)


def delayed_matrix(bit: RGDBit, steady: SteadyDrilling) -> np.ndarray:
    """D of the linearized bit forces: (δW, δT) = D (x(t) − x(t − t_n0)), x = (u, φ).

    Rows: weight [N] and torque [N m]; columns: per metre of u and per radian of φ.
    """
    ratio = steady.rop / steady.bit_speed  # V₀ / Ω₀ = d₀ / 2π, m/rad
    n = bit.blades
    weight, torque = bit.cutting_weight_per_depth, bit.cutting_torque_per_depth
    return n * np.array([[weight, -weight * ratio], [torque, -torque * ratio]])


def two_dof_parameters(assembly: DrillingAssembly) -> tuple[float, float, float, float]:
    """(I [kg m²], k [N m/rad], M [kg], c [N m s/rad]) of a 2-DOF assembly
    (:func:`~torsio.axial.assembly.two_dof_assembly`: one node under the weight hook).

    Raises
    ------
    ConfigError
        An assembly of more than one node, or with the speed hook.
    """
    if not assembly.is_two_dof:
        raise ConfigError(
            "assembly",
            f"{assembly.nodes} node(s) with the {assembly.hook!r} hook: the linearization is "
            "of the 2-DOF model only (one node under the weight hook)",
        )
    return (
        float(assembly.inertias[0]),
        float(assembly.stiffnesses[0]),
        assembly.bit_mass,
        float(assembly.damping[0]),
    )


def drilling_linearization(
    assembly: DrillingAssembly, bit: RGDBit, wob: float, rpm: float
) -> LinearDelaySystem:
    """The 2-DOF RGD model linearized about steady drilling, x = (u [m], φ [rad]).

    Parameters
    ----------
    assembly : DrillingAssembly
        The 2-DOF assembly (:func:`~torsio.axial.assembly.two_dof_assembly`): the
        torsional inertia I [kg m²] and axial mass M [kg] of the bit assembly, the
        torsional stiffness k [N m/rad] of the string to the top drive and a viscous
        damper c [N m s/rad] in parallel with it.
    bit : RGDBit
        The bit law.
    wob : float
        W₀ [N], the constant weight on top of the bit assembly.
    rpm : float
        Ω₀ [rev/min], the speed of the top drive and, steadily, of the bit.

    Raises
    ------
    ConfigError
        An assembly that is not 2-DOF, or a weight on bit at which the bit does not cut.
    """
    inertia, stiffness, mass, damping = two_dof_parameters(assembly)
    steady = steady_drilling(bit, wob, rpm)
    return LinearDelaySystem(
        mass=np.diag([mass, inertia]),
        damping=np.diag([0.0, damping]),
        stiffness=np.diag([0.0, stiffness]),
        delayed=delayed_matrix(bit, steady),
        delay=steady.delay,
    )


def characteristic_function(
    assembly: DrillingAssembly, bit: RGDBit, wob: float, rpm: float
) -> Callable[[complex], complex]:
    """Δ(λ) of the module docstring, written out (a check on the matrix form).

    Examples
    --------
    >>> from torsio.axial.assembly import rgd_two_dof_example
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
    )
