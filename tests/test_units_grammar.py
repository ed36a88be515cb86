"""Unit strings are checked before pint sees them: no power is evaluated beyond a unit's
small exponent (issue 36, case 12: ``"9**9**9 N"`` hung pint, which computes 9**(9**9))."""

from __future__ import annotations

import subprocess
import sys
import time

import pytest

from torsio.errors import ConfigError
from torsio.units import MAX_UNIT_EXPONENT, to_si

HOSTILE = ["9**9**9 N", "9^9^9 N", "1 N**99", "1 m^(9)", "(9)**9 N", "2 (kg)**2", "1 N*2**9"]


@pytest.mark.parametrize("text", HOSTILE)
def test_powers_of_numbers_and_large_exponents_are_refused(text):
    started = time.perf_counter()
    with pytest.raises(ConfigError) as info:
        to_si(text, "force", key="operation.wob")
    assert info.value.key == "operation.wob"
    message = info.value.message
    assert text in message
    assert "a power applies" in message or f"-{MAX_UNIT_EXPONENT} to {MAX_UNIT_EXPONENT}" in message
    assert time.perf_counter() - started < 5.0


def test_other_characters_are_refused_before_pint():
    with pytest.raises(ConfigError, match="wob: cannot read '5 kN; x' as a quantity"):
        to_si("5 kN; x", "force", key="wob")


@pytest.mark.parametrize(
    ("text", "dimension", "si"),
    [
        # 1 g/cm^3 = 1000 kg/m^3 (definition of the gram and centimetre, SI brochure)
        ("1.2 g/cm**3", "density", 1200.0),
        ("1.2 g/(cm^3)", "density", 1200.0),
        # 1 N = 1 kg m s^-2 (SI brochure, table 4)
        ("3 kg*m/s^2", "force", 3.0),
        ("3 kg*m*s^-2", "force", 3.0),
        # 1 ft = 0.3048 m and 1 lbf = 4.4482216152605 N exactly (NIST SP 811, B.8)
        ("2 ft*lbf", "torque", 2 * 0.3048 * 4.4482216152605),
        ("0.5 s**-1", "inverse_time", 0.5),
    ],
)
def test_unit_exponents_still_read(text, dimension, si):
    assert to_si(text, dimension, key="k") == pytest.approx(si, rel=1e-12)


def test_a_hostile_wob_flag_is_refused_within_seconds():
    """Through the CLI in a fresh process, with a hard time limit: exit 2, the flag named."""
    code = "import sys; from torsio.cli import main; sys.exit(main(['drag', '--wob', '9**9**9 N']))"
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=60, check=False
    )
    assert done.returncode == 2
    assert "--wob" in done.stderr and "9**9**9 N" in done.stderr
    assert "Traceback" not in done.stderr


def test_a_hostile_unit_in_the_configuration_names_its_key(tmp_path):
    from importlib import resources

    from torsio.config.reading import load_config

    text = resources.files("torsio").joinpath("data/deviated_well.toml").read_text("utf-8")
    assert "mud_density = " in text
    path = tmp_path / "hostile.toml"
    lines = [
        'mud_density = "9**9**9 kg/m^3"' if line.startswith("mud_density") else line
        for line in text.splitlines()
    ]
    path.write_text("\n".join(lines), "utf-8")
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert info.value.key == "well.mud_density"
