"""Maps over (weight on bit, rpm) of axial-torsional runs (torsio.analysis.axial_maps).

Reference: every point of a map is the single run of torsio.analysis.axial_transient.simulate_axial
with the same options (the same engine, so equal to round-off), and its growth rate the
rightmost root of torsio.axial.stability."""

from __future__ import annotations

import json
import time

import numpy as np
import pytest
from axial_files import pipe_chain

from torsio.analysis.axial_maps import axial_map
from torsio.analysis.axial_transient import simulate_axial
from torsio.axial.rgd import rgd_example
from torsio.axial.stability import drilling_stability
from torsio.errors import ConfigError
from torsio.model.axial_assembly import rgd_two_dof_example, tube_section

ASSEMBLY = rgd_two_dof_example()
BIT = rgd_example()
WOBS, RPMS = [90e3, 130e3, 170e3], [50.0, 120.0]


def test_every_point_of_the_map_is_the_single_run():
    grid = axial_map(ASSEMBLY, BIT, WOBS, RPMS, duration=30.0, window=15.0, growth_rate=True)
    assert grid.severity.shape == (len(RPMS), len(WOBS))  # severity[i][j] at rpm[i], wob[j]
    for i, rpm in enumerate(RPMS):
        for j, wob in enumerate(WOBS):
            run = simulate_axial(ASSEMBLY, BIT, wob, rpm, duration=30.0, window=15.0, samples=0)
            assert grid.severity[i, j] == pytest.approx(run.severity, rel=1e-12)
            assert grid.stick_fraction[i, j] == run.stick_fraction
            assert grid.off_bottom_fraction[i, j] == run.axial.off_bottom_fraction
            assert grid.rop[i, j] == pytest.approx(run.axial.rop_mean, rel=1e-12)
            assert grid.mse[i, j] == pytest.approx(run.axial.mse_mean, rel=1e-12)
            assert grid.axial_severity[i, j] == pytest.approx(run.axial.axial_severity, rel=1e-12)
            assert grid.growth_rate is not None
            rate = drilling_stability(ASSEMBLY, BIT, wob, rpm).growth_rate
            assert grid.growth_rate[i, j] == pytest.approx(rate, rel=1e-12)


def test_the_map_gives_design_keys_as_plain_json():
    grid = axial_map(ASSEMBLY, BIT, WOBS[:2], RPMS[:1], duration=10.0, window=5.0)
    data = json.loads(json.dumps(grid.to_dict()))
    for key in ("wob", "rpm", "severity", "rop", "mse", "stick_fraction", "off_bottom_fraction"):
        assert key in data
    assert np.shape(data["rop"]) == (1, 2)
    assert data["growth_rate"] is None


# --- where the points run: the same map to the bit -----------------------------------------
FIELDS = ("severity", "axial_severity", "stick_fraction", "off_bottom_fraction", "rop", "mse")
CHAIN = pipe_chain(2, tube_section(900.0, 2.1e11, 8.1e10, 7850.0, 3.4e-3, 1.5e-5), 29981.3, 230.0)


def _same_to_the_bit(first, second):
    for name in (*FIELDS, "growth_rate"):
        np.testing.assert_array_equal(getattr(first, name), getattr(second, name), err_msg=name)


def _small_map(assembly, **where):
    return axial_map(assembly, BIT, WOBS, RPMS, duration=10.0, window=5.0, growth_rate=True,
                     **where)  # fmt: skip


@pytest.mark.parametrize("assembly", [ASSEMBLY, CHAIN], ids=["2-DOF", "chain"])
def test_threads_and_processes_give_the_serial_map_to_the_bit(assembly):
    # reference: the map run point after point on one thread
    serial = _small_map(assembly, threads=1)
    assert serial.executor == "threads(1)"
    threaded = _small_map(assembly, threads=2)
    assert threaded.executor == "threads(2)"
    _same_to_the_bit(serial, threaded)
    processes = _small_map(assembly, executor=2, chunk_size=2)
    assert processes.executor == "processes(2)"
    _same_to_the_bit(serial, processes)


def test_a_dask_scheduler_gives_the_serial_map_to_the_bit():
    distributed = pytest.importorskip("distributed")
    serial = _small_map(ASSEMBLY, threads=1)
    with distributed.LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=False,
        protocol="tcp://",
        host="127.0.0.1",
        dashboard_address=None,
        silence_logs=40,
    ) as cluster:
        on_dask = _small_map(ASSEMBLY, executor=cluster.scheduler_address, timeout=10.0)
    assert on_dask.executor == f"dask({cluster.scheduler_address})"
    _same_to_the_bit(serial, on_dask)


def test_progress_counts_every_point():
    seen = []
    axial_map(ASSEMBLY, BIT, WOBS, RPMS[:1], duration=2.0, window=1.0, threads=2,
              progress=lambda done, total: seen.append((done, total)))  # fmt: skip
    assert sorted(seen) == [(1, 3), (2, 3), (3, 3)]


@pytest.mark.parametrize(
    ("where", "key"),
    [({"threads": 0}, "threads"), ({"threads": 2, "executor": 2}, "threads"),
     ({"executor": 2, "chunk_size": 0}, "chunk_size")],
)  # fmt: skip
def test_bad_parallel_options_name_their_key(where, key):
    with pytest.raises(ConfigError) as info:
        axial_map(ASSEMBLY, BIT, WOBS[:1], RPMS[:1], duration=2.0, window=1.0, **where)
    assert info.value.key == key


@pytest.mark.slow
def test_a_21_by_21_map_of_the_2dof_model_takes_under_a_minute():
    axial_map(ASSEMBLY, BIT, [100e3], [60.0], duration=2.0, window=1.0)  # compiled, cached
    start = time.perf_counter()
    axial_map(ASSEMBLY, BIT, np.linspace(80e3, 200e3, 21), np.linspace(30.0, 200.0, 21))
    assert time.perf_counter() - start < 60.0
