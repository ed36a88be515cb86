"""Bad input at the boundary: configuration files, CLI numbers and plugin laws (issue 12).

Each case is a piece of hostile or careless input; every one must end in torsio's own
error (exit status 2 on the command line) whose message names the key, option or
plugin, never in a traceback, a hang or a silently wrong number.
"""

from __future__ import annotations

import importlib.metadata

import numpy as np
import pytest

from torsio.cli import main
from torsio.config.reading import load_config, parse_config_text
from torsio.errors import ConfigError, PluginError, SolverError
from torsio.examples import builtin_config
from torsio.hookspecs import hookimpl
from torsio.physics.laws import BitRockLaw, Parameter
from torsio.plugins import build_bit_law, plugin_manager


def _builtin_text() -> str:
    from importlib import resources

    return resources.files("torsio").joinpath("data/ritto2017.toml").read_text(encoding="utf-8")


def _variant(old: str, new: str) -> str:
    text = _builtin_text()
    assert old in text, old
    return text.replace(old, new, 1)


def cli_error(capsys, *args: str) -> str:
    try:
        status = main(list(args))
    except SystemExit as exc:  # argparse refuses the option itself
        status = exc.code
    captured = capsys.readouterr()
    assert status == 2, captured.err
    assert "Traceback" not in captured.err
    return captured.err


# --- configuration files --------------------------------------------------------------------
# (replaced text, replacement, key named, fragment of the message)
BAD_CONFIGS = [
    ("od = 0.140", "od = 1e200", "section[0].od", "polar moment"),
    ("length = 4733.6", "length = 1e-300", "section[0].length", "1e-300"),
    ('density = "7800 kg/m^3"', "density = 1e-300", "material.density", "density = 1e-300"),
    ('shear_modulus = "85.3 GPa"', "shear_modulus = 1e308", "material.shear_modulus", "stiffness"),
    ("length = 4733.6", 'length = "5 dimensionless"', "section[0].length", "pure number"),
    ("od = 0.140", 'od = "0.14 dimensionless"', "section[0].od", "not a length"),
    (
        'shear_modulus = "85.3 GPa"',
        'shear_modulus = "1e400 Pa"',
        "material.shear_modulus",
        "finite",
    ),
    ("a0 = 0.221", "a0 = 1e400", "bit_rock.a0", "finite"),  # TOML reads 1e400 as inf
]


@pytest.mark.parametrize(("old", "new", "key", "fragment"), BAD_CONFIGS)
def test_bad_config_values_name_the_key(old, new, key, fragment):
    with pytest.raises(ConfigError) as caught:
        parse_config_text(_variant(old, new))
    message = str(caught.value)
    assert key in message and fragment in message, message


def test_section_key_is_not_repeated():
    """A bad value in a section's own material is named once: section[1].material.density."""
    text = _variant(
        'kind = "hwdp"', 'kind = "hwdp"\nmaterial = { shear_modulus = 85.3e9, density = -1 }'
    )
    with pytest.raises(ConfigError) as caught:
        parse_config_text(text)
    assert caught.value.key == "section[1].material.density"


def test_non_utf8_config_file(tmp_path, capsys):
    path = tmp_path / "latin1.toml"
    path.write_bytes(_builtin_text().replace("Drill pipes", "Drill pipés").encode("latin-1"))
    with pytest.raises(ConfigError, match=r"not UTF-8.*line \d+"):
        load_config(path)
    assert "not UTF-8" in cli_error(capsys, "modes", str(path))


@pytest.mark.parametrize(
    "text",
    ["5 dimensionless", "5 rad", "5 s"],
)
def test_a_length_needs_a_length_unit(text):
    from torsio.units import to_si

    with pytest.raises(ConfigError, match="^od: "):
        to_si(text, "length", key="od")
    # a bare number in a string is SI, like the number itself (5 m)
    assert to_si("5", "length", key="od") == 5.0


# --- command-line numbers -------------------------------------------------------------------
BAD_OPTIONS = [
    (["map", "--timeout", "nan", "--wob", "1:2:2", "--rpm", "50:60:2"], "--timeout"),
    (["map", "--timeout", "0", "--scheduler", "tcp://127.0.0.1:9"], "timeout"),
    (["map", "--rtol", "inf", "--wob", "1:2:2", "--rpm", "50:60:2"], "--rtol"),
    (["map", "--threshold", "nan", "--wob", "1:2:2", "--rpm", "50:60:2"], "--threshold"),
    (["simulate", "--rtol", "10"], "--rtol"),
    (["simulate", "--rtol", "0.5"], "--rtol"),
    (["map", "--rtol", "10", "--wob", "1:2:2", "--rpm", "50:60:2"], "--rtol"),
    (["map", "--rtol", "0.5", "--wob", "1:2:2", "--rpm", "50:60:2"], "--rtol"),
    (["simulate", "--rtol", "1e-20"], "--rtol"),
    (["simulate", "--atol", "nan"], "--atol"),
    (["simulate", "--duration", "nan"], "--duration"),
    (["simulate", "--output-step", "-1"], "--output-step"),
]


@pytest.mark.parametrize(("args", "option"), BAD_OPTIONS)
def test_bad_numbers_on_the_command_line(capsys, args, option):
    assert option in cli_error(capsys, *args)


# --- plugin laws ------------------------------------------------------------------------------
class _RaisesInConstructor(BitRockLaw):
    name = "test-raises"
    parameters = {"mu": Parameter("-", "friction coefficient", default=0.5)}

    def __init__(self, **values):
        super().__init__(**values)
        raise ZeroDivisionError("calibration table is empty")

    def torque(self, speed, wob, radius):
        return np.asarray(wob) * radius * self.mu * np.tanh(speed)


class _WrongShape(_RaisesInConstructor):
    name = "test-wrong-shape"

    def __init__(self, **values):
        BitRockLaw.__init__(self, **values)

    def torque(self, speed, wob, radius):
        return [1.0, 2.0]  # always two values, whatever the speed


class _NaNTorque(_WrongShape):
    name = "test-nan"

    def torque(self, speed, wob, radius):
        return np.asarray(speed, dtype=float) * np.nan


class _TorqueRaises(_WrongShape):
    name = "test-torque-raises"

    def torque(self, speed, wob, radius):
        if np.ndim(speed):
            raise TypeError("only scalars please")
        return 1.0


class _NaNAfterStart(_WrongShape):
    """Finite at the probe speeds, NaN once the bit turns faster than 5 rad/s... not 10."""

    name = "test-nan-later"

    def torque(self, speed, wob, radius):
        w = np.asarray(speed, dtype=float)
        return np.where((w > 3.0) & (w < 9.0), np.nan, np.asarray(wob) * radius * 0.2 * np.tanh(w))


class _TestLaws:
    @hookimpl
    def torsio_bit_laws(self):
        return [_RaisesInConstructor, _WrongShape, _NaNTorque, _TorqueRaises, _NaNAfterStart]


class _Dist:
    name = "torsio-test-laws"


class _EntryPoint:
    name, value, group, dist = "test_laws", "test:plugin", "torsio", _Dist()

    def load(self):
        return _TestLaws()


@pytest.fixture
def test_laws(monkeypatch):
    real = importlib.metadata.entry_points

    def entry_points(**kwargs):
        found = real(**kwargs)
        return [*found, _EntryPoint()] if kwargs.get("group") == "torsio" else found

    monkeypatch.setattr(importlib.metadata, "entry_points", entry_points)
    plugin_manager.cache_clear()
    yield
    plugin_manager.cache_clear()


@pytest.mark.parametrize(
    ("law", "error", "fragment"),
    [
        ("test-raises", PluginError, "ZeroDivisionError: calibration table is empty"),
        ("test-wrong-shape", PluginError, "shape"),
        ("test-nan", ConfigError, "not finite"),
        ("test-torque-raises", PluginError, "TypeError: only scalars please"),
    ],
)
def test_broken_plugin_law_names_law_and_distribution(test_laws, law, error, fragment):
    with pytest.raises(error) as caught:
        build_bit_law(law, {})
    message = str(caught.value)
    assert law in message and "torsio-test-laws" in message and fragment in message, message


def test_broken_plugin_law_in_a_configuration(test_laws, capsys, tmp_path):
    path = tmp_path / "broken.toml"
    text = _builtin_text()
    start = text.index("[bit_rock]")
    end = text.index("[damping]")
    path.write_text(text[:start] + '[bit_rock]\nlaw = "test-raises"\n\n' + text[end:])
    err = cli_error(capsys, "simulate", str(path), "--strategy", "A")
    assert "test-raises" in err and "torsio-test-laws" in err


GRID_ARGS = ["--wob", "50kN:150kN:2", "--rpm", "60:100:2", "--refine", "0"]


@pytest.mark.parametrize(
    "args",
    [
        ["simulate"],
        ["map", *GRID_ARGS],
        ["map", *GRID_ARGS, "--engine", "numpy"],
        ["map", *GRID_ARGS, "--engine", "scipy"],
    ],
    ids=["simulate", "map", "map numpy", "map scipy"],
)
def test_nan_torque_on_the_command_line_names_the_law(test_laws, capsys, tmp_path, args):
    """A plugin law that turns NaN once the bit moves: every engine names it, status 2."""
    path = tmp_path / "nan.toml"
    text = _builtin_text()
    start, end = text.index("[bit_rock]"), text.index("[damping]")
    path.write_text(text[:start] + '[bit_rock]\nlaw = "test-nan-later"\n\n' + text[end:])
    err = cli_error(capsys, args[0], str(path), "--strategy", "A", *args[1:])
    assert "'test-nan-later'" in err and "torsio-test-laws" in err, err


def test_nan_torque_during_a_run_names_the_law(test_laws):
    from torsio.analysis.transient import simulate

    system = builtin_config().system(strategy="A").at(wob=100e3, rpm=60)
    system = type(system)(**{**_fields(system), "law": build_bit_law("test-nan-later", {})})
    with pytest.raises(SolverError, match=r"'test-nan-later'.*torsio-test-laws"):
        simulate(system, duration=60.0, steady_window=20.0)


def _fields(system):
    import attrs

    return {f.name: getattr(system, f.name) for f in attrs.fields(type(system)) if f.init}


# --- extreme but finite law parameters --------------------------------------------------------
@pytest.mark.parametrize(
    ("old", "new"),
    [
        ("a0 = 0.221", "a0 = 1e200"),
        ("a0 = 0.221", "a0 = 1e20"),
        ("a1 = 0.2", "a1 = 1e8"),
        ("radius = 0.108", "radius = 1e300"),
    ],
)
def test_law_too_stiff_to_integrate_is_refused(capsys, tmp_path, old, new):
    """The bit's time scale at sticking is beyond what the run can resolve: a clear error."""
    path = tmp_path / "stiff.toml"
    path.write_text(_variant(old, new))
    err = cli_error(capsys, "simulate", str(path), "--strategy", "A")
    assert "bit_rock" in err and "tucker-wang" in err


# --- output paths, checked before the work starts ---------------------------------------------
def _output_cases(tmp_path):
    folder = tmp_path / "folder.png"  # a folder, whatever the suffix says
    folder.mkdir()
    config = tmp_path / "x.toml"
    config.write_text(_builtin_text())
    return {
        "folder": ([str(folder)], "is a folder"),
        "proc": (["/proc/torsio-out.png"], "cannot write"),
        "missing folder": ([str(tmp_path / "nowhere" / "m.png")], "does not exist"),
        "config": ([str(config)], "configuration file"),
    }, str(config)


@pytest.mark.parametrize("case", ["folder", "proc", "missing folder", "config"])
@pytest.mark.parametrize(
    ("command", "option"),
    [
        ("map", "--out"),
        ("map", "--csv"),
        ("map", "--plot"),
        ("simulate", "--csv"),
        ("simulate", "--plot"),
        ("report", "--html"),
    ],
)
def test_unwritable_outputs_are_refused_before_the_work(capsys, tmp_path, case, command, option):
    cases, config = _output_cases(tmp_path)
    paths, fragment = cases[case]
    grid = ["--wob", "1:2:2", "--rpm", "50:60:2"] if command == "map" else []
    # a grid this small would run in seconds; the refusal must come first (no partial file)
    err = cli_error(capsys, command, config, *grid, option, paths[0])
    # a plot named like the configuration is refused for its suffix already
    assert option in err and (fragment in err or "matplotlib cannot write" in err), err
    assert not list(tmp_path.glob("*.partial.*"))


@pytest.mark.parametrize(
    "args",
    [
        ["map", "--wob", "1:2:2", "--rpm", "50:60:2", "--out"],
        ["map", "--wob", "1:2:2", "--rpm", "50:60:2", "--csv"],
        ["simulate", "--csv"],
        ["report", "--html"],
    ],
    ids=lambda args: " ".join(args[:1] + args[-1:]),
)
def test_read_only_folder_is_refused(args):
    """A folder the user may not write into: refused before the work, naming the option.

    Root writes everywhere, so as root the command runs in a forked child that has
    become ``nobody`` (the modules it needs are imported before the fork).
    """
    import os
    import tempfile

    import torsio.analysis.maps  # noqa: F401  (imported before the fork)
    import torsio.analysis.transient  # noqa: F401
    from torsio.cli import build_parser

    build_parser()
    base = tempfile.mkdtemp(prefix="torsio-ro-")
    os.chmod(base, 0o755)
    folder = os.path.join(base, "ro")
    os.mkdir(folder, 0o555)
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: never return into pytest
        status = 70
        try:
            import sys

            if os.geteuid() == 0:
                os.setgid(65534)
                os.setuid(65534)
            sys.stderr = os.fdopen(write, "w")
            status = main([*args, os.path.join(folder, "out.file")])
            sys.stderr.flush()
        finally:
            os._exit(status)
    os.close(write)
    with os.fdopen(read) as stream:
        err = stream.read()
    _, status = os.waitpid(pid, 0)
    os.chmod(folder, 0o755)
    assert os.waitstatus_to_exitcode(status) == 2, err
    assert args[-1] in err and "cannot write" in err and "Traceback" not in err, err
    assert os.listdir(folder) == []


def test_plot_path_is_the_file_written(capsys, tmp_path):
    pytest.importorskip("matplotlib")
    import json

    target = tmp_path / "out"
    status = main(
        [
            "simulate",
            "--strategy",
            "A",
            "--duration",
            "60",
            "--window",
            "20",
            "--plot",
            str(target),
            "--json",
        ]
    )
    captured = capsys.readouterr()
    assert status == 0, captured.err
    assert json.loads(captured.out)["plot"] == str(target) + ".png"
    assert (tmp_path / "out.png").is_file()
    assert "--plot" in cli_error(capsys, "simulate", "--plot", str(tmp_path / "x.docx"))
