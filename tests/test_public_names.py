"""Each public name is exported once: by the module that defines it (issue 17, item 5).

A module's ``__all__`` lists what it defines; a name it only imports is not exported again.
Package ``__init__`` modules (``torsio.well``, ``torsio.plotting``) are facades that gather
their modules' names for ``from torsio.well import ...``, and ``torsio`` itself maps every
top-level name to its defining module (``torsio._EXPORTS``).
"""

from __future__ import annotations

import ast
import importlib
import inspect
import pkgutil
from collections import defaultdict
from pathlib import Path

import torsio


def _modules():
    for info in pkgutil.walk_packages(torsio.__path__, "torsio."):
        if info.name.endswith("__main__") or info.ispkg:
            continue
        yield importlib.import_module(info.name)


def test_no_module_exports_an_object_another_module_exports():
    owners: dict[int, list[str]] = defaultdict(list)
    for module in _modules():
        for name in getattr(module, "__all__", ()):
            value = getattr(module, name)
            if isinstance(value, int | float | str | bool | tuple):
                continue  # equal constants are not the same object; their names are checked below
            owners[id(value)].append(f"{module.__name__}.{name}")
    twice = {key: names for key, names in owners.items() if len(names) > 1}
    assert not twice, f"exported by more than one module: {list(twice.values())}"


def test_no_constant_is_exported_by_two_modules():
    exporters: dict[str, list[str]] = defaultdict(list)
    for module in _modules():
        for name in getattr(module, "__all__", ()):
            if isinstance(getattr(module, name), int | float | str | bool | tuple):
                exporters[name].append(module.__name__)
    twice = {name: modules for name, modules in exporters.items() if len(modules) > 1}
    assert not twice, f"constants exported by more than one module: {twice}"


def test_top_level_names_come_from_their_defining_module():
    assert sorted(torsio.__all__) == sorted(torsio._LAZY)
    for name, module in torsio._LAZY.items():
        value = getattr(torsio, name)
        if inspect.isclass(value) or inspect.isfunction(value):  # (hookimpl: a pluggy marker)
            assert value.__module__ == module, f"torsio.{name}: {module}, not {value.__module__}"


def test_the_type_checking_imports_of_torsio_are_its_name_table():
    # torsio/__init__.py imports its names for type checkers only; they must be _EXPORTS
    tree = ast.parse(Path(torsio.__file__).read_text(encoding="utf-8"))
    block = next(
        node
        for node in tree.body
        if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING"
    )
    imported = {
        (node.module, alias.name)
        for node in ast.walk(block)
        if isinstance(node, ast.ImportFrom)
        for alias in node.names
    }
    assert imported == {(module, name) for name, module in torsio._LAZY.items()}
    assert torsio.__all__ == list(torsio._LAZY)
