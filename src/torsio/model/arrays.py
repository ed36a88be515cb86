"""Read-only float arrays: the converter of the frozen classes that hold arrays.

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

__all__ = ["read_only", "read_only_vector"]


def read_only(values: Any) -> NDArray[np.float64]:
    """A new float array of ``values`` (its shape kept) that cannot be written to."""
    array = np.array(values, dtype=float)
    array.setflags(write=False)
    return array


def read_only_vector(values: Any) -> NDArray[np.float64]:
    """:func:`read_only` flattened to one dimension; ``None`` gives an empty vector."""
    return read_only(np.reshape(np.asarray(() if values is None else values, dtype=float), -1))
