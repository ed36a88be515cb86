"""--strategy, --dp-elements and --bha-elements on every model: the file read again with
them (``torsio.config.reading.rediscretized``), its axial chain and its ``[well]`` contacts
included.

References: the same file with those keys written in its ``[discretization]`` table (the
command line must give that file's run, map and contacts bit for bit), and strategy C's
discretizer of the same string (:class:`torsio.model.discretize.StrategyC`).
"""

from __future__ import annotations

import json
import tomllib
from importlib import resources

import attrs
import numpy as np
import pytest

from torsio.analysis.config_runs import config_map
from torsio.analysis.map_options import MapOptions
from torsio.analysis.transient import simulate_config
from torsio.cli import main
from torsio.config.configuration import OperationConfig
from torsio.config.reading import parse_config, rediscretized
from torsio.errors import ConfigError
from torsio.examples import rgd_deviated_well_config, rgd_wave_pipe_config
from torsio.model.axial_assembly import axial_model
from torsio.model.continuum import bar_frequencies
from torsio.model.discretize import StrategyC
from torsio.model.modal import modal_analysis
from torsio.model.wave import WaveStrategy
from torsio.report.axial import axial_frequencies

DATA = resources.files("torsio").joinpath("data")
WAVE_PIPE = str(DATA.joinpath("rgd_wave_pipe.toml"))
TWO_DOF = str(DATA.joinpath("rgd_2dof.toml"))
WELL = str(DATA.joinpath("rgd_deviated_well.toml"))
TIMES = ["--duration", "20", "--window", "10"]


def _file_with(name: str, **tables) -> dict:
    data = tomllib.loads(DATA.joinpath(name).read_text(encoding="utf-8"))
    data.update(tables)
    return data


def _json(capsys, *args) -> dict:
    status = main([*args, "--json"])
    captured = capsys.readouterr()
    assert status == 0, captured.err
    return json.loads(captured.out)


def test_simulate_lumps_the_axial_chain_as_the_flags_say(capsys):
    flags = ["--strategy", "B", "--dp-elements", "4", "--bha-elements", "1"]
    data = _json(capsys, "simulate", WAVE_PIPE, *flags, *TIMES)
    written = parse_config(_file_with("rgd_wave_pipe.toml", discretization={
        "strategy": "B", "dp_elements": 4, "bha_elements": 1}))  # fmt: skip
    assert written.axial.assembly.dofs == 5  # 3 + 1 pipe elements (900 m, 100 m), 1 collar
    run = simulate_config(written, duration=20.0, steady_window=10.0)
    expected = json.loads(json.dumps(run.to_dict()))
    for key in ("severity", "stick_fraction", "bit_speed_max", "mean_bit_torque"):
        assert data[key] == expected[key], key
    assert (data["model"]["strategy"], data["model"]["nodes"]) == ("B", 5)  # what ran


def test_map_lumps_the_axial_chain_as_the_flags_say(capsys):
    grid = ["--wob", "80kN:120kN:2", "--rpm", "60:120:2", "--refine", "0", *TIMES]
    data = _json(capsys, "map", WAVE_PIPE, "--strategy", "C", "--dp-elements", "3", *grid)
    written = parse_config(_file_with("rgd_wave_pipe.toml", discretization={"dp_elements": 3}))
    options = MapOptions(duration=20.0, steady_window=10.0, refine=0)
    expected = config_map(written, np.array([80e3, 120e3]), np.array([60.0, 120.0]), options)
    assert data["severity"] == json.loads(json.dumps(expected.to_dict()))["severity"]


def test_a_count_on_the_command_line_replaces_axial_element_length():
    config = parse_config(_file_with("rgd_wave_pipe.toml", discretization={},
                                     axial={"element_length": "50 m"}))  # fmt: skip
    assert config.axial.assembly.dofs == 20  # 1000 m of pipe in 50 m, the rigid BHA on the last
    counted = rediscretized(config, dp_elements=5)
    expected = StrategyC(dp_elements=5).discretize(config.string)
    np.testing.assert_array_equal(counted.axial.assembly.node_depths, expected.node_depths)
    np.testing.assert_array_equal(counted.axial.assembly.stiffness, expected.stiffness)


def test_the_well_contacts_follow_the_new_chain():
    config = rediscretized(rgd_deviated_well_config(), strategy="B", dp_elements=6,
                           bha_elements=2)  # fmt: skip
    written = _file_with("rgd_deviated_well.toml", discretization={
        "strategy": "B", "dp_elements": 6, "bha_elements": 2})  # fmt: skip
    del written["axial"]["element_length"]  # the count replaces it, as on the command line
    written = parse_config(written)
    contacts = config.axial.contacts
    assert contacts.radius.size == config.axial.assembly.dofs
    for name in ("radius", "static_force", "sliding_force", "depths"):
        np.testing.assert_array_equal(getattr(contacts, name),
                                      getattr(written.axial.contacts, name))  # fmt: skip


def test_a_torsional_model_is_the_one_of_the_overrides():
    ritto = _file_with("ritto2017.toml")  # strategy C, 5 DP elements
    config = parse_config(ritto)
    again = rediscretized(config, strategy="B", dp_elements=4, bha_elements=2)
    ritto["discretization"] = {"strategy": "B", "dp_elements": 4, "bha_elements": 2}
    written = parse_config(ritto).model()
    np.testing.assert_array_equal(again.model().stiffness, written.stiffness)
    np.testing.assert_array_equal(again.model().inertia, written.inertia)
    assert rediscretized(config) is config  # nothing given: the configuration itself


def test_what_was_changed_in_python_is_kept_and_a_file_is_needed_for_the_chain():
    changed = attrs.evolve(rgd_wave_pipe_config(), operation=OperationConfig(123e3, 77.0))
    again = rediscretized(changed, strategy="C", dp_elements=3)
    assert again.operation == changed.operation and again.axial.assembly.dofs == 3
    with pytest.raises(ConfigError) as caught:
        rediscretized(attrs.evolve(changed, table={}), dp_elements=3)
    assert caught.value.key == "discretization" and "not read from one" in caught.value.message


@pytest.mark.parametrize(
    ("args", "words"),
    [
        ([TWO_DOF, "--dp-elements", "3"], ["--dp-elements:", "[chain] given directly"]),
        ([WAVE_PIPE, "--strategy", "Q"], ["--strategy (discretization.strategy):", "'Q'"]),
        ([WAVE_PIPE, "--strategy", "A"], ["--strategy (discretization.strategy):", "axial"]),
        # a single count of a chain [axial] element_length counts: the pipe would be 1 element
        (
            [WELL, "--strategy", "B", "--bha-elements", "3"],
            ["--bha-elements:", "give dp_elements too"],
        ),
        (
            [WELL, "--strategy", "B", "--dp-elements", "20"],
            ["--dp-elements:", "give bha_elements too"],
        ),
        # a key of the file that the flags made wrong names them
        ([WELL, "--strategy", "wave"], ["axial.element_length (with --strategy wave):"]),
    ],
)
def test_a_refused_override_names_its_flag(capsys, args, words):
    assert main(["simulate", *args]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and all(word in captured.err for word in words), captured.err


def test_the_python_map_of_an_axial_file_refuses_an_override():
    options = MapOptions(duration=20.0, steady_window=10.0, refine=0)
    with pytest.raises(ConfigError) as caught:
        config_map(rgd_wave_pipe_config(), np.array([1e5]), np.array([60.0]), options,
                   discretization={"strategy": "B"})  # fmt: skip
    assert caught.value.key == "strategy" and "rediscretized" in caught.value.message


def test_the_advisor_lumps_the_chain_as_the_flags_say(capsys, tmp_path):
    # reference: the advice on the same file with the count written in [discretization]
    # (the file's own 100 m elements, 23 in the pipe, advise the same point at S_SS 0.799
    # against 0.786 with 12: the flags reach the chain)
    small = ["--wob", "78kN:110kN:2", "--rpm", "160:180:2", "--duration", "40", "--window",
             "15", "--no-compare", "--threads", "1"]  # fmt: skip
    flagged = _json(capsys, "advise", WELL, "--dp-elements", "12", *small)
    text = DATA.joinpath("rgd_deviated_well.toml").read_text(encoding="utf-8")
    line = 'element_length = "100 m"       # the lumped chain\'s longest element\n'
    assert line in text  # the count replaces it, as on the command line
    text = text.replace(line, "").replace(
        "[damping]", "[discretization]\ndp_elements = 12\n\n[damping]"
    )
    written = tmp_path / "written.toml"
    written.write_text(text, encoding="utf-8")
    assert flagged["recommended"] == _json(capsys, "advise", str(written), *small)["recommended"]


def test_the_files_torsional_model_is_its_axial_chains(capsys):
    # reference: the chain the axial engine runs ([I] and [K] of its torsional rows), which
    # [axial] element_length lumps when [discretization] counts nothing; torsio modes on the
    # file failed (strategy C's default of 1 element could not cover the 2 pipe sections)
    config = rgd_deviated_well_config()
    model, chain = config.model(), config.axial.assembly
    np.testing.assert_array_equal(model.stiffness, chain.stiffness)
    np.testing.assert_array_equal(model.inertia, chain.inertia)
    data = _json(capsys, "modes", WELL, "--count", "3")
    assert data["dofs"] == chain.dofs == 24
    expected = modal_analysis(chain, 3).frequencies_hz
    np.testing.assert_array_equal(data["frequencies_hz"], expected)
    # its axial modes (bit free, top free under the weight hook) beside them: the chain's,
    # within its lumping error of the exact bar with the rigid BHA's mass at the tip (the
    # distributed pipe's continuum; 4e-4, 1.8e-3, 4.1e-3 at 100 m elements, second order
    # as tests/test_axial_discretizers.py measures)
    assert data["axial_boundaries"] == "bit free, top free"
    assert data["axial_frequencies_hz"] == axial_frequencies(chain)[:3]
    pipe = axial_model(config.string, WaveStrategy(rigid_bha=True))
    exact = axial_frequencies(pipe, 3)
    np.testing.assert_allclose(data["axial_frequencies_hz"], exact, rtol=5e-3)
    # and re-lumped from the command line, the torsional model is the new chain's, and so
    # is the model of Config.model with the same count
    flagged = rediscretized(config, strategy="B")
    data = _json(capsys, "modes", WELL, "--strategy", "B", "--count", "3")
    assert data["dofs"] == flagged.axial.assembly.dofs == 26  # the 3 collar elements too
    assert data["axial_frequencies_hz"] == axial_frequencies(flagged.axial.assembly)[:3]
    counted = rediscretized(config, dp_elements=5).axial.assembly
    np.testing.assert_array_equal(config.model(dp_elements=5).stiffness, counted.stiffness)


def test_modes_of_a_chain_without_axial_springs_and_of_the_distributed_pipe(capsys):
    # the 2-DOF chain: one axial mass under the weight hook, no axial spring (axially rigid)
    data = _json(capsys, "modes", TWO_DOF)
    assert data["axial_frequencies_hz"] == []
    main(["modes", TWO_DOF])
    out = capsys.readouterr().out
    assert "none (axially rigid)" in out and "the model is a [chain] given directly" in out
    # the distributed pipe: its exact continuum's, 10 by default (the report's count)
    pipe = rgd_wave_pipe_config().axial.assembly
    data = _json(capsys, "modes", WAVE_PIPE)
    rows = pipe.axial
    omega = bar_frequencies(rows.rigidities, pipe.lengths, rows.wave_speeds, rows.bha_mass, 10,
                            free_top=True)  # fmt: skip
    np.testing.assert_allclose(data["axial_frequencies_hz"], omega / (2 * np.pi), rtol=1e-14)
