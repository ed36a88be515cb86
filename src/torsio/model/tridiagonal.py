"""Chains as band arrays: whether a matrix is tridiagonal, its bands, and its product.

A chain's [I], [K] and [C] couple neighbouring nodes only; the compiled engines and the
right-hand side take them as (diagonal, upper) arrays of length n, ``upper[i]`` coupling
nodes i and i+1 and ``upper[-1] = 0``.

Examples
--------
>>> matrix = np.array([[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]])
>>> is_tridiagonal(matrix), [b.tolist() for b in tridiagonal_bands(matrix, "stiffness")]
(True, [[2.0, 2.0, 1.0], [-1.0, -1.0, 0.0]])
>>> tridiagonal_matvec(*tridiagonal_bands(matrix, "stiffness"), np.ones(3)).tolist()
[1.0, 0.0, 0.0]
"""

from __future__ import annotations

import numpy as np

from torsio.errors import ConfigError

__all__ = ["is_tridiagonal", "tridiagonal_bands", "tridiagonal_matvec"]


def is_tridiagonal(matrix: np.ndarray) -> bool:
    """Whether ``matrix`` couples neighbouring nodes only (zero beyond the first diagonals)."""
    return not (np.count_nonzero(np.triu(matrix, 2)) or np.count_nonzero(np.tril(matrix, -2)))


def tridiagonal_bands(matrix: np.ndarray, key: str) -> tuple[np.ndarray, np.ndarray]:
    """(diagonal, upper) of a symmetric tridiagonal matrix; upper[-1] = 0.

    A clear error naming ``key`` if the matrix couples nodes that are not neighbours.
    """
    matrix = np.asarray(matrix, dtype=float)
    if not is_tridiagonal(matrix):
        raise ConfigError(
            key, "expected a chain (tridiagonal matrix); this model couples non-neighbour nodes"
        )
    upper = np.zeros(matrix.shape[0])
    upper[:-1] = np.diag(matrix, 1)
    return np.diag(matrix).copy(), upper


def tridiagonal_matvec(diag: np.ndarray, upper: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The product of the symmetric tridiagonal matrix (``diag``, ``upper``) with ``x``."""
    out = diag * x
    out[:-1] += upper[:-1] * x[1:]
    out[1:] += upper[:-1] * x[:-1]
    return out
