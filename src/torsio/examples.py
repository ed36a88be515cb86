"""Ready-made examples that tests, doctests and users share: the built-in configurations
(``src/torsio/data/*.toml``) and the drill-string of the paper's Table 1.

>>> builtin_config().name
'Ritto et al. (2017)'
>>> string = ritto2017_string()
>>> string.name
'Ritto et al. (2017)'
>>> deviated_well_config().well.survey.depth
2500.0
>>> rgd_two_dof_config().axial.assembly.axial.masses.tolist()
[29981.3]
>>> rgd_wave_pipe_config().axial.assembly.lengths.tolist()
[900.0, 100.0]
>>> rgd_deviated_well_config().axial.contacts.count
20
>>> example_names()  # doctest: +NORMALIZE_WHITESPACE
('deviated_well', 'navarro_lopez_cortes_2007', 'rgd_2dof', 'rgd_deviated_well',
 'rgd_wave_pipe', 'ritto2017')
>>> example_summary("rgd_2dof")
'The 2-DOF model of Richard, Germay and Detournay (2007) with the RGD bit'
"""

from __future__ import annotations

from importlib import resources

from torsio.config.configuration import Config
from torsio.config.reading import parse_config_text
from torsio.errors import ConfigError
from torsio.model.drillstring import DrillString

__all__ = [
    "builtin_config",
    "data_text",
    "deviated_well_config",
    "example_names",
    "example_summary",
    "example_text",
    "rgd_deviated_well_config",
    "rgd_two_dof_config",
    "rgd_wave_pipe_config",
    "ritto2017_string",
]


TEMPLATE = "template"
"""The data file ``torsio init`` writes by default (not an example: it describes itself)."""


def example_names() -> tuple[str, ...]:
    """The built-in configuration files by name (``data/NAME.toml``), the template aside."""
    files = resources.files("torsio").joinpath("data").iterdir()
    stems = (f.name.removesuffix(".toml") for f in files if f.name.endswith(".toml"))
    return tuple(sorted(stem for stem in stems if stem != TEMPLATE))


def example_text(name: str) -> str:
    """The text of the built-in file ``name`` (:func:`example_names`); a ConfigError on
    ``--example`` naming them."""
    if name not in example_names():
        raise ConfigError(
            "--example", f"no built-in example {name!r}; they are {', '.join(example_names())}"
        )
    return data_text(name)


def data_text(name: str) -> str:
    """The text of ``data/NAME.toml`` (an example, or the template)."""
    return resources.files("torsio").joinpath(f"data/{name}.toml").read_text(encoding="utf-8")


def example_summary(name: str) -> str:
    """What the built-in file ``name`` is: its first comment line up to a colon (or an
    unclosed parenthesis)."""
    first = example_text(name).splitlines()[0].lstrip("# ").partition(": ")[0]
    if first.count("(") > first.count(")"):
        first = first[: first.rindex("(")]
    return first.strip().rstrip(",.")


def _data(name: str) -> Config:
    return parse_config_text(data_text(name.removesuffix(".toml")), source=f"built-in {name}")


def builtin_config() -> Config:
    """The built-in example: the Ritto et al. (2017) string of the paper's Table 1
    (``data/ritto2017.toml``, G = 85.3 GPa), what ``torsio report`` shows without a file."""
    return _data("ritto2017.toml")


def ritto2017_string() -> DrillString:
    """The drill-string of the paper's Table 1: drill pipes, HWDP, collars/MWD/LWD, bit."""
    string = builtin_config().string
    assert string is not None  # the built-in example is a drill-string, not a chain
    return string


def deviated_well_config() -> Config:
    """A 2.5 km string in an S-shaped well with a 3-D turn (``data/deviated_well.toml``):
    the built-in example of ``[well]`` and ``torsio drag``."""
    return _data("deviated_well.toml")


def rgd_two_dof_config() -> Config:
    """The 2-DOF model of RGD (2007) with the RGD bit (``data/rgd_2dof.toml``): the
    parameters of :func:`torsio.model.axial_assembly.rgd_two_dof_example` and
    :func:`torsio.axial.rgd.rgd_example`, 100 kN at 60 rpm; the built-in axial example."""
    return _data("rgd_2dof.toml")


def rgd_wave_pipe_config() -> Config:
    """A 1 km stepped pipe (900 m of 5 in drill pipe, 100 m of HWDP) as the distributed
    axial-torsional model above a rigid BHA with the RGD bit (``data/rgd_wave_pipe.toml``,
    ``[discretization] strategy = "wave"``), 100 kN at 60 rpm."""
    return _data("rgd_wave_pipe.toml")


def rgd_deviated_well_config() -> Config:
    """The stepped RGD string of ``rgd_wave_pipe.toml`` (its drill pipe reaching the
    surface) as the lumped axial-torsional chain in the survey of ``deviated_well.toml``,
    with Coulomb friction at every node (``data/rgd_deviated_well.toml``), 100 kN at 60 rpm."""
    return _data("rgd_deviated_well.toml")
