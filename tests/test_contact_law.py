"""The one contact law along the string (torsio.solvers.contact_law): its step forms agree
with each other and its event form with the law's definition (Aarsnes & Shor 2018)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsio.solvers import contact_law as law


@pytest.mark.parametrize("free", [2.5, -2.5, 0.3, -0.05, 0.02, 0.0])
def test_the_cone_without_axial_motion_is_the_one_dimensional_law(free):
    # Moreau's step in one dimension (the closed form): a node of inertia I, free speed w*,
    # under the capacity C over h sticks while I |w*| <= h C, else w = sign(w*) (|w*| - h C/I);
    # that is excess(I w*/h, C) h/I, the torsional wave march's form (load d = I w*/h).
    # The cone with no axial velocity gives the same (measured: within 5e-16 rad/s).
    inertia, radius, step, static, sliding = 2.0, 0.0635, 1e-3, 60.0, 50.0
    for sticky, capacity in ((True, static), (False, sliding)):
        forces = static / radius, sliding / radius  # torque capacities C = F r
        velocity, speed, stuck = law.cone_step(
            0.0, free, radius, 1.0 / 500.0, 1.0 / inertia, *forces, step, sticky
        )
        load = inertia * free / step
        expected = math.copysign(law.excess(load, capacity), load) * step / inertia
        assert velocity == 0.0
        assert speed == pytest.approx(expected, abs=1e-15)
        assert stuck == (expected == 0.0)


def test_the_event_form_follows_the_definition():
    # the law (module docstring): friction C_s sign w slow, C_d sign w fast, 0 stuck; a node
    # at rest sticks if |H| < C_s, else moves the way of H on the static branch (the dynamic
    # one when w_th = 0); a stuck one breaks free the way of H; slow and fast swap at w_th
    static, dynamic, threshold = 4.0, 3.0, 0.5
    assert [law.friction(c, static, dynamic) for c in (-2.0, -1.0, 0.0, 1.0, 2.0)] == [
        -3.0, -4.0, 0.0, 4.0, 3.0
    ]  # fmt: skip
    assert [law.start_code(w, threshold) for w in (-1.0, -0.2, 0.0, 0.2, 0.5)] == [
        -2.0, -1.0, 0.0, 1.0, 2.0
    ]  # fmt: skip
    assert law.switched(0.0, 1, -4.5, static, threshold) == -1.0  # breaks free
    assert law.switched(0.0, 1, 4.5, static, 0.0) == 2.0  # no static branch without w_th
    assert law.switched(-1.0, 1, 3.9, static, threshold) == 0.0  # at rest, held
    assert law.switched(-1.0, 1, 4.1, static, threshold) == 1.0  # at rest, turns
    assert law.switched(-1.0, 2, 0.0, static, threshold) == -2.0  # across w_th
    assert law.switched(2.0, 2, 0.0, static, threshold) == 1.0
    # margins fall through 0 at the switches: a moving node's speed in its direction, a
    # stuck one's C_s - |H|, a moving one's distance to w_th; inf where no contact
    code = np.array([[0.0, -1.0, 2.0, 0.0]])
    speed, holding = np.array([[0.0, -0.2, 0.7, 0.0]]), np.array([[3.0, 0.0, 0.0, 0.0]])
    out = np.empty((1, 2, 4))
    law.margins(code, np.array([static, static, static, 0.0]), np.full(4, threshold), speed,
                holding, out)  # fmt: skip
    assert out[0, 0].tolist() == pytest.approx([1.0, 0.2, 0.7, math.inf])
    assert out[0, 1].tolist() == pytest.approx([1.0, 0.3, 0.2, math.inf])
