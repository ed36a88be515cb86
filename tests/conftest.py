"""Shared fixtures: the paper's string and its continuum reference."""

from __future__ import annotations

import pytest

from torsio import builtin_config, continuum_modes, ritto2017_string
from torsio.model.drillstring import DrillString
from torsio.model.lumped import LumpedModel
from torsio.physics.damping import ModelDamping
from torsio.physics.laws import TuckerWang
from torsio.physics.system import System


@pytest.fixture(scope="session")
def ritto() -> DrillString:
    """The drill-string of the paper's Table 1 (Ritto et al. 2017)."""
    return ritto2017_string()


@pytest.fixture(scope="session")
def continuum30(ritto: DrillString):
    """First 30 exact frequencies of the flexible stepped shaft."""
    return continuum_modes(ritto, 30)


@pytest.fixture(scope="session")
def continuum_rigid(ritto: DrillString):
    """First 5 exact frequencies with the BHA rigid (strategy C's limit)."""
    return continuum_modes(ritto, 5, rigid_bha=True)


@pytest.fixture(scope="session")
def one_dof() -> System:
    """The built-in Ritto (2017) system with strategy A (1 DOF)."""
    return builtin_config().system(strategy="A")


@pytest.fixture(scope="session")
def ten_dof() -> System:
    """The built-in Ritto (2017) system with strategy C and 10 drill-pipe elements."""
    return builtin_config().system(strategy="C", dp_elements=10)


@pytest.fixture
def chain_with_own_dampers() -> System:
    """A 3-inertia chain carrying its own dampers and drag (ModelDamping), Tucker-Wang."""
    model = LumpedModel.from_chain(
        inertias=[300.0, 200.0, 450.0],
        stiffnesses=[900.0, 700.0, 800.0],
        dampings=[40.0, 30.0, 35.0],
        drag=[20.0, 0.0, 50.0],
    )
    return System(
        model=model,
        law=TuckerWang(a0=0.221, a1=0.2, a2=0.89, a3=0.06, speed_unit="rpm"),
        bit_radius=0.108,
        damping=ModelDamping(),
        wob=100e3,
        rpm=40.0,
    )
