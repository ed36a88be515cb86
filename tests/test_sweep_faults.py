"""Faults of the machinery that runs sweeps: stalled, lost or silent executors (issue 12).

Real processes and real sockets on 127.0.0.1 only. Each fault must end in a
:class:`~torsio.errors.TorsioError` that says what happened and carries the
results finished so far, and leave no worker process behind.
"""

from __future__ import annotations

import os
import socket
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import pytest

from torsio.analysis.sweep import SweepError, connect_dask, run_tasks
from torsio.errors import ConfigError


# --- helpers run by workers (module level, so that they can be pickled) ---------------------
def sleep_then(value: int, seconds: float) -> int:
    time.sleep(seconds)
    return value


def record_pid_and_sleep(folder: str, seconds: float) -> int:
    Path(folder, f"{os.getpid()}.pid").write_text("")
    time.sleep(seconds)
    return os.getpid()


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    # a zombie has ended; only its parent has not read its status yet
    try:
        return Path(f"/proc/{pid}/stat").read_text().split()[2] != "Z"
    except OSError:
        return False


def _wait_until_gone(pids: list[int], seconds: float) -> list[int]:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline and any(_alive(p) for p in pids):
        time.sleep(0.2)
    return [p for p in pids if _alive(p)]


# --- process pools ------------------------------------------------------------------------------
def test_no_progress_ends_with_the_finished_results() -> None:
    """One task finishes at once, the other not within the limit: a SweepError with the first."""
    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(2) as pool:
        with pytest.raises(SweepError, match=r"no task finished within 1\.5 s.*1 of 2") as caught:
            run_tasks(sleep_then, [(1, 0.0), (2, 3.0)], executor=pool, no_progress_timeout=1.5)
    assert caught.value.results == [1, None]


@pytest.mark.slow
def test_no_progress_on_processes_stops_the_workers(tmp_path) -> None:
    """The same on a process pool the sweep owns: the hanging worker is ended with it."""
    with pytest.raises(SweepError, match=r"no task finished within 20 s") as caught:
        run_tasks(
            record_pid_and_sleep, [(str(tmp_path), 600.0)], executor=1, no_progress_timeout=20.0
        )
    assert caught.value.results == [None]
    workers = [int(p.stem) for p in tmp_path.glob("*.pid")]
    assert workers and _wait_until_gone(workers, 10.0) == []


def test_a_watched_process_ends_with_its_parent() -> None:
    """watch_parent (the pools' worker initializer) ends a process whose parent is killed."""
    child = (
        "import os, sys, time; from torsio.analysis.sweep import watch_parent; "
        "watch_parent(os.getppid()); print(os.getpid(), flush=True); time.sleep(120)"
    )
    parent = subprocess.Popen(
        ["/bin/sh", "-c", f'"{sys.executable}" -c "{child}"; sleep 120'],
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert parent.stdout is not None
        pid = int(parent.stdout.readline())
        assert _alive(pid)
    finally:
        parent.kill()
        parent.wait()
    assert _wait_until_gone([pid], 10.0) == []


@pytest.mark.slow
def test_workers_do_not_outlive_a_killed_parent(tmp_path) -> None:
    """SIGKILL to the process that owns a pool: its workers end by themselves."""
    script = textwrap.dedent(
        f"""
        import sys
        sys.path.insert(0, {str(Path(__file__).parent)!r})
        from test_sweep_faults import record_pid_and_sleep
        from torsio.analysis.sweep import run_tasks
        if __name__ == "__main__":
            run_tasks(record_pid_and_sleep, [({str(tmp_path)!r}, 120.0)] * 2, executor=2)
        """
    )
    parent = subprocess.Popen([sys.executable, "-c", script])
    try:
        deadline = time.monotonic() + 60.0
        while len(list(tmp_path.glob("*.pid"))) < 2 and time.monotonic() < deadline:
            time.sleep(0.2)
        workers = [int(p.stem) for p in tmp_path.glob("*.pid")]
        assert len(workers) == 2
    finally:
        parent.kill()
        parent.wait()
    assert _wait_until_gone(workers, 10.0) == []


# --- Dask schedulers that are not what they seem ------------------------------------------------
def _server(reply: bytes | None) -> tuple[socket.socket, int, threading.Event]:
    """A TCP server on 127.0.0.1 that accepts and then says ``reply`` (or nothing, ever)."""
    server = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    server.bind(("127.0.0.1", 0))
    server.listen(8)
    stop = threading.Event()
    held: list[socket.socket] = []

    def serve() -> None:
        server.settimeout(0.2)
        while not stop.is_set():
            try:
                connection, _ = server.accept()
            except (TimeoutError, OSError):
                continue
            held.append(connection)
            if reply is not None:
                try:
                    connection.recv(4096)
                    connection.sendall(reply)
                except OSError:
                    pass
        for connection in held:
            connection.close()
        server.close()

    threading.Thread(target=serve, daemon=True).start()
    return server, server.getsockname()[1], stop


@pytest.mark.parametrize(
    "reply",
    [None, b"HTTP/1.1 200 OK\r\nContent-Length: 2\r\nConnection: close\r\n\r\nok"],
    ids=["silent", "http"],
)
def test_scheduler_address_that_is_not_a_scheduler(reply) -> None:
    pytest.importorskip("distributed")
    _, port, stop = _server(reply)
    start = time.monotonic()
    try:
        with pytest.raises(ConfigError, match=rf"scheduler.*127\.0\.0\.1:{port}.*within 2 s"):
            connect_dask(f"tcp://127.0.0.1:{port}", timeout=2.0)
    finally:
        stop.set()
    # not a hang: the --timeout plus the few seconds the issue allows (the connecting
    # thread is given up 2 s after the timeout)
    assert time.monotonic() - start < 2.0 + 10.0


def test_scheduler_without_workers() -> None:
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=0, processes=False, dashboard_address=None, silence_logs=40
    ) as cluster:
        with pytest.raises(ConfigError, match="has no worker after 5 s"):
            connect_dask(cluster.scheduler_address, timeout=5.0)


# --- torsio map ended by a signal ---------------------------------------------------------------
def _descendants(pid: int) -> list[int]:
    children: dict[int, list[int]] = {}
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        children.setdefault(int(fields[1]), []).append(int(stat.parent.name))
    found, queue = [], [pid]
    while queue:
        for child in children.get(queue.pop(), []):
            found.append(child)
            queue.append(child)
    return found


@pytest.mark.slow
def test_sigterm_to_a_map_on_two_workers(tmp_path) -> None:
    """SIGTERM: within 10 s no process of the map is left, and the partial file holds its points."""
    from torsio.analysis.map_results import load_map

    out = tmp_path / "m.json"
    command = [sys.executable, "-m", "torsio", "map", "--workers", "2", "--strategy", "A"]
    command += ["--wob", "25kN:225kN:15", "--rpm", "40:140:15", "--refine", "0"]
    command += ["--engine", "numpy", "--out", str(out)]
    process = subprocess.Popen(command, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 120.0
        workers: list[int] = []
        while time.monotonic() < deadline and len(workers) < 2:
            time.sleep(0.5)
            workers = [p for p in _descendants(process.pid) if _alive(p)]
        assert len(workers) >= 2, "the map never started its workers"
        time.sleep(15.0)  # let some chunks finish
        family = [process.pid, *_descendants(process.pid)]
        process.terminate()  # SIGTERM
        _, err = process.communicate(timeout=30.0)
    finally:
        if process.poll() is None:
            process.kill()
    assert process.returncode == 143, err
    assert "partial results written" in err and "Traceback" not in err
    assert _wait_until_gone(family, 10.0) == []
    partial = load_map(tmp_path / "m.partial.json")  # validated: done points have values
    assert not partial.complete and not (tmp_path / "m.json").exists()
