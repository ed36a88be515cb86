"""An axial assembly is the torsional core's LumpedModel with axial rows (model/axial_rows.py).

References: the chain's matrices by construction (chain_matrix of the springs, the paper's
Eq. 6-7), IEEE 754 rounding of a sum, the closed form ω = √(k/I) of one node on one spring,
scipy's dense generalized eigensolver, and the [chain] table's own torsional model.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg
from axial_files import pipe_chain

from torsio.errors import ConfigError
from torsio.examples import rgd_two_dof_config
from torsio.model.axial_assembly import (
    assembly_description,
    axial_chain,
    rgd_two_dof_example,
    tube_section,
)
from torsio.model.axial_rows import AxialRows
from torsio.model.lumped import LumpedModel, chain_matrix
from torsio.model.modal import modal_analysis
from torsio.report.axial import torsional_frequencies


def test_the_chains_springs_and_dampers_come_back_as_given():
    # k_i (i >= 1) and c_i are stored as they are (-[K]_(i-1,i), the top damper) and k_0
    # with the chain (top_spring): every one exact. Through [K] alone k_0 comes back as
    # (k_0 + k_1) - k_1, here 0.10000000000000003: one rounding of the sum away
    springs, dampers = np.array([0.1, 0.2, 0.7]), np.array([0.3, 0.01, 0.02])
    model = LumpedModel.from_chain([1.0, 2.0, 3.0], springs, dampings=dampers)
    np.testing.assert_array_equal(model.springs, springs)
    np.testing.assert_array_equal(model.dampers, dampers)
    bare = LumpedModel(model.inertia, model.stiffness, model.node_depths)
    assert bare.springs[0] != springs[0]
    assert abs(bare.springs[0] - springs[0]) <= np.finfo(float).eps * (springs[0] + springs[1])
    with pytest.raises(ConfigError) as info:  # a top spring [K] does not have
        LumpedModel(model.inertia, model.stiffness, model.node_depths, top_spring=0.2)
    assert info.value.key == "top_spring"
    # the JSON of a run gives the file's springs back
    chain = axial_chain([1.0, 2.0], [324.857, 698.063], [1.0, 1.0], axial_stiffnesses=[1.0, 1.0])
    assert assembly_description(chain)["stiffnesses"] == [324.857, 698.063]
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
    # a LumpedModel with axial rows is a lumped model: its modes are those of [K], [I],
    # here against scipy's dense generalized eigensolver of the same matrices
    pipe = tube_section(900.0, 2.1e11, 8.1e10, 7850.0, 3.4e-3, 1.5e-5)
    chain = pipe_chain(6, pipe, 29981.3, 230.0)
    dense = np.sqrt(scipy.linalg.eigh(chain.stiffness, chain.inertia, eigvals_only=True))
    np.testing.assert_allclose(modal_analysis(chain).frequencies_rad, dense, rtol=1e-12)
    hz = np.array(torsional_frequencies(chain))
    np.testing.assert_allclose(2 * math.pi * hz, dense, rtol=1e-12)
    # the nodes at the bottoms of the 900 m / 6 = 150 m elements
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
        (  # the masses' count is checked first, not the springs' against the masses
            lambda: axial_chain([1.0, 1.0], [1.0, 1.0], [1.0], axial_stiffnesses=[1.0, 1.0]),
            "chain.masses",
        ),
        (
            lambda: LumpedModel.from_chain([1.0], [1.0], drag=[5.0]).with_axial(AxialRows([1.0])),
            "chain.drag",
        ),
        (  # not a chain: node 2 tied to the top too
            lambda: LumpedModel(
                np.eye(2), np.array([[3.0, -1.0], [-1.0, 2.0]]), [1.0, 2.0]
            ).with_axial(AxialRows([1.0, 1.0])),
            "discretization.strategy",
        ),
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


def test_each_engine_refuses_the_chain_it_cannot_move():
    from torsio.analysis.axial_transient import simulate_axial
    from torsio.axial.rgd import rgd_example
    from torsio.physics.laws import ConstantTorque
    from torsio.physics.system import System

    torsional = LumpedModel.from_chain([455.65], [324.857])
    with pytest.raises(ConfigError) as info:
        simulate_axial(torsional, rgd_example(), 100e3, 60.0, duration=1.0, window=0.5)
    assert info.value.key == "chain.masses"
    with pytest.raises(ConfigError) as info:  # the torsional engines would not move it axially
        System(model=rgd_two_dof_example(), law=ConstantTorque(torque_on_bit=1.0), bit_radius=0.108)
    assert info.value.key == "model" and "simulate_axial" in info.value.message
    assert (
        System(model=torsional, law=ConstantTorque(torque_on_bit=1.0), bit_radius=0.108).model
        is torsional
    )


def test_empty_dampers_are_none():
    # dampings=[] and axial_dampings=[] both mean no dampers, as in a [chain] file
    chain = axial_chain([1.0], [2.0], [3.0], dampings=[], axial_dampings=[])
    assert chain.dampers.tolist() == [0.0] and chain.axial.dampings.tolist() == [0.0]


def test_a_discretizers_chain_drills_as_the_two_dof_model():
    # strategy A of the built-in string is the torsional chain of the 2-DOF model of
    # docs/axial.md (I = 455.65 kg m², k = 324.857 N m/rad there: within half their last
    # digit); with its mass M = 29981.3 kg and no dampers the linearization of steady
    # drilling is the 2-DOF model's to that rounding (1.1e-5 relative at most in I): the
    # growth rate within 1e-5 (measured 3e-9: the unstable root is the axial mode's)
    from torsio import StrategyA, ritto2017_string
    from torsio.axial.rgd import rgd_example
    from torsio.axial.stability import drilling_stability
    from torsio.model.axial_assembly import two_dof_assembly

    chain = StrategyA().discretize(ritto2017_string()).with_axial(AxialRows([29981.3]))
    np.testing.assert_allclose(chain.node_inertias, [455.65], rtol=0, atol=0.005)
    np.testing.assert_allclose(chain.springs, [324.857], rtol=0, atol=0.0005)
    ours = drilling_stability(chain, rgd_example(), 100e3, 90.0)
    reference = drilling_stability(
        two_dof_assembly(455.65, 324.857, 29981.3), rgd_example(), 100e3, 90.0
    )
    assert ours.growth_rate == pytest.approx(reference.growth_rate, rel=1e-5)
    assert ours.stable == reference.stable
