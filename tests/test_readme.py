"""The README's examples run as written."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from torsio import parse_config
from torsio.config.reading import parse_config_text

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


def test_readme_toml_example_runs_simulate_and_map(tmp_path, monkeypatch, capsys):
    import json
    import warnings

    from torsio.cli import main

    (text,) = blocks("toml")
    path = tmp_path / "my.toml"
    path.write_text(text, encoding="utf-8")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # complete as written: no warning (damping is given)
        config = parse_config_text(text, source="README")
    assert config.bit_rock is not None and config.damping.alpha == 0.35
    argv = ["simulate", str(path), "--wob", "100 kN", "--rpm", "60", "--json"]
    assert main(argv) == 0
    captured = capsys.readouterr()
    data = json.loads(captured.out)
    assert data["wob"] == 100e3 and data["rpm"] == 60  # the options, in N and rpm
    assert data["severity"] >= 0  # S_SS = (max - min)/(2 Omega) of the bit speed, Eq. 12
    assert "warning" not in captured.err
    argv = ["map", str(path), "--wob", "25kN:225kN:2", "--rpm", "40:140:2", "--json"]
    assert main([*argv, "--refine", "0"]) == 0
    assert len(json.loads(capsys.readouterr().out)["severity"]) == 2
