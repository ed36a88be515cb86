"""Read-only float arrays: the converter of the frozen classes that hold arrays, and the
checks of their values (:func:`check_values`, :func:`check_count`) that name the key.

Examples
--------
>>> vector = read_only_vector([[1, 2], [3, 4]])
>>> vector, vector.flags.writeable
(array([1., 2., 3., 4.]), False)
>>> read_only_vector(None).size
0
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from torsio.errors import ConfigError

__all__ = ["check_count", "check_values", "read_only", "read_only_vector"]


def read_only(values: Any) -> NDArray[np.float64]:
    """A new float array of ``values`` (its shape kept) that cannot be written to."""
    array = np.array(values, dtype=float)
    array.setflags(write=False)
    return array


def read_only_vector(values: Any) -> NDArray[np.float64]:
    """:func:`read_only` flattened to one dimension; ``None`` gives an empty vector."""
    return read_only(np.reshape(np.asarray(() if values is None else values, dtype=float), -1))


def check_count(key: str, values: NDArray[np.float64], size: int) -> None:
    """Raise a ConfigError naming ``key`` unless ``values`` has ``size`` values, one per node."""
    if values.size != size:
        raise ConfigError(key, f"has {values.size} values; expected {size}, one per node")


def check_values(key: str, values: NDArray[np.float64], allow_zero: bool) -> None:
    """Raise a ConfigError naming ``key[i]`` at the first value that is not finite and
    positive (non-negative with ``allow_zero``)."""
    bad = ~np.isfinite(values) | ((values < 0) if allow_zero else (values <= 0))
    if bad.any():
        i = int(np.argmax(bad))
        expected = "non-negative" if allow_zero else "positive"
        raise ConfigError(f"{key}[{i}]", f"expected a {expected} finite value, got {values[i]!r}")
