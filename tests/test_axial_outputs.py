"""The outputs of axial-torsional runs and maps through the commands every model uses:
``torsio simulate --csv --plot --recording`` and ``torsio map --plot --csv --out`` on the
built-in ``rgd_2dof.toml``, the map's critical weight on bit, its files and its partial
map on Ctrl-C.

References: every file is read back against the same run in memory
(:func:`torsio.analysis.axial_transient.simulate_axial`, the same deterministic engine, so equal to
the digits the file keeps); the critical weight on bit against its definition (the lowest
weight on bit above which every point of the row is severe, the paper's Fig. 6, as the
torsional maps read it from the grid) applied to the single runs of each point; the
growth rate's change of sign against the rightmost root of torsio.axial.stability.
"""

from __future__ import annotations

import json
from importlib import resources

import numpy as np
import pytest

from torsio.analysis.axial_maps import _sign_change, axial_map
from torsio.analysis.axial_transient import simulate_axial
from torsio.analysis.map_results import MapInterrupted, load_map
from torsio.analysis.transient import simulate
from torsio.analysis.transient_results import TransientResults
from torsio.axial.rgd import rgd_example
from torsio.axial.stability import drilling_stability
from torsio.calibration.recording import read_recording
from torsio.cli import main
from torsio.examples import builtin_config
from torsio.model.axial_assembly import rgd_two_dof_example
from torsio.physics.top_drives import TorqueTopDrive
from torsio.solvers.axial_layouts import SAMPLE_COLUMNS, SAMPLE_UNITS

EXAMPLE = str(resources.files("torsio").joinpath("data/rgd_2dof.toml"))
TIMES = ["--duration", "20", "--window", "10"]
ASSEMBLY, BIT = rgd_two_dof_example(), rgd_example()


def run_json(capsys, *args):
    status = main([*args, "--json"])
    captured = capsys.readouterr()
    assert status == 0, captured.err
    return json.loads(captured.out)


def test_simulate_writes_csv_plot_and_recording_of_the_run(capsys, tmp_path):
    files = {name: tmp_path / f"run.{suffix}" for name, suffix in
             (("csv", "csv"), ("plot", "png"), ("recording", "rec.csv"))}  # fmt: skip
    flags = [item for name, path in files.items() for item in (f"--{name}", str(path))]
    data = run_json(capsys, "simulate", EXAMPLE, *TIMES, *flags)
    assert {name: data[name] for name in files} == {k: str(v) for k, v in files.items()}
    run = simulate_axial(ASSEMBLY, BIT, 100e3, 60.0, duration=20.0, window=10.0)
    assert data["severity"] == run.severity  # the file's run is this run
    # the CSV: every signal by name, to its 10 significant digits
    header = files["csv"].read_text().splitlines()[0].split(",")
    assert header == [f"{n}_{u}" for n, u in zip(SAMPLE_COLUMNS, SAMPLE_UNITS, strict=True)]
    table = np.loadtxt(files["csv"], delimiter=",", skiprows=1)
    for k, name in enumerate(SAMPLE_COLUMNS):
        np.testing.assert_allclose(table[:, k], run.signal(name), rtol=1e-9, atol=1e-12)
    # the recording, read as torsio fit reads it: the run's surface torque and speeds
    recording = read_recording(files["recording"])
    np.testing.assert_allclose(recording.time, run.time, rtol=1e-12)
    np.testing.assert_allclose(recording.surface_torque, run.surface_torque, rtol=1e-12)
    np.testing.assert_allclose(recording.top_speed, run.top_speed, rtol=1e-12)
    np.testing.assert_allclose(recording.bit_speed, run.bit_speed, rtol=1e-12, atol=1e-12)
    assert files["plot"].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_series_of_the_json_are_the_signals():
    # reference: the samples of the run itself, by name
    run = simulate_axial(ASSEMBLY, BIT, 100e3, 60.0, duration=2.0, window=1.0)
    series = run.to_dict(series=True)["series"]
    assert list(series) == list(SAMPLE_COLUMNS)
    assert series["surface_torque"] == run.surface_torque.tolist()


def test_an_axial_run_is_a_transient_result_with_every_runs_json_keys():
    # one results class: the keys of a torsional run's JSON that are not its model's are in
    # an axial run's, each by its definition (TransientResults.run_keys)
    run = simulate_axial(ASSEMBLY, BIT, 100e3, 60.0, duration=2.0, window=1.0)
    torsional = simulate(builtin_config().system(strategy="A").at(wob=100e3, rpm=60.0))
    assert type(run) is type(torsional) is TransientResults and run.system is None
    data = run.to_dict()
    model_keys = {"dofs", "strategy", "bit_radius", "output_step_s"}  # the System's
    assert set(torsional.to_dict()) - model_keys <= set(data)
    assert set(run.run_keys()) == set(torsional.run_keys())
    omega = 60.0 * 2 * np.pi / 60  # Ω₀ [rad/s] of 60 rpm
    assert data["omega_rad_s"] == pytest.approx(omega, rel=1e-15)
    assert data["severity"] == pytest.approx(
        (data["bit_speed_max"] - data["bit_speed_min"]) / (2 * omega), rel=1e-12
    )  # Eq. 12
    assert data["severe"] == (data["severity"] > 0.8)  # the paper's threshold
    assert data["mean_bit_torque"] == data["torque_mean"]  # the window's, every step
    # the stuck fraction counted below every engine's threshold (analysis.severity)
    assert (data["stick_threshold"], data["rpm_source"], data["law"]) == (0.1, "set", "rgd")
    assert data["samples"] == run.time.size and data["duration_s"] == 2.0


def test_an_axial_runs_window_and_top_speed_are_its_json_and_a_torque_top_has_no_set_speed():
    # the window's samples and the mean top speed as the axial engine's JSON reads them
    # (its samples end before the run: every k-th step); a torque-driven top has no set
    # speed and the run's rpm is the one it was given (S_SS is read against its Ω₀)
    top = TorqueTopDrive(inertia=2900.0, torque=6000.0)
    for samples in (4000, 5):
        run = simulate_axial(ASSEMBLY, BIT, 100e3, 60.0, duration=5.0, window=2.0,
                             top_drive=top, samples=samples)  # fmt: skip
        data = run.to_dict()
        assert run.time[-1] < run.duration == 5.0
        assert run.top_speed_mean == data["top_speed_mean"]
        assert run.top_speed_mean == run.top_speed[run.window_mask].mean()
        assert (data["rpm"], data["rpm_source"]) == (60.0, "given")
        assert "no set speed" in run.plot_label
    empty = simulate_axial(ASSEMBLY, BIT, 100e3, 60.0, duration=2.0, window=1.0, samples=0)
    assert np.isnan(empty.top_speed_mean) and empty.to_dict()["top_speed_mean"] is None
    with pytest.raises(AttributeError, match="keeps no twists"):
        empty.bit_twist  # noqa: B018


def test_the_critical_wob_of_an_rgd_map_is_its_severity_threshold_crossing(capsys, tmp_path):
    """The critical weight on bit is read from the map's own S_SS (the torsional maps'
    definition): the RGD 2-DOF's linear growth rate does not change sign along the weight
    on bit at any speed (its boundary runs along the rpm, near 153 rpm: torsio report),
    so there is no linear-stability weight on bit to compare with; the reference is the
    definition applied to the single runs of each point."""
    out = tmp_path / "map.json"
    grid = ["--wob", "80kN:120kN:2", "--rpm", "60:120:2", "--threshold", "0.9", "--refine", "0"]
    files = ["--out", str(out), "--plot", str(tmp_path / "map.png")]
    data = run_json(capsys, "map", EXAMPLE, *grid, *TIMES, *files, "--csv", str(tmp_path / "m.csv"))
    wobs, expected = [80e3, 120e3], []
    for rpm in (60.0, 120.0):
        severity = [simulate_axial(ASSEMBLY, BIT, w, rpm, duration=20.0, window=10.0,
                                   samples=0).severity for w in wobs]  # fmt: skip
        severe = [s > 0.9 for s in severity]
        if not severe[-1]:
            expected.append(("none", None))
        elif all(severe):
            expected.append(("below_range", None))
        else:  # the cell of the crossing, its middle (no bisection: --refine 0)
            expected.append(("grid", 0.5 * (wobs[0] + wobs[1])))
    assert list(zip(data["critical_status"], data["critical_wob"], strict=True)) == expected
    assert ("grid", 100e3) in expected  # the grid crosses the threshold on one row
    assert data["stability_wob"] == [None, None]
    # the saved map is the map, its layers too
    saved = load_map(out)
    assert saved.to_dict()["rop"] == data["rop"] and saved.to_dict()["mse"] == data["mse"]
    assert saved.critical_status == tuple(data["critical_status"])
    assert (tmp_path / "map.png").read_bytes()[:4] == b"\x89PNG"
    rows = (tmp_path / "m.csv").read_text().splitlines()
    assert len(rows) == 1 + 4


def test_stability_wob_is_where_the_growth_rate_changes_sign():
    # reference: a growth rate linear in the weight on bit crosses zero where the line does
    wob = np.array([100e3, 150e3, 200e3])
    rates = np.array([[-2.0, -1.0, 1.0], [1.0, 2.0, 3.0]])
    np.testing.assert_allclose(_sign_change(wob, rates, 2), [175e3, np.nan])
    # on the RGD 2-DOF the rightmost root keeps its sign along the weight on bit
    grid = axial_map(ASSEMBLY, BIT, [80e3, 150e3], [140.0, 200.0], duration=2.0, window=1.0,
                     growth_rate=True)  # fmt: skip
    for i, rpm in enumerate((140.0, 200.0)):
        signs = {drilling_stability(ASSEMBLY, BIT, w, rpm).growth_rate > 0 for w in grid.wob}
        assert len(signs) == 1 and np.isnan(grid.stability_wob[i])


def test_an_interrupted_map_keeps_the_points_done(tmp_path):
    # reference: the complete map, point by point
    whole = axial_map(ASSEMBLY, BIT, [90e3, 110e3], [60.0, 120.0], duration=2.0, window=1.0,
                      threads=1)  # fmt: skip

    def stop_after_two(done, total):
        if done == 2:
            raise KeyboardInterrupt

    with pytest.raises(MapInterrupted) as info:
        axial_map(ASSEMBLY, BIT, [90e3, 110e3], [60.0, 120.0], duration=2.0, window=1.0,
                  threads=1, progress=stop_after_two)  # fmt: skip
    partial = info.value.partial
    assert not partial.complete and partial.done.tolist() == [[True, True], [False, False]]
    np.testing.assert_array_equal(partial.severity[0], whole.severity[0])
    assert np.isnan(partial.severity[1]).all() and np.isnan(partial.rop[1]).all()
    path = partial.save(tmp_path / "map.partial.json")
    again = load_map(path)
    assert not again.complete and again.done.tolist() == partial.done.tolist()
    np.testing.assert_array_equal(again.rop[0], whole.rop[0])


def test_the_bisected_critical_wob_is_bracketed_by_single_runs():
    # reference: the definition, S_SS of the single runs at the bracket's ends
    grid = axial_map(ASSEMBLY, BIT, [80e3, 120e3], [120.0], duration=20.0, window=10.0,
                     threshold=0.9, refine=3)  # fmt: skip
    assert grid.critical_status == ("bisected",) and grid.info["extra_runs"] == 3
    low, high = grid.critical_bracket[0]
    assert high - low == pytest.approx(40e3 / 2**3, rel=1e-12)
    assert grid.critical_wob[0] == pytest.approx(0.5 * (low + high), rel=1e-12)
    at = {w: simulate_axial(ASSEMBLY, BIT, w, 120.0, duration=20.0, window=10.0, samples=0)
          for w in (low, high)}  # fmt: skip
    assert at[low].severity <= 0.9 < at[high].severity


@pytest.mark.parametrize(
    ("flags", "flag"),
    [(["simulate", "--rtol", "1e-3"], "--rtol"), (["map", "--pi1", "1:2:2", "--pi2", "1:2:2"],
     "--pi1"), (["simulate", "--output-step", "0.1"], "--output-step")],
)  # fmt: skip
def test_a_refusal_names_the_flag_and_what_would_work(capsys, flags, flag):
    command, *rest = flags
    assert main([command, EXAMPLE, *rest]) == 2
    err = capsys.readouterr().err
    assert f"{flag}:" in err and "axial" in err and "remove it" in err


def test_an_axial_run_reports_its_progress_as_every_run():
    # reference: the run's own number of steps, reached by the last report
    seen = []
    run = simulate_axial(ASSEMBLY, BIT, 100e3, 60.0, duration=2.0, window=1.0,
                         progress=lambda done, total: seen.append((done, total)))  # fmt: skip
    steps = round(run.duration / run.axial.step)
    assert seen[-1] == (steps, steps) and {total for _, total in seen} == {steps}
    from torsio.analysis.transient import simulate_config
    from torsio.examples import rgd_two_dof_config

    through_the_file = []
    again = simulate_config(rgd_two_dof_config(), duration=2.0, steady_window=1.0,
                            progress=lambda done, total: through_the_file.append(done))  # fmt: skip
    assert through_the_file[-1] == steps and again.severity == run.severity
