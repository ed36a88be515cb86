"""21 x 21 severity maps of the built-in deviated well with friction along the string
against the same maps without it, through the CLI.

The issue's target: a map with friction within 2x the same map without it. Both files are
the built-in ``deviated_well.toml``; the one without friction drops its ``[well]`` tables
(survey, hole sections, friction factors), so the string, bit law, damping and grid are
the same. Each pair runs ``torsio map FILE --wob 0:80e3:21 --rpm 40:120:21 --json`` as a
whole new process (all cores, the default run length, steady-cycle end and critical-WOB
bisection, caches warm: one small map of each file runs first, untimed), with the file's
wave model and with the lumped strategy B (``--strategy B --dp-elements 10
--bha-elements 4``). The contacts follow each point's weight on bit. It prints each time,
the medians over ``--repeat`` pairs (wall and the children's CPU), their ratios, the
cores and the machine's load before and after.

Run: ``python benchmarks/bench_friction_maps.py`` (about 5 minutes on 2 cores);
``--quick`` for a 5 x 5 grid and one pair; ``--model wave`` or ``--model B`` for one model.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from importlib import resources
from pathlib import Path

from machine_load import children_cpu, load_average

GRID = ["--wob", "0:80e3:21", "--rpm", "40:120:21"]
QUICK = ["--wob", "0:80e3:5", "--rpm", "40:120:5"]
# 64 points: a batch that size compiles the batch loop as well (rodas_kernels.SMALL_BATCH)
WARM = ["--wob", "0:80e3:8", "--rpm", "40:120:8", "--duration", "2", "--window", "1"]
MODELS = {"wave": [], "B": ["--strategy", "B", "--dp-elements", "10", "--bha-elements", "4"]}


def without_well(text: str) -> str:
    """The configuration's text without its ``[well]`` and ``[[well.*]]`` tables."""
    kept, skipping = [], False
    for line in text.splitlines(keepends=True):
        header = line.strip().split("#")[0].strip()
        if header.startswith("["):
            skipping = header.strip("[]").split(".")[0] == "well"
        if not skipping:
            kept.append(line)
    return "".join(kept)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="5 x 5 grid, one pair")
    parser.add_argument("--repeat", type=int, default=None, help="pairs of runs (default 2)")
    parser.add_argument("--model", choices=sorted(MODELS), action="append", help="default both")
    args = parser.parse_args()
    grid, repeat = (QUICK, 1) if args.quick else (GRID, args.repeat or 2)
    models = args.model or list(MODELS)
    print(
        f"grid {' '.join(grid)}; {repeat} pair(s); {os.cpu_count()} cores; before: {load_average()}"
    )
    text = resources.files("torsio").joinpath("data/deviated_well.toml").read_text("utf-8")
    with tempfile.TemporaryDirectory() as folder:
        files = {"friction": Path(folder, "friction.toml"), "none": Path(folder, "none.toml")}
        files["friction"].write_text(text)
        files["none"].write_text(without_well(text))
        for model in models:
            wall: dict[str, list[float]] = {name: [] for name in files}
            cpu: dict[str, list[float]] = {name: [] for name in files}
            for path in files.values():  # compile or load the caches, untimed
                command = [sys.executable, "-m", "torsio", "map", str(path), *MODELS[model]]
                subprocess.run([*command, *WARM, "--json"], check=True, capture_output=True)
            for k in range(repeat):
                for name, path in files.items():
                    command = [sys.executable, "-m", "torsio", "map", str(path), *MODELS[model]]
                    start, children = time.perf_counter(), children_cpu()
                    subprocess.run([*command, *grid, "--json"], check=True, capture_output=True)
                    wall[name].append(time.perf_counter() - start)
                    cpu[name].append(children_cpu() - children)
                    print(f"{model:>4} pair {k + 1}: {name:>8} {wall[name][-1]:.1f} s "
                          f"(CPU {cpu[name][-1]:.1f} s)", flush=True)  # fmt: skip
            w = {name: statistics.median(values) for name, values in wall.items()}
            c = {name: statistics.median(values) for name, values in cpu.items()}
            print(f"{model:>4}: friction {w['friction']:.1f} s, without {w['none']:.1f} s: "
                  f"{w['friction'] / w['none']:.2f}x wall (target <= 2), "
                  f"{c['friction'] / c['none']:.2f}x CPU", flush=True)  # fmt: skip
    print(f"after: {load_average()}")


if __name__ == "__main__":
    main()
