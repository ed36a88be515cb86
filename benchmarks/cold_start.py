"""The first run after an install: ``torsio report`` with an empty numba cache, then warm.

Each run is a new process (as a user types the command) with its own ``TORSIO_CACHE_DIR``:
a new empty folder for each cold run, the last cold run's folder for the warm runs. It
prints the CPU time (user + system, of the process and its children) and the wall time of
each run, the longest time the command printed nothing (stdout and stderr; target: 5 s),
and the cold run against the warm one. Target: a cold ``torsio report`` within 20 s of CPU.

``--functions`` runs the cold command once more in process with a listener on numba's
compile events and prints the CPU seconds of each compiled function (the outermost ones,
and those compiled within them), the figures of
:data:`torsio.kernel_cache.COMPILE_ESTIMATES`. ``--torsio PATH`` times another
installation's command (another virtualenv's ``bin/torsio``, e.g. one with the main branch
installed) for a baseline. Unix only (CPU times of child processes).

Run: ``python benchmarks/cold_start.py [--cold 2] [--warm 2] [--functions] [-- report ARGS]``.
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

TARGET_CPU = 20.0
TARGET_SILENCE = 5.0


def run(command: list[str], cache: Path) -> tuple[float, float, float, str]:
    """(CPU s, wall s, longest silence s, stderr) of ``command`` with its cache in ``cache``."""
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env["TORSIO_CACHE_DIR"] = str(cache)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    process = subprocess.Popen(
        command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    stamps = [start]
    errors: list[str] = []

    def read(stream, keep: list[str] | None) -> None:
        for line in stream:
            stamps.append(time.perf_counter())
            if keep is not None:
                keep.append(line)

    readers = [
        threading.Thread(target=read, args=(process.stdout, None)),
        threading.Thread(target=read, args=(process.stderr, errors)),
    ]
    for reader in readers:
        reader.start()
    for reader in readers:
        reader.join()
    status = process.wait()
    end = time.perf_counter()
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if status != 0:
        raise SystemExit(f"{' '.join(command)} exited with {status}:\n{''.join(errors)}")
    marks = sorted([*stamps, end])
    silence = max(b - a for a, b in zip(marks, marks[1:], strict=False))
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, end - start, silence, "".join(errors)


CHILD = """
import sys, time
from numba.core import event

class Times(event.Listener):
    def __init__(self):
        self.stack, self.rows = [], []
    def on_start(self, ev):
        f = ev.data["dispatcher"].py_func
        self.stack.append((f"{f.__module__}.{f.__qualname__}", time.process_time()))
    def on_end(self, ev):
        name, cpu = self.stack.pop()
        self.rows.append((len(self.stack), name, time.process_time() - cpu))

times = Times()
event.register("numba:compile", times)
from torsio.cli import main
try:
    main(sys.argv[1:])
except SystemExit:
    pass
for depth, name, cpu in times.rows:
    if depth == 0 or cpu >= 1.0:
        print(f"FUNCTION {depth} {cpu:.2f} {name}", file=sys.stderr)
"""


def functions(arguments: list[str]) -> None:
    """Per-function compile CPU times of a cold run (in a new process)."""
    with tempfile.TemporaryDirectory(prefix="torsio-cold-") as folder:
        *_, errors = run([sys.executable, "-c", CHILD, *arguments], Path(folder))
    print("compiled functions (CPU s; indented: compiled within the one above it, >= 1 s):")
    for line in errors.splitlines():
        if line.startswith("FUNCTION "):
            _, depth, cpu, name = line.split(" ", 3)
            print(f"  {'  ' * int(depth)}{float(cpu):6.2f}  {name}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cold", type=int, default=2, help="cold runs (default 2)")
    parser.add_argument("--warm", type=int, default=2, help="warm runs (default 2)")
    parser.add_argument("--functions", action="store_true", help="per-function compile times")
    parser.add_argument("--torsio", help="the torsio command to time (default: this one's)")
    parser.add_argument("arguments", nargs="*", help="the command's arguments (default: report)")
    args = parser.parse_args()
    arguments = args.arguments or ["report"]
    torsio = args.torsio or shutil.which("torsio")
    command = [torsio] if torsio else [sys.executable, "-m", "torsio"]
    print(
        f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f} before; "
        f"python {sys.version.split()[0]}; command: torsio {' '.join(arguments)} ({command[0]})"
    )
    cold: list[tuple[float, float, float]] = []
    warm: list[tuple[float, float, float]] = []
    with tempfile.TemporaryDirectory(prefix="torsio-cold-") as root:
        for k in range(args.cold):
            cache = Path(root) / f"cache-{k}"  # a new, empty cache folder
            cpu, wall, silence, _ = run([*command, *arguments], cache)
            cold.append((cpu, wall, silence))
            print(f"  cold {k + 1}: CPU {cpu:6.2f} s  wall {wall:6.2f} s  silent {silence:5.2f} s")
        for k in range(args.warm):
            cpu, wall, silence, _ = run([*command, *arguments], cache)
            warm.append((cpu, wall, silence))
            print(f"  warm {k + 1}: CPU {cpu:6.2f} s  wall {wall:6.2f} s  silent {silence:5.2f} s")
    print(f"load average {os.getloadavg()[0]:.2f} after")
    if cold:
        summary(cold, warm)
    if args.functions:
        functions(arguments)
    return 0


def summary(cold: list[tuple[float, float, float]], warm: list[tuple[float, float, float]]) -> None:
    """The medians of the cold and warm runs, against the targets."""
    cold_cpu = statistics.median(c[0] for c in cold)
    longest = max(c[2] for c in cold)
    print(
        f"cold: median CPU {cold_cpu:.2f} s (target < {TARGET_CPU:g} s: "
        f"{'met' if cold_cpu < TARGET_CPU else 'NOT met'}), median wall "
        f"{statistics.median(c[1] for c in cold):.2f} s; longest silence {longest:.2f} s "
        f"(target <= {TARGET_SILENCE:g} s: {'met' if longest <= TARGET_SILENCE else 'NOT met'})"
    )
    if warm:
        warm_cpu = statistics.median(w[0] for w in warm)
        print(
            f"warm: median CPU {warm_cpu:.2f} s, wall "
            f"{statistics.median(w[1] for w in warm):.2f} s; cold/warm CPU "
            f"{cold_cpu / warm_cpu:.1f}x"
        )


if __name__ == "__main__":
    sys.exit(main())
