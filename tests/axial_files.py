"""Configurations the axial tests share: the built-in 2-DOF file, a [[section]] string
with its RGD bit (1000 m of 5 in drill pipe above 150 m of 6 3/4 in collars and the bit),
and the damped 3-node pipe of the chain stability tests."""

from __future__ import annotations

import tomllib
from collections.abc import Sequence
from importlib import resources
from typing import Any

from torsio.model.axial_assembly import axial_chain, axial_model, pipe_string, tube_section
from torsio.model.components import Section
from torsio.model.discretize import StrategyC
from torsio.model.lumped import LumpedModel
from torsio.model.wave import WaveModel, WaveStrategy

TEXT = resources.files("torsio").joinpath("data/rgd_2dof.toml").read_text(encoding="utf-8")
BASE: dict[str, Any] = tomllib.loads(TEXT)

STRING: dict[str, Any] = {
    "material": {"shear_modulus": "79.3 GPa", "density": 7850, "youngs_modulus": "207 GPa"},
    "section": [
        {"kind": "drill_pipe", "od": "5 in", "id": "4.276 in", "length": "1000 m"},
        {"kind": "drill_collar", "od": "6.75 in", "id": "2.8125 in", "length": "150 m"},
        {"kind": "bit", "od": "8.5 in", "id": 0.0, "length": 0.3},
    ],
    "damping": {"beta": 0.06},
    "bit_rock": dict(BASE["bit_rock"]),
    "operation": {"wob": "100 kN", "rpm": 60},
}


def pipe_chain(
    nodes: int, pipe: Section, bha_mass: float, bha_inertia: float, hook: str = "weight"
) -> LumpedModel:
    """The strategy-C chain of a uniform ``pipe`` in ``nodes`` elements above a rigid BHA
    of ``bha_mass`` [kg] and ``bha_inertia`` [kg m²], undamped."""
    string = pipe_string([pipe], bha_mass, bha_inertia)
    chain = axial_model(string, StrategyC(dp_elements=nodes), hook)
    assert isinstance(chain, LumpedModel)
    return chain


def wave_pipe(
    pipes: Sequence[Section],
    bha_mass: float,
    bha_inertia: float,
    hook: str = "weight",
    travel_time_tolerance: float | None = None,
) -> WaveModel:
    """The distributed pipe of ``pipes`` (from the top down) above a rigid BHA of
    ``bha_mass`` [kg] and ``bha_inertia`` [kg m²]."""
    strategy = WaveStrategy(travel_time_tolerance=travel_time_tolerance, rigid_bha=True)
    pipe = axial_model(pipe_string(pipes, bha_mass, bha_inertia), strategy, hook)
    assert isinstance(pipe, WaveModel)
    return pipe


PIPE = (3, tube_section(900.0, 2.1e11, 8.1e10, 7850.0, 3.4e-3, 1.5e-5), 29981.3, 230.0)
"""pipe_chain's arguments: 3 nodes of a 900 m pipe (E = 210 GPa, G = 81 GPa, ρ = 7850
kg/m³, A = 3.4e-3 m², J = 1.5e-5 m⁴) above the 2-DOF example's BHA (29981.3 kg, 230 kg m²)."""


def damped_pipe(hook: str) -> LumpedModel:
    """The 3-node :data:`PIPE` with dampers β k (β = 0.06 s, the built-in Rayleigh β) and
    1e-3 s k_a."""
    pipe = pipe_chain(*PIPE, hook=hook)
    return axial_chain(
        pipe.node_inertias,
        pipe.springs,
        pipe.axial.masses,
        axial_stiffnesses=pipe.axial.stiffnesses,
        dampings=0.06 * pipe.springs,
        axial_dampings=1e-3 * pipe.axial.stiffnesses,
        hook=hook,
    )
