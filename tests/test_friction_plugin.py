"""The plugin distribution plugins/torsio-friction-laws, used as a third party would.

It is installed (``pip install -e plugins/torsio-friction-laws``) and found through
its ``torsio`` entry point. Sources: the friction law of Navarro-López and Cortés
(2007) with their values mu_sb = 0.8, mu_cb = 0.5, gamma_b = 0.9, v_f = 1 rad/s,
W_ob = 97347 N, R_b = 0.155575 m, written out here by hand; the generalized
Stribeck curve of Armstrong-Hélouvry et al. (1994).
"""

from __future__ import annotations

import doctest
import importlib.metadata
import json
import math
import os
import shutil
import subprocess
import sys
import warnings
from importlib import resources
from pathlib import Path

import attrs
import numpy as np
import pytest

from torsio.analysis.transient import simulate
from torsio.config.reading import parse_config_text
from torsio.errors import ConfigError
from torsio.examples import builtin_config
from torsio.hookspecs import hookimpl
from torsio.physics.laws import BitRockLaw, TuckerWang
from torsio.plugins import PluginWarning, bit_laws, get_bit_law, plugin_manager

PLUGIN_DIR = Path(__file__).resolve().parents[1] / "plugins" / "torsio-friction-laws"
W_OB, R_B = 97347.0, 0.155575  # Navarro-López and Cortés (2007)


@pytest.fixture
def fresh_plugins():
    """A plugin manager rebuilt for the test, and again afterwards."""
    plugin_manager.cache_clear()
    yield
    plugin_manager.cache_clear()


def test_discovered_through_entry_point():
    points = [ep for ep in importlib.metadata.entry_points(group="torsio")]
    mine = [ep for ep in points if ep.value == "torsio_friction_laws"]
    assert mine, "plugins/torsio-friction-laws is not installed (pip install -e it)"
    assert mine[0].dist is not None and mine[0].dist.name == "torsio-friction-laws"
    laws = bit_laws()
    for name in ("coulomb-stribeck", "generalized-stribeck"):
        assert name in laws
        assert laws[name].__module__ == "torsio_friction_laws"
        assert issubclass(laws[name], BitRockLaw)
    assert laws["tucker-wang"] is TuckerWang  # the built-in law is still there


def test_plugin_doctests():
    module = __import__("torsio_friction_laws")
    failures, tried = doctest.testmod(module, optionflags=doctest.ELLIPSIS)
    assert tried > 0 and failures == 0


def test_coulomb_stribeck_is_navarro_lopez_cortes():
    law = get_bit_law("coulomb-stribeck")()  # defaults: their values
    w = np.array([0.2, 0.5, 1.0, 3.0, 10.0])  # rad/s, where tanh(w/0.01) = 1
    mu = 0.5 + (0.8 - 0.5) * np.exp(-0.9 * w / 1.0)
    assert np.allclose(law.torque(w, W_OB, R_B), W_OB * R_B * mu, rtol=1e-12)
    assert np.allclose(law.torque(-w, W_OB, R_B), -W_OB * R_B * mu, rtol=1e-12)
    assert float(law.torque(0.0, W_OB, R_B)) == 0.0  # smooth sign: zero at rest
    # static and Coulomb limits
    assert float(law.torque(0.1, W_OB, R_B)) == pytest.approx(W_OB * R_B * 0.8, rel=0.1)
    assert float(law.torque(50.0, W_OB, R_B)) == pytest.approx(W_OB * R_B * 0.5, rel=1e-12)
    # broadcasting over speeds and weights on bit
    assert law.torque(w[:, None], np.array([1e4, 2e4]), R_B).shape == (5, 2)


def test_generalized_stribeck_formula_and_units():
    law_cls = get_bit_law("generalized-stribeck")
    law = law_cls(mu_static=0.8, mu_coulomb=0.5, stribeck_speed=2.0, exponent=2.0)
    w = np.array([0.5, 1.0, 2.0, 4.0])
    mu = 0.5 + 0.3 * np.exp(-((w / 2.0) ** 2))
    assert np.allclose(law.torque(w, 1e5, 0.1), 1e5 * 0.1 * mu, rtol=1e-12)
    # the same law stated for a speed in rpm (w_s = 2 rad/s = 60/pi rpm); the default
    # smoothing stays 0.01 rad/s
    in_rpm = law_cls(
        mu_static=0.8, mu_coulomb=0.5, stribeck_speed=2.0 * 30 / math.pi, speed_unit="rpm"
    )
    assert in_rpm.smoothing == 0.01
    assert np.allclose(in_rpm.torque(w, 1e5, 0.1), law.torque(w, 1e5, 0.1), rtol=1e-12)
    # analytic slope against a central difference
    s = np.linspace(-3, 3, 25)
    h = 1e-6
    numeric = (law.torque(s + h, 1e5, 0.1) - law.torque(s - h, 1e5, 0.1)) / (2 * h)
    assert np.allclose(law.slope(s, 1e5, 0.1), numeric, rtol=1e-5, atol=1e-2)


@pytest.mark.parametrize(
    ("name", "values", "key", "fragment"),
    [
        ("coulomb-stribeck", {"mu_static": 0.4, "mu_coulomb": 0.5}, "mu_coulomb", "0.5"),
        ("coulomb-stribeck", {"smoothing": 0.0}, "smoothing", "0.0"),
        ("coulomb-stribeck", {"stribeck_speed": -1.0}, "stribeck_speed", "-1.0"),
        ("coulomb-stribeck", {"mu_static": float("nan")}, "mu_static", "nan"),
        ("coulomb-stribeck", {"friction": 0.3}, "friction", "no parameter 'friction'"),
        (
            "generalized-stribeck",
            {"mu_static": 0.8, "mu_coulomb": 0.5},
            "stribeck_speed",
            "needs parameter",
        ),
        (
            "generalized-stribeck",
            {"mu_static": 0.8, "mu_coulomb": 0.5, "stribeck_speed": 1.0, "exponent": 0.5},
            "exponent",
            "0.5",
        ),
    ],
)
def test_bad_parameters_name_the_value(name, values, key, fragment):
    with pytest.raises(ConfigError) as info:
        get_bit_law(name)(**values)
    assert info.value.key == f"bit_rock.{key}"
    assert fragment in str(info.value)


def test_unknown_law_is_an_error():
    with pytest.raises(
        ConfigError,
        match=r"bit_rock\.law: unknown bit-rock law 'stribek'.*"
        r"coulomb-stribeck",
    ):
        get_bit_law("stribek")


def test_plugin_law_in_a_configuration_file():
    text = (
        "name = 'plugin law'\n"
        "[[section]]\nkind = 'drill_pipe'\nod = 0.140\nid = 0.119\nlength = 4733.6\n"
        "[[section]]\nkind = 'bha'\nod = 0.171\nid = 0.071\nlength = 294.9\n"
        "[[section]]\nkind = 'bit'\nod = 0.216\nid = 0.057\nlength = 0.25\n"
        "[bit_rock]\nlaw = 'coulomb-stribeck'\nmu_static = 0.8\nmu_coulomb = 0.5\n"
        "stribeck_speed = 10.6\nspeed_unit = 'rpm'\n"
        "[damping]\nalpha = 0.35\nbeta = 0.06\n"
        "[discretization]\nstrategy = 'A'\n"
    )
    config = parse_config_text(text)
    system = config.system().at(wob=100e3, rpm=20)
    assert system.law.name == "coulomb-stribeck"
    assert system.law.stribeck_speed == pytest.approx(10.6 * math.pi / 30)
    results = simulate(system)
    assert results.severity > 0.8  # velocity weakening: stick-slip at 20 rpm
    with pytest.raises(ConfigError, match=r"bit_rock\.mu_coulomb.*0\.9"):
        parse_config_text(text.replace("mu_coulomb = 0.5", "mu_coulomb = 0.9"))


# --- broken and conflicting plugins --------------------------------------------------------
class _FakeEntryPoint:
    """Stands for an installed distribution's entry point of group ``torsio``."""

    def __init__(self, name, value, loader):
        self.name, self.value, self.group, self.dist = name, value, "torsio", None
        self._loader = loader

    def load(self):
        return self._loader()


def _fake_entry_points(monkeypatch, *extra):
    real = importlib.metadata.entry_points

    def entry_points(**kwargs):
        found = real(**kwargs)
        if kwargs.get("group") == "torsio":
            return [*found, *extra]
        return found

    monkeypatch.setattr(importlib.metadata, "entry_points", entry_points)


def _missing_module():
    import torsio_plugin_that_is_not_installed  # noqa: F401


class _Clash(BitRockLaw):
    name = "tucker-wang"  # already taken by the built-in law


class _ClashingPlugin:
    @hookimpl
    def torsio_bit_laws(self):
        return [_Clash]


class _RaisingPlugin:
    @hookimpl
    def torsio_bit_laws(self):
        raise RuntimeError("cannot read my calibration file")


def test_broken_plugin_is_reported_not_fatal(monkeypatch, fresh_plugins):
    _fake_entry_points(
        monkeypatch,
        _FakeEntryPoint("broken_laws", "torsio_plugin_that_is_not_installed", _missing_module),
        _FakeEntryPoint("raising_laws", "raising:plugin", _RaisingPlugin),
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        laws = bit_laws()
    messages = [str(w.message) for w in caught if issubclass(w.category, PluginWarning)]
    assert any("broken_laws" in m and "ModuleNotFoundError" in m for m in messages)
    assert any("raising_laws" in m and "cannot read my calibration file" in m for m in messages)
    # the other laws keep working
    assert "tucker-wang" in laws and "coulomb-stribeck" in laws
    with pytest.warns(PluginWarning, match="raising_laws"):  # reported again on each look-up
        system = builtin_config().system(strategy="A").at(wob=100e3, rpm=60)
    assert simulate(system, duration=40.0, steady_window=10.0).severity >= 0.0


def test_conflicting_plugin_is_reported(monkeypatch, fresh_plugins):
    _fake_entry_points(
        monkeypatch, _FakeEntryPoint("clashing_laws", "clash:plugin", _ClashingPlugin)
    )
    with pytest.warns(PluginWarning, match=r"'tucker-wang' is already registered") as record:
        laws = bit_laws()
    assert any("clashing_laws" in str(w.message) for w in record)
    assert "coulomb-stribeck" in laws and "tucker-wang" in laws


def test_conflicting_plugin_does_not_replace_builtin(monkeypatch, fresh_plugins):
    _fake_entry_points(
        monkeypatch, _FakeEntryPoint("clashing_laws", "clash:plugin", _ClashingPlugin)
    )
    with pytest.warns(PluginWarning, match="clashing_laws"):
        laws = bit_laws()
    assert laws["tucker-wang"] is TuckerWang


def test_broken_plugin_in_the_cli(monkeypatch, fresh_plugins, capsys):
    from torsio.cli import main

    _fake_entry_points(
        monkeypatch,
        _FakeEntryPoint("broken_laws", "torsio_plugin_that_is_not_installed", _missing_module),
    )
    with pytest.warns(PluginWarning, match="broken_laws.*ModuleNotFoundError"):
        assert main(["laws", "--json"]) == 0
    captured = capsys.readouterr()
    names = [law["name"] for law in json.loads(captured.out)["laws"]]
    assert "tucker-wang" in names and "coulomb-stribeck" in names


class _PlainLaw:
    """Exponential weakening, written from the plugin contract alone (no base class)."""

    name = "plain-exponential"

    def __init__(self, mu_static=0.8, mu_dynamic=0.5, *, decay, label="rock"):
        self.mu_static, self.mu_dynamic = mu_static, mu_dynamic
        self.decay, self.label = decay, label

    def torque(self, speed, wob, radius):
        w = np.asarray(speed, dtype=float)
        weakening = (self.mu_static - self.mu_dynamic) * np.exp(-np.abs(w) / self.decay)
        return wob * radius * (self.mu_dynamic + weakening) * np.tanh(w / 0.05)


class _PlainPlugin:
    @hookimpl
    def torsio_bit_laws(self):
        return [_PlainLaw]


def test_a_law_without_the_base_class_lists_its_keyword_parameters(
    monkeypatch, fresh_plugins, capsys
):
    # the constructor's signature is all such a law declares: its names and defaults (the
    # number as given, the text of another default, None where required), units unknown
    from torsio.cli import main

    _fake_entry_points(monkeypatch, _FakeEntryPoint("plain_laws", "plain:plugin", _PlainPlugin))
    assert main(["laws", "--json"]) == 0
    laws = {law["name"]: law for law in json.loads(capsys.readouterr().out)["laws"]}
    plain = laws["plain-exponential"]
    assert plain["description"] == _PlainLaw.__doc__
    assert plain["parameters"] == [
        {"name": "mu_static", "unit": None, "default": 0.8},
        {"name": "mu_dynamic", "unit": None, "default": 0.5},
        {"name": "decay", "unit": None, "default": None},
        {"name": "label", "unit": None, "default": "rock"},
    ]
    assert main(["laws"]) == 0
    table = capsys.readouterr().out
    assert "mu_static = 0.8" in table and "decay = required" in table


def test_the_report_shows_what_the_file_gave_a_law_without_the_base_class(
    monkeypatch, fresh_plugins, capsys, tmp_path
):
    # a plain class has no `given`: the report's operating point shows the [bit_rock]
    # parameters of the file (the law reads them in rad/s, the only reading it takes)
    from torsio.cli import main

    _fake_entry_points(monkeypatch, _FakeEntryPoint("plain_laws", "plain:plugin", _PlainPlugin))
    text = resources.files("torsio").joinpath("data/ritto2017.toml").read_text("utf-8")
    start = text.index("[bit_rock]")
    end = text.index("\n[", start + 1)
    table = "[bit_rock]\nlaw = 'plain-exponential'\ndecay = 2.0\nlabel = 'shale'\n"
    path = tmp_path / "plain.toml"
    path.write_text(text[:start] + table + text[end + 1 :], encoding="utf-8")
    assert main(["report", str(path), "--json"]) == 0
    law = json.loads(capsys.readouterr().out)["operation"]["bit_rock_law"]
    assert law["name"] == "plain-exponential" and law["speed_unit"] == "rad/s"
    assert law["given"] == {"decay": 2.0, "label": "shale"}
    assert main(["report", str(path)]) == 0
    assert "plain-exponential (decay = 2, label = shale; bit speed in rad/s)" in (
        capsys.readouterr().out
    )


def test_a_law_without_the_base_class_gets_only_a_known_speed_unit():
    # the configuration's readings (docs/configuration.md): rad/s or rpm, for every law
    from torsio.plugins import build_law

    class Reading:
        name = "reading"

        def __init__(self, c=1.0, speed_unit="rad/s"):
            self.c, self.unit = c, speed_unit

    assert build_law(Reading, {}, "rpm").unit == "rpm"
    from torsio.cli.laws import describe  # the table's reading, not one of its parameters

    assert [p["name"] for p in describe(Reading)["parameters"]] == ["c"]
    with pytest.raises(ConfigError, match=r"bit_rock\.speed_unit: expected one of .*'rps'"):
        build_law(Reading, {}, "rps")


# --- a fresh environment ---------------------------------------------------------------
@pytest.mark.slow
def test_fresh_environment_discovers_the_plugin(tmp_path):
    """A new virtual environment sees the plugin only once it is pip-installed there."""
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    python = venv / ("Scripts" if os.name == "nt" else "bin") / "python"
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PIP_REQUIRE_VIRTUALENV")}
    # a venv gets its own setuptools; building without isolation needs the wheel package too
    if subprocess.run([str(python), "-c", "import wheel"], env=env).returncode != 0:
        subprocess.run([str(python), "-m", "pip", "install", "-q", "wheel"], env=env, check=True)
    source = tmp_path / "torsio-friction-laws"  # build outside the work tree
    shutil.copytree(
        PLUGIN_DIR, source, ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__")
    )
    subprocess.run(
        [
            str(python),
            "-m",
            "pip",
            "install",
            "-q",
            "--no-build-isolation",
            "--no-deps",
            str(source),
        ],
        env=env,
        check=True,
    )
    where = subprocess.run(
        [
            str(python),
            "-c",
            "import importlib.metadata as m; print(m.distribution('torsio-friction-laws')"
            ".locate_file(''))",
        ],
        env=env,
        check=True,
        capture_output=True,
        text=True,
    ).stdout.strip()
    assert Path(where).resolve().is_relative_to(venv.resolve())  # the venv's own copy
    listed = subprocess.run(
        [str(python), "-m", "torsio", "laws", "--json"],
        env=env,
        check=True,
        capture_output=True,
        text=True,
    )
    names = {law["name"] for law in json.loads(listed.stdout)["laws"]}
    assert {"coulomb-stribeck", "generalized-stribeck", "tucker-wang"} <= names


def test_plugin_system_runs_in_strategy_c():
    """A plugin law drives the multi-DOF model like the built-in one (stick-slip found)."""
    law = get_bit_law("coulomb-stribeck")()
    system = attrs.evolve(builtin_config().system(), law=law).at(wob=100e3, rpm=20)
    results = simulate(system)
    assert results.severity > 0.8
    assert results.stick_fraction > 0.1


# --- the plugin author's guide ----------------------------------------------------------
def _python_blocks(markdown: str) -> list[str]:
    blocks, inside, current = [], False, []
    for line in markdown.splitlines():
        if line.strip() == "```python":
            inside, current = True, []
        elif inside and line.strip() == "```":
            inside = False
            blocks.append("\n".join(current))
        elif inside:
            current.append(line)
    return blocks


def test_guide_example_works(fresh_plugins):
    """The complete minimal plugin of docs/plugins.md registers and runs as written."""
    import types

    guide = (Path(__file__).resolve().parents[1] / "docs" / "plugins.md").read_text()
    module_code, usage_code = _python_blocks(guide)[:2]
    module = types.ModuleType("linear_weakening")
    # a file name that does not exist: nothing is cached next to the docs
    exec(compile(module_code, "<docs/plugins.md>", "exec"), module.__dict__)
    plugin_manager().register(module, name="linear_weakening")
    law_cls = get_bit_law("saturating-weakening")
    law = law_cls(mu_static=0.8, weakening_speed=20.0, speed_unit="rpm")
    w_s = 20.0 * math.pi / 30.0  # rad/s
    w = np.array([1.0, 5.0])
    # defaults are in the rad/s reading whatever the speed unit (smoothing 0.05 rad/s)
    expected = 1e5 * 0.1 * (0.4 + 0.4 / (1 + w / w_s)) * np.tanh(w / 0.05)
    assert np.allclose(law.torque(w, 1e5, 0.1), expected, rtol=1e-12)
    with pytest.raises(ConfigError, match=r"bit_rock\.mu_sliding.*0\.9"):
        law_cls(mu_static=0.8, mu_sliding=0.9)
    # its compiled kernel is the same formula (torsio.solvers.law_kernels contract)
    from torsio.solvers.law_kernels import law_kernel

    kernel = law_kernel(law)
    compiled = [kernel.torque(kernel.parameters, float(x), 1e5, 0.1) for x in w]
    assert np.allclose(compiled, expected, rtol=1e-12)
    # the analytic slope against a central difference of the torque (step 1e-6 rad/s)
    ahead, behind = law.torque(w + 1e-6, 1e5, 0.1), law.torque(w - 1e-6, 1e5, 0.1)
    assert np.allclose(law.slope(w, 1e5, 0.1), (ahead - behind) / 2e-6, rtol=1e-6)
    namespace: dict = {}
    exec(compile(usage_code, "docs/plugins.md", "exec"), namespace)


def test_guide_plain_class_compiles_as_written():
    """The plain class of docs/plugins.md ("A plain class is enough") compiles with numba
    as it is written (law_kernels.python_law_kernel checks it against the Python torque at
    ten speeds, to 1e-12), and its constructor names the key of a bad value."""
    import types

    from torsio.solvers.law_kernels import python_law_kernel

    guide = (Path(__file__).resolve().parents[1] / "docs" / "plugins.md").read_text()
    module = types.ModuleType("stribeck_strengthening")
    exec(compile(_python_blocks(guide)[2], "<docs/plugins.md>", "exec"), module.__dict__)
    law = module.StribeckStrengthening(mu_s=0.8, strengthening=0.01)
    kernel = python_law_kernel(law)
    # exact at 5 rad/s, 1e5 N, 0.1 m: tanh(100) = 1 to double precision
    expected = 1e5 * 0.1 * (0.5 + 0.3 * math.exp(-2.5) + 0.01 * 5.0)
    assert kernel.torque(kernel.parameters, 5.0, 1e5, 0.1) == pytest.approx(expected, rel=1e-12)
    with pytest.raises(ConfigError, match=r"bit_rock\.mu_d: expected at most"):
        module.StribeckStrengthening(mu_s=0.4, mu_d=0.5)
