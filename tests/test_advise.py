"""``torsio advise`` on the built-in RGD deviated well: the recommended point against a
brute-force map, the surface-torque limit, the Monte Carlo margin against an independent
Monte Carlo, Ctrl-C, and bad inputs.

Where the expected values come from:

* the reference optimum is a fine brute-force map of the same region with the same model,
  run by another path (:func:`torsio.analysis.axial_maps.axial_map`, the engine of ``torsio map``);
* "not severe" and the surface torque of the recommended point are read from a run of the
  point on its own (:func:`torsio.analysis.axial_transient.simulate_axial`), S_SS against the
  paper's
  0.8 (Eq. 12 and §4);
* the independent Monte Carlo draws its own friction factors (numpy's normal with another
  seed, truncated at two sigma), writes them into the configuration file's ``[well]`` and
  reads it again, and bounds the probability with the one-sided 95 % Clopper-Pearson bound
  (Clopper and Pearson 1934; scipy's beta quantile).

CI runs the region 78-110 kN x 140-180 rpm with runs of 80 s (window 30 s) instead of the
default 40 and 15 periods (170 s, 64 s), to stay within a minute on two cores; the default
region against a 33 x 15 map is ``-m slow``.
"""

from __future__ import annotations

import json
import re
from importlib import resources

import numpy as np
import pytest

from torsio.advice import AdviceInterrupted, Constraints, Region, Uncertainty, advise
from torsio.advice.margin import upper_bound
from torsio.analysis.axial_maps import axial_map
from torsio.analysis.axial_transient import simulate_axial
from torsio.cli import main
from torsio.config.reading import load_config
from torsio.examples import rgd_deviated_well_config

WELL = str(resources.files("torsio").joinpath("data/rgd_deviated_well.toml"))
TIMES = {"duration": 80.0, "window": 30.0}
REGION = Region((78e3, 110e3), (140.0, 180.0), wob_points=3, rpm_points=3)
THRESHOLD = 0.8  # the paper's severe stick-slip: S_SS > 0.8


def alone(config, point, samples=0):
    """The point run on its own with the advice's run options."""
    axial = config.axial
    return simulate_axial(
        axial.assembly,
        axial.bit,
        point["wob"],
        point["rpm"],
        samples=samples,
        growth_rate=False,
        **{**axial.run_options(), "duration": TIMES["duration"], "window": TIMES["window"]},
    )


@pytest.fixture(scope="module")
def config():
    return rgd_deviated_well_config()


@pytest.fixture(scope="module")
def unconstrained(config):
    return advise(config, REGION, compare=False, threads=2, **TIMES)


def test_recommended_point_is_not_severe_and_near_the_brute_force_optimum(config, unconstrained):
    point = unconstrained.recommended
    assert point is not None and unconstrained.complete
    run = alone(config, point)
    assert run.severity <= THRESHOLD
    assert run.axial.rop_mean == pytest.approx(
        point["rop"], rel=1e-12
    )  # the same deterministic run
    axial = config.axial
    fine = axial_map(
        axial.assembly,
        axial.bit,
        np.linspace(*REGION.wob, 17),
        np.linspace(*REGION.rpm, 5),
        threads=2,
        **{**axial.run_options(), **TIMES},
    )
    calm = fine.severity <= THRESHOLD
    best = fine.rop[calm].max()
    assert point["rop"] >= 0.95 * best
    # measured: 36 runs of the search against the map's 85
    assert unconstrained.window.runs < fine.severity.size / 2


def test_surface_torque_limit_is_respected(config, unconstrained):
    free = unconstrained.recommended
    calm = unconstrained.window.admissible
    lowest = unconstrained.window.points.surface_torque[calm].min()
    limit = 0.5 * (lowest + free["surface_torque"])  # below the free optimum's torque
    advice = advise(
        config, REGION, Constraints(max_surface_torque=limit), compare=False, threads=2, **TIMES
    )
    point = advice.recommended
    assert point is not None
    run = alone(config, point, samples=1500)
    assert run.axial.top_drive_summary()["mean_surface_torque"] == pytest.approx(
        point["surface_torque"], rel=1e-12
    )
    assert point["surface_torque"] <= limit < free["surface_torque"]
    assert run.severity <= THRESHOLD


FIT = {
    "parameters": {"friction_static": 0.35, "friction_dynamic": 0.30},
    "uncertainty": {"friction_static": 0.03, "friction_dynamic": 0.03},
}


def independent_draws(count, seed):
    """The fit's friction factors drawn without torsio: independent normals truncated at
    two sigma, the dynamic factor at most the static one (as the well requires)."""
    rng = np.random.default_rng(seed)
    draws = []
    for _ in range(count):
        values = {}
        for name, mean in FIT["parameters"].items():
            sigma = FIT["uncertainty"][name]
            values[name] = float(
                np.clip(rng.normal(mean, sigma), mean - 2 * sigma, mean + 2 * sigma)
            )
        values["friction_dynamic"] = min(values["friction_dynamic"], values["friction_static"])
        draws.append(values)
    return draws


def well_with(text, values):
    """The configuration file's text with the open hole's factors of ``values``: the
    ``[well]`` table's own lines, the first of each name (``[[well.hole]]`` comes after)."""
    for name, value in values.items():
        pattern = rf"^{name} = [0-9.]+"
        text, count = re.subn(pattern, f"{name} = {value!r}", text, count=1, flags=re.M)
        assert count == 1
    return text


def test_probability_of_severe_stick_slip_is_below_the_level(config, tmp_path):
    from concurrent.futures import ThreadPoolExecutor

    path = tmp_path / "fit.json"
    path.write_text(json.dumps(FIT))
    level = 0.1
    advice = advise(
        config,
        REGION,
        compare=False,
        threads=2,
        uncertainty=Uncertainty.from_fit(path),
        level=level,
        samples=30,
        **TIMES,
    )
    point, margin = advice.recommended, advice.margin
    assert point is not None and margin.samples == 30
    assert margin.probability_upper < level
    # the independent Monte Carlo: twice the samples, another seed, another path to the
    # model (the file's text rewritten and read again)
    text = open(WELL, encoding="utf-8").read()

    def severity(values):
        variant = tmp_path / f"well_{abs(hash(tuple(values.values())))}.toml"
        variant.write_text(well_with(text, values))
        return alone(load_config(variant), point).severity

    draws = independent_draws(60, seed=12345)
    with ThreadPoolExecutor(2) as pool:
        values = list(pool.map(severity, draws))
    severe = sum(s > THRESHOLD for s in values)
    # one-sided 95 % Clopper-Pearson bound of the independent estimate below the level
    assert upper_bound(severe, len(values)) < level, (severe, len(values))


def test_ctrl_c_leaves_a_partial_advice_marked_incomplete(config):
    done = []

    def progress(count):
        done.append(count)
        if sum(done) >= 4:
            raise KeyboardInterrupt

    with pytest.raises(AdviceInterrupted) as caught:
        advise(config, REGION, compare=False, threads=1, progress=progress, **TIMES)
    partial = caught.value.advice
    assert not partial.complete and partial.to_dict()["complete"] is False
    # the four runs that finished before Ctrl-C (one thread: one after the other) are kept
    assert partial.window.runs == 4 and partial.window.points.wob.size == 4


def error(capsys, *args):
    status = main(["advise", WELL, *args])
    captured = capsys.readouterr()
    assert status == 2 and captured.out == ""
    return captured.err


@pytest.mark.parametrize(
    ("args", "flag", "expected"),
    [
        (["--wob", "80kN:100kN"], "--wob", "START:STOP:N"),
        (["--rpm", "100:100:3"], "--rpm", "START = STOP"),
        (["--max-surface-torque", "-5 kN*m"], "--max-surface-torque", "positive"),
        (["--objective", "speed"], "--objective", "rop, mse"),
        (["--vary", "mu=0.1:0.2"], "--vary", "friction_static"),
        (["--vary", "friction_static=0.3:0.4", "--samples", "10"], "--samples", "at least 29"),
        (["--fit", "nowhere.json"], "--fit", "parameters"),
        (["--level", "1.5", "--vary", "friction_static=0.3:0.4"], "--level", "between 0 and 1"),
    ],
)
def test_bad_inputs_name_the_flag_and_what_was_expected(capsys, args, flag, expected):
    message = error(capsys, *args)
    assert f"torsio advise: error: {flag}:" in message and expected in message


def test_a_top_drive_the_advisor_cannot_take_is_refused(capsys, tmp_path):
    path = tmp_path / "torque.toml"
    text = open(WELL, encoding="utf-8").read()
    path.write_text(text + '\n[top_drive]\nkind = "recorded"\nrecording = "rig.csv"\n')
    (tmp_path / "rig.csv").write_text("time,top_rpm,surface_torque\n0,60,1000\n1,60,1000\n")
    status = main(["advise", str(path), "--json"])
    captured = capsys.readouterr()
    assert status == 2 and "top_drive.kind" in captured.err


def test_torsional_configuration_is_refused_by_key(capsys):
    ritto = str(resources.files("torsio").joinpath("data/ritto2017.toml"))  # torsional only
    status = main(["advise", ritto, "--json"])
    assert status == 2 and "bit_rock.law" in capsys.readouterr().err


SMALL = ["--wob", "78kN:110kN:2", "--rpm", "160:180:2", "--duration", "80", "--window", "30"]


def test_json_has_the_design_keys(capsys):
    status = main(["advise", WELL, *SMALL, "--no-compare", "--threads", "2", "--json"])
    captured = capsys.readouterr()
    assert status == 0, captured.err
    data = json.loads(captured.out)
    # DESIGN.md's CLI table: recommended (wob, rpm, rop, mse, severity, surface_torque,
    # probability_severe), constraints, top_drives (each its recommended point)
    assert {"recommended", "constraints", "top_drives"} <= set(data)
    design = {"wob", "rpm", "rop", "mse", "severity", "surface_torque", "probability_severe"}
    assert design <= set(data["recommended"])
    assert [d["top_drive"] for d in data["top_drives"]] == ["constant-speed (configured)"]
    assert data["top_drives"][0]["recommended"]["wob"] == data["recommended"]["wob"]
    assert data["complete"] is True and data["runs"]["coarse"] == 4
    assert data["recommended"]["severity"] <= THRESHOLD


def test_ctrl_c_on_the_command_line_prints_the_partial_advice(capsys, monkeypatch):
    from torsio.advice.evaluate import AxialCase

    run = AxialCase.__call__
    calls = []

    def interrupted_after_three(self, wob, rpm):
        calls.append((wob, rpm))
        if len(calls) > 3:
            raise KeyboardInterrupt  # what Ctrl-C raises in the main thread
        return run(self, wob, rpm)

    monkeypatch.setattr(AxialCase, "__call__", interrupted_after_three)
    status = main(["advise", WELL, *SMALL, "--no-compare", "--threads", "1", "--json"])
    captured = capsys.readouterr()
    assert status == 130 and "interrupted" in captured.err
    data = json.loads(captured.out)
    assert data["complete"] is False and data["runs"]["total"] == 3


def test_points_are_the_same_wherever_they_run():
    # every point is one deterministic run (docs/advise.md, "Where the runs go"): two local
    # processes give the threads' numbers to the bit
    from torsio.advice.evaluate import AxialCase, evaluate
    from torsio.examples import rgd_two_dof_config

    case = AxialCase.from_config(rgd_two_dof_config(), duration=20.0, window=10.0)
    wob, rpm = [90e3, 110e3, 130e3], [60.0, 120.0, 90.0]
    here = evaluate(case, wob, rpm, threads=2)
    there = evaluate(case, wob, rpm, executor=2)
    for name in ("severity", "rop", "mse", "surface_torque", "surface_torque_max"):
        assert np.array_equal(getattr(here, name), getattr(there, name)), name


def test_clopper_pearson_bound_of_no_severe_sample_is_the_closed_form():
    # with none of n severe the one-sided bound solves (1 - p)^n = 1 - confidence:
    # p = 1 - 0.05^(1/n) (Clopper and Pearson 1934)
    for n in (29, 30, 60):
        assert upper_bound(0, n) == pytest.approx(1 - 0.05 ** (1 / n), rel=1e-9)
    assert upper_bound(0, 28) > 0.1 > upper_bound(0, 29)  # why 29 samples at least for 10 %


def test_rpm_margin_follows_the_critical_curve_linearly():
    from torsio.advice.margin import rpm_margin

    # critical WOB 60 kN at 60 rpm rising linearly to 100 kN at 120 rpm: a point at 90 kN
    # and 120 rpm crosses it at 60 + (90 - 60)/(100 - 60) * 60 = 105 rpm, 15 rpm away
    rows, critical = np.array([60.0, 120.0]), np.array([60e3, 100e3])
    assert rpm_margin(rows, critical, 90e3, 120.0) == pytest.approx(15.0)
    assert rpm_margin(rows, critical, 50e3, 120.0) is None  # below the whole curve


def test_the_files_top_drive_limit_is_the_default_torque_limit(capsys, tmp_path):
    # a rig limit in the configuration: [top_drive] max_torque bounds the surface torque
    # when --max-surface-torque is not given
    path = tmp_path / "limited.toml"
    text = open(WELL, encoding="utf-8").read()
    path.write_text(
        text + '\n[top_drive]\nkind = "soft-torque"\ninertia = 2900.0\nmax_torque = "12 kN*m"\n'
    )
    status = main(["advise", str(path), *SMALL, "--no-compare", "--threads", "2", "--json"])
    captured = capsys.readouterr()
    assert status == 0, captured.err
    data = json.loads(captured.out)
    limits = data["constraints"]
    assert limits["max_surface_torque"] == 12e3
    assert limits["max_surface_torque_from"] == "top_drive.max_torque"
    point = data["recommended"]
    assert point is None or point["surface_torque"] <= 12e3


def test_without_a_configuration_it_advises_on_the_built_in_rgd_deviated_well(capsys):
    # the default of the command: the built-in file whose name the JSON's model carries
    status = main(["advise", "--no-compare", "--wob", "80kN:100kN:2", "--rpm", "150:180:2",
                   "--duration", "40", "--window", "15", "--json"])  # fmt: skip
    assert status == 0
    data = json.loads(capsys.readouterr().out)
    assert data["model"] == rgd_deviated_well_config().name
