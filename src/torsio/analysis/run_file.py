"""A run read back from the file :meth:`TransientResults.save` wrote: :func:`load_run`.

Examples
--------
>>> import pathlib, tempfile
>>> from torsio.analysis.transient import simulate
>>> from torsio.examples import builtin_config
>>> run = simulate(builtin_config().system(strategy="A").at(wob=100e3, rpm=60))
>>> with tempfile.TemporaryDirectory() as folder:
...     again = load_run(run.save(pathlib.Path(folder) / "run.npz"))
>>> again.to_dict(series=True) == run.to_dict(series=True), again.system is None
(True, True)
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from torsio.analysis.run_facts import RunFacts
from torsio.analysis.transient_results import (
    RUN_ARRAYS,
    RUN_FORMAT,
    RUN_FORMAT_VERSION,
    RUN_VALUES,
    TransientResults,
)
from torsio.errors import ConfigError
from torsio.output_files import read_saved

__all__ = ["load_run"]


def load_run(path: str | Path) -> TransientResults:
    """The run saved at ``path`` (:meth:`TransientResults.save`), with its facts and
    without its System (an analysis that needs the System, such as
    :func:`torsio.analysis.energy.energy_balance`, says so). A file that is not a saved
    run is a ConfigError naming ``path``."""
    metadata, arrays = read_saved(path, "transient run")
    known = metadata if isinstance(metadata, dict) else {}
    name, version = known.get("format"), known.get("version")
    if name != RUN_FORMAT or version not in range(1, RUN_FORMAT_VERSION + 1):
        raise ConfigError(
            "path",
            f"{str(path)!r} is not a saved transient run of this torsio (its format "
            f"{name!r}, version {version!r}; expected {RUN_FORMAT!r} up to {RUN_FORMAT_VERSION})",
        )
    try:
        return _results(metadata, arrays)
    except (KeyError, TypeError, ValueError) as exc:
        raise ConfigError(
            "path", f"{str(path)!r} is a damaged saved run ({type(exc).__name__}: {exc})"
        ) from None


def _results(metadata: dict[str, Any], arrays: dict[str, Any]) -> TransientResults:
    warnings = tuple(metadata["warnings"])
    if metadata.get("axial") is not None:
        from torsio.analysis.axial_results import AxialChannels, axial_results

        channels = AxialChannels.from_saved(metadata["axial"], arrays["axial_samples"])
        return axial_results(channels, warnings)
    extremes = metadata["bit_speed_extremes"]
    return TransientResults(
        **{name: arrays[name] for name in RUN_ARRAYS},
        **{name: metadata[name] for name in RUN_VALUES},
        system=None,
        bit_speed_extremes=None if extremes is None else (extremes[0], extremes[1]),
        warnings=warnings,
        facts=RunFacts(**metadata["facts"]),
    )
