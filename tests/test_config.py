"""Configuration files: the built-in example, units at the edge, and clear errors."""

from __future__ import annotations

import copy
import tomllib
from importlib import resources

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from torsio import builtin_config, load_config, parse_config
from torsio.config.reading import parse_config_text
from torsio.errors import ConfigError, TorsioError

BUILTIN = tomllib.loads(
    resources.files("torsio").joinpath("data/ritto2017.toml").read_text(encoding="utf-8")
)


def with_change(path: tuple, value) -> dict:
    """The built-in configuration with one value replaced (path of keys / indices)."""
    data = copy.deepcopy(BUILTIN)
    target = data
    for key in path[:-1]:
        target = target[key]
    if value is _DELETE:
        del target[path[-1]]
    else:
        target[path[-1]] = value
    return data


_DELETE = object()


def test_builtin_reproduces_table_1():
    # Source: paper Table 1 (Ritto et al. 2017) and Section 3 (G = 85.3 GPa, rho = 7800).
    string = builtin_config().string
    table = [
        (0.140, 0.119, 4733.6),
        (0.140, 0.076, 171.30),
        (0.171, 0.071, 294.90),
        (0.216, 0.057, 0.25),
    ]
    assert [(s.od, s.id, s.length) for s in string.sections] == table
    assert all(
        s.material.shear_modulus == 85.3e9 and s.material.density == 7800.0 for s in string.sections
    )
    assert [s.in_bha for s in string.sections] == [False, True, True, True]  # HWDP is "BHA 1"
    assert builtin_config().bit_radius == 0.108  # 8 1/2 in bit (ERRATA)


def test_strings_with_units_are_converted():
    data = with_change(("section", 0, "od"), "5.5 in")
    data["material"]["shear_modulus"] = "85300 MPa"
    data["operation"]["wob"] = "22.48 kip"
    data["operation"]["rpm"] = "10 rad/s"
    config = parse_config(data)
    assert config.string.sections[0].od == pytest.approx(0.1397)  # 5.5 in = 0.1397 m exactly
    assert config.string.sections[0].material.shear_modulus == pytest.approx(85.3e9)
    assert config.operation.wob == pytest.approx(22.48 * 4448.2216, rel=1e-6)  # 1 kip = 1000 lbf
    assert config.operation.rpm == pytest.approx(10 * 30 / 3.141592653589793)


def test_section_material_overrides_default():
    data = with_change(("section", 2, "material"), {"shear_modulus": 80e9})
    config = parse_config(data)
    assert config.string.sections[2].material.shear_modulus == 80e9
    assert config.string.sections[2].material.density == 7800.0  # the default's density


def test_bha_override():
    data = with_change(("section", 1, "bha"), False)
    assert parse_config(data).string.sections[1].in_bha is False


@pytest.mark.parametrize(
    ("path", "value", "key", "text"),
    [
        (("section", 0, "id"), 0.2, "section[0].id", "smaller than the outer diameter"),
        (("section", 0, "id"), 0.140, "section[0].id", "smaller than the outer diameter"),
        (("section", 0, "length"), 0.0, "section[0].length", "positive"),
        (("section", 0, "length"), -3.0, "section[0].length", "positive"),
        (("section", 1, "od"), "3 kg", "section[1].od", "not a length"),
        (("section", 1, "od"), "lots", "section[1].od", "cannot read"),
        (("section", 1, "kind"), "casing", "section[1].kind", "unknown section kind"),
        (("section", 1, "colour"), "red", "section[1].colour", "unknown key"),
        (("section", 1, "od"), _DELETE, "section[1].od", "missing"),
        (("material", "shear_modulus"), -1.0, "material.shear_modulus", "positive"),
        (("material", "density"), 0, "material.density", "positive"),
        (("discretization", "strategy"), "Z", "discretization.strategy", "unknown strategy"),
        (("discretization", "dp_elements"), 0, "discretization.dp_elements", ">= 1"),
        (("discretization", "bha_elements"), 30, "discretization.bha_elements", "rigid"),
        (("discretization", "elements"), 3, "discretization.elements", "unknown key"),
        (("operation", "wob"), "-5 kN", "operation.wob", "non-negative"),
        (("operation", "rpm"), 0, "operation.rpm", "positive"),
        (("bit_rock", "law"), "magic", "bit_rock.law", "unknown bit-rock law"),
        (("bit_rock", "a0"), -0.2, "bit_rock.a0", "must be > 0"),
        (("bit_rock", "a0"), _DELETE, "bit_rock.a0", "needs parameter"),
        (("bit_rock", "a9"), 1.0, "bit_rock.a9", "no parameter"),
        (("bit_rock", "speed_unit"), "rps", "bit_rock.speed_unit", "expected one of"),
        (("damping", "gamma"), 1.0, "damping.gamma", "unknown key"),
        (("colour",), "blue", "colour", "unknown key"),
    ],
)
def test_bad_values_name_the_key(path, value, key, text):
    with pytest.raises(ConfigError) as info:
        parse_config(with_change(path, value))
    assert info.value.key == key
    assert text in str(info.value)


def test_no_bit_and_bit_not_last():
    data = copy.deepcopy(BUILTIN)
    bit = data["section"].pop()
    with pytest.raises(ConfigError, match="no bit"):
        parse_config(data)
    data["section"].insert(1, bit)
    with pytest.raises(ConfigError, match="must be the last section") as info:
        parse_config(data)
    assert info.value.key == "section[1]"


def test_drill_pipe_below_bha_is_rejected():
    data = with_change(("section", 2, "kind"), "drill_pipe")
    with pytest.raises(ConfigError, match="lies below the BHA") as info:
        parse_config(data)
    assert info.value.key == "section[2].bha"


def test_malformed_toml_is_a_clear_error(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("[section\nkind = 'bit'\n")
    with pytest.raises(ConfigError, match="not valid TOML"):
        load_config(path)
    with pytest.raises(ConfigError, match="cannot read configuration file"):
        load_config(tmp_path / "missing.toml")


def test_damping_ratios():
    data = copy.deepcopy(BUILTIN)
    data["damping"] = {"ratios": [0.05, 0.05], "modes": [1, 3]}
    config = parse_config(data)
    assert config.damping.ratios == (0.05, 0.05) and config.damping.modes == (1, 3)
    data["damping"] = {"ratios": [0.05, 0.05], "alpha": 0.1}
    with pytest.raises(ConfigError, match="either alpha/beta or ratios"):
        parse_config(data)


# --- property-based: malformed configurations give a ConfigError, never a traceback -----------
scalars = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(-(10**6), 10**6),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=12),
    st.sampled_from(["5 in", "-3 m", "1e400 m", "85 GPa", "kN", "1/0", "nan m"]),
)
values = st.recursive(
    scalars,
    lambda inner: st.one_of(
        st.lists(inner, max_size=3), st.dictionaries(st.text(max_size=6), inner, max_size=3)
    ),
    max_leaves=6,
)


def _paths(data, prefix=()):
    if isinstance(data, dict):
        for key, value in data.items():
            yield prefix + (key,)
            yield from _paths(value, prefix + (key,))
    elif isinstance(data, list):
        for i, value in enumerate(data):
            yield prefix + (i,)
            yield from _paths(value, prefix + (i,))


ALL_PATHS = list(_paths(BUILTIN))


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.tuples(st.sampled_from(ALL_PATHS), values), min_size=1, max_size=3))
def test_malformed_configurations_raise_config_error(changes):
    data = copy.deepcopy(BUILTIN)
    for path, value in changes:
        target = data
        try:
            for key in path[:-1]:
                target = target[key]
            target[path[-1]] = value
        except (KeyError, IndexError, TypeError):
            continue
    try:
        parse_config(data).model()  # what validates must also discretize, or say why not
    except TorsioError as exc:
        assert str(exc)  # a message, naming what is wrong


@settings(max_examples=200, deadline=None)
@given(st.text(max_size=200))
def test_arbitrary_text_never_crashes_the_parser(text):
    try:
        parse_config_text(text)
    except TorsioError:
        pass
