"""The sign and scale convention of mode shapes, shared by lumped and continuum modes."""

from __future__ import annotations

import numpy as np

__all__ = ["normalize_shape"]


def normalize_shape(shape: np.ndarray) -> np.ndarray:
    """Scale a shape (or each column of an array of shapes) to peak magnitude 1, positive at
    the first non-zero entry (the node nearest the surface).

    The sign convention is robust for high modes, whose peaks of either sign are nearly
    equal: a mode shape leaves the fixed top with a non-zero slope, so its first node below
    the surface is never zero.

    >>> normalize_shape(np.array([0.0, -0.5, 2.0, 1.0]))
    array([-0.  ,  0.25, -1.  , -0.5 ])
    """
    shape = np.asarray(shape, dtype=float)
    flat = shape.reshape(shape.shape[0], -1)
    peaks = np.max(np.abs(flat), axis=0)
    scale = np.where(peaks > 0, peaks, 1.0)
    nonzero = np.abs(flat) > 1e-12 * scale
    first = flat[np.argmax(nonzero, axis=0), np.arange(flat.shape[1])]
    signs = np.where(first < 0, -1.0, 1.0)
    return (flat * (signs / scale)).reshape(shape.shape)
