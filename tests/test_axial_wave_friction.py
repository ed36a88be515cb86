"""Coulomb friction along the distributed axial pipe (torsio.solvers.axial_wave_lines.pipe_contacts,
the cone of torsio.solvers.contact_law): the built-in rgd_wave_pipe.toml with the [well] of
rgd_deviated_well.toml, against the steady torque and drag of torsio.well.torque_drag and
the closed form of torsio.axial.steady_friction, and through the command line."""

from __future__ import annotations

import json
from importlib import resources

import attrs
import numpy as np
import pytest

from torsio.analysis.axial_transient import simulate_axial
from torsio.cli import main
from torsio.config.reading import parse_config_text
from torsio.errors import ConfigError
from torsio.solvers import axial_layouts as slot
from torsio.solvers.axial_wave_setup import contact_nodes
from torsio.well.torque_drag import torque_drag


def _text(name: str) -> str:
    return resources.files("torsio").joinpath(f"data/{name}").read_text(encoding="utf-8")


def wave_well_text() -> str:
    """rgd_wave_pipe.toml with the [well] tables of rgd_deviated_well.toml."""
    well = _text("rgd_deviated_well.toml")
    well = well[well.index("[well]") : well.index("[bit_rock]")]
    return _text("rgd_wave_pipe.toml").replace("[bit_rock]", well + "[bit_rock]")


@pytest.fixture(scope="module")
def config():
    return parse_config_text(wave_well_text())


def _steady_run(config, hook: str):
    axial = config.axial
    options = {**axial.run_options(), "start": "steady", "perturbation": 0.0}
    pipe = axial.assembly
    assembly = pipe.with_axial(attrs.evolve(pipe.axial, hook=hook))
    return simulate_axial(assembly, axial.bit, 100e3, 60.0, duration=2.0, window=1.0,
                          samples=200, growth_rate=False, **options)  # fmt: skip


def test_the_pipe_takes_the_contacts_of_its_lumped_twin(config):
    # every node of the twin's 100 m elements, the capacities of the soft-string state
    # (torsio.well.axial_contacts.axial_contacts): 10 depths, the 6 below the vertical
    # top (500 m) press on the borehole; the last, at the pipe's bottom, takes the BHA's
    # and the bit's share, on the last inner node of the pipe's grid
    contacts = config.axial.contacts
    assert contacts.depths.tolist() == pytest.approx([100.0 * k for k in range(1, 11)])
    assert contacts.count == 6


@pytest.mark.parametrize("hook", ["weight", "speed"])
def test_steady_sliding_against_torque_and_drag(config, hook):
    # The steady start (every contact sliding at (V0, r Omega0)) is a fixed point of the
    # pipe's contact step: the top torque keeps the closed form of steady_friction
    # (T_b + sum F_d r^2 Omega0/|s0|; measured to 2e-14 relative), and its friction part is
    # the soft-string torque and drag's rotating on bottom (torsio.well.torque_drag, an
    # independent integration of the same well) less the axial share of the sliding
    # velocity, 1 - r Omega0/|s0| ~ (V0 / r Omega0)^2 / 2 = 2e-4 (measured 1.1e-4).
    run = _steady_run(config, hook)
    steady = run.axial.steady_friction
    top = run.axial.samples[:, slot.TOP_TORQUE]
    assert top == pytest.approx(np.full(top.size, steady["surface_torque"]), rel=1e-9)
    assert run.axial.samples[:, slot.BIT_SPEED] == pytest.approx(
        run.axial.steady.bit_speed, rel=1e-9
    )
    assert run.axial.contact_switches == 0
    bit_torque = run.axial.steady.bit_torque
    drag = torque_drag(config.well, config.axial.string, wob=100e3, bit_torque=bit_torque)
    expected = drag.surface_torque_on_bottom - bit_torque
    assert steady["surface_torque"] - bit_torque == pytest.approx(expected, rel=5e-4)
    # the friction's work: its power sum F_a V0 + T_f Omega0 over the run, whose length is
    # whole steps (within one step of 2 s: 7.5e-4 relative)
    power = steady["axial_friction"] * run.axial.steady.rop
    power += steady["friction_torque"] * run.axial.steady.bit_speed
    assert run.axial.string_friction_work == pytest.approx(power * 2.0, rel=run.axial.step / 2.0)
    if hook == "speed":  # the hook carries the bit's weight and the axial friction
        assert steady["hook_force"] == pytest.approx(100e3 + steady["axial_friction"], rel=1e-12)


def test_contact_nodes_are_inner_nodes():
    # two sections of 10 cells on [0, 100] and [100, 150] m (nodes 0-10 and 11-21): a depth
    # on the junction takes the lower section's first inner node; the ends are never taken
    offsets = np.array([0, 11, 22])
    lengths = np.array([100.0, 50.0])
    nodes = contact_nodes(offsets, lengths, np.array([0.0, 52.0, 100.0, 149.0]))
    assert nodes.tolist() == [1, 5, 12, 20]
    with pytest.raises(ConfigError, match="well: two contacts"):
        contact_nodes(offsets, lengths, np.array([50.0, 51.0]))
    with pytest.raises(ConfigError, match="well: a contact at 120 m"):
        contact_nodes(np.array([0, 11, 13]), lengths, np.array([120.0]))


def test_cli_simulate_gives_the_pipe_friction(config, tmp_path, capsys):
    # the brief's case through the command line: exit 0 and JSON, from rest the contacts
    # stick and slip (switches) and their friction works (> 0, it only dissipates); no
    # growth rate (the pipe's characteristic equation has no friction), said so
    path = tmp_path / "wave_well.toml"
    path.write_text(wave_well_text(), encoding="utf-8")
    assert main(["simulate", str(path), "--duration", "20", "--window", "10", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["string_contacts"]["count"] == 6
    assert data["string_friction_work"] > 0.0
    assert data["contact_switches"] > 0
    assert data["growth_rate"] is None
    assert any("carries no friction" in text for text in data["warnings"])
    axial = config.axial
    with pytest.raises(ConfigError, match="growth_rate"):
        simulate_axial(axial.assembly, axial.bit, 100e3, 60.0, duration=1.0, window=0.5,
                       growth_rate=True, contacts=axial.contacts)  # fmt: skip


def test_from_rest_against_the_lumped_chain_of_the_same_well():
    # An independent engine: the lumped axial-torsional chain of the same sections in 100 m
    # elements (torsio.solvers.axial_kernel) with the same contacts (the config without its
    # [discretization]), both from rest with the file's defaults (about 95 s). Measured:
    # friction work 1.44555e6 J against 1.44569e6 J (1e-4), mean surface torque 7512
    # against 7476 N m (0.5 %), S_SS 1.299 against 1.310, ROP 8.21e-3 against 8.18e-3
    # m/s (0.4 %): the lumping's discretization error; tolerances about 3x those.
    text = wave_well_text()
    lumped = text[: text.index("\n[discretization]")] + text[text.index("\n[axial]") :]
    runs = []
    for config in (parse_config_text(text), parse_config_text(lumped)):
        axial = config.axial
        runs.append(simulate_axial(axial.assembly, axial.bit, 100e3, 60.0, growth_rate=False,
                                   **axial.run_options()))  # fmt: skip
    pipe, chain = runs
    assert pipe.axial.string_friction_work == pytest.approx(
        chain.axial.string_friction_work, rel=3e-4
    )
    torques = [run.axial.top_drive_summary()["mean_surface_torque"] for run in runs]
    assert torques[0] == pytest.approx(torques[1], rel=1.5e-2)
    assert pipe.severity == pytest.approx(chain.severity, abs=0.03)
    assert pipe.axial.rop_mean == pytest.approx(chain.axial.rop_mean, rel=1.2e-2)
