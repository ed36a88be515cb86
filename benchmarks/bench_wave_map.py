"""The 21 x 21 severity map of the wave model against the 5-DOF strategy-C map, through the CLI.

Both maps run ``torsio map`` on the paper's string (Table 1, Tucker-Wang in the rpm
reading) with Rayleigh alpha = 0.35 1/s and beta = 0 (the wave model refuses beta), the
default grid (WOB 25..225 kN x 40..140 rpm, 21 x 21), default run length (40 first-mode
periods), window (15), steady-cycle tolerance (1e-3) and critical-WOB refinement, as whole
processes (start-up and compiled-code cache loading included). The wave model runs on its
default characteristic grid (dt = 1.44 ms, 1093 cells, the drag lumped every 4 cells).
The two maps run back to back, C then wave, and the pair is repeated (``--repeat``,
default 3); the script prints each time, the medians, their ratio (target: wave within
10x of C), the CPU time of the children as well (less sensitive to other work on the
machine than the wall time), the cores, numba's threads and the machine's load
(``os.getloadavg``) before and after.
``--travel-time-tolerance 3e-3`` runs the wave model on a coarser grid (dt = 3.71 ms
instead of 1.44 ms for the paper's string; docs/wave.md gives its S_SS differences),
``--drag-spacing K`` with the drag lumped every K cells.

Run: ``python benchmarks/bench_wave_map.py`` (minutes on 2 cores);
``--quick`` for a 5 x 5 grid and one repetition.
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

# 64 points: a batch that size compiles the lumped batch loop as well (rodas_kernels.SMALL_BATCH)
COMPILE = ["--wob", "50kN:150kN:8", "--rpm", "60:120:8", "--duration", "1", "--window", "0.5"]


def config(
    folder: Path, strategy: str, tolerance: float | None = None, spacing: int | None = None
) -> Path:
    """The built-in file with beta = 0 and the given strategy (and the wave grid's options)."""
    text = resources.files("torsio").joinpath("data/ritto2017.toml").read_text(encoding="utf-8")
    text = text.replace("beta = 0.06", "beta = 0.0").replace(
        'strategy = "C"', f'strategy = "{strategy}"'
    )
    if strategy == "wave":
        text = text.replace("dp_elements = 5\n", "").replace("bha_elements = 1\n", "")
        if tolerance is not None:
            text = text.replace(
                'strategy = "wave"', f'strategy = "wave"\ntravel_time_tolerance = {tolerance}'
            )
        if spacing is not None:
            text = text.replace('strategy = "wave"', f'strategy = "wave"\ndrag_spacing = {spacing}')
    path = folder / f"{strategy}.toml"
    path.write_text(text)
    return path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="5 x 5 grid, one repetition")
    parser.add_argument("--repeat", type=int, default=None, help="pairs of runs (default 3)")
    parser.add_argument(
        "--travel-time-tolerance", type=float, default=None, help="of the wave grid (default 3e-4)"
    )
    parser.add_argument(
        "--drag-spacing", type=int, default=None, help="cells between drag nodes (default 4)"
    )
    args = parser.parse_args()
    grid = ["--wob", "25kN:225kN:5", "--rpm", "40:140:5"] if args.quick else []
    repeat = args.repeat or (1 if args.quick else 3)
    import numba

    print(
        f"grid {'5 x 5' if args.quick else '21 x 21 (default)'}, {repeat} pair(s); "
        f"wave travel-time tolerance {args.travel_time_tolerance or 'default (3e-4)'}, "
        f"drag spacing {args.drag_spacing or 'default (4)'}; "
        f"{os.cpu_count()} cores, numba threads {numba.config.NUMBA_NUM_THREADS}; "
        f"before: {load_average()}",
        flush=True,
    )
    times: dict[str, list[float]] = {"C": [], "wave": []}
    cpu: dict[str, list[float]] = {"C": [], "wave": []}
    with tempfile.TemporaryDirectory() as folder:
        paths = {
            s: config(Path(folder), s, args.travel_time_tolerance, args.drag_spacing) for s in times
        }
        for path in paths.values():  # compile (or load the cache) once, untimed
            base = [sys.executable, "-m", "torsio", "map", str(path)]
            subprocess.run([*base, *COMPILE, "--json"], check=True, capture_output=True)
        for k in range(repeat):
            for strategy, path in paths.items():
                command = [sys.executable, "-m", "torsio", "map", str(path), *grid, "--json"]
                start, children = time.perf_counter(), children_cpu()
                subprocess.run(command, check=True, capture_output=True)
                times[strategy].append(time.perf_counter() - start)
                cpu[strategy].append(children_cpu() - children)
                print(
                    f"pair {k + 1}: {strategy:>4} {times[strategy][-1]:.1f} s "
                    f"(CPU {cpu[strategy][-1]:.1f} s)",
                    flush=True,
                )
    medians = {strategy: statistics.median(values) for strategy, values in times.items()}
    cpu_medians = {strategy: statistics.median(values) for strategy, values in cpu.items()}
    print(f"after: {load_average()}")
    print(f"medians: C {medians['C']:.1f} s, wave {medians['wave']:.1f} s (wall)")
    print(f"         C {cpu_medians['C']:.1f} s, wave {cpu_medians['wave']:.1f} s (CPU)")
    print(f"wave / C = {medians['wave'] / medians['C']:.2f} wall (target <= 10), ", end="")
    print(f"{cpu_medians['wave'] / cpu_medians['C']:.2f} CPU")


if __name__ == "__main__":
    main()
