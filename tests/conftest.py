"""Shared fixtures: the paper's string and its continuum reference."""

from __future__ import annotations

import pytest

from torsio import continuum_modes, ritto2017_string
from torsio.drillstring import DrillString


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
