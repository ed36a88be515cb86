"""The runs of a configuration, whatever its model: the engine that runs it, the options
that engine takes, its transient and its map.

A file whose bit law declares ``needs_axial`` (:func:`torsio.physics.laws.law_capabilities`,
the RGD bit) or whose chain has masses runs on the axial engine
(:mod:`torsio.analysis.axial_transient`, :mod:`torsio.analysis.axial_maps`); every other on the
torsional
engines (:mod:`torsio.analysis.transient`, :mod:`torsio.analysis.maps`). Both give the
same kinds of results: a transient with its signals by name, CSV, plot and rig recording,
and a :class:`~torsio.analysis.map_results.SeverityMap` with its critical curve, files
and optional layers. :func:`run_capabilities` says which options the engine cannot take,
and why, so that a command refuses them naming the flag and what would work.

Examples
--------
>>> from torsio.examples import rgd_two_dof_config
>>> capabilities = run_capabilities(rgd_two_dof_config())
>>> capabilities.engine, "growth_rate" in capabilities.cannot, "rtol" in capabilities.cannot
('axial', False, True)
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import attrs
import numpy as np

from torsio.analysis.severity import DEFAULT_STICK_THRESHOLD
from torsio.errors import ConfigError
from torsio.physics.laws import law_capabilities

if TYPE_CHECKING:
    from torsio.analysis.transient_results import TransientResults

__all__ = ["RunCapabilities", "config_map", "run_capabilities", "simulate_axial_config"]

_FIXED_STEP = (
    "the axial engine steps the file's assembly with a fixed step (simulation.step) and "
    "no error control"
)
_ASSEMBLY = (
    "the axial engine runs the assembly of the file as read ([chain] masses, or [[section]] "
    "lumped by its [discretization] and [axial]): read it with other options "
    "(torsio.config.reading.rediscretized, as the command line's --strategy does)"
)
_AXIAL_CANNOT = {
    "strategy": _ASSEMBLY,
    "dp_elements": _ASSEMBLY,
    "bha_elements": _ASSEMBLY,
    "method": _FIXED_STEP,
    "rtol": _FIXED_STEP,
    "atol": _FIXED_STEP,
    "steady_tolerance": f"{_FIXED_STEP}: every point runs to its end",
    "output_step": "the axial engine keeps about 4000 samples of its run, at its step",
    "pi1": "an axial map is over weight on bit and rotary speed: use --wob and --rpm",
    "pi2": "an axial map is over weight on bit and rotary speed: use --wob and --rpm",
    "on_failure": "a failed run of the axial engine stops the map",
    "initial_state": "the axial engine starts from rest or the steady state (simulation.start)",
}
"""What the axial engine cannot take, by option, and what to do instead."""


SINGLE_RUNS_ONLY = (
    "apply to single runs (torsio simulate, report) only: the map integrates every point "
    "with its own engine (--engine), reads S_SS from the extremes of the bit speed and "
    "counts the bit stuck below 0.1 Ω, as every map"
)
"""What a map says of the ``[simulation]`` keys it does not use."""

_AXIAL_MAP_OPTIONS = ("duration", "threshold", "refine", "timeout", "chunk_size")
"""The map options :func:`torsio.analysis.axial_maps.axial_map` takes by the same name."""


@attrs.frozen
class RunCapabilities:
    """What the engine of a configuration takes.

    Attributes
    ----------
    engine : str
        ``"axial"`` or ``"torsional"``.
    cannot : dict
        Option name -> why the engine cannot take it and what would work.
    batch_engines : tuple of str or None
        The ``engine`` option's values it takes (None: every batch engine).
    """

    engine: str
    cannot: dict[str, str]
    batch_engines: tuple[str, ...] | None = None

    def refuse(self, given: dict[str, tuple[str, Any]]) -> None:
        """A ConfigError naming the flag of the first given option (``name: (flag,
        value)``; None: not given) the engine cannot take, and what would work."""
        for name, (flag, value) in given.items():
            if value is None:
                continue
            if name in self.cannot:
                raise ConfigError(flag, f"{self.cannot[name]}; remove it")
            if name == "engine" and self.batch_engines and value not in self.batch_engines:
                raise ConfigError(
                    flag, f"{value!r}: the {self.engine} engine is compiled (numba); use auto"
                )


def run_capabilities(config: Any) -> RunCapabilities:
    """What the engine of ``config`` takes (see the module documentation)."""
    if config.axial is None:
        return RunCapabilities(
            "torsional",
            {
                "growth_rate": "applies to axial runs, with a bit law that needs axial dynamics "
                '(law = "rgd"): a torsional run has no growth rate of steady drilling (torsio '
                "report gives its linear stability)"
            },
        )
    bit = config.axial.bit
    cannot = dict(_AXIAL_CANNOT)
    if not law_capabilities(getattr(bit, "law", bit))["needs_axial"]:
        cannot["growth_rate"] = (
            f"the {bit.name} law is a law of the torque alone (it does not declare "
            "needs_axial): its axial motion rests on the rock, and the linear stability is "
            "the torsional chain's (torsio report)"
        )
    return RunCapabilities("axial", cannot, ("auto", "numba"))


def default_wob_range(config: Any, torsional: str) -> str:
    """The default --wob of a map: ``torsional`` (START:STOP:N), or for a bit that cuts
    (RGD) 1.1 to 2 times the weight its wear flats carry (σ a l, below which it does not
    cut), 5 points."""
    if config.axial is None or not config.axial.bit.needs_axial:
        return torsional
    friction = config.axial.bit.friction_weight
    return f"{1.1 * friction:.6g}:{2 * friction:.6g}:5"


def simulate_axial_config(
    config: Any,
    wob: Any = None,
    rpm: Any = None,
    *,
    duration: float | None = None,
    steady_window: float | None = None,
    growth_rate: bool | None = None,
    stick_threshold: float | None = None,
    progress: Any = None,
) -> TransientResults:
    """The run of a configuration with axial dynamics at its operating point (``wob``,
    ``rpm`` override ``[operation]``), its ``[simulation]`` times and stick threshold
    unless given; progress on stderr after 2 s as every long run (``progress=False``:
    none)."""
    from torsio.analysis.axial_transient import simulate_axial
    from torsio.solvers.run_chunks import run_progress

    axial, times, point = config.axial, config.simulation.options, config.operating_point(wob, rpm)
    duration, steady_window = (
        duration or times.get("duration"),
        steady_window or times.get("steady_window"),
    )
    options = axial.run_options()
    if stick_threshold is not None:
        options["stick_threshold"] = stick_threshold
    with run_progress(progress) as report:
        return simulate_axial(axial.assembly, axial.bit, point["wob"], point["rpm"],
                              duration=duration, window=steady_window, **options,
                              growth_rate=growth_rate, progress=report)  # fmt: skip


def config_map(
    config: Any,
    wob: np.ndarray,
    rpm: np.ndarray,
    options: Any,
    *,
    discretization: dict[str, Any] | None = None,
    dimensionless: bool = False,
    executor: Any = None,
    progress: bool | Callable[[int, int], None] | None = None,
    rtol: float | None = None,
    note: Callable[[str], None] = print,
) -> Any:
    """The severity map of ``config`` over ``wob`` [N] x ``rpm`` (Pi_2 x Pi_1 when
    ``dimensionless``) with the map ``options``
    (:class:`~torsio.analysis.map_options.MapOptions`), on its engine; ``note(text)``
    says what of the file the map does not use; ``rtol``: the tolerance asked for
    explicitly (refused on a fixed-step model); ``discretization`` overrides
    ``[discretization]`` of a torsional model (an axial chain is lumped when the file is
    read: :func:`torsio.config.reading.rediscretized`)."""
    discretization = {k: v for k, v in (discretization or {}).items() if v is not None}
    if config.axial is not None:
        from torsio.analysis.axial_maps import axial_map

        run_capabilities(config).refuse(
            {key: (key, value) for key, value in discretization.items()}
        )

        axial = config.axial
        grow = axial.bit.needs_axial
        if grow:
            from torsio.axial.stability import growth_rate_skipped

            skipped = growth_rate_skipped(axial.assembly, axial.contacts)
            if skipped is not None:  # the same at every point: said once
                note(f"warning: {skipped}")
                grow = False
        chosen = {name: getattr(options, name) for name in _AXIAL_MAP_OPTIONS}
        run = axial.run_options()
        if run.pop("stick_threshold") != DEFAULT_STICK_THRESHOLD:  # as on every map
            note(f"[simulation] stick_threshold {SINGLE_RUNS_ONLY}")
        return axial_map(axial.assembly, axial.bit, wob, rpm, window=options.steady_window,
                         **chosen, **run, growth_rate=grow, executor=executor,
                         progress=progress)  # fmt: skip
    from torsio.analysis.maps import dimensionless_map, severity_map

    system = config.system(**discretization)
    simulation = dict(config.simulation.options)
    if system.model.time_step is not None:  # fixed steps, no integrator: --rtol is an error
        from torsio.analysis.wave import fixed_step_note

        unused = fixed_step_note(set(simulation) - {"method"}, {"--rtol (simulation.rtol)": rtol})
        if unused is not None:
            note(unused)
    single_run_only = sorted(set(simulation) & {"method", "output_step", "stick_threshold"})
    if single_run_only:
        note(f"[simulation] {', '.join(single_run_only)} {SINGLE_RUNS_ONLY}")
    run_on = {"executor": executor, "progress": progress}
    if dimensionless:
        return dimensionless_map(system, rpm, wob, options, **run_on)
    return severity_map(system, wob, rpm, options, **run_on)
