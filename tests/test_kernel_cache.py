"""Where numba caches torsio's kernels: the same folders and stamps for a regular and an
editable install of the same sources (torsio.kernel_cache)."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import pytest

from torsio import kernel_cache

numba = pytest.importorskip("numba")


def test_the_folder_key_reads_contents_not_paths_or_times(monkeypatch, tmp_path) -> None:
    # a copy of the package elsewhere, with other file times, as `pip install .` makes one
    # next to the sources an editable install uses: the same key
    package = kernel_cache._package()
    copy = tmp_path / "torsio"
    for source in kernel_cache.kernel_sources():
        target = copy / source.relative_to(package)
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(source, target)  # new times
    key = kernel_cache._sources_key()
    monkeypatch.setattr(kernel_cache, "_package", lambda: copy)
    assert kernel_cache._sources_key() == key
    laws = copy / "physics" / "laws.py"
    laws.write_text(laws.read_text(encoding="utf-8") + "\n# changed\n", encoding="utf-8")
    assert kernel_cache._sources_key() != key  # a changed source: another folder


def test_the_folder_key_is_the_environments_not_the_interpreters_name(monkeypatch) -> None:
    # pip writes `#!<venv>/bin/python3` into the console scripts, while a user runs a
    # script with `<venv>/bin/python`: one environment, one folder (a second one compiled
    # the step loop again, 15 s); another environment gets its own folder
    key = kernel_cache._sources_key()
    monkeypatch.setattr(sys, "executable", str(Path(sys.prefix) / "bin" / "python3.99"))
    assert kernel_cache._sources_key() == key
    monkeypatch.setattr(sys, "prefix", str(Path(sys.prefix) / "another-venv"))
    assert kernel_cache._sources_key() != key


def test_torsios_functions_are_filed_by_their_place_in_the_package(tmp_path) -> None:
    from numba.core import caching

    import torsio.solvers.compiled  # noqa: F401  (sets the folder and the locator)
    from torsio.solvers import rodas

    folder = Path(numba.config.CACHE_DIR)
    locator = caching.FunctionCache(rodas.advance.py_func)._impl.locator
    assert Path(locator.get_cache_path()) == folder / "solvers"
    assert locator.get_source_stamp() == kernel_cache._content_hash(rodas.__file__)

    # the same file in another installed folder: the same cache folder and stamp
    base = type(locator).__mro__[1]
    other = tmp_path / "site-packages" / "torsio"
    (other / "solvers").mkdir(parents=True)
    copied = other / "solvers" / "rodas.py"
    shutil.copyfile(rodas.__file__, copied)
    moved = kernel_cache._package_locator(base, folder, other)
    found = moved.from_function(rodas.advance.py_func, str(copied))
    assert Path(found.get_cache_path()) == folder / "solvers"
    assert found.get_source_stamp() == locator.get_source_stamp()


def test_other_packages_keep_numbas_locators(tmp_path) -> None:
    import torsio.solvers.compiled  # noqa: F401  (sets the locator)

    module = tmp_path / "elsewhere.py"
    module.write_text("def f(x):\n    return x\n", encoding="utf-8")
    namespace: dict = {}
    exec(compile(module.read_text(encoding="utf-8"), str(module), "exec"), namespace)
    from numba.core import caching

    locator = caching.FunctionCache(namespace["f"])._impl.locator
    assert not hasattr(locator, "torsio_folder")
