"""Start-up of the command line against a bare ``python -c "import numpy"``, in one run.

Each command runs as a new process (as a user types it), ``--repeat`` times (default 3),
the runs of the commands interleaved so that a load on the machine hits them alike; the
median wall time of each is printed with its ratio to the numpy import. Target: ``torsio
laws`` and ``torsio --help`` within 4x.

Run: ``python benchmarks/bench_startup.py [--repeat N]``.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import time

TARGET = 4.0


def commands() -> dict[str, list[str]]:
    torsio = shutil.which("torsio") or ""
    cli = [torsio] if torsio else [sys.executable, "-m", "torsio.cli"]
    return {
        "python -c 'import numpy'": [sys.executable, "-c", "import numpy"],
        "torsio --help": [*cli, "--help"],
        "torsio laws": [*cli, "laws"],
        "torsio laws --json": [*cli, "laws", "--json"],
        "python -c 'import torsio'": [sys.executable, "-c", "import torsio"],
    }


def wall_time(command: list[str]) -> float:
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs of each command (default 3)")
    args = parser.parse_args()
    runs = commands()
    for command in runs.values():  # warm the file-system cache; not timed
        wall_time(command)
    times: dict[str, list[float]] = {name: [] for name in runs}
    for _ in range(args.repeat):
        for name, command in runs.items():
            times[name].append(wall_time(command))
    base = statistics.median(times["python -c 'import numpy'"])
    print(
        f"machine: {os.cpu_count()} cores, python {sys.version.split()[0]}; median of "
        f"{args.repeat} interleaved runs, wall time of a new process"
    )
    met = True
    for name, values in times.items():
        ratio = statistics.median(values) / base
        targeted = name in ("torsio --help", "torsio laws")
        met &= not targeted or ratio <= TARGET
        mark = f"  (target <= {TARGET:g}x)" if targeted else ""
        print(f"  {name:28s} {statistics.median(values):6.3f} s  {ratio:5.2f}x numpy{mark}")
    verdict = "met" if met else "NOT met"
    print(f"target: torsio --help and torsio laws within {TARGET:g}x: {verdict}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
