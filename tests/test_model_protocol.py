"""Both structural models satisfy the one model protocol (torsio.model.protocol).

Sources of the numbers:

* the paper's Table 1 (drill pipes 0.140/0.119 m x 4733.6 m, HWDP 0.140/0.076 m x 171.30 m,
  collars/MWD/LWD 0.171/0.071 m x 294.90 m) and G = 85.3 GPa, J = pi (D^4 - d^4) / 32;
* Eq. 9, k_eq = 1 / [K^-1]_(N,N), and for the continuum (or springs in series) the static
  stiffness 1 / sum(L / (G J)); ERRATA 1: k = G J_DP / L_DP = 324.86 N m/rad;
* the exact continuum of the stepped shaft, :func:`torsio.model.continuum.continuum_modes`
  (the paper's FEM first frequency 0.1307 Hz);
* the wave grid rounds each section's travel time to whole cells within 3e-4 (the default
  ``travel_time_tolerance``): its static stiffness and frequencies are those of the string
  as given to that tolerance, and exactly those of its grid string.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from torsio.errors import ConfigError
from torsio.examples import ritto2017_string
from torsio.model.continuum import continuum_modes
from torsio.model.discretize import ConsistentMass, MixedMass, StrategyA, StrategyB, StrategyC
from torsio.model.lumped import LUMPED_ENGINES, LumpedModel
from torsio.model.modal import first_natural_frequency
from torsio.model.protocol import ModelEngines, StructuralModel, resolve
from torsio.model.wave import WAVE_ENGINES, WaveStrategy

G = 85.3e9  # Pa (the paper)
TABLE_1 = [(0.140, 0.119, 4733.6), (0.140, 0.076, 171.30), (0.171, 0.071, 294.90)]
"""(outer diameter [m], inner diameter [m], length [m]) of the flexible sections, Table 1."""
GRID_TOLERANCE = 3e-4  # the wave grid's default travel-time tolerance


def _series_stiffness(sections) -> float:
    """1 / sum(L / (G J)) [N m/rad] of (od, id, length) sections in series, top held."""
    return 1.0 / sum(length / (G * math.pi * (od**4 - id_**4) / 32) for od, id_, length in sections)


K_DP = _series_stiffness(TABLE_1[:1])  # drill pipes alone: 324.86 N m/rad (ERRATA 1)
K_STRING = _series_stiffness(TABLE_1)  # drill pipes, HWDP and collars in series


@pytest.fixture(scope="module")
def string():
    return ritto2017_string()


@pytest.fixture(scope="module")
def models(string):
    """Every built-in kind: the lumped strategies, a [chain], the wave grid (two ways)."""
    return {
        "A": StrategyA().discretize(string),
        "B": StrategyB(dp_elements=6, bha_elements=3).discretize(string),
        "C": StrategyC(dp_elements=5).discretize(string),
        "consistent": ConsistentMass(dp_elements=6, bha_elements=3).discretize(string),
        "mixed": MixedMass(dp_elements=6, bha_elements=3).discretize(string),
        "chain": LumpedModel.from_chain([2782.25, 750.0, 471.9698], [698.063, 1080.0, 907.48]),
        "wave": WaveStrategy().discretize(string),
        "wave rigid BHA": WaveStrategy(rigid_bha=True).discretize(string),
    }


def test_the_paper_numbers_this_file_rests_on():
    assert K_DP == pytest.approx(324.86, abs=0.005)  # ERRATA 1


@pytest.mark.parametrize(
    "name", ["A", "B", "C", "consistent", "mixed", "chain", "wave", "wave rigid BHA"]
)
def test_every_model_satisfies_the_protocol(models, name):
    model = models[name]
    assert isinstance(model, StructuralModel)
    assert isinstance(model.strategy, str) and model.dofs >= 1
    assert model.node_depths.shape == (model.dofs,)
    assert model.equivalent_stiffness > 0 and model.first_frequency() > 0
    assert model.bit_inertia > 0
    assert isinstance(model.engines, ModelEngines)
    assert isinstance(model.linearizable, bool) and isinstance(model.has_matrices, bool)
    json.dumps(model.describe())  # plain data for reports
    # the one entry for omega_1 is the model's own method
    assert first_natural_frequency(model) == model.first_frequency()


def test_an_object_without_the_members_is_not_a_model():
    assert not isinstance(np.eye(2), StructuralModel)


def test_lumped_models_capabilities_and_engines(models):
    for name in ("A", "B", "C", "consistent", "mixed", "chain"):
        model = models[name]
        assert model.linearizable and model.has_matrices and model.time_step is None
        assert model.engines == LUMPED_ENGINES
        assert model.bit_inertia == model.inertia[-1, -1]


def test_wave_model_capabilities_and_engines(models):
    grid = models["wave"]
    assert not grid.linearizable and not grid.has_matrices
    assert grid.time_step == pytest.approx(1.4386e-3, abs=5e-8)  # docs/wave.md's default grid
    assert grid.engines == WAVE_ENGINES
    assert grid.bit_inertia == ritto2017_string().bit.inertia
    describe = grid.describe()
    assert describe["strategy"] == "wave" and describe["cells"] == [995, 36, 62]


# --- k_eq (Eq. 9) -----------------------------------------------------------------------------
def test_lumped_k_eq_is_eq_9(models):
    for name in ("A", "B", "C", "consistent", "mixed", "chain"):
        model = models[name]
        eq_9 = 1.0 / np.linalg.inv(model.stiffness)[-1, -1]  # Eq. 9 as the paper writes it
        assert model.equivalent_stiffness == pytest.approx(eq_9, rel=1e-12), name
    # a chain: springs in series
    assert models["chain"].equivalent_stiffness == pytest.approx(
        1.0 / (1 / 698.063 + 1 / 1080.0 + 1 / 907.48), rel=1e-12
    )


def test_lumped_k_eq_is_the_exact_static_stiffness_of_the_paper_string(models):
    # elements in series hold the static twist exactly, whatever their number
    for name in ("A", "C"):  # rigid BHA: the drill pipes alone
        assert models[name].equivalent_stiffness == pytest.approx(K_DP, rel=1e-12)
    for name in ("B", "consistent", "mixed"):  # every flexible section
        assert models[name].equivalent_stiffness == pytest.approx(K_STRING, rel=1e-12)


def test_wave_k_eq_is_the_continuum_static_stiffness(models):
    grid, rigid = models["wave"], models["wave rigid BHA"]
    assert grid.equivalent_stiffness == pytest.approx(K_STRING, rel=GRID_TOLERANCE)
    assert rigid.equivalent_stiffness == pytest.approx(K_DP, rel=GRID_TOLERANCE)
    # exactly that of the grid string (each section's length rounded to whole cells)
    on_grid = [(s.od, s.id, s.length) for s in grid.grid_string().flexible_sections]
    assert grid.equivalent_stiffness == pytest.approx(_series_stiffness(on_grid), rel=1e-12)


# --- omega_1 --------------------------------------------------------------------------------
def test_wave_first_frequency_is_the_exact_continuum(models, string):
    grid, rigid = models["wave"], models["wave rigid BHA"]
    exact = continuum_modes(string, 1).frequencies_rad[0]
    assert grid.first_frequency() == pytest.approx(exact, rel=GRID_TOLERANCE)
    assert exact / (2 * math.pi) == pytest.approx(0.1307, abs=5e-5)  # the paper's FEM
    on_grid = continuum_modes(grid.grid_string(), 1).frequencies_rad[0]
    assert grid.first_frequency() == pytest.approx(on_grid, rel=1e-14)
    exact_rigid = continuum_modes(string, 1, rigid_bha=True).frequencies_rad[0]
    assert rigid.first_frequency() == pytest.approx(exact_rigid, rel=GRID_TOLERANCE)


def test_lumped_first_frequency_is_its_first_mode(models):
    model = models["B"]
    eigenvalues = np.linalg.eigvals(np.linalg.solve(model.inertia, model.stiffness))
    assert model.first_frequency() == pytest.approx(math.sqrt(min(eigenvalues.real)), rel=1e-10)
    # strategy A: ERRATA 1, 0.1344 Hz
    assert models["A"].first_frequency() / (2 * math.pi) == pytest.approx(0.13438, abs=5e-6)


# --- engines --------------------------------------------------------------------------------
def test_wave_engines_resolve_to_its_stepping():
    from torsio.analysis.wave import simulate_wave
    from torsio.solvers.wave_batch import simulate_wave_batch

    assert resolve(WAVE_ENGINES.transient) is simulate_wave
    assert resolve(WAVE_ENGINES.batch) is simulate_wave_batch


@pytest.mark.parametrize("role", ["transient", "batch"])
def test_lumped_engines_resolve(role):
    assert callable(resolve(getattr(LUMPED_ENGINES, role)))


def test_engine_names_are_checked_and_resolve_names_what_is_missing():
    with pytest.raises(ValueError, match="'module:function'"):
        ModelEngines(transient="torsio.analysis.wave.simulate_wave", batch="a:b")
    with pytest.raises(LookupError, match="has no function nothing_here"):
        resolve("torsio.analysis.wave:nothing_here")


def test_wave_transient_engine_runs_like_wave_response():
    import attrs

    from torsio.analysis.simulation_options import SimulationOptions
    from torsio.analysis.wave import simulate_wave, wave_response
    from torsio.examples import builtin_config
    from torsio.physics.damping import RayleighDamping

    system = builtin_config().system(strategy="wave")
    system = attrs.evolve(system, damping=RayleighDamping(alpha=0.35)).at(wob=150e3, rpm=60)
    options = {"duration": 3.0, "steady_window": 1.0}
    given = SimulationOptions(**options, method="LSODA", rtol=1e-6)  # the grid's: not used
    results = simulate_wave(system, given, progress=False)
    reference = wave_response(system, **options, progress=False).transient
    assert results.severity == reference.severity
    np.testing.assert_array_equal(results.bit_speed, reference.bit_speed)


def test_the_wave_stepping_refuses_a_model_that_does_not_name_it():
    from torsio.analysis.wave import wave_response
    from torsio.examples import builtin_config

    with pytest.raises(ConfigError, match="expected the wave model"):
        wave_response(builtin_config().system())  # strategy C: the lumped engines
