"""Sweeps on executors (torsio.analysis.sweep): serial, local processes, a Dask LocalCluster.

Source of the reference numbers: the serial map. Each grid point is integrated
on its own (its own steps and error control), so any executor, chunking or
worker must give bit-for-bit the same S_SS.
"""

from __future__ import annotations

import os
import signal
from pathlib import Path

import numpy as np
import pytest

from torsio.analysis.map_results import SeverityMap
from torsio.analysis.maps import severity_map
from torsio.analysis.sweep import SweepError, SweepInterrupted, run_tasks
from torsio.errors import ConfigError
from torsio.examples import builtin_config
from torsio.physics.system import System

WOB = np.linspace(25e3, 225e3, 6)
RPM = np.linspace(40.0, 140.0, 4)


@pytest.fixture(scope="module")
def system() -> System:
    return builtin_config().system(strategy="C", dp_elements=4)


@pytest.fixture(scope="module")
def serial(system: System) -> SeverityMap:
    return severity_map(system, WOB, RPM, refine=2)


def assert_same_map(result: SeverityMap, reference: SeverityMap) -> None:
    np.testing.assert_array_equal(result.severity, reference.severity)
    np.testing.assert_array_equal(result.critical_wob, reference.critical_wob)
    np.testing.assert_array_equal(result.steps, reference.steps)
    assert result.critical_status == reference.critical_status
    assert result.complete


# --- helpers run by workers (module level, so that they can be pickled) ---------------------
def die_once(marker: str, value: int) -> int:
    """Kill the worker process the first time it runs for this marker file."""
    path = Path(marker)
    if not path.exists():
        path.write_text("died")
        os._exit(1)
    return value * 10


def always_die(value: int) -> int:
    os._exit(1)


def fail(value: int) -> int:
    raise ValueError(f"bad task {value}")


# --- serial and local processes ---------------------------------------------------------------
def test_serial_results_in_task_order() -> None:
    outcome = run_tasks(pow, [(2, 3), (3, 2), (10, 0)])
    assert outcome.results == [8, 9, 1] and outcome.executor == "serial"


def test_chunking_does_not_change_the_map(system: System, serial: SeverityMap) -> None:
    assert_same_map(severity_map(system, WOB, RPM, refine=2, chunk_size=5), serial)


def test_local_processes_give_the_serial_map(system: System, serial: SeverityMap) -> None:
    result = severity_map(system, WOB, RPM, refine=2, executor=2, chunk_size=4)
    assert_same_map(result, serial)
    assert result.info["executor"] == "processes(2)"


def test_thread_pool_gives_the_serial_map(system: System, serial: SeverityMap) -> None:
    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(2) as pool:  # chunks run concurrently in two threads
        result = severity_map(system, WOB, RPM, refine=2, executor=pool, chunk_size=2)
    assert_same_map(result, serial)


def test_dead_process_worker_is_replaced_and_its_task_retried(tmp_path) -> None:
    tasks = [(str(tmp_path / "marker"), k) for k in range(4)]
    outcome = run_tasks(die_once, tasks, executor=2, retries=2)
    assert outcome.results == [0, 10, 20, 30]
    assert outcome.retries >= 1


def test_task_that_keeps_killing_its_worker_fails_clearly() -> None:
    with pytest.raises(SweepError, match="lost a worker process"):
        run_tasks(always_die, [(1,)], executor=1, retries=1)


def test_task_errors_are_not_retried() -> None:
    with pytest.raises(ValueError, match="bad task 1"):
        run_tasks(fail, [(1,)], executor=None, retries=3)


def test_interrupt_returns_finished_results() -> None:
    def progress(done: int, total: int) -> None:
        raise KeyboardInterrupt

    with pytest.raises(SweepInterrupted) as info:
        run_tasks(pow, [(2, 2), (3, 3)], progress=progress)
    assert info.value.results == [4, None] and info.value.done == 1


def test_bad_executor_specifications() -> None:
    with pytest.raises(ConfigError, match="workers"):
        run_tasks(pow, [(2, 2)], executor=0)
    with pytest.raises(ConfigError, match="executor"):
        run_tasks(pow, [(2, 2)], executor=3.5)  # type: ignore[arg-type]
    with pytest.raises(ConfigError, match="retries"):
        run_tasks(pow, [(2, 2)], retries=-1)


# --- Dask ---------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def cluster():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None, silence_logs=40
    ) as local:
        with distributed.Client(local) as client:
            yield local, client


def test_dask_executor_gives_the_serial_map(cluster, system: System, serial: SeverityMap) -> None:
    _, client = cluster
    result = severity_map(system, WOB, RPM, refine=2, executor=client.get_executor(), chunk_size=3)
    assert_same_map(result, serial)


def test_dask_scheduler_address_gives_the_serial_map(
    cluster, system: System, serial: SeverityMap
) -> None:
    local, _ = cluster
    result = severity_map(system, WOB, RPM, refine=2, executor=local.scheduler_address)
    assert_same_map(result, serial)
    assert result.info["executor"] == f"dask({local.scheduler_address})"


def test_dask_worker_killed_mid_map_is_retried(
    cluster, system: System, serial: SeverityMap
) -> None:
    local, client = cluster
    before = client.run(os.getpid)
    killed: list[int] = []

    def kill_a_worker(done: int, total: int) -> None:
        if not killed:  # after the first chunk: the other chunks are queued or running
            pid = sorted(before.values())[0]
            os.kill(pid, signal.SIGKILL)
            killed.append(pid)

    result = severity_map(
        system,
        WOB,
        RPM,
        refine=2,
        executor=client.get_executor(),
        chunk_size=1,
        progress=kill_a_worker,
    )
    assert killed
    assert_same_map(result, serial)
    # the scheduler's log shows chunks lost with the killed worker and run again: running
    # on it, or (on a loaded machine, where the kill can come after they finished) done and
    # held in its memory, which the scheduler releases and recomputes elsewhere
    log = client.run_on_scheduler(
        lambda dask_scheduler: [(t[1], t[2], t[4]) for t in dask_scheduler.transition_log]
    )
    assert any(
        start in ("processing", "memory") and end == "released" and "worker" in stimulus
        for start, end, stimulus in log
    )
    client.wait_for_workers(2, timeout=60)
    assert killed[0] not in client.run(os.getpid).values()  # the nanny started a new one


def test_unreachable_scheduler_is_a_clear_error(system: System) -> None:
    with pytest.raises(
        ConfigError,
        match=r"cannot reach the Dask scheduler at "
        r"'tcp://127.0.0.1:9' within 1 s",
    ):
        severity_map(system, WOB, RPM, executor="tcp://127.0.0.1:9", timeout=1.0)


def test_a_serial_map_imports_nothing_of_dask() -> None:
    # importing distributed costs about 0.8 s; a serial map (the CLI's default) must not pay
    # for it: the Dask error types are looked up only once a Dask executor is in use
    import subprocess
    import sys

    pytest.importorskip("distributed")
    code = (
        "import sys\n"
        "from torsio.cli import main\n"
        "main(['map', '--strategy', 'A', '--wob', '50kN:200kN:2', '--rpm', '60:100:2',"
        " '--json'])\n"
        "loaded = sorted(m for m in sys.modules if m.split('.')[0] in ('dask', 'distributed'))\n"
        "print('DASK', loaded, file=sys.stderr)\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert "DASK []" in result.stderr, result.stderr
