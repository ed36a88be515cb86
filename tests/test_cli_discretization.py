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

import numpy as np
import pytest

from torsio.analysis.config_runs import config_map
from torsio.analysis.map_options import MapOptions
from torsio.analysis.transient import simulate_config
from torsio.cli import main
from torsio.config.reading import parse_config, rediscretized
from torsio.errors import ConfigError
from torsio.examples import rgd_deviated_well_config, rgd_wave_pipe_config
from torsio.model.discretize import StrategyC

DATA = resources.files("torsio").joinpath("data")
WAVE_PIPE = str(DATA.joinpath("rgd_wave_pipe.toml"))
TWO_DOF = str(DATA.joinpath("rgd_2dof.toml"))
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
    data = _json(capsys, "simulate", WAVE_PIPE, "--strategy", "B", "--dp-elements", "4", *TIMES)
    written = parse_config(_file_with("rgd_wave_pipe.toml", discretization={
        "strategy": "B", "dp_elements": 4}))  # fmt: skip
    assert written.axial.assembly.dofs == 5  # 3 + 1 pipe elements (900 m, 100 m), 1 collar
    run = simulate_config(written, duration=20.0, steady_window=10.0)
    expected = json.loads(json.dumps(run.to_dict()))
    for key in ("severity", "stick_fraction", "bit_speed_max", "mean_bit_torque"):
        assert data[key] == expected[key], key


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
    config = rediscretized(rgd_deviated_well_config(), strategy="B", dp_elements=6)
    written = _file_with(
        "rgd_deviated_well.toml", discretization={"strategy": "B", "dp_elements": 6}
    )
    del written["axial"]["element_length"]  # the count replaces it, as on the command line
    written = parse_config(written)
    contacts = config.axial.contacts
    assert contacts.radius.size == config.axial.assembly.dofs
    for name in ("radius", "static_force", "sliding_force", "depths"):
        np.testing.assert_array_equal(getattr(contacts, name),
                                      getattr(written.axial.contacts, name))  # fmt: skip


def test_a_torsional_model_is_the_one_of_the_overrides():
    config = rgd_wave_pipe_config()
    ritto = _file_with("ritto2017.toml")  # its Tucker-Wang law on the same string
    tables = {k: v for k, v in config.table.items() if k not in ("axial", "simulation")}
    torsional = parse_config(tables | {"bit_rock": ritto["bit_rock"], "damping": ritto["damping"]})
    again = rediscretized(torsional, strategy="B", dp_elements=4, bha_elements=2)
    given = torsional.model(strategy="B", dp_elements=4, bha_elements=2)
    np.testing.assert_array_equal(again.model().stiffness, given.stiffness)
    assert rediscretized(torsional) is torsional  # nothing given: the configuration itself


@pytest.mark.parametrize(
    ("args", "words"),
    [
        ([TWO_DOF, "--dp-elements", "3"], ["--dp-elements:", "[chain] given directly"]),
        ([WAVE_PIPE, "--strategy", "Q"], ["--strategy (discretization.strategy):", "'Q'"]),
        ([WAVE_PIPE, "--strategy", "A"], ["--strategy (discretization.strategy):", "axial"]),
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
