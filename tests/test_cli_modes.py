"""``torsio modes`` and the CLI's error contract."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from torsio.cli import main


def run_json(capsys, *argv: str) -> dict:
    assert main(list(argv)) == 0
    out = capsys.readouterr().out
    return json.loads(out)


def test_modes_json_keys_and_values(capsys):
    # Contract: DESIGN.md, `torsio modes --json` keys. Values: ERRATA 1 (A: 0.1344 Hz) and
    # the paper's FEM first frequency 0.1307 Hz for the continuum.
    data = run_json(capsys, "modes", "--strategy", "A", "--json")
    assert data["strategy"] == "A" and data["dofs"] == 1
    assert round(data["frequencies_hz"][0], 4) == 0.1344
    assert len(data["continuum_hz"]) == len(data["frequencies_hz"]) == 1


def test_modes_overrides_and_count(capsys):
    data = run_json(
        capsys,
        "modes",
        "--strategy",
        "B",
        "--dp-elements",
        "120",
        "--bha-elements",
        "30",
        "--count",
        "25",
        "--json",
    )
    assert data["dofs"] == 150
    freqs = data["frequencies_hz"]
    assert freqs == sorted(freqs) and len(freqs) == len(data["continuum_hz"]) == 25
    # paper Fig. 5: modes 15 and 25 within 2 % of the reference
    assert abs(freqs[24] / data["continuum_hz"][24] - 1) < 0.02


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["modes", "--strategy", "Q"], "unknown strategy 'Q'"),
        (["modes", "--dp-elements", "0", "--strategy", "B"], "dp_elements"),
        (["modes", "--count", "0"], "--count"),
        (["modes", "/nonexistent/file.toml"], "cannot read configuration file"),
    ],
)
def test_errors_go_to_stderr_with_status_2(capsys, argv, needle):
    assert main(argv) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert needle in captured.err and "Traceback" not in captured.err


def test_bad_config_file_through_the_console_script(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(
        '[[section]]\nkind = "drill_pipe"\nod = 0.1\nid = 0.2\nlength = 10\n'
        '[[section]]\nkind = "bit"\nod = 0.2\nid = 0.0\nlength = 0.3\n'
    )
    result = subprocess.run(
        [sys.executable, "-m", "torsio.cli", "modes", str(path), "--json"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 2 and result.stdout == ""
    assert "section[0].id" in result.stderr and "Traceback" not in result.stderr
