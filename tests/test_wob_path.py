"""The weight on bit's path from `torsio map --wob` to the compiled kernel (the core issue:
at most 8 function calls), traced on a 2 x 2 map of the 1-DOF paper model."""

from __future__ import annotations

import traceback

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
