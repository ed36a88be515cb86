"""The 21 x 21 severity map of the wave model against the 5-DOF strategy-C map, through the CLI.

Both maps run ``torsio map`` on the paper's string (Table 1, Tucker-Wang in the rpm
reading) with Rayleigh alpha = 0.35 1/s and beta = 0 (the wave model refuses beta), the
default grid (WOB 25..225 kN x 40..140 rpm, 21 x 21), default run length (40 first-mode
periods), window (15) and critical-WOB refinement, in one run of this script, one after
the other. Prints the wall times and their ratio (target: wave within 10x of C).

Run: ``python benchmarks/bench_wave_map.py`` (tens of minutes on 2 cores);
``--quick`` for a 5 x 5 grid.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from importlib import resources
from pathlib import Path


def config(folder: Path, strategy: str) -> Path:
    """The built-in file with beta = 0 and the given strategy."""
    text = resources.files("torsio").joinpath("data/ritto2017.toml").read_text(encoding="utf-8")
    text = text.replace("beta = 0.06", "beta = 0.0").replace(
        'strategy = "C"', f'strategy = "{strategy}"'
    )
    if strategy == "wave":
        text = text.replace("dp_elements = 5\n", "").replace("bha_elements = 1\n", "")
    path = folder / f"{strategy}.toml"
    path.write_text(text)
    return path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="5 x 5 grid")
    args = parser.parse_args()
    grid = ["--wob", "25kN:225kN:5", "--rpm", "40:140:5"] if args.quick else []
    times = {}
    with tempfile.TemporaryDirectory() as folder:
        for strategy in ("C", "wave"):
            path = config(Path(folder), strategy)
            command = [sys.executable, "-m", "torsio", "map", str(path), *grid, "--json"]
            subprocess.run(
                command[:4]
                + [
                    "--wob",
                    "100kN:100kN:1",
                    "--rpm",
                    "60:60:1",
                    "--duration",
                    "1",
                    "--window",
                    "0.5",
                    "--json",
                ],
                check=True,
                capture_output=True,
            )  # fmt: skip  (compile first)
            start = time.perf_counter()
            subprocess.run(command, check=True, capture_output=True)
            times[strategy] = time.perf_counter() - start
            print(f"{strategy:>5}: {times[strategy]:.1f} s", flush=True)
    print(f"wave / C = {times['wave'] / times['C']:.1f} (target <= 10)")


if __name__ == "__main__":
    main()
