"""The packed arrays of the compiled kernels are laid out once (solvers/layouts.py)."""

from __future__ import annotations

import re
from pathlib import Path

from torsio.solvers import layouts
from torsio.solvers.layouts import field_starts

SOLVERS = Path(__file__).parents[1] / "src" / "torsio" / "solvers"

# an array of a layout indexed by a number: settings[5], out[:, 2], heads[s, 0], ...
LITERAL_SLOT = re.compile(
    r"\b(?:settings|summary|top|carry|window|cycle|cycle_settings|previous|coefficients"
    r"|bit_state|top_state|gains|chain|vectors|small|contacts|speed_table|table)\[-?\d"
    r"|\bout\[(?::, )?\d|\b(?:heads|contact_index)\[s, \d"
)


def test_field_starts_follow_the_lengths():
    assert field_starts() == (0,)
    assert field_starts(2, 9, 1) == (0, 2, 11, 12)


def test_sizes_and_named_starts():
    assert layouts.TOP_SIZE == layouts.TOP_W + layouts.MAX_STATES
    assert layouts.TOP_B - layouts.TOP_A == layouts.MAX_STATES**2
    assert layouts.OUT_COLUMNS == layouts.OUT_ENDED + 1
    assert layouts.VEC_CONTACT_STATE == layouts.VEC_CROSS + layouts.CROSS_ROWS
    assert layouts.VECTOR_ROWS == layouts.VEC_CONTACT_PENDING + 1
    assert layouts.FRICTION_SIZE <= layouts.SMALL_COLUMNS
    assert layouts.SMALL_CARRY + 1 == layouts.SMALL_WINDOW < layouts.SMALL_ROWS
    assert max(layouts.CARRY_SIZE, layouts.WINDOW_SIZE, layouts.CYCLE_SIZE) <= layouts.SMALL_COLUMNS
    assert layouts.GAIN_STATES + layouts.MAX_STATES <= layouts.SMALL_COLUMNS
    assert layouts.SUMMARY_SIZE == layouts.SUM_BIT_FIRST_MOTION + 1
    assert len(layouts.SUMMARY_FIELDS) == layouts.SUM_FAILED_STEP + 1
    assert layouts.SUM_STEPS == layouts.SUM_POWERS + layouts.POWER_COUNT


def test_no_slot_index_is_written_as_a_number():
    found = [
        f"{path.name}:{number}: {line.strip()}"
        for path in sorted(SOLVERS.glob("*.py"))
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
        if LITERAL_SLOT.search(line)
    ]
    assert found == []
