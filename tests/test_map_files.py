"""load_map refuses what is not a saved severity map with a ConfigError, never a traceback."""

from __future__ import annotations

import json

import numpy as np
import pytest

from torsio.analysis.maps import load_map
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
