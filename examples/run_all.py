"""Run every example script; exit non-zero if any fails.

Usage: python examples/run_all.py [OUT_FOLDER] [--quick]

Each script runs in its own Python process with the same OUT_FOLDER (default
``out/``) and ``--quick`` passed through. The examples use small matrices, for
which multi-threaded BLAS only adds overhead (and, on a busy machine, a lot of
it), so BLAS runs single-threaded unless the environment already says otherwise.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
SINGLE_THREAD = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


def scripts() -> list[Path]:
    """The example scripts: every ``*.py`` here but this one and private modules."""
    return sorted(
        p for p in HERE.glob("*.py") if p.name != "run_all.py" and not p.name.startswith("_")
    )


def environment() -> dict[str, str]:
    """The current environment with BLAS single-threaded unless already set."""
    env = dict(os.environ)
    for key in SINGLE_THREAD:
        env.setdefault(key, "1")
    env.setdefault("MPLBACKEND", "Agg")
    return env


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", type=Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced sizes (CI)")
    args = parser.parse_args(argv)
    failed = []
    for script in scripts():
        command = [sys.executable, str(script), str(args.out)] + (["--quick"] if args.quick else [])
        start = time.perf_counter()
        result = subprocess.run(command, env=environment(), check=False)
        elapsed = time.perf_counter() - start
        status = "ok" if result.returncode == 0 else f"FAILED (exit {result.returncode})"
        print(f"== {script.name}: {status} in {elapsed:.1f} s", flush=True)
        if result.returncode != 0:
            failed.append(script.name)
    if failed:
        print(f"{len(failed)} example(s) failed: {', '.join(failed)}", file=sys.stderr)
        return 1
    print(f"all {len(scripts())} examples ran")
    return 0


if __name__ == "__main__":
    sys.exit(main())
