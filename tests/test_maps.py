"""Severity maps (torsio.analysis.maps) against independent single transient runs.

Sources of the reference numbers:

* independent single runs: torsio.analysis.transient.simulate (scipy LSODA) at rtol = 1e-8,
  atol = 1e-10, each started from rest, same run length and steady window as the
  map (the defaults of torsio.analysis.severity: 40 and 15 first-mode periods);
* the definitions Pi_1 = Omega/omega_1 and Pi_2 = W_ob R_bit/k_eq as implemented by
  torsio.physics.dimensionless (a separate module);
* the dimensionless system of Eq. 11 (torsio.physics.dimensionless.dimensionless_system),
  integrated in tau = omega_1 t, which must give the same S_SS.

The issue's requirement, |dS_SS| <= 0.01 at every point of a 21 x 21 map for a
1-DOF and a 10-DOF model, is checked in full by the slow tests (``-m slow``) and on
sub-grids (every fifth WOB, every fifth or tenth rpm) and on the bisection
brackets of the critical curve (where S_SS jumps) in the fast suite.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from torsio.analysis import map_runs
from torsio.analysis.critical_wob import locate_critical_wob
from torsio.analysis.map_results import MapInterrupted, SeverityMap, load_map
from torsio.analysis.map_runs import check_grid_size
from torsio.analysis.maps import dimensionless_map, severity_map
from torsio.analysis.sweep import run_tasks
from torsio.analysis.transient import simulate
from torsio.errors import ConfigError, SolverError
from torsio.physics.system import System
from torsio.solvers import batch

TIGHT = {"method": "LSODA", "rtol": 1e-8, "atol": 1e-10}
WOB21 = np.linspace(25e3, 225e3, 21)
RPM21 = np.linspace(40.0, 140.0, 21)


def single_run(system: System, wob: float, rpm: float, duration: float, window: float) -> float:
    """S_SS of one independent transient run (module level: picklable for workers)."""
    return simulate(
        system.at(wob=wob, rpm=rpm), duration=duration, steady_window=window, **TIGHT
    ).severity


def assert_map_matches_single_runs(result: SeverityMap, system: System, executor=None) -> None:
    duration, window = result.info["duration"], result.info["steady_window"]
    tasks = [(system, float(w), float(r), duration, window) for r in result.rpm for w in result.wob]
    expected = np.array(run_tasks(single_run, tasks, executor=executor).results).reshape(
        result.shape
    )
    difference = np.abs(result.severity - expected)
    worst = np.unravel_index(np.argmax(difference), difference.shape)
    assert difference.max() <= 0.01, (
        f"|dS_SS| = {difference.max():.3g} at rpm "
        f"{result.rpm[worst[0]]}, wob {result.wob[worst[1]]}"
    )


# --- the accuracy requirement -------------------------------------------------------
def test_one_dof_subgrid_matches_single_runs(one_dof: System) -> None:
    result = severity_map(one_dof, WOB21[::5], RPM21[::5], refine=0)
    assert_map_matches_single_runs(result, one_dof)


def test_ten_dof_subgrid_matches_single_runs(ten_dof: System) -> None:
    result = severity_map(ten_dof, WOB21[::5], RPM21[::10], refine=0)
    assert_map_matches_single_runs(result, ten_dof)


@pytest.mark.slow
@pytest.mark.parametrize("model", ["one_dof", "ten_dof"])
def test_full_21_by_21_map_matches_single_runs(model: str, request: pytest.FixtureRequest) -> None:
    system = request.getfixturevalue(model)
    result = severity_map(system, WOB21, RPM21, refine=0)
    assert_map_matches_single_runs(result, system, executor=2)


def test_critical_bracket_is_confirmed_by_single_runs(one_dof: System) -> None:
    result = severity_map(one_dof, WOB21, [60.0, 100.0], refine=5)
    duration, window = result.info["duration"], result.info["steady_window"]
    for i, rpm in enumerate(result.rpm):
        low, high = result.critical_bracket[i]
        assert result.critical_status[i] == "bisected"
        assert high - low == pytest.approx(10e3 / 2**5)  # grid step / 2^refine
        assert result.critical_wob[i] == pytest.approx(0.5 * (low + high))
        # the bracket straddles the threshold according to independent runs
        assert single_run(one_dof, low, rpm, duration, window) <= 0.8
        assert single_run(one_dof, high, rpm, duration, window) > 0.8
        # and every grid point above it is severe, every one below the cell is not
        above = result.wob >= high
        assert (result.severity[i, above] > 0.8).all()
        assert (result.severity[i, result.wob <= low] <= 0.8).all()


# --- rules: classification, critical curve ------------------------------------------------
def test_critical_rule_statuses(one_dof: System) -> None:
    result = severity_map(one_dof, [150e3, 190e3, 225e3], [40.0, 140.0], refine=0)
    # 40 rpm: severe over the whole row; 140 rpm: never severe (21 x 21 map above)
    assert result.critical_status == ("below_range", "none")
    # off the grid: no value (JSON null, DESIGN.md), only the side it lies on
    assert math.isnan(result.critical_wob[0]) and math.isnan(result.critical_wob[1])
    assert result.to_dict()["critical_wob"] == [None, None]
    assert result.to_dict()["critical_wob_bound"] == ["below", "above"]
    assert result.critical_wob_texts() == ["≤ 150", "> 225"]
    assert math.isnan(result.critical_pi2[0])


def test_progress_total_is_fixed_from_the_start(one_dof: System) -> None:
    # 3 rpm x 3 wob grid + refine (2) bisection runs per rpm = 15 runs, by construction;
    # 40 rpm is severe over the row and 140 rpm never (test_critical_rule_statuses), so only
    # 90 rpm is bisected and the other rows' planned runs are counted as done
    calls: list[tuple[int, int]] = []
    result = severity_map(
        one_dof, [25e3, 150e3, 225e3], [40.0, 90.0, 140.0], refine=2, chunk_size=2,
        progress=lambda done, total: calls.append((done, total)),
    )  # fmt: skip
    assert {total for _, total in calls} == {9 + 2 * 3}
    done = [d for d, _ in calls]
    assert done == sorted(done) and done[-1] == 15
    assert result.info["extra_runs"] == 2 * result.critical_status.count("bisected")


def test_critical_rule_on_given_severities() -> None:
    wob = np.array([10.0, 20.0, 30.0, 40.0])
    severity = np.array(
        [
            [0.0, 1.2, 0.0, 1.1],  # severe island, then severe from 40
            [0.0, 0.0, 0.0, 0.5],  # never severe
            [0.9, 1.0, 1.1, 1.2],  # severe everywhere
            [0.0, np.nan, 1.0, 1.0],
        ]
    )  # a failed point
    critical, status, bracket = locate_critical_wob(None, wob, np.ones(4), severity, 0.8, 0, "mark")
    assert status == ("grid", "none", "below_range", "unresolved")
    assert critical[0] == 35.0 and tuple(bracket[0]) == (30.0, 40.0)
    assert math.isnan(critical[1]) and math.isnan(critical[2]) and math.isnan(critical[3])


def test_off_grid_critical_wob_is_marked_not_drawn(tmp_path) -> None:
    # the rows of test_critical_rule_on_given_severities, as a map
    wob = np.array([10e3, 20e3, 30e3, 40e3])
    severity = np.array([[0.0, 0.0, 1.0, 1.1], [0.0, 0.0, 0.0, 0.5], [0.9, 1.0, 1.1, 1.2]])
    critical, status, bracket = locate_critical_wob(None, wob, np.ones(3), severity, 0.8, 0, "mark")
    ones = np.ones(severity.shape)
    result = SeverityMap(
        wob, np.array([40.0, 90.0, 140.0]), severity, critical, status, bracket,
        np.full(3, np.nan), 0.8, 0.05, 1e4, 1.0, 0.1,
        (0 * ones).astype(int), ones.astype(int), ones.astype(bool),
    )  # fmt: skip
    assert result.critical_wob_bound == (None, "above", "below")
    assert result.critical_wob_texts() == ["25", "> 40", "≤ 10"]
    # a saved map of an older torsio gave wob[0] below the range: read back as no value
    data = result.to_dict()
    data["critical_wob"][2] = 10e3
    assert math.isnan(SeverityMap.from_dict(data).critical_wob[2])
    assert "SeverityMap(" in repr(result) and "3 rpm x 4 wob points" in repr(result)
    pytest.importorskip("matplotlib")
    from torsio.plotting.map_plot import OFF_GRID_LABELS

    ax = result.plot(tmp_path / "map.png")
    lines = {line.get_label(): line for line in ax.get_lines()}
    up, down = lines[OFF_GRID_LABELS["above"]], lines[OFF_GRID_LABELS["below"]]
    assert up.get_xdata().tolist() == [90.0] and up.get_ydata().tolist() == [40.0]  # kN
    assert down.get_xdata().tolist() == [140.0] and down.get_ydata().tolist() == [10.0]
    curve = lines[next(label for label in lines if label.startswith("critical WOB ($"))]
    assert np.isnan(curve.get_ydata()[1:]).all()  # the curve is not drawn along the edges


def test_classification_thresholds(one_dof: System) -> None:
    result = severity_map(one_dof, [50e3, 150e3], [60.0], refine=0)
    labels = result.classification()
    assert labels.tolist() == [["stable", "severe"]]
    looser = severity_map(
        one_dof, [50e3, 150e3], [60.0], refine=0, threshold=1.5, stick_slip_threshold=0.01
    )
    assert looser.classification().tolist() == [["stable", "stick-slip"]]  # S = 1.32
    with pytest.raises(ConfigError, match="stick_slip_threshold"):
        severity_map(one_dof, [50e3], [60.0], threshold=0.5, stick_slip_threshold=0.6)


def test_orientation_severity_i_j_is_rpm_i_wob_j(one_dof: System) -> None:
    result = severity_map(one_dof, [50e3, 150e3, 200e3], [60.0, 120.0], refine=0)
    direct = batch.simulate_batch(one_dof, [150e3], [120.0])
    assert result.severity.shape == (2, 3)
    assert result.severity[1, 1] == direct.severity[0]


# --- dimensionless map ----------------------------------------------------------------------
def test_dimensionless_map_axes_and_invariance(one_dof: System) -> None:
    from torsio.physics.dimensionless import dimensionless_groups, dimensionless_system

    pi1, pi2 = np.array([5.0, 9.0]), np.array([15.0, 45.0])
    result = dimensionless_map(one_dof, pi1, pi2, refine=0)
    groups = dimensionless_groups(one_dof)
    np.testing.assert_allclose(result.pi1, pi1, rtol=1e-12)
    np.testing.assert_allclose(result.pi2, pi2, rtol=1e-12)
    for i, p1 in enumerate(pi1):
        for j, p2 in enumerate(pi2):
            wob, rpm = groups.operating_point(p1, p2)
            assert result.rpm[i] == pytest.approx(rpm, rel=1e-12)
            assert result.wob[j] == pytest.approx(wob, rel=1e-12)
    # Eq. 11 integrated in tau gives the same S_SS (the dimensionless law has no
    # compiled kernel: this also runs the numpy engine)
    scaled = dimensionless_system(one_dof)
    tau_duration = result.info["duration"] * groups.omega1
    tau_window = result.info["steady_window"] * groups.omega1
    grid_pi1, grid_pi2 = np.meshgrid(pi1, pi2, indexing="ij")
    tau = batch.simulate_batch(
        scaled,
        grid_pi2.ravel(),
        grid_pi1.ravel() * 30 / math.pi,
        duration=tau_duration,
        steady_window=tau_window,
    )
    np.testing.assert_allclose(tau.severity.reshape(2, 2), result.severity, atol=1e-3)
    assert result.critical_pi2.shape == (2,)


# --- files ------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def small_map(one_dof: System) -> SeverityMap:
    return severity_map(one_dof, np.linspace(25e3, 225e3, 5), [40.0, 90.0, 140.0], refine=2)


@pytest.mark.parametrize("suffix", [".json", ".npz"])
def test_save_and_load_round_trip(small_map: SeverityMap, tmp_path, suffix: str) -> None:
    path = small_map.save(tmp_path / f"map{suffix}")
    loaded = load_map(path)
    np.testing.assert_array_equal(loaded.severity, small_map.severity)
    np.testing.assert_array_equal(loaded.critical_wob, small_map.critical_wob)
    np.testing.assert_array_equal(loaded.stability_wob, small_map.stability_wob)
    np.testing.assert_array_equal(loaded.critical_bracket, small_map.critical_bracket)
    assert loaded.critical_status == small_map.critical_status
    assert loaded.complete and loaded.info["rtol"] == small_map.info["rtol"]
    assert loaded.to_dict() == small_map.to_dict()
    assert not list(tmp_path.glob(".*tmp"))  # the temporary file was renamed


def test_json_has_the_design_keys(small_map: SeverityMap, tmp_path) -> None:
    data = json.loads(small_map.save(tmp_path / "map.json").read_text())
    assert {"wob", "rpm", "severity", "critical_wob"} <= set(data)
    assert len(data["severity"]) == 3 and len(data["severity"][0]) == 5


def test_load_rejects_other_files(tmp_path) -> None:
    path = tmp_path / "other.json"
    path.write_text('{"format": "something-else"}')
    with pytest.raises(ConfigError, match="format"):
        load_map(path)
    with pytest.raises(ConfigError, match="cannot read"):
        load_map(tmp_path / "missing.json")


def test_csv_export(small_map: SeverityMap, tmp_path) -> None:
    lines = small_map.to_csv(tmp_path / "map.csv").read_text().splitlines()
    assert lines[0] == "rpm,wob_N,pi1,pi2,severity,class,status"
    assert len(lines) == 1 + 15
    rpm, wob, _, _, severity, label, status = lines[1 + 5 + 4].split(",")  # rpm[1], wob[4]
    assert float(rpm) == 90.0 and float(wob) == 225e3
    assert float(severity) == small_map.severity[1, 4] and status == "0"
    assert label == small_map.classification()[1, 4]


def test_plot_writes_png(small_map: SeverityMap, tmp_path) -> None:
    pytest.importorskip("matplotlib")
    for dimensionless in (False, True):
        path = tmp_path / f"map{dimensionless}.png"
        small_map.plot(path, dimensionless=dimensionless)
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


# --- interruption, failures, bad input ---------------------------------------------------------
def test_ctrl_c_leaves_a_partial_map_marked_incomplete(one_dof: System, tmp_path) -> None:
    calls = []

    def progress(done: int, total: int) -> None:
        calls.append(done)
        if len(calls) == 2:
            raise KeyboardInterrupt

    wob, rpm = np.linspace(25e3, 225e3, 4), [50.0, 100.0]
    with pytest.raises(MapInterrupted) as info:
        severity_map(one_dof, wob, rpm, chunk_size=2, progress=progress)
    partial = info.value.partial
    assert not partial.complete
    assert partial.done.sum() == 4 and not partial.done.all()
    full = severity_map(one_dof, wob, rpm, refine=0)
    np.testing.assert_array_equal(partial.severity[partial.done], full.severity[partial.done])
    assert np.isnan(partial.severity[~partial.done]).all()
    assert set(partial.classification()[~partial.done]) == {"missing"}
    saved = json.loads(partial.save(tmp_path / "partial.json").read_text())
    assert saved["complete"] is False
    assert not load_map(tmp_path / "partial.json").complete


def test_solver_failures_raise_or_are_marked(one_dof: System, monkeypatch) -> None:
    original = batch.simulate_batch

    def few_steps(*args, **kwargs):
        return original(*args, **{**kwargs, "max_steps": 500, "steady_tolerance": 0.0})

    monkeypatch.setattr(map_runs, "simulate_batch", few_steps)  # what each chunk calls
    with pytest.raises(SolverError, match="wob=150000 N, rpm=60: too many steps"):
        severity_map(one_dof, [50e3, 150e3], [60.0])
    with pytest.warns(RuntimeWarning, match="failed at 1 points"):
        marked = severity_map(one_dof, [50e3, 150e3], [60.0], on_failure="mark")
    assert marked.classification().tolist() == [["stable", "failed"]]
    assert marked.critical_status == ("unresolved",)
    assert "too many steps" in marked.failures()[0]


@pytest.mark.parametrize(
    "wob, rpm, key",
    [
        ([], [60.0], "wob"),
        ([2e5, 1e5], [60.0], "wob"),
        ([-1.0, 1e5], [60.0], "wob"),
        ([1e5], [60.0, 60.0], "rpm"),
        ([1e5], [0.0], "rpm"),
    ],
)
def test_bad_axes(one_dof: System, wob, rpm, key: str) -> None:
    with pytest.raises(ConfigError, match=f"^{key}:"):
        severity_map(one_dof, wob, rpm)


def test_grid_too_large_for_memory() -> None:
    with pytest.raises(
        ConfigError,
        match=r"100,000 rpm x 100,000 wob = 10,000,000,000 points "
        r"needs about 2.56 TB",
    ):
        check_grid_size(100_000, 100_000, memory=16e9)
    check_grid_size(100, 100, memory=16e9)  # 2.56 MB: fine
