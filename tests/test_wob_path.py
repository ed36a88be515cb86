"""The weight on bit's path from `torsio map --wob` to the compiled kernel (the core issue:
at most 8 function calls, checked once), traced on a 2 x 2 map of the 1-DOF paper model."""

from __future__ import annotations

import traceback

import numpy as np

import torsio.analysis.maps as maps
import torsio.solvers.batch as batch
from torsio.cli import main


def test_the_weight_on_bit_reaches_the_kernel_in_at_most_eight_calls(monkeypatch, capsys):
    # the stack at the compiled kernel's call, from the CLI function that parses --wob; the
    # executor's frames (analysis/sweep.py) carry a task, not the weight, and do not count
    stacks = []
    original = batch._run_compiled

    def traced(arguments, threads):
        stacks.append(traceback.extract_stack()[:-1])
        return original(arguments, threads)

    monkeypatch.setattr(batch, "_run_compiled", traced)
    argv = ["map", "--strategy", "A", "--wob", "50e3:150e3:2", "--rpm", "40:120:2", "--json"]
    assert main(argv) == 0
    capsys.readouterr()
    frames = [f for f in stacks[0] if "/torsio/" in f.filename.replace("\\", "/")]
    names = [f"{f.filename.split('/torsio/')[-1]}:{f.name}" for f in frames]
    start = names.index("cli/map.py:_run")  # where --wob becomes an array of weights
    path = [n for n in names[start + 1 :] if not n.startswith("analysis/sweep.py")]
    assert len(path) + 1 <= 8, path  # + 1: the call of the kernel itself


def test_the_weight_on_bit_is_checked_once_on_its_way(monkeypatch, capsys):
    # the map checks its axes (analysis/map_runs._axis); its chunks reach the engine as
    # BatchPoints, which the batch's own check (batch_results.batch_points) passes through
    import torsio.analysis.map_runs as map_runs
    import torsio.solvers.batch_results as batch_results

    checks = []
    axis, points = map_runs._axis, batch_results.batch_points

    def counted_axis(key, values, positive):
        checks.append(("axis", key))
        return axis(key, values, positive)

    def counted_points(system, wob, rpm):
        if not isinstance(wob, batch_results.BatchPoints) and np.size(wob):
            checks.append(("batch", "wob"))
        return points(system, wob, rpm)

    monkeypatch.setattr(map_runs, "_axis", counted_axis)
    monkeypatch.setattr(maps, "_axis", counted_axis)
    monkeypatch.setattr(batch, "batch_points", counted_points)
    argv = ["map", "--strategy", "A", "--wob", "50e3:150e3:2", "--rpm", "40:120:2", "--json"]
    assert main(argv) == 0
    capsys.readouterr()
    assert checks.count(("axis", "wob")) + checks.count(("batch", "wob")) == 1, checks
