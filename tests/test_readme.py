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


def test_readme_quick_start_is_what_ci_runs():
    # .ci/run reads the README's two commands from the README and runs them in order
    commands = re.findall(r"```bash\n(pip install[^\n]*)\n```", README)
    assert len(commands) == 2
    assert commands[0].startswith("pip install . ") and "torsio report" in commands[0]
    assert "-e " in commands[1] and "pytest" in commands[1]
    ci = (Path(__file__).parents[1] / ".ci" / "run").read_text(encoding="utf-8")
    assert 'first="$(readme_command 0)"' in ci and 'second="$(readme_command 1)"' in ci
    assert ci.index('bash -c "$first"') < ci.index('bash -c "$second"')
    assert parse_config  # the module imports
