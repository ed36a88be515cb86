"""The axial rows of a discretizer's chain (``Discretizer.axial_rows``): a ``[[section]]``
file with the RGD bit is lumped by its own ``[discretization]`` strategy.

Independent references:

- the exact natural frequencies of the stepped bar with the bit's mass at its tip
  (:func:`torsio.model.continuum.bar_frequencies`; checked against a transfer-matrix root
  search in tests/test_axial_wave_config.py), to which a lumped-mass chain converges like
  h² (the error falls 4 times when the elements halve);
- the string's mass Σ ρ A L and its axial compliance Σ L / (E A), summed here from the
  file's numbers (A = π (od² − id²)/4);
- the paper's torsional strategies B and C (``StrategyB``/``StrategyC.discretize``), whose
  rows the axial chain's torsional rows are.
"""

from __future__ import annotations

import math
import tomllib
from importlib import resources

import numpy as np
import pytest
import scipy.linalg

from torsio.config.reading import parse_config
from torsio.errors import ConfigError
from torsio.model.continuum import bar_frequencies
from torsio.model.discretize import StrategyB, StrategyC
from torsio.model.lumped import chain_matrix

TEXT = resources.files("torsio").joinpath("data/rgd_wave_pipe.toml").read_text(encoding="utf-8")
INCH = 0.0254
E, RHO = 207e9, 7850.0  # the file's [material]
# (od, id, length) [m] of the file's sections: drill pipe, HWDP (in the pipe), collars, bit
SECTIONS = [
    (5 * INCH, 4.276 * INCH, 900.0),
    (5 * INCH, 3 * INCH, 100.0),
    (6.75 * INCH, 2.8125 * INCH, 150.0),
    (8.5 * INCH, 0.0, 0.3),
]


def _area(od: float, inner: float) -> float:
    return math.pi * (od**2 - inner**2) / 4


def _axial(discretization: dict, hook: str = "weight", **tables):
    data = tomllib.loads(TEXT)
    data["discretization"] = discretization
    data["axial"] = {"hook": hook}
    data.update(tables)
    return parse_config(data).axial


def _frequencies(chain, count: int) -> np.ndarray:
    """The chain's first axial frequencies [rad/s], the top held (the speed hook)."""
    stiffness = chain_matrix(chain.axial.stiffnesses)
    squares = scipy.linalg.eigh(stiffness, np.diag(chain.axial.masses), eigvals_only=True)
    return np.sqrt(squares[:count])


@pytest.mark.parametrize(
    ("strategy", "flexible", "bounds"),
    [("B", 3, [1e-4, 2e-3, 6e-3]), ("C", 2, [2e-4, 2e-3, 6e-3])],
)
def test_the_axial_chain_converges_to_the_stepped_bar(strategy, flexible, bounds):
    # strategy B splits the collars too, the bit (0.3 m) its tip mass; strategy C keeps the
    # collars and the bit rigid, their mass the tip. The exact stepped bar of E A, L, √(E/ρ)
    # per flexible section above that tip mass: at 50 m elements (modes 1-3) the errors are
    # 8.1e-5, 1.4e-3, 4.8e-3 (B) and 1.3e-4, 1.5e-3, 5.1e-3 (C), falling 4.00 times per
    # halving (measured 3.994-4.000): second order, as a lumped-mass chain must
    rigidities = [E * _area(od, inner) for od, inner, _ in SECTIONS[:flexible]]
    lengths = [length for *_, length in SECTIONS[:flexible]]
    tip = sum(RHO * _area(od, inner) * length for od, inner, length in SECTIONS[flexible:])
    speeds = [math.sqrt(E / RHO)] * flexible
    exact = bar_frequencies(rigidities, lengths, speeds, tip, count=3)
    errors = []
    for element_length in (50.0, 25.0):
        options = {"strategy": strategy, "max_element_length": element_length}
        chain = _axial(options, "speed").assembly
        assert chain.dofs == sum(math.ceil(length / element_length) for length in lengths)
        errors.append(np.abs(_frequencies(chain, 3) / exact - 1))
    assert np.all(errors[0] < bounds)
    np.testing.assert_allclose(errors[0] / errors[1], 4.0, rtol=0.01)


@pytest.mark.parametrize(
    ("discretization", "discretizer"),
    [
        ({"strategy": "B", "dp_elements": 7, "bha_elements": 3}, StrategyB(7, 3)),
        ({"strategy": "C", "section_elements": [9, 2]}, StrategyC(section_elements=[9, 2])),
        ({}, StrategyC(max_element_length=100.0)),  # the default: [axial] element_length
    ],
)
def test_the_chain_is_the_files_discretizer_with_axial_rows(discretization, discretizer):
    axial = _axial(discretization)
    chain, model = axial.assembly, discretizer.discretize(axial.string)
    # the torsional rows are the paper's strategy, element for element
    np.testing.assert_array_equal(chain.inertia, model.inertia)
    np.testing.assert_array_equal(chain.stiffness, model.stiffness)
    np.testing.assert_array_equal(chain.node_depths, model.node_depths)
    # the weight hook: the whole string's mass on the nodes (the free top's half included)
    string_mass = sum(RHO * _area(od, inner) * length for od, inner, length in SECTIONS)
    assert chain.axial.masses.sum() == pytest.approx(string_mass, rel=1e-14)
    # the springs in series: the compliance of the sections they split
    flexible = SECTIONS[:3] if discretizer.name == "B" else SECTIONS[:2]
    compliance = sum(length / (E * _area(od, inner)) for od, inner, length in flexible)
    assert (1 / chain.axial.stiffnesses).sum() == pytest.approx(compliance, rel=1e-13)


def test_the_speed_hook_holds_the_top_half_element_and_beta_damps_every_spring():
    elements = {"strategy": "B", "section_elements": [3, 1, 1]}  # the top element 300 m
    weight = _axial(elements).assembly
    speed = _axial(elements, "speed", damping={"beta": 0.01}).assembly
    top_element = RHO * _area(*SECTIONS[0][:2]) * 300.0
    assert weight.axial.masses[0] - speed.axial.masses[0] == pytest.approx(top_element / 2)
    np.testing.assert_array_equal(weight.axial.masses[1:], speed.axial.masses[1:])
    np.testing.assert_allclose(speed.dampers, 0.01 * speed.springs, rtol=1e-15)
    np.testing.assert_allclose(speed.axial.dampings, 0.01 * speed.axial.stiffnesses, rtol=1e-15)


@pytest.mark.parametrize(
    ("tables", "key", "words"),
    [
        ({"discretization": {"strategy": "A"}}, "discretization.strategy", "builds no axial"),
        ({"discretization": {"strategy": "consistent"}}, "discretization.strategy", "lumped-mass"),
        (
            {"discretization": {"dp_elements": 5}, "axial": {"element_length": "50 m"}},
            "axial.element_length",
            "give one of them",
        ),
        (
            {"discretization": {"strategy": "B", "dp_elements": 0}},
            "discretization.dp_elements",
            ">= 1",
        ),
        (
            {"discretization": {}, "axial": {"element_length": "0.1 m"}},
            "axial.element_length",
            "exceed the limit of 5000",
        ),
    ],
)
def test_a_strategy_without_axial_rows_is_refused_by_key(tables, key, words):
    data = tomllib.loads(TEXT)
    data.update(tables)
    with pytest.raises(ConfigError) as caught:
        parse_config(data)
    assert caught.value.key == key and words in caught.value.message


def test_a_section_without_youngs_modulus_is_named():
    data = tomllib.loads(TEXT)
    del data["material"]["youngs_modulus"]
    del data["discretization"]
    with pytest.raises(ConfigError) as caught:
        parse_config(data)
    assert caught.value.key == "material.youngs_modulus"


class _CountedOnly:
    """A plugin discretizer of the documented contract that takes its element count only."""

    name = "counted-only"

    def __init__(self, dp_elements: int = 2) -> None:
        self._inner = StrategyC(dp_elements=dp_elements)

    def discretize(self, string):
        return self._inner.discretize(string)

    def axial_rows(self, string, hook):
        return self._inner.axial_rows(string, hook)


def test_a_plugin_discretizer_without_max_element_length_is_refused_by_key(monkeypatch):
    import torsio.plugins

    registered = {**torsio.plugins.discretizers(), "counted-only": _CountedOnly}
    monkeypatch.setattr(torsio.plugins, "discretizers", lambda: registered)
    data = tomllib.loads(TEXT)
    data["discretization"] = {"strategy": "counted-only"}  # no count: [axial]'s would apply
    with pytest.raises(ConfigError) as caught:
        parse_config(data)
    assert caught.value.key == "discretization.strategy"
    assert "max_element_length" in caught.value.message
    # with its own count, the same plugin lumps the string: strategy C's chain, 2 DP elements
    data["discretization"] = {"strategy": "counted-only", "dp_elements": 2}
    axial = parse_config(data).axial
    reference = StrategyC(dp_elements=2)
    np.testing.assert_array_equal(
        axial.assembly.stiffness, reference.discretize(axial.string).stiffness
    )
    np.testing.assert_array_equal(
        axial.assembly.axial.masses, reference.axial_rows(axial.string, "weight").masses
    )
