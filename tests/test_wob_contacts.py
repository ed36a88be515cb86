"""The contacts along the string at the run's weight on bit (docs/well.md, "Friction in the
dynamics"): the normal force of the rotating soft-string state on bottom, whose tension is
the off-bottom one less the weight on bit (no axial friction while rotating).

References: the closed form of a straight inclined hole (N = w sin(inc), whatever the
tension) and torsio.well.break_off at the same weight (the capacities add up to it).
"""

from __future__ import annotations

import pickle

import attrs
import numpy as np
import pytest

from torsio.examples import deviated_well_config
from torsio.model.components import Bit, DrillPipe, Material
from torsio.model.drillstring import DrillString
from torsio.solvers.batch import simulate_batch
from torsio.well.break_off import break_off
from torsio.well.string_contacts import CONTACT_CELL_LENGTH
from torsio.well.survey import Survey
from torsio.well.wellbore import Wellbore


def _lumped():
    return deviated_well_config().system(strategy="B", dp_elements=10, bha_elements=4)


def test_a_straight_inclined_hole_breaks_off_at_the_same_torque_on_bottom():
    # closed form: no curvature, so N = w sin(inc) whatever the tension (soft-string model)
    steel = Material(shear_modulus=80e9, density=7850.0)
    pipe = DrillPipe(od=0.127, id=0.1086, length=999.0, material=steel)
    string = DrillString([pipe, Bit(od=0.127, id=0.1086, length=1.0, material=steel)])
    well = Wellbore(Survey([0.0, 1000.0], [60.0, 60.0], [0.0, 0.0]), friction_static=0.3,
                    friction_dynamic=0.2)  # fmt: skip
    off = break_off(well, string)
    on = break_off(well, string, wob=80e3)
    assert on.torque == pytest.approx(off.torque, rel=1e-12)


@pytest.mark.parametrize("strategy", ["B", "wave"])
def test_the_contacts_follow_the_weight_on_bit(strategy):
    # reference: break_off at the same weight; in the curves of the built-in S-shaped well
    # the lower tension lowers the normal force: measured -11 % of the break-off torque at
    # 80 kN (10819 against 12174 N m off bottom)
    config = deviated_well_config()
    options = {"dp_elements": 10, "bha_elements": 4} if strategy == "B" else {}
    assert config.operation.wob == 80e3  # the file's operating point: contacts built there
    assert config.system(strategy=strategy, **options).model.contacts.wob == 80e3
    system = config.system(strategy=strategy, **options).at(wob=0.0)
    assert system.model.contacts.wob == 0.0
    moved = system.at(wob=80e3).model.contacts
    expected = break_off(config.well, config.string, CONTACT_CELL_LENGTH, wob=80e3)
    assert moved.wob == 80e3
    assert moved.static_total == pytest.approx(expected.torque, rel=1e-12)
    assert moved.dynamic_total == pytest.approx(expected.sliding_torque, rel=1e-12)
    assert moved.static_total < 0.97 * system.model.contacts.static_total
    off = break_off(config.well, config.string, CONTACT_CELL_LENGTH)
    assert system.model.contacts.static_total == pytest.approx(off.torque, rel=1e-12)


def test_the_gravity_normal_force_does_not_depend_on_the_weight_on_bit():
    config = deviated_well_config()
    well = attrs.evolve(config.well, normal_force="gravity")
    system = attrs.evolve(config, well=well).system(strategy="B", dp_elements=10, bha_elements=4)
    assert not system.model.contacts.depends_on_wob
    assert system.at(wob=80e3).model.contacts is system.model.contacts


@pytest.mark.parametrize("strategy", ["B", "wave"])
def test_a_batch_runs_each_weight_with_its_own_contacts(strategy):
    # the same kernel on the same chain (lumped: the batch runs weight by weight; wave: each
    # point with the System at its weight): a batch over two weights equals each weight's
    # batch run with the System at that weight, to the last digit
    options = {"dp_elements": 10, "bha_elements": 4} if strategy == "B" else {}
    system = deviated_well_config().system(strategy=strategy, **options).at(wob=0.0)
    run = {"duration": 10.0, "steady_window": 5.0}
    points = [(20e3, 60.0), (60e3, 60.0), (20e3, 100.0)]
    both = simulate_batch(system, *np.array(points).T, **run)
    for k, (wob, rpm) in enumerate(points):
        alone = simulate_batch(system.at(wob=wob), [wob], [rpm], **run)
        assert both.severity[k] == alone.severity[0]
        assert both.steps[k] == alone.steps[0]
    fixed = attrs.evolve(system.model.contacts, rebuild=None)  # all at 0 N
    at_zero = simulate_batch(attrs.evolve(system, model=system.model.with_contacts(fixed)),
                             [60e3], [60.0], **run)  # fmt: skip
    assert at_zero.severity[0] != both.severity[1]


def test_a_system_with_contacts_that_follow_the_weight_travels_to_workers():
    system = pickle.loads(pickle.dumps(_lumped().at(wob=30e3)))
    assert system.model.contacts.wob == 30e3
    np.testing.assert_allclose(
        system.at(wob=60e3).model.contacts.static,
        _lumped().at(wob=60e3).model.contacts.static,
        rtol=1e-12,
    )
