"""``[top_drive]`` in TOML, ``--rpm`` with a torque-driven top, the report's top-drive section."""

from __future__ import annotations

import copy
import json
import math
import tomllib
from importlib import resources

import pytest

from torsio.cli import main
from torsio.config.reading import parse_config
from torsio.errors import ConfigError
from torsio.examples import builtin_config
from torsio.physics.top_drives import (
    ConstantSpeedTop,
    PITopDrive,
    SoftTorqueTopDrive,
    TorqueTopDrive,
    ZTorqueTopDrive,
    top_pipe_impedance,
)
from torsio.report.document import report_data

BUILTIN = tomllib.loads(
    resources.files("torsio").joinpath("data/ritto2017.toml").read_text(encoding="utf-8")
)


def with_top_drive(table: dict | None, strategy: str = "A", operation: bool = True) -> dict:
    """The built-in configuration with a [top_drive] table (and without [operation])."""
    data = copy.deepcopy(BUILTIN)
    data["discretization"] = {"strategy": strategy}
    if not operation:  # the report then leaves out the transient sections
        del data["operation"]
    if table is not None:
        data["top_drive"] = table
    return data


def test_absent_table_is_constant_speed():
    config = builtin_config()
    assert config.top_drive.kind == "constant-speed"
    assert isinstance(config.system().top, ConstantSpeedTop)


def test_each_kind_is_built_with_units():
    cases = {
        "torque": ({"inertia": "930 kg*m^2", "torque": "10 kN*m", "drag": 425}, TorqueTopDrive),
        "pi": ({"inertia": 2900.0, "kp": "23 kN*m*s/rad", "ki": "14.5 kN*m/rad"}, PITopDrive),
        "soft-torque": ({"inertia": 2900.0}, SoftTorqueTopDrive),
        "z-torque": ({"inertia": 2900.0, "highpass_period": "20 s"}, ZTorqueTopDrive),
    }
    for kind, (parameters, cls) in cases.items():
        data = with_top_drive({"kind": kind, **parameters})
        if kind == "torque":
            del data["operation"]["rpm"]
        top = parse_config(data).system().top
        assert isinstance(top, cls), kind
    pi = parse_config(with_top_drive({"kind": "pi", **cases["pi"][0]})).system().top
    assert (pi.kp, pi.ki) == (23e3, 14.5e3)  # converted from kN to N


PI = {"kind": "pi", "inertia": 2900.0, "kp": 1.0, "ki": 1.0}


@pytest.mark.parametrize(
    ("table", "key", "needle"),
    [
        ({"kind": "hover"}, "top_drive.kind", "hover"),
        ({"kind": 3}, "top_drive.kind", "expected a top-drive name"),
        ({**PI, "gain": 2.0}, "top_drive.gain", "no parameter"),
        ({**PI, "gain": "2 s"}, "top_drive.gain", "no parameter"),
        ({"kind": "pi", "kp": 1.0, "ki": 1.0}, "top_drive.inertia", "inertia"),
        ({**PI, "inertia": -5.0}, "top_drive.inertia", "positive"),
        ({**PI, "inertia": "3 m"}, "top_drive.inertia", "not a inertia"),
        ({**PI, "kp": "3 N*m"}, "top_drive.kp", "not a rotational damping"),
        (
            {"kind": "torque", "inertia": 930.0, "torque": "10 kN"},
            "top_drive.torque",
            "not a torque",
        ),
        ({"kind": "z-torque", "inertia": 2900.0, "alpha": 1.5}, "top_drive.alpha", "(0, 1]"),
        ("pi", "top_drive", "expected a table"),
    ],
)
def test_bad_top_drives_name_the_key(table, key, needle):
    with pytest.raises(ConfigError) as info:
        parse_config(with_top_drive(table))
    assert info.value.key == key
    assert needle in str(info.value)


def test_a_torque_driven_top_has_no_rotary_speed(tmp_path, capsys):
    table = {"kind": "torque", "inertia": 930.0, "torque": 10e3}
    with pytest.raises(ConfigError, match="torque balance") as info:
        parse_config(with_top_drive(table))  # [operation] rpm = 100 in the built-in file
    assert info.value.key == "operation.rpm"
    data = with_top_drive(table)
    del data["operation"]["rpm"]
    lines = [f"{k} = {json.dumps(v)}" for k, v in table.items()]
    path = tmp_path / "torque.toml"
    text = resources.files("torsio").joinpath("data/ritto2017.toml").read_text(encoding="utf-8")
    text = text.replace("rpm = 100\n", "") + "\n[top_drive]\n" + "\n".join(lines) + "\n"
    path.write_text(text)
    assert main(["simulate", str(path), "--rpm", "60", "--json"]) == 2
    err = capsys.readouterr().err
    assert "--rpm" in err and "torque" in err
    assert main(["map", str(path), "--rpm", "60:60:1", "--wob", "50kN:60kN:2", "--json"]) == 2
    err = capsys.readouterr().err
    assert "--rpm" in err and "torque" in err


def test_soft_torque_on_a_chain_needs_kp():
    text = (
        "[chain]\ninertias = [1000.0]\nstiffnesses = [500.0]\n"
        "[bit_rock]\nlaw = 'tucker-wang'\nradius = 0.1\na0 = 0.2\na1 = 0.2\na2 = 0.9\na3 = 0.06\n"
        "[top_drive]\nkind = 'soft-torque'\ninertia = 2900.0\n"
    )
    from torsio.config.reading import parse_config_text

    config = parse_config_text(text)
    with pytest.raises(ConfigError, match="kp") as info:
        config.system().top.boundary(config.system())
    assert info.value.key == "top_drive.kp"


def test_report_top_drive_section_for_soft_torque():
    config = parse_config(
        with_top_drive({"kind": "soft-torque", "inertia": 2900.0}, operation=False)
    )
    data = report_data(config)["top_drive"]
    system = config.system()
    zeta = top_pipe_impedance(system)
    omega1 = data["omega1_rad_s"]
    # SoftTorque defaults (Kyllingstad and Nessjoen 2009): kp = zeta, ki = omega_1^2 J, so at
    # omega_1 the impedance is the pure damper kp = zeta and nothing is reflected.
    assert data["kind"] == "soft-torque"
    assert data["kp_n_m_s_per_rad"] == pytest.approx(zeta, rel=1e-12)
    assert data["ki_n_m_per_rad"] == pytest.approx(omega1**2 * 2900.0, rel=1e-12)
    impedance = data["impedance_at_omega1_n_m_s_per_rad"]
    assert impedance["real"] == pytest.approx(zeta, rel=1e-12)
    assert abs(impedance["imag"]) <= 1e-9 * zeta
    assert abs(data["reflection_coefficient"]) <= 1e-12
    assert data["reflection_at_omega1"]["abs"] <= 1e-9
    assert data["groups"]["tuning_over_omega1"] == pytest.approx(1.0, rel=1e-12)


def test_report_top_drive_section_for_a_stiff_pi_and_a_held_top(capsys):
    config = builtin_config()
    system = config.system(strategy="A")
    zeta = top_pipe_impedance(system)
    table = {"kind": "pi", "inertia": 2900.0, "kp": 50.0 * zeta, "ki": 5.0 * 2900.0}
    data = report_data(parse_config(with_top_drive(table, operation=False)))["top_drive"]
    # R = (zeta - kp)/(zeta + kp) = (1 - 50)/(1 + 50) for kp = 50 zeta (docs/top_drives.md).
    assert data["reflection_coefficient"] == pytest.approx(-49.0 / 51.0, rel=1e-12)
    held = report_data(config, strategy="A")["top_drive"]
    assert held["held"] and held["reflection_at_omega1"]["real"] == -1.0
    assert held["impedance_at_omega1_n_m_s_per_rad"] is None
    assert main(["report", "--strategy", "A"]) == 0
    assert "Top drive" in capsys.readouterr().out


def test_report_of_the_navarro_lopez_cortes_chain():
    pytest.importorskip("torsio_friction_laws")
    from torsio.config.reading import load_config

    path = resources.files("torsio").joinpath("data/navarro_lopez_cortes_2007.toml")
    config = load_config(str(path))
    ctx_data = report_data(config)
    data = ctx_data["top_drive"]
    assert data["kind"] == "torque" and data["set_speed_rad_s"] is None
    assert data["motor_torque_n_m"] == 10e3 and data["pipe_impedance_n_m_s_per_rad"] is None
    # Z(i w) = J i w + drag for a torque-driven top (no controller): J = 930, drag = 425.
    omega1 = data["omega1_rad_s"]
    impedance = data["impedance_at_omega1_n_m_s_per_rad"]
    assert impedance["real"] == pytest.approx(425.0, rel=1e-12)
    assert impedance["imag"] == pytest.approx(930.0 * omega1, rel=1e-12)
    assert ctx_data["modes"]["continuum_hz"] is None
    # Stick-slip at 97,347 N (Navarro-Lopez and Cortes 2007), S_SS relative to the mean
    # table speed; no critical-WOB search without a set speed.
    assert ctx_data["response"]["severity"] > 0.8 and "critical" not in ctx_data
    assert math.isfinite(omega1)
