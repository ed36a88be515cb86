"""Map files from outside: load_map refuses what is not a consistent saved map (issue 12).

Each case damages a real saved map (or writes something else under its name) and
must give a ConfigError naming the file and the key, never a traceback or a map
that says more than it holds.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from torsio.analysis.maps import SeverityMap, load_map, severity_map
from torsio.errors import ConfigError
from torsio.physics.system import System, builtin_config


@pytest.fixture(scope="module")
def saved(tmp_path_factory) -> dict:
    system = System.from_config(builtin_config(), strategy="A")
    result = severity_map(system, wob=[50e3, 150e3], rpm=[60.0, 120.0], refine=0)
    folder = tmp_path_factory.mktemp("maps")
    json_path = result.save(folder / "m.json")
    npz_path = result.save(folder / "m.npz")
    return {"map": result, "json": json_path, "npz": npz_path}


def test_a_saved_map_loads_back(saved) -> None:
    for key in ("json", "npz"):
        loaded = load_map(saved[key])
        # the map as computed (the round trip of save/load_map)
        np.testing.assert_array_equal(loaded.severity, saved["map"].severity)
        assert loaded.complete


def _json(saved) -> dict:
    return json.loads(saved["json"].read_text())


def _edit(**changes):
    def edit(data: dict) -> dict:
        data.update(changes)
        return data

    return edit


def _drop(key: str):
    def edit(data: dict) -> dict:
        del data[key]
        return data

    return edit


def _none_done(data: dict) -> dict:
    data["done"] = [[False] * len(data["wob"]) for _ in data["rpm"]]
    data["severity"] = [[None] * len(data["wob"]) for _ in data["rpm"]]
    return data  # still "complete": true


# (id, edit of the saved JSON object, key named, fragment)
BAD_JSON = [
    ("missing severity", _drop("severity"), "severity", "missing key"),
    ("missing done", _drop("done"), "done", "missing key"),
    ("complete with no point done", _none_done, "complete", "not done"),
    ("severity of the wrong shape", _edit(severity=[[0.1, 0.2, 0.3]]), "severity", "shape"),
    ("ragged severity", _edit(severity=[[0.1], [0.2, 0.3]]), "severity", "regular array"),
    ("text in steps", _edit(steps=[["a", "b"], ["c", "d"]]), "steps", "regular array"),
    ("unknown critical status", _edit(critical_status=["maybe", "none"]), "critical_status", ""),
    ("decreasing wob", _edit(wob=[150e3, 50e3]), "wob", "increasing"),
    ("threshold as text", _edit(threshold="0.8"), "threshold", "number"),
    ("complete as text", _edit(complete="yes"), "complete", "true or false"),
    (
        "done point without severity",
        _edit(severity=[[None, None], [None, None]]),
        "severity",
        "no severity",
    ),
]


@pytest.mark.parametrize(
    ("edit", "key", "fragment"), [c[1:] for c in BAD_JSON], ids=[c[0] for c in BAD_JSON]
)
def test_damaged_json_map(saved, tmp_path, edit, key, fragment) -> None:
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(edit(_json(saved))))
    with pytest.raises(ConfigError) as caught:
        load_map(path)
    message = str(caught.value)
    assert "bad.json" in message and key in message and fragment in message, message


def _truncated_npz(saved, path) -> None:
    data = saved["npz"].read_bytes()
    path.write_bytes(data[: len(data) // 2])


def _npy_renamed(saved, path) -> None:
    with open(path, "wb") as stream:
        np.save(stream, np.arange(4.0))


def _json_list(saved, path) -> None:
    path.write_text("[1, 2, 3]")


def _deeply_nested(saved, path) -> None:
    path.write_text("[" * 200_000 + "]" * 200_000)


def _not_json(saved, path) -> None:
    path.write_bytes(b"\xff\xfe not text")


def _empty(saved, path) -> None:
    path.write_bytes(b"")


BAD_FILES = [
    ("truncated npz", _truncated_npz, "m.npz"),
    ("npy renamed npz", _npy_renamed, "m.npz"),
    ("JSON list", _json_list, "m.json"),
    ("deeply nested JSON", _deeply_nested, "m.json"),
    ("binary garbage", _not_json, "m.json"),
    ("empty npz", _empty, "m.npz"),
]


@pytest.mark.parametrize(
    ("write", "name"), [c[1:] for c in BAD_FILES], ids=[c[0] for c in BAD_FILES]
)
def test_files_that_are_not_maps(saved, tmp_path, write, name) -> None:
    path = tmp_path / name
    write(saved, path)
    with pytest.raises(ConfigError, match=name.replace(".", r"\.")):
        load_map(path)


def test_incomplete_map_keeps_its_points(saved, tmp_path) -> None:
    """A partial map (complete = false) with some points done loads, marked incomplete."""
    data = _json(saved)
    data["complete"] = False
    data["done"][1] = [False, False]
    data["severity"][1] = [None, None]
    path = tmp_path / "m.partial.json"
    path.write_text(json.dumps(data))
    loaded = load_map(path)
    assert isinstance(loaded, SeverityMap) and not loaded.complete
    assert loaded.done.sum() == 2
