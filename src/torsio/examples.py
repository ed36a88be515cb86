"""Ready-made examples that tests, doctests and users share.

>>> string = ritto2017_string()
>>> string.name
'Ritto et al. (2017)'
"""

from __future__ import annotations

from torsio.io.config import Config, builtin_config
from torsio.model.drillstring import DrillString


def ritto2017_config() -> Config:
    """The built-in configuration: Table 1 of the paper (Ritto et al. 2017), G = 85.3 GPa."""
    return builtin_config()


def ritto2017_string() -> DrillString:
    """The drill-string of the paper's Table 1: drill pipes, HWDP, collars/MWD/LWD, bit."""
    string = builtin_config().string
    assert string is not None  # the built-in example is a drill-string, not a chain
    return string
