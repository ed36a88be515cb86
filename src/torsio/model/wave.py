"""The distributed model: the stepped string as torsional wave lines on a characteristic grid.

Each flexible section obeys the torsional wave equation

    rho J theta_tt = G J theta_xx - d theta_t,      d = alpha rho J  (distributed drag)

written for the angular velocity w = theta_t and the torque T = -G J theta_x that the
section above transmits to the one below. With the impedance Z = J sqrt(G rho) and
wave speed c = sqrt(G / rho), the Riemann invariants

    p = T + Z w   (travels down at +c),        m = T - Z w   (travels up at -c)

are constant along their characteristics when d = 0. The grid is matched to the wave
speeds: one global time step dt and, in section i, cells of length c_i dt, so a wave
moves exactly one cell per step and nothing is interpolated (no numerical dispersion).
Section lengths are rounded to whole cells; :func:`wave_grid` chooses dt so that the
largest relative change of a section's travel time L_i / c_i is below a tolerance and
reports it (:attr:`WaveModel.travel_time_errors`).

At a junction of sections 1 (above) and 2 (below) speed and torque are continuous, so an
incoming wave splits exactly: a velocity wave is transmitted with 2 Z1 / (Z1 + Z2) and
reflected with (Z1 - Z2) / (Z1 + Z2); in torque the factors are 2 Z2 / (Z1 + Z2) and
(Z2 - Z1) / (Z1 + Z2).

Damping: the mass-proportional part alpha [I] of Rayleigh damping is the lumped form of
a distributed viscous drag d = alpha rho J per unit length (and alpha J_bit on the bit),
which the wave model carries, lumped in its turn into point dampers at every
``drag_spacing``-th node (:func:`~torsio.model.wave_grid.drag_lumping`; 1: at every node). The
stiffness-proportional part beta [K] is a Kelvin-Voigt material damping,
T = -G J (theta_x + beta theta_xt); it turns the wave equation into a wave-diffusion
equation with no characteristics, and the wave model refuses it
(``ConfigError`` on ``damping.beta``, naming the alpha with the same first-mode damping
ratio, :func:`equivalent_alpha`): compare lumped and distributed models with beta = 0.

Examples
--------
>>> from torsio.examples import ritto2017_string
>>> grid = WaveStrategy().discretize(ritto2017_string())
>>> grid.cells, round(grid.time_step * 1e3, 4)
((995, 36, 62), 1.4386)
>>> float(grid.travel_time_errors.max()) < 3e-4
True
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.model.arrays import check_count
from torsio.model.axial_rows import PipeAxialRows, youngs_modulus
from torsio.model.continuum import continuum_modes
from torsio.model.drillstring import DrillString
from torsio.model.protocol import ModelEngines
from torsio.model.wave_grid import MAX_CELLS, choose_time_step

DEFAULT_MAX_TIME_STEP = 5e-3
"""Default largest time step of the characteristic grid [s]."""

DEFAULT_TRAVEL_TIME_TOLERANCE = 3e-4
"""Default largest relative change of a section's travel time by rounding to whole cells."""

DEFAULT_DRAG_SPACING = 4
"""Default number of cells between the nodes that carry the distributed drag (docs/wave.md
gives its effect on S_SS: less than that of halving the time step)."""


WAVE_ENGINES = ModelEngines(
    transient="torsio.analysis.wave:simulate_wave",
    batch="torsio.solvers.wave_batch:simulate_wave_batch",
)
"""The engines of the distributed model: its stepping along characteristics, for one run
and for many."""


def _as_tuple(values: Any) -> tuple[Any, ...]:
    return tuple(values)


@attrs.frozen
class WaveModel:
    """The characteristic grid of a stepped string, returned by the ``wave`` strategy.

    The grid is a :class:`torsio.model.protocol.StructuralModel`: it has no matrices and
    no linearization (yet), steps with its own fixed ``time_step`` and runs on
    :data:`WAVE_ENGINES`.

    Attributes
    ----------
    string : DrillString
        The string the grid follows.
    time_step : float
        Global time step dt [s]; a wave crosses one cell per step.
    cells : tuple of int
        Cells per flexible section, from the surface down.
    impedances : ndarray
        Z_i = J_i sqrt(G_i rho_i) of each flexible section [N m s/rad].
    wave_speeds : ndarray
        c_i = sqrt(G_i / rho_i) [m/s].
    polar_moments : ndarray
        J_i [m^4].
    densities : ndarray
        rho_i [kg/m^3].
    bit_inertia : float
        Inertia of the bit, a rigid body below the last section [kg m^2] (with
        ``rigid_bha``: the BHA's and the bit's).
    strategy : str
        ``"wave"``.
    rigid_bha : bool
        The grid covers the drill pipes only, the BHA a rigid body with the bit:
        strategy C's string, the limit its discretization converges to.
    drag_spacing : int
        Cells between the nodes that carry the distributed drag
        (:func:`~torsio.model.wave_grid.drag_lumping`).
    contacts : StringContacts or None
        Coulomb friction of the drag nodes with the borehole
        (:class:`torsio.model.contacts.StringContacts`; None: no contact).
    travel_time_tolerance : float
        The largest relative change of a section's travel time the grid allows.
    axial : PipeAxialRows or None
        The pipe's axial lines and the BHA's mass (:meth:`with_axial`; None: torsion
        only). A pipe with axial rows runs on the axial engine, which steps both lines on
        a grid of its own step (:func:`torsio.solvers.axial_wave_setup.pipe_grid`).
    """

    linearizable: ClassVar[bool] = False
    """No linearization of the distributed model (yet): no linear stability analysis."""
    has_matrices: ClassVar[bool] = False
    """No [I], [K]: its modes are the exact continuum of :meth:`grid_string`."""
    engines: ClassVar[ModelEngines] = WAVE_ENGINES
    """The engines that run the grid (:func:`torsio.model.protocol.resolve`)."""

    string: DrillString
    time_step: float
    cells: tuple[int, ...] = attrs.field(converter=_as_tuple)
    impedances: np.ndarray
    wave_speeds: np.ndarray
    polar_moments: np.ndarray
    densities: np.ndarray
    bit_inertia: float
    strategy: str = "wave"
    details: dict[str, Any] = attrs.field(factory=dict, eq=False)
    rigid_bha: bool = False
    drag_spacing: int = DEFAULT_DRAG_SPACING
    contacts: Any = attrs.field(default=None, eq=False)
    travel_time_tolerance: float = DEFAULT_TRAVEL_TIME_TOLERANCE
    axial: PipeAxialRows | None = attrs.field(default=None, eq=False)

    @property
    def sections(self) -> tuple[Any, ...]:
        """The sections on the grid: the flexible ones, or the drill pipes with ``rigid_bha``."""
        string = self.string
        return string.drill_pipe_sections if self.rigid_bha else string.flexible_sections

    @property
    def lengths(self) -> np.ndarray:
        """Length L_i of each section on the grid, as given [m]."""
        return np.array([s.length for s in self.sections])

    @property
    def travel_times(self) -> np.ndarray:
        """Travel time L_i / c_i of each section of the string as given [s]."""
        return self.lengths / self.wave_speeds

    @property
    def grid_travel_times(self) -> np.ndarray:
        """Travel time of each section on the grid, cells_i dt [s]."""
        return np.array(self.cells, dtype=float) * self.time_step

    @property
    def travel_time_errors(self) -> np.ndarray:
        """Relative change of each section's travel time by rounding to whole cells."""
        return np.abs(self.grid_travel_times - self.travel_times) / self.travel_times

    @property
    def cell_lengths(self) -> np.ndarray:
        """Length of a cell in each section, c_i dt [m]."""
        return self.wave_speeds * self.time_step

    @property
    def grid_lengths(self) -> np.ndarray:
        """Length of each section on the grid, cells_i c_i dt [m]."""
        return self.cell_lengths * np.array(self.cells)

    @property
    def dofs(self) -> int:
        """Number of grid nodes (two invariants each), for reports."""
        return int(sum(self.cells) + 1)

    @property
    def node_depths(self) -> np.ndarray:
        """Depth of every grid node on the grid string [m] (interface nodes once)."""
        depths = [np.zeros(1)]
        top = 0.0
        for n, dx in zip(self.cells, self.cell_lengths, strict=True):
            depths.append(top + dx * np.arange(1, n + 1))
            top += n * dx
        return np.concatenate(depths)

    def with_contacts(self, contacts: Any) -> WaveModel:
        """The same grid with Coulomb contacts at its drag nodes (a
        :class:`torsio.model.contacts.StringContacts` of its nodes; None: none)."""
        return attrs.evolve(self, contacts=contacts)

    def with_axial(self, axial: PipeAxialRows) -> WaveModel:
        """The same pipe carrying axial waves too (:class:`PipeAxialRows` of its sections,
        from :meth:`WaveStrategy.axial_rows`), the BHA one rigid body with the bit."""
        if not self.rigid_bha:
            raise ConfigError(
                "discretization.rigid_bha",
                "false: the distributed axial pipe's BHA is one rigid body with the bit "
                "(expected WaveStrategy(rigid_bha=True); in a file, rigid_bha = true or "
                "leave it out)",
            )
        check_count("axial.wave_speeds", axial.wave_speeds, len(self.cells))
        return attrs.evolve(self, axial=axial)

    def grid_string(self) -> DrillString:
        """The string the grid represents exactly: each section's length rounded to whole cells.

        Its continuum modes are the ones the wave model rings at.
        """
        sections = [
            attrs.evolve(s, length=float(length))
            for s, length in zip(self.sections, self.grid_lengths, strict=True)
        ]
        rigid = list(self.string.bha_sections) if self.rigid_bha else []
        return self.string.with_sections([*sections, *rigid, self.string.bit])

    @property
    def equivalent_stiffness(self) -> float:
        """k_eq of Eq. 9 for the string on the grid [N m/rad]: its static stiffness seen at
        the bit with the top held, 1 / sum(L_i / (G_i J_i)) over the grid's sections (the
        drill pipes only with ``rigid_bha``)."""
        grid = self.grid_string()
        sections = grid.drill_pipe_sections if self.rigid_bha else grid.flexible_sections
        return 1.0 / sum(1.0 / s.stiffness for s in sections)

    def first_frequency(self) -> float:
        """First natural frequency [rad/s] of the string on the grid (top held, exact
        continuum; the rigid-BHA continuum with ``rigid_bha``). With axial rows the axial
        engine steps a grid of its own, within the same tolerance: the string's own
        continuum, unrounded."""
        string = self.string if self.axial is not None else self.grid_string()
        modes = continuum_modes(string, count=1, rigid_bha=self.rigid_bha)
        return float(modes.frequencies_rad[0])

    def describe(self) -> dict[str, Any]:
        """Grid facts for reports and JSON."""
        return {
            "strategy": self.strategy,
            "time_step_s": self.time_step,
            "cells": list(self.cells),
            "impedances_N_m_s": [float(z) for z in self.impedances],
            "travel_time_errors": [float(e) for e in self.travel_time_errors],
            "bit_inertia_kg_m2": self.bit_inertia,
            "rigid_bha": self.rigid_bha,
            "drag_spacing": self.drag_spacing,
            **({} if self.contacts is None else {"contacts": self.contacts.describe()}),
            **({} if self.axial is None else {"axial": self.axial.describe()}),
        }


def interface_factors(upper: float, lower: float) -> dict[str, float]:
    """Exact splitting of a wave arriving from impedance ``upper`` at impedance ``lower``.

    >>> interface_factors(1.0, 3.0)
    {'velocity_transmitted': 0.5, 'velocity_reflected': -0.5, 'torque_transmitted': 1.5, \
'torque_reflected': 0.5}
    """
    total = upper + lower
    return {
        "velocity_transmitted": 2.0 * upper / total,
        "velocity_reflected": (upper - lower) / total,
        "torque_transmitted": 2.0 * lower / total,
        "torque_reflected": (lower - upper) / total,
    }


class WaveStrategy:
    """The ``wave`` strategy: the distributed model on a characteristic grid.

    Parameters
    ----------
    time_step : float, optional
        Largest time step [s] (default :data:`DEFAULT_MAX_TIME_STEP`); the grid takes the
        largest step below it that keeps every section's travel time within
        ``travel_time_tolerance``.
    travel_time_tolerance : float, optional
        Largest relative change of a section's travel time L/c by rounding to whole cells
        (default :data:`DEFAULT_TRAVEL_TIME_TOLERANCE`).
    rigid_bha : bool, optional
        Waves in the drill pipes only, the BHA a rigid body with the bit (strategy C's
        string; default False: every section flexible).
    drag_spacing : int, optional
        Cells between the nodes that carry the distributed drag (default
        :data:`DEFAULT_DRAG_SPACING`, or the most cells of any section on a grid with
        fewer; 1: every node).
    """

    name: ClassVar[str] = "wave"
    description: ClassVar[str] = "distributed model: wave equation along characteristics"

    def __init__(
        self,
        time_step: float | None = None,
        travel_time_tolerance: float | None = None,
        rigid_bha: bool | None = None,
        drag_spacing: int | None = None,
        **options: Any,
    ) -> None:
        for key, value in options.items():
            if value is not None:
                raise ConfigError(
                    key,
                    f"the wave strategy takes no option {key!r}: its grid follows the wave "
                    "speeds; give time_step [s], travel_time_tolerance and drag_spacing "
                    "instead",
                )
        self.time_step = _positive("time_step", time_step, DEFAULT_MAX_TIME_STEP)
        self.travel_time_tolerance = _positive(
            "travel_time_tolerance", travel_time_tolerance, DEFAULT_TRAVEL_TIME_TOLERANCE
        )
        if self.travel_time_tolerance >= 0.5:  # a travel time off by half or more: no grid
            raise ConfigError(
                "discretization.travel_time_tolerance",
                f"expected a relative tolerance in (0, 0.5), got {travel_time_tolerance!r}",
            )
        if rigid_bha is not None and not isinstance(rigid_bha, bool):
            raise ConfigError(
                "discretization.rigid_bha", f"expected true or false, got {rigid_bha!r}"
            )
        self.rigid_bha = bool(rigid_bha)
        self.drag_spacing_given = drag_spacing is not None
        if drag_spacing is None:
            drag_spacing = DEFAULT_DRAG_SPACING
        if isinstance(drag_spacing, bool) or not isinstance(drag_spacing, int) or drag_spacing < 1:
            raise ConfigError(
                "discretization.drag_spacing",
                f"expected a whole number of cells >= 1 between the drag nodes, got "
                f"{drag_spacing!r}",
            )
        self.drag_spacing = int(drag_spacing)

    def discretize(self, string: DrillString) -> WaveModel:
        """The characteristic grid of ``string``."""
        sections = string.drill_pipe_sections if self.rigid_bha else string.flexible_sections
        if not sections:
            raise ConfigError(
                "discretization.rigid_bha", "the string has no drill pipes above its BHA"
            )
        taus = np.array([s.wave_travel_time for s in sections])
        if taus.sum() / self.time_step > MAX_CELLS:
            raise ConfigError(
                "discretization.time_step",
                f"a time step of {self.time_step:g} s gives {taus.sum() / self.time_step:.3g} "
                f"cells, more than the limit of {MAX_CELLS:,}; expected a time step of at least "
                f"{taus.sum() / MAX_CELLS:.3g} s",
            )
        dt, cells = choose_time_step(taus, self.time_step, self.travel_time_tolerance)
        most = int(cells.max())
        spacing = self.drag_spacing if self.drag_spacing_given else min(self.drag_spacing, most)
        if spacing > most:
            longest = sections[int(np.argmax(cells))]
            raise ConfigError(
                "discretization.drag_spacing",
                f"expected 1 to {most} cells between the drag nodes (the most cells of any "
                f"section on this grid: {longest.name or longest.kind}, {most} cells of "
                f"{float(longest.material.wave_speed) * dt:.3g} m), got {spacing}; "
                f"a spacing of {most} or more leaves every section its end dampers only",
            )
        polar = np.array([s.polar_moment for s in sections])
        density = np.array([s.material.density for s in sections])
        speed = np.array([s.material.wave_speed for s in sections])
        return WaveModel(
            string=string,
            time_step=dt,
            cells=tuple(int(n) for n in cells),
            impedances=polar * density * speed,
            wave_speeds=speed,
            polar_moments=polar,
            densities=density,
            bit_inertia=float(string.bha_inertia if self.rigid_bha else string.bit.inertia),
            details={
                "time_step_s": dt,
                "max_time_step_s": self.time_step,
                "travel_time_tolerance": self.travel_time_tolerance,
                "cells": {s.name or s.kind: int(n) for s, n in zip(sections, cells, strict=True)},
                "drag_spacing": spacing,
            },
            rigid_bha=self.rigid_bha,
            drag_spacing=spacing,
            travel_time_tolerance=self.travel_time_tolerance,
        )

    def axial_rows(self, string: DrillString, hook: str) -> PipeAxialRows:
        """The axial lines of :meth:`discretize`'s pipe (:meth:`WaveModel.with_axial`):
        each drill pipe's √(E/ρ) and A √(E ρ) (A the body's cross-section), the BHA's and
        the bit's Σ ρ A L below them (a ConfigError on ``material.youngs_modulus``
        without E)."""
        pipes = string.drill_pipe_sections
        moduli = np.array([youngs_modulus(s) for s in pipes])
        density = np.array([s.material.density for s in pipes])
        area = np.array([s.area for s in pipes])
        bha = [s for s in string.sections if s.in_bha]
        return PipeAxialRows(
            np.sqrt(moduli / density),
            area * np.sqrt(moduli * density),
            sum(s.material.density * s.area * s.length for s in bha),
            hook,
        )


def _positive(key: str, value: Any, default: float) -> float:
    if value is None:
        return default
    ok = isinstance(value, int | float) and not isinstance(value, bool)
    if not ok or not (math.isfinite(value) and value > 0):
        raise ConfigError(f"discretization.{key}", f"expected a positive number, got {value!r}")
    return float(value)


def is_wave_model(model: Any) -> bool:
    """Whether ``model`` is the wave strategy's grid (not a lumped model).

    For ``torsio.model`` itself: elsewhere a model is read through its protocol
    (:class:`torsio.model.protocol.StructuralModel`), never by its kind.
    """
    return isinstance(model, WaveModel)


def check_wave_damping(damping: Any, grid: WaveModel | None = None) -> float:
    """alpha [1/s] of a damping the wave model can carry; a clear error otherwise.

    With ``grid`` the error for beta != 0 names the alpha that gives the first mode of
    the grid's string the same damping ratio (:func:`equivalent_alpha`).

    >>> from torsio.physics.damping import RayleighDamping
    >>> check_wave_damping(RayleighDamping(alpha=0.35))
    0.35
    """
    alpha = getattr(damping, "alpha", None)
    beta = getattr(damping, "beta", None)
    if alpha is None or beta is None:
        raise ConfigError(
            "damping",
            "the wave model needs Rayleigh damping of a drill-string "
            f"(alpha as distributed drag), got {damping!r}",
        )
    if beta != 0.0:
        hint = "set [damping] beta = 0 and give the damping as alpha [1/s]"
        if grid is not None:
            omega = first_frequency(grid)
            ratio = 0.5 * (alpha / omega + beta * omega)
            hint += (
                f": alpha = {equivalent_alpha(alpha, beta, omega):.4g} 1/s (alpha + beta w1^2, "
                f"w1 = {omega:.4g} rad/s) keeps the first mode's damping ratio {ratio:.3g}"
            )
        raise ConfigError(
            "damping.beta",
            f"the wave model carries the mass-proportional part alpha of Rayleigh damping as "
            f"distributed viscous drag, but not the stiffness-proportional (Kelvin-Voigt) part; "
            f"got beta = {beta!r} s. To run the wave model, {hint} "
            "(docs/wave.md, Damping)",
        )
    return float(alpha)


def equivalent_alpha(alpha: float, beta: float, first_frequency: float) -> float:
    """Mass-proportional alpha [1/s] with the first-mode damping ratio of (alpha, beta).

    Rayleigh damping gives mode n the ratio (alpha / w_n + beta w_n) / 2; alpha + beta w1^2
    alone gives mode 1 the same ratio (the higher modes less: Kelvin-Voigt damping grows
    with frequency, distributed drag falls).

    >>> round(equivalent_alpha(0.35, 0.06, 0.8215), 4)
    0.3905
    """
    return float(alpha + beta * first_frequency**2)


def first_frequency(grid: WaveModel) -> float:
    """omega_1 [rad/s] of the string on the grid (:meth:`WaveModel.first_frequency`)."""
    return grid.first_frequency()


from torsio.hookspecs import hookimpl  # noqa: E402  (after the class it registers)


@hookimpl
def torsio_discretizers() -> tuple[type[WaveStrategy], ...]:
    """The ``wave`` strategy, registered like any discretizer."""
    return (WaveStrategy,)
