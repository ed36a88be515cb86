"""Axial-torsional transients with the RGD bit on the compiled engine.

:func:`simulate_axial` runs a :class:`~torsio.axial.assembly.DrillingAssembly` drilling
with an :class:`~torsio.axial.rgd.RGDBit` under the weight W₀ with the top turning at Ω₀,
from rest or from the steady state (:mod:`torsio.axial.run_setup`), with the fixed-step
scheme of :mod:`torsio.axial.kernel`, and returns :class:`AxialTransient`: the window's
S_SS, axial severity, stuck and off-bottom fractions, mean ROP and MSE, the bit's
signals, and the growth rate of the linearization of steady drilling
(:func:`torsio.axial.stability.drilling_stability`; not with a prescribed bit rotation).

Default run length and window as torsio's other runs
(:func:`torsio.analysis.severity.default_times`): 40 and 15 periods of the first torsional
mode, top held.

Examples
--------
>>> from torsio.axial.assembly import rgd_two_dof_example
>>> from torsio.axial.rgd import rgd_example
>>> run = simulate_axial(rgd_two_dof_example(), rgd_example(), 100e3, 60.0, duration=2.0,
...                      window=1.0, start="steady", perturbation=0.0)
>>> round(run.rop_mean / run.steady.rop, 12), run.stick_fraction
(1.0, 0.0)
>>> sorted(run.to_dict())[:4]
['axial_severity', 'bit_speed_max', 'bit_speed_min', 'depth_of_cut_max']
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np
import scipy.linalg
from numpy.typing import NDArray

from torsio.analysis.severity import default_times
from torsio.axial import layouts as slot
from torsio.axial.assembly import DrillingAssembly
from torsio.axial.kernel import march
from torsio.axial.rgd import RGDBit
from torsio.axial.run_setup import (
    DEFAULT_STEPS_PER_PERIOD,
    BitRotation,
    RunOptions,
    RunSetup,
    WindowSummary,
    run_setup,
    summarize,
)
from torsio.axial.steady import SteadyDrilling
from torsio.axial.wave_assembly import WaveDrillingAssembly
from torsio.axial.wave_setup import WaveRunSetup, run_wave, wave_run_setup
from torsio.errors import ConfigError, SolverError
from torsio.model.lumped import chain_matrix

__all__ = ["AxialTransient", "first_torsional_frequency", "run_times", "simulate_axial"]


def first_torsional_frequency(assembly: DrillingAssembly | WaveDrillingAssembly) -> float:
    """ω₁ [rad/s] of the torsional chain (or the distributed pipe's exact one), top held,
    undamped."""
    if isinstance(assembly, WaveDrillingAssembly):
        return float(assembly.torsional_frequencies(1)[0])
    stiffness = chain_matrix(assembly.stiffnesses)
    values = scipy.linalg.eigh(stiffness, np.diag(assembly.inertias), eigvals_only=True)
    return float(math.sqrt(values[0]))


def run_times(
    assembly: DrillingAssembly | WaveDrillingAssembly, duration: float | None, window: float | None
) -> tuple[float, float]:
    """(duration, window) [s]: the given ones, or torsio's defaults (40 and 15 periods of
    ω₁; a given duration gets at most half of it as its default window)."""
    if duration is None or window is None:
        default_duration, default_window = default_times(first_torsional_frequency(assembly))
        if window is None:
            window = default_window if duration is None else min(default_window, 0.5 * duration)
        if duration is None:
            duration = default_duration
    return float(duration), float(window)


def run_kernel(
    setup: RunSetup | WaveRunSetup, samples: NDArray[np.float64], sample_every: int
) -> NDArray:
    """Run the compiled loop of ``setup``, lumped or distributed (its state arrays change);
    the stats vector.

    Raises SolverError when the history could not give the delay.
    """
    if isinstance(setup, WaveRunSetup):
        stats = run_wave(setup, samples, sample_every)
        state = [setup.axial_p, setup.torsional_p, setup.bha]
    else:
        settings = setup.settings.copy()
        settings[slot.SAMPLE_EVERY] = sample_every
        stats = np.zeros(len(slot.STATS))
        march(
            setup.bit,
            setup.torsional,
            setup.axial,
            settings,
            setup.theta,
            setup.omega,
            setup.u,
            setup.v,
            setup.history,
            setup.cursor,
            stats,
            samples,
        )
        state = [setup.u, setup.theta]
    if stats[slot.FAILED]:
        done = stats[slot.STEPS_DONE]
        raise SolverError(
            f"the bit's history did not hold the delay at step {int(done)} "
            f"(t = {done * setup.step:.6g} s): non-finite state or a stalled bit"
        )
    if not all(np.isfinite(values).all() for values in state):
        raise SolverError("the run produced non-finite values; try a smaller step")
    return stats


_SUMMARY_NAMES = frozenset(attrs.fields_dict(WindowSummary))


@attrs.frozen(eq=False)
class AxialTransient:
    """One axial-torsional run with the RGD bit.

    Attributes
    ----------
    wob, rpm : float
        W₀ [N] and Ω₀ [rev/min].
    steady : SteadyDrilling
        The steady drilling state of (W₀, Ω₀).
    summary : WindowSummary
        The window's outputs (also as attributes: ``severity``, ``rop_mean`` ...).
    growth_rate : float or None
        The rightmost root's real part [1/s] of the linearization about the steady state
        (None with a prescribed bit rotation or when not asked).
    step, duration, window : float
        The step h, the run's length and its window [s].
    start : str
        ``"rest"`` or ``"steady"``.
    samples : ndarray (k, 10)
        The bit's signals, columns :data:`torsio.axial.layouts.SAMPLE_COLUMNS`.
    """

    wob: float
    rpm: float
    steady: SteadyDrilling
    summary: WindowSummary
    growth_rate: float | None
    step: float
    duration: float
    window: float
    start: str
    samples: NDArray[np.float64]

    def __getattr__(self, name: str) -> Any:
        if name in _SUMMARY_NAMES:
            return getattr(self.summary, name)
        raise AttributeError(name)

    def signal(self, name: str) -> NDArray[np.float64]:
        """One column of :attr:`samples` by name (e.g. ``"bit_speed"``)."""
        return self.samples[:, slot.SAMPLE_COLUMNS.index(name)]

    def to_dict(self) -> dict[str, Any]:
        """DESIGN.md's JSON keys: ``wob``, ``rpm``, ``severity``, ``rop_mean`` (m/s),
        ``mse_mean`` (Pa; null when the bit did not advance), ``off_bottom_fraction``,
        ``stick_fraction``, ``axial_severity``, ``steady_state``, ``growth_rate`` and more."""
        data: dict[str, Any] = {"wob": self.wob, "rpm": self.rpm}
        for key, value in attrs.asdict(self.summary).items():
            data[key] = value if math.isfinite(value) else None
        data.update(
            steady_state=self.steady.to_dict(),
            growth_rate=self.growth_rate,
            step=self.step,
            duration=self.duration,
            steady_window=self.window,
            start=self.start,
        )
        return data

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"AxialTransient(wob={self.wob:g} N, rpm={self.rpm:g}, S_SS={s.severity:.4g}, "
            f"stuck={s.stick_fraction:.3g}, rop={s.rop_mean * 3600:.4g} m/h)"
        )


def simulate_axial(
    assembly: DrillingAssembly | WaveDrillingAssembly,
    bit: RGDBit,
    wob: float,
    rpm: float,
    *,
    duration: float | None = None,
    window: float | None = None,
    start: str = "rest",
    perturbation: float = 1e-3,
    step: float | None = None,
    steps_per_period: int = DEFAULT_STEPS_PER_PERIOD,
    samples: int = 4000,
    bit_rotation: BitRotation | None = None,
    growth_rate: bool = True,
) -> AxialTransient:
    """Run the assembly drilling at ``wob`` [N] and ``rpm`` [rev/min].

    Parameters
    ----------
    assembly : DrillingAssembly or WaveDrillingAssembly
        A lumped chain (:mod:`torsio.axial.kernel`) or a distributed pipe above a lumped
        BHA (:mod:`torsio.axial.wave_kernel`).
    duration, window : float, optional
        Run length and steady window at its end [s] (:func:`run_times`).
    start : str
        ``"rest"`` (default) or ``"steady"`` with the bit speed raised by ``perturbation``.
    step, steps_per_period : float, int
        The step rule of :mod:`torsio.axial.run_setup` (lumped) or
        :mod:`torsio.axial.wave_setup` (distributed).
    samples : int
        About how many rows of signals to keep (0: none; every step at most).
    bit_rotation : BitRotation, optional
        A prescribed bit rotation instead of the torsional chain (lumped assemblies only).
    growth_rate : bool
        Compute the linear growth rate (any assembly; not with ``bit_rotation``, whose
        torsional chain is not integrated).
    """
    duration, window = run_times(assembly, duration, window)
    options = RunOptions(duration, window, start, perturbation, step, steps_per_period)
    setup: RunSetup | WaveRunSetup
    if isinstance(assembly, WaveDrillingAssembly):
        if bit_rotation is not None:
            raise ConfigError(
                "bit_rotation",
                f"{bit_rotation!r} given; a prescribed rotation applies to lumped assemblies "
                "only (expected None with a WaveDrillingAssembly)",
            )
        setup = wave_run_setup(assembly, bit, wob, rpm, options)
    else:
        setup = run_setup(assembly, bit, wob, rpm, options, bit_rotation)
    every = max(1, setup.steps // samples) if samples > 0 else 0
    rows = (setup.steps - 1) // every + 1 if every else 0
    table = np.zeros((rows, len(slot.SAMPLE_COLUMNS)))
    stats = run_kernel(setup, table, every)
    rate = None
    if growth_rate and isinstance(assembly, DrillingAssembly) and bit_rotation is None:
        from torsio.axial.stability import drilling_stability

        rate = drilling_stability(assembly, bit, wob, rpm, count=1).growth_rate
    return AxialTransient(
        wob=float(wob),
        rpm=float(rpm),
        steady=setup.steady,
        summary=summarize(stats, setup, bit),
        growth_rate=rate,
        step=setup.step,
        duration=duration,
        window=setup.window_steps * setup.step,
        start=start,
        samples=table,
    )
