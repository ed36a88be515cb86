"""The ``[well]`` table of a configuration: survey, hole sections, friction and mud.

The survey is given inline (``md``, ``inclination``, ``azimuth``: arrays, md in m or with
units, angles in degrees) or as a CSV file (``survey = "file.csv"``, relative to the
configuration file's folder). Every error names its key (``well.md[3]``,
``well.hole[1].friction_dynamic``) or the file and line.

Examples
--------
>>> well = parse_well({"md": [0, 1000, 1600], "inclination": [0, 0, 60],
...                    "azimuth": [0, 0, 0], "mud_density": "1.2 g/cm^3"})
>>> well.mud_density, well.survey.depth
(1200.0, 1600.0)
>>> parse_well({"md": [0, 1000], "inclination": [0, 190], "azimuth": [0, 0]})
Traceback (most recent call last):
...
torsio.errors.ConfigError: well.inclination[1]: expected an inclination from 0 to 180 degrees, ...
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from torsio.config.tables import _positive_number, _string, _table
from torsio.errors import ConfigError
from torsio.units import to_si
from torsio.well.survey import Survey
from torsio.well.survey_csv import read_survey_csv
from torsio.well.wellbore import HoleSection, Wellbore, check_mud_density, string_top_md

if TYPE_CHECKING:
    from torsio.model.drillstring import DrillString

__all__ = ["HOLE_KEYS", "WELL_KEYS", "parse_well", "well_table"]

WELL_KEYS = {
    "mud_density",
    "md",
    "inclination",
    "azimuth",
    "survey",
    "friction_static",
    "friction_dynamic",
    "threshold_speed",
    "normal_force",
    "hole",
}
HOLE_KEYS = {"to_md", "friction_static", "friction_dynamic", "name"}
_INLINE = ("md", "inclination", "azimuth")


def _folder(source: str) -> Path:
    """The folder relative survey paths are read from: the configuration file's, else the
    working directory (a configuration given as text or a dict)."""
    path = Path(source)
    return path.parent if source and path.is_file() else Path.cwd()


def _degrees(values: Any, key: str) -> list[Any]:
    if not isinstance(values, list):
        raise ConfigError(key, f"expected an array of angles in degrees, got {values!r}")
    out: list[Any] = []
    for i, value in enumerate(values):
        if isinstance(value, str):
            try:
                value = float(value)
            except ValueError:
                raise ConfigError(
                    f"{key}[{i}]", f"expected a number of degrees, got {value!r}"
                ) from None
        out.append(value)
    return out


def _survey(table: Mapping[str, Any], source: str) -> Survey:
    inline = [key for key in _INLINE if key in table]
    if "survey" in table:
        if inline:
            raise ConfigError(
                f"well.{inline[0]}",
                "the survey is given twice: as the file well.survey and as arrays; give one",
            )
        name = _string(table["survey"], "well.survey")
        path = Path(name)
        if not path.is_absolute():
            path = _folder(source) / path
        return read_survey_csv(path, key="well.survey")
    if not inline:
        raise ConfigError(
            "well",
            'no survey: give md, inclination and azimuth (arrays) or survey = "file.csv"',
        )
    for key in _INLINE:
        if key not in table:
            raise ConfigError(f"well.{key}", "missing: md, inclination and azimuth go together")
    raw_md = table["md"]
    if not isinstance(raw_md, list):
        raise ConfigError("well.md", f"expected an array of measured depths, got {raw_md!r}")
    md = [to_si(value, "length", key=f"well.md[{i}]") for i, value in enumerate(raw_md)]
    try:
        return Survey(
            md,
            _degrees(table["inclination"], "inclination"),
            _degrees(table["azimuth"], "azimuth"),
            source="[well]",
        )
    except ConfigError as exc:  # keys inside are relative to [well]: prefixed here only
        raise ConfigError(f"well.{exc.key}", exc.message) from None


def _hole(raw: Any) -> tuple[HoleSection, ...]:
    if not isinstance(raw, list):
        raise ConfigError("well.hole", "expected an array of tables [[well.hole]]")
    sections = []
    for i, item in enumerate(raw):
        key = f"well.hole[{i}]"
        table = _table(item, key, HOLE_KEYS)
        if "to_md" not in table:
            raise ConfigError(f"{key}.to_md", "missing required key (the section's bottom)")
        factors = {
            name: _positive_number(table[name], f"{key}.{name}", "dimensionless")
            for name in ("friction_static", "friction_dynamic")
            if name in table
        }
        sections.append(
            HoleSection(
                to_md=to_si(table["to_md"], "length", key=f"{key}.to_md"),
                name=_string(table.get("name", ""), f"{key}.name"),
                **factors,
            )
        )
    return tuple(sections)


def parse_well(raw: Any, source: str = "") -> Wellbore:
    """The :class:`~torsio.well.wellbore.Wellbore` of a ``[well]`` table ``raw`` as read
    from TOML; relative survey paths are read from the folder of ``source``, the
    configuration file.

    Raises
    ------
    ConfigError
        An unknown key, a bad survey (arrays or file), friction factors, hole sections,
        mud density or threshold speed; the key is named with its ``well.`` path.
    """
    table = _table(raw, "well", WELL_KEYS)
    survey = _survey(table, source)
    options: dict[str, Any] = {}
    if "mud_density" in table:
        options["mud_density"] = _positive_number(
            table["mud_density"], "well.mud_density", "density"
        )
    for name in ("friction_static", "friction_dynamic"):
        if name in table:
            options[name] = _positive_number(table[name], f"well.{name}", "dimensionless")
    if "threshold_speed" in table:
        options["threshold_speed"] = _positive_number(
            table["threshold_speed"], "well.threshold_speed", "angular_speed"
        )
    if "normal_force" in table:
        options["normal_force"] = _string(table["normal_force"], "well.normal_force")
    if "hole" in table:
        options["hole"] = _hole(table["hole"])
    try:
        return Wellbore(survey, **options)
    except ConfigError as exc:
        raise ConfigError(f"well.{exc.key}", exc.message) from None


def well_table(
    table: Mapping[str, Any], string: DrillString | None, source: str
) -> Wellbore | None:
    """The ``[well]`` table of a whole configuration ``table`` (None when absent), checked
    against the ``string`` of ``[[section]]``: it hangs from the rig floor (md 0), its bit
    at md = its length."""
    if "well" not in table:
        return None
    if string is None:
        raise ConfigError("well", "[well] needs a drill-string ([[section]]), not a [chain]")
    well = parse_well(table["well"], source)
    key = "well.survey" if "survey" in table["well"] else "well.md"
    string_top_md(well, sum(s.length for s in string.sections), key=key)
    check_mud_density(well, string, key="well.mud_density")
    return well
