"""Every file torsio writes, written whole or not at all, and the saved results read back.

:func:`atomic_output` opens a temporary file beside the target (same folder, so the
rename stays on one file system), hands it to the writer, flushes it to the disk
(``fsync``) and renames it over the target (:func:`os.replace`). A write that fails (a
full disk, a quota, an I/O error) or is interrupted removes the temporary file and leaves
the target as it was: never a truncated file that looks complete. The failure is an
:class:`~torsio.errors.OutputError` naming the path and the system's reason.

A saved result (a severity map, a transient run) is a numpy ``.npz`` archive of its arrays
with its other data as a JSON string ``metadata`` (:func:`write_npz`), or JSON
(:func:`read_saved` reads both).

Examples
--------
>>> import pathlib, tempfile
>>> with tempfile.TemporaryDirectory() as folder:
...     path = write_text(pathlib.Path(folder) / "note.txt", "rotary speed 60 rpm\\n")
...     print(path.read_text(), end="")
...     sorted(p.name for p in path.parent.iterdir())
rotary speed 60 rpm
['note.txt']
"""

from __future__ import annotations

import contextlib
import json
import os
import uuid
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any

from torsio.errors import ConfigError, OutputError

__all__ = [
    "atomic_output",
    "read_saved",
    "save_columns",
    "save_figure_file",
    "write_bytes",
    "write_npz",
    "write_text",
]


@contextlib.contextmanager
def atomic_output(path: str | os.PathLike[str], binary: bool = False) -> Iterator[IO[Any]]:
    """A stream whose content becomes ``path`` only once it is all on the disk.

    Parameters
    ----------
    path : str or path-like
        The file to write (its folder must exist).
    binary : bool
        A bytes stream; else text in UTF-8 with newlines as written (``newline=""``,
        what :mod:`csv` needs).

    Raises
    ------
    OutputError
        The file could not be written (the OS's reason named); the target is unchanged
        and no temporary file is left.
    """
    target = Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    temporary = folder / f".{target.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp"
    try:
        mode = "xb" if binary else "x"
        encoding = None if binary else "utf-8"
        with open(temporary, mode, encoding=encoding, newline=None if binary else "") as stream:
            yield stream
            stream.flush()
            os.fsync(stream.fileno())
        os.replace(temporary, target)
    except OSError as exc:
        _remove(temporary)
        raise OutputError(target, exc.strerror or str(exc)) from exc
    except BaseException:
        _remove(temporary)
        raise
    _sync_folder(folder)


def write_text(path: str | os.PathLike[str], text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically (:func:`atomic_output`); the path."""
    with atomic_output(path) as stream:
        stream.write(text)
    return Path(path)


def write_bytes(path: str | os.PathLike[str], data: bytes) -> Path:
    """Write ``data`` to ``path`` atomically (:func:`atomic_output`); the path."""
    with atomic_output(path, binary=True) as stream:
        stream.write(data)
    return Path(path)


def save_columns(path: str | os.PathLike[str], names: list[str], columns: list[Any]) -> Path:
    """Signals as CSV, atomically: a header of ``names``, then one row per sample of the
    equally long ``columns`` (10 significant digits). Returns the path written."""
    import numpy as np

    with atomic_output(path) as stream:
        np.savetxt(stream, np.column_stack(columns), delimiter=",", header=",".join(names),
                   comments="", fmt="%.10g")  # fmt: skip
    return Path(path)


def save_figure_file(figure: Any, path: str | os.PathLike[str], **savefig: Any) -> Path:
    """A matplotlib figure written atomically to ``path`` in the format of its suffix
    (``.png`` added when it has none, as matplotlib does); ``savefig``: matplotlib's
    options (``dpi``, ...). Returns the path written."""
    target = Path(path)
    if not target.suffix:
        target = target.with_name(target.name + ".png")
    kind = target.suffix.lower().lstrip(".")
    with atomic_output(target, binary=True) as stream:
        figure.savefig(stream, format=kind, **savefig)
    return target


def write_npz(
    path: str | os.PathLike[str], metadata: dict[str, Any], arrays: dict[str, Any]
) -> Path:
    """A compressed ``.npz`` archive of ``arrays`` and the JSON string ``metadata``,
    written atomically; numpy numbers in ``metadata`` are written as Python's. Returns the
    path written."""
    import numpy as np

    text = json.dumps(metadata, default=_plain)
    with atomic_output(path, binary=True) as stream:
        np.savez_compressed(stream, metadata=np.array(text), **arrays)
    return Path(path)


def read_saved(path: str | os.PathLike[str], what: str) -> tuple[dict[str, Any], dict[str, Any]]:
    """The data of a saved ``what`` (e.g. ``"severity map"``): of an ``.npz`` archive
    (:func:`write_npz`) its metadata and its arrays; of any other file its JSON and no
    arrays. A file that cannot be read, or is not such a file, is a ConfigError naming
    ``path``."""
    import numpy as np

    path = Path(path)
    try:
        if path.suffix != ".npz":
            return json.loads(path.read_text(encoding="utf-8")), {}
        archive = np.load(path, allow_pickle=False)
        if not isinstance(archive, np.lib.npyio.NpzFile):
            raise ValueError(f"an .npy array, not an .npz archive of a {what}")
        with archive:
            arrays = {key: archive[key] for key in archive.files if key != "metadata"}
            metadata = json.loads(str(archive["metadata"]))
        if not isinstance(metadata, dict):
            raise ValueError(f"its metadata is a JSON {type(metadata).__name__}, not an object")
        return metadata, arrays
    except OSError as exc:
        raise ConfigError(
            "path", f"cannot read {what} file {str(path)!r}: {exc.strerror or exc}"
        ) from None
    except (ValueError, KeyError, EOFError, RecursionError, zipfile.BadZipFile) as exc:
        raise ConfigError("path", f"{str(path)!r} is not a saved {what} ({exc})") from None


def _plain(value: Any) -> Any:
    """A numpy number or array as JSON can write it."""
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"{type(value).__name__} is not JSON serializable")


def _remove(path: Path) -> None:
    with contextlib.suppress(OSError):
        path.unlink(missing_ok=True)


def _sync_folder(folder: Path) -> None:
    """The rename on the disk too (where the platform lets a folder be synced)."""
    try:
        handle = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(handle)
    except OSError:
        pass
    finally:
        os.close(handle)
