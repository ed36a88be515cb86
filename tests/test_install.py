"""What a new installation meets: no matplotlib, numba's cache folder, the compile notes."""

from __future__ import annotations

import io
import json
import sys
import time
import types
from importlib import resources
from pathlib import Path
from typing import Any

import pytest

from torsio import kernel_cache
from torsio.cli import main


@pytest.fixture
def no_matplotlib(monkeypatch: pytest.MonkeyPatch) -> None:
    """matplotlib as if not installed (the README's first command installs no extras)."""
    for name in list(sys.modules):
        if name == "matplotlib" or name.startswith("matplotlib."):
            monkeypatch.setitem(sys.modules, name, None)
    monkeypatch.setitem(sys.modules, "matplotlib", None)


def test_html_report_without_matplotlib(no_matplotlib, tmp_path: Path, capsys) -> None:
    page = tmp_path / "out.html"
    assert main(["report", "--strategy", "A", "--html", str(page)]) == 0
    text = page.read_text(encoding="utf-8")
    assert "data:image/png" not in text and "torsio[plot]" in text
    assert "Distance to the critical weight" in text  # the report itself is all there
    captured = capsys.readouterr()
    assert "torsio[plot]" in captured.err and "Traceback" not in captured.err


@pytest.mark.parametrize(
    "argv",
    [
        ["simulate", "--strategy", "A", "--wob", "100 kN", "--rpm", "60", "--plot", "x.png"],
        ["map", "--strategy", "A", "--wob", "25kN:225kN:2", "--rpm", "40:140:2", "--plot", "x.png"],
    ],
)
def test_plot_options_without_matplotlib(no_matplotlib, argv, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "--plot" in err and "torsio[plot]" in err and "Traceback" not in err
    assert not (tmp_path / "x.png").exists()


def test_user_cache_dir_order() -> None:
    # the XDG base directory specification, then the platforms' conventions
    home = {"HOME": "/home/me"}
    assert kernel_cache.user_cache_dir({**home, "TORSIO_CACHE_DIR": "/c"}, "linux") == Path("/c")
    assert kernel_cache.user_cache_dir({**home, "XDG_CACHE_HOME": "/x"}, "linux") == Path(
        "/x/torsio"
    )
    assert kernel_cache.user_cache_dir(home, "linux") == Path("/home/me/.cache/torsio")
    assert kernel_cache.user_cache_dir(home, "darwin") == Path("/home/me/Library/Caches/torsio")
    assert kernel_cache.user_cache_dir({**home, "LOCALAPPDATA": "/l"}, "win32") == Path(
        "/l/torsio/Cache"
    )


def test_numba_cache_is_outside_the_package() -> None:
    numba = pytest.importorskip("numba")
    import torsio.solvers.compiled  # noqa: F401  (sets the folder before any kernel)

    package = Path(torsio.__file__).resolve().parent
    folder = Path(numba.config.CACHE_DIR).resolve()
    assert numba.config.CACHE_DIR and package not in (folder, *folder.parents)


def test_a_users_numba_cache_dir_is_kept(monkeypatch: pytest.MonkeyPatch, tmp_path) -> None:
    numba = pytest.importorskip("numba")
    monkeypatch.setattr(numba.config, "CACHE_DIR", str(tmp_path))
    kernel_cache.use_user_cache_dir()
    assert numba.config.CACHE_DIR == str(tmp_path)


def _notes(delay: float, interval: float) -> tuple[io.StringIO, Any]:
    """A fresh compile-notes listener writing to a string (not the process's own)."""
    event = pytest.importorskip("numba.core.event")
    stream = io.StringIO()
    return stream, kernel_cache._compile_notes(event.Listener)(stream, delay, interval)


def _compile_event(function: Any) -> Any:
    """A stand-in for numba's ``numba:compile`` event of ``function``."""
    return types.SimpleNamespace(data={"dispatcher": types.SimpleNamespace(py_func=function)})


def test_a_long_compile_is_never_silent() -> None:
    # the outermost compile prints its note, then a line every interval until it ends
    stream, listener = _notes(delay=0.0, interval=0.02)
    outer = _compile_event(test_a_long_compile_is_never_silent)
    listener.on_start(outer)
    listener.on_start(_compile_event(_notes))  # a function the kernel calls: no note of its own
    time.sleep(0.2)
    listener.on_end(outer)
    listener.on_end(outer)
    lines = stream.getvalue().splitlines()
    name = f"{__name__}.test_a_long_compile_is_never_silent"
    assert lines[0].startswith(f"torsio: compiling {name} with numba")
    assert f"with numba, once ({kernel_cache.OTHER_COMPILE}; later runs" in lines[0]
    assert all("still compiling" in line for line in lines[1:-1]) and len(lines) >= 4
    assert lines[-1].startswith(f"torsio: compiled {name} in ")
    assert "_notes" not in stream.getvalue()


def test_an_entry_point_says_its_estimate_as_it_starts(monkeypatch) -> None:
    # the estimates of kernel_cache.COMPILE_ESTIMATES are printed at once, for a kernel
    # compiled within another too (the step loop in a first map's batch loop)
    outer, inner = test_a_long_compile_is_never_silent, _notes
    estimates = {
        f"{__name__}.{outer.__qualname__}": ("the batch loop", 3.0),
        f"{__name__}.{inner.__qualname__}": ("the step loop", 13.0),
    }
    monkeypatch.setattr(kernel_cache, "COMPILE_ESTIMATES", estimates)
    stream, listener = _notes(delay=30.0, interval=30.0)
    listener.on_start(_compile_event(outer))
    listener.on_start(_compile_event(inner))
    lines = stream.getvalue().splitlines()
    listener.on_end(_compile_event(inner))
    listener.on_end(_compile_event(outer))
    assert lines == [
        f"torsio: compiling {__name__}.{outer.__qualname__} (the batch loop) with numba, "
        "once: about 3 s on a 2 GHz core; later runs load it at once",
        f"torsio: compiling {__name__}.{inner.__qualname__} (the step loop) with numba, "
        "once: about 13 s on a 2 GHz core; later runs load it at once",
    ]
    assert stream.getvalue().splitlines()[-1].startswith(f"torsio: compiled {__name__}.test_a")


def test_every_estimate_names_a_compiled_function() -> None:
    # a renamed kernel would lose its note's estimate: each name is a function of torsio
    import importlib

    pytest.importorskip("numba")
    for name in kernel_cache.COMPILE_ESTIMATES:
        module, _, qualname = name.rpartition(".")
        function = getattr(importlib.import_module(module), qualname)
        assert callable(function), name


def test_a_short_compile_prints_nothing() -> None:
    # a compile shorter than the delay (a cache load is not even a compile) says nothing
    stream, listener = _notes(delay=30.0, interval=30.0)
    listener.on_start(_compile_event(_notes))
    listener.on_end(_compile_event(_notes))
    assert stream.getvalue() == ""


def test_numba_compiles_are_reported() -> None:
    # numba broadcasts its compile event to the listener (numba.core.event's API)
    numba = pytest.importorskip("numba")
    from numba.core import event

    stream, listener = _notes(delay=0.0, interval=60.0)

    def add_one(x: float) -> float:
        return x + 1.0

    with event.install_listener("numba:compile", listener):
        assert numba.njit(add_one)(1.0) == 2.0
    assert f"torsio: compiling {__name__}.test_numba_compiles" in stream.getvalue()
    assert "add_one in " in stream.getvalue().splitlines()[-1]


def _stderr_of(code: str) -> str:
    """What ``code`` run in a fresh interpreter prints on stderr (it must exit 0)."""
    import subprocess

    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=False
    )
    assert result.returncode == 0, result.stderr
    return result.stderr


@pytest.mark.parametrize("argv", [["laws"], ["laws", "--json"], ["--help"]])
def test_light_commands_load_no_heavy_module(argv: list[str]) -> None:
    # start-up: `torsio laws` and `torsio --help` must not pay for scipy, numba or pint
    # (seconds of imports; benchmarks/bench_startup.py times them against `import numpy`)
    code = (
        "import sys\n"
        "from torsio.cli import main\n"
        f"try:\n    main({argv!r})\nexcept SystemExit:\n    pass\n"
        "heavy = [m for m in ('scipy', 'numba', 'pint', 'matplotlib') if m in sys.modules]\n"
        "print('HEAVY', heavy, file=sys.stderr)\n"
    )
    assert "HEAVY []" in _stderr_of(code)


@pytest.mark.parametrize(("side", "kernel"), [(3, "run_chunk"), (8, "integrate_serial")])
def test_a_map_loads_only_what_it_runs(side: int, kernel: str) -> None:
    # a serial map through the CLI: one compiled entry point (a map of fewer than
    # rodas_kernels.SMALL_BATCH = 64 points the single run's step loop, a larger one the
    # batch loop), and none of scipy's sparse matrices or integrators (the scipy engine's)
    code = (
        "import sys\n"
        "from torsio.cli import main\n"
        f"main(['map', '--strategy', 'A', '--wob', '50kN:150kN:{side}',"
        f" '--rpm', '60:120:{side}', '--refine', '0', '--json'])\n"
        "from torsio.solvers import rodas_kernels\n"
        "loaded = [m for m in ('scipy.sparse', 'scipy.integrate', 'distributed')\n"
        "          if m in sys.modules]\n"
        "kernels = [k for k in ('integrate_serial', 'run_chunk') if k in vars(rodas_kernels)]\n"
        "print('LOADED', loaded, 'KERNELS', kernels, file=sys.stderr)\n"
    )
    assert f"LOADED [] KERNELS ['{kernel}']" in _stderr_of(code)


def test_a_lumped_run_loads_no_wave_kernel() -> None:
    # the wave model's stepping compiles as its module is imported (5 s on a first run):
    # `torsio simulate` of a lumped model does not import it, nor its batch kernel
    code = (
        "import sys\n"
        "from torsio.cli import main\n"
        "main(['simulate', '--strategy', 'A', '--duration', '20', '--json'])\n"
        "from torsio.solvers import rodas_kernels\n"
        "wave = [m for m in ('torsio.solvers.characteristics', 'torsio.analysis.wave')\n"
        "        if m in sys.modules]\n"
        "kernels = sorted(k for k in ('integrate_serial', 'run_chunk')\n"
        "                 if k in vars(rodas_kernels))\n"
        "print('WAVE', wave, 'KERNELS', kernels, file=sys.stderr)\n"
    )
    assert "WAVE [] KERNELS ['run_chunk']" in _stderr_of(code)


def test_console_script_returns_the_status_and_freezes_the_collector() -> None:
    # the console script is main() then gc.freeze(): the exit does not scan numba's
    # registries again; the status and the output are main's
    code = (
        "import gc, sys\n"
        "import torsio.cli\n"
        "torsio.cli.main = lambda: 3\n"
        "status = torsio.cli.console_main()\n"
        "print('STATUS', status, 'FROZEN', gc.get_freeze_count() > 0, file=sys.stderr)\n"
    )
    assert "STATUS 3 FROZEN True" in _stderr_of(code)


def test_bare_numbers_are_read_without_pint() -> None:
    import subprocess

    code = (
        "import sys\n"
        "from torsio.units import to_si\n"
        "assert to_si('150', 'force', key='wob') == 150.0\n"
        "assert to_si(' 1e5 ', 'force', key='wob') == 1e5\n"
        "print('pint' in sys.modules)\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    )
    assert result.stdout.strip() == "False"


def test_init_writes_a_template_that_runs(tmp_path: Path, capsys) -> None:
    import json
    import warnings

    from torsio.cli.init import template_text
    from torsio.config.reading import load_config

    path = tmp_path / "new.toml"
    assert main(["init", str(path)]) == 0
    assert f"wrote {path}" in capsys.readouterr().out
    assert path.read_text(encoding="utf-8") == template_text()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        config = load_config(path)
    assert config.bit_rock is not None and config.operation.wob == 100e3  # "100 kN"
    # every key of the template is explained: a comment on its line or naming it
    lines = template_text().splitlines()
    comments = " ".join(line.partition("#")[2] for line in lines)
    keys = [line.partition("=")[0].strip() for line in lines if "=" in line[:30]]
    keys = [key for key in keys if key and not key.startswith(("#", "["))]
    with_comment = {line.partition("=")[0].strip() for line in lines if " # " in line}
    for key in keys:
        assert key in with_comment or key in comments, key
    assert main(["modes", str(path), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["dofs"] == 10
    # a second init keeps the file
    assert main(["init", str(path)]) == 2
    assert "--force" in capsys.readouterr().err
    assert main(["init", str(path), "--force"]) == 0


def test_init_writes_a_builtin_example_that_runs_as_its_comment_says(
    tmp_path, capsys, monkeypatch
) -> None:
    # reference: the package's own data files, byte for byte, and the commands their
    # opening comments name
    import shlex

    from torsio.cli import build_parser
    from torsio.examples import example_names, example_summary

    monkeypatch.chdir(tmp_path)
    assert main(["init", "--list"]) == 0
    listed = capsys.readouterr().out.splitlines()
    assert [line.split()[0] for line in listed] == list(example_names())
    assert "rgd_2dof" in example_names() and "template" not in example_names()
    assert example_summary("rgd_2dof").startswith("The 2-DOF model of Richard, Germay")
    for name in example_names():
        assert main(["init", "--example", name]) == 0
        out = capsys.readouterr().out
        data = resources.files("torsio").joinpath(f"data/{name}.toml").read_text(encoding="utf-8")
        assert (tmp_path / f"{name}.toml").read_text(encoding="utf-8") == data
        commands = out.split("try: ")[1].strip().split("   or   ")
        for command in commands:  # each runs on the file written, as the CLI parses it
            argv = shlex.split(command)
            assert argv[0] == "torsio" and f"{name}.toml" in argv, command
            build_parser().parse_args(argv[1:])
    assert main(["simulate", "rgd_2dof.toml", "--duration", "5", "--window", "2", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["law"] == "rgd"
    assert main(["init", "--example", "rgd_2dof"]) == 2  # kept without --force
    for wrong in ("nope", "template"):
        assert main(["init", "--example", wrong]) == 2
        err = capsys.readouterr().err
        assert f"--example: no built-in example {wrong!r}" in err and "rgd_wave_pipe" in err
    assert main(["init", "--list", "--example", "rgd_2dof"]) == 2


def test_missing_damping_is_a_warning_and_the_report_says_undamped(tmp_path) -> None:
    from torsio.cli.init import template_text

    text = template_text()
    start = text.index("[damping]")
    undamped = text[:start] + text[text.index("[discretization]") :]
    path = tmp_path / "undamped.toml"
    path.write_text(undamped, encoding="utf-8")
    import subprocess

    # a new process, as a user runs it (pytest records warnings instead of printing them)
    command = [sys.executable, "-m", "torsio.cli", "report", str(path), "--strategy", "A"]
    result = subprocess.run(command, capture_output=True, text=True, check=True)
    assert "warning: " in result.stderr and "undamped" in result.stderr
    assert "Traceback" not in result.stderr
    out = result.stdout
    assert "undamped" in out and "from the file" not in out


def test_map_threads_option(capsys) -> None:
    # each point is integrated alone: the map does not depend on the threads (bit for bit)
    import json

    args = ["map", "--strategy", "A", "--wob", "50kN:200kN:3", "--rpm", "50:120:2", "--json"]
    assert main([*args, "--refine", "0", "--duration", "60", "--window", "20"]) == 0
    default = json.loads(capsys.readouterr().out)
    argv = [*args, "--refine", "0", "--duration", "60", "--window", "20", "--threads", "1"]
    assert main(argv) == 0
    assert json.loads(capsys.readouterr().out)["severity"] == default["severity"]
    assert main([*args, "--threads", "0"]) == 2
    assert "--threads" in capsys.readouterr().err
    assert main([*args, "--threads", "2", "--workers", "2"]) == 2
    assert "--threads" in capsys.readouterr().err


def test_the_cache_key_covers_every_compiled_module() -> None:
    # numba checks a cached kernel against its own file only: every module that defines a
    # compiled function, or a constant one reads, must be in the key of the cache folder
    import torsio

    package = Path(torsio.__file__).resolve().parent
    compiled = {
        path
        for path in package.rglob("*.py")
        if "@njit" in path.read_text(encoding="utf-8") or path.name.endswith("layouts.py")
    }
    assert compiled and compiled <= set(kernel_cache.kernel_sources())


def test_reading_a_configuration_loads_no_numba():
    # modules beside the axial engines import their constants (solvers/axial_layouts.py)
    # at module level; numba comes with the first kernel (solvers/compiled.py), not before
    import subprocess

    code = (
        "import sys; from torsio.examples import builtin_config, rgd_deviated_well_config; "
        "builtin_config(); rgd_deviated_well_config(); "
        "import torsio.axial.stability, torsio.report.axial; "
        "print('numba' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
