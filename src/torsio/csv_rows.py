"""The rows of a small CSV file of numbers (a survey, a rig recording), with line numbers.

One reader for every CSV input: UTF-8 text (a byte-order mark allowed), the standard
library's ``csv``, blank lines and lines starting with ``#`` skipped; errors name the
configuration key and the file.

Examples
--------
>>> import pathlib, tempfile
>>> path = pathlib.Path(tempfile.mkdtemp()) / "survey.csv"
>>> _ = path.write_text("# a survey\\nmd,inclination,azimuth\\n\\n0,0,0\\n")
>>> csv_rows(path, "well.survey", "survey file", "md,inclination,azimuth")
[(2, ['md', 'inclination', 'azimuth']), (4, ['0', '0', '0'])]
"""

from __future__ import annotations

import csv
import re
from pathlib import Path

from torsio.errors import ConfigError

__all__ = ["csv_rows", "header_cell"]

_HEADER_CELL = re.compile(r"^\s*(.*?)\s*(?:\[\s*([^\]]*?)\s*\]|\(\s*([^)]*?)\s*\))?\s*$")


def header_cell(cell: str) -> tuple[str, str | None]:
    """A header cell's column name (lower case, inner spaces single) and its unit, if it
    gives one in brackets or parentheses (``md [ft]``, ``MD (ft)``, ``md[ft]``).

    Examples
    --------
    >>> header_cell(" MD (ft) "), header_cell("md[ft]"), header_cell("Measured  Depth")
    (('md', 'ft'), ('md', 'ft'), ('measured depth', None))
    >>> header_cell("surface_torque [kN*m]")
    ('surface_torque', 'kN*m')
    """
    match = _HEADER_CELL.match(cell)
    assert match is not None  # the pattern matches any text
    unit = match[2] if match[2] is not None else match[3]
    return " ".join(match[1].lower().split()), unit


def csv_rows(path: Path, key: str, what: str, header: str) -> list[tuple[int, list[str]]]:
    """(line number, cells) of every row of ``path`` that holds something, the header first.

    ``what`` names the file in errors (``"survey file"``), ``header`` the columns expected
    of an empty file. ConfigError on ``key`` when the file cannot be read, is not UTF-8 or
    holds no row.
    """
    try:
        text = path.read_text(encoding="utf-8-sig")
    except OSError as exc:
        raise ConfigError(key, f"cannot read {what} {str(path)!r}: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise ConfigError(key, f"{what} {str(path)!r} is not UTF-8 text") from None
    rows = [
        (number, row)
        for number, row in enumerate(csv.reader(text.splitlines()), start=1)
        if row and any(cell.strip() for cell in row) and not row[0].lstrip().startswith("#")
    ]
    if not rows:
        raise ConfigError(key, f"{path.name}: the file is empty; expected a header {header}")
    return rows
