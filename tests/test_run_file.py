"""A run saved and read back (TransientResults.save, load_run) and ``torsio simulate --out``.

The expected values are the run's own: a saved file must give back every array, every
number and every output (JSON, CSV, terminal table) of the run that wrote it, bit for bit
(lossless storage); nothing here is recomputed.
"""

from __future__ import annotations

import json
import math
from importlib import resources

import attrs
import numpy as np
import pytest

from torsio import SoftTorqueTopDrive, TorqueTopDrive, energy_balance, load_run, simulate
from torsio.analysis.axial_transient import simulate_axial
from torsio.analysis.transient_results import RUN_ARRAYS
from torsio.axial.rgd import rgd_example
from torsio.calibration.recording import Recording
from torsio.cli import main
from torsio.display_units import DisplayUnits
from torsio.errors import ConfigError
from torsio.examples import builtin_config, deviated_well_config, rgd_wave_pipe_config
from torsio.model.axial_assembly import rgd_two_dof_example
from torsio.physics.dimensionless import dimensionless_system
from torsio.physics.recorded_top import RecordedTopDrive


def _runs():
    system = builtin_config().system(strategy="A").at(wob=100e3, rpm=60)
    held = simulate(system, duration=60.0, steady_window=20.0)
    yield "held top", held
    yield (
        "SoftTorque",
        simulate(
            system.with_top(SoftTorqueTopDrive(inertia=930.0)), duration=60.0, steady_window=20.0
        ),
    )
    yield (
        "torque top (no set speed)",
        simulate(
            system.with_top(TorqueTopDrive(inertia=930.0, torque=8e3)),
            duration=60.0,
            steady_window=20.0,
        ),
    )
    yield "dimensionless", simulate(dimensionless_system(system), duration=60.0)
    well = deviated_well_config().system(strategy="A")
    yield "well (contacts)", simulate(well, duration=60.0, steady_window=20.0)
    wave = deviated_well_config().system()  # the distributed model of the file
    yield "wave model", simulate(wave, duration=20.0, steady_window=5.0)
    axial = simulate_axial(
        rgd_two_dof_example(), rgd_example(), 100e3, 60.0, duration=2.0, window=1.0
    )
    yield "axial (RGD 2-DOF)", axial
    pipe = rgd_wave_pipe_config().axial
    yield (
        "axial, distributed pipe, no samples",
        simulate_axial(pipe.assembly, pipe.bit, 100e3, 60.0, duration=2.0, window=1.0, samples=0),
    )
    record = Recording.from_transient(held, name="held.csv")
    yield (
        "recorded top",
        simulate(
            system.with_top(RecordedTopDrive(recording=record)), duration=60.0, steady_window=20.0
        ),
    )


RUNS = dict(_runs())


@pytest.fixture(params=list(RUNS))
def saved(request, tmp_path):
    run = RUNS[request.param]
    return run, load_run(run.save(tmp_path / "run.npz"))


def test_every_output_of_a_saved_run_is_the_runs(saved, tmp_path):
    run, again = saved
    assert json.dumps(again.to_dict(series=True)) == json.dumps(run.to_dict(series=True))
    first, second = run.to_csv(tmp_path / "a.csv"), again.to_csv(tmp_path / "b.csv")
    assert first.read_bytes() == second.read_bytes()
    units = DisplayUnits("si")
    assert again.summary_rows(units) == run.summary_rows(units)
    assert json.dumps(attrs.asdict(again.facts)) == json.dumps(attrs.asdict(run.facts))
    assert (again.rpm_source, again.plot_label) == (run.rpm_source, run.plot_label)
    assert again.warnings == run.warnings
    assert json.dumps(again.solver) == json.dumps(run.solver)  # the wave model's rtol is NaN


def test_every_array_of_a_saved_run_comes_back_bit_for_bit(saved):
    run, again = saved
    for name in RUN_ARRAYS:
        before, after = getattr(run, name), getattr(again, name)
        assert after.shape == before.shape and after.dtype == before.dtype, name
        assert np.array_equal(after, before, equal_nan=True), name
    if run.axial is not None:
        assert np.array_equal(again.axial.samples, run.axial.samples)
        assert again.axial.energy == run.axial.energy
        assert again.axial.steady == run.axial.steady
        assert again.axial.summary == run.axial.summary
        np.testing.assert_array_equal(again.signal("bit_weight"), run.signal("bit_weight"))


def test_a_torque_driven_top_keeps_its_mean_speed_as_its_rpm(tmp_path):
    run = RUNS["torque top (no set speed)"]
    again = load_run(run.save(tmp_path / "run.npz"))
    assert again.rpm_source == run.rpm_source == "top_speed_mean"
    assert again.rpm == run.rpm and math.isnan(again.facts.rpm)


def test_a_loaded_run_has_no_system_and_its_energy_balance_says_so(tmp_path):
    again = load_run(RUNS["held top"].save(tmp_path / "run.npz"))
    assert again.system is None
    with pytest.raises(TypeError, match="keeps no System"):
        energy_balance(again)


def test_a_run_is_saved_as_npz_only(tmp_path):
    with pytest.raises(ConfigError, match=r"ending in \.npz") as info:
        RUNS["held top"].save(tmp_path / "run.json")
    assert info.value.key == "path"
    assert not (tmp_path / "run.json").exists()


def test_a_file_that_is_not_a_saved_run_is_refused_by_name(tmp_path):
    with pytest.raises(ConfigError, match="cannot read transient run file"):
        load_run(tmp_path / "missing.npz")
    other = tmp_path / "other.npz"
    np.savez(other, metadata=np.array(json.dumps({"format": "torsio severity map"})))
    with pytest.raises(ConfigError, match="is not a saved transient run"):
        load_run(other)
    text = tmp_path / "run.npz"
    text.write_text("not an archive")
    with pytest.raises(ConfigError, match="is not a saved transient run"):
        load_run(text)
    listed = tmp_path / "run.json"
    listed.write_text("[1, 2]")
    with pytest.raises(ConfigError, match="is not a saved transient run"):
        load_run(listed)
    damaged = tmp_path / "damaged.npz"
    np.savez(damaged, metadata=np.array(json.dumps({"format": "torsio transient", "version": 1})))
    with pytest.raises(ConfigError, match="damaged saved run .*KeyError"):
        load_run(damaged)


def test_simulate_out_saves_the_run_it_prints(tmp_path, capsys):
    out = tmp_path / "run.npz"
    example = str(resources.files("torsio").joinpath("data/rgd_2dof.toml"))
    code = main(["simulate", example, "--duration", "2", "--window", "1", "--json",
                 "--no-growth-rate", "--out", str(out)])  # fmt: skip
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    assert data["out"] == str(out)
    again = load_run(out).to_dict()
    assert again["severity"] == data["severity"] and again["rop_mean"] == data["rop_mean"]


def test_simulate_out_refuses_another_suffix_before_it_runs(tmp_path, capsys):
    code = main(["simulate", "--out", str(tmp_path / "run.json")])
    assert code == 2
    error = capsys.readouterr().err
    assert "--out" in error and "ending in .npz" in error
    assert not (tmp_path / "run.json").exists()


def test_a_saved_run_draws_the_runs_figure(saved, tmp_path):
    pytest.importorskip("matplotlib")
    run, again = saved
    figures = [r.plot(tmp_path / f"{name}.png") for name, r in (("a", run), ("b", again))]
    for before, after in zip(*(f.axes for f in figures), strict=True):
        assert before.get_title() == after.get_title()
        lines = [
            [(line.get_xdata(), line.get_ydata()) for line in ax.lines] for ax in (before, after)
        ]
        for (x0, y0), (x1, y1) in zip(*lines, strict=True):
            np.testing.assert_array_equal(x1, x0)
            np.testing.assert_array_equal(y1, y0)
