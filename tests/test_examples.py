"""Smoke test of examples/: each script runs with --quick and writes non-empty PNG files.

The convention every script in examples/ follows (private helpers start with "_"):
``python examples/SCRIPT.py [OUT_FOLDER] [--quick]`` writes its figures as PNG files
into OUT_FOLDER, prints ``wrote PATH`` for each file, and exits 0.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
SCRIPTS = sorted(
    p.name for p in EXAMPLES.glob("*.py") if p.name != "run_all.py" and not p.name.startswith("_")
)

pytest.importorskip("matplotlib")


def _environment() -> dict[str, str]:
    env = dict(os.environ)
    for key in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        env.setdefault(key, "1")  # small matrices: threads only cost time
    env["MPLBACKEND"] = "Agg"
    return env


def test_examples_are_found() -> None:
    assert len(SCRIPTS) >= 7, SCRIPTS


@pytest.mark.parametrize("script", SCRIPTS)
def test_example_writes_its_figures(script: str, tmp_path: Path) -> None:
    result = subprocess.run(
        [sys.executable, str(EXAMPLES / script), str(tmp_path), "--quick"],
        capture_output=True,
        text=True,
        env=_environment(),
        timeout=120,
        check=False,
    )
    assert result.returncode == 0, result.stderr
    written = [
        Path(line.removeprefix("wrote ").strip())
        for line in result.stdout.splitlines()
        if line.startswith("wrote ")
    ]
    pngs = sorted(tmp_path.rglob("*.png"))
    assert pngs, f"{script} wrote no PNG in {tmp_path}"
    for path in written:
        assert path.exists() and path.stat().st_size > 0, path
    for path in pngs:
        assert path.stat().st_size > 1000, path
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", path
