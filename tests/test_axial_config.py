"""Axial dynamics from a configuration (torsio.config.axial): the built-in RGD 2-DOF file
against the Python API's example, a [[section]] string's chain from E, ρ and the sections,
every refusal by key, and the torsional engines refusing ``law = "rgd"``.

Numbers checked: the file's assembly and bit equal rgd_two_dof_example() and rgd_example();
the string's chain carries the string's whole mass under the weight hook (less the top
half element at the hook under the speed hook) and its springs are E A / Δ, G J / Δ.
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from axial_files import BASE, STRING, TEXT

from torsio.axial import rgd_example, rgd_two_dof_example
from torsio.config.reading import parse_config
from torsio.errors import ConfigError
from torsio.examples import builtin_config, rgd_two_dof_config
from torsio.model.axial_assembly import assembly_description


def _with(data, path, value):
    data = copy.deepcopy(data)
    *tables, key = path.split(".")
    target = data
    for name in tables:
        target = target.setdefault(name, {})
    if value is None:
        target.pop(key)
    else:
        target[key] = value
    return data


def test_builtin_file_is_the_api_example():
    config = rgd_two_dof_config()
    axial = config.axial
    example = rgd_two_dof_example()
    assert assembly_description(axial.assembly) == assembly_description(example)
    assert np.array_equal(axial.assembly.dampers, example.dampers)
    assert axial.bit == rgd_example()
    assert axial.run_options() == {
        "start": "rest",
        "perturbation": 1e-3,
        "step": None,
        "steps_per_period": 100,
        "stick_threshold": 0.1,  # every engine's default (analysis.severity)
        "top_drive": None,
        "string": None,
    }
    assert axial.is_two_dof
    assert (config.operation.wob, config.operation.rpm) == (100e3, 60.0)


def test_axial_keys_are_read_with_units():
    data = _with(BASE, "chain.inertias", [200.0, 255.65])
    data = _with(data, "chain.stiffnesses", [600.0, "700 N*m/rad"])
    data = _with(data, "chain.dampings", None)
    data = _with(data, "chain.masses", ["10 t", 19981.3])
    data = _with(data, "chain.axial_stiffnesses", ["2 MN/m", 3e6])
    data = _with(data, "chain.axial_dampings", [100.0, "200 N*s/m"])
    data = _with(data, "axial.hook", "speed")
    data = _with(data, "axial.steps_per_period", 50)
    data = _with(data, "damping.beta", "0.05 s")
    data = _with(data, "simulation.start", "steady")
    data = _with(data, "simulation.perturbation", 0.01)
    data = _with(data, "simulation.step", "1 ms")
    data = _with(data, "simulation.stick_threshold", 0.05)
    axial = parse_config(data).axial
    a = axial.assembly
    assert a.axial.masses.tolist() == [10000.0, 19981.3]
    assert a.axial.stiffnesses.tolist() == [2e6, 3e6]
    assert a.axial.dampings.tolist() == [100.0, 200.0]
    assert a.dampers.tolist() == pytest.approx([0.05 * 600.0, 0.05 * 700.0])
    assert a.axial.hook == axial.hook == "speed" and not axial.is_two_dof
    assert axial.run_options() == {
        "start": "steady",
        "perturbation": 0.01,
        "step": 1e-3,
        "steps_per_period": 50,
        "stick_threshold": 0.05,
        "top_drive": None,
        "string": None,
    }


def test_string_chain_from_youngs_modulus():
    config = parse_config(STRING)
    a = config.axial.assembly
    string = config.string
    pipe, collars, bit = string.sections
    assert a.dofs == 10  # 1000 m of pipe in 100 m elements, the BHA rigid on the last node
    area = math.pi * (pipe.od**2 - pipe.id**2) / 4
    assert a.axial.stiffnesses == pytest.approx(207e9 * area / 100.0)
    assert a.springs == pytest.approx(79.3e9 * pipe.polar_moment / 100.0)
    bha_mass = sum(7850 * math.pi * (s.od**2 - s.id**2) / 4 * s.length for s in (collars, bit))
    pipe_mass = 7850 * area * 1000.0
    # under the weight hook the top of the pipe is free: the chain carries the whole mass
    # (the top element's upper half on node 0, as pipe_chain); torsionally that half
    # inertia is at the top drive
    assert a.axial.masses.sum() == pytest.approx(bha_mass + pipe_mass, rel=1e-14)
    assert a.node_inertias.sum() == pytest.approx(
        string.bha_inertia + 7850 * pipe.polar_moment * 950.0, rel=1e-14
    )
    speed = parse_config(_with(_with(STRING, "axial.hook", "speed"), "damping", None)).axial
    assert speed.assembly.axial.masses.sum() == pytest.approx(
        bha_mass + pipe_mass - 7850 * area * 50.0, rel=1e-14
    )
    assert a.dampers == pytest.approx(0.06 * a.springs)
    assert a.axial.dampings == pytest.approx(0.06 * a.axial.stiffnesses)
    coarse = parse_config(_with(STRING, "axial.element_length", "250 m")).axial.assembly
    assert coarse.dofs == 4


REFUSALS = [
    (BASE, "chain.masses", [0.0], "chain.masses[0]"),
    (BASE, "chain.masses", [1.0, 2.0], "chain.masses"),
    (BASE, "chain.masses", "heavy", "chain.masses"),
    (BASE, "chain.axial_stiffnesses", [-1.0], "chain.axial_stiffnesses[0]"),
    (BASE, "chain.axial_stiffnesses", [1e6, 1e6], "chain.axial_stiffnesses"),
    (BASE, "chain.axial_dampings", [10.0], "chain.axial_dampings"),
    (BASE, "chain.drag", [1.0], "chain.drag"),
    (BASE, "chain.mass", [1.0], "chain.mass"),
    (BASE, "axial.hook", "crane", "axial.hook"),
    (BASE, "axial.hook", "speed", "axial.hook"),
    (BASE, "axial.steps_per_period", 3, "axial.steps_per_period"),
    (BASE, "axial.element_length", 100.0, "axial.element_length"),
    (BASE, "axial.hooks", "weight", "axial.hooks"),
    (BASE, "bit_rock", {"law": "rgd-bit", "radius": 0.1}, "bit_rock.law"),  # not registered
    (BASE, "bit_rock", {"law": "constant", "radius": 0.1}, "bit_rock.torque_on_bit"),
    (BASE, "bit_rock.blades", 0, "bit_rock.blades"),
    (BASE, "bit_rock.blades", 2.5, "bit_rock.blades"),
    (BASE, "bit_rock.contact_stress", "60 m", "bit_rock.contact_stress"),
    (BASE, "bit_rock.wear_flat_length", -1.0, "bit_rock.wear_flat_length"),
    (BASE, "bit_rock.radius", None, "bit_rock.radius"),
    (BASE, "bit_rock.speed_unit", "rpm", "bit_rock.speed_unit"),
    (BASE, "bit_rock.blade", 4, "bit_rock.blade"),
    (BASE, "simulation.start", "moving", "simulation.start"),
    (BASE, "simulation.perturbation", -1.0, "simulation.perturbation"),
    (BASE, "simulation.step", 0.0, "simulation.step"),
    (BASE, "simulation.rtol", 1e-6, "simulation.rtol"),
    (BASE, "simulation.method", "RK45", "simulation.method"),
    (BASE, "damping.alpha", 0.1, "damping.alpha"),
    (BASE, "top_drive", {"kind": "torque", "inertia": 930.0, "torque": 1e4}, "top_drive.kind"),
    (BASE, "well", {"survey": []}, "well"),
    (STRING, "material.youngs_modulus", None, "material.youngs_modulus"),
    (STRING, "material.youngs_modulus", -1.0, "material.youngs_modulus"),
    (STRING, "material.youngs_modulus", "207 m", "material.youngs_modulus"),
    (STRING, "axial.element_length", 0.0, "axial.element_length"),
]


@pytest.mark.parametrize(("base", "path", "value", "key"), REFUSALS)
def test_every_bad_value_names_its_key(base, path, value, key):
    if base is BASE and path in ("chain.drag", "damping.alpha"):
        base = _with(base, "chain.dampings", None)
    with pytest.raises(ConfigError) as info:
        parse_config(_with(base, path, value))
    assert info.value.key == key


def test_axial_keys_without_axial_dynamics_are_refused_and_axial_gives_them():
    torsional = _with(_with(BASE, "chain.masses", None), "axial", None)
    torsional = _with(_with(torsional, "chain.axial_stiffnesses", None), "simulation", None)
    for path, key in (
        ("chain.axial_stiffnesses", "chain.axial_stiffnesses"),
        ("axial.hook", "axial"),
        ("simulation.step", "simulation.step"),
    ):
        value = [] if path.startswith("chain") else ("weight" if "hook" in path else 1e-3)
        if path == "chain.axial_stiffnesses":
            value = [1e6]
        with pytest.raises(ConfigError) as info:
            parse_config(_with(torsional, path, value))
        assert info.value.key == key
    string = _with(
        _with(STRING, "bit_rock", {"law": "constant", "torque_on_bit": 5e3}), "axial.hook", "weight"
    )
    # a string's [axial] gives it axial dynamics whatever its law (the constant torque here
    # rests on the rock: tests/test_axial_string_law.py)
    assert parse_config(string).axial.bit.name == "constant"


def test_torsional_engines_refuse_rgd_by_key():
    torsional = _with(_with(BASE, "chain.masses", None), "axial", None)
    torsional = _with(_with(torsional, "chain.axial_stiffnesses", None), "simulation", None)
    config = parse_config(torsional)  # reads: the law is checked, not built
    assert config.axial is None
    with pytest.raises(ConfigError, match="the rgd law needs axial dynamics") as info:
        config.system()
    assert info.value.key == "bit_rock.law"


def test_existing_configurations_have_no_axial_dynamics():
    assert builtin_config().axial is None


def test_axial_frequency_of_two_masses_is_the_closed_form():
    from torsio.axial import axial_chain
    from torsio.report.axial import axial_frequencies

    # top free under the weight hook: two masses on one spring, ω² = k (1/m1 + 1/m2)
    pair = axial_chain([1.0, 1.0], [1.0, 1.0], [2.0e3, 3.0e3], axial_stiffnesses=[1e6, 4e6])
    expected = math.sqrt(4e6 * (1 / 2.0e3 + 1 / 3.0e3)) / (2 * math.pi)
    assert axial_frequencies(pair) == pytest.approx([expected], rel=1e-12)


def test_youngs_modulus_is_read_once_with_the_material_of_every_string():
    # E travels in the sections' Material (read with [material] and a section's own table,
    # which inherits what it does not give); a torsional string checks it too: a bad value
    # was ignored while no law needed it
    config = parse_config(STRING)
    assert {s.material.youngs_modulus for s in config.string.sections} == {207e9}
    tucker_wang = {"law": "tucker-wang", "radius": 0.108, "a0": 0.221, "a1": 0.2, "a2": 0.89,
                   "a3": 0.06, "speed_unit": "rpm"}  # fmt: skip
    torsional = _with(STRING, "bit_rock", tucker_wang)
    assert parse_config(_with(torsional, "material.youngs_modulus", None)).axial is None
    with pytest.raises(ConfigError) as info:
        parse_config(_with(torsional, "material.youngs_modulus", "207 m"))
    assert info.value.key == "material.youngs_modulus"


def test_the_stick_threshold_reaches_an_axial_run_and_a_map_says_it_keeps_its_own(tmp_path, capsys):
    # simulate_config passes stick_threshold on (1e-9 Ω₀: the bit at rest, Ω_b = 0) and
    # refuses by name an option an axial run has not; a map counts at every map's 0.1 Ω
    # and says that the file's threshold applies to single runs
    from torsio.analysis.transient import simulate_config
    from torsio.cli import main

    config = rgd_two_dof_config()
    run = simulate_config(
        config, duration=5.0, steady_window=2.0, stick_threshold=1e-9, progress=False
    )
    assert run.stick_threshold == 1e-9 and run.to_dict()["stick_threshold"] == 1e-9
    with pytest.raises(ConfigError) as caught:
        simulate_config(config, duration=5.0, samples=10)
    assert caught.value.key == "samples"
    path = tmp_path / "stick.toml"
    path.write_text(TEXT.replace("[simulation]", "[simulation]\nstick_threshold = 0.05"))
    assert main(["map", str(path), "--wob", "100kN:100kN:1", "--rpm", "60:60:1", "--json"]) == 0
    assert "stick_threshold apply to single runs" in capsys.readouterr().err
