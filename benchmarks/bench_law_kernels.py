"""Bit-rock law kernels: what the law-agnostic compiled kernel costs, in one run.

1. **Through the CLI** (what a user waits for), caches warm: ``torsio map`` on the 1-DOF
   (strategy A) built-in Ritto et al. (2017) string, 31 x 31 grid WOB 20..250 kN x
   30..150 rpm, default run length, tolerances and critical-curve bisection, with
   ``tucker-wang`` (the built-in law) and with the bundled plugin's ``coulomb-stribeck``
   (stick-slip at low speed, as in Navarro-Lopez and Cortes 2007). Target: plugin law
   <= 2x Tucker-Wang. Each command runs once to warm numba's cache, then ``--repeat``
   times, interleaved; medians are printed.
2. **The kernel alone** (in process, one thread, the same 31 x 31 grid without the
   bisection): the law passed as first-class functions (``numba.types.FunctionType``,
   the shipped kernel) against the same kernel compiled with Tucker-Wang as a
   compile-time constant (what an inlined, law-specific kernel would give).
3. **The numpy fallback** on the same grid (a law without ``kernel()``), for scale.

Run: ``python benchmarks/bench_law_kernels.py [--repeat 3] [--quick]``. The machine is
often shared: compare the ratios, which are taken within the run, not the seconds.
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from torsio.examples import builtin_config
from torsio.physics.laws import tucker_wang_slope, tucker_wang_torque
from torsio.solvers import batch, rodas, rodas_kernels
from torsio.solvers.compiled import njit
from torsio.solvers.layouts import OUT_BIT_SPEED_MAX, OUT_BIT_SPEED_MIN, OUT_COLUMNS, OUT_STEPS
from torsio.solvers.lumped_inputs import run_settings, step_limits

BUILTIN = Path(batch.__file__).resolve().parents[1] / "data" / "ritto2017.toml"
COULOMB_STRIBECK = """
[bit_rock]
law = "coulomb-stribeck"
radius = 0.108
mu_static = 0.8
mu_coulomb = 0.5
"""


def _config_files(folder: Path) -> dict[str, Path]:
    text = BUILTIN.read_text()
    head, _, rest = text.partition("[bit_rock]")
    tail = rest[rest.index("[damping]") :]
    files = {"tucker-wang": folder / "tucker_wang.toml", "coulomb-stribeck": folder / "cs.toml"}
    files["tucker-wang"].write_text(text)
    files["coulomb-stribeck"].write_text(head + COULOMB_STRIBECK.lstrip() + "\n" + tail)
    return files


def cli_map(config: Path, points: int) -> tuple[float, dict]:
    command = [sys.executable, "-m", "torsio", "map", str(config), "--strategy", "A"]
    command += ["--wob", f"20e3:250e3:{points}", "--rpm", f"30:150:{points}", "--json"]
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, check=True)
    return time.perf_counter() - start, json.loads(done.stdout)


def part_cli(points: int, repeat: int) -> None:
    print(f"1. torsio map, 1 DOF, {points} x {points}, caches warm (median of {repeat})")
    with tempfile.TemporaryDirectory() as folder:
        files = _config_files(Path(folder))
        times: dict[str, list[float]] = {name: [] for name in files}
        engines = {}
        for name, path in files.items():  # warm numba's cache
            _, data = cli_map(path, 8)  # 64 points: the batch loop (SMALL_BATCH)
            engines[name] = data["engine"]
        for _ in range(repeat):
            for name, path in files.items():
                seconds, data = cli_map(path, points)
                times[name].append(seconds)
                severe = sum(row.count("severe") for row in data["classification"])
                engines[name] = f"{data['engine']}, {severe} severe points"
    base = statistics.median(times["tucker-wang"])
    for name, values in times.items():
        ratio = statistics.median(values) / base
        print(f"   {name:18s} {statistics.median(values):6.2f} s  x{ratio:4.2f}  ({engines[name]})")


TW_TORQUE = njit(cache=True)(tucker_wang_torque)
TW_SLOPE = njit(cache=True)(tucker_wang_slope)


@njit(cache=True)
def _serial_tucker_wang_constant(chain, top, p, settings, wob, omega, omega_set, out) -> None:
    for k in range(wob.size):  # the shipped per-point entry, the law compiled in
        rodas.point(chain, top, TW_TORQUE, TW_SLOPE, p, settings, wob, omega, omega_set, out, k)


def part_kernel(points: int, repeat: int) -> None:
    system = builtin_config().system(strategy="A")
    model = batch.BatchModel.from_system(system)
    torque, slope, parameters = system.law.kernel()
    ww, rr = np.meshgrid(np.linspace(20e3, 250e3, points), np.linspace(30.0, 150.0, points))
    wob = np.ascontiguousarray(ww.ravel())
    omega = np.ascontiguousarray(rr.ravel() * math.pi / 30.0)
    duration, window = batch.run_times(system, None, None)
    # the kernel's settings: every run to the end, no steady-cycle stop
    steps = step_limits(model.first_frequency)
    settings = run_settings(duration, window, 1e-5, 1e-6, steps, 2_000_000, 0.108, 0.0, 0.0)
    outputs = {}
    runs = {
        "FunctionType (shipped)": lambda out: rodas_kernels.integrate_serial(
            model.chain, model.top, torque, slope, parameters, settings, wob, omega, omega, out
        ),
        "Tucker-Wang constant": lambda out: _serial_tucker_wang_constant(
            model.chain, model.top, parameters, settings, wob, omega, omega, out
        ),
    }
    times: dict[str, list[float]] = {name: [] for name in runs}
    for name, run in runs.items():
        outputs[name] = np.zeros((wob.size, OUT_COLUMNS))
        run(outputs[name])  # compile or load
    for _ in range(repeat):
        for name, run in runs.items():
            start = time.perf_counter()
            run(outputs[name])
            times[name].append(time.perf_counter() - start)
    print(f"2. the kernel alone, 1 DOF, {points} x {points}, one thread (median of {repeat})")
    base = statistics.median(times["Tucker-Wang constant"])
    for name, values in times.items():
        steps = int(outputs[name][:, OUT_STEPS].sum())
        seconds = statistics.median(values)
        print(f"   {name:24s} {seconds:6.2f} s  x{seconds / base:4.2f}  ({steps} steps)")
    extremes = [OUT_BIT_SPEED_MAX, OUT_BIT_SPEED_MIN]
    same = np.array_equal(*(out[:, extremes] for out in outputs.values()))
    print(f"   identical bit-speed extremes: {same}")
    start = time.perf_counter()
    numpy_run = batch.simulate_batch(system, wob, rr.ravel(), engine="numpy")
    seconds = time.perf_counter() - start
    print(
        f"3. numpy engine, same grid: {seconds:6.2f} s  x{seconds / base:4.1f} ({numpy_run.engine})"
    )


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="timed runs of each case")
    parser.add_argument("--quick", action="store_true", help="11 x 11 grids, one repeat")
    args = parser.parse_args(argv)
    points, repeat = (11, 1) if args.quick else (31, args.repeat)
    part_cli(points, repeat)
    part_kernel(points, repeat)


if __name__ == "__main__":
    main()
