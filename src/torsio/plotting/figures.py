"""Figure helpers shared by torsio's plots: :func:`pyplot` and :func:`save_figure`.

matplotlib is imported only when a plot is asked for; without it, :func:`pyplot`
raises a clear error naming the ``[plot]`` extra.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Any

from torsio.errors import TorsioError
from torsio.output_files import atomic_output, save_figure_file

__all__ = ["pyplot", "save_figure"]


def pyplot() -> Any:
    """``matplotlib.pyplot``, with the Agg backend when there is no display.

    Raises
    ------
    TorsioError
        If matplotlib is not installed.
    """
    try:
        import matplotlib
    except ImportError:
        raise TorsioError(
            "plotting needs matplotlib, which is not installed; "
            "install it with: pip install 'torsio[plot]'"
        ) from None
    headless = sys.platform.startswith("linux") and not (
        os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
    )
    if headless and "MPLBACKEND" not in os.environ and "matplotlib.pyplot" not in sys.modules:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(
    figure: Any, path: str | os.PathLike[str], dpi: float = 100.0, palette: bool = False
) -> Path:
    """Save a figure (creating its folder), close it and return the path written.

    The file is written whole or not at all (:mod:`torsio.output_files`; a failure is
    an :class:`~torsio.errors.OutputError` naming the path).

    Parameters
    ----------
    figure : matplotlib Figure
    path : str or path-like
        File to write; the format follows the suffix (``.png``, ``.svg``, ...).
    dpi : float
        Resolution of raster formats [dots per inch].
    palette : bool
        For PNG: store at most 256 colours (an indexed PNG, typically a third of
        the size; line plots look the same).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> figure = pyplot().figure(figsize=(2, 2))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = save_figure(figure, pathlib.Path(folder) / "sub" / "empty.png", palette=True)
    ...     path.stat().st_size > 0
    True
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    if palette and path.suffix.lower() == ".png":
        from io import BytesIO

        from PIL import Image  # a dependency of matplotlib

        buffer = BytesIO()
        figure.savefig(buffer, format="png", dpi=dpi, bbox_inches="tight")
        buffer.seek(0)
        with Image.open(buffer) as image:
            indexed = image.convert("RGB").quantize(colors=256, dither=Image.Dither.NONE)
            with atomic_output(path, binary=True) as stream:  # whole or not at all
                indexed.save(stream, format="PNG", optimize=True)
    else:
        path = save_figure_file(figure, path, dpi=dpi, bbox_inches="tight")
    pyplot().close(figure)
    return path


def _ticker() -> Any:
    pyplot()
    import matplotlib.ticker

    return matplotlib.ticker


def _axes(ax: Any) -> Any:
    if ax is not None:
        return ax
    _, ax = pyplot().subplots()
    return ax
