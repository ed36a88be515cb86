"""``torsio map``: JSON contract, ranges with units, files, executors, errors, Ctrl-C.

Source of the reference numbers: the library call torsio.analysis.maps.severity_map on the
same grid (the command must print what the library computes), and the DESIGN.md
contract for the JSON keys.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from torsio.analysis import map_results, maps
from torsio.cli import main
from torsio.examples import builtin_config

ARGS = ["--strategy", "A", "--wob", "25kN:225kN:3", "--rpm", "40:140:3"]


def run_json(capsys: pytest.CaptureFixture[str], *args: str) -> dict:
    assert main(["map", *args, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.fixture(scope="module")
def library_map() -> map_results.SeverityMap:
    system = builtin_config().system(strategy="A")
    return maps.severity_map(system, [25e3, 125e3, 225e3], [40.0, 90.0, 140.0])


def test_json_contract(capsys, library_map) -> None:
    data = run_json(capsys, *ARGS)
    assert {"wob", "rpm", "severity", "critical_wob"} <= set(data)
    assert data["wob"] == [25e3, 125e3, 225e3] and data["rpm"] == [40.0, 90.0, 140.0]
    assert np.array_equal(np.array(data["severity"]), library_map.severity)  # [i][j]: rpm, wob
    expected = [None if np.isnan(w) else w for w in library_map.critical_wob]
    assert data["critical_wob"] == expected
    assert data["critical_wob"][2] is None  # 140 rpm: never severe up to 225 kN
    assert data["complete"] is True


def test_ranges_accept_units(capsys) -> None:
    data = run_json(
        capsys,
        "--strategy",
        "A",
        "--wob",
        "25 kN:0.225 MN:2",
        "--rpm",
        "40 rpm:4.5 rad/s:2",
        "--refine",
        "0",
    )
    assert data["wob"] == [25e3, 225e3]
    assert data["rpm"] == pytest.approx([40.0, 4.5 * 30 / np.pi])


def test_dimensionless_grid(capsys) -> None:
    data = run_json(
        capsys, "--strategy", "A", "--pi1", "5:10:2", "--pi2", "10:40:2", "--refine", "0"
    )
    assert data["pi1"] == pytest.approx([5.0, 10.0]) and data["pi2"] == pytest.approx([10.0, 40.0])
    assert data["dimensionless"] is True and len(data["critical_pi2"]) == 2


def test_human_output(capsys) -> None:
    assert main(["map", *ARGS]) == 0
    out = capsys.readouterr().out
    assert "critical WOB [kN]" in out and "severe" in out and "linear stability" in out


def test_files(tmp_path: Path, capsys) -> None:
    out, csv, plot = tmp_path / "m.json", tmp_path / "m.csv", tmp_path / "m.png"
    data = run_json(capsys, *ARGS, "--out", str(out), "--csv", str(csv), "--plot", str(plot))
    assert map_results.load_map(out).to_dict()["severity"] == data["severity"]
    assert len(csv.read_text().splitlines()) == 1 + 9
    assert plot.read_bytes()[:4] == b"\x89PNG"
    npz = tmp_path / "m.npz"
    run_json(capsys, *ARGS, "--out", str(npz))
    assert map_results.load_map(npz).to_dict()["severity"] == data["severity"]


def test_workers_give_the_serial_result(capsys) -> None:
    serial = run_json(capsys, *ARGS)
    parallel = run_json(capsys, *ARGS, "--workers", "2")
    assert parallel["severity"] == serial["severity"]
    assert parallel["critical_wob"] == serial["critical_wob"]


@pytest.mark.parametrize(
    "args, message",
    [
        (["--wob", "225kN:25kN:3"], "--wob: reversed range"),
        (["--wob", "25kN:225kN:0"], "--wob: empty range"),
        (["--rpm", "60:60:5"], "--rpm: empty range"),
        (["--rpm", "40:140:2.5"], "--rpm: N in START:STOP:N must be a whole number"),
        (["--rpm", "40:140"], "--rpm: expected START:STOP:N"),
        (["--wob=-5kN:25kN:3"], "--wob: expected non-negative"),
        (["--rpm", "0:140:3"], "--rpm: expected a positive rotary speed"),
        (["--wob", "25 parsec:1:2"], "--wob: '25 parsec' is not a force"),
        (
            ["--wob", "0:1:100000", "--rpm", "1:2:100000"],
            "--wob/--rpm: a grid of 100,000 rpm x 100,000 wob = 10,000,000,000 points needs about",
        ),
        (["--workers", "0"], "--workers: expected a number of processes"),
        (["--workers", "2", "--scheduler", "tcp://127.0.0.1:9"], "--workers: give either"),
        (["--wob", "1:2:2", "--pi2", "1:2:2"], "--pi2: give either --wob or --pi2"),
        (["--pi1", "1:2:2"], "--pi2: a dimensionless map needs both"),
        (["--threshold", "-1"], "--threshold: expected a non-negative number"),
        (["--engine", "rk4"], "--engine: expected one of"),
        (["--out", "/nonexistent-dir/map.json"], "--out: directory"),
    ],
)
def test_errors_name_the_option(capsys, args: list[str], message: str) -> None:
    assert main(["map", "--strategy", "A", *args]) == 2
    captured = capsys.readouterr()
    assert message in captured.err
    assert captured.out == ""


def test_unreachable_scheduler(capsys) -> None:
    assert main(["map", *ARGS, "--scheduler", "tcp://127.0.0.1:9", "--timeout", "1"]) == 2
    assert (
        "--scheduler: cannot reach the Dask scheduler at 'tcp://127.0.0.1:9' within 1 s"
        in capsys.readouterr().err
    )


def test_ctrl_c_writes_only_a_partial_file(tmp_path: Path, capsys, monkeypatch) -> None:
    real = maps.severity_map

    def interrupted(*args, **kwargs):
        def progress(done: int, total: int) -> None:
            raise KeyboardInterrupt

        return real(*args, **{**kwargs, "progress": progress, "chunk_size": 2})

    monkeypatch.setattr(maps, "severity_map", interrupted)
    out = tmp_path / "map.json"
    assert main(["map", *ARGS, "--out", str(out), "--json"]) == 130
    captured = capsys.readouterr()
    assert not out.exists()  # never written as if complete
    partial = json.loads((tmp_path / "map.partial.json").read_text())
    assert partial["complete"] is False
    assert sum(map(sum, partial["done"])) == 2
    assert "partial results written" in captured.err and captured.out == ""


def test_the_map_counts_its_points_on_stderr_with_or_without_json(monkeypatch, capsys) -> None:
    # stdout keeps the one JSON object; the points done go to stderr after 2 s, a bar on a
    # terminal, else a line every 4 s (torsio.solvers.run_chunks.stderr_progress)
    import io

    from torsio.solvers.run_chunks import stderr_progress

    seen = {}
    real = maps.severity_map

    def spy(*args, **kwargs):
        seen["progress"] = kwargs.get("progress")
        return real(*args, **kwargs)

    monkeypatch.setattr(maps, "severity_map", spy)
    run_json(capsys, *ARGS)
    assert seen["progress"].unit == "points" and seen["progress"].label == "map"
    main(["map", *ARGS])
    assert seen["progress"].unit == "points"
    capsys.readouterr()
    stream = io.StringIO()
    report = stderr_progress("map", stream, quiet=0.0, every=0.0, unit="points")
    report(16, 36)
    report.close()
    assert stream.getvalue().startswith("torsio: map: 44% (16 of 36 points), ")


def test_the_files_simulation_tolerances_reach_the_map(capsys, tmp_path: Path) -> None:
    # [simulation] rtol/atol set the map's engine too (--rtol wins); the keys of single runs
    # only are said on stderr, never silently dropped
    from importlib import resources

    text = resources.files("torsio").joinpath("data/ritto2017.toml").read_text(encoding="utf-8")
    path = tmp_path / "tolerances.toml"
    path.write_text(text + "\n[simulation]\nrtol = 1e-4\natol = 1e-5\noutput_step = 0.05\n")
    assert main(["map", str(path), *ARGS, "--json"]) == 0
    captured = capsys.readouterr()
    data = json.loads(captured.out)
    assert (data["info"]["rtol"], data["info"]["atol"]) == (1e-4, 1e-5)
    assert "[simulation] output_step apply to single runs" in captured.err
    data = run_json(capsys, str(path), *ARGS, "--rtol", "1e-6")
    assert data["info"]["rtol"] == 1e-6
