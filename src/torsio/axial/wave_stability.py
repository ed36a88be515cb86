"""Linear stability of steady drilling with the distributed pipe: its exact characteristic
equation.

The pipe's sections are exact wave lines; at the bottom the rigid BHA (m_b, I_b) carries
the RGD bit, whose linearized forces are D (x_b(t) − x_b(t − t_n0)) with x_b = (u_b, φ_b)
(:func:`~torsio.axial.linearization.delayed_matrix`, the same as the lumped chain's). For
a motion x_b e^{λt} each line is solved exactly from the top's boundary down to the bit:
its end stiffness Z(λ), the force the pipe puts on the BHA per unit displacement of its
bottom end, is N/U at the bottom of the transfer matrices of the sections

    [U, N](x + L) = [[cosh γL, sinh γL / (R γ)], [R γ sinh γL, cosh γL]] [U, N](x),
    γ = λ / c,

R = E A and c = √(E/ρ) axially, R = G J and c = √(G/ρ) torsionally, started at the top from
(U, N) = (0, 1) where it is held and (1, 0) where it is free. The characteristic function is

    Δ(λ) = det( diag(m_b λ² + Z_a(λ), I_b λ² + Z_t(λ)) + (1 − e^{−λ t_n0}) D ),

with the axial top free under the weight hook (then Z_a(0) = 0 and λ = 0 is the neutral
root, a shift of the whole string, deflated), held under the speed hook; the torsional
top held at the set speed. Δ is entire in λ; its roots are found by Newton (the derivative
by a central difference in the complex plane) started from the rightmost roots of a lumped
twin of the pipe (:func:`~torsio.axial.stability.drilling_stability`), whose low roots
approach the continuum's like Δx² as its elements shrink. In the static limit Z_a → E A / L
(top held) or ρ A L λ² (top free: the pipe moving as a body), Z_t → G J / L.

Examples
--------
At a slow motion the pipe held at the top is the static spring E A / L:

>>> z = end_stiffness(1e-6j, [2.1e11 * 3.4e-3], [1000.0], [5172.2], free_top=False)
>>> round(z.real / (2.1e11 * 3.4e-3 / 1000.0), 9)
1.0

The built-in distributed pipe at 100 kN and 60 rpm grows at 3.218 1/s (its 10-node twin:
3.223 1/s):

>>> from torsio.examples import rgd_wave_pipe_config
>>> axial = rgd_wave_pipe_config().axial
>>> result = distributed_stability(axial.assembly, axial.bit, 100e3, 60.0,
...                                twin=axial.stability_assembly)
>>> round(result.growth_rate, 3), round(float(result.twin_roots[0].real), 3)
(3.218, 3.223)
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np
from numpy.typing import ArrayLike, NDArray

from torsio.axial.delay_roots import newton_root
from torsio.axial.linearization import delayed_matrix
from torsio.axial.rgd import RGDBit
from torsio.axial.stability import drilling_stability
from torsio.axial.steady import SteadyDrilling, steady_drilling
from torsio.errors import SolverError
from torsio.model.axial_assembly import pipe_rows
from torsio.model.axial_rows import PipeAxialRows
from torsio.model.lumped import LumpedModel
from torsio.model.wave import WaveModel

__all__ = ["DistributedStability", "distributed_stability", "end_stiffness", "WaveCharacteristic"]

ROOT_TOLERANCE = 1e-12
"""Newton stops when its step is below this times max(1, |λ|)."""


def end_stiffness(
    root: complex,
    rigidities: ArrayLike,
    lengths: ArrayLike,
    wave_speeds: ArrayLike,
    *,
    free_top: bool,
) -> complex:
    """Z(λ) = N/U at the bottom of a stepped line [N/m or N m/rad] (the module docstring).

    ``rigidities`` E A or G J [N or N m²], ``lengths`` [m], ``wave_speeds`` [m/s], from the
    top down; the top held, or free with ``free_top``.
    """
    lam = complex(root)
    u, n = (1.0 + 0j, 0j) if free_top else (0j, 1.0 + 0j)
    for rigidity, length, speed in zip(
        np.asarray(rigidities, float),
        np.asarray(lengths, float),
        np.asarray(wave_speeds, float),
        strict=True,
    ):
        gamma_l = lam * length / speed
        stiffness = rigidity / length  # R γ sinh(γL)/(γL) · γL  with the limits kept exact
        cosh = np.cosh(gamma_l)
        sinhc = np.sinh(gamma_l) / gamma_l if gamma_l != 0 else 1.0
        u, n = cosh * u + sinhc * n / stiffness, stiffness * gamma_l**2 * sinhc * u + cosh * n
    return complex(n / u)


@attrs.frozen(eq=False)
class WaveCharacteristic:
    """Δ(λ) of steady drilling with a distributed pipe (the module docstring)."""

    assembly: WaveModel
    delayed: NDArray[np.float64]
    delay: float

    @property
    def rows(self) -> PipeAxialRows:
        """The pipe's axial rows."""
        return pipe_rows(self.assembly)

    @property
    def neutral_roots(self) -> tuple[complex, ...]:
        """(0,) under the weight hook, else none."""
        return (0j,) if self.rows.hook == "weight" else ()

    def end_stiffnesses(self, root: complex) -> tuple[complex, complex]:
        """(Z_a(λ) [N/m], Z_t(λ) [N m/rad]) of the pipe at the BHA: E A = Z c and
        G J = Z c of each section."""
        a, rows = self.assembly, self.rows
        axial = end_stiffness(root, rows.rigidities, a.lengths, rows.wave_speeds,
                              free_top=rows.hook == "weight")  # fmt: skip
        torsional = end_stiffness(root, a.impedances * a.wave_speeds, a.lengths, a.wave_speeds,
                                  free_top=False)  # fmt: skip
        return axial, torsional

    def matrix(self, root: complex) -> NDArray[np.complex128]:
        """The 2 × 2 matrix whose determinant is Δ(λ), rows (weight, torque)."""
        lam = complex(root)
        axial, torsional = self.end_stiffnesses(lam)
        mass, inertia = self.rows.bha_mass, self.assembly.bit_inertia
        body = np.diag([mass * lam**2 + axial, inertia * lam**2 + torsional])
        return body + (1 - np.exp(-lam * self.delay)) * self.delayed

    def value(self, root: complex) -> complex:
        """Δ(λ)."""
        return complex(np.linalg.det(self.matrix(root)))

    def relative_residual(self, root: complex) -> float:
        """|Δ(λ)| over Hadamard's bound on the matrix of term magnitudes (as
        :meth:`~torsio.axial.delay_roots.LinearDelaySystem.relative_residual`): 0 at a
        root, at most 1."""
        lam = complex(root)
        axial, torsional = self.end_stiffnesses(lam)
        mass, inertia = self.rows.bha_mass, self.assembly.bit_inertia
        size = abs(lam) ** 2
        terms = np.diag([mass * size + abs(axial), inertia * size + abs(torsional)])
        terms = terms + abs(1 - np.exp(-lam * self.delay)) * np.abs(self.delayed)
        return float(abs(self.value(lam)) / np.prod(np.linalg.norm(terms, axis=1)))

    def refine(self, start: complex) -> complex:
        """Newton on Δ(λ)/Π(λ − r) (r the neutral roots) from ``start``
        (:func:`~torsio.axial.delay_roots.newton_root`, Δ' by a central difference).

        Raises
        ------
        SolverError
            If it does not converge in 60 steps.
        """

        def logarithmic(lam: complex) -> complex | None:
            value = self.value(lam)
            if value == 0:
                return None
            h = 1e-6 * max(1.0, abs(lam))
            return (self.value(lam + h) - self.value(lam - h)) / (2 * h * value)

        return newton_root(logarithmic, start, self.neutral_roots, ROOT_TOLERANCE)


def wave_characteristic(
    assembly: WaveModel, bit: RGDBit, wob: float, rpm: float
) -> WaveCharacteristic:
    """Δ(λ) of ``assembly`` drilling steadily at ``wob`` [N] and ``rpm`` [rev/min]."""
    steady = steady_drilling(bit, wob, rpm)
    delay = 2 * math.pi / (bit.blades * steady.bit_speed)
    return WaveCharacteristic(assembly, delayed_matrix(bit, steady), delay)


@attrs.frozen(eq=False)
class DistributedStability:
    """Linear stability of steady drilling with the distributed pipe.

    Attributes
    ----------
    steady : SteadyDrilling
        The state linearized about.
    roots : ndarray of complex
        The continuum's roots λ [1/s] (Im >= 0) refined from the twin's, largest real part
        first, the neutral root left out.
    twin_roots : ndarray of complex
        The lumped twin's roots they started from (same order).
    residuals : ndarray of float
        :meth:`WaveCharacteristic.relative_residual` at each root.
    growth_rate : float
        max Re λ [1/s].
    stable : bool
        Whether the growth rate is negative.
    """

    steady: SteadyDrilling
    roots: NDArray[np.complex128]
    twin_roots: NDArray[np.complex128]
    residuals: NDArray[np.float64]
    growth_rate: float
    stable: bool

    def to_dict(self) -> dict[str, Any]:
        """Plain data for JSON: roots as ``[real, imag]`` pairs."""
        return {
            "growth_rate": self.growth_rate,
            "stable": self.stable,
            "roots": [[r.real, r.imag] for r in self.roots],
            "twin_roots": [[r.real, r.imag] for r in self.twin_roots],
        }


def distributed_stability(
    assembly: WaveModel,
    bit: RGDBit,
    wob: float,
    rpm: float,
    *,
    twin: LumpedModel,
    count: int = 6,
) -> DistributedStability:
    """The rightmost roots of the distributed pipe's Δ(λ) by Newton from the ``count``
    rightmost of its lumped ``twin`` (the same sections in elements; e.g. the
    configuration's :attr:`~torsio.config.axial.AxialConfig.stability_assembly`).

    A start is kept when Newton reaches a root within half the distance to the nearest
    other start (its own root, not a neighbour's); the twin's high modes, far from the
    continuum's, may be dropped so (``twin_roots`` has the kept ones).

    Raises
    ------
    SolverError
        If no start is kept (the twin too coarse: give it shorter elements).
    """
    characteristic = wave_characteristic(assembly, bit, wob, rpm)
    starts = drilling_stability(twin, bit, wob, rpm, count=count).roots
    kept, found = [], []
    for i, start in enumerate(starts):
        others = [abs(start - other) for j, other in enumerate(starts) if j != i]
        reach = 0.5 * min(others) if others else abs(start)
        try:
            root = _upper(characteristic.refine(start))
        except SolverError:
            continue
        if abs(root - start) <= reach:  # its own root, not a neighbour's
            kept.append(complex(start))
            found.append(root)
    if not found:
        raise SolverError(
            f"no root of the lumped twin ({twin.dofs} nodes) refines to a root of the "
            "distributed pipe near it; give the twin shorter elements"
        )
    order = np.argsort([-r.real for r in found], kind="stable")
    chosen = np.array([found[i] for i in order], dtype=complex)
    growth = float(chosen[0].real)
    return DistributedStability(
        steady=steady_drilling(bit, wob, rpm),
        roots=chosen,
        twin_roots=np.array([kept[i] for i in order], dtype=complex),
        residuals=np.array([characteristic.relative_residual(r) for r in chosen]),
        growth_rate=growth,
        stable=growth < 0,
    )


def _upper(root: complex) -> complex:
    return root.conjugate() if root.imag < 0 else root
