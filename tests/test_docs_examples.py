"""Code of the docs that must run as written outside the doctests."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

DOCS = Path(__file__).parents[1] / "docs"


def dask_script() -> str:
    text = (DOCS / "maps.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    return next(block for block in blocks if block.startswith("# dask_map.py"))


def test_dask_example_is_a_guarded_script() -> None:
    source = dask_script()
    compile(source, "dask_map.py", "exec")
    assert '\nif __name__ == "__main__":' in source


@pytest.mark.slow
def test_dask_example_runs_as_a_script(tmp_path: Path) -> None:
    pytest.importorskip("distributed")
    script = tmp_path / "dask_map.py"
    script.write_text(dask_script(), encoding="utf-8")
    result = subprocess.run(
        [sys.executable, str(script)], capture_output=True, text=True, cwd=tmp_path, check=False
    )
    assert result.returncode == 0, result.stderr[-2000:]
    # the result does not depend on the executor (docs/maps.md): identical arrays
    assert result.stdout.strip().splitlines()[-1] == "True"
