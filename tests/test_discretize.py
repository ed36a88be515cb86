"""Discretizers A, B, C, consistent and mixed: the paper's numbers and convergence."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsio import (
    Bit,
    ConsistentMass,
    DrillPipe,
    DrillString,
    LumpedModel,
    MixedMass,
    StrategyA,
    StrategyB,
    StrategyC,
    continuum_modes,
    modal_analysis,
)
from torsio.errors import ConfigError
from torsio.model.discretize import split_count


def frequencies_hz(discretizer, string, count=None):
    return modal_analysis(discretizer.discretize(string), count).frequencies_hz


def observed_order(errors_coarse: float, errors_fine: float) -> float:
    """Convergence order from errors at element counts n and 2n."""
    return math.log2(abs(errors_coarse) / abs(errors_fine))


# --- strategy A ------------------------------------------------------------------------------
def test_strategy_a_inertia_and_stiffness_match_errata(ritto):
    # Source: ERRATA 1: k = G J_DP / L_DP = 324.86 N m/rad,
    # I = I_DP/3 + I_BHA = 665.61/3 + 233.78 = 455.65 kg m^2 (Eq. 5).
    model = StrategyA().discretize(ritto)
    assert model.dofs == 1
    assert model.stiffness[0, 0] == pytest.approx(324.86, abs=0.01)
    assert model.inertia[0, 0] == pytest.approx(455.65, abs=0.01)


def test_strategy_a_frequency_is_paper_value_and_2_8_percent_above_continuum(ritto):
    # Source: paper Section 3 with ERRATA 1: 0.1344 Hz, +2.8 % against the FEM 0.1307 Hz.
    f_a = frequencies_hz(StrategyA(), ritto)[0]
    assert round(float(f_a), 4) == 0.1344
    exact = continuum_modes(ritto, 1).frequencies_hz[0]
    assert round(100 * (f_a / exact - 1), 1) == 2.8


def test_one_element_model_is_k_over_i():
    # Source: analytic 1-DOF frequency sqrt(k/I).
    model = LumpedModel.from_chain([455.0], [325.0])
    assert modal_analysis(model).frequencies_rad[0] == pytest.approx(
        math.sqrt(325.0 / 455.0), rel=1e-14
    )


# --- strategy B with the drill pipes as one DOF (paper Fig. 4) ----------------------------------
@pytest.mark.parametrize("bha_elements", [2, 10, 50])
def test_strategy_b_one_dp_dof_first_frequency_about_8_percent_low(ritto, bha_elements):
    # Source: paper, Fig. 4 discussion: "remains with a difference of 8 % with respect to
    # the FEM results" whatever the BHA discretization.
    exact = continuum_modes(ritto, 1).frequencies_hz[0]
    f1 = frequencies_hz(StrategyB(dp_elements=1, bha_elements=bha_elements), ritto, 1)[0]
    assert -0.085 < f1 / exact - 1 < -0.075


def test_strategy_b_one_dp_dof_second_frequency_is_not_a_continuum_frequency(ritto, continuum30):
    # Source: paper, Fig. 4(a): the 2nd frequency converges to a value that does not
    # exist in the reference. Converged: changes < 0.01 % from 50 to 100 BHA elements; and
    # it is more than 2 % away from every exact frequency.
    f50 = frequencies_hz(StrategyB(dp_elements=1, bha_elements=50), ritto, 2)[1]
    f100 = frequencies_hz(StrategyB(dp_elements=1, bha_elements=100), ritto, 2)[1]
    assert abs(f100 / f50 - 1) < 1e-4
    nearest = continuum30.frequencies_hz[np.argmin(np.abs(continuum30.frequencies_hz - f100))]
    assert abs(f100 / nearest - 1) > 0.02
    assert abs(f100 / continuum30.frequencies_hz[1] - 1) > 1.0  # not the 2nd mode at all


# --- strategy C (paper Fig. 3) -----------------------------------------------------------------
def test_strategy_c_modes_1_to_3_converge_at_second_order(ritto, continuum_rigid):
    # Source: paper Fig. 3(a): modes 1-3 converge towards the reference with a rigid BHA;
    # order 2 is the analytic dispersion error of lumped-mass linear elements.
    exact = continuum_rigid.frequencies_hz[:3]
    errors = {
        n: frequencies_hz(StrategyC(dp_elements=n), ritto, 3) / exact - 1 for n in (5, 10, 20, 40)
    }
    for mode in range(3):
        sequence = [abs(errors[n][mode]) for n in (5, 10, 20, 40)]
        assert sequence == sorted(sequence, reverse=True)
        assert observed_order(errors[20][mode], errors[40][mode]) == pytest.approx(2.0, abs=0.05)
    assert abs(errors[5][0]) < 0.005  # "the first natural frequency is predicted very well"


def test_strategy_c_one_dof_is_eq_8(ritto):
    # Source: Eq. 8: one DOF with strategy C has I = I_DP/2 + I_BHA.
    model = StrategyC(dp_elements=1).discretize(ritto)
    assert model.inertia[0, 0] == pytest.approx(ritto.drill_pipe_inertia / 2 + ritto.bha_inertia)


# --- strategy B with both refined, consistent and mixed mass (paper Fig. 5) ----------------------
def test_strategy_b_120_30_modes_15_and_25_within_2_percent(ritto, continuum30):
    # Source: paper Fig. 5: modes 15 and 25 close to the reference with 120 DP + 30 BHA DOFs.
    model = StrategyB(dp_elements=120, bha_elements=30).discretize(ritto)
    assert model.dofs == 150
    errors = modal_analysis(model, 25).frequencies_hz / continuum30.frequencies_hz[:25] - 1
    assert abs(errors[14]) < 0.02 and abs(errors[24]) < 0.02
    assert errors[14] < 0 and errors[24] < 0  # lumped mass converges from below


def test_consistent_mass_bounds_from_above_at_the_same_order(ritto, continuum30):
    # Source: Rayleigh-Ritz: consistent-mass FE frequencies are upper bounds of the exact ones;
    # for linear elements their dispersion error is +(kh)^2/24 against -(kh)^2/24 for lumped
    # mass, i.e. the same second order and about the same size.
    exact = continuum30.frequencies_hz[:25]
    lumped = frequencies_hz(StrategyB(dp_elements=120, bha_elements=30), ritto, 25) / exact - 1
    consistent = (
        frequencies_hz(ConsistentMass(dp_elements=120, bha_elements=30), ritto, 25) / exact - 1
    )
    assert np.all(consistent > 0)
    np.testing.assert_allclose(np.abs(consistent[[14, 24]]), np.abs(lumped[[14, 24]]), rtol=0.1)


def test_mixed_mass_is_fourth_order_preasymptotically_and_far_more_accurate(ritto, continuum30):
    # Source: analytic dispersion of the averaged mass matrix in a uniform shaft,
    # omega_h = omega (1 - (kh)^4/480), against (1 -+ (kh)^2/24) for lumped/consistent mass.
    # The end node (bit) and section junctions add an O(h^2) term with a small constant, so
    # the observed order falls from 4 towards 2 as h -> 0 (measured, docs/strategies.md).
    # Measured: from 80 + 20 elements on, modes 15 and 25 are 20-50x closer than lumped mass
    # (at 40 + 10, with 1.6 elements per half wave of mode 25, only 5x).
    exact = continuum30.frequencies_hz[:25]
    mixed, lumped = [], []
    for n, m in ((40, 10), (80, 20), (160, 40)):
        mixed.append(
            frequencies_hz(MixedMass(dp_elements=n, bha_elements=m), ritto, 25) / exact - 1
        )
        lumped.append(
            frequencies_hz(StrategyB(dp_elements=n, bha_elements=m), ritto, 25) / exact - 1
        )
    for mode in (14, 24):
        assert observed_order(mixed[0][mode], mixed[1][mode]) > 3.0
        for level in (1, 2):
            assert abs(mixed[level][mode]) < abs(lumped[level][mode]) / 20


def test_dofs_needed_for_1_percent_on_mode_25(ritto, continuum30):
    # Measured claim (docs/strategies.md): to bring mode 25 within 1 % the mixed mass matrix
    # needs fewer DOFs than lumped (B) or consistent mass, at equal DP/BHA split 4:1.
    exact = continuum30.frequencies_hz[24]

    def dofs_needed(cls):
        for total in range(30, 400, 5):
            dp = round(total * 0.8)
            f = frequencies_hz(cls(dp_elements=dp, bha_elements=total - dp), ritto, 25)[24]
            if abs(f / exact - 1) < 0.01:
                return total
        return None

    needed = {cls.name: dofs_needed(cls) for cls in (StrategyB, ConsistentMass, MixedMass)}
    assert needed["mixed"] < needed["B"] and needed["mixed"] < needed["consistent"]


# --- invariants -------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "discretizer",
    [
        StrategyA(),
        StrategyB(dp_elements=7, bha_elements=4),
        StrategyC(dp_elements=6),
        ConsistentMass(dp_elements=5, bha_elements=3),
        MixedMass(dp_elements=5, bha_elements=3),
    ],
)
def test_matrices_symmetric_and_positive_definite(ritto, discretizer):
    model = discretizer.discretize(ritto)
    for matrix in (model.inertia, model.stiffness):
        np.testing.assert_array_equal(matrix, matrix.T)
        assert np.all(np.linalg.eigvalsh(matrix) > 0)
    # the chain is tied to the top only through k_1: [K] 1 = k_1 e_1
    top = model.top_stiffness
    assert top[0] > 0 and np.allclose(top[1:], 0.0, atol=1e-9 * top[0])


@pytest.mark.parametrize(
    ("cls", "top_fraction"), [(StrategyB, 1 / 2), (ConsistentMass, 2 / 3), (MixedMass, 7 / 12)]
)
def test_total_inertia_is_conserved(ritto, cls, top_fraction):
    # Source: conservation of mass: 1^T [I] 1 = sum of rho J L over every section, less the
    # entries of the prescribed top node, which belong to the first element m_1: m_1/2 for
    # lumped mass, (2 + 1 + 1)/6 m_1 for consistent mass, the average 7/12 m_1 for mixed.
    model = cls(dp_elements=10, bha_elements=4).discretize(ritto)
    top_share = ritto.sections[0].inertia / 10 * top_fraction
    total = sum(s.inertia for s in ritto.sections)
    assert model.total_inertia == pytest.approx(total - top_share, rel=1e-12)


def test_splitting_a_section_into_identical_halves_gives_the_same_model(ritto):
    # Two identical halves with 60 elements each are the same chain as one section with 120.
    dp = ritto.sections[0]
    half = DrillPipe(od=dp.od, id=dp.id, length=dp.length / 2, material=dp.material)
    split = DrillString([half, half, *ritto.sections[1:]])
    whole = StrategyB(section_elements=[120, 11, 19]).discretize(ritto)
    halves = StrategyB(section_elements=[60, 60, 11, 19]).discretize(split)
    np.testing.assert_allclose(
        modal_analysis(halves).frequencies_rad, modal_analysis(whole).frequencies_rad, rtol=1e-10
    )


def test_equivalent_stiffness_is_the_series_stiffness(ritto):
    # Source: Eq. 9 for a chain: 1/[K^-1]_NN = 1 / sum(1/k_i).
    model = StrategyB(dp_elements=4, bha_elements=3).discretize(ritto)
    series = 1.0 / sum(1.0 / s.stiffness for s in ritto.flexible_sections)
    assert model.equivalent_stiffness == pytest.approx(series, rel=1e-12)


# --- element counts -----------------------------------------------------------------------------
def test_bha_count_split_in_proportion_to_length(ritto):
    # Rule (discretize module docstring): largest remainders on wave travel time, >= 1 each.
    # HWDP 171.3 m and collars 294.9 m share 30 elements: 1 + 28*171.3/466.2 = 11.29 -> 11.
    assert split_count(30, ritto.bha_sections, "bha_elements") == [11, 19]
    assert sum(split_count(7, ritto.bha_sections, "bha_elements")) == 7


def test_max_element_length(ritto):
    model = StrategyB(max_element_length=100.0).discretize(ritto)
    assert model.details["elements"] == {
        "Drill pipes 5 1/2 in": 48,
        "HWDP 5 1/2 in": 2,
        "Drill collars, MWD and LWD tools 6 3/4 in": 3,
    }
    assert np.all(np.diff(np.concatenate([[0.0], model.node_depths])) <= 100.0 + 1e-9)


@pytest.mark.parametrize(
    ("factory", "key"),
    [
        (lambda: StrategyB(dp_elements=0), "dp_elements"),
        (lambda: StrategyB(dp_elements=2.5), "dp_elements"),
        (lambda: StrategyB(bha_elements=-1), "bha_elements"),
        (lambda: StrategyC(bha_elements=30), "bha_elements"),
        (lambda: StrategyA(dp_elements=5), "dp_elements"),
        (lambda: StrategyB(dp_elements=3, max_element_length=10.0), "discretization"),
        (lambda: StrategyB(max_element_length=-5.0), "max_element_length"),
        (lambda: StrategyB(section_elements=[1, 0, 1]), "section_elements[1]"),
    ],
)
def test_bad_element_options_name_the_key(factory, key):
    with pytest.raises(ConfigError) as info:
        factory()
    assert info.value.key == key


def test_too_few_bha_elements_for_its_sections(ritto):
    with pytest.raises(ConfigError, match="2 sections"):
        StrategyB(dp_elements=3, bha_elements=1).discretize(ritto)


def test_section_elements_length_must_match(ritto):
    with pytest.raises(ConfigError, match="expected one count per"):
        StrategyB(section_elements=[3, 3]).discretize(ritto)


def test_rigid_bha_strategies_need_drill_pipe():
    string = DrillString(
        [DrillPipe(od=0.2, id=0.1, length=100.0, bha=True), Bit(od=0.2, id=0.05, length=0.3)]
    )
    with pytest.raises(ConfigError, match="drill-pipe"):
        StrategyC(dp_elements=2).discretize(string)
