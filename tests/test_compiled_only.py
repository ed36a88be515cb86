"""Functions compiled with ``njit_inner`` (:mod:`torsio.solvers.compiled`) have no Python
wrapper: a call from Python would crash the process instead of raising. Each is used only
inside other compiled functions, in the package, its tests and its benchmarks."""

from __future__ import annotations

import ast
import doctest
import inspect
from pathlib import Path

ROOT = Path(__file__).parents[1]
FILES = sorted(
    path
    for folder in ("src", "tests", "benchmarks", "examples", "plugins", "docs")
    for path in (ROOT / folder).rglob("*")
    if path.suffix in (".py", ".md")
) + [ROOT / "README.md"]


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


def _imported(tree: ast.AST, module: str | None, inner: dict[str, set[str]]):
    """(bare names, module aliases) of ``inner`` functions and modules that ``tree`` imports."""
    names: dict[str, str] = {n: module for n in inner.get(module or "", ())}  # its own
    aliases: dict[str, str] = {}  # alias -> module
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            base = (module or "").split(".")[: -node.level] if node.level else []
            source = ".".join([*base, node.module] if node.module else base)
            for alias in node.names:
                if alias.name in inner.get(source, ()):
                    names[alias.asname or alias.name] = source
                if f"{source}.{alias.name}" in inner:
                    aliases[alias.asname or alias.name] = f"{source}.{alias.name}"
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name in inner and alias.asname:
                    aliases[alias.asname] = alias.name
    return names, aliases


def _python_uses(source: str, module: str | None, inner: dict[str, set[str]]) -> list[str]:
    """Lines of ``source`` (module ``module``, None outside the package) that use an
    ``njit_inner`` function from Python: outside every ``njit``/``njit_inner`` body, by
    its name, through a module alias or by its dotted path."""
    tree = ast.parse(source)
    names, aliases = _imported(tree, module, inner)
    dotted = {f"{m}.{n}" for m, functions in inner.items() for n in functions}
    uses: list[str] = []

    def visit(node: ast.AST) -> None:
        if _decorators(node) & {"njit", "njit_inner"}:
            return  # compiled code may call them
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            return
        if isinstance(node, ast.Name) and node.id in names:
            uses.append(f"line {node.lineno}: {node.id}")
        if isinstance(node, ast.Attribute):
            path = ast.unparse(node)
            base = aliases.get(path.rsplit(".", 1)[0], "")
            if path in dotted or node.attr in inner.get(base, ()):
                uses.append(f"line {node.lineno}: {path}")
                return
        for child in ast.iter_child_nodes(node):
            visit(child)

    visit(tree)
    return uses


def _doctests(text: str) -> str:
    """The source of every ``>>>`` example in ``text`` (a docstring, a Markdown page)."""
    return "".join(example.source for example in doctest.DocTestParser().get_examples(text))


def _docstring_tests(tree: ast.AST) -> str:
    """The ``>>>`` examples of every docstring in ``tree``, in order."""
    documented = (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)
    return "".join(
        _doctests(inspect.cleandoc(text))
        for node in ast.walk(tree)
        if isinstance(node, documented) and (text := ast.get_docstring(node, clean=False))
    )


def test_compiled_only_functions_are_not_called_from_python() -> None:
    inner = _compiled_only()
    assert inner, "no njit_inner function found: the check would pass vacuously"
    offenders = {}
    for path in FILES:
        text = path.read_text(encoding="utf-8")
        module = _module(path) if path.is_relative_to(ROOT / "src") else None
        uses = _python_uses(text, module, inner) if path.suffix == ".py" else []
        if path.suffix == ".py":  # its doctests run in its namespace
            tree = ast.parse(text)
            imports = "".join(
                f"{ast.unparse(node)}\n"
                for node in ast.walk(tree)
                if isinstance(node, (ast.Import, ast.ImportFrom))
            )
            examples = imports + _docstring_tests(tree)
            uses += [f"doctest {use}" for use in _python_uses(examples, module, inner)]
        else:
            uses = [f"doctest {use}" for use in _python_uses(_doctests(text), None, inner)]
        if uses:
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
    dotted = "import torsio.solvers.k\nimport torsio.solvers.k as kk\n" + _doctests(
        "    >>> torsio.solvers.k.step(1.0)\n    1.0\n    >>> kk.other(2.0)\n"
    )
    assert _python_uses(dotted, None, inner) == [
        "line 3: torsio.solvers.k.step", "line 4: kk.other"
    ]  # fmt: skip
    own = "@njit_inner()\ndef step(x):\n    return x\ndef python(x):\n    return step(x)\n"
    assert _python_uses(own, "torsio.solvers.k", inner) == ["line 5: step"]
