"""A lumped model given directly in TOML (``[chain]``, DESIGN.md contract)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from torsio.cli import main
from torsio.config.reading import parse_config_text
from torsio.errors import ConfigError
from torsio.model.lumped import LumpedModel
from torsio.physics.damping import ModelDamping, RayleighDamping
from torsio.report.document import report_data

# Two inertias I = (2, 1) kg m^2 on springs k = (100, 50) N m/rad, the first tied to the
# top: det([K] - w^2 [I]) = 2 (w^2)^2 - 250 w^2 + 5000 = 0 gives w^2 = 25 and 100 exactly.
TWO_NODES = """
name = "two nodes"
[chain]
inertias = [2.0, "1 kg*m^2"]
stiffnesses = [100.0, "50 N*m/rad"]
"""
EXACT_HZ = [5.0 / (2 * math.pi), 10.0 / (2 * math.pi)]

BIT_ROCK = """
[bit_rock]
law = "tucker-wang"
radius = 0.108
a0 = 0.221
a1 = 0.2
a2 = 0.89
a3 = 0.06
"""


def test_chain_builds_the_same_model_as_from_chain():
    text = TWO_NODES.replace("[chain]", "[chain]\ndampings = [1.0, 2.0]\ndrag = [0.0, 3.0]")
    config = parse_config_text(text)
    assert config.string is None and config.chain is not None
    model = config.model()
    expected = LumpedModel.from_chain([2.0, 1.0], [100.0, 50.0], [1.0, 2.0], [0.0, 3.0])
    np.testing.assert_array_equal(model.inertia, expected.inertia)
    np.testing.assert_array_equal(model.stiffness, expected.stiffness)
    np.testing.assert_array_equal(model.damping, expected.damping)
    assert isinstance(config.model_damping(model), ModelDamping)  # the chain's own dampers


def test_chain_without_dampers_takes_rayleigh_damping():
    config = parse_config_text(TWO_NODES + "[damping]\nalpha = 0.1\nbeta = 0.01\n")
    damping = config.model_damping(config.model())
    assert isinstance(damping, RayleighDamping)
    assert (damping.alpha, damping.beta) == (0.1, 0.01)


def test_chain_with_a_bit_law_builds_a_system():

    config = parse_config_text(TWO_NODES + BIT_ROCK + "[operation]\nwob = '50 kN'\nrpm = 60\n")
    system = config.system()
    assert system.model.dofs == 2 and system.bit_radius == 0.108 and system.string is None
    with_dampers = TWO_NODES.replace("[chain]", "[chain]\ndampings = [1.0, 2.0]")
    system = parse_config_text(with_dampers + BIT_ROCK).system()
    assert isinstance(system.damping, ModelDamping)  # the chain's own dampers, not Rayleigh


@pytest.mark.parametrize(
    ("text", "key", "needle"),
    [
        ("[chain]\nstiffnesses = [1.0]\n", "chain.inertias", "missing"),
        ("[chain]\ninertias = [1.0]\n", "chain.stiffnesses", "missing"),
        ("[chain]\ninertias = [1.0, 2.0]\nstiffnesses = [1.0]\n", "chain.stiffnesses", "2 values"),
        (
            "[chain]\ninertias = [1.0]\nstiffnesses = [1.0]\ndampings = [1.0, 2.0]\n",
            "chain.dampings",
            "1 values",
        ),
        (
            "[chain]\ninertias = [1.0, 0.0]\nstiffnesses = [1.0, 1.0]\n",
            "chain.inertias[1]",
            "positive",
        ),
        ("[chain]\ninertias = [1.0]\nstiffnesses = [-1.0]\n", "chain.stiffnesses[0]", "positive"),
        (
            "[chain]\ninertias = [1.0]\nstiffnesses = [1.0]\ndrag = [-2.0]\n",
            "chain.drag[0]",
            "non-negative",
        ),
        (
            "[chain]\ninertias = ['3 kN']\nstiffnesses = [1.0]\n",
            "chain.inertias[0]",
            "not a inertia",
        ),
        ("[chain]\ninertias = 3.0\nstiffnesses = [1.0]\n", "chain.inertias", "array"),
        ("[chain]\ninertias = []\nstiffnesses = []\n", "chain.inertias", "non-empty"),
        ("[chain]\ninertias = [1.0]\nstiffnesses = [1.0]\nmass = [1.0]\n", "chain.mass", "unknown"),
        (
            "[chain]\ninertias = [1.0]\nstiffnesses = [1.0]\n[discretization]\nstrategy = 'A'\n",
            "discretization",
            "[chain]",
        ),
        (
            "[chain]\ninertias = [1.0]\nstiffnesses = [1.0]\n[[section]]\nkind = 'bit'\n"
            "od = 0.2\nid = 0.0\nlength = 0.3\n",
            "section",
            "[chain]",
        ),
        (
            "[chain]\ninertias = [1.0]\nstiffnesses = [1.0]\ndampings = [0.5]\n"
            "[damping]\nalpha = 0.1\n",
            "damping",
            "given twice",
        ),
        (
            "[chain]\ninertias = [1.0]\nstiffnesses = [1.0]\ndrag = [0.5]\n[damping]\nbeta = 0.1\n",
            "damping",
            "given twice",
        ),
        (
            "[chain]\ninertias = [1.0]\nstiffnesses = [1.0]\n[bit_rock]\nlaw = 'tucker-wang'\n"
            "a0 = 0.221\na1 = 0.2\na2 = 0.89\na3 = 0.06\n",
            "bit_rock.radius",
            "required with [chain]",
        ),
    ],
)
def test_bad_chains_name_the_key(text, key, needle):
    with pytest.raises(ConfigError) as info:
        parse_config_text(text)
    assert info.value.key == key
    assert needle in str(info.value)


def test_a_chain_is_not_discretized():
    config = parse_config_text(TWO_NODES)
    with pytest.raises(ConfigError, match="not discretized") as info:
        config.model(strategy="B")
    assert info.value.key == "strategy"
    assert config.model(strategy=None).dofs == 2  # no override given: fine


def test_modes_of_a_chain_say_there_is_no_continuum(tmp_path, capsys):
    path = tmp_path / "chain.toml"
    path.write_text(TWO_NODES)
    assert main(["modes", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    # Exact: w^2 = 25 and 100 (header of this file).
    np.testing.assert_allclose(data["frequencies_hz"], EXACT_HZ, rtol=1e-12)
    assert data["continuum_hz"] is None and "[chain]" in data["continuum"]
    assert main(["modes", str(path)]) == 0
    assert "no drill-string" in capsys.readouterr().out
    assert main(["modes", str(path), "--strategy", "B"]) == 2
    assert "strategy" in capsys.readouterr().err


def test_report_of_a_chain(tmp_path, capsys):
    config = parse_config_text(TWO_NODES + BIT_ROCK, source="chain.toml")
    data = report_data(config)
    assert [node["inertia_kg_m2"] for node in data["chain"]["nodes"]] == [2.0, 1.0]
    assert "string" not in data and data["discretization"]["dofs"] == 2
    np.testing.assert_allclose(data["modes"]["frequencies_hz"], EXACT_HZ, rtol=1e-12)
    assert data["modes"]["continuum_hz"] is None and "[chain]" in data["modes"]["continuum"]
    path = tmp_path / "chain.toml"
    path.write_text(TWO_NODES)
    html = tmp_path / "chain.html"
    assert main(["report", str(path), "--html", str(html)]) == 0
    out = capsys.readouterr().out
    assert "Lumped chain" in out and "no exact continuum" in out
    assert "Lumped chain" in html.read_text()
