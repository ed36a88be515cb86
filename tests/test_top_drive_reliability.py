"""Top drives, chains and the Python API on hostile inputs (issue 21, cases 8-12 and 14).

Every out-of-scale value ends in exit 2 (or a ConfigError) naming its key before any
integration starts; a result that a limit of the model makes doubtful says so.
"""

from __future__ import annotations

import json
import math
from importlib import resources

import pytest

from torsio.cli import main
from torsio.config.reading import parse_config_text
from torsio.errors import ConfigError
from torsio.examples import builtin_config
from torsio.physics.system import System

RITTO = resources.files("torsio").joinpath("data/ritto2017.toml").read_text(encoding="utf-8")
ONE_DOF = RITTO.replace('strategy = "C"\ndp_elements = 5\nbha_elements = 1', 'strategy = "A"')
assert ONE_DOF != RITTO

CHAIN = """
[chain]
inertias = [2782.25, 750.0, 471.9698]
stiffnesses = [698.063, 1080.0, 907.48]
dampings = [139.6126, 190.0, 181.49]
drag = [0.0, 0.0, 50.0]

[bit_rock]
law = "tucker-wang"
radius = 0.155575
a0 = 0.221
a1 = 0.2
a2 = 0.89
a3 = 0.06
speed_unit = "rpm"

[operation]
wob = 50000.0
"""
"""The Navarro-Lopez and Cortes (2007) chain with the built-in Tucker-Wang law (no plugin)."""

TORQUE_TOP = '\n[top_drive]\nkind = "torque"\ninertia = 930.0\ndrag = 425.0\ntorque = 10000.0\n'
PI_TOP = '\n[top_drive]\nkind = "pi"\ninertia = 2900.0\nkp = 23250.0\nki = 14500.0\n'


def run_cli(tmp_path, capsys, text, *args):
    """``torsio simulate FILE --json ARGS``: (exit status, stdout, stderr)."""
    path = tmp_path / "case.toml"
    path.write_text(text)
    status = main(["simulate", str(path), "--json", *args])
    out, err = capsys.readouterr()
    return status, out, err


def torque_driven(text: str) -> str:
    """A configuration whose top drive has no set speed: [operation] rpm removed."""
    return text.replace("rpm = 100\n", "")


# --- case 8: the rotary speed of a torque-driven top drive is what the top did -----------------


def test_torque_driven_top_reports_the_speed_it_turned_at(tmp_path, capsys):
    # Off bottom (wob 0) the torque balance of the 1-DOF string is linear: the steady top
    # speed is torque / (drag_top + alpha I_1), with alpha I_1 the Rayleigh drag of the
    # model's node ([C] 1 - c_t = alpha [I] 1), I_1 = 455.65 kg m^2 (strategy A).
    top = '\n[top_drive]\nkind = "torque"\ninertia = 930.0\ndrag = 2000.0\ntorque = 10000.0\n'
    text = torque_driven(ONE_DOF) + top
    status, out, err = run_cli(tmp_path, capsys, text, "--wob", "0", "--duration", "60")
    assert status == 0, err
    data = json.loads(out)
    inertia = parse_config_text(text).system().model.inertia[0, 0]
    expected = 10000.0 / (2000.0 + 0.35 * inertia)  # rad/s, the torque balance
    assert data["top_speed_mean"] == pytest.approx(expected, rel=1e-5)
    assert data["rpm"] == pytest.approx(expected * 30.0 / math.pi, rel=1e-5)
    assert data["rpm_source"] == "top_speed_mean"
    main(["simulate", str(tmp_path / "case.toml"), "--wob", "0", "--duration", "60"])
    table = capsys.readouterr().out
    assert f"{expected * 30.0 / math.pi:.4g} rpm" in table and "none is set" in table


def test_a_set_speed_is_reported_as_set(tmp_path, capsys):
    status, out, err = run_cli(tmp_path, capsys, ONE_DOF, "--duration", "30")
    assert status == 0, err
    data = json.loads(out)
    assert (data["rpm"], data["rpm_source"]) == (100.0, "set")


# --- cases 9, 10, 12: out-of-scale parameters name their key before any integration ------------

PI_STRING = ONE_DOF + PI_TOP
Z_STRING = ONE_DOF + '\n[top_drive]\nkind = "z-torque"\ninertia = 2900.0\n'
TORQUE_CHAIN = CHAIN + TORQUE_TOP
HELD_CHAIN = CHAIN.replace("wob = 50000.0", "wob = 50000.0\nrpm = 60.0")

CASES = {
    # case 9: torque top drive
    "torque inertia 1e300": (TORQUE_CHAIN, "inertia = 930.0", "inertia = 1e300"),
    "torque inertia 1e-300": (TORQUE_CHAIN, "inertia = 930.0", "inertia = 1e-300"),
    # case 10
    "pi ki 1e300": (PI_STRING, "ki = 14500.0", "ki = 1e300"),
    "pi ki 1e12": (PI_STRING, "ki = 14500.0", "ki = 1e12"),
    "pi kp 1e300": (PI_STRING, "kp = 23250.0", "kp = 1e300"),
    "torque drag 1e300": (TORQUE_CHAIN, "drag = 425.0", "drag = 1e300"),
    "z-torque highpass_period 1e-300": (
        Z_STRING,
        "[top_drive]",
        "[top_drive]\nhighpass_period = 1e-300",
    ),
    "z-torque zeta 1e-300": (Z_STRING, "[top_drive]", "[top_drive]\nzeta = 1e-300"),
    "z-torque ki 1e300": (Z_STRING, "[top_drive]", "[top_drive]\nki = 1e300"),
    "z-torque zeta 1e-5": (Z_STRING, "[top_drive]", "[top_drive]\nzeta = 1e-5"),
    # an unstable loop: a run at 50 gave S_SS = 2336 and the top at -571 rad/s
    "z-torque zeta 50": (Z_STRING, "[top_drive]", "[top_drive]\nzeta = 50.0"),
    "chain drag[2] 1e300": (HELD_CHAIN, "drag = [0.0, 0.0, 50.0]", "drag = [0.0, 0.0, 1e300]"),
    "chain stiffnesses[0] 1e300, torque top": (TORQUE_CHAIN, "[698.063,", "[1e300,"),
    # case 12
    "chain inertias[0] 1e-300": (CHAIN, "[2782.25,", "[1e-300,"),
    "chain inertias[0] 1e300": (CHAIN, "[2782.25,", "[1e300,"),
    "chain stiffnesses[0] 1e-300": (CHAIN, "[698.063,", "[1e-300,"),
    "chain stiffnesses[0] 1e300": (CHAIN, "[698.063,", "[1e300,"),
}
"""(configuration, text replaced, its replacement): the key named is in the case's name."""


def _key_and_value(name: str) -> tuple[str, str]:
    """("top_drive.ki", "1e12") of "pi ki 1e12"; ("chain.drag[2]", "1e300") of a chain case."""
    words = name.split(",")[0].split()
    key = words[1] if words[0] == "chain" else words[-2]
    return (f"chain.{key}" if words[0] == "chain" else f"top_drive.{key}"), words[-1]


@pytest.mark.parametrize("name", sorted(CASES))
def test_out_of_scale_values_name_their_key(tmp_path, capsys, name):
    text, old, new = CASES[name]
    key, value = _key_and_value(name)
    assert old in text
    changed = text.replace(old, new, 1)
    status, out, err = run_cli(tmp_path, capsys, changed)
    assert status == 2, out
    assert f"error: {key}: {float(value):.6g} " in err, err  # the key and its value
    assert "expected" in err and "Traceback" not in err  # and what works instead


def test_values_in_scale_stay_accepted():
    # the tunings in docs/top_drives.md on the paper's 1-DOF string, and the chain as
    # published, pass the checks (time_scales: run/(J/kp) and sqrt(ki/J)/omega_1 limits)
    from torsio.analysis.time_scales import check_time_scales
    from torsio.physics.top_drives import PITopDrive, SoftTorqueTopDrive, ZTorqueTopDrive

    system = builtin_config().system(strategy="A")
    for top in (
        PITopDrive(inertia=2900.0, kp=1e12, ki=14500.0),  # measured: runs in 4 s
        PITopDrive(inertia=2900.0, kp=23250.0, ki=1e8),  # sqrt(ki/J) = 220 omega_1: 13 s
        SoftTorqueTopDrive(inertia=2900.0),
        ZTorqueTopDrive(inertia=2900.0),
        ZTorqueTopDrive(inertia=2900.0, zeta=80.0),  # stable: S_SS 2e-14
    ):
        check_time_scales(system.with_top(top), 297.7)
    check_time_scales(parse_config_text(CHAIN).system(), 600.0)


# --- case 14: the Python API ------------------------------------------------------------------


def test_top_drive_constructors_take_units_like_a_file():
    from torsio.physics.top_drives import PITopDrive, TorqueTopDrive, ZTorqueTopDrive

    pi = PITopDrive(inertia="2900 kg*m^2", kp="23.25 kN*m*s/rad", ki="14.5 kN*m/rad")
    assert (pi.inertia, pi.kp, pi.ki) == (2900.0, 23250.0, 14500.0)
    assert TorqueTopDrive(inertia=930.0, torque="10 kN*m").torque == 10000.0
    assert ZTorqueTopDrive(inertia=2900.0, highpass_period="1 min").highpass_period == 60.0
    with pytest.raises(ConfigError, match="top_drive.inertia: '3 m' is not a inertia"):
        PITopDrive(inertia="3 m", kp=1.0, ki=1.0)


@pytest.mark.parametrize(
    ("option", "value", "key"),
    [
        ("method", "bogus", "simulation.method"),
        ("rtol", 10.0, "simulation.rtol"),
        ("stick_threshold", math.nan, "simulation.stick_threshold"),
    ],
)
def test_simulate_validates_its_options_on_the_wave_model(option, value, key):
    from torsio.analysis.transient import simulate

    system = builtin_config().system(strategy="wave")
    with pytest.raises(ConfigError, match=key.replace(".", r"\.")):
        simulate(system, **{option: value})


def test_system_refuses_what_is_not_a_model_or_a_law():
    system = builtin_config().system(strategy="A")
    with pytest.raises(ConfigError, match="^model: expected a structural model"):
        System(model=None, law=system.law, bit_radius=0.1)
    with pytest.raises(ConfigError, match="^law: expected a bit-rock law"):
        System(model=system.model, law=None, bit_radius=0.1)


def test_severity_map_reads_units_and_names_its_arguments():
    from torsio.analysis.maps import severity_map

    system = builtin_config().system(strategy="A")
    result = severity_map(
        system, wob="100 kN", rpm=["60 rpm"], refine=0, duration=60.0, engine="numpy"
    )
    assert (result.wob.tolist(), result.rpm.tolist()) == ([100e3], [60.0])
    with pytest.raises(ConfigError, match="^wob: expected a number"):
        severity_map(system, wob=["100 kN", None], rpm=[60])
    with pytest.raises(ConfigError, match="^rpm: '60 kN' is not a angular speed"):
        severity_map(system, wob=[1e5], rpm="60 kN")


# --- case 11: a motor torque limit below the steady load is said -------------------------------


@pytest.mark.parametrize("kind", ["pi", "soft-torque"])
def test_a_saturated_motor_is_said(tmp_path, capsys, kind):
    gains = "kp = 23250.0\nki = 14500.0\n" if kind == "pi" else ""
    top = f'\n[top_drive]\nkind = "{kind}"\ninertia = 2900.0\n{gains}max_torque = 1000.0\n'
    text = ONE_DOF + top
    system = parse_config_text(text).system()
    # the steady load at the set speed: the bit torque plus the Rayleigh drag alpha I_1 Omega
    # (4.4 kN m at 100 kN, 100 rpm) is above the motor's 1 kN m, so the top never gets there
    load = float(system.bit_torque(system.omega)) + 0.35 * system.model.inertia[0, 0] * system.omega
    assert load > 4000.0
    status, out, err = run_cli(tmp_path, capsys, text, "--duration", "60")
    assert status == 0, err
    data = json.loads(out)
    (saturated,) = [w for w in data["warnings"] if "torque limit" in w]
    assert "max_torque = 1000 N m) during 100% of the steady window" in saturated
    assert "against the set 100 rpm" in saturated and "never reaches" in saturated
    assert data["top_speed_mean"] < 0.05 * system.omega
    assert f"warning: {saturated}" in err


def test_a_motor_limit_above_the_load_says_nothing(tmp_path, capsys):
    top = '\n[top_drive]\nkind = "soft-torque"\ninertia = 2900.0\nmax_torque = 60000.0\n'
    status, out, err = run_cli(tmp_path, capsys, ONE_DOF + top, "--duration", "60")
    assert status == 0, err
    assert not [w for w in json.loads(out)["warnings"] if "torque limit" in w]


def test_a_top_drive_that_never_gets_up_to_speed_is_said(tmp_path, capsys):
    # J = 1e300 kg m^2: J/kp = 4e295 s, the top drive cannot be turned within any run
    text = PI_STRING.replace("inertia = 2900.0", "inertia = 1e300")
    status, out, err = run_cli(tmp_path, capsys, text, "--duration", "30")
    assert status == 0, err
    (short,) = [w for w in json.loads(out)["warnings"] if "set speed" in w]
    assert short.startswith("the top drive never reaches its set speed: its mean speed is 0 rpm")
    assert f"warning: {short}" in err


def test_a_torque_driven_top_that_does_not_turn_names_the_torque(tmp_path, capsys):
    # 1e-300 N m against drag and a bit at rest: the top does not turn, S_SS has no speed
    text = TORQUE_CHAIN.replace("torque = 10000.0", "torque = 1e-300")
    status, out, err = run_cli(tmp_path, capsys, text, "--duration", "30")
    assert status == 2, out
    assert "error: top_drive.torque: the top drive did not turn" in err, err
