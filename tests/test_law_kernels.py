"""Bit-rock laws with their own compiled kernels, laws without, and plain contract classes.

Sources of the reference numbers: each law's own vectorized ``torque``/``slope`` (the
compiled function must give the same value: both are the one formula of the law, see
torsio.solvers.law_kernels); the numpy engine, which runs the same method through the
law's vectorized torque (an independent path to the same S_SS); the Tucker-Wang law
evaluated by hand for the plain class.
"""

from __future__ import annotations

import json
import math
from typing import Any

import attrs
import numpy as np
import pytest

from torsio.config.reading import parse_config_text
from torsio.errors import ConfigError
from torsio.hookspecs import hookimpl
from torsio.physics.dimensionless import DimensionlessTuckerWang, dimensionless_system
from torsio.physics.laws import ConstantTorque, TuckerWang
from torsio.physics.system import System
from torsio.plugins import build_law, get_bit_law, plugin_manager
from torsio.solvers import batch
from torsio.solvers.law_kernels import law_kernel

SPEEDS = np.linspace(-3.0, 8.0, 23)  # rad/s, both signs and the weakening range


@pytest.mark.parametrize(
    "law",
    [
        TuckerWang(a0=0.221, a1=0.2, a2=0.89, a3=0.06, speed_unit="rpm"),
        ConstantTorque(torque_on_bit=-1234.5),
        get_bit_law("coulomb-stribeck")(viscous=3.0),
        get_bit_law("generalized-stribeck")(
            mu_static=0.8, mu_coulomb=0.5, stribeck_speed=1.2, viscous=2.0
        ),
    ],
    ids=lambda law: law.name,
)
def test_kernel_is_the_law(law: Any) -> None:
    kernel = law_kernel(law)
    assert kernel is not None
    wob, radius = 97347.0, 0.155575
    torque = [kernel.torque(kernel.parameters, float(w), wob, radius) for w in SPEEDS]
    slope = [kernel.slope(kernel.parameters, float(w), wob, radius) for w in SPEEDS]
    # the same formula compiled: equal to the last bits of libm's tanh/exp
    np.testing.assert_allclose(torque, law.torque(SPEEDS, wob, radius), rtol=1e-13, atol=1e-9)
    np.testing.assert_allclose(slope, law.slope(SPEEDS, wob, radius), rtol=1e-12, atol=1e-9)


def test_dimensionless_tucker_wang_runs_compiled(one_dof: System) -> None:
    scaled = dimensionless_system(one_dof.at(wob=150e3, rpm=60.0))
    assert isinstance(scaled.law, DimensionlessTuckerWang)
    compiled = batch.simulate_batch(scaled, [scaled.wob], [scaled.rpm])
    numpy = batch.simulate_batch(scaled, [scaled.wob], [scaled.rpm], engine="numpy")
    assert compiled.engine == "compiled" and numpy.engine == "numpy"
    # same method, same law, two implementations: agree within the solver tolerance
    assert abs(compiled.severity[0] - numpy.severity[0]) < 1e-3
    # Eq. 11 is the same dynamics: S_SS of the dimensional map point (ERRATA 3)
    dimensional = batch.simulate_batch(one_dof, [150e3], [60.0])
    assert abs(compiled.severity[0] - dimensional.severity[0]) < 2e-3


# --- a plain class following the documented contract ----------------------------------------
class PlainTuckerWang:
    """Tucker-Wang written to the contract only: name, keyword parameters, torque."""

    name = "plain-tucker-wang"

    def __init__(self, a0: float, a1: float, a2: float = 0.0, a3: float = 0.0) -> None:
        if a0 <= 0:
            raise ValueError(f"a0 must be positive, got {a0!r}")
        self.a0, self.a1, self.a2, self.a3 = a0, a1, a2, a3

    def torque(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        w = np.asarray(speed, dtype=float)
        friction = np.tanh(self.a1 * w) + self.a2 * w / (1.0 + self.a3 * w * w)
        return np.asarray(wob) * np.asarray(radius) * self.a0 * friction


class _PlainPlugin:
    @hookimpl
    def torsio_bit_laws(self) -> list[type]:
        return [PlainTuckerWang]


@pytest.fixture
def plain_law_registered():
    plugin_manager.cache_clear()
    plugin_manager().register(_PlainPlugin(), name="plain-law-test")
    yield
    plugin_manager.cache_clear()


# Tucker-Wang's paper values in the rad/s reading (a1 = 0.2 s/rad x 30/pi etc.)
RAD_S = {"a0": 0.221, "a1": 0.2 * 30 / math.pi, "a2": 0.89 * 30 / math.pi}
RAD_S["a3"] = 0.06 * (30 / math.pi) ** 2


def _config_text(law: str, extra: str = "") -> str:
    keys = "\n".join(f"{k} = {v!r}" for k, v in RAD_S.items())
    return (
        "name = 'plain law'\n"
        "[[section]]\nkind = 'drill_pipe'\nod = 0.140\nid = 0.119\nlength = 4733.6\n"
        "[[section]]\nkind = 'bha'\nod = 0.171\nid = 0.071\nlength = 294.9\n"
        "[[section]]\nkind = 'bit'\nod = 0.216\nid = 0.057\nlength = 0.25\n"
        f"[bit_rock]\nlaw = '{law}'\nradius = 0.108\n{keys}\n{extra}"
        "[damping]\nalpha = 0.35\nbeta = 0.06\n"
        "[discretization]\nstrategy = 'A'\n"
    )


def test_plain_class_is_built_without_speed_unit(plain_law_registered) -> None:
    config = parse_config_text(_config_text("plain-tucker-wang"))
    law = config.bit_law()
    assert isinstance(law, PlainTuckerWang)
    # by hand: T = W R a0 (tanh(a1 w) + a2 w / (1 + a3 w^2)) at w = 2 rad/s, 100 kN, 0.108 m
    w = 2.0
    a0, a1, a2, a3 = RAD_S.values()
    expected = 100e3 * 0.108 * a0 * (math.tanh(a1 * w) + a2 * w / (1 + a3 * w * w))
    assert float(law.torque(w, 100e3, 0.108)) == pytest.approx(expected, rel=1e-14)


@pytest.mark.parametrize(
    ("extra", "key", "fragment"),
    [
        ("speed_unit = 'rpm'\n", "bit_rock.speed_unit", "rad/s reading only"),
        ("a9 = 1.0\n", "bit_rock.a9", "has no parameter 'a9'"),
    ],
)
def test_plain_class_errors_name_the_law_and_key(
    plain_law_registered, extra: str, key: str, fragment: str
) -> None:
    with pytest.raises(ConfigError, match=fragment) as caught:
        parse_config_text(_config_text("plain-tucker-wang", extra))
    assert caught.value.key == key and "plain-tucker-wang" in str(caught.value)


def test_plain_class_rejecting_its_value_is_a_config_error() -> None:
    with pytest.raises(ConfigError, match=r"plain-tucker-wang.*a0 must be positive") as caught:
        build_law(PlainTuckerWang, {"a0": -1.0, "a1": 1.0})
    assert caught.value.key == "bit_rock.law"
    with pytest.raises(ConfigError, match="needs parameter 'a1'") as caught:
        build_law(PlainTuckerWang, {"a0": 0.2})
    assert caught.value.key == "bit_rock.a1"


def test_plain_class_runs_in_map(plain_law_registered, tmp_path, capsys) -> None:
    from torsio.cli import main

    path = tmp_path / "plain.toml"
    path.write_text(_config_text("plain-tucker-wang"))
    args = ["map", str(path), "--wob", "50e3:150e3:2", "--rpm", "60:120:2", "--refine", "0"]
    assert main([*args, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["engine"] == "numpy"
    # the same string with the built-in law (same values) runs compiled: the same S_SS
    assert main([*args[:1], str(_tucker_copy(tmp_path)), *args[2:], "--json"]) == 0
    builtin = json.loads(capsys.readouterr().out)
    assert builtin["engine"] == "compiled"
    np.testing.assert_allclose(data["severity"], builtin["severity"], atol=1e-3)
    assert main(args) == 0
    assert "numpy engine" in capsys.readouterr().out


def _tucker_copy(tmp_path: Any) -> Any:
    path = tmp_path / "tucker.toml"
    path.write_text(_config_text("tucker-wang"))
    return path


# --- a kernel that breaks the contract ------------------------------------------------------
def test_malformed_kernel_is_reported(one_dof: System) -> None:
    class Broken(TuckerWang):
        name = "broken-kernel"

        def kernel(self) -> Any:
            return (np.tanh, np.tanh, np.zeros(4))  # not numba functions

    law = Broken(a0=0.221, a1=0.2, a2=0.89, a3=0.06, speed_unit="rpm")
    system = attrs.evolve(one_dof, law=law)
    with pytest.raises(ConfigError, match="compiled by numba"):
        batch.simulate_batch(system, [150e3], [60.0], engine="compiled")
    with pytest.warns(RuntimeWarning, match="numpy engine"):
        result = batch.simulate_batch(system, [150e3], [60.0])
    assert result.engine == "numpy"


def _nan_slope(p: Any, w: float, wob: float, radius: float) -> float:
    """A slope that is not a number once the bit turns slower than p[4] rad/s."""
    return math.nan if w < p[4] else 0.0


def test_a_law_whose_slope_is_not_a_number_is_a_non_finite_state(one_dof: System) -> None:
    # the law, not the step, is at fault: the point's status says so (not "step size
    # underflow", as when the step shrank on the NaN until it vanished)
    from torsio.solvers.batch_results import STATUS_MESSAGES, STATUS_NOT_FINITE
    from torsio.solvers.law_kernels import compile_law_function

    class NanSlope(TuckerWang):
        name = "nan-slope"

        def kernel(self) -> Any:
            torque, _, parameters = super().kernel()
            return (torque, compile_law_function(_nan_slope), np.append(parameters, 1.0))

    law = NanSlope(a0=0.221, a1=0.2, a2=0.89, a3=0.06, speed_unit="rpm")
    result = batch.simulate_batch(attrs.evolve(one_dof, law=law), [150e3], [60.0])
    assert result.engine == "compiled"
    assert result.status[0] == STATUS_NOT_FINITE
    assert "non-finite" in STATUS_MESSAGES[STATUS_NOT_FINITE]
    assert np.isnan(result.severity[0])
