"""The growth of a small perturbation in an axial transient, shared by the transient tests
(tests/test_axial_transient.py) and the chain stability tests
(tests/test_axial_chain_stability.py): a run from the perturbed steady state, every step
sampled, and the growth rate of its envelope."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsio.analysis.axial_transient import simulate_axial
from torsio.analysis.transient_results import TransientResults


def perturbed_run(
    assembly: Any, bit: Any, wob: float, rpm: float, duration: float, perturbation: float,
    **options: Any,
) -> TransientResults:  # fmt: skip
    """The run of ``duration`` [s] from steady drilling, the bit speed raised by
    ``perturbation``, every step sampled (a window of 1 s; ``options`` to simulate_axial)."""
    return simulate_axial(
        assembly,
        bit,
        wob,
        rpm,
        duration=duration,
        window=1.0,
        start="steady",
        perturbation=perturbation,
        samples=10**9,
        **options,
    )


def envelope_rate(run, signal: str, reference: float, omega: float, t0: float, t1: float):
    """Slope of log max |x − reference| over successive periods 2π/ω in [t0, t1]."""
    t, x = run.signal("time"), run.signal(signal) - reference
    period = 2 * math.pi / omega
    edges = np.arange(t0, t1 - 0.999 * period, period)
    peaks = [np.abs(x[(t >= e) & (t < e + period)]).max() for e in edges]
    return float(np.polyfit(edges + period / 2, np.log(peaks), 1)[0])
