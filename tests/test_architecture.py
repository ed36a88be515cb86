"""The layout rules of docs/architecture.md: short modules, no import cycles, physics free of io."""

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


def _import_time_nodes(tree: ast.AST):
    """Statements run when the module is imported: its body, not function bodies, and not
    ``if TYPE_CHECKING:`` blocks."""
    for node in ast.iter_child_nodes(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            continue
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda):
            continue
        yield node
        yield from _import_time_nodes(node)


def _imports(path: Path) -> set[str]:
    """torsio modules a file imports when it is imported (deferred imports are not edges)."""
    found: set[str] = set()
    for node in _import_time_nodes(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("torsio"):
            found.add(node.module)
            found.update(f"{node.module}.{alias.name}" for alias in node.names)
        elif isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names if alias.name.startswith("torsio"))
    return {name for name in found if name in MODULES}


# The package facade re-exports everything and is imported by nobody inside torsio
# except for ``__version__``; it is left out of the graph.
GRAPH = {
    name: _imports(path) - {"torsio", name} for name, path in MODULES.items() if name != "torsio"
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
