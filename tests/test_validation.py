"""The validation table: every check passes, and docs/validation.md is up to date."""

from __future__ import annotations

from pathlib import Path

import pytest

from torsio.io.validation import CHECKS, page

PAGE = Path(__file__).parents[1] / "docs" / "validation.md"


@pytest.mark.parametrize("name", list(CHECKS))
def test_check_passes(name):
    row = CHECKS[name]()
    assert row.passed, (
        f"{row.quantity}: torsio {row.value!r} vs {row.source} "
        f"{row.source_value!r} (tolerance {row.tolerance!r})"
    )


def test_validation_page_is_generated_from_the_checks():
    # Regenerate with: python -m torsio.io.validation --write docs/validation.md
    assert PAGE.read_text(encoding="utf-8") == page()
