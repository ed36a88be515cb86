"""Recordings of rig data (torsio.calibration.recording) and the top drive that follows one
(kind ``recorded``, torsio.physics.recorded_top)."""

from __future__ import annotations

import math
import warnings
from importlib import resources
from types import SimpleNamespace

import numpy as np
import pytest

from torsio.analysis.wave import wave_response
from torsio.calibration.recording import Recording, read_recording
from torsio.config.reading import load_config
from torsio.errors import ConfigError
from torsio.examples import deviated_well_config
from torsio.physics.recorded_top import RecordedTopDrive

HEADER = "time,top_rpm,surface_torque\n"
WELL_TOML = resources.files("torsio").joinpath("data/deviated_well.toml").read_text("utf-8")


def _write(tmp_path, text, name="rig.csv"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_a_recording_reads_in_rpm_and_n_m_by_default(tmp_path):
    # reference: 1 rpm = pi/30 rad/s
    record = read_recording(_write(tmp_path, HEADER + "0,0,0\n0.5,60,1000\n1,120,2000\n"))
    assert record.top_speed.tolist() == pytest.approx([0.0, 2 * math.pi, 4 * math.pi])
    assert record.surface_torque.tolist() == [0.0, 1000.0, 2000.0]
    assert record.bit_speed is None and record.name == "rig.csv"


def test_units_in_the_header_and_an_optional_bit_speed(tmp_path):
    # reference: 1 kN m = 1000 N m, 1 ms = 1e-3 s, 1 ft lbf = 1.3558179483314004 N m
    text = "# rig 7\ntime[ms],top_speed[rad/s],surface_torque[kN*m],bit_rpm,hookload\n"
    text += "0,0,0,0,1\n500,2,1.5,30,1\n1000,4,3,60,1\n"
    record = read_recording(_write(tmp_path, text))
    assert record.time.tolist() == [0.0, 0.5, 1.0]
    assert record.top_speed.tolist() == [0.0, 2.0, 4.0]
    assert record.surface_torque.tolist() == [0.0, 1500.0, 3000.0]
    assert record.bit_speed[-1] == pytest.approx(2 * math.pi)
    feet = read_recording(_write(tmp_path, "time,top_rpm,surface_torque[ft*lbf]\n0,0,0\n1,1,1\n"))
    assert feet.surface_torque[-1] == pytest.approx(1.3558179483314004)


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("time,top_rpm\n0,0\n1,1\n", r"rig\.csv, line 1: .*no column for surface_torque"),
        (HEADER + "0,0,0\n1,zero,0\n", r"rig\.csv, line 3: column top_rpm: 'zero' is not a number"),
        (HEADER + "0,0,0\n1,nan,0\n", r"rig\.csv, line 3: column top_rpm: 'nan' is not a finite"),
        (HEADER + "0,0,0\n2,1,1\n1,1,1\n", r"rig\.csv, line 4: time 1 s does not increase"),
        (HEADER + "0,0,0\n1,1\n", r"rig\.csv, line 3: 2 fields, expected 3"),
        # issue 38 item 4: a thousands separator in a comma CSV makes an extra field
        (HEADER + "0,0,0\n0.02,2,12,503\n", r"line 3: 4 fields, expected 3 .*thousands"),
        # quoted, it is one field of the right column; a letter O for a zero likewise
        (HEADER + '0,0,0\n0.02,2,"12,503"\n', r"line 3: column surface_torque: .*thousands"),
        (HEADER + "0,0,0\n0.02,2,5O3\n", r"line 3: column surface_torque: '5O3' .*letter"),
        ("time,surface_torque,top_rpm\n0,0,0\n1,5O3,2\n", r"line 3: column surface_torque"),
        (HEADER + "0,0,0\n1,1,1\n0.5,1,1\n", r"rig\.csv, line 4: time 0\.5 s does not"),
        ("time,top_rpm,surface_torque[lbs]\n0,0,0\n", r"line 1: .*unknown unit 'lbs'"),
        (HEADER, r"rig\.csv: expected at least 2 samples"),
        ("", r"rig\.csv: the file is empty"),
    ],
)
def test_a_bad_recording_is_an_error_naming_the_file_and_the_line(tmp_path, text, match):
    with pytest.raises(ConfigError, match=match):
        read_recording(_write(tmp_path, text))


def test_gaps_and_spikes_are_warnings_naming_the_line(tmp_path):
    time = [0.1 * i for i in range(40)] + [10.0, 10.1]
    torque = [1000.0 + 10.0 * math.sin(i) for i in range(42)]
    torque[20] = 9000.0
    rows = "".join(f"{t:g},60,{q:g}\n" for t, q in zip(time, torque, strict=True))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        read_recording(_write(tmp_path, HEADER + rows))
    messages = [str(w.message) for w in caught]
    assert any("1 gap in all: line 42: a gap of 6.1 s" in m for m in messages), messages
    assert any("1 surface-torque spike in all: line 22: 9000 N m" in m for m in messages)


def test_spikes_in_a_record_logged_to_10_n_m_are_found_and_counted(tmp_path):
    # a rig logs the torque to 10 N m: on a smooth ramp most samples are their own median,
    # so the median absolute deviation is 0 (the check used to return there, silently);
    # five 5x spikes (a glitch no string makes) are counted and the first three named
    time = 0.01 * np.arange(1000)
    torque = np.round(12e3 * (1.0 - np.exp(-time)), -1)
    spiky = [200, 400, 500, 600, 800]
    torque[spiky] *= 5.0
    rows = "".join(f"{t:.2f},120,{q:g}\n" for t, q in zip(time, torque, strict=True))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        record = read_recording(_write(tmp_path, HEADER + rows))
    messages = [str(w.message) for w in caught if "spike" in str(w.message)]
    assert len(messages) == 1, messages
    # line = index + 2 (the header is line 1)
    assert "5 surface-torque spikes in all (the first 3 named): line 202: " in messages[0]
    assert "line 402: " in messages[0] and "line 502: " in messages[0]
    assert "line 602" not in messages[0]
    assert record.spikes().tolist() == spiky
    # without them: the record linear between the neighbours (exact on a 10 N m grid to 10)
    assert np.abs(record.without_spikes().surface_torque[spiky] - torque[spiky] / 5).max() <= 10


def test_a_break_free_drop_is_not_a_spike():
    # a step of the torque (the string breaking free, a wave reaching the top) is followed
    # sample for sample by the median of 11: no departure, no spike
    torque = np.r_[np.linspace(0.0, 15e3, 300), np.full(300, 11e3)]
    record = Recording(time=np.arange(600.0), top_speed=np.ones(600), surface_torque=torque)
    assert record.spikes().size == 0


def test_a_recording_too_large_is_refused_before_it_is_read(tmp_path, monkeypatch):
    # issue 36 case 14: a 10-million-row file was read (66 s, 6.5 GB) before the run's
    # duration was refused; the size is checked first
    from torsio.calibration import recording

    path = _write(tmp_path, HEADER + "0,0,0\n1,1,1\n")
    monkeypatch.setattr(recording, "MAX_BYTES", 10)
    # the file: 28 bytes of header and two lines of 6 bytes
    with pytest.raises(ConfigError, match=r"^recording: rig\.csv: 4e-05 MB, more than the 1e-05"):
        read_recording(path)


def test_torsio_fit_on_a_line_with_extra_fields_exits_2_naming_the_line(tmp_path, capsys):
    from torsio.cli import main

    config = _write(tmp_path, WELL_TOML, name="well.toml")
    record = _write(tmp_path, HEADER + "0,0,0\n0.01,2,12503\n0.02,2,12,503\n")
    status = main(["fit", str(config), "--recording", str(record), "--fit", "friction_dynamic"])
    error = capsys.readouterr().err
    assert status == 2 and "Traceback" not in error
    assert "rig.csv, line 4: 4 fields, expected 3" in error


def test_a_recording_saved_reads_back(tmp_path):
    record = Recording(
        time=[0.0, 1.0], top_speed=[0.0, 3.0], surface_torque=[0.0, 5.0], bit_speed=[0.0, 1.0]
    )
    record.save(tmp_path / "out.csv")
    again = read_recording(tmp_path / "out.csv")
    assert again.top_speed.tolist() == pytest.approx([0.0, 3.0])
    assert again.bit_speed.tolist() == pytest.approx([0.0, 1.0])


def test_a_recording_of_a_run_draws_its_noise_from_the_seed():
    # reference: the noise written out, relative and Gaussian, the speed's draws first
    time = np.linspace(0.0, 2.0, 201)
    run = SimpleNamespace(
        time=time, top_speed=1.0 + time, surface_torque=2e3 + time, bit_speed=3.0 - time
    )
    record = Recording.from_transient(
        run, torque_noise=0.02, speed_noise=0.01, seed=7, bit_speed=True, name="run"
    )
    draws = np.random.default_rng(7).normal(size=(3, time.size))
    assert np.array_equal(record.time, time) and record.name == "run"
    assert np.array_equal(record.top_speed, run.top_speed * (1.0 + 0.01 * draws[0]))
    assert np.array_equal(record.surface_torque, run.surface_torque * (1.0 + 0.02 * draws[1]))
    assert np.array_equal(record.bit_speed, run.bit_speed * (1.0 + 0.01 * draws[2]))
    clean = Recording.from_transient(run)
    assert np.array_equal(clean.surface_torque, run.surface_torque) and clean.bit_speed is None


def test_the_recorded_top_turns_at_the_recorded_speed():
    # reference: the record itself, linear between its samples (the held top's table)
    record = Recording(
        time=[10.0, 12.0, 14.0, 20.0],
        top_speed=[0.0, 6.0, 4.0, 4.0],
        surface_torque=[0.0, 1.0, 1.0, 1.0],
    )
    system = deviated_well_config().system(strategy="wave")
    system = system.with_top(RecordedTopDrive(recording=record)).at(wob=0.0, rpm=38.2)
    tr = wave_response(
        system, duration=6.0, steady_window=1.0, output_step=system.model.time_step, progress=False
    ).transient
    expected = np.interp(tr.time, record.time - 10.0, record.top_speed)
    assert np.max(np.abs(tr.top_speed - expected)) < 1e-12


def test_the_recorded_kind_reads_its_file_from_the_configuration_folder(tmp_path):
    # the rule of [well] survey = "survey.csv": a relative path is the config file's folder's
    text = WELL_TOML
    (tmp_path / "data").mkdir()
    _write(tmp_path / "data", HEADER + "0,0,0\n5,120,9000\n", name="startup.csv")
    text += '\n[top_drive]\nkind = "recorded"\nrecording = "data/startup.csv"\n'
    _write(tmp_path, text, name="well.toml")
    config = load_config(tmp_path / "well.toml")
    top = config.top_drive.build()
    assert top.name == "recorded" and top.recording.name == "startup.csv"
    assert top.boundary(None).set_speed == pytest.approx(4 * math.pi)


def test_a_missing_recording_file_is_an_error_on_its_key(tmp_path):
    text = WELL_TOML + '\n[top_drive]\nkind = "recorded"\nrecording = "nowhere.csv"\n'
    _write(tmp_path, text, name="well.toml")
    with pytest.raises(ConfigError, match=r"top_drive\.recording: cannot read recording"):
        load_config(tmp_path / "well.toml")


def test_a_recorded_top_drive_takes_no_rpm_reports_the_recorded_speed_and_says_when_outlasted(
    tmp_path, capsys
):
    # issue 36 case 9: --rpm 60 was ignored silently, the JSON said rpm 100 (the file's
    # operation.rpm) "set", and the record was held past its end without a word
    import json

    from torsio.cli import main

    _write(tmp_path, HEADER + "0,0,0\n2,90,9000\n5,90,8000\n", name="startup.csv")
    text = WELL_TOML + '\n[top_drive]\nkind = "recorded"\nrecording = "startup.csv"\n'
    config = str(_write(tmp_path, text, name="well.toml"))
    status = main(["simulate", config, "--wob", "0", "--rpm", "60"])
    error = capsys.readouterr().err
    assert status == 2
    assert "--rpm: the top drive is 'recorded' (top_drive.kind): its speed follows the" in error
    run = ["simulate", config, "--wob", "0", "--duration", "20", "--window", "10", "--json"]
    status = main(run)
    captured = capsys.readouterr()
    data = json.loads(captured.out)
    assert status == 0
    # reference: the record holds 90 rpm from 2 s on, so over the window (10 to 20 s) too
    assert data["rpm_source"] == "top_speed_mean"
    assert data["rpm"] == pytest.approx(90.0, rel=1e-9)
    expected = (
        "the run (20 s) outlasts the recording startup.csv (5 s): the top is held at its last "
        "speed, 90 rpm, for the last 15 s"
    )
    assert data["warnings"] == [expected]
    assert expected in captured.err
