"""load_map refuses what is not a saved severity map with a ConfigError, never a traceback."""

from __future__ import annotations

import json

import numpy as np
import pytest

from torsio.analysis.map_results import load_map
from torsio.errors import ConfigError

BAD_JSON = {
    "a list": "[1, 2]",
    "no severity": json.dumps({"wob": [1e5], "rpm": [60.0]}),
    "deeply nested": "[" * 100_000 + "]" * 100_000,
    "not JSON": "severity = 1",
}


@pytest.mark.parametrize("text", BAD_JSON.values(), ids=list(BAD_JSON))
def test_bad_json_map_files(tmp_path, text):
    path = tmp_path / "map.json"
    path.write_text(text)
    with pytest.raises(ConfigError, match="map"):
        load_map(path)


def test_truncated_npz(tmp_path):
    path = tmp_path / "map.npz"
    np.savez(path, severity=np.zeros((2, 2)))
    path.write_bytes(path.read_bytes()[:40])
    with pytest.raises(ConfigError):
        load_map(path)


def test_npy_renamed_npz(tmp_path):
    npy = tmp_path / "map.npy"
    np.save(npy, np.zeros(3))
    path = tmp_path / "map.npz"
    npy.rename(path)
    with pytest.raises(ConfigError):
        load_map(path)


def test_messages_name_the_cause(tmp_path):
    """Each refusal says what is wrong with the file, not only that it is refused."""
    cases = {
        "list.json": ("[1, 2]", "expected a JSON object"),
        "nosev.json": (BAD_JSON["no severity"], "severity"),
        "deep.json": (BAD_JSON["deeply nested"], "map"),
    }
    for name, (text, fragment) in cases.items():
        (tmp_path / name).write_text(text)
        with pytest.raises(ConfigError) as caught:
            load_map(tmp_path / name)
        assert name in str(caught.value) and fragment in str(caught.value), str(caught.value)


@pytest.fixture(scope="module")
def small_map():
    from torsio.analysis.maps import severity_map
    from torsio.examples import builtin_config

    system = builtin_config().system(strategy="A")
    return severity_map(system, wob=[50e3, 150e3], rpm=[60.0, 100.0], refine=0)


@pytest.mark.parametrize("suffix", [".json", ".npz"])
def test_complete_flag_with_no_point_done(tmp_path, small_map, suffix):
    """A file that says complete but holds no computed point is refused, naming 'complete'."""
    import attrs

    empty = attrs.evolve(
        small_map,
        severity=np.full_like(small_map.severity, np.nan),
        done=np.zeros_like(small_map.done),
    )
    path = empty.save(tmp_path / f"map{suffix}")
    assert load_map(small_map.save(tmp_path / f"good{suffix}")).complete  # the format itself
    with pytest.raises(ConfigError, match=r"complete: the map says it is complete but 4 of 4"):
        load_map(path)
