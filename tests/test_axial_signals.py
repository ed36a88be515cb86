"""Axial runs go in chunks and stop on SIGINT / SIGTERM (issue 36, case 6).

Sources: a run in chunks is the same arithmetic as one call of every step (the kernel keeps
its state and sums between calls), so the two agree exactly; the command line's exit codes
130 (SIGINT) and 143 (SIGTERM) and the 2 s bound are the issue's.
"""

from __future__ import annotations

import signal
import subprocess
import sys
import time
from importlib import resources

import numpy as np
import pytest

from torsio.analysis.axial_transient import _chain_chunk, run_kernel
from torsio.axial import rgd_example, rgd_two_dof_example
from torsio.solvers import axial_layouts as slot
from torsio.solvers.axial_run_setup import RunOptions, run_setup

DEVIATED = resources.files("torsio").joinpath("data/rgd_deviated_well.toml")


def _setup():
    options = RunOptions(10.0, 5.0)
    return run_setup(rgd_two_dof_example(), rgd_example(), 100e3, 60.0, options)


def test_a_run_in_chunks_is_the_run_in_one_call():
    chunked, whole = _setup(), _setup()
    every = 10
    rows = (chunked.steps - 1) // every + 1
    samples_chunked, samples_whole = np.zeros((rows, 13)), np.zeros((rows, 13))
    calls = []
    stats = run_kernel(chunked, samples_chunked, every, lambda done, total: calls.append(done))
    settings = whole.settings.copy()
    settings[slot.SAMPLE_EVERY] = every
    settings[slot.FIRST_STEP], settings[slot.STEPS] = 0, whole.steps
    single = np.zeros(len(slot.STATS))
    _chain_chunk(whole, settings, single, samples_whole)
    assert len(calls) > 1 and calls[-1] == chunked.steps  # 5160 steps, first chunk 1000
    np.testing.assert_array_equal(stats, single)
    np.testing.assert_array_equal(samples_chunked, samples_whole)
    np.testing.assert_array_equal(chunked.theta, whole.theta)


@pytest.mark.parametrize(("name", "code"), [("SIGINT", 130), ("SIGTERM", 143)])
def test_a_long_axial_run_stops_within_two_seconds(tmp_path, name, code):
    text = DEVIATED.read_text(encoding="utf-8")
    path = tmp_path / "fine.toml"
    path.write_text(text.replace('element_length = "100 m"', 'element_length = "25 m"'))
    command = [sys.executable, "-m", "torsio", "simulate", str(path), "--duration", "20"]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    time.sleep(6.0)
    assert process.poll() is None, "the run ended before the signal"
    sent = time.perf_counter()
    process.send_signal(getattr(signal, name))
    _, err = process.communicate(timeout=30)
    assert process.returncode == code, err.decode()
    assert time.perf_counter() - sent < 2.0
    assert b"Traceback" not in err
