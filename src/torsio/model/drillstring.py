"""The drill-string: an ordered, validated assembly of sections from the surface to the bit.

Examples
--------
>>> from torsio.examples import ritto2017_string
>>> string = ritto2017_string()
>>> [s.kind for s in string.sections]
['drill_pipe', 'hwdp', 'bha', 'bit']
>>> round(string.drill_pipe_inertia, 2), round(string.bha_inertia, 2)
(665.61, 233.78)
"""

from __future__ import annotations

from collections.abc import Iterable

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.model.components import Bit, Section


def _to_tuple(sections: Iterable[Section]) -> tuple[Section, ...]:
    return tuple(sections)


@attrs.frozen(repr=False)
class DrillString:
    """Sections listed from the surface down to the bit.

    Rules checked on construction:

    * every item is a :class:`~torsio.model.components.Section`;
    * exactly one :class:`~torsio.model.components.Bit`, and it is last;
    * at least one flexible (non-bit) section;
    * the BHA is one contiguous block just above the bit (drill pipe cannot sit
      below a BHA section), and the bit is always part of the BHA.

    Parameters
    ----------
    sections : iterable of Section
        From the surface down; the bit last.
    name : str
        Shown in reports.
    """

    sections: tuple[Section, ...] = attrs.field(converter=_to_tuple)
    name: str = attrs.field(default="", converter=str)

    def __repr__(self) -> str:  # short: section names, not every field
        names = ", ".join(repr(s.name or type(s).__name__) for s in self.sections)
        length = sum(s.length for s in self.sections)
        return f"DrillString({self.name!r}, {len(self.sections)} sections, {length:g} m: {names})"

    def __attrs_post_init__(self) -> None:
        sections = self.sections
        for i, section in enumerate(sections):
            if not isinstance(section, Section):
                raise ConfigError(f"section[{i}]", f"expected a Section, got {section!r}")
        if not sections:
            raise ConfigError("section", "a drill-string needs at least one section and a bit")
        bits = [i for i, s in enumerate(sections) if isinstance(s, Bit)]
        if not bits:
            raise ConfigError("section", 'no bit: the last section must have kind = "bit"')
        if len(bits) > 1:
            raise ConfigError(
                f"section[{bits[1]}]", f"a drill-string has one bit; found bits at positions {bits}"
            )
        if bits[0] != len(sections) - 1:
            raise ConfigError(
                f"section[{bits[0]}]",
                f"the bit must be the last section (it is at position {bits[0]} "
                f"of {len(sections)})",
            )
        if sections[-1].bha is False:
            raise ConfigError(
                f"section[{len(sections) - 1}].bha",
                "the bit always belongs to the BHA; bha = false is not allowed",
            )
        if len(sections) < 2:
            raise ConfigError(
                "section", "a drill-string needs at least one flexible section above the bit"
            )
        flags = [s.in_bha for s in sections[:-1]]
        first_bha = flags.index(True) if True in flags else len(flags)
        for i in range(first_bha, len(flags)):
            if not flags[i]:
                raise ConfigError(
                    f"section[{i}].bha",
                    f"{sections[i].describe()} is not BHA but lies below the BHA section "
                    f"{sections[first_bha].describe()}; the BHA must be one block above the bit",
                )

    # --- parts -------------------------------------------------------------------------
    @property
    def bit(self) -> Bit:
        """The bit (always the last section)."""
        bit = self.sections[-1]
        assert isinstance(bit, Bit)
        return bit

    @property
    def flexible_sections(self) -> tuple[Section, ...]:
        """All sections but the bit, from the surface down: the springs of the models."""
        return self.sections[:-1]

    @property
    def drill_pipe_sections(self) -> tuple[Section, ...]:
        """Sections above the BHA."""
        return tuple(s for s in self.flexible_sections if not s.in_bha)

    @property
    def bha_sections(self) -> tuple[Section, ...]:
        """Flexible BHA sections (the bit excluded)."""
        return tuple(s for s in self.flexible_sections if s.in_bha)

    # --- lumped quantities ---------------------------------------------------------------
    @property
    def drill_pipe_inertia(self) -> float:
        """I_DP: inertia of the drill pipes [kg m^2]."""
        return float(sum(s.inertia for s in self.drill_pipe_sections))

    @property
    def bha_inertia(self) -> float:
        """I_BHA: inertia of the BHA sections and the bit [kg m^2]."""
        return float(sum(s.inertia for s in self.bha_sections) + self.bit.inertia)

    @property
    def drill_pipe_stiffness(self) -> float:
        """Series stiffness of the drill pipes, 1 / sum(L/GJ) [N m/rad]."""
        dps = self.drill_pipe_sections
        if not dps:
            return float("inf")
        return 1.0 / sum(1.0 / s.stiffness for s in dps)

    @property
    def flexible_length(self) -> float:
        """Depth of the top of the bit [m] (the bit length excluded)."""
        return float(sum(s.length for s in self.flexible_sections))

    @property
    def section_tops(self) -> np.ndarray:
        """Depth of the top of each section, bit included [m]."""
        return np.concatenate([[0.0], np.cumsum([s.length for s in self.sections])[:-1]])

    def with_sections(self, sections: Iterable[Section]) -> DrillString:
        """A copy with other sections (e.g. one made longer), validated again."""
        return DrillString(sections, name=self.name)
