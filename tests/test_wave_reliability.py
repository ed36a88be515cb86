"""Reliability of the wave model (issue 21, cases 1-6 and 13): bounded runs that stop on a
signal, errors that name the key, results that say what limits their meaning.

Every case goes through the command line (``torsio.cli.main`` with captured output, or a
subprocess for the signals) or the API, on the built-in string with ``beta = 0`` (the wave
model refuses Kelvin-Voigt damping, docs/wave.md) and short runs: the default grid steps
about 0.2-0.9 us a step, so a run of 10 s (7 000 steps) takes milliseconds.
"""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import time
from importlib import resources
from pathlib import Path

import attrs
import numpy as np
import pytest

import torsio.solvers.wave_march as wave_march
from torsio.analysis.budget import MAX_WAVE_STEPS, check_wave_steps
from torsio.analysis.limits import short_window, stuck_throughout
from torsio.analysis.wave import wave_response
from torsio.cli import main
from torsio.errors import ConfigError
from torsio.examples import builtin_config
from torsio.model.wave import DEFAULT_TRAVEL_TIME_TOLERANCE, WaveStrategy, first_frequency
from torsio.physics.damping import RayleighDamping
from torsio.solvers.batch import simulate_batch
from torsio.solvers.batch_options import DEFAULT_MAX_STEPS
from torsio.solvers.run_chunks import run_in_chunks, stderr_progress

SRC = Path(__file__).parents[1] / "src"
MAP = ["map", "--wob", "100kN:150kN:2", "--rpm", "60:80:2", "--refine", "0"]


def _wave_config(tmp_path: Path, discretization: str = "", name: str = "wave.toml") -> str:
    """The built-in file with beta = 0, strategy wave and extra [discretization] lines."""
    text = resources.files("torsio").joinpath("data/ritto2017.toml").read_text(encoding="utf-8")
    text = text.replace("beta = 0.06", "beta = 0.0")
    text = text.replace('strategy = "C"\ndp_elements = 5\nbha_elements = 1', 'strategy = "wave"')
    text = text.replace('strategy = "wave"', f'strategy = "wave"\n{discretization}')
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def _system(**grid: object):  # type: ignore[no-untyped-def]
    system = builtin_config().system(strategy="wave", **grid)
    return attrs.evolve(system, damping=RayleighDamping(alpha=0.35)).at(wob=150e3, rpm=60)


def _refused(capsys, *args: str) -> str:  # type: ignore[no-untyped-def]
    """``torsio ARGS`` ends with status 2, no traceback; returns stderr."""
    status = main(list(args))
    captured = capsys.readouterr()
    assert status == 2, (status, captured.err)
    assert "Traceback" not in captured.err
    assert captured.out == ""
    return captured.err


# --- case 1: a work budget up front, progress on stderr ------------------------------------
def test_a_run_beyond_the_work_budget_is_refused_naming_the_deciding_key(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    # time_step = 1e-5: 157 241 nodes x 30.6 million steps of the default run (306 s)
    fine = _wave_config(tmp_path, "time_step = 1e-5")
    err = _refused(capsys, "simulate", fine, "--json")
    assert "discretization.time_step" in err and "2,000,000 steps" in err
    # --duration 1e6 on the default grid: 695 million steps of 1.4386 ms
    err = _refused(capsys, "simulate", _wave_config(tmp_path), "--duration", "1e6", "--json")
    assert err.startswith("torsio simulate: error: --duration (simulation.duration)")
    assert "at most 2877.21 s" in err  # 2,000,000 steps of 1.4386 ms


def test_the_budget_is_that_of_a_map_point() -> None:
    # docs/cli.md: a map point past 2 000 000 steps fails; one run has the same limit
    assert MAX_WAVE_STEPS == DEFAULT_MAX_STEPS == 2_000_000
    grid = WaveStrategy().discretize(builtin_config().string)
    assert check_wave_steps(grid, 2_000_000 * grid.time_step) == 2_000_000
    with pytest.raises(ConfigError, match="simulation.duration"):
        check_wave_steps(grid, 2_000_001 * grid.time_step)


def test_progress_reaches_its_total_and_stays_off_stdout(tmp_path, capfd, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    calls: list[tuple[int, int]] = []
    response = wave_response(
        _system(), duration=20.0, steady_window=10.0, progress=lambda d, t: calls.append((d, t))
    )
    steps = response.transient.solver["steps"]
    assert calls[-1] == (steps, steps) and all(t == steps for _, t in calls)
    # not a terminal: one line every `every` seconds after `quiet`, on the given stream
    import io

    stream = io.StringIO()
    clock = iter([0.0, 10.0, 30.0])  # the reporter's start, then its two calls [s]
    with monkeypatch.context() as patch:
        patch.setattr("torsio.solvers.run_chunks.time.perf_counter", lambda: next(clock))
        report = stderr_progress("wave run", stream, quiet=0.0, every=0.0)
        report(1000, 4000)
        report(2000, 4000)
    report.close()
    first, second = stream.getvalue().splitlines()
    # the first line has no rate yet (the first steps may hold numba's compile); the second
    # the rate since the first, 1000 steps in 20 s: 2000 steps left take 40 s
    assert first == "torsio: wave run: 25% (1,000 of 4,000 steps), 10 s, time left not known yet"
    assert second == "torsio: wave run: 50% (2,000 of 4,000 steps), 30 s, about 40 s left"
    # --json: one JSON object on stdout, nothing else
    status = main(["simulate", _wave_config(tmp_path), "--duration", "10", "--json"])
    out = capfd.readouterr().out
    assert status == 0 and json.loads(out)["strategy"] == "wave"


# --- case 2: chunks of bounded wall time, bit-identical; SIGINT / SIGTERM ---------------------
def test_steps_in_chunks_are_bit_identical_to_one_call(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    def whole(total, advance, progress=None):  # type: ignore[no-untyped-def]
        return run_in_chunks(total, advance, progress, first=total)

    def irregular(total, advance, progress=None):  # type: ignore[no-untyped-def]
        done, calls, sizes = 0, 0, [1, 7, 1000, 3, 2345]
        while done < total:
            k = min(sizes[calls % len(sizes)], total - done)
            stopped = advance(k)
            done, calls = done + k, calls + 1
            if stopped:
                break
        return done

    runs = []
    for chunks in (whole, irregular):
        monkeypatch.setattr(wave_march, "run_in_chunks", chunks)
        response = wave_response(_system(), duration=15.0, steady_window=7.0)
        points = simulate_batch(  # a steady cycle ends the first point early
            _system(), [50e3, 150e3], [120.0, 60.0], duration=60.0, steady_window=20.0, threads=1
        )
        runs.append((response.run, points))
    (one, map_one), (many, map_many) = runs
    assert np.array_equal(one.records, many.records, equal_nan=True)
    assert one.summary == many.summary
    assert np.array_equal(one.state.p, many.state.p) and np.array_equal(one.state.m, many.state.m)
    assert np.array_equal(map_one.severity, map_many.severity)
    assert np.array_equal(map_one.steps, map_many.steps) and map_one.steps[0] < map_one.steps[1]


@pytest.fixture(scope="module")
def long_run(tmp_path_factory):  # type: ignore[no-untyped-def]
    """(command, environment) of a wave run whose kernel is compiled into the cache."""
    # time_step = 1e-4: 15 726 nodes; 199 s are 1.99 million steps, about 10 s of stepping
    config = _wave_config(tmp_path_factory.mktemp("signals"), "time_step = 1e-4")
    env = {**os.environ, "PYTHONPATH": f"{SRC}{os.pathsep}{os.environ.get('PYTHONPATH', '')}"}
    command = [sys.executable, "-m", "torsio", "simulate", config, "--json"]
    warm = subprocess.run([*command, "--duration", "1"], env=env, capture_output=True, timeout=120)
    assert warm.returncode == 0, warm.stderr
    return command, env


@pytest.mark.parametrize(("name", "status"), [("SIGINT", 130), ("SIGTERM", 143)])
def test_a_signal_stops_a_long_wave_run(long_run, name, status) -> None:  # type: ignore[no-untyped-def]
    command, env = long_run
    process = subprocess.Popen(
        [*command, "--duration", "199"], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE
    )
    try:
        time.sleep(3.0)  # past the start (about 1 s), stepping
        assert process.poll() is None, process.communicate()
        sent = time.monotonic()
        process.send_signal(getattr(signal, name))
        out, err = process.communicate(timeout=2.0)
        assert time.monotonic() - sent < 2.0
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
    assert process.returncode == status, err
    assert out == b"" and b"Traceback" not in err


# --- case 3: drag_spacing within the grid ---------------------------------------------------
@pytest.mark.parametrize("spacing", ["1000000000", "2000", "996"])
def test_a_drag_spacing_beyond_the_longest_section_is_refused(tmp_path, capsys, spacing) -> None:  # type: ignore[no-untyped-def]
    config = _wave_config(tmp_path, f"drag_spacing = {spacing}")
    err = _refused(capsys, "simulate", config, "--duration", "1")
    # 995 cells: the drill pipes on the default grid (docs/wave.md)
    assert "discretization.drag_spacing: expected 1 to 995 cells" in err
    assert f"got {spacing}" in err


def test_the_longest_section_s_cells_are_a_drag_spacing(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    status = main(["simulate", _wave_config(tmp_path, "drag_spacing = 995"), "--duration", "5"])
    assert status == 0, capsys.readouterr().err


# --- case 4: a grid that honours its tolerance, or an error ----------------------------------
@pytest.mark.parametrize("step", [1.0, 0.1, 1e300])
def test_a_long_time_step_still_gives_a_grid_within_the_tolerance(step) -> None:
    grid = WaveStrategy(time_step=step).discretize(builtin_config().string)
    assert grid.travel_time_errors.max() <= DEFAULT_TRAVEL_TIME_TOLERANCE
    # the default grid (docs/wave.md): the largest step within 3e-4
    assert grid.cells == (995, 36, 62) and round(grid.time_step * 1e3, 4) == 1.4386


def test_a_tolerance_no_grid_can_meet_is_refused(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    config = _wave_config(tmp_path, "travel_time_tolerance = 1e-300")
    err = _refused(capsys, "simulate", config, "--duration", "1")
    assert "discretization.travel_time_tolerance" in err and "200,000 cells" in err
    assert "expected a tolerance of at least" in err


def test_a_tiny_time_step_is_refused_with_the_prefix_and_short_numbers(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    err = _refused(capsys, "simulate", _wave_config(tmp_path, "time_step = 1e-300"))
    assert "discretization.time_step" in err and "1.57e+300 cells" in err
    assert not re.search(r"\d{12}", err)  # no 300-digit cell count


# --- case 5: runs and windows too short ------------------------------------------------------
def test_a_run_shorter_than_a_step_is_refused(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    config = _wave_config(tmp_path)
    err = _refused(capsys, "simulate", config, "--duration", "1e-6")
    assert "--duration (simulation.duration)" in err and "shorter than one time step" in err
    err = _refused(capsys, *MAP, config, "--duration", "1e-6")
    assert "--duration" in err and "shorter than one time step" in err
    # 0.01 s: the default window (half the run) holds 3 steps of 1.4386 ms
    err = _refused(capsys, "simulate", config, "--duration", "0.01")
    assert "--duration (simulation.duration)" in err and "fewer than 10 time steps" in err


def test_a_window_with_too_few_samples_is_refused(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    config = _wave_config(tmp_path)
    err = _refused(capsys, "simulate", config, "--window", "1e-6")
    assert "--window (simulation.steady_window)" in err and "fewer than 10 time steps" in err
    err = _refused(capsys, *MAP, config, "--duration", "5", "--window", "1e-6")
    assert "--window" in err and "fewer than 10 time steps" in err
    # the lumped rule (simulation_options.MIN_WINDOW_SAMPLES): 10 output samples
    err = _refused(capsys, "simulate", config, "--duration", "2", "--window", "0.2")
    assert "--output-step (simulation.output_step)" in err and "fewer than 10 samples" in err


def test_a_wave_run_says_what_limits_its_meaning(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    # a window shorter than the first period (7.648 s, the grid string's first mode)
    status = main(
        ["simulate", _wave_config(tmp_path), "--duration", "20", "--window", "3", "--json"]
    )
    captured = capsys.readouterr()
    period = 2 * np.pi / first_frequency(_system().model)
    expected = short_window(3.0, period)
    assert status == 0 and json.loads(captured.out)["warnings"] == [expected]
    assert f"warning: {expected}" in captured.err
    # 10 MN: the static bit torque (239 kN m) needs about 70 s of twist; stuck over 20-40 s,
    # the warning of the lumped transient (analysis.limits)
    stuck = wave_response(_system().at(wob=1e7, rpm=60), duration=40.0, steady_window=20.0)
    assert stuck.transient.warnings == (stuck_throughout(1.0, 0.1),)


# --- case 6: options the wave model has no use for; over-long map points ----------------------
@pytest.mark.parametrize("engine", ["bogus", "numpy", "scipy"])
def test_a_wave_map_refuses_an_engine_it_does_not_have(tmp_path, capsys, engine) -> None:  # type: ignore[no-untyped-def]
    err = _refused(capsys, *MAP, _wave_config(tmp_path), "--duration", "5", "--engine", engine)
    assert err.startswith("torsio map: error: --engine:") and repr(engine) in err


def test_tolerances_and_integrators_are_refused_on_the_wave_model(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    config = _wave_config(tmp_path)
    err = _refused(capsys, *MAP, config, "--duration", "5", "--rtol", "1e-4")
    assert err.startswith("torsio map: error: --rtol (simulation.rtol): has no effect")
    for option, value in (("--rtol", "1e-8"), ("--atol", "1e-3"), ("--method", "Radau")):
        err = _refused(capsys, "simulate", config, "--duration", "5", option, value)
        assert err.startswith(f"torsio simulate: error: {option} (simulation.")
    with pytest.raises(ConfigError, match="engine"):
        simulate_batch(_system(), [1e5], [60.0], duration=5.0, engine="numpy")


def test_the_python_run_of_a_wave_file_refuses_and_notes_integrator_options(tmp_path) -> None:  # type: ignore[no-untyped-def]
    # as the command line: an option given is refused by key, the file's is noted on the run
    from torsio.analysis.transient import simulate_config
    from torsio.config.reading import load_config

    config = load_config(_wave_config(tmp_path))
    with pytest.raises(ConfigError) as caught:
        simulate_config(config, duration=5.0, atol=1e-3)
    assert caught.value.key == "simulation.atol" and "has no effect" in caught.value.message
    text = (
        Path(_wave_config(tmp_path)).read_text(encoding="utf-8") + "\n[simulation]\nrtol = 1e-6\n"
    )
    path = tmp_path / "with_rtol.toml"
    path.write_text(text, encoding="utf-8")
    run = simulate_config(load_config(path), duration=5.0, progress=False)
    assert [w for w in run.warnings if w.startswith("[simulation] rtol not used: the wave")]


def test_a_wave_map_point_past_the_step_limit_is_refused_up_front(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    # 3000 s: 2.09 million steps of 1.4386 ms, beyond the 2,000,000 of docs/cli.md
    err = _refused(capsys, *MAP, _wave_config(tmp_path), "--duration", "3000")
    assert "--duration" in err and "2,000,000 steps" in err


# --- case 13: the real cause of a refused long map --------------------------------------------
def test_a_long_wave_map_names_the_duration_not_the_law(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    err = _refused(capsys, *MAP, _wave_config(tmp_path), "--duration", "1e6", "--steady-tol", "0")
    assert err.startswith("torsio map: error: --duration") and "bit_rock" not in err
