"""The torque on bit on bottom that torque and drag adds at the bit: the configured law's at
the operating point (``torsio drag``, the report's well section).

Examples
--------
>>> from torsio.examples import deviated_well_config
>>> torque, source = law_bit_torque(deviated_well_config(), 80e3)
>>> round(torque), source  # N m: Tucker-Wang at [operation] rpm, the bit turning steadily
(2191, 'tucker-wang at 100 rpm')
"""

from __future__ import annotations

from typing import Any

from torsio.config.tables import parse_rpm
from torsio.errors import ConfigError
from torsio.units import RPM_TO_RAD_S

__all__ = ["law_bit_torque"]


def law_bit_torque(config: Any, wob: float, rpm: Any = None) -> tuple[float, str]:
    """The torque on bit [N m] of the configured law at ``wob`` [N] and the operating rotary
    speed (``rpm``, else ``[operation] rpm``), and where it comes from: Tucker-Wang (or any
    rate law) at the bit turning steadily at that speed; the RGD bit's steady drilling state
    (:func:`torsio.axial.steady.steady_drilling`). Off bottom (``wob`` 0): none.
    """
    if wob == 0.0:
        return 0.0, "off bottom"
    if config.bit_rock is None:
        raise ConfigError(
            "bit_rock",
            "the torque on bit on bottom comes from the bit-rock law, and the configuration "
            "has none: add [bit_rock] or give --bit-torque",
        )
    if rpm is not None:
        speed = parse_rpm(rpm, "--rpm")
    elif config.operation.rpm is not None:
        speed = float(config.operation.rpm)
    else:
        raise ConfigError(
            "operation.rpm",
            "the torque on bit on bottom is the law's at the rotary speed: give --rpm, set "
            "[operation] rpm, or give --bit-torque",
        )
    if config.axial is not None:  # the RGD bit
        from torsio.axial.steady import steady_drilling

        state = steady_drilling(config.axial.bit, wob, speed)
        return float(state.bit_torque), f"rgd steady drilling at {speed:g} rpm"
    law = config.bit_law()
    torque = float(law.torque(speed * RPM_TO_RAD_S, wob, config.bit_radius))
    return torque, f"{law.name} at {speed:g} rpm"
