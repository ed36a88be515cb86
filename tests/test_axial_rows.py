"""An axial assembly is the torsional core's LumpedModel with axial rows (model/axial_rows.py).

References: the chain's matrices by construction (chain_matrix of the springs, the paper's
Eq. 6-7), IEEE 754 rounding for the one spring read back through a sum, the closed form
ω = √(k/I) of one node on one spring, and the [chain] table's own torsional model.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsio.axial.assembly import axial_chain, pipe_assembly, rgd_two_dof_example
from torsio.axial.wave_assembly import PipeSection
from torsio.errors import ConfigError
from torsio.examples import rgd_two_dof_config
from torsio.model.axial_rows import AxialRows
from torsio.model.lumped import LumpedModel, chain_matrix
from torsio.model.modal import modal_analysis
from torsio.report.axial import torsional_frequencies


def test_the_chains_springs_and_dampers_read_back_from_its_matrices():
    # k_i (i >= 1) and c_i are stored as they are (-[K]_(i-1,i), the top damper): exact;
    # k_0 comes back through the row sum (k_0 + k_1) - k_1, one rounding of the sum away
    springs, dampers = np.array([0.1, 0.2, 0.7]), np.array([0.3, 0.01, 0.02])
    model = LumpedModel.from_chain([1.0, 2.0, 3.0], springs, dampings=dampers)
    np.testing.assert_array_equal(model.springs[1:], springs[1:])
    assert abs(model.springs[0] - springs[0]) <= np.finfo(float).eps * (springs[0] + springs[1])
    np.testing.assert_array_equal(model.dampers, dampers)
    np.testing.assert_array_equal(chain_matrix(model.springs), model.stiffness)
    np.testing.assert_array_equal(model.node_inertias, [1.0, 2.0, 3.0])
    undamped = LumpedModel.from_chain([1.0], [2.0])
    assert undamped.dampers.tolist() == [0.0] and not np.signbit(undamped.dampers).any()


def test_a_chain_file_gives_one_model_turning_and_moving_axially():
    # the [chain] of rgd_2dof.toml: its axial assembly is the torsional model of the same
    # table (ChainConfig.model) with axial rows, matrix for matrix
    config = rgd_two_dof_config()
    assembly, torsional = config.axial.assembly, config.chain.model()
    for name in ("inertia", "stiffness", "damping", "top_damping", "node_depths"):
        np.testing.assert_array_equal(getattr(assembly, name), getattr(torsional, name))
    assert assembly.first_frequency() == torsional.first_frequency()
    assert assembly.axial.masses.tolist() == [29981.3] and assembly.axial.hook == "weight"
    assert torsional.axial is None
    # one node on one spring, top held: ω = √(k/I) (closed form)
    omega = math.sqrt(324.857 / 455.65)
    assert assembly.first_frequency() == pytest.approx(omega, rel=1e-14)
    assert torsional_frequencies(assembly) == pytest.approx([omega / (2 * math.pi)], rel=1e-14)


def test_the_modal_analysis_of_an_axial_chain_is_its_torsional_chains():
    # a LumpedModel with axial rows is a lumped model: its modes are those of [K], [I]
    pipe = PipeSection(900.0, 2.1e11, 8.1e10, 7850.0, 3.4e-3, 1.5e-5)
    chain = pipe_assembly(6, pipe, 29981.3, 230.0)
    bare = LumpedModel(chain.inertia, chain.stiffness, chain.node_depths)
    ours, theirs = modal_analysis(chain), modal_analysis(bare)
    np.testing.assert_array_equal(ours.frequencies_rad, theirs.frequencies_rad)
    np.testing.assert_allclose(chain.node_depths, 150.0 * np.arange(1, 7), rtol=1e-15)
    assert "axial rows, hook weight" in repr(chain)


@pytest.mark.parametrize(
    ("build", "key"),
    [
        (lambda: AxialRows([]), "chain.masses"),
        (lambda: AxialRows([1.0, -2.0]), "chain.masses[1]"),
        (lambda: AxialRows([1.0, 2.0], stiffnesses=[1e6]), "chain.axial_stiffnesses"),
        (lambda: AxialRows([1.0], stiffnesses=[1e6], dampings=[-1.0]), "chain.axial_dampings[0]"),
        (lambda: AxialRows([1.0], dampings=[1.0, 2.0]), "chain.axial_dampings"),
        (lambda: AxialRows([1.0], hook="crane"), "axial.hook"),
        (lambda: AxialRows([1.0], hook="speed"), "axial.hook"),
        (lambda: axial_chain([], [], []), "chain.inertias"),
        (lambda: axial_chain([1.0], [0.0], [1.0]), "chain.stiffnesses[0]"),
        (lambda: axial_chain([1.0], [1.0], [1.0], dampings=[1.0, 2.0]), "chain.dampings"),
        (lambda: axial_chain([1.0, 1.0], [1.0, 1.0], [1.0]), "chain.masses"),
        (
            lambda: LumpedModel(
                np.array([[2.0, 1.0], [1.0, 2.0]]), np.eye(2), [1.0, 2.0]
            ).with_axial(AxialRows([1.0, 1.0])),
            "discretization.strategy",
        ),
    ],
)
def test_bad_axial_rows_name_the_key(build, key):
    with pytest.raises(ConfigError) as info:
        build()
    assert info.value.key == key


def test_a_torsional_chain_has_no_axial_rows_to_drill_with():
    from torsio.axial.rgd import rgd_example
    from torsio.axial.transient import simulate_axial

    torsional = LumpedModel.from_chain([455.65], [324.857])
    with pytest.raises(ConfigError) as info:
        simulate_axial(torsional, rgd_example(), 100e3, 60.0, duration=1.0, window=0.5)
    assert info.value.key == "chain.masses"
    assert rgd_two_dof_example().axial is not None
