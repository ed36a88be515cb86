"""Characteristic roots of a linear second-order system with one delay.

The system is

    M x''(t) + C x'(t) + K x(t) + D (x(t) − x(t − τ)) = 0,

whose solutions x = x̂ e^{λt} need det Λ(λ) = 0 with the characteristic matrix

    Λ(λ) = λ² M + λ C + K + (1 − e^{−λτ}) D.

Its rightmost roots are found in two steps (Breda, Maset and Vermiglio 2005):

1. **Pseudospectral collocation.** The delay system is the abstract ODE y' = 𝒜 y on the
   state y(0) = (x, x')(0) and the history of the delayed coordinates z = Vᵀ x, D = U S Vᵀ
   of rank r (the drilling systems' D has rank 1: the bit's depth of cut). The history is
   discretized on the N + 1 Chebyshev points θ_j = τ (cos(jπ/N) − 1)/2 of [−τ, 0]: at
   θ_1..θ_N the derivative of the interpolating polynomial of z (z(θ_0) = Vᵀ x(0)), at
   θ_0 = 0 the equation of motion y'(0) = A₀ y(0) + B z(−τ). The 2m + N r eigenvalues of
   this matrix approximate the roots of smallest modulus with spectral accuracy (the full
   state's history, (N + 1)·2m unknowns, has the same roots).
2. **Newton on det Λ(λ)**, started from each collocation eigenvalue, with the logarithmic
   derivative Δ'/Δ = tr(Λ⁻¹ Λ') (Jacobi's formula). The roots every parameter has, the
   system's ``neutral_roots`` (λ = 0 of the drilling system under a hook weight: a shift
   of the axial position), are deflated: Newton runs on det Λ(λ) / λ, so they are never
   reported.

Reference: D. Breda, S. Maset and R. Vermiglio, "Pseudospectral differencing methods for
characteristic roots of delay differential equations", SIAM J. Sci. Comput. 27 (2005)
482-495; the Chebyshev differentiation matrix of L. N. Trefethen, *Spectral methods in
MATLAB*, SIAM (2000), ch. 6.

Examples
--------
With no delayed term, a 1-DOF oscillator has the roots of λ² + 0.2 λ + 4 = 0,
λ = −0.1 ± i √3.99:

>>> system = LinearDelaySystem([[1.0]], [[0.2]], [[4.0]], [[0.0]], delay=0.5)
>>> roots = rightmost_roots(system, count=1, deflate=()).roots
>>> complex(round(roots[0].real, 12), round(roots[0].imag, 12))
(-0.1+1.997498435544j)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import attrs
import numpy as np
import scipy.linalg
from numpy.typing import ArrayLike, NDArray

from torsio.errors import SolverError

DEFAULT_ORDER = 32
"""Smallest default collocation order N (N + 1 Chebyshev points on [−τ, 0])."""

MAX_DEFAULT_ORDER = 256
"""Largest default collocation order (a matrix of 2m + 256 r rows)."""

RANK_TOLERANCE = 1e-12
"""Singular values of D below this fraction of the largest are zero (its rank r)."""


def _square(value: ArrayLike) -> NDArray[np.float64]:
    matrix = np.atleast_2d(np.asarray(value, dtype=float))
    if matrix.shape[0] != matrix.shape[1]:
        raise ValueError(f"expected a square matrix, got shape {matrix.shape}")
    return matrix


def _roots(values: Sequence[complex]) -> tuple[complex, ...]:
    return tuple(complex(value) for value in values)


@attrs.frozen(eq=False)
class LinearDelaySystem:
    """M x'' + C x' + K x + D (x(t) − x(t − τ)) = 0, matrices in SI units of the DOFs.

    Parameters
    ----------
    mass, damping, stiffness, delayed : array_like
        M (invertible), C, K and D, all m × m.
    delay : float
        τ > 0 [s].
    neutral_roots : sequence of complex
        Roots of Δ(λ) for every parameter [1/s]: steady motions, not modes (default none).
        :func:`rightmost_roots` deflates them.
    """

    mass: NDArray[np.float64] = attrs.field(converter=_square)
    damping: NDArray[np.float64] = attrs.field(converter=_square)
    stiffness: NDArray[np.float64] = attrs.field(converter=_square)
    delayed: NDArray[np.float64] = attrs.field(converter=_square)
    delay: float = attrs.field(converter=float)
    neutral_roots: tuple[complex, ...] = attrs.field(default=(), converter=_roots)

    def __attrs_post_init__(self) -> None:
        shapes = {m.shape for m in (self.mass, self.damping, self.stiffness, self.delayed)}
        if len(shapes) != 1:
            raise ValueError(f"M, C, K and D must have one shape, got {sorted(shapes)}")
        if not self.delay > 0:
            raise ValueError(f"delay {self.delay!r} must be > 0 s")

    @property
    def dofs(self) -> int:
        """m, the number of degrees of freedom."""
        return int(self.mass.shape[0])

    def characteristic_matrix(self, root: complex) -> NDArray[np.complex128]:
        """Λ(λ) = λ² M + λ C + K + (1 − e^{−λτ}) D."""
        lam = complex(root)
        return (
            lam**2 * self.mass
            + lam * self.damping
            + self.stiffness
            + (1 - np.exp(-lam * self.delay)) * self.delayed
        )

    def characteristic_derivative(self, root: complex) -> NDArray[np.complex128]:
        """Λ'(λ) = 2λ M + C + τ e^{−λτ} D."""
        lam = complex(root)
        return (
            2 * lam * self.mass
            + self.damping
            + self.delay * np.exp(-lam * self.delay) * (self.delayed)
        )

    def characteristic(self, root: complex) -> complex:
        """Δ(λ) = det Λ(λ)."""
        return complex(np.linalg.det(self.characteristic_matrix(root)))

    def characteristic_slope(self, root: complex) -> complex:
        """Δ'(λ) = tr(adj Λ(λ) Λ'(λ)) (Jacobi's formula; also where Λ is singular)."""
        matrix = self.characteristic_matrix(root)
        return complex(np.trace(_adjugate(matrix) @ self.characteristic_derivative(root)))

    def logarithmic_derivative(self, root: complex) -> complex:
        """Δ'(λ)/Δ(λ) = tr(Λ(λ)⁻¹ Λ'(λ)) [s], without forming Δ (which over- or
        underflows for many DOFs). Raises numpy's LinAlgError where Λ is singular."""
        matrix = self.characteristic_matrix(root)
        return complex(np.trace(np.linalg.solve(matrix, self.characteristic_derivative(root))))

    def relative_residual(self, root: complex) -> float:
        """|Δ(λ)| relative to its scale: 0 at a root, at most 1.

        The scale is Hadamard's bound Π_i ‖row_i S‖ on the matrix of term magnitudes
        S = |λ|² |M| + |λ| |C| + |K| + |1 − e^{−λτ}| |D| (entrywise), which bounds |Δ(λ)|
        and does not vanish where the terms of Λ(λ) cancel. Both are taken as logarithms
        (many DOFs would overflow them).
        """
        lam = complex(root)
        magnitudes = (
            abs(lam) ** 2 * np.abs(self.mass)
            + abs(lam) * np.abs(self.damping)
            + np.abs(self.stiffness)
            + abs(1 - np.exp(-lam * self.delay)) * np.abs(self.delayed)
        )
        rows = np.linalg.norm(magnitudes, axis=1)
        if not np.all(rows > 0):
            return 0.0
        sign, log_value = np.linalg.slogdet(self.characteristic_matrix(lam))
        if sign == 0:
            return 0.0
        return float(np.exp(log_value - np.sum(np.log(rows))))

    def first_order(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """A₀, A₁ of y' = A₀ y(t) + A₁ y(t − τ), y = (x, x')."""
        m = self.dofs
        inverse = np.linalg.inv(self.mass)
        a0 = np.zeros((2 * m, 2 * m))
        a0[:m, m:] = np.eye(m)
        a0[m:, :m] = -inverse @ (self.stiffness + self.delayed)
        a0[m:, m:] = -inverse @ self.damping
        a1 = np.zeros((2 * m, 2 * m))
        a1[m:, :m] = inverse @ self.delayed
        return a0, a1

    def frequency_scale(self) -> float:
        """ρ [1/s]: the largest |eigenvalue| of A₀ + s A₁ for e^{−λτ} = s ∈ {0, 1, −1}.

        The rightmost roots lie near these frequencies; the default collocation order
        resolves |λ| up to 1.5 ρ.
        """
        a0, a1 = self.first_order()
        return max(float(np.max(np.abs(np.linalg.eigvals(a0 + s * a1)))) for s in (0, 1, -1))

    def default_order(self) -> int:
        """N = max(32, ⌈3 ρ τ⌉), at most 256: the candidates |λ| τ < N/2 then reach
        |λ| = 1.5 ρ (with the cap, |λ| = 128/τ: give ``order`` to go further)."""
        wanted = math.ceil(3 * self.frequency_scale() * self.delay)
        return min(MAX_DEFAULT_ORDER, max(DEFAULT_ORDER, wanted))

    def delayed_coordinates(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(U S, V) of D = (U S) Vᵀ, rank r: the coordinates z = Vᵀ x whose past enters
        the equation, and how (m × r each; r = 0 without delay terms)."""
        left, values, right = np.linalg.svd(self.delayed)
        rank = int(np.sum(values > RANK_TOLERANCE * values[0])) if values[0] > 0 else 0
        return left[:, :rank] * values[:rank], right[:rank].T

    def collocation_matrix(self, order: int = DEFAULT_ORDER) -> NDArray[np.float64]:
        """The (2m + N r) square pseudospectral discretization of the generator 𝒜: the
        state y(0) = (x, x')(0), then the delayed coordinates z at θ_1 .. θ_N (the module
        docstring)."""
        if order < 2:
            raise ValueError(f"collocation order {order!r} must be >= 2")
        a0, _ = self.first_order()
        weights, coordinates = self.delayed_coordinates()
        m, r = self.dofs, weights.shape[1]
        size = 2 * m
        derivative = chebyshev_differentiation(order) * (2.0 / self.delay)
        generator = np.zeros((size + order * r, size + order * r))
        generator[:size, :size] = a0
        generator[m:size, size + (order - 1) * r :] = np.linalg.solve(self.mass, weights)
        history = generator[size:, :]
        history[:, :m] = np.kron(derivative[1:, :1], coordinates.T)  # z(θ_0) = Vᵀ x(0)
        history[:, size:] = np.kron(derivative[1:, 1:], np.eye(r))
        return generator

    def collocation_eigenvalues(self, order: int = DEFAULT_ORDER) -> NDArray[np.complex128]:
        """Eigenvalues of :meth:`collocation_matrix`, approximations of the roots."""
        return np.asarray(scipy.linalg.eigvals(self.collocation_matrix(order)), dtype=complex)

    def refine(self, start: complex, deflate: Sequence[complex] = ()) -> complex:
        """Newton on Δ(λ) / Π(λ − r), r in ``deflate``, from ``start`` (:func:`newton_root`).

        Raises
        ------
        SolverError
            If Newton does not converge in 60 steps.
        """

        def logarithmic(lam: complex) -> complex | None:
            try:
                return self.logarithmic_derivative(lam)
            except np.linalg.LinAlgError:  # Λ(λ) exactly singular: λ is a root
                return None

        return newton_root(logarithmic, start, deflate)


def newton_root(
    logarithmic_derivative: Callable[[complex], complex | None],
    start: complex,
    deflate: Sequence[complex] = (),
    tolerance: float = 1e-14,
) -> complex:
    """A root of Δ(λ) / Π(λ − r), r in ``deflate``, by Newton from ``start``, given
    Δ'(λ)/Δ(λ) (None where Δ(λ) = 0: λ is a root); it stops when a step is at most
    ``tolerance`` × max(1, |λ|).

    Raises
    ------
    SolverError
        If it does not converge in 60 steps.
    """
    lam = complex(start)
    for _ in range(60):
        logarithmic = logarithmic_derivative(lam)
        if logarithmic is None:
            return lam
        logarithmic -= sum(1.0 / (lam - r) for r in deflate)
        if not (np.isfinite(logarithmic) and logarithmic != 0):
            break
        step = 1.0 / logarithmic
        lam -= step
        if abs(step) <= tolerance * max(1.0, abs(lam)):
            return lam
    raise SolverError(f"Newton on the characteristic equation did not converge from {start}")


def _adjugate(matrix: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """adj A, the transposed cofactor matrix (A adj A = det A I), also for singular A."""
    size = matrix.shape[0]
    if size == 1:
        return np.ones((1, 1), dtype=complex)
    cofactors = np.empty_like(matrix, dtype=complex)
    for i in range(size):
        for j in range(size):
            minor = np.delete(np.delete(matrix, i, axis=0), j, axis=1)
            cofactors[i, j] = (-1) ** (i + j) * np.linalg.det(minor)
    return cofactors.T


def chebyshev_differentiation(order: int) -> NDArray[np.float64]:
    """Trefethen's Chebyshev differentiation matrix on x_j = cos(jπ/N), j = 0..N.

    Examples
    --------
    >>> d = chebyshev_differentiation(4)
    >>> x = np.cos(np.pi * np.arange(5) / 4)
    >>> bool(np.allclose(d @ x**3, 3 * x**2))
    True
    """
    n = order
    x = np.cos(np.pi * np.arange(n + 1) / n)
    c = np.ones(n + 1)
    c[0] = c[-1] = 2.0
    c *= (-1.0) ** np.arange(n + 1)
    dx = x[:, None] - x[None, :]
    d = np.outer(c, 1.0 / c) / (dx + np.eye(n + 1))
    d -= np.diag(d.sum(axis=1))
    return d


@attrs.frozen(eq=False)
class DelayRoots:
    """Rightmost characteristic roots of a :class:`LinearDelaySystem`.

    Attributes
    ----------
    roots : ndarray of complex
        Refined roots with Im λ >= 0 (one of each conjugate pair), largest real part first.
    residuals : ndarray of float
        :meth:`LinearDelaySystem.relative_residual` at each root.
    collocation : ndarray of complex
        The collocation eigenvalue each root was refined from.
    deflated : tuple of complex
        The roots known in advance and kept out (e.g. the neutral root 0).
    order : int
        Collocation order N.
    dropped : tuple of complex
        The collocation eigenvalue nearest each deflated root, dropped (a check: it
        approximates that root).
    """

    roots: NDArray[np.complex128]
    residuals: NDArray[np.float64]
    collocation: NDArray[np.complex128]
    deflated: tuple[complex, ...]
    order: int
    dropped: tuple[complex, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """Roots as ``[real, imag]`` pairs [1/s, rad/s], for JSON."""
        return {
            "roots": [[r.real, r.imag] for r in self.roots],
            "residuals": [float(r) for r in self.residuals],
            "order": self.order,
        }


def rightmost_roots(
    system: LinearDelaySystem,
    count: int = 6,
    *,
    order: int | None = None,
    deflate: Sequence[complex] | None = None,
) -> DelayRoots:
    """The ``count`` rightmost roots of ``system`` (Im >= 0), collocation then Newton.

    Collocation eigenvalues within |λ| τ < N/2 (where the Chebyshev interpolant resolves
    e^{λθ} on [−τ, 0]) are candidates; the one nearest each deflated root is dropped (it
    approximates that root), every other is refined by Newton with the deflation; refined
    roots that coincide are kept once. ``order`` defaults to
    :meth:`LinearDelaySystem.default_order`; ``deflate`` to the system's
    ``neutral_roots``. A root beyond |λ| = N / (2τ) is not seen:
    for a retarded delay equation like this one the roots far from the origin lie ever
    further left (Re λ falls like −ln|λ| / τ), and comparing N with 2N checks the cut.

    Raises
    ------
    SolverError
        If no candidate converges to a root.
    """
    if order is None:
        order = system.default_order()
    if deflate is None:
        deflate = system.neutral_roots
    eigenvalues = system.collocation_eigenvalues(order)
    tau = system.delay
    keep = np.ones(eigenvalues.size, dtype=bool)
    dropped = []
    for known in deflate:
        nearest = int(np.argmin(np.abs(eigenvalues - known)))
        keep[nearest] = False
        dropped.append(complex(eigenvalues[nearest]))
    candidates = eigenvalues[keep & (eigenvalues.imag >= -1e-9 * np.abs(eigenvalues))]
    candidates = candidates[np.abs(candidates) * tau < order / 2]
    candidates = candidates[np.argsort(-candidates.real)]
    roots: list[complex] = []
    starts: list[complex] = []
    for start in candidates:
        try:
            root = system.refine(start, deflate)
        except SolverError:
            continue
        if root.imag < 0:
            root = root.conjugate()
        if abs(root.imag) <= 1e-12 * max(1.0, abs(root)):
            root = complex(root.real, 0.0)
        scale = max(1.0, abs(root)) * 1e-8
        if any(abs(root - other) <= scale for other in roots):
            continue
        if system.relative_residual(root) > 1e-8:
            continue
        roots.append(root)
        starts.append(complex(start))
    if not roots:
        raise SolverError("no collocation eigenvalue converged to a characteristic root")
    ordering = np.argsort([-r.real for r in roots], kind="stable")[:count]
    chosen = np.array([roots[i] for i in ordering], dtype=complex)
    return DelayRoots(
        roots=chosen,
        residuals=np.array([system.relative_residual(r) for r in chosen]),
        collocation=np.array([starts[i] for i in ordering], dtype=complex),
        deflated=tuple(complex(r) for r in deflate),
        order=order,
        dropped=tuple(dropped),
    )
