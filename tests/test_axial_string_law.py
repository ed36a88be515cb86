"""Any law on a ``[[section]]`` string's axial chain: an ``[axial]`` table gives a string
axial dynamics whatever its law, so Tucker-Wang and the RGD bit run on the same chain.

Numbers checked: Tucker-Wang (the paper's Eq. 2) on the axial chain of the built-in
``rgd_wave_pipe.toml`` string (strategy C in 100 m elements, dampers β k) through the axial
engine (fixed step, semi-implicit Euler) against the same string without ``[axial]``
through the torsional engine (RODAS4 on strategy C's model with Rayleigh damping
β [K], α = 0: the same dampers; an independent engine). The bit rests on the rock under
the hook weight, so the torsional motion must be the same, its stuck fraction (one
definition, |Ω_b| < 0.1 Ω₀) with it. The axial engine is first order:
at its default 100 steps per period S_SS is 9.7e-4 and 4.7e-4 (relative) above the
torsional engine's at 60 and 120 rpm, at 400 steps per period 2.4e-4 and 1.2e-4 (measured).
The test takes the finer run within 1e-3 and asserts the first-order fall of the error
(4 times per 4 times the steps; at least 3).
"""

from __future__ import annotations

import copy
import tomllib
from importlib import resources

import pytest

from torsio.analysis.transient import simulate
from torsio.axial import simulate_axial
from torsio.axial.rgd import RGDBit
from torsio.config.reading import parse_config
from torsio.errors import ConfigError
from torsio.physics.torque_law_bit import TorqueLawBit

TEXT = resources.files("torsio").joinpath("data/rgd_wave_pipe.toml").read_text(encoding="utf-8")
TUCKER_WANG = {  # the paper's Eq. 2 values (Ritto et al. 2017), rpm reading; the file's radius
    "law": "tucker-wang", "radius": 0.108, "a0": 0.221, "a1": 0.2, "a2": 0.89, "a3": 0.06,
    "speed_unit": "rpm",
}  # fmt: skip
WOB = 100e3
ELEMENTS = {"strategy": "C", "max_element_length": 100.0}


def _table(bit_rock: dict, axial: bool = True) -> dict:
    table = copy.deepcopy(tomllib.loads(TEXT))
    table["bit_rock"] = dict(bit_rock)
    table["discretization"] = dict(ELEMENTS)
    table["damping"] = {"alpha": 0.0, "beta": 0.06}
    if not axial:  # the same string, torsional only
        del table["axial"], table["simulation"]
    return table


@pytest.mark.parametrize("rpm", [60.0, 120.0])
def test_tucker_wang_on_a_strings_axial_chain_is_the_torsional_run(rpm):
    axial = parse_config(_table(TUCKER_WANG)).axial
    torsional = parse_config(_table(TUCKER_WANG, axial=False))
    assert isinstance(axial.bit, TorqueLawBit) and axial.bit.radius == 0.108
    assert axial.assembly.dofs == torsional.system().model.dofs == 10
    reference = simulate(torsional.system().at(wob=WOB, rpm=rpm))
    runs = [
        simulate_axial(axial.assembly, axial.bit, WOB, rpm,
                       **{**axial.run_options(), "steps_per_period": steps})
        for steps in (100, 400)
    ]  # fmt: skip
    assert reference.severity > 1.0  # stick-slip: a run that tests the law
    run, fine = runs
    assert fine.severity == pytest.approx(reference.severity, rel=1e-3)
    errors = [abs(r.severity - reference.severity) for r in runs]
    assert errors[0] > 3 * errors[1]  # first order in the step
    # the stuck fraction is counted as on the torsional engine, |Ω_b| < 0.1 Ω₀ (measured
    # 0.4016 against 0.4019 at 60 rpm, 0.2262 against 0.2243 at 120 rpm; its samples are
    # 1/200 of a period apart, the axial engine counts every step)
    assert fine.stick_threshold == reference.stick_threshold == 0.1
    assert fine.stick_fraction == pytest.approx(reference.stick_fraction, abs=0.005)
    assert run.axial.rop_mean == 0.0  # the bit rests on the rock
    assert run.axial.weight_mean == pytest.approx(WOB, rel=1e-9)


def test_the_same_axial_table_runs_the_rgd_bit_on_the_same_chain():
    rgd = parse_config(_table(tomllib.loads(TEXT)["bit_rock"])).axial
    tucker_wang = parse_config(_table(TUCKER_WANG)).axial
    assert isinstance(rgd.bit, RGDBit)
    for rows in ("inertia", "stiffness", "damping"):
        assert (getattr(rgd.assembly, rows) == getattr(tucker_wang.assembly, rows)).all()
    assert (rgd.assembly.axial.masses == tucker_wang.assembly.axial.masses).all()


def test_the_radius_defaults_to_the_bit_sections():
    law = {k: v for k, v in TUCKER_WANG.items() if k != "radius"}
    axial = parse_config(_table(law)).axial
    assert axial.bit.radius == pytest.approx(8.5 * 0.0254 / 2, rel=1e-15)  # the 8½ in bit


def test_without_axial_a_law_of_the_torque_alone_stays_torsional():
    table = _table(TUCKER_WANG, axial=False)
    assert parse_config(table).axial is None
    table["simulation"] = {"start": "steady"}
    with pytest.raises(ConfigError) as caught:
        parse_config(table)
    assert caught.value.key == "simulation.start" and "[axial]" in caught.value.message


def test_the_distributed_pipe_and_the_well_refuse_a_law_of_the_torque_alone_by_key():
    table = _table(TUCKER_WANG)
    table["discretization"] = {"strategy": "wave"}
    del table["damping"]
    with pytest.raises(ConfigError) as caught:
        parse_config(table)
    assert caught.value.key == "discretization.strategy" and "RGD bit only" in str(caught.value)
    well = tomllib.loads(
        resources.files("torsio").joinpath("data/rgd_deviated_well.toml").read_text("utf-8")
    )["well"]
    with pytest.raises(ConfigError) as caught:
        parse_config({**_table(TUCKER_WANG), "well": well})
    assert caught.value.key == "well" and "remove [axial]" in caught.value.message
    parse_config({**_table(TUCKER_WANG, axial=False), "well": well})  # torsionally: runs
