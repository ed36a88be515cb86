"""A full disk loses nothing computed and leaves no truncated file (issue 36, case 11).

Every file goes through :mod:`torsio.output_files`; the disk is made full in-process by
an ``fsync`` that fails with ENOSPC in that module only (what a full disk answers when
the data reach it), or in a subprocess by a file-size limit (``ulimit -f``: every write
past it fails with EFBIG, as a full disk fails with ENOSPC).
"""

from __future__ import annotations

import errno
import json
import os
import subprocess
import sys

import pytest

import torsio.output_files
from torsio.cli import main
from torsio.errors import OutputError
from torsio.output_files import atomic_output, write_text

FULL = os.strerror(errno.ENOSPC)  # "No space left on device"


class _FullDisk:
    """The os module, except that nothing reaches the disk."""

    def __getattr__(self, name: str) -> object:
        return getattr(os, name)

    @staticmethod
    def fsync(descriptor: int) -> None:
        raise OSError(errno.ENOSPC, FULL)


@pytest.fixture
def full_disk(monkeypatch):
    monkeypatch.setattr(torsio.output_files, "os", _FullDisk())


def test_failed_write_keeps_the_old_file_and_leaves_no_temporary(tmp_path, full_disk):
    path = tmp_path / "map.json"
    path.write_text("the previous map")
    with pytest.raises(OutputError) as caught:
        write_text(path, "a new map")
    assert str(path) in str(caught.value) and FULL in str(caught.value)
    assert isinstance(caught.value, OSError)
    assert path.read_text() == "the previous map"
    assert os.listdir(tmp_path) == ["map.json"]


def test_interrupted_writer_leaves_no_temporary(tmp_path):
    with pytest.raises(KeyboardInterrupt), atomic_output(tmp_path / "m.csv") as stream:
        stream.write("rpm,wob\n")
        raise KeyboardInterrupt
    assert os.listdir(tmp_path) == []


def _cli(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


@pytest.mark.parametrize("suffix", [".json", ".npz", ".csv"])
def test_map_on_a_full_disk_prints_the_map(capsys, tmp_path, full_disk, suffix):
    """The completed map is on stdout as JSON, the error names the path, no file is left."""
    option = "--csv" if suffix == ".csv" else "--out"
    path = tmp_path / f"m{suffix}"
    status, out, err = _cli(
        capsys, "map", "--wob", "50 kN:60 kN:2", "--rpm", "50:60:2", option, str(path)
    )
    assert status == 2, err
    assert f"{option}: cannot write {str(path)!r}: {FULL}" in err and "Traceback" not in err
    data = json.loads(out)
    assert len(data["severity"]) == 2 and "out" not in data and "csv" not in data
    assert os.listdir(tmp_path) == []


def test_simulate_csv_and_recording_on_a_full_disk(capsys, tmp_path, full_disk):
    """The time series (what the CSV files would hold) are on stdout as JSON."""
    csv, recording = tmp_path / "s.csv", tmp_path / "r.csv"
    status, out, err = _cli(
        capsys, "simulate", "--duration", "5", "--csv", str(csv), "--recording", str(recording)
    )
    assert status == 2, err
    assert str(csv) in err and str(recording) in err and FULL in err
    data = json.loads(out)
    assert len(data["series"]["time"]) == data["samples"]
    assert os.listdir(tmp_path) == []


def test_drag_plot_and_report_html_on_a_full_disk(capsys, tmp_path, full_disk):
    pytest.importorskip("matplotlib")
    plot = tmp_path / "drag.png"
    status, out, err = _cli(capsys, "drag", "--plot", str(plot))
    assert status == 2 and str(plot) in err and FULL in err, err
    assert "hookload_trip_out" in json.loads(out)
    html = tmp_path / "report.html"
    status, out, err = _cli(capsys, "report", "--json", "--html", str(html))
    assert status == 2 and str(html) in err and "the report is on stdout" in err, err
    assert json.loads(out)
    status, out, err = _cli(capsys, "init", str(tmp_path / "torsio.toml"))
    assert status == 2 and "torsio.toml" in err and FULL in err, err
    assert os.listdir(tmp_path) == []


def _torsio(*argv: str, limit_kib: int | None = None, stdout: object = None):
    code = "import sys; from torsio.cli import console_main; sys.exit(console_main())"
    command = [sys.executable, "-c", code, *argv]
    if limit_kib is not None:  # a file-size limit: writes past it fail (EFBIG)
        command = ["bash", "-c", f'ulimit -f {limit_kib}; exec "$@"', "torsio", *command]
    return subprocess.run(
        command, stdout=stdout or subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=300
    )


def test_stdout_on_a_full_device_is_a_clear_error():
    with open("/dev/full", "w") as full:
        done = _torsio("drag", "--json", stdout=full)
    assert done.returncode == 2, done.stderr
    assert f"cannot write to stdout: {FULL}" in done.stderr and "Traceback" not in done.stderr


def test_real_short_write_leaves_no_truncated_csv(tmp_path):
    """A write that really fails part way (a 4 KiB limit; the table is larger): the CSV
    is not there at all, the map is on stdout (a pipe: no limit)."""
    csv = tmp_path / "m.csv"
    done = _torsio(
        "map", "--wob", "50 kN:60 kN:8", "--rpm", "50:60:8", "--csv", str(csv), limit_kib=4
    )
    assert done.returncode == 2 and str(csv) in done.stderr, done.stderr
    assert os.listdir(tmp_path) == []
    assert len(json.loads(done.stdout)["severity"]) == 8
