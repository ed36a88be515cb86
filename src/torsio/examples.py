"""Ready-made examples that tests, doctests and users share.

>>> string = ritto2017_string()
>>> string.name
'Ritto et al. (2017)'
>>> deviated_well_config().well.survey.depth
2500.0
"""

from __future__ import annotations

from importlib import resources

from torsio.io.config import Config, builtin_config, parse_config_text
from torsio.model.drillstring import DrillString


def ritto2017_config() -> Config:
    """The built-in configuration: Table 1 of the paper (Ritto et al. 2017), G = 85.3 GPa."""
    return builtin_config()


def ritto2017_string() -> DrillString:
    """The drill-string of the paper's Table 1: drill pipes, HWDP, collars/MWD/LWD, bit."""
    string = builtin_config().string
    assert string is not None  # the built-in example is a drill-string, not a chain
    return string


def deviated_well_config() -> Config:
    """A 2.5 km string in an S-shaped well with a 3-D turn (``data/deviated_well.toml``):
    the built-in example of ``[well]`` and ``torsio drag``."""
    path = resources.files("torsio").joinpath("data/deviated_well.toml")
    return parse_config_text(path.read_text(encoding="utf-8"), source="built-in deviated_well.toml")
