"""The one protocol of a structural model: what analyzers and solvers may ask of any model.

torsio has two kinds of structural model, the lumped chain
(:class:`torsio.model.lumped.LumpedModel`: strategies A, B, C, consistent, mixed and a
``[chain]`` given directly) and the distributed model on a characteristic grid
(:class:`torsio.model.wave.WaveModel`: the ``wave`` strategy). Both satisfy
:class:`StructuralModel`, and code outside ``torsio.model`` reads a model only through
it: it asks a model for its numbers and its capabilities, never for its kind.

A model names the engines that run it (:class:`ModelEngines`) as importable
``"module:function"`` strings. The model layer sits below the analyzers and the solvers
and never imports them; :func:`resolve` imports an engine when it is called, so that
``torsio.analysis.transient.simulate`` and ``torsio.solvers.batch.simulate_batch`` hand a
run to ``resolve(system.model.engines.transient)`` and
``resolve(system.model.engines.batch)``.

Examples
--------
>>> from torsio.examples import ritto2017_string
>>> from torsio.model.discretize import StrategyC
>>> from torsio.model.wave import WaveStrategy
>>> lumped = StrategyC(dp_elements=5).discretize(ritto2017_string())
>>> grid = WaveStrategy().discretize(ritto2017_string())
>>> isinstance(lumped, StructuralModel), isinstance(grid, StructuralModel)
(True, True)
>>> round(lumped.first_frequency(), 4), round(grid.first_frequency(), 4)
(0.8205, 0.8215)
>>> lumped.linearizable, grid.linearizable, grid.time_step is None
(True, False, False)
>>> resolve(grid.engines.batch).__name__
'simulate_wave_batch'
"""

from __future__ import annotations

import importlib
import re
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

import attrs
import numpy as np

__all__ = ["ModelEngines", "StructuralModel", "resolve"]

_ENGINE_NAME = re.compile(r"^[A-Za-z_]\w*(\.[A-Za-z_]\w*)*:[A-Za-z_]\w*$")


def _check_engine_name(instance: Any, attribute: attrs.Attribute[str], value: str) -> None:
    if not isinstance(value, str) or not _ENGINE_NAME.match(value):
        raise ValueError(
            f"engine {attribute.name!r}: expected an importable 'module:function' name, "
            f"got {value!r}"
        )


@attrs.frozen
class ModelEngines:
    """The engines that run a model, as importable ``"module:function"`` names.

    Attributes
    ----------
    transient : str
        One run in time from an initial state: a function ``(system, options,
        initial_state=None, progress=None)`` of a System and its validated
        :class:`torsio.analysis.simulation_options.SimulationOptions` (options without a
        meaning for the model are not used), returning a ``TransientResults``.
    batch : str
        Many operating points, each from rest, for maps: a function ``(system, wob, rpm,
        options)`` of a System, the points and their
        :class:`torsio.solvers.batch_options.BatchOptions`, returning a ``BatchResults``.

    Examples
    --------
    >>> ModelEngines(transient="torsio.analysis.wave:simulate_wave", batch="solve")
    Traceback (most recent call last):
    ...
    ValueError: engine 'batch': expected an importable 'module:function' name, got 'solve'
    """

    transient: str = attrs.field(validator=_check_engine_name)
    batch: str = attrs.field(validator=_check_engine_name)


def resolve(name: str) -> Callable[..., Any]:
    """The function a ``"module:function"`` engine name stands for, imported now.

    >>> resolve("torsio.model.continuum:continuum_modes").__name__
    'continuum_modes'
    >>> resolve("torsio.model.continuum:no_such_engine")
    Traceback (most recent call last):
    ...
    LookupError: engine 'torsio.model.continuum:no_such_engine': module \
torsio.model.continuum has no function no_such_engine
    """
    module_name, _, function_name = name.partition(":")
    function = getattr(importlib.import_module(module_name), function_name, None)
    if not callable(function):
        raise LookupError(f"engine {name!r}: module {module_name} has no function {function_name}")
    return function


@runtime_checkable
class StructuralModel(Protocol):
    """What every structural model provides; analyzers and solvers read models through it.

    A new kind of structural model (one that is not a :class:`LumpedModel`, which every
    discretizer may return) provides these members, names its engines and registers its
    discretizer through the hook ``torsio_discretizers()``; nothing outside
    ``torsio.model`` then needs to know of it.

    ``isinstance(model, StructuralModel)`` checks that the members are there (not their
    types or values: the tests of each model do).
    """

    @property
    def strategy(self) -> str:
        """Name of the discretizer that built the model (``"C"``, ``"wave"``, ...)."""
        ...

    @property
    def dofs(self) -> int:
        """Degrees of freedom of a lumped model; grid nodes of a distributed one (reports)."""
        ...

    @property
    def node_depths(self) -> np.ndarray:
        """Measured depth of each degree of freedom or grid node [m], increasing."""
        ...

    @property
    def equivalent_stiffness(self) -> float:
        """k_eq [N m/rad] (Eq. 9): the static torsional stiffness seen at the bit, top held.

        The scale of the dimensionless weight on bit Pi_2 = W R / k_eq and of maps.
        """
        ...

    @property
    def bit_inertia(self) -> float:
        """Inertia of the body that carries the bit [kg m^2] (the time scale of a bit-rock
        law's slope at rest, :func:`torsio.analysis.budget.check_law_time_scale`)."""
        ...

    def first_frequency(self) -> float:
        """omega_1 [rad/s]: the first natural frequency, top held, undamped.

        Every default counted in periods reads it (through
        :func:`torsio.model.modal.first_natural_frequency`).
        """
        ...

    @property
    def linearizable(self) -> bool:
        """Whether the linear stability analysis (:mod:`torsio.analysis.stability`) applies."""
        ...

    @property
    def has_matrices(self) -> bool:
        """Whether the model is inertia and stiffness matrices [I], [K]: modal analysis
        (:func:`torsio.model.modal.modal_analysis`) applies. False: a distributed model,
        whose modes are the exact continuum of the string it represents."""
        ...

    @property
    def time_step(self) -> float | None:
        """The fixed time step of the model's own stepping [s] (no error tolerances);
        None when its engines choose their steps (rtol, atol)."""
        ...

    @property
    def engines(self) -> ModelEngines:
        """The engines that run the model (:func:`resolve` imports them)."""
        ...

    def describe(self) -> dict[str, Any]:
        """Plain data (JSON-ready) on what the model is, for reports."""
        ...


if TYPE_CHECKING:  # mypy checks that both kinds satisfy the protocol (no import at run time)
    from torsio.model.lumped import LumpedModel
    from torsio.model.wave import WaveModel

    def _both_kinds(lumped: LumpedModel, grid: WaveModel) -> tuple[StructuralModel, ...]:
        return lumped, grid
