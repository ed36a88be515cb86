"""Calibration from rig data (torsio.calibration.fit, ``torsio fit``; docs/calibration.md).

The recordings are made with torsio itself from known friction factors, the truth: the
built-in deviated well (torsio.examples.deviated_well_config: open hole mu_s 0.35,
mu_d 0.3 below a casing with its own 0.25/0.2), wave strategy, bit off bottom, 60 s
start-ups to 120 and 150 rpm by a SoftTorque top drive (J = 2900 kg m^2) whose set speed
ramps over 5 s, sampled every ~0.01 s; the noisy ones add 2 % (torque) and 1 % (speed)
Gaussian noise, sample by sample, from a fixed seed.
"""

from __future__ import annotations

import json

import attrs
import numpy as np
import pytest

from torsio.analysis.wave import wave_response
from torsio.calibration.fit import fit_recordings
from torsio.calibration.parameters import SystemFamily
from torsio.calibration.recording import Recording
from torsio.calibration.start import closed_form_start
from torsio.cli import main
from torsio.config.reading import load_config
from torsio.config.top_drive import TopDriveConfig
from torsio.errors import ConfigError
from torsio.examples import deviated_well_config
from torsio.physics.top_drives import SoftTorqueTopDrive

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

TRUTH = {"friction_static": 0.35, "friction_dynamic": 0.3}  # deviated_well.toml, open hole
NAMES = ["friction_static", "friction_dynamic"]
SPEEDS = (120.0, 150.0)  # rpm
GRID = {"drag_spacing": 4}  # the grid that made the recordings (the wave model's default)


def _startup(rpm: float, torque_noise: float = 0.0, speed_noise: float = 0.0) -> Recording:
    system = deviated_well_config().system(strategy="wave")
    system = system.with_top(SoftTorqueTopDrive(inertia=2900.0, ramp=5.0)).at(wob=0.0, rpm=rpm)
    tr = wave_response(
        system, duration=60.0, steady_window=6.0, output_step=0.01, progress=False
    ).transient
    return Recording.from_transient(
        tr,
        torque_noise=torque_noise,
        speed_noise=speed_noise,
        seed=int(rpm),
        name=f"startup_{rpm:g}rpm.csv",
    )


@pytest.fixture(scope="module")
def clean():
    return [_startup(rpm) for rpm in SPEEDS]


@pytest.fixture(scope="module")
def noisy():
    return [_startup(rpm, 0.02, 0.01) for rpm in SPEEDS]


def _check_recovered(results) -> None:
    fitted = results.parameters
    assert abs(fitted["friction_dynamic"] - TRUTH["friction_dynamic"]) < 0.01
    assert abs(fitted["friction_static"] - TRUTH["friction_static"]) < 0.05
    for name, spread in zip(results.names, results.uncertainty, strict=True):
        low, high = spread.interval  # the stated two-sigma interval
        assert low <= TRUTH[name] <= high, (name, spread)
        assert spread.identifiable


@pytest.mark.parametrize("which", ["clean", "noisy"])
def test_start_ups_recorded_by_torsio_give_back_their_friction_factors(which, request):
    recordings = request.getfixturevalue(which)
    config = deviated_well_config()
    # the speed as recorded: the drive that made the records (the 0.2 s default smoothing
    # rounds the ramp's corners, 10 N m RMS on the clean records)
    results = fit_recordings(config, recordings, NAMES, speed_smoothing=0.0, **GRID)
    _check_recovered(results)
    # it started from the closed forms, and says so
    start = closed_form_start(SystemFamily(config), recordings, NAMES)
    assert set(start) == set(NAMES)
    assert results.notes()[0].startswith("started from the closed forms")
    assert results.to_dict()["start"]["friction_static"] != pytest.approx(0.35, abs=1e-3)
    assert results.residual < (1.0 if which == "clean" else 0.03 * 12e3)  # N m


def test_clean_and_noisy_start_ups_have_no_spike(clean, noisy):
    # the break-free moment is physics, not a fault of the torque sub
    assert [r.spikes().size for r in clean + noisy] == [0, 0, 0, 0]


def test_a_spike_in_a_record_logged_to_10_n_m_does_not_drive_the_fit(clean):
    # issue 36 case 7: one 5x spike at 30 s in the 120 rpm start-up logged to 10 N m gave
    # mu_s = 2.245 +- 0.049 (identifiable, no warning); the spike is left out, the fit
    # returns the truth of the record (TRUTH) and says what it left out
    record = clean[0]
    torque = np.round(record.surface_torque, -1)
    spike = int(np.searchsorted(record.time, 30.0))
    torque[spike] *= 5.0
    record = attrs.evolve(record, surface_torque=torque, name="rig.csv")
    results = fit_recordings(deviated_well_config(), [record], NAMES, **GRID)
    _check_recovered(results)
    assert results.warnings == (
        "rig.csv: 1 surface-torque spike (at 30.0008 s) left out of the fit: each replaced "
        "by the record linear between its neighbours",
    )
    assert results.to_dict()["warnings"] == list(results.warnings)


def _moving(record: Recording) -> Recording:
    # the 120 rpm start-up from 20 s on: its first sample at 117 rpm, the string sliding
    keep = record.time >= 20.0
    return Recording(
        time=record.time[keep],
        top_speed=record.top_speed[keep],
        surface_torque=record.surface_torque[keep],
        name="moving.csv",
    )


def test_a_record_that_does_not_start_at_rest_cannot_inform_the_static_factor(clean):
    # issue 36 case 8: such a record returned mu_s 0.288 < mu_d 0.301, only "weakly
    # identifiable"; with no break-over recorded (the first speed, 117 rpm, is above the
    # threshold speed 0.5 rad/s of data/deviated_well.toml) mu_s is refused, named
    moving = _moving(clean[0])
    with pytest.raises(
        ConfigError,
        match=r"^fit: friction_static cannot be fitted .*"
        r"moving\.csv starts at 117 rpm, above the threshold speed 4\.77 rpm",
    ):
        fit_recordings(deviated_well_config(), [moving], NAMES, **GRID)
    # with a start-up beside it: said, and the fit stays in the admissible set mu_d <= mu_s
    results = fit_recordings(deviated_well_config(), [moving, clean[1]], NAMES, **GRID)
    assert results.parameters["friction_dynamic"] <= results.parameters["friction_static"]
    assert len(results.warnings) == 1
    assert results.warnings[0].startswith("moving.csv starts at 117 rpm")
    assert "only the other recordings inform friction_static" in results.warnings[0]


def test_the_same_top_drive_and_grid_that_made_the_recordings_return_the_truth(clean):
    # the model that made the recordings: its fit has nothing left to explain
    config = deviated_well_config()
    top = TopDriveConfig("soft-torque", {"inertia": 2900.0, "ramp": 5.0})
    config = attrs.evolve(config, top_drive=top)
    results = fit_recordings(
        config, clean, NAMES, top="configured", rpm=SPEEDS, profile=False, **GRID
    )
    for name, value in results.parameters.items():
        assert value == pytest.approx(TRUTH[name], abs=1e-3)


def test_smoothing_the_recorded_speed_takes_out_the_bias_its_noise_drives(noisy):
    # the recorded speed drives the model: its 1 % noise drives the string too (errors in
    # the variables), which biases the damping fitted to the torque; a centred 0.1 s mean
    # of the speed (10 samples) takes it out. Measured: mu_d -1.1e-3 (sigma 3.3e-4) and
    # alpha +4.8e-3 (1.3e-3) as recorded, -2.3e-4 and +9.4e-4 smoothed, within two sigma;
    # truth: alpha 0.35 1/s of data/deviated_well.toml
    truth = {**TRUTH, "alpha": 0.35}
    names = ["friction_dynamic", "alpha"]
    raw = fit_recordings(
        deviated_well_config(), noisy, names, profile=False, speed_smoothing=0.0, **GRID
    )
    smoothed = fit_recordings(
        deviated_well_config(), noisy, names, profile=False, speed_smoothing=0.1, **GRID
    )
    for name, spread in zip(smoothed.names, smoothed.uncertainty, strict=True):
        low, high = spread.interval
        assert low <= truth[name] <= high, (name, spread)
    error = {r: abs(r.parameters["alpha"] - truth["alpha"]) for r in (raw, smoothed)}
    assert error[smoothed] < 0.5 * error[raw]
    with pytest.raises(ConfigError, match="^speed_smoothing: "):
        fit_recordings(deviated_well_config(), noisy, names, speed_smoothing=-1.0, **GRID)


def test_a_parameter_the_data_cannot_pin_down_is_reported_with_its_interval(noisy, tmp_path):
    # the first 2.5 s of a start-up: the torque has not reached the static friction of the
    # string anywhere below the top (the bit moves after 3.9 s), so the record bounds mu_s
    # from below only; the data allow anything from the sliding factor (0.3) upward
    record = noisy[0]
    early = record.time <= 2.5
    early = Recording(
        time=record.time[early],
        top_speed=record.top_speed[early],
        surface_torque=record.surface_torque[early],
        name="early.csv",
    )
    results = fit_recordings(deviated_well_config(), [early], ["friction_static"], **GRID)
    assert results.weak == ("friction_static",)
    low, high = results.to_dict()["interval"]["friction_static"]
    assert low <= TRUTH["friction_static"] <= high and high - low > 0.2
    assert results.to_dict()["identifiable"] == {"friction_static": False}
    assert results.to_dict()["interval_method"]["friction_static"].startswith("profile: ")
    assert any("weakly identifiable" in note and f"{low:.4g}" in note for note in results.notes())
    _check_the_figure(results, tmp_path / "fit.png")


def _check_the_figure(results, path) -> None:
    # what the figure draws is the results' own data: the record's peak (the break-over,
    # objectives.break_over) and the stated two-sigma interval shaded on the profile
    pytest.importorskip("matplotlib")
    figure = results.plot(path)
    assert path.stat().st_size > 0
    torque_axis, profile_axis = figure.axes
    record = results.recordings[0]
    peak = int(np.argmax(record.surface_torque))
    marked = [ln for ln in torque_axis.lines if ln.get_marker() == "v"][0]
    assert marked.get_xdata()[0] == record.time[peak]
    assert marked.get_ydata()[0] == pytest.approx(record.surface_torque[peak] / 1e3, rel=1e-12)
    (shaded,) = profile_axis.patches
    low, high = results.uncertainty[0].interval  # axvspan: a rectangle from low, high - low wide
    assert (shaded.get_x(), shaded.get_width()) == pytest.approx((low, high - low), rel=1e-12)
    assert profile_axis.get_title() == "friction_static: not identifiable"


def test_torsio_fit_json_has_the_contract_keys(clean, tmp_path, capsys):
    paths = []
    for record in clean:
        record.save(tmp_path / record.name)
        paths += ["--recording", str(tmp_path / record.name)]
    config = deviated_well_config()
    source = tmp_path / "well.toml"
    from importlib import resources

    source.write_text(
        resources.files("torsio").joinpath("data/deviated_well.toml").read_text("utf-8")
    )
    assert config.well is not None
    status = main(
        ["fit", str(source), *paths, "--fit", "friction_dynamic", "--no-profile", "--json"]
    )
    assert status == 0
    data = json.loads(capsys.readouterr().out)
    assert {"parameters", "uncertainty", "residual", "recordings"} <= set(data)
    assert data["parameters"]["friction_dynamic"] == pytest.approx(0.3, abs=1e-3)
    assert data["uncertainty"]["friction_dynamic"] > 0.0
    assert [r["name"] for r in data["recordings"]] == [r.name for r in clean]
    assert data["correlation"] == {"friction_dynamic": {"friction_dynamic": 1.0}}  # one name
    assert data["interval_method"]["friction_dynamic"].startswith("jacobian: the value +- 2")


def test_a_bad_fit_name_is_an_error_naming_it_and_the_valid_ones(tmp_path, capsys):
    record = tmp_path / "rig.csv"
    record.write_text("time,top_rpm,surface_torque\n0,0,0\n1,60,5000\n")
    from importlib import resources

    source = tmp_path / "well.toml"
    source.write_text(
        resources.files("torsio").joinpath("data/deviated_well.toml").read_text("utf-8")
    )
    status = main(["fit", str(source), "--recording", str(record), "--fit", "mu_s"])
    error = capsys.readouterr().err
    assert status != 0
    assert "'mu_s'" in error and "friction_static, friction_dynamic" in error


def test_a_bad_recording_through_the_command_names_the_line(tmp_path, capsys):
    record = tmp_path / "rig.csv"
    record.write_text("time,top_rpm,surface_torque\n0,0,0\n1,sixty,5000\n")
    status = main(["fit", "x.toml", "--recording", str(record), "--fit", "friction_dynamic"])
    assert status != 0
    assert capsys.readouterr().err  # the configuration is read first: it names x.toml
    with pytest.raises(ConfigError, match=r"rig\.csv, line 3"):
        fit_recordings(deviated_well_config(), [record], ["friction_dynamic"], **GRID)


def test_a_fit_without_spread_gives_the_severe_points_of_its_own_map():
    # reference: severity_map of the configuration itself; with sigma 0 every sample is
    # that configuration, so the probability is 1 where it is severe and 0 elsewhere
    from torsio.analysis.maps import severity_map
    from torsio.calibration.fit_results import FitResults
    from torsio.calibration.monte_carlo import severity_probability
    from torsio.calibration.uncertainty import ParameterSpread

    config = deviated_well_config()
    spread = ParameterSpread(0.0, 0.0, 0.0, (0.3, 0.3), "jacobian", True)
    fit = FitResults(
        ("friction_dynamic",),
        (0.3,),
        (0.3,),
        (0.3,),
        (spread,),
        0.0,
        (),
        "torque",
        "recorded",
        0,
        0.0,
        "",
    )
    wob, rpm = [0.0, 160e3], [40.0, 100.0]
    result = severity_probability(config, fit, wob, rpm, samples=2, refine=0)
    reference = severity_map(config.system(strategy="wave"), wob, rpm, refine=0)
    expected = (reference.severity > reference.threshold).astype(float)
    assert result.probability.tolist() == expected.tolist()
    assert expected.min() == 0.0 and expected.max() == 1.0  # both kinds of point
    assert [s["friction_dynamic"] for s in result.samples] == [0.3, 0.3]


def _cli_fit(tmp_path, rows: str, *options: str, config: str = "deviated_well.toml"):
    from importlib import resources

    record = tmp_path / "rig.csv"
    record.write_text("time,top_rpm,surface_torque\n" + rows)
    source = tmp_path / "well.toml"
    source.write_text(resources.files("torsio").joinpath(f"data/{config}").read_text("utf-8"))
    args = ["fit", str(source), "--recording", str(record), "--fit", "friction_dynamic"]
    return main([*args, "--no-profile", *options])


STARTUP_ROWS = "".join(f"{0.1 * i:.1f},{min(12 * i, 120)},{100 * i}\n" for i in range(40))


@pytest.mark.parametrize(
    ("rows", "options", "config", "message"),
    [
        # issue 36 case 14: each named operation.wob, operation.rpm, simulation.steady_window
        # or asked the RGD file for the youngs_modulus it has
        (STARTUP_ROWS, ("--wob", "-1"), "deviated_well.toml", "--wob: expected a weight"),
        (
            "".join(f"{0.1 * i:.1f},0,{100 * i}\n" for i in range(40)),
            (),
            "deviated_well.toml",
            "recording: rig.csv: the top-drive speed never exceeds the threshold speed",
        ),
        (
            "0,0,0\n0.001,60,5000\n",
            (),
            "deviated_well.toml",
            "recording: rig.csv: 2 samples over 0.001 s; a fit needs at least 11 samples",
        ),
        # the wave model's grid only
        (
            STARTUP_ROWS,
            ("--time-step", "1ms", "--strategy", "C"),
            "deviated_well.toml",
            "--time-step: sets the wave model's grid: drop --strategy",
        ),
        (STARTUP_ROWS, ("--time-step", "0"), "deviated_well.toml", "--time-step: expected a"),
        # a file with axial dynamics is fitted off bottom (tests/test_fit_axial.py)
        (
            STARTUP_ROWS,
            ("--wob", "10 kN"),
            "rgd_deviated_well.toml",
            "--wob: 10000 N on a configuration with axial dynamics",
        ),
        # 0 means no smoothing (taken); a negative window is not a window
        (
            STARTUP_ROWS,
            ("--speed-smoothing", "-0.1"),
            "deviated_well.toml",
            "--speed-smoothing: expected a finite time >= 0, got '-0.1'",
        ),
    ],
)
def test_bad_fit_input_names_the_flag_or_the_recording(
    tmp_path, capsys, rows, options, config, message
):
    status = _cli_fit(tmp_path, rows, *options, config=config)
    error = capsys.readouterr().err
    assert status == 2 and "Traceback" not in error
    assert f"torsio fit: error: {message}" in error


def test_the_grid_of_a_fit_is_the_callers_then_the_files_then_contacts_on_every_node():
    from torsio.calibration.fit import DRAG_SPACING, _grid

    config = deviated_well_config()  # [discretization] strategy = "wave", no drag_spacing
    assert _grid(config, {}) == {"drag_spacing": DRAG_SPACING}
    assert _grid(config, {"drag_spacing": 4}) == {"drag_spacing": 4}
    lumped_every_fourth = attrs.evolve(
        config,
        discretization=attrs.evolve(config.discretization, options={"drag_spacing": 4}),
    )
    assert _grid(lumped_every_fourth, {}) == {}  # the file's 4 is kept by config.system


def test_a_surface_casing_in_the_vertical_section_fits(tmp_path, capsys):
    # issue 36, case 2: the casing ending at 400 m, inside the vertical section (kick-off at
    # 500 m), was refused with a drag-spacing error; the fit recovers the open hole's sliding
    # factor that made the recording (0.3, deviated_well.toml)
    from importlib import resources

    text = resources.files("torsio").joinpath("data/deviated_well.toml").read_text("utf-8")
    assert "to_md = 1200.0" in text
    source = tmp_path / "surface_casing.toml"
    source.write_text(text.replace("to_md = 1200.0", "to_md = 400.0"), "utf-8")
    config = load_config(source)
    system = config.system(strategy="wave").with_top(SoftTorqueTopDrive(inertia=2900.0, ramp=5.0))
    run = wave_response(
        system.at(wob=0.0, rpm=120.0), duration=60.0, steady_window=6.0, output_step=0.01,
        progress=False,
    ).transient  # fmt: skip
    record = tmp_path / "startup.csv"
    Recording.from_transient(run, name=record.name).save(record)
    argv = ["fit", str(source), "--recording", str(record), "--fit", "friction_dynamic",
            "--no-profile", "--json"]  # fmt: skip
    assert main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["parameters"]["friction_dynamic"] == pytest.approx(0.3, abs=1e-3)


def test_torsio_fit_runs_on_a_lumped_strategy(clean, tmp_path, capsys):
    # the recordings are the wave model's; fitted on strategy C (10 drill-pipe elements,
    # contacts on every node). The chain's node capacities add up to the torque-and-drag
    # sliding torque exactly (well.string_contacts.node_contacts), so the sliding level
    # reads the open hole's mu_d (0.3, deviated_well.toml) within the 0.01
    paths = []
    for record in clean:
        record.save(tmp_path / record.name)
        paths += ["--recording", str(tmp_path / record.name)]
    source = tmp_path / "well.toml"
    from importlib import resources

    source.write_text(
        resources.files("torsio").joinpath("data/deviated_well.toml").read_text("utf-8")
    )
    fitted = ["--fit", "friction_dynamic", "--strategy", "C", "--dp-elements", "10"]
    status = main(["fit", str(source), *paths, *fitted, "--no-profile", "--json"])
    assert status == 0
    data = json.loads(capsys.readouterr().out)
    assert data["parameters"]["friction_dynamic"] == pytest.approx(0.3, abs=0.01)


@pytest.mark.slow  # about 40 s on 2 quiet cores: 370 runs of the chain, 60 the continuum's
def test_a_lumped_fit_widens_its_intervals_by_what_the_lumping_misreads(noisy):
    # on strategy C with 10 drill-pipe elements the chain reads the wave model's start-ups
    # (truth 0.35 / 0.3, deviated_well.toml) differently from the continuum: the continuum,
    # reading the same records along the profile, is the lumping's part of each interval,
    # and the stated two-sigma intervals hold the truth
    results = fit_recordings(deviated_well_config(), noisy, NAMES, strategy="C", dp_elements=10)
    for name, spread in zip(results.names, results.uncertainty, strict=True):
        low, high = spread.interval
        assert low <= TRUTH[name] <= high, (name, spread)
        assert "continuum" in spread.profile.twin_values
    assert results.uncertainty[0].sigma_grid > 0.01  # mu_s: the lumping's misreading
