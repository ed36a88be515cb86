"""The layout rules of docs/architecture.md: short modules, no import cycles (deferred
imports included), the data flowing one way: the input side (config/) builds the objects of
the core, the output side (report/) reads them, and neither is imported back."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).parents[1] / "src" / "torsio"
MAX_LINES = 500
# docs/architecture.md, "Module size": one job per module, at most MAX_LINES lines; a module
# whose one job needs more is named here with its limit (at most LONGEST) and the reason
LONGEST = 800
LONGER_JOBS: dict[str, tuple[int, str]] = {}


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


def _lines(name: str) -> int:
    return len(MODULES[name].read_text(encoding="utf-8").splitlines())


@pytest.mark.parametrize("name", list(MODULES))
def test_modules_are_short(name):
    # the layout rule of docs/architecture.md: one job per module, at most 500 lines
    limit = LONGER_JOBS.get(name, (MAX_LINES, ""))[0]
    assert _lines(name) <= limit, f"{name} has {_lines(name)} lines"


def test_longer_jobs_are_few_and_still_long():
    # an entry says why its one job needs more, stays under LONGEST and goes when it shrinks
    for name, (limit, reason) in LONGER_JOBS.items():
        assert name in MODULES and reason and MAX_LINES < limit <= LONGEST, name
        assert _lines(name) > MAX_LINES, f"{name} fits in {MAX_LINES} lines again"


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


# The input side (the configuration and the built-in examples read from it), the output
# side (the report) and the command line sit above the core; config/ is input only.
INPUT = ("torsio.config", "torsio.examples")
OUTPUT = ("torsio.report",)
CLI = ("torsio.cli",)
CORE = ("torsio.model", "torsio.physics", "torsio.solvers", "torsio.analysis", "torsio.well")
CORE += ("torsio.axial", "torsio.calibration", "torsio.advice")
LAYER_RULES = {
    **{layer: INPUT + OUTPUT + CLI for layer in CORE},
    "torsio.config": OUTPUT + CLI,
    "torsio.report": CLI,
}


def _in(name: str, packages: tuple[str, ...]) -> bool:
    return any(name == p or name.startswith(p + ".") for p in packages)


@pytest.mark.parametrize("layer", list(LAYER_RULES))
def test_layers_do_not_import_the_layers_above(layer):
    # the flow of data runs one way: configuration builds the model, reports read it, never
    # back (plotting is a layer of its own below the results, which use it)
    offenders = {
        name: sorted(t for t in targets if _in(t, LAYER_RULES[layer]))
        for name, targets in GRAPH.items()
        if _in(name, (layer,))
    }
    assert not {k: v for k, v in offenders.items() if v}


def test_every_module_is_under_a_layer_rule_or_above_them():
    # a new folder gets a rule (or joins the edges: cli, the package facade, the plugins)
    top = {name.split(".")[1] for name in GRAPH if name.count(".") >= 1}
    ruled = {p.split(".")[1] for p in LAYER_RULES} | {"cli", "examples"}
    edges = {"__main__", "errors", "units", "csv_rows", "hookspecs", "plugins", "kernel_cache"}
    edges |= {"display_units"}  # the units tables and plots are printed in, like units
    edges |= {"output_files"}  # writing a file whole or not at all, like errors
    edges |= {"stop_signals"}  # Ctrl-C and SIGTERM, installed by cli, checked by run loops
    edges |= {"plotting"}
    assert top <= ruled | edges, sorted(top - ruled - edges)


def test_deferred_imports_are_edges_and_type_checking_blocks_are_not(tmp_path):
    # the graph above must see an import inside a function (it runs on the first call and
    # closes a cycle as surely as a module-level one) and skip ``if TYPE_CHECKING:``
    source = tmp_path / "probe.py"
    source.write_text(
        "from typing import TYPE_CHECKING\n"
        "if TYPE_CHECKING:\n"
        "    from torsio.config.configuration import Config\n"
        "def run():\n"
        "    from torsio.model.modal import modal_analysis\n"
        "    from .wave import is_wave_model\n",
        encoding="utf-8",
    )
    edges = _imports(source, "torsio.model.probe")
    assert edges == {"torsio.model.modal", "torsio.model.wave"}


# --- one model protocol (torsio.model.protocol) -------------------------------------------------
MODEL_KINDS = {"WaveModel", "LumpedModel"}

KIND_TESTS_ALLOWED: set[str] = set()
# (analysis.transient and solvers.batch hand a run to resolve(system.model.engines.<role>))


def _names(node: ast.AST) -> set[str]:
    """Names and attribute names in an expression (``wave.WaveModel`` gives both)."""
    return {n.id for n in ast.walk(node) if isinstance(n, ast.Name)} | {
        n.attr for n in ast.walk(node) if isinstance(n, ast.Attribute)
    }


def _kind_tests(source: str) -> list[str]:
    """Where a module tests the kind of a model: a use of ``is_wave_model`` (a call, an
    import, a reference), an ``isinstance``/``issubclass`` against a model class."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.ImportFrom) and any(a.name == "is_wave_model" for a in node.names):
            found.append(f"line {node.lineno}: imports is_wave_model")
        elif (isinstance(node, ast.Name) and node.id == "is_wave_model") or (
            isinstance(node, ast.Attribute) and node.attr == "is_wave_model"
        ):
            found.append(f"line {node.lineno}: is_wave_model")
        elif (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Name)
            and node.func.id in ("isinstance", "issubclass")
            and len(node.args) == 2
            and _names(node.args[1]) & MODEL_KINDS
        ):
            found.append(f"line {node.lineno}: {ast.unparse(node)}")
    return found


KIND_TESTS = {
    name: tests
    for name, path in MODULES.items()
    if not name.startswith("torsio.model")
    and (tests := _kind_tests(path.read_text(encoding="utf-8")))
}


def test_no_module_outside_the_model_tests_the_kind_of_a_model():
    # docs/architecture.md, "The model protocol": analyzers, solvers, reports and the CLI
    # read a model through torsio.model.protocol.StructuralModel, never by its class
    offenders = {k: v for k, v in KIND_TESTS.items() if k not in KIND_TESTS_ALLOWED}
    assert not offenders, f"kind tests outside torsio.model: {offenders}"


def test_the_kind_test_allow_list_holds_only_modules_that_still_test():
    # an entry goes as soon as its module reads the protocol instead
    assert set(KIND_TESTS_ALLOWED) <= set(KIND_TESTS), sorted(
        set(KIND_TESTS_ALLOWED) - set(KIND_TESTS)
    )


def test_the_kind_test_finder_sees_calls_imports_and_isinstance():
    source = (
        "from torsio.model.wave import is_wave_model\n"
        "import torsio.model.wave as wave\n"
        "def run(model):\n"
        "    a = wave.is_wave_model(model)\n"
        "    b = isinstance(model, (wave.WaveModel, int))\n"
        "    c = isinstance(model, LumpedModel)\n"
        "    return model.linearizable and isinstance(model, dict)\n"
    )
    lines = [entry.split(":")[0] for entry in _kind_tests(source)]
    assert sorted(lines) == ["line 1", "line 4", "line 5", "line 6"]
