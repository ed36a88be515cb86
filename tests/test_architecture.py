"""The layout rules of docs/architecture.md: short modules, no import cycles (deferred
imports included), physics free of io."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).parents[1] / "src" / "torsio"
MAX_LINES = 500


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {_module_name(path): path for path in sorted(PACKAGE.rglob("*.py"))}


def _import_nodes(tree: ast.AST):
    """Every statement that can run: the module body and function bodies alike (a deferred
    import is an edge too), all but ``if TYPE_CHECKING:`` blocks, which never run."""
    for node in ast.iter_child_nodes(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            continue
        yield node
        yield from _import_nodes(node)


def _absolute(node: ast.ImportFrom, name: str, path: Path) -> str:
    """The module an ``from ... import`` names, relative imports resolved."""
    if not node.level:
        return node.module or ""
    package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
    base = package[: len(package) - (node.level - 1)]
    return ".".join([*base, node.module] if node.module else base)


def _imports(path: Path, name: str) -> set[str]:
    """torsio modules a file imports, at import time or inside its functions."""
    found: set[str] = set()
    for node in _import_nodes(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            module = _absolute(node, name, path)
            if module.startswith("torsio"):
                found.add(module)
                found.update(f"{module}.{alias.name}" for alias in node.names)
        elif isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names if alias.name.startswith("torsio"))
    return {module for module in found if module in MODULES}


# The package facade re-exports everything lazily (PEP 562: ``import torsio`` imports
# none of the modules) and is imported inside torsio only for ``__version__`` and
# ``__file__``; it is left out of the graph.
GRAPH = {
    name: _imports(path, name) - {"torsio", name}
    for name, path in MODULES.items()
    if name != "torsio"
}


@pytest.mark.parametrize("name", list(MODULES))
def test_modules_are_short(name):
    # the layout rule of docs/architecture.md: one job per module, at most 500 lines
    lines = len(MODULES[name].read_text(encoding="utf-8").splitlines())
    assert lines <= MAX_LINES, f"{name} has {lines} lines"


def _cycle_from(start: str) -> list[str] | None:
    stack = [(start, [start])]
    seen: set[str] = set()
    while stack:
        node, path = stack.pop()
        for target in GRAPH.get(node, ()):
            if target == start:
                return [*path, start]
            if target not in seen:
                seen.add(target)
                stack.append((target, [*path, target]))
    return None


def test_no_import_cycles():
    cycles = [cycle for name in GRAPH if (cycle := _cycle_from(name))]
    assert not cycles, "import cycles: " + "; ".join(" -> ".join(c) for c in cycles[:5])


@pytest.mark.parametrize("layer", ["torsio.model", "torsio.physics", "torsio.solvers"])
def test_core_layers_do_not_import_the_edges(layer):
    # the flow of data runs one way: configuration and reports read the model, never back
    edges = ("torsio.io", "torsio.cli")  # plotting is a layer of its own, results use it
    offenders = {
        name: sorted(t for t in targets if t.startswith(edges))
        for name, targets in GRAPH.items()
        if name.startswith(layer)
    }
    assert not {k: v for k, v in offenders.items() if v}


def test_deferred_imports_are_edges_and_type_checking_blocks_are_not(tmp_path):
    # the graph above must see an import inside a function (it runs on the first call and
    # closes a cycle as surely as a module-level one) and skip ``if TYPE_CHECKING:``
    source = tmp_path / "probe.py"
    source.write_text(
        "from typing import TYPE_CHECKING\n"
        "if TYPE_CHECKING:\n"
        "    from torsio.io.config import Config\n"
        "def run():\n"
        "    from torsio.model.modal import modal_analysis\n"
        "    from .wave import is_wave_model\n",
        encoding="utf-8",
    )
    edges = _imports(source, "torsio.model.probe")
    assert edges == {"torsio.model.modal", "torsio.model.wave"}
