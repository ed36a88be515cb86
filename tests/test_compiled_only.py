"""Functions compiled with ``njit_inner`` (:mod:`torsio.solvers.compiled`) have no Python
wrapper: a call from Python would crash the process instead of raising. Each is used only
inside other compiled functions, in the package, its tests and its benchmarks."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).parents[1]
FILES = sorted(
    [*(ROOT / "src" / "torsio").rglob("*.py"), *(ROOT / "tests").glob("*.py"),
     *(ROOT / "benchmarks").glob("*.py")]
)  # fmt: skip


def _decorators(node: ast.AST) -> set[str]:
    names = set()
    for decorator in getattr(node, "decorator_list", []):
        target = decorator.func if isinstance(decorator, ast.Call) else decorator
        names.add(ast.unparse(target).split(".")[-1])
    return names


def _module(path: Path) -> str:
    return ".".join(path.relative_to(ROOT / "src").with_suffix("").parts)


def _compiled_only() -> dict[str, set[str]]:
    """module -> names of its ``njit_inner`` functions."""
    found: dict[str, set[str]] = {}
    for path in (ROOT / "src" / "torsio").rglob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        names = {n.name for n in tree.body if "njit_inner" in _decorators(n)}
        if names:
            found[_module(path)] = names
    return found


def _python_uses(source: str, module: str | None, inner: dict[str, set[str]]) -> list[str]:
    """Lines of ``source`` (module ``module``, None outside the package) that use an
    ``njit_inner`` function from Python: outside every ``njit``/``njit_inner`` body."""
    tree = ast.parse(source)
    names: dict[str, str] = {n: module for n in inner.get(module or "", ())}  # bare names
    aliases: dict[str, str] = {}  # module aliases: alias -> module
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module:
            for alias in node.names:
                if alias.name in inner.get(node.module, ()):
                    names[alias.asname or alias.name] = node.module
                if f"{node.module}.{alias.name}" in inner:
                    aliases[alias.asname or alias.name] = f"{node.module}.{alias.name}"
    uses: list[str] = []

    def visit(node: ast.AST) -> None:
        if _decorators(node) & {"njit", "njit_inner"}:
            return  # compiled code may call them
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            return
        if isinstance(node, ast.Name) and node.id in names:
            uses.append(f"line {node.lineno}: {node.id}")
        if (
            isinstance(node, ast.Attribute)
            and isinstance(node.value, ast.Name)
            and node.attr in inner.get(aliases.get(node.value.id, ""), ())
        ):
            uses.append(f"line {node.lineno}: {node.value.id}.{node.attr}")
        for child in ast.iter_child_nodes(node):
            visit(child)

    for statement in tree.body:
        if isinstance(statement, (ast.FunctionDef, ast.ClassDef)) or not (
            isinstance(statement, (ast.Import, ast.ImportFrom))
        ):
            visit(statement)
    return uses


def test_compiled_only_functions_are_not_called_from_python() -> None:
    inner = _compiled_only()
    assert inner, "no njit_inner function found: the check would pass vacuously"
    offenders = {}
    for path in FILES:
        module = _module(path) if path.is_relative_to(ROOT / "src") else None
        if uses := _python_uses(path.read_text(encoding="utf-8"), module, inner):
            offenders[str(path.relative_to(ROOT))] = uses
    assert not offenders, f"njit_inner functions used from Python: {offenders}"


def test_the_finder_sees_bare_names_aliases_and_skips_compiled_bodies() -> None:
    inner = {"torsio.solvers.k": {"step", "other"}}
    source = (
        "from torsio.solvers.k import step\n"
        "from torsio.solvers import k as kernel\n"
        "@njit(cache=True)\n"
        "def compiled(x):\n"
        "    return step(x) + kernel.other(x)\n"
        "def python(x):\n"
        "    return step(x)\n"
        "y = kernel.other(1.0)\n"
    )
    assert _python_uses(source, None, inner) == ["line 7: step", "line 8: kernel.other"]
    own = "@njit_inner()\ndef step(x):\n    return x\ndef python(x):\n    return step(x)\n"
    assert _python_uses(own, "torsio.solvers.k", inner) == ["line 5: step"]
