"""Read a survey from a CSV file: a header naming the columns md, inclination, azimuth.

Each column has its usual names (case ignored): ``md``, ``measured depth``; ``inclination``,
``inc``, ``incl``; ``azimuth``, ``azi``, ``azim``. A name may carry its unit in brackets or
parentheses, the header cell read as for recordings (``md [ft]``, ``MD (ft)``, ``md[ft]``,
``Inc (deg)``): md in m (default) or ft (0.3048 m exactly), angles in deg (default) or rad.
The columns may come in any order; other columns (tvd, north, ...) are read past; blank
lines and lines starting with ``#`` are skipped. A bad line is an error naming the file and
the line.

Examples
--------
>>> import pathlib, tempfile
>>> with tempfile.TemporaryDirectory() as folder:
...     path = pathlib.Path(folder) / "survey.csv"
...     _ = path.write_text("md,inclination,azimuth\\n0,0,0\\n1000,0,0\\n1300,30,45\\n")
...     read_survey_csv(path)
Survey(3 stations to md 1300 m, survey.csv)
>>> with tempfile.TemporaryDirectory() as folder:
...     path = pathlib.Path(folder) / "bad.csv"
...     _ = path.write_text("md,inclination,azimuth\\n0,0,0\\n1000,zero,0\\n")
...     read_survey_csv(path, key="well.survey")
Traceback (most recent call last):
...
torsio.errors.ConfigError: well.survey: bad.csv, line 3: column inclination: 'zero' is not a number
"""

from __future__ import annotations

import math
from pathlib import Path

from torsio.csv_rows import csv_rows, header_cell
from torsio.errors import ConfigError
from torsio.well.survey import Survey

__all__ = ["SURVEY_COLUMNS", "read_survey_csv"]

SURVEY_COLUMNS = ("md", "inclination", "azimuth")
"""The columns a survey file must name in its header (m, deg, deg)."""

COLUMN_NAMES: dict[str, str] = {
    **dict.fromkeys(("md", "measured depth"), "md"),
    **dict.fromkeys(("inclination", "inc", "incl"), "inclination"),
    **dict.fromkeys(("azimuth", "azi", "azim"), "azimuth"),
}
"""The column each header name stands for."""

_LENGTH = {"m": 1.0, "ft": 0.3048}  # 1 ft = 0.3048 m exactly (NIST SP 811, B.8)
_ANGLE = {"deg": 1.0, "°": 1.0, "rad": 180.0 / math.pi}
COLUMN_UNITS: dict[str, dict[str, float]] = {
    "md": _LENGTH,
    "inclination": _ANGLE,
    "azimuth": _ANGLE,
}
"""Factors from the units a column may name to its default unit (m, deg, deg)."""


def read_survey_csv(path: str | Path, key: str = "survey") -> Survey:
    """The :class:`~torsio.well.survey.Survey` in the CSV file ``path``.

    Parameters
    ----------
    path : str or Path
        The file; its header names the columns ``md`` [m], ``inclination`` [deg] and
        ``azimuth`` [deg] (case and surrounding spaces ignored).
    key : str
        The configuration key shown in errors.

    Raises
    ------
    ConfigError
        The file cannot be read, its header lacks a column, a line has too few fields or
        a value that is not a finite number, or the stations are not a valid survey
        (the error names the line of the offending station).
    """
    path = Path(path)
    name = path.name
    rows = csv_rows(path, key, "survey file", "md,inclination,azimuth")
    header_line, header = rows[0]
    index, factor = _header(header, name, header_line, key)
    columns: dict[str, list[float]] = {column: [] for column in SURVEY_COLUMNS}
    lines: list[int] = []
    for number, row in rows[1:]:
        for column, i in index.items():
            if i >= len(row):
                raise ConfigError(
                    key,
                    f"{name}, line {number}: {len(row)} fields, no value for column {column}",
                )
            cell = row[i].strip()
            try:
                value = float(cell)
            except ValueError:
                raise ConfigError(
                    key, f"{name}, line {number}: column {column}: {cell!r} is not a number"
                ) from None
            if not math.isfinite(value):
                raise ConfigError(
                    key,
                    f"{name}, line {number}: column {column}: expected a finite number, "
                    f"got {cell!r}",
                )
            columns[column].append(value * factor[column])
        lines.append(number)
    try:
        return Survey(columns["md"], columns["inclination"], columns["azimuth"], source=name)
    except ConfigError as exc:
        column, _, rest = exc.key.partition("[")
        station = int(rest.rstrip("]")) if rest else None
        where = f", line {lines[station]}" if station is not None and station < len(lines) else ""
        raise ConfigError(key, f"{name}{where}: column {column}: {exc.message}") from None


def _header(
    header: list[str], name: str, line: int, key: str
) -> tuple[dict[str, int], dict[str, float]]:
    """The index of each survey column in ``header`` and its factor to m or deg."""
    index: dict[str, int] = {}
    factor: dict[str, float] = {}
    for i, cell in enumerate(header):
        label, unit = header_cell(cell)
        column = COLUMN_NAMES.get(label)
        if column is None:
            continue
        if column in index:
            raise ConfigError(key, f"{name}, line {line}: column {column} is given twice")
        units = COLUMN_UNITS[column]
        if unit is not None and unit.lower() not in units:
            raise ConfigError(
                key,
                f"{name}, line {line}: column {cell.strip()!r}: unknown unit {unit!r}; "
                f"expected one of {', '.join(units)}",
            )
        index[column] = i
        factor[column] = units[unit.lower()] if unit is not None else 1.0
    missing = [column for column in SURVEY_COLUMNS if column not in index]
    if missing:
        raise ConfigError(
            key,
            f"{name}, line {line}: the header {','.join(header)!r} has no column "
            f"{missing[0]!r}; expected the columns {', '.join(SURVEY_COLUMNS)} "
            "(or MD, Inc, Azi; units in brackets, e.g. 'MD (ft)')",
        )
    return index, factor
