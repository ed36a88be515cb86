"""Severity maps with a PI top drive against the constant-speed top, in one run.

The top drive adds a node (its inertia) and a controller state to every run of the map;
the compiled kernel eliminates the state into the first two rows, so a step stays a
tridiagonal solve. Measured through the CLI (what a user waits for), caches warm:
``torsio map`` on the built-in Ritto et al. (2017) string, 1 DOF (strategy A) and
5 DOF (strategy C), 21 x 21 grid WOB 20..250 kN x 30..150 rpm, default run length,
tolerances and critical-curve bisection, with the top held at constant speed and with a
stiff PI top drive (``[top_drive] kind = "pi"``, J = 2900 kg m^2, kp = 50 zeta,
ki = 5 J with zeta = 465 N m s/rad the drill pipe's impedance: the NORCE/OSDC
Simulator4nDOF stiff PI). Target: PI <= 3x constant speed.

Run: ``python benchmarks/bench_top_drive_map.py [--repeat 3] [--quick]``. The machine is
often shared: compare the ratios, which are taken within the run.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from torsio.solvers import batch

BUILTIN = Path(batch.__file__).resolve().parents[1] / "data" / "ritto2017.toml"
ZETA = 465.0  # N m s/rad: J_p sqrt(G rho) of the 5 1/2 in drill pipe (od 0.140, id 0.119 m)
PI = f"""
[top_drive]
kind = "pi"
inertia = 2900.0
kp = {50 * ZETA}
ki = {5 * 2900.0}
"""


def cli_map(config: Path, strategy: str, points: int) -> tuple[float, dict]:
    command = [sys.executable, "-m", "torsio", "map", str(config), "--strategy", strategy]
    command += ["--wob", f"20e3:250e3:{points}", "--rpm", f"30:150:{points}", "--json"]
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    if done.returncode:
        raise SystemExit(f"{' '.join(command)} failed:\n{done.stderr}")
    return time.perf_counter() - start, json.loads(done.stdout)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="timed runs of each case")
    parser.add_argument("--quick", action="store_true", help="11 x 11 grids, one repeat")
    args = parser.parse_args(argv)
    points, repeat = (11, 1) if args.quick else (21, args.repeat)
    with tempfile.TemporaryDirectory() as folder:
        files = {"constant speed": Path(folder) / "held.toml", "PI": Path(folder) / "pi.toml"}
        files["constant speed"].write_text(BUILTIN.read_text())
        files["PI"].write_text(BUILTIN.read_text() + PI)
        for strategy in ("A", "C"):
            times: dict[str, list[float]] = {name: [] for name in files}
            notes = {}
            for path in files.values():
                cli_map(path, strategy, 8)  # warm numba's cache (64 points: the batch loop)
            for _ in range(repeat):
                for name, path in files.items():
                    seconds, data = cli_map(path, strategy, points)
                    times[name].append(seconds)
                    severe = sum(row.count("severe") for row in data["classification"])
                    notes[name] = f"{data['engine']}, {severe} severe points"
            print(f"torsio map, strategy {strategy}, {points} x {points} (median of {repeat})")
            base = statistics.median(times["constant speed"])
            for name, values in times.items():
                seconds = statistics.median(values)
                print(f"   {name:15s} {seconds:6.2f} s  x{seconds / base:4.2f}  ({notes[name]})")


if __name__ == "__main__":
    main()
