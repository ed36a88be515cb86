"""Read a survey from a CSV file: a header naming the columns md, inclination, azimuth.

Units: md in metres, inclination and azimuth in degrees. The columns may come in any
order; other columns (tvd, north, ...) are read past; blank lines and lines starting with
``#`` are skipped. A bad line is an error naming the file and the line.

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

from torsio.csv_rows import csv_rows
from torsio.errors import ConfigError
from torsio.well.survey import Survey

__all__ = ["SURVEY_COLUMNS", "read_survey_csv"]

SURVEY_COLUMNS = ("md", "inclination", "azimuth")
"""The columns a survey file must name in its header (m, deg, deg)."""


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
    names = [cell.strip().lower() for cell in header]
    missing = [column for column in SURVEY_COLUMNS if column not in names]
    if missing:
        raise ConfigError(
            key,
            f"{name}, line {header_line}: the header {','.join(header)!r} has no column "
            f"{missing[0]!r}; expected the columns {', '.join(SURVEY_COLUMNS)}",
        )
    index = {column: names.index(column) for column in SURVEY_COLUMNS}
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
            columns[column].append(value)
        lines.append(number)
    try:
        return Survey(columns["md"], columns["inclination"], columns["azimuth"], source=name)
    except ConfigError as exc:
        column, _, rest = exc.key.partition("[")
        station = int(rest.rstrip("]")) if rest else None
        where = f", line {lines[station]}" if station is not None and station < len(lines) else ""
        raise ConfigError(key, f"{name}{where}: column {column}: {exc.message}") from None
