"""``torsio simulate``, ``torsio map`` and ``torsio report`` on a configuration with axial
dynamics (the built-in ``rgd_2dof.toml``), the flags they refuse, and the torsional
commands unchanged.

Numbers checked: the JSON equals the Python API (simulate_axial, axial_map,
drilling_stability, mode_crossings on rgd_two_dof_example() and rgd_example()); the steady
state equals the closed form d0 = (W0 - σ a l)/(ζ ε a), V0 = Ω0 d0 / 2π,
T0 = ε a² d0 / 2 + μ γ a² σ l / 2, MSE = W0/A + Ω0 T0 / (A V0).
"""

from __future__ import annotations

import io
import json
import math
from importlib import resources

import pytest
from rich.console import Console

from torsio.analysis.map_options import DEFAULT_REFINE
from torsio.analysis.transient import simulate_config
from torsio.axial import (
    DrillingCase,
    axial_map,
    drilling_stability,
    mode_crossings,
    rgd_example,
    rgd_two_dof_example,
    simulate_axial,
)
from torsio.cli import main
from torsio.config.reading import load_config
from torsio.examples import builtin_config, rgd_two_dof_config
from torsio.report.context import ReportContext
from torsio.report.document import render, report_data

EXAMPLE = str(resources.files("torsio").joinpath("data/rgd_2dof.toml"))
TIMES = ["--duration", "20", "--window", "10"]
DESIGN_KEYS = {"rop_mean", "mse_mean", "off_bottom_fraction", "steady_state", "growth_rate"}


def run_json(capsys, *args):
    status = main([*args, "--json"])
    captured = capsys.readouterr()
    assert status == 0, captured.err
    return json.loads(captured.out)


def run_error(capsys, *args):
    status = main(list(args))
    captured = capsys.readouterr()
    assert status == 2 and captured.out == ""
    return captured.err


def test_simulate_json_is_the_python_api(capsys):
    data = run_json(capsys, "simulate", EXAMPLE, *TIMES)
    assert DESIGN_KEYS | {"wob", "rpm", "severity", "stick_fraction", "solver"} <= set(data)
    assert set(data["steady_state"]) == {"depth_of_cut", "rop", "bit_torque", "mse"}
    run = simulate_axial(
        rgd_two_dof_example(), rgd_example(), 100e3, 60.0, duration=20.0, window=10.0
    )
    expected = run.to_dict()
    for key, value in expected.items():
        assert data[key] == value, key
    assert data["solver"] == {
        "engine": "axial",
        "method": "fixed-step",
        "scheme": data["solver"]["scheme"],
        "step": run.axial.step,
    }
    assert "Euler" in data["solver"]["scheme"]
    growth = drilling_stability(rgd_two_dof_example(), rgd_example(), 100e3, 60.0)
    assert data["growth_rate"] == pytest.approx(growth.growth_rate, rel=1e-9)


def test_steady_state_is_the_closed_form(capsys):
    data = run_json(capsys, "simulate", EXAMPLE, "--wob", "120 kN", "--rpm", "90", *TIMES)
    bit = rgd_example()
    a, eps, zeta = bit.radius, bit.intrinsic_specific_energy, bit.cutting_force_ratio
    sigma, wear, mu, gamma = bit.contact_stress, bit.wear_flat_length, 0.6, 1.0
    w0, omega = 120e3, 90 * math.pi / 30
    d0 = (w0 - sigma * a * wear) / (zeta * eps * a)
    v0 = omega * d0 / (2 * math.pi)
    t0 = eps * a**2 * d0 / 2 + mu * gamma * a**2 * sigma * wear / 2
    area = math.pi * a**2
    steady = data["steady_state"]
    assert steady["depth_of_cut"] == pytest.approx(d0, rel=1e-12)
    assert steady["rop"] == pytest.approx(v0, rel=1e-12)
    assert steady["bit_torque"] == pytest.approx(t0, rel=1e-12)
    assert steady["mse"] == pytest.approx(w0 / area + omega * t0 / (area * v0), rel=1e-12)
    assert data["wob"] == 120e3 and data["rpm"] == 90.0


def test_simulate_table_shows_engineering_units(capsys):
    assert main(["simulate", EXAMPLE, *TIMES]) == 0
    out = capsys.readouterr().out
    for text in ("mean ROP", "m/h", "m/s", "MPa", "off-bottom", "stuck", "growth rate"):
        assert text in out


def test_map_json_is_the_python_api(capsys):
    grid = ["--wob", "80kN:120kN:2", "--rpm", "60:150:2"]
    data = run_json(capsys, "map", EXAMPLE, *grid, *TIMES)
    expected = axial_map(
        rgd_two_dof_example(),
        rgd_example(),
        [80e3, 120e3],
        [60.0, 150.0],
        duration=20.0,
        window=10.0,
        growth_rate=True,
        refine=DEFAULT_REFINE,  # the critical weight on bit bisected, as every map's
    ).to_dict()
    for key, value in expected.items():  # info: the run's own wall time
        assert data[key] == value or key == "info", key
    assert len(data["rop"]) == len(data["severity"]) == 2
    assert all(len(row) == 2 for row in data["mse"])
    assert data["info"]["engine"] == "axial"


@pytest.mark.parametrize("flags", [["--threads", "2"], ["--workers", "2"]])
def test_map_runs_on_threads_and_workers_as_the_serial_map(capsys, flags):
    # reference: the Python map on one thread (identical to the bit wherever it runs)
    grid = ["--wob", "80kN:120kN:2", "--rpm", "60:150:2"]
    data = run_json(capsys, "map", EXAMPLE, *grid, *TIMES, *flags)
    serial = axial_map(rgd_two_dof_example(), rgd_example(), [80e3, 120e3], [60.0, 150.0],
                       duration=20.0, window=10.0, growth_rate=True, threads=1,
                       refine=DEFAULT_REFINE)  # fmt: skip
    for key, value in serial.to_dict().items():  # info: the run's own wall time, executor
        assert data[key] == value or key == "info", key
    assert data["info"]["executor"] == ("threads(2)" if flags[0] == "--threads" else "processes(2)")


@pytest.mark.parametrize(
    "flags",
    [
        ["simulate", "--rtol", "1e-3"],
        ["simulate", "--method", "RK45"],
        ["simulate", "--strategy", "A"],
        ["simulate", "--output-step", "0.1"],
        ["map", "--rtol", "1e-3"],
        ["map", "--pi1", "0.5:1:2", "--pi2", "1:2:2"],
        ["map", "--engine", "numpy"],
    ],
)
def test_flags_the_axial_engine_lacks_are_refused(capsys, flags):
    command, *rest = flags
    err = run_error(capsys, command, EXAMPLE, *rest)
    assert flags[1] in err


def test_report_has_the_axial_section():
    ctx = ReportContext(rgd_two_dof_config())  # computed once: JSON and terminal alike
    section = report_data(ctx)["axial"]
    assert section["steady_state"]["depth_of_cut"] == pytest.approx(0.0073868312757, rel=1e-9)
    case = DrillingCase(rgd_two_dof_example(), rgd_example(), 100e3)
    crossings = [c.rpm for c in mode_crossings(case, (20.0, 300.0), points=15)]
    assert section["stability"]["crossing_rpm"] == crossings
    assert section["stability"]["growth_rate"] > 0
    console = Console(width=80, record=True, file=io.StringIO())
    render(ctx, console)
    out = console.export_text()
    assert "Axial dynamics" in out and "crossing rpm" in out and "153.3 rpm" in out


def test_report_html_and_json_of_an_axial_file(capsys, tmp_path):
    page = tmp_path / "report.html"
    data = run_json(capsys, "report", EXAMPLE, "--html", str(page))
    assert list(data) == ["name", "source", "chain", "axial"]
    assert "Axial dynamics" in page.read_text(encoding="utf-8")


def test_torsional_commands_refuse_rgd_by_key(capsys, tmp_path):
    text = open(EXAMPLE, encoding="utf-8").read()
    text = text.replace("masses = [29981.3]", "").replace("axial_stiffnesses = []", "")
    text = text.split("[axial]")[0] + "[bit_rock]" + text.split("[bit_rock]")[1]
    text = text.split("[simulation]")[0]
    path = tmp_path / "torsional_rgd.toml"
    path.write_text(text, encoding="utf-8")
    for command in ("simulate", "map", "report"):
        err = run_error(capsys, command, str(path))
        assert "bit_rock.law: the rgd law needs axial dynamics" in err


# the keys of `torsio simulate --json` on the built-in example before axial dynamics came in
TORSIONAL_KEYS = {
    "bit_radius", "bit_speed_max", "bit_speed_min", "dimensionless", "dofs", "duration_s",
    "law", "mean_bit_torque", "mean_motor_torque", "mean_surface_torque", "omega_rad_s",
    "output_step_s", "rpm", "rpm_source", "samples", "severe", "severity", "solver",
    "steady_window_s", "stick_fraction", "stick_threshold", "strategy", "top_drive",
    "top_speed_mean", "warnings", "wob",
}  # fmt: skip


def test_torsional_simulate_is_unchanged(capsys):
    data = run_json(capsys, "simulate", "--strategy", "A", "--duration", "60", "--window", "20")
    assert set(data) == TORSIONAL_KEYS
    expected = simulate_config(
        builtin_config(), discretization={"strategy": "A"}, duration=60.0, steady_window=20.0
    ).to_dict()
    expected["solver"].pop("wall_time_s")
    data["solver"].pop("wall_time_s")
    assert json.loads(json.dumps(expected)) == data


STRING_FILE = """
[material]
youngs_modulus = "207 GPa"
[[section]]
kind = "drill_pipe"
od = "5 in"
id = "4.276 in"
length = "1000 m"
[[section]]
kind = "drill_collar"
od = "6.75 in"
id = "2.8125 in"
length = "150 m"
[[section]]
kind = "bit"
od = "8.5 in"
id = 0
length = 0.3
[damping]
beta = 0.06
"""


def test_simulate_a_string_with_the_rgd_law(capsys, tmp_path):
    text = open(EXAMPLE, encoding="utf-8").read()
    bit = "[bit_rock]" + text.split("[bit_rock]")[1].split("[simulation]")[0]
    path = tmp_path / "string.toml"
    path.write_text(STRING_FILE + bit, encoding="utf-8")
    data = run_json(capsys, "simulate", str(path), *TIMES)
    config = load_config(path)
    expected = simulate_axial(
        config.axial.assembly, rgd_example(), 100e3, 60.0, duration=20.0, window=10.0
    ).to_dict()
    assert data["model"]["nodes"] == 10
    # a chain has its growth rate too: the rightmost root of its linearization
    stability = drilling_stability(config.axial.assembly, rgd_example(), 100e3, 60.0, count=1)
    assert data["growth_rate"] == stability.growth_rate
    for key, value in expected.items():
        assert data[key] == value, key
    path.write_text(STRING_FILE.replace('youngs_modulus = "207 GPa"', "") + bit, encoding="utf-8")
    assert "material.youngs_modulus: missing" in run_error(capsys, "simulate", str(path))
