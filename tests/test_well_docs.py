"""docs/well.md: its Python example runs as written."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

WELL_MD = Path(__file__).parents[1] / "docs" / "well.md"


def test_well_page_example_runs(tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    (code,) = re.findall(r"```python\n(.*?)```", WELL_MD.read_text(encoding="utf-8"), re.S)
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "docs/well.md", "exec"), {})
    assert (tmp_path / "drag.png").stat().st_size > 0
