"""The context every report section reads, the section type and the table helpers.

See :mod:`torsio.report.document` for how sections make up the report.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

import attrs
from rich import box
from rich.console import Console, ConsoleOptions, Group, RenderableType, RenderResult
from rich.table import Table
from rich.text import Text

from torsio.config.configuration import Config
from torsio.display_units import DisplayUnits
from torsio.errors import ConfigError
from torsio.model.lumped import LumpedModel
from torsio.model.modal import ModalComparison, ModalResults, modal_analysis
from torsio.physics.damping import ModelDamping, RayleighDamping
from torsio.physics.system import System

DEFAULT_MODES = 5
"""Modes shown by default (fewer if the model has fewer degrees of freedom)."""

WIDE = 100
"""Console width [columns] from which tables use their wide layout."""


class ReportContext:
    """A configuration and what the report computes from it, each computed once on demand.

    One System is built (one discretization, one bit-rock law); the modal analysis runs
    once and every later omega_1 of the model reads it; the transient, the critical-WOB
    search and the sections themselves (:attr:`sections`) are computed once and shared by
    the terminal, JSON and HTML outputs.

    Parameters
    ----------
    config : Config
        The validated configuration.
    strategy : str, optional
        Discretizer name overriding the file's ``[discretization] strategy``.
    dp_elements, bha_elements : int, optional
        Element counts overriding the file's (see :mod:`torsio.model.discretize`).
    modes : int
        How many modes to show (at most the model's degrees of freedom).
    units : str
        ``"si"`` (default) or ``"field"``: the units of the printed string, well, operating
        point and critical-WOB lines (:class:`~torsio.display_units.DisplayUnits`); the
        data (JSON) stay SI.
    """

    def __init__(
        self,
        config: Config,
        *,
        strategy: str | None = None,
        dp_elements: int | None = None,
        bha_elements: int | None = None,
        modes: int = DEFAULT_MODES,
        units: str = "si",
    ) -> None:
        if isinstance(modes, bool) or not isinstance(modes, int) or modes < 1:
            raise ConfigError("modes", f"expected a whole number of modes >= 1, got {modes!r}")
        self.config = config
        self.overrides: dict[str, Any] = {
            "strategy": strategy,
            "dp_elements": dp_elements,
            "bha_elements": bha_elements,
        }
        self.requested_modes = modes
        self.units = DisplayUnits(units)
        self.dynamics_note = ""
        """Why the dynamic sections are missing ('' when they are not)."""
        self.sections: list[ReportSection] | None = None
        """The report's sections once computed (:func:`torsio.report.document.report_sections`)."""

    @functools.cached_property
    def system(self) -> System | None:
        """The System of the configuration (model, damping, bit-rock law, operating point).

        None when the configuration has no ``[bit_rock]`` table (modal analyses only), or
        has a ``[well]`` whose friction the model cannot carry (consistent mass, a
        ``[chain]`` without sections); :attr:`dynamics_note` then says why.
        """
        if self.config.bit_rock is None:
            return None
        try:
            return self.config.system(**self.overrides)
        except ConfigError as exc:
            if exc.key != "well":
                raise
            self.dynamics_note = f"not run: {exc.message}"
            return None

    @functools.cached_property
    def law(self) -> Any:
        """The bit-rock law of the System (None without a ``[bit_rock]`` table)."""
        return None if self.system is None else self.system.law

    @functools.cached_property
    def model(self) -> LumpedModel:
        """The discretized string."""
        if self.system is not None:
            return self.system.model
        return self.config.model(**self.overrides)

    @functools.cached_property
    def damping(self) -> RayleighDamping | ModelDamping:
        """The damping of the model, as :meth:`Config.system` sets it."""
        if self.system is not None:
            return self.system.damping
        damping: RayleighDamping | ModelDamping = self.config.model_damping(self.model)
        return damping

    @functools.cached_property
    def has_matrices(self) -> bool:
        """Whether the model has matrices [I], [K] (a lumped model): the report shows its
        modal analysis; otherwise (the distributed model) its grid and exact continuum."""
        return bool(self.model.has_matrices)

    @functools.cached_property
    def first_frequency(self) -> float:
        """omega_1 [rad/s]: the model's first mode (the wave model's: its exact continuum)."""
        if self.has_matrices:  # the modal analysis the report shows
            return float(self.modal.frequencies_rad[0])
        return self.model.first_frequency()

    @functools.cached_property
    def modal(self) -> ModalResults:
        """The first modes of the model."""
        count = min(self.requested_modes, self.model.dofs)
        return modal_analysis(self.model, count, string=self.config.string)

    @functools.cached_property
    def transient(self) -> Any:
        """The transient response at the operating point (None without law or operating point)."""
        op = self.config.operation
        no_speed = op.rpm is None and self.config.top_drive.has_set_speed
        if self.system is None or op.wob is None or no_speed:
            return None
        from torsio.analysis.simulation_options import SimulationOptions
        from torsio.analysis.transient import simulate

        options = SimulationOptions.from_config(self.config)
        return simulate(self.system, **options.kwargs())  # as simulate_config, on this System

    @functools.cached_property
    def comparison(self) -> ModalComparison | None:
        """The modes against the exact continuum (rigid BHA if the model keeps it rigid).

        None for a ``[chain]`` model: it has no drill-string, hence no continuum.
        """
        if self.config.string is None:
            return None
        return self.modal.compare()


@attrs.frozen
class ReportSection:
    """One part of the report: the same content as data and as a rich renderable.

    Attributes
    ----------
    key : str
        Key of the section in :func:`report_data`.
    title : str
        Heading in the terminal.
    data : dict
        JSON-ready plain data (numbers in SI units unless the key names another).
    body : rich renderable
        What the terminal shows under the title.
    """

    key: str
    title: str
    data: dict[str, Any]
    body: RenderableType

    def __rich__(self) -> RenderableType:
        return Group(Text(self.title, style="bold cyan"), self.body, Text(""))


class _ByWidth:
    """A renderable that picks a narrow or a wide layout from the console width."""

    def __init__(
        self,
        narrow: Callable[[], RenderableType],
        wide: Callable[[], RenderableType],
        min_wide: int = WIDE,
    ) -> None:
        self.narrow, self.wide, self.min_wide = narrow, wide, min_wide

    def __rich_console__(self, console: Console, options: ConsoleOptions) -> RenderResult:
        yield (self.wide if options.max_width >= self.min_wide else self.narrow)()


def _table(*columns: str, left: tuple[str, ...] = ()) -> Table:
    table = Table(
        box=box.SIMPLE_HEAD,
        pad_edge=False,
        show_edge=False,
        collapse_padding=True,
        header_style="bold",
    )
    for column in columns:  # Text: "[m]" in a header is a unit, not rich markup
        table.add_column(Text(column), justify="left" if column in left else "right")
    return table


def _diameter(value: float, units: DisplayUnits) -> str:
    """A diameter [m] in mm (SI) or in (field), four significant digits."""
    return units.number("diameter", value, ".4g")


def _number(value: float, digits: int = 4, scientific: bool = False) -> str:
    """``value`` to ``digits`` significant digits, exponents written short (1.715e4)."""
    text = f"{value:.{digits - 1}e}" if scientific else f"{value:.{digits}g}"
    if "e" in text:
        mantissa, exponent = text.split("e")
        text = f"{mantissa}e{int(exponent)}"
    return text
