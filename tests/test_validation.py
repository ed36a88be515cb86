"""The validation table: every check passes, and docs/validation.md is up to date."""

from __future__ import annotations

from pathlib import Path

import pytest

from torsio.report.validation import CHECKS, Check, page
from torsio.report.validation_page import difference_text

PAGE = Path(__file__).parents[1] / "docs" / "validation.md"


@pytest.mark.parametrize("name", list(CHECKS))
def test_check_passes(name):
    row = CHECKS[name]()
    assert row.passed, (
        f"{row.quantity}: torsio {row.value!r} vs {row.source} "
        f"{row.source_value!r} (tolerance {row.tolerance!r})"
    )


def test_validation_page_is_generated_from_the_checks():
    # Regenerate with: python -m torsio.report.validation --write docs/validation.md
    assert PAGE.read_text(encoding="utf-8") == page()


def test_round_off_is_printed_as_a_machine_independent_bound():
    # two machines' round-off on the same check (the page differed by CPU/BLAS):
    # -4.89e-10 % and +1.44e-14 % of 6.15656 rad, tolerance 1e-6 relative (the page's row)
    tolerance = 1e-6 * 6.15656
    a = Check("twist", "Eq. 9", -6.15656, -6.15656 * (1 - 4.89e-12), tolerance)
    b = Check("twist", "Eq. 9", -6.15656, -6.15656 * (1 + 1.44e-16), tolerance)
    assert difference_text(a) == difference_text(b) == "< 1e-7 %"
    # a difference of a tenth of the tolerance keeps its digits: 1e-7 relative = 1e-5 %
    c = Check("twist", "Eq. 9", -6.15656, -6.15656 + 0.1 * tolerance, tolerance)
    assert difference_text(c) == "+1e-05 %"
