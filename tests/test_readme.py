"""The README's examples run as written."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from torsio import parse_config
from torsio.io.config import parse_config_text

README = (Path(__file__).parents[1] / "README.md").read_text(encoding="utf-8")


def blocks(language: str) -> list[str]:
    return re.findall(rf"```{language}\n(.*?)```", README, flags=re.S)


def test_readme_toml_example_is_valid():
    (text,) = blocks("toml")
    config = parse_config_text(text, source="README")
    assert config.string.sections[0].od == pytest.approx(0.127)  # 5 in
    assert config.model().dofs == 10


def test_readme_python_example_runs(capsys):
    (code,) = blocks("python")
    exec(compile(code, "README.md", "exec"), {})
    printed = capsys.readouterr().out
    assert "0.1306" in printed  # the frequency the README shows in its comment


def test_readme_quick_start_matches_ci():
    commands = re.findall(r"```bash\n(pip install[^\n]*)\n```", README)
    assert len(commands) == 2
    ci = (Path(__file__).parents[1] / ".ci" / "run").read_text(encoding="utf-8")
    test_command = commands[1].replace("pip install", "python -m pip install -q")
    assert test_command in ci
    assert parse_config  # the module imports
