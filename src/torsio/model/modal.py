"""Modal analysis of a lumped model: [K] phi = omega^2 [I] phi.

Mode shapes are normalized to a peak magnitude of 1, with the node nearest the
surface positive (a shape reads as a fraction of its peak rotation; the sign is
fixed so results are reproducible and comparable with the continuum).
Mass-normalized shapes (phi^T [I] phi = 1) are also kept.

Examples
--------
>>> from torsio import StrategyC, ritto2017_string
>>> string = ritto2017_string()
>>> results = modal_analysis(StrategyC(dp_elements=5).discretize(string), string=string)
>>> comparison = results.compare()
>>> [round(float(e), 4) for e in comparison.relative_error[:2]]
[-0.0034, -0.0288]
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import attrs
import numpy as np
import scipy.linalg

from torsio.errors import ConfigError
from torsio.model.continuum import ContinuumModes, continuum_modes
from torsio.model.drillstring import DrillString
from torsio.model.shapes import normalize_shape
from torsio.model.tridiagonal import is_tridiagonal

if TYPE_CHECKING:  # the lumped model calls back into this module for its omega_1
    from torsio.model.lumped import LumpedModel


@attrs.frozen(repr=False)
class ModalResults:
    """Natural frequencies and mode shapes of a lumped model.

    Attributes
    ----------
    model : LumpedModel
    frequencies_rad : ndarray, shape (m,)
        Natural frequencies [rad/s], ascending.
    mode_shapes : ndarray, shape (dofs, m)
        Column j is mode j+1: peak magnitude 1, positive at the node nearest the surface.
    mass_normalized_shapes : ndarray, shape (dofs, m)
        The same modes with phi^T [I] phi = 1 [kg^-1/2 m^-1].
    string : DrillString or None
        The string the model was discretized from, for the continuum reference.
    """

    model: LumpedModel
    frequencies_rad: np.ndarray
    mode_shapes: np.ndarray
    mass_normalized_shapes: np.ndarray
    string: DrillString | None = None

    @property
    def frequencies_hz(self) -> np.ndarray:
        """Natural frequencies [Hz]."""
        return self.frequencies_rad / (2.0 * math.pi)

    @property
    def node_depths(self) -> np.ndarray:
        """Depth of each degree of freedom [m]."""
        return self.model.node_depths

    def damping_ratios(self, alpha: float, beta: float) -> np.ndarray:
        """Modal damping ratios of Rayleigh damping [C] = alpha [I] + beta [K]:
        zeta = alpha / (2 omega) + beta omega / 2."""
        return alpha / (2.0 * self.frequencies_rad) + beta * self.frequencies_rad / 2.0

    def compare(self, reference: ContinuumModes | None = None) -> ModalComparison:
        """Compare with the exact continuum, mode by mode (same index).

        Without ``reference``, the continuum of the string the model came from is
        used, with the BHA rigid if the model's strategy keeps it rigid (A, C); the
        continuum of the string as given (flexible BHA) is then kept as well
        (:attr:`ModalComparison.as_given`).
        """
        if reference is None:
            if self.string is None:
                raise ConfigError(
                    "reference",
                    "this model has no drill-string to compare against; pass a ContinuumModes",
                )
            rigid = bool(self.model.details.get("elements", {}).get("BHA") == "rigid")
            reference = continuum_modes(self.string, self.frequencies_rad.size, rigid)
            if rigid:  # the string as given as well: the reference of the paper and of JSON
                flexible = continuum_modes(self.string, self.frequencies_rad.size, False)
                count = min(reference.frequencies_rad.size, self.frequencies_rad.size)
                return ModalComparison(self, reference, count, flexible)
        count = min(reference.frequencies_rad.size, self.frequencies_rad.size)
        return ModalComparison(self, reference, count)

    def to_dict(self) -> dict[str, Any]:
        """Plain data for JSON."""
        return {
            "strategy": self.model.strategy,
            "dofs": self.model.dofs,
            "frequencies_rad_s": self.frequencies_rad.tolist(),
            "frequencies_hz": self.frequencies_hz.tolist(),
            "node_depths_m": self.node_depths.tolist(),
        }

    def __repr__(self) -> str:
        hz = ", ".join(f"{f:.4g}" for f in self.frequencies_hz[:5])
        more = ", ..." if self.frequencies_hz.size > 5 else ""
        return (
            f"ModalResults(strategy {self.model.strategy}, {self.model.dofs} DOFs, "
            f"{self.frequencies_hz.size} modes: [{hz}{more}] Hz)"
        )

    def plot(self, modes: tuple[int, ...] = (1,), ax: Any = None, reference: bool = True) -> Any:
        """Plot mode shapes against depth (matplotlib); the continuum as lines if known."""
        from torsio.plotting import plot_mode_shapes

        return plot_mode_shapes(self, modes, ax=ax, reference=reference)


@attrs.frozen(repr=False)
class ModalComparison:
    """Lumped frequencies against the exact continuum, mode by mode.

    Attributes
    ----------
    modal : ModalResults
    reference : ContinuumModes
        The continuum compared mode by mode (rigid BHA for strategies A and C:
        the limit of the discretization).
    count : int
        Number of compared modes.
    flexible : ContinuumModes or None
        When ``reference`` keeps the BHA rigid: the continuum of the string as given.
    """

    modal: ModalResults
    reference: ContinuumModes
    count: int
    flexible: ContinuumModes | None = None

    def __repr__(self) -> str:
        errors = ", ".join(f"{100 * e:+.3g} %" for e in self.relative_error[:5])
        which = "rigid-BHA" if self.reference.rigid_bha else "flexible"
        return f"ModalComparison({self.count} modes against the {which} continuum: [{errors}])"

    @property
    def as_given(self) -> ContinuumModes | None:
        """The continuum of the string as given (flexible BHA), if known."""
        return self.flexible if self.reference.rigid_bha else self.reference

    @property
    def frequencies_hz(self) -> np.ndarray:
        """Lumped frequencies [Hz] of the compared modes."""
        return self.modal.frequencies_hz[: self.count]

    @property
    def reference_hz(self) -> np.ndarray:
        """Continuum frequencies [Hz] of the compared modes."""
        return self.reference.frequencies_hz[: self.count]

    @property
    def relative_error(self) -> np.ndarray:
        """(lumped - continuum) / continuum for each compared mode."""
        return self.frequencies_hz / self.reference_hz - 1.0

    def rows(self) -> list[tuple[int, float, float, float]]:
        """(mode, lumped Hz, continuum Hz, relative error) per mode."""
        return [
            (i + 1, float(f), float(r), float(e))
            for i, (f, r, e) in enumerate(
                zip(self.frequencies_hz, self.reference_hz, self.relative_error, strict=True)
            )
        ]

    def to_dict(self) -> dict[str, Any]:
        """Plain data for JSON.

        ``continuum_hz`` and ``relative_error`` are always against the string as given
        (flexible BHA; DESIGN.md); a rigid-BHA reference has keys of its own,
        ``continuum_rigid_bha_hz`` and ``relative_error_rigid_bha``.
        """
        data: dict[str, Any] = {}
        given = self.as_given
        if given is not None:
            given_hz = given.frequencies_hz[: self.count]
            data["continuum_hz"] = given_hz.tolist()
            data["relative_error"] = (self.frequencies_hz / given_hz - 1.0).tolist()
        data["continuum_rigid_bha"] = self.reference.rigid_bha
        if self.reference.rigid_bha:
            data["continuum_rigid_bha_hz"] = self.reference_hz.tolist()
            data["relative_error_rigid_bha"] = self.relative_error.tolist()
        return data


def first_natural_frequency(model: Any) -> float:
    """omega_1 [rad/s] of a model (or a System's model), top held, undamped.

    The model's own :meth:`~torsio.model.protocol.StructuralModel.first_frequency`: for a
    lumped model its first mode (:func:`lowest_natural_frequency`); for the distributed
    (``wave``) model the first frequency of its exact continuum. Every default that counts
    periods reads this.
    """
    model = getattr(model, "model", model)
    return float(model.first_frequency())


def lowest_natural_frequency(model: LumpedModel) -> float:
    """omega_1 [rad/s] of a lumped model, top held: solved once per model and kept with it
    (or taken from an earlier modal analysis of it)."""
    known = _memo(model).get("first_frequency")
    if known is not None:  # from an earlier modal analysis of this model
        return float(known)
    return float(modal_analysis(model, 1).frequencies_rad[0])


def natural_frequencies(model: LumpedModel) -> np.ndarray:
    """Every natural frequency [rad/s] of a lumped model, top held, ascending: solved once
    per model and kept with it (or taken from a modal analysis of all its modes)."""
    memo = _memo(model)
    if "frequencies" not in memo:
        _remember(
            model, np.sqrt(_eigen(model.stiffness, model.inertia, (0, model.dofs - 1), False)[0])
        )
    return np.asarray(memo["frequencies"])


def highest_natural_frequency(model: LumpedModel) -> float:
    """omega_n [rad/s] of a lumped model, top held: it bounds the stiffness of the equations."""
    return float(natural_frequencies(model)[-1])


def _memo(model: Any) -> dict[str, Any]:
    """What has been computed from the model's matrices (a throw-away dict for a model
    type that keeps none)."""
    memo = getattr(model, "_memo", None)
    return memo if isinstance(memo, dict) else {}


def _remember(model: Any, frequencies: np.ndarray) -> None:
    memo = _memo(model)
    memo["first_frequency"] = float(frequencies[0])
    if frequencies.size == model.dofs:
        memo["frequencies"] = frequencies


def modal_analysis(
    model: LumpedModel, count: int | None = None, string: DrillString | None = None
) -> ModalResults:
    """Solve [K] phi = omega^2 [I] phi for the lowest ``count`` modes (all by default).

    Lumped (diagonal) inertia with a chain stiffness is solved as the tridiagonal
    matrix D^-1/2 [K] D^-1/2 (``scipy.linalg.eigh_tridiagonal``); any other model with
    ``scipy.linalg.eigh`` on the symmetric-definite pencil. ``string`` (the
    drill-string the model was built from) enables :meth:`ModalResults.compare`.
    """
    n = model.dofs
    if count is None:
        count = n
    if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count:
        raise ConfigError("count", f"expected a whole number of modes >= 1, got {count!r}")
    count = min(count, n)
    eigenvalues, vectors = _eigen(model.stiffness, model.inertia, (0, count - 1))
    frequencies = np.sqrt(eigenvalues)
    _remember(model, frequencies)  # every later omega_1 (and spectrum) of the model reads it
    return ModalResults(model, frequencies, normalize_shape(vectors), vectors, string)


def _eigen(
    stiffness: np.ndarray, inertia: np.ndarray, indices: tuple[int, int], vectors: bool = True
) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues omega^2 [rad^2/s^2] ``indices[0]..indices[1]`` of the pencil ([K], [I]),
    ascending, with their vectors (columns; none with ``vectors=False``).

    Lumped (diagonal) inertia with a chain stiffness is solved as the tridiagonal matrix
    D^-1/2 [K] D^-1/2 (O(n^2), no dense BLAS); any other model as the dense pencil.
    """
    shapes = np.empty((stiffness.shape[0], 0))
    lumped = not np.count_nonzero(inertia - np.diag(np.diag(inertia)))
    if lumped and is_tridiagonal(stiffness):
        scale = 1.0 / np.sqrt(np.diag(inertia))
        diagonal = np.diag(stiffness) * scale**2
        off_diagonal = np.diag(stiffness, 1) * scale[:-1] * scale[1:]
        solved = scipy.linalg.eigh_tridiagonal(
            diagonal, off_diagonal, eigvals_only=not vectors, select="i", select_range=indices
        )
        eigenvalues, shapes = solved if vectors else (solved, shapes)
        shapes = shapes * scale[:, None] if vectors else shapes
    else:
        solved = scipy.linalg.eigh(
            stiffness, inertia, eigvals_only=not vectors, subset_by_index=indices
        )
        eigenvalues, shapes = solved if vectors else (solved, shapes)
    if np.any(eigenvalues <= 0):
        raise ConfigError(
            "stiffness",
            "non-positive eigenvalue: the model is not fixed at the top or not positive definite",
        )
    return eigenvalues, shapes
