"""``torsio simulate`` and ``torsio laws``: JSON contract of DESIGN.md, files, errors.

Numbers checked: the JSON equals the library's result for the same options
(torsio.analysis.transient.simulate_config); 100 kN = 100000 N (unit conversion).
"""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from torsio.analysis.transient import simulate_config
from torsio.cli import main
from torsio.examples import builtin_config

FAST = ["--strategy", "A", "--duration", "60", "--window", "20"]


def run_json(capsys, *args):
    status = main(["simulate", *args, "--json"])
    captured = capsys.readouterr()
    assert status == 0, captured.err
    return json.loads(captured.out)


def run_error(capsys, *args):
    status = main(list(args))
    captured = capsys.readouterr()
    assert status == 2
    assert captured.out == ""
    return captured.err


def test_simulate_json_contract(capsys):
    data = run_json(capsys, "--wob", "100 kN", "--rpm", "60", *FAST)
    assert {"wob", "rpm", "severity"} <= set(data)
    assert data["wob"] == 100000.0 and data["rpm"] == 60.0
    expected = simulate_config(
        builtin_config(),
        wob="100 kN",
        rpm=60,
        discretization={"strategy": "A"},
        duration=60.0,
        steady_window=20.0,
    )
    assert data["severity"] == expected.severity
    assert data["solver"]["method"] == "RODAS4" and data["solver"]["status"] == 0
    assert data["solver"]["engine"] == "compiled"
    assert data["duration_s"] == 60.0 and data["steady_window_s"] == 20.0


def test_simulate_defaults_from_the_file(capsys):
    """Without --wob/--rpm the [operation] table of the file is used (100 kN, 100 rpm)."""
    data = run_json(capsys, *FAST)
    assert data["wob"] == 100000.0 and data["rpm"] == 100.0


def test_simulate_options_and_units(capsys):
    data = run_json(
        capsys,
        "--wob",
        "22.5 klbf",
        "--rpm",
        "6.283185307179586 rad/s",
        "--strategy",
        "A",
        "--duration",
        "1 min",
        "--window",
        "20 s",
        "--method",
        "Radau",
        "--rtol",
        "1e-7",
        "--atol",
        "1e-10",
    )
    assert data["wob"] == pytest.approx(22.5 * 4448.2216152605)
    assert data["rpm"] == pytest.approx(60.0)
    assert data["duration_s"] == 60.0
    assert data["solver"]["method"] == "Radau" and data["solver"]["rtol"] == 1e-7


def test_simulate_csv_and_plot(capsys, tmp_path):
    csv = tmp_path / "series.csv"
    png = tmp_path / "series.png"
    data = run_json(
        capsys, "--wob", "100 kN", "--rpm", "60", *FAST, "--csv", str(csv), "--plot", str(png)
    )
    table = np.genfromtxt(csv, delimiter=",", names=True)
    assert table.size == data["samples"]
    assert {"time_s", "bit_speed_rad_s", "surface_torque_Nm", "bit_torque_Nm"} <= set(
        table.dtype.names
    )
    window = table["time_s"] >= 60.0 - 20.0 - 1e-9
    speeds = table["bit_speed_rad_s"][window]
    # the CSV holds the samples; S_SS (compiled engine) is read from the continuous
    # solution's extremes, which the samples under-read by the output grid's error
    # (2e-5 here; docs/dynamics.md, "Output step")
    sampled = (speeds.max() - speeds.min()) / (2 * 2 * np.pi)
    assert data["solver"]["engine"] == "compiled"
    assert sampled <= data["severity"] + 1e-12 and data["severity"] - sampled < 5e-5
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_plot_without_matplotlib(capsys, tmp_path, monkeypatch):
    for name in [m for m in sys.modules if m == "matplotlib" or m.startswith("matplotlib.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # import matplotlib -> ImportError
    err = run_error(
        capsys,
        "simulate",
        "--wob",
        "100 kN",
        "--rpm",
        "60",
        *FAST,
        "--plot",
        str(tmp_path / "x.png"),
    )
    assert "--plot: needs matplotlib" in err and "torsio[plot]" in err
    assert not (tmp_path / "x.png").exists()


def test_human_summary(capsys):
    assert main(["simulate", "--wob", "100 kN", "--rpm", "60", *FAST]) == 0
    out = capsys.readouterr().out
    assert "S_SS" in out and "RODAS4 (compiled engine)" in out


@pytest.mark.parametrize(
    ("args", "fragments"),
    [
        (["--wob=-5 kN", "--rpm", "60"], ["--wob", "non-negative", "'-5 kN'"]),
        (["--wob", "100 kN", "--rpm", "0"], ["--rpm", "positive", "'0'"]),
        (["--wob", "100 kN", "--rpm=-30"], ["--rpm", "positive", "'-30'"]),
        (["--wob", "100 kN", "--rpm", "60", "--window", "90"], ["--window", "longer than the run"]),
        (["--wob", "100 kN", "--rpm", "60", "--method", "Euler"], ["--method", "'Euler'"]),
        (["--wob", "100 kN", "--rpm", "60", "--rtol", "0"], ["--rtol", "0.0"]),
        (["--wob", "100 kN", "--rpm", "60", "--duration", "10 kg"], ["--duration", "10 kg"]),
        (["--wob", "100 m", "--rpm", "60"], ["wob", "'100 m'"]),
        (["--wob", "100 kN", "--rpm", "60", "--strategy", "Z"], ["strategy", "'Z'"]),
    ],
)
def test_bad_input_names_the_value(capsys, args, fragments):
    extra = [] if "--strategy" in args else ["--strategy", "A"]
    if not any(a.startswith("--duration") for a in args):
        extra += ["--duration", "60"]
    err = run_error(capsys, "simulate", *args, *extra)
    for fragment in fragments:
        assert fragment in err, err


def _write(tmp_path, bit_rock: str) -> str:
    text = (
        "[[section]]\nkind = 'drill_pipe'\nod = 0.140\nid = 0.119\nlength = 4733.6\n"
        "[[section]]\nkind = 'bit'\nod = 0.216\nid = 0.057\nlength = 0.25\n"
        f"[bit_rock]\n{bit_rock}\n[discretization]\nstrategy = 'A'\n"
    )
    path = tmp_path / "string.toml"
    path.write_text(text)
    return str(path)


@pytest.mark.parametrize(
    ("bit_rock", "fragments"),
    [
        ("law = 'nope'", ["bit_rock.law", "'nope'", "tucker-wang"]),
        ("law = 'tucker-wang'\na1 = 0.2\na2 = 0.89\na3 = 0.06", ["bit_rock.a0", "needs"]),
        ("law = 'tucker-wang'\na0 = -0.2\na1 = 0.2\na2 = 0.89\na3 = 0.06", ["bit_rock.a0", "-0.2"]),
        ("law = 'coulomb-stribeck'\nmu_static = 0.3", ["bit_rock.mu_coulomb", "0.5", "0.3"]),
    ],
)
def test_bad_law_in_the_file(capsys, tmp_path, bit_rock, fragments):
    path = _write(tmp_path, bit_rock)
    err = run_error(capsys, "simulate", path, "--wob", "100 kN", "--rpm", "60")
    for fragment in fragments:
        assert fragment in err, err


def test_missing_operating_point(capsys, tmp_path):
    path = _write(tmp_path, "law = 'constant'\ntorque_on_bit = 1000.0")
    err = run_error(capsys, "simulate", path, "--rpm", "60")
    assert "operation.wob" in err and "--wob" in err


def test_laws_json(capsys):
    assert main(["laws", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    laws = {law["name"]: law for law in data["laws"]}
    assert {"tucker-wang", "constant", "coulomb-stribeck", "generalized-stribeck"} <= set(laws)
    for law in laws.values():
        assert isinstance(law["parameters"], list)
    names = [p["name"] for p in laws["tucker-wang"]["parameters"]]
    assert names == ["a0", "a1", "a2", "a3"]
    stribeck = {p["name"]: p for p in laws["coulomb-stribeck"]["parameters"]}
    assert stribeck["mu_static"]["default"] == 0.8
    # the RGD bit of the axial engine, with the [bit_rock] keys of DESIGN.md's axial example
    rgd = laws["rgd"]
    assert rgd["engine"] == "axial" and laws["tucker-wang"]["engine"] == "torsional"
    keys = {p["name"]: p for p in rgd["parameters"]}
    assert set(keys) == {
        "radius", "blades", "intrinsic_specific_energy", "cutting_force_ratio",
        "contact_stress", "wear_flat_length", "contact_friction", "bit_geometry",
    }  # fmt: skip
    assert keys["bit_geometry"]["default"] == 1.0 and keys["radius"]["default"] is None
    assert keys["contact_stress"]["unit"] == "Pa"


def test_laws_human(capsys):
    assert main(["laws"]) == 0
    out = capsys.readouterr().out
    assert "tucker-wang" in out and "coulomb-stribeck" in out
    assert "[rad/s]" in out  # units shown, not swallowed as markup


def test_console_entry_point():
    """The installed command, as a user runs it (one process, strategy A)."""
    result = subprocess.run(
        [
            sys.executable,
            "-m",
            "torsio",
            "simulate",
            "--wob",
            "150 kN",
            "--rpm",
            "60",
            *FAST,
            "--json",
        ],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["wob"] == 150000.0 and data["severity"] > 0.8


def test_small_bare_wob_warns_on_stderr(capsys):
    # bare numbers are N (DESIGN.md: bare numbers are SI); 150 N is no drilling load
    assert main(["simulate", *FAST, "--wob", "150", "--rpm", "100", "--json"]) == 0
    captured = capsys.readouterr()
    assert json.loads(captured.out)["wob"] == 150.0  # taken as given, not rescaled
    assert "--wob 150 is 150 N (bare numbers are N); did you mean '150 kN'?" in captured.err
    assert main(["simulate", *FAST, "--wob", "150 kN", "--rpm", "100", "--json"]) == 0
    assert "warning" not in capsys.readouterr().err


def test_fallback_to_scipy_is_one_line_on_stderr(capsys, monkeypatch):
    # a model the compiled engine cannot run (stood in for by its check saying so): the run
    # goes to LSODA, the JSON names the engine and the reason, stderr says it in one line
    import torsio.solvers.single_run as single_run

    monkeypatch.setattr(single_run, "compiled_engine", lambda system, dynamics: (None, "a test"))
    status = main(["simulate", "--wob", "100 kN", "--rpm", "60", *FAST, "--json"])
    captured = capsys.readouterr()
    assert status == 0
    data = json.loads(captured.out)  # stdout: one JSON object and nothing else
    assert data["solver"]["engine"] == "scipy" and data["solver"]["method"] == "LSODA"
    assert data["solver"]["fallback"] == "a test"
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and "scipy LSODA" in lines[0] and "(a test)" in lines[0]


def test_progress_only_for_long_runs_off_a_terminal(capsys):
    # stderr is not a terminal here and the run is short: no progress line at all
    assert main(["simulate", "--wob", "100 kN", "--rpm", "60", *FAST, "--json"]) == 0
    captured = capsys.readouterr()
    json.loads(captured.out)
    assert captured.err == ""


def test_a_recording_written_by_simulate_is_fitted_back_to_its_friction(capsys, tmp_path):
    # reference: the configuration's open-hole mu_d = 0.3 (data/deviated_well.toml); the fit
    # drives the same wave grid with the recorded top speed, so the record is its own model
    # (measured: 0.3 to 3e-12, residual 7e-8 N m)
    from importlib import resources

    source = tmp_path / "well.toml"
    text = resources.files("torsio").joinpath("data/deviated_well.toml").read_text()
    # the fit's grid (contacts on every node): the record is made by the fit's own model
    source.write_text(text.replace('strategy = "wave"', 'strategy = "wave"\ndrag_spacing = 1'))
    recording = tmp_path / "startup.csv"
    run = ["simulate", str(source), "--strategy", "wave", "--wob", "0", "--rpm", "120"]
    assert main([*run, "--duration", "60", "--recording", str(recording), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["recording"] == str(recording)
    header = recording.read_text().splitlines()[0]
    assert header == "time,top_rpm,surface_torque,bit_rpm"
    fit = ["fit", str(source), "--recording", str(recording), "--fit", "friction_dynamic"]
    assert main([*fit, "--no-profile", "--speed-smoothing", "0", "--json"]) == 0
    fitted = json.loads(capsys.readouterr().out)["parameters"]["friction_dynamic"]
    assert fitted == pytest.approx(0.3, abs=1e-6)


def test_units_field_table_and_readable_energy(capsys):
    """--units field: the table's forces in klbf and torques in kft·lbf (1 lbf =
    4.4482216152605 N, 1 ft = 0.3048 m, exact: NIST SP 811, B.8), energy without an
    exponent; the JSON stays SI (the same numbers with and without --units)."""
    from importlib import resources

    path = str(resources.files("torsio").joinpath("data/deviated_well.toml"))
    run = ["simulate", path, "--duration", "20", "--window", "10"]
    assert main([*run, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert main([*run, "--units", "field", "--json"]) == 0
    field_json = json.loads(capsys.readouterr().out)
    assert field_json["friction_work"] == data["friction_work"]
    assert main([*run, "--units", "field"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    lbf, ft_lbf = 4.4482216152605, 0.3048 * 4.4482216152605
    assert f"{data['wob'] / lbf / 1e3:.4g} klbf" in out
    peak = data["surface_torque_peak"]
    assert f"peak surface torque │ {peak / ft_lbf / 1e3:.4g} kft·lbf" in out
    work = data["friction_work"] / ft_lbf / 1e3
    assert f"{work:,.0f} kft·lbf" in out and "e+" not in out
    assert " kN" not in out
