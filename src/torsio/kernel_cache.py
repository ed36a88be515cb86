"""Where numba keeps torsio's compiled kernels, and the note printed before the first compile.

numba compiles the batch engine once and caches the machine code. torsio points that
cache to the user's cache folder, never into the installed package (a cache inside
``site-packages/torsio`` outlives ``pip uninstall`` and shadows a later install):

- ``$NUMBA_CACHE_DIR`` when the user set it (torsio leaves it alone);
- else ``$TORSIO_CACHE_DIR/numba``, ``$XDG_CACHE_HOME/torsio/numba``, or the platform's
  cache folder: ``~/.cache/torsio/numba`` (Linux), ``~/Library/Caches/torsio/numba``
  (macOS), ``%LOCALAPPDATA%\\torsio\\Cache\\numba`` (Windows); in it, one folder per
  state of the kernel sources (``kernels-<key>``, the key a hash of torsio's and numba's
  versions and of every kernel source file's size and time: ``solvers/``, ``axial/`` and
  ``physics/laws.py``).

numba checks a cached function against its own source file only, not against the files
of the functions it calls and compiles in (the kernel's cycle tracker, the chain's
forces): after an update of one of those, it would load the old machine code. A folder
per state of all the sources can never hold stale code; folders not written to for
:data:`STALE_DAYS` days are removed.

The first process that compiles prints one line to stderr (never to stdout, so
``--json`` output stays clean): ``compiling the batch engine once (20 to 60 s); later
runs start at once``.

Examples
--------
>>> import os
>>> env = {"XDG_CACHE_HOME": "/tmp/cache", "HOME": "/home/me"}
>>> str(user_cache_dir(env, platform="linux"))
'/tmp/cache/torsio'
>>> str(user_cache_dir({"HOME": "/home/me"}, platform="linux"))
'/home/me/.cache/torsio'
"""

from __future__ import annotations

import atexit
import hashlib
import os
import shutil
import sys
import time
from collections.abc import Mapping
from pathlib import Path
from typing import Any, TextIO

#: Seconds the first compile of the engine takes on a 2-core machine, by the processor
#: (numba 0.68, Python 3.11: 15-25 s on 2026-12-01's, 48 s for the first map and 65 s for
#: the first report on 2026-12-05's AMD EPYC 2.0 GHz); printed in the first-run note.
FIRST_COMPILE_SECONDS = "20 to 60"

#: Days after which a cache folder of other kernel sources (an older version, another
#: installation) that nothing wrote to is removed.
STALE_DAYS = 30

_ANNOUNCED = "TORSIO_COMPILE_ANNOUNCED"  # set once the note is printed (seen by child processes)


def user_cache_dir(environ: Mapping[str, str] | None = None, platform: str | None = None) -> Path:
    """torsio's folder in the user's cache (see the module docstring for the order).

    Parameters
    ----------
    environ : mapping, optional
        Environment variables (default: ``os.environ``).
    platform : str, optional
        ``sys.platform`` value (default: this machine's).
    """
    env = os.environ if environ is None else environ
    platform = sys.platform if platform is None else platform
    if env.get("TORSIO_CACHE_DIR"):
        return Path(env["TORSIO_CACHE_DIR"])
    home = Path(env.get("HOME") or env.get("USERPROFILE") or Path.home())
    if platform.startswith("win"):
        base = env.get("LOCALAPPDATA") or str(home / "AppData" / "Local")
        return Path(base) / "torsio" / "Cache"
    if platform == "darwin":
        return home / "Library" / "Caches" / "torsio"
    if env.get("XDG_CACHE_HOME"):
        return Path(env["XDG_CACHE_HOME"]) / "torsio"
    return home / ".cache" / "torsio"


def numba_cache_dir() -> Path:
    """The folder numba caches torsio's kernels in: ``$NUMBA_CACHE_DIR`` if set, else ours."""
    if os.environ.get("NUMBA_CACHE_DIR"):
        return Path(os.environ["NUMBA_CACHE_DIR"])
    return user_cache_dir() / "numba"


def use_user_cache_dir() -> None:
    """Point numba's cache to :func:`numba_cache_dir` unless the user chose a folder.

    Called before any kernel module of :mod:`torsio.solvers` is imported, because
    numba fixes the cache location of a function when it is decorated. Without numba
    this does nothing.
    """
    try:
        import numba
    except ImportError:  # pragma: no cover - numba is a dependency; the numpy engine remains
        return
    config: Any = numba.config
    if config.CACHE_DIR:  # NUMBA_CACHE_DIR, or set by the user in this process
        return
    folder = _kernels_folder()
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError:  # read-only home: numba falls back to its own locations
        return
    config.CACHE_DIR = str(folder)
    stale = time.time() - STALE_DAYS * 86400.0
    for old in folder.parent.glob("kernels-*"):  # earlier states, other installations
        try:
            if old != folder and old.stat().st_mtime < stale:
                shutil.rmtree(old, ignore_errors=True)
        except OSError:  # pragma: no cover - removed meanwhile by another process
            pass


def _kernels_folder() -> Path:
    """The cache folder of the current state of the kernel sources."""
    return numba_cache_dir() / f"kernels-{_sources_key()}"


def kernel_sources() -> list[Path]:
    """The files numba compiles torsio's kernels from (and the constants they read):
    ``solvers/``, ``axial/`` and ``physics/laws.py``."""
    import torsio

    package = Path(torsio.__file__).resolve().parent
    sources = [
        *sorted((package / "solvers").glob("*.py")),
        *sorted((package / "axial").glob("*.py")),
    ]
    sources.append(package / "physics" / "laws.py")
    return sources


def _sources_key() -> str:
    """A hash of torsio's, Python's and numba's versions and the kernel sources' stamps."""
    import torsio

    key = hashlib.sha1()
    key.update(f"{torsio.__version__} {sys.version} {sys.executable}".encode())
    try:
        import numba

        key.update(numba.__version__.encode())
    except ImportError:  # pragma: no cover
        pass
    for source in kernel_sources():
        try:
            stat = source.stat()
        except OSError:
            continue
        key.update(f"{source} {stat.st_mtime_ns} {stat.st_size}".encode())
    return key.hexdigest()[:16]


def _stamp_path() -> Path:
    """A file whose presence says: these sources were compiled into the cache."""
    folder = Path(os.environ.get("NUMBA_CACHE_DIR") or _kernels_folder())
    return folder / f"torsio-kernels-{_sources_key()}.stamp"


def kernels_cached() -> bool:
    """Whether the batch engine of this installation was compiled into the cache before."""
    try:
        return _stamp_path().exists()
    except OSError:  # pragma: no cover
        return False


def _mark_cached() -> None:
    engines = (
        "torsio.solvers.batch",
        "torsio.solvers.single_run",
        "torsio.solvers.wave_march",
        "torsio.axial.kernel",
        "torsio.axial.wave_kernel",
    )
    if "numba" not in sys.modules or not any(name in sys.modules for name in engines):
        return  # nothing was compiled (e.g. the process stopped on an error before a run)
    try:
        path = _stamp_path()
        path.parent.mkdir(parents=True, exist_ok=True)
        path.touch()
    except OSError:  # pragma: no cover - a read-only cache: the note shows again, no harm
        pass


def announce_first_compile(stream: TextIO | Any = None) -> bool:
    """Print the first-compile note to stderr once, if the kernels are not cached yet.

    Returns True when the note was printed. The note is printed at most once per
    process tree (worker processes inherit the marker); the cache is marked compiled
    when the process that used the engine exits.
    """
    if os.environ.get(_ANNOUNCED) or kernels_cached():
        return False
    try:
        import importlib.util

        if importlib.util.find_spec("numba") is None:  # pragma: no cover
            return False
    except (ImportError, ValueError):  # pragma: no cover
        return False
    os.environ[_ANNOUNCED] = "1"
    atexit.register(_mark_cached)
    print(
        f"torsio: compiling the batch engine once ({FIRST_COMPILE_SECONDS} s); "
        "later runs start at once",
        file=sys.stderr if stream is None else stream,
        flush=True,
    )
    return True
