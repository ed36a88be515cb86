"""Short reprs: a model, a system or a results object prints on a line or two, no arrays."""

from __future__ import annotations

import numpy as np

from torsio import builtin_config
from torsio.analysis.energy import energy_balance
from torsio.analysis.transient import simulate
from torsio.model.modal import modal_analysis
from torsio.physics.system import System
from torsio.solvers.batch import simulate_batch


def assert_short(text: str, *needles: str) -> None:
    assert len(text) < 400 and "array(" not in text and "\n" not in text, text
    for needle in needles:
        assert needle in text, (needle, text)


def test_model_and_system_reprs(ten_dof: System, chain_with_own_dampers: System) -> None:
    # ten_dof: strategy C with 10 drill-pipe elements, rigid BHA on the last node (conftest)
    assert_short(repr(ten_dof.model), "strategy 'C'", "10 DOFs")
    assert_short(repr(ten_dof), "System('Ritto et al. (2017)'", "10 DOFs", "100 rpm")
    assert_short(repr(ten_dof.string), "4 sections", "'Drill bit 8 1/2 in'")
    assert_short(repr(chain_with_own_dampers.model), "3 DOFs", "own dampers")
    large = builtin_config().system(strategy="B", dp_elements=400)
    assert_short(repr(large), "DOFs")


def test_results_reprs(one_dof: System) -> None:
    results = simulate(one_dof.at(rpm=60.0), duration=10.0)
    assert_short(repr(results), "samples over 10 s", "S_SS")
    assert_short(repr(energy_balance(results)), "relative residual")
    batch = simulate_batch(one_dof, np.array([50e3, 100e3]), np.array([60.0, 60.0]))
    assert_short(repr(batch), "2 points", "0 failed")
    modal = modal_analysis(one_dof.model, string=one_dof.string)
    assert_short(repr(modal), "strategy A", "1 DOFs")
    assert_short(repr(modal.compare()), "rigid-BHA continuum")
