"""Where numba keeps torsio's compiled kernels, and the notes printed while numba compiles.

numba compiles the batch engine once and caches the machine code. torsio points that
cache to the user's cache folder, never into the installed package (a cache inside
``site-packages/torsio`` outlives ``pip uninstall`` and shadows a later install):

- ``$NUMBA_CACHE_DIR`` when the user set it (torsio leaves it alone);
- else ``$TORSIO_CACHE_DIR/numba``, ``$XDG_CACHE_HOME/torsio/numba``, or the platform's
  cache folder: ``~/.cache/torsio/numba`` (Linux), ``~/Library/Caches/torsio/numba``
  (macOS), ``%LOCALAPPDATA%\\torsio\\Cache\\numba`` (Windows); in it, one folder per
  state of the kernel sources (``kernels-<key>``, the key a hash of torsio's, Python's and
  numba's versions, of the environment (``sys.prefix``: not the interpreter's name, so
  ``python`` and ``python3`` share it) and of the contents of every kernel source file:
  ``solvers/``, the RGD bit's step and history (``axial/bit_step.py``, ``axial/history.py``),
  ``physics/laws.py`` and ``physics/top_drive_boundary.py``), and in that a folder per
  subpackage (``solvers``, ``axial``, ``physics``).

Neither depends on where the package is installed: a regular install (``pip install .``)
and an editable one (``pip install -e .``, the README's second command) of the same
sources load each other's kernels (numba's own locator would file them under a hash of
the installed folder's path).

numba checks a cached function against its own source file only, not against the files
of the functions it calls and compiles in (the kernel's cycle tracker, the chain's
forces): after an update of one of those, it would load the old machine code. A folder
per state of all the sources can never hold stale code; folders not written to for
:data:`STALE_DAYS` days are removed.

While numba compiles (a cache miss: the first run after an install or an update, or a
law compiled for the first time), :func:`watch_compiles` says so on stderr (never on
stdout, so ``--json`` output stays clean): ``compiling <kernel> (<what>) with numba, once:
about N s on a 2 GHz core; later runs load it at once`` as an entry point of
:data:`COMPILE_ESTIMATES` starts (any other compile, a law's, after :data:`NOTE_DELAY`
seconds, so that one that ends sooner says nothing), then ``still compiling <kernel> (N
s)`` every :data:`NOTE_INTERVAL` seconds and ``compiled <kernel> in N s`` at the end, so
that no command is silent for longer while it compiles. A kernel loaded from the cache
takes tens of milliseconds and prints nothing.

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

import functools
import hashlib
import os
import shutil
import sys
import threading
import time
from collections.abc import Mapping
from pathlib import Path
from typing import Any, TextIO

#: The compiled entry points, with what each is and the CPU seconds of its first compile
#: (numba 0.68.1, Python 3.11, one core of a 2-core AMD EPYC 2.0 GHz, 2026-12-06;
#: ``python benchmarks/cold_start.py --functions``), printed as its note's estimate when
#: it starts. A kernel that another compiles with it (the lumped step loop within the
#: batch loop of a first map) prints its own note as well.
COMPILE_ESTIMATES: dict[str, tuple[str, float]] = {
    "torsio.solvers.rodas.advance": ("the lumped engine's step loop", 15.0),
    "torsio.solvers.rodas_kernels._serial": ("the lumped engine's batch loop", 4.0),
    "torsio.solvers.characteristics._march": ("the wave model's stepping", 6.0),
    "torsio.solvers.axial_kernel.march": ("the axial-torsional chain's stepping", 4.0),
    "torsio.solvers.axial_wave_kernel.march": ("the axial-torsional wave model's stepping", 3.0),
}

#: The estimate of any other compile (a law's functions, a plugin's).
OTHER_COMPILE = "seconds"

#: Seconds a compile runs before its note is printed (a small law compiles in less).
NOTE_DELAY = 2.0

#: Seconds between two "still compiling" lines.
NOTE_INTERVAL = 4.0

#: Days after which a cache folder of other kernel sources (an older version, another
#: installation) that nothing wrote to is removed.
STALE_DAYS = 30


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

    Called by :mod:`torsio.solvers.compiled` before any kernel is decorated, because
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
    _locate_by_content(folder)
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
    ``solvers/``, ``axial/bit_step.py`` and ``axial/history.py`` (the RGD bit's part of a
    step), ``physics/laws.py`` and ``physics/top_drive_boundary.py``."""
    package = _package()
    sources = sorted((package / "solvers").glob("*.py"))
    sources += [package / "axial" / "bit_step.py", package / "axial" / "history.py"]
    sources.append(package / "physics" / "laws.py")
    sources.append(package / "physics" / "top_drive_boundary.py")  # the controller's evaluation
    return sources


def _sources_key() -> str:
    """A hash of torsio's, Python's and numba's versions, of the environment's prefix and of
    the kernel sources' contents (not their paths or times: a regular and an editable
    install of the same sources share the folder)."""
    import torsio

    key = hashlib.sha1()
    # the environment (its prefix), not the interpreter's name: python, python3 and
    # python3.11 of one virtualenv share the folder (pip's scripts start with python3)
    key.update(f"{torsio.__version__} {sys.version} {sys.prefix}".encode())
    try:
        import numba

        key.update(numba.__version__.encode())
    except ImportError:  # pragma: no cover
        pass
    package = _package()
    for source in kernel_sources():
        try:
            digest = _content_hash(str(source))
        except OSError:
            continue
        key.update(f"{source.relative_to(package).as_posix()} {digest}".encode())
    return key.hexdigest()[:16]


def _package() -> Path:
    """The folder of the torsio package in use (installed, or the sources of an editable one)."""
    import torsio

    return Path(torsio.__file__).resolve().parent


def _content_hash(path: str) -> str:
    """SHA-256 of a file's bytes, read once per state of the file (its time and size)."""
    stat = os.stat(path)
    return _hash_of(path, stat.st_mtime_ns, stat.st_size)


@functools.cache
def _hash_of(path: str, mtime_ns: int, size: int) -> str:
    """:func:`_content_hash` of the file's state ``(mtime_ns, size)``."""
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def _locate_by_content(folder: Path) -> None:
    """Make numba cache torsio's compiled functions in ``folder``/<subpackage>, checked
    against their files' contents.

    numba's own locator files a function under a hash of its source folder's absolute path
    (``site-packages/torsio/solvers`` after ``pip install .``, ``src/torsio/solvers`` after
    ``pip install -e .``), so the README's second command would compile every kernel again.
    This locator, put first in numba's list, files torsio's functions by their place in the
    package; the other packages' functions keep numba's locators.
    """
    from numba.core import caching

    impl: Any = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl", None)
    base: Any = getattr(caching, "_CacheLocator", None)
    if impl is None or base is None:  # pragma: no cover - a numba without these internals
        return
    classes = impl._locator_classes
    if not any(getattr(cls, "torsio_folder", None) == folder for cls in classes):
        classes[:] = [c for c in classes if not hasattr(c, "torsio_folder")]
        classes.insert(0, _package_locator(base, folder, _package()))


def _package_locator(base: type, folder: Path, package: Path) -> type:
    """The locator class of :func:`_locate_by_content`, on numba's ``_CacheLocator``."""

    class PackageLocator(base):
        """torsio's functions in ``folder``/<subpackage>, stamped with their file's hash."""

        torsio_folder = folder

        def __init__(self, py_func: Any, py_file: str, place: Path) -> None:
            self._py_file = py_file
            self._lineno = py_func.__code__.co_firstlineno
            self._cache_path = str(folder / place)

        def get_cache_path(self) -> str:
            return self._cache_path

        def get_source_stamp(self) -> str:
            return _content_hash(self._py_file)

        def get_disambiguator(self) -> str:
            return str(self._lineno)

        @classmethod
        def from_function(cls, py_func: Any, py_file: str) -> Any:
            from numba.core import config

            if getattr(config, "CACHE_DIR", None) != str(folder):  # another folder chosen since
                return None
            try:
                place = Path(py_file).resolve().parent.relative_to(package)
            except (OSError, ValueError):  # not one of torsio's files
                return None
            locator = cls(py_func, py_file, place)
            try:
                locator.ensure_cache_path()
            except OSError:
                return None
            return locator

    return PackageLocator


_WATCHING: list[Any] = []  # the one listener of this process, once registered


def watch_compiles(
    stream: TextIO | None = None, delay: float = NOTE_DELAY, interval: float = NOTE_INTERVAL
) -> Any:
    """Register (once per process) the listener that reports numba's compiles on ``stream``
    (default stderr); return it. Without numba this does nothing and returns None.

    numba broadcasts a ``numba:compile`` event around each compile of a cache miss (its
    event API, ``numba.core.event``); the outermost compile of a thread (a kernel with the
    functions it calls) starts a timer thread that prints the notes of the module docstring.
    """
    if _WATCHING:
        return _WATCHING[0]
    try:
        from numba.core import event
    except ImportError:  # pragma: no cover - numba is a dependency; the numpy engine remains
        return None
    listener = _compile_notes(event.Listener)(stream, delay, interval)
    event.register("numba:compile", listener)
    _WATCHING.append(listener)
    return listener


def _compile_notes(base: type) -> type:
    """The listener class, on numba's ``Listener`` base (imported only when numba is)."""

    class CompileNotes(base):
        """Notes on stderr while the outermost compile of a thread runs (see the module)."""

        def __init__(self, stream: TextIO | None, delay: float, interval: float) -> None:
            self.stream, self.delay, self.interval = stream, delay, interval
            self.local = threading.local()

        def say(self, text: str) -> None:
            print(f"torsio: {text}", file=self.stream or sys.stderr, flush=True)

        def on_start(self, event: Any) -> None:
            depth = getattr(self.local, "depth", 0)
            self.local.depth = depth + 1
            function = event.data["dispatcher"].py_func
            name = f"{function.__module__}.{function.__qualname__}"
            known = COMPILE_ESTIMATES.get(name)
            if depth:  # a function the outer kernel calls: the outer note covers it,
                if known:  # but a kernel of its own says what it adds
                    self.say(_start_note(name, known))
                return
            done = threading.Event()
            started = time.perf_counter()
            said: list[bool] = []
            if known:  # at once, with its estimate
                said.append(True)
                self.say(_start_note(name, known))

            def notes() -> None:
                if not said:  # a law compiles in less than the delay: no note
                    if done.wait(self.delay):
                        return
                    said.append(True)
                    self.say(_start_note(name, None))
                while not done.wait(self.interval):
                    self.say(f"still compiling {name} ({time.perf_counter() - started:.0f} s)")

            thread = threading.Thread(target=notes, name="torsio-compile-notes", daemon=True)
            self.local.watch = (name, started, done, said, thread)
            thread.start()

        def on_end(self, event: Any) -> None:
            self.local.depth -= 1
            if self.local.depth:
                return
            name, started, done, said, thread = self.local.watch
            done.set()
            thread.join()
            if said:
                self.say(f"compiled {name} in {time.perf_counter() - started:.0f} s")

    return CompileNotes


def _start_note(name: str, known: tuple[str, float] | None) -> str:
    """The note of a compile that starts: what it is and how long it takes."""
    if known is None:
        return f"compiling {name} with numba, once ({OTHER_COMPILE}; later runs load it at once)"
    what, seconds = known
    return (
        f"compiling {name} ({what}) with numba, once: about {seconds:.0f} s on a 2 GHz core; "
        "later runs load it at once"
    )
