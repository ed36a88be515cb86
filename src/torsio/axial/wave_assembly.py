"""Distributed drilling assemblies: a stepped pipe of wave lines above a lumped BHA.

From the top drive and the hook down, one or more uniform pipe sections (length, E, G, ρ,
A, J each) carry axial waves at √(E/ρ) and torsional waves at √(G/ρ); the BHA at the
bottom is a rigid body (mass m_b, inertia I_b) that carries the RGD bit. The boundaries at
the top:

- torsionally the top drive turning at Ω₀;
- axially ``hook = "weight"``: the constant force W₀ at the top of the pipe (zero gravity,
  as in the lumped model: in steady drilling the whole pipe carries W₀), or
  ``hook = "speed"``: the top of the pipe moving down at V₀, the steady rate of
  penetration of the run's (W₀, Ω₀).

:mod:`torsio.axial.wave_pipe` steps the lines, :mod:`torsio.axial.wave_kernel` the run;
:func:`torsio.axial.transient.simulate_axial` runs it like a lumped assembly.

Examples
--------
>>> pipe = PipeSection(1000.0, 2.1e11, 8.1e10, 7850.0, 3.4e-3, 3.0e-5)
>>> assembly = WaveDrillingAssembly([pipe], bha_mass=3.0e4, bha_inertia=455.65, hook="speed")
>>> round(float(assembly.axial_wave_speeds[0]), 1), round(float(assembly.axial_impedances[0]))
(5172.2, 138046)
>>> [round(float(w), 4) for w in assembly.axial_frequencies(2)]  # rad/s, top held
[4.2609, 17.5735]
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any, ClassVar

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.axial.assembly import lumped_pipe
from torsio.errors import ConfigError
from torsio.model.axial_rows import check_hook
from torsio.model.continuum import bar_frequencies
from torsio.model.lumped import LumpedModel
from torsio.model.wave import DEFAULT_TRAVEL_TIME_TOLERANCE

__all__ = ["PipeSection", "WaveDrillingAssembly", "wave_pipe_assembly"]


DEFAULT_ELEMENT_LENGTH = 100.0
"""Largest element [m] of a lumped chain of pipe sections by default: ``[axial]
element_length``, and a distributed pipe's lumped twin."""


def _positive(key: str, value: Any) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ConfigError(key, f"expected a positive number, got {value!r}") from None
    if not (math.isfinite(number) and number > 0):
        raise ConfigError(key, f"expected a positive finite value, got {value!r}")
    return number


@attrs.frozen
class PipeSection:
    """One uniform section of pipe: of the distributed pipe, or of a lumped chain
    (:func:`~torsio.axial.assembly.lumped_pipe`, :func:`torsio.axial.assembly.pipe_assembly`).

    Parameters
    ----------
    length : float
        L [m].
    youngs_modulus, shear_modulus : float
        E, G [Pa].
    density : float
        ρ [kg/m³].
    area : float
        Cross-section A [m²].
    polar_moment : float
        Polar moment of area J [m⁴].
    """

    length: float
    youngs_modulus: float
    shear_modulus: float
    density: float
    area: float
    polar_moment: float

    def __attrs_post_init__(self) -> None:
        for field in attrs.fields(PipeSection):
            value = _positive(f"section.{field.name}", getattr(self, field.name))
            object.__setattr__(self, field.name, value)


def _sections(values: Iterable[PipeSection]) -> tuple[PipeSection, ...]:
    if isinstance(values, PipeSection) or not isinstance(values, Iterable):
        raise ConfigError("sections", f"expected a sequence of PipeSection, got {values!r}")
    sections = tuple(values)
    for i, section in enumerate(sections):
        if not isinstance(section, PipeSection):
            raise ConfigError(f"sections[{i}]", f"expected a PipeSection, got {section!r}")
    return sections


@attrs.frozen(eq=False)
class WaveDrillingAssembly:
    """A distributed pipe of uniform sections above a rigid BHA that carries the bit.

    Parameters
    ----------
    sections : sequence of PipeSection
        From the top down (at least one).
    bha_mass : float
        m_b [kg], the BHA's axial mass with the bit's.
    bha_inertia : float
        I_b [kg m²].
    hook : str
        ``"weight"`` (the constant force W₀ on the top of the pipe) or ``"speed"`` (the top
        of the pipe moving down at the steady rate of penetration V₀).
    travel_time_tolerance : float
        Largest relative change of a section's travel time L/c by rounding it to whole
        steps (the step rule of :mod:`torsio.axial.wave_setup`); in (0, 0.5).
    """

    linearizable: ClassVar[bool] = False
    """:func:`~torsio.axial.linearization.drilling_linearization` is of lumped chains; the
    pipe's stability is its characteristic equation (:mod:`torsio.axial.wave_stability`)."""
    has_matrices: ClassVar[bool] = False
    """No mass and stiffness matrices: the pipe's modes are its exact continuum's."""

    sections: tuple[PipeSection, ...] = attrs.field(converter=_sections)
    bha_mass: float = attrs.field(kw_only=True)
    bha_inertia: float = attrs.field(kw_only=True)
    hook: str = attrs.field(default="weight", kw_only=True)
    travel_time_tolerance: float = attrs.field(default=DEFAULT_TRAVEL_TIME_TOLERANCE, kw_only=True)

    def __attrs_post_init__(self) -> None:
        if not self.sections:
            raise ConfigError("sections", "is empty; expected at least one PipeSection")
        object.__setattr__(self, "bha_mass", _positive("bha_mass", self.bha_mass))
        object.__setattr__(self, "bha_inertia", _positive("bha_inertia", self.bha_inertia))
        check_hook(self.hook)
        tolerance = self.travel_time_tolerance
        if not (isinstance(tolerance, int | float) and 0 < tolerance < 0.5):
            raise ConfigError(
                "discretization.travel_time_tolerance",
                f"expected a relative tolerance in (0, 0.5), got {tolerance!r}",
            )

    def _column(self, name: str) -> NDArray[np.float64]:
        return np.array([getattr(s, name) for s in self.sections], dtype=float)

    @property
    def lengths(self) -> NDArray[np.float64]:
        """Section lengths L [m], from the top down."""
        return self._column("length")

    @property
    def axial_wave_speeds(self) -> NDArray[np.float64]:
        """c = √(E/ρ) of each section [m/s]."""
        return np.sqrt(self._column("youngs_modulus") / self._column("density"))

    @property
    def torsional_wave_speeds(self) -> NDArray[np.float64]:
        """c = √(G/ρ) of each section [m/s]."""
        return np.sqrt(self._column("shear_modulus") / self._column("density"))

    @property
    def axial_impedances(self) -> NDArray[np.float64]:
        """Z = A √(E ρ) of each section [N s/m]."""
        e, rho = self._column("youngs_modulus"), self._column("density")
        return self._column("area") * np.sqrt(e * rho)

    @property
    def torsional_impedances(self) -> NDArray[np.float64]:
        """Z = J √(G ρ) of each section [N m s/rad]."""
        g, rho = self._column("shear_modulus"), self._column("density")
        return self._column("polar_moment") * np.sqrt(g * rho)

    def axial_frequencies(self, count: int = 10, *, free_top: bool = False) -> NDArray[np.float64]:
        """The first exact axial frequencies [rad/s] of the pipe with the BHA and the bit off
        bottom (:func:`torsio.model.continuum.bar_frequencies` with E A, √(E/ρ) and m_b): the
        top held (the speed hook), or with ``free_top`` free (the weight hook's constant
        force; the rigid-body zero left out)."""
        rigidity = self._column("youngs_modulus") * self._column("area")
        return bar_frequencies(
            rigidity, self.lengths, self.axial_wave_speeds, self.bha_mass, count, free_top=free_top
        )

    def torsional_frequencies(self, count: int = 10) -> NDArray[np.float64]:
        """The first exact torsional frequencies [rad/s], the top drive held and the bit free
        (G J, √(G/ρ) and I_b)."""
        rigidity = self._column("shear_modulus") * self._column("polar_moment")
        return bar_frequencies(
            rigidity, self.lengths, self.torsional_wave_speeds, self.bha_inertia, count
        )

    def first_frequency(self) -> float:
        """ω₁ [rad/s]: the first exact torsional frequency, top held
        (:meth:`torsional_frequencies`)."""
        return float(self.torsional_frequencies(1)[0])

    def fastest_rate(self) -> float:
        """The largest of Z_a/m_b and Z_t/I_b [1/s], the rates at which the pipe's bottom
        section takes the BHA's motion away: what the step must resolve beside the bit."""
        return float(
            max(
                self.axial_impedances[-1] / self.bha_mass,
                self.torsional_impedances[-1] / self.bha_inertia,
            )
        )

    def lumped_twin(self, element_length: float = DEFAULT_ELEMENT_LENGTH) -> LumpedModel:
        """The lumped chain of the same sections and BHA in elements of at most
        ``element_length`` [m], undamped like the pipe
        (:func:`~torsio.axial.assembly.lumped_pipe`): what its stability's roots start
        from."""
        return lumped_pipe(
            self.sections, self.bha_mass, self.bha_inertia, element_length, self.hook
        )

    def describe(self) -> dict[str, Any]:
        """Plain data for reports and JSON."""
        return {
            "kind": "distributed",
            "sections": [attrs.asdict(s) for s in self.sections],
            "bha_mass": self.bha_mass,
            "bha_inertia": self.bha_inertia,
            "hook": self.hook,
            "travel_time_tolerance": self.travel_time_tolerance,
        }


def wave_pipe_assembly(
    pipe: PipeSection,
    bha_mass: float,
    bha_inertia: float,
    *,
    sections: int = 1,
    hook: str = "weight",
) -> WaveDrillingAssembly:
    """A uniform ``pipe`` section above the BHA, in ``sections`` equal sections.

    The distributed counterpart of :func:`torsio.axial.assembly.pipe_assembly` (the same
    pipe and BHA, the same units). More than one section changes nothing: the junctions of
    equal sections are transparent (:mod:`torsio.axial.wave_pipe`).

    >>> pipe = PipeSection(2500.0, 2.1e11, 8.1e10, 7850.0, 3.4e-3, 3e-5)
    >>> wave_pipe_assembly(pipe, 3e4, 455.65).hook
    'weight'
    """
    if isinstance(sections, bool) or not isinstance(sections, int) or sections < 1:
        raise ConfigError("sections", f"{sections!r} must be a whole number >= 1")
    piece = attrs.evolve(pipe, length=pipe.length / sections)
    return WaveDrillingAssembly(
        [piece] * sections, bha_mass=bha_mass, bha_inertia=bha_inertia, hook=hook
    )
