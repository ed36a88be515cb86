"""Every path gives the same S_SS on the same System: scipy, compiled batch, numpy batch.

The three are independent implementations of the one description of the dynamics
(torsio.physics.dynamics): ``torsio.analysis.transient.simulate`` integrates its
right-hand side with scipy's LSODA (rtol 1e-8, atol 1e-10, the reference); the compiled
batch kernel (torsio.solvers.rodas) and the numpy engine (torsio.solvers.numpy_engine)
integrate the chain arrays with RODAS4, each point with its own step, here at
rtol 1e-6, atol 1e-8. Agreement within 2e-3 in S_SS (of order 1 at the stick-slip
points) is agreement to solver tolerance: the two batch engines run the same method
and agree far closer (1e-6). With a PI top drive the scipy path is
``torsio.solvers.reference.reference_severity`` (solve_ivp, Radau, rtol 1e-8, atol 1e-10,
on the same right-hand side and exact Jacobian of the description).

The batch engine's own scipy path (engine="scipy": reference_severity per point, Radau
at the batch tolerances) is checked against the reference too. Which engine ran is asserted,
so that a law without a compiled kernel cannot silently fall back. The linearization's
eigenvalues against those of a central-difference Jacobian of the same right-hand side, for
the same 1, 5 and 40 DOF models and laws, are in tests/test_top_drive_analyses.py.

Cases: the built-in Ritto et al. (2017) string with 1 DOF (strategy A), 5 DOF (strategy C)
and 40 DOF (strategy C, 40 drill-pipe elements); Tucker-Wang and the bundled plugin's
coulomb-stribeck law; the top held at constant speed and a PI top drive (kp = 5000
N m s/rad, about 11 times the drill pipe's impedance, ki = 2900 N m/rad, J = 2900 kg m^2).
"""

from __future__ import annotations

import attrs
import numpy as np
import pytest

from torsio.analysis.transient import simulate
from torsio.examples import builtin_config
from torsio.physics.system import System
from torsio.plugins import get_bit_law, top_drive_from_parameters
from torsio.solvers.batch import simulate_batch
from torsio.solvers.batch_results import DEFAULT_STEADY_TOLERANCE
from torsio.solvers.reference import reference_options, reference_severity

DURATION, WINDOW = 60.0, 20.0  # s: long enough for stick-slip to form from rest
BATCH = {"rtol": 1e-6, "atol": 1e-8, "duration": DURATION, "steady_window": WINDOW}
MODELS = {1: {"strategy": "A"}, 5: {"strategy": "C"}, 40: {"strategy": "C", "dp_elements": 40}}
# operating points with stick-slip from rest (S_SS > 0.8 in every case below)
POINT = {"tucker-wang": (150e3, 60.0), "coulomb-stribeck": (100e3, 30.0)}


def _system(dofs: int, law: str, top: str) -> System:
    system = builtin_config().system(**MODELS[dofs])
    assert system.model.dofs == dofs
    if law != "tucker-wang":
        system = attrs.evolve(system, law=get_bit_law(law)())
    if top == "pi":
        pi = top_drive_from_parameters("pi", inertia=2900.0, kp=5000.0, ki=2900.0)
        system = system.with_top(pi)
    wob, rpm = POINT[law]
    return system.at(wob=wob, rpm=rpm)


def _slow(dofs: int, law: str, top: str) -> list[pytest.MarkDecorator]:
    # 40 DOFs run by default once (Tucker-Wang, held top, about 20 s); the rest with -m slow
    default = (dofs, law, top) == (40, "tucker-wang", "constant-speed")
    return [pytest.mark.slow] if dofs == 40 and not default else []


CASES = [
    pytest.param(dofs, law, top, marks=_slow(dofs, law, top))
    for dofs in (1, 5, 40)
    for law in ("tucker-wang", "coulomb-stribeck")
    for top in ("constant-speed", "pi")
]


@pytest.mark.parametrize(("dofs", "law", "top"), CASES)
def test_same_severity_on_every_path(dofs: int, law: str, top: str) -> None:
    system = _system(dofs, law, top)
    if top == "pi":
        reference, _ = reference_severity(
            system, reference_options(duration=DURATION, steady_window=WINDOW)
        )
    else:
        reference = simulate(
            system, duration=DURATION, steady_window=WINDOW, method="LSODA", rtol=1e-8, atol=1e-10
        ).severity
    point = ([system.wob], [system.rpm])
    compiled = simulate_batch(system, *point, engine="compiled", **BATCH)  # ends on the cycle
    whole = simulate_batch(system, *point, engine="compiled", steady_tolerance=0.0, **BATCH)
    numpy = simulate_batch(system, *point, engine="numpy", **BATCH)
    assert compiled.ok.all() and whole.ok.all() and numpy.ok.all()
    # each path really ran: the law's compiled kernel (Tucker-Wang's and the plugin's alike),
    # the fallback engine, and the scipy path
    assert (compiled.engine, whole.engine, numpy.engine) == ("compiled", "compiled", "numpy")
    if top != "pi":  # (with the PI top drive the reference already is the scipy engine's run)
        scipy = simulate_batch(system, *point, engine="scipy", **BATCH)
        assert scipy.engine == "scipy" and scipy.ok.all()
        assert abs(scipy.severity[0] - reference) < 2e-3
    assert reference > 0.8  # a stick-slip point: the comparison is not trivially 0 = 0
    assert abs(compiled.severity[0] - reference) < 2e-3
    assert abs(numpy.severity[0] - reference) < 2e-3
    # the same method to the end of the run: the same steps, S_SS to round-off
    np.testing.assert_allclose(numpy.severity, whole.severity, atol=1e-6)
    # ending on the steady cycle moves S_SS by at most the steady tolerance
    assert compiled.ended[0] < DURATION
    assert abs(compiled.severity[0] - whole.severity[0]) <= DEFAULT_STEADY_TOLERANCE
