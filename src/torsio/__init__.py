"""torsio: torsional dynamics of oil-well drill-strings with lumped-parameter models.

>>> import torsio
>>> model = torsio.StrategyA().discretize(torsio.ritto2017_string())
>>> round(float(torsio.modal_analysis(model).frequencies_hz[0]), 4)
0.1344
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

__version__ = "0.1.0"

# Every public name, by the module it lives in. ``import torsio`` imports none of these
# modules: each is imported on the first use of one of its names (PEP 562), so that the
# command line starts fast (scipy, numba and pint are loaded only by what needs them).
# To export a name, add it here and to the TYPE_CHECKING imports below (for type checkers;
# tests/test_public_names.py checks that they agree); __all__ is generated from this table.
_EXPORTS: dict[str, tuple[str, ...]] = {
    "torsio.analysis.energy": ("EnergyBalance", "energy_balance"),
    "torsio.analysis.simulation_options": ("SimulationOptions",),
    "torsio.analysis.transient": ("simulate", "simulate_config"),
    "torsio.analysis.transient_results": ("TransientResults",),
    "torsio.analysis.run_file": ("load_run",),
    "torsio.errors": ("ConfigError", "PluginError", "SolverError", "TorsioError"),
    "torsio.config.configuration": ("Config",),
    "torsio.config.reading": ("load_config", "parse_config"),
    "torsio.examples": ("builtin_config", "ritto2017_string"),
    "torsio.hookspecs": ("hookimpl",),
    "torsio.model.components": (
        "LWD",
        "MWD",
        "STEEL",
        "BHASection",
        "Bit",
        "DrillCollar",
        "DrillPipe",
        "HeavyWeightDrillPipe",
        "Material",
        "Section",
        "Stabilizer",
    ),
    "torsio.model.continuum": ("ContinuumModes", "continuum_modes"),
    "torsio.model.discretize": (
        "ConsistentMass",
        "MixedMass",
        "StrategyA",
        "StrategyB",
        "StrategyC",
    ),
    "torsio.model.drillstring": ("DrillString",),
    "torsio.model.lumped": ("LumpedModel",),
    "torsio.model.modal": ("ModalResults", "modal_analysis"),
    "torsio.physics.damping": ("RayleighDamping",),
    "torsio.physics.dimensionless": (
        "DimensionlessGroups",
        "dimensional_system",
        "dimensionless_groups",
        "dimensionless_system",
    ),
    "torsio.physics.laws": ("BitRockLaw", "Parameter", "TuckerWang"),
    "torsio.physics.dynamics": ("Dynamics",),
    "torsio.physics.system": ("System",),
    "torsio.physics.top_drives": (
        "ConstantSpeedTop",
        "PITopDrive",
        "SoftTorqueTopDrive",
        "TorqueTopDrive",
        "ZTorqueTopDrive",
    ),
    "torsio.physics.top_drive_boundary": ("TopDriveBoundary",),
    "torsio.physics.recorded_top": ("RecordedTopDrive",),
    "torsio.calibration.recording": ("Recording", "read_recording"),
    "torsio.calibration.fit": ("fit_recordings",),
    "torsio.calibration.fit_results": ("FitResults",),
    "torsio.plugins": ("top_drive_from_parameters",),
    "torsio.analysis.maps": ("severity_map", "dimensionless_map"),
    "torsio.analysis.map_results": ("SeverityMap", "load_map"),
    "torsio.analysis.map_options": ("MapOptions",),
    "torsio.solvers.batch": ("simulate_batch",),
    "torsio.analysis.stability": (
        "StabilityBoundary",
        "stability_boundary",
        "critical_bit_damping",
    ),
}
_LAZY = {name: module for module, names in _EXPORTS.items() for name in names}
_SUBPACKAGES = (
    "analysis",
    "calibration",
    "cli",
    "config",
    "model",
    "physics",
    "report",
    "solvers",
    "well",
)

if TYPE_CHECKING:  # for type checkers and editors; at run time see __getattr__
    from torsio.analysis.energy import EnergyBalance, energy_balance
    from torsio.analysis.map_options import MapOptions
    from torsio.analysis.map_results import SeverityMap, load_map
    from torsio.analysis.maps import dimensionless_map, severity_map
    from torsio.analysis.run_file import load_run
    from torsio.analysis.simulation_options import SimulationOptions
    from torsio.analysis.stability import (
        StabilityBoundary,
        critical_bit_damping,
        stability_boundary,
    )
    from torsio.analysis.transient import simulate, simulate_config
    from torsio.analysis.transient_results import TransientResults
    from torsio.calibration.fit import fit_recordings
    from torsio.calibration.fit_results import FitResults
    from torsio.calibration.recording import Recording, read_recording
    from torsio.config.configuration import Config
    from torsio.config.reading import load_config, parse_config
    from torsio.errors import ConfigError, PluginError, SolverError, TorsioError
    from torsio.examples import builtin_config, ritto2017_string
    from torsio.hookspecs import hookimpl
    from torsio.model.components import (
        LWD,
        MWD,
        STEEL,
        BHASection,
        Bit,
        DrillCollar,
        DrillPipe,
        HeavyWeightDrillPipe,
        Material,
        Section,
        Stabilizer,
    )
    from torsio.model.continuum import ContinuumModes, continuum_modes
    from torsio.model.discretize import ConsistentMass, MixedMass, StrategyA, StrategyB, StrategyC
    from torsio.model.drillstring import DrillString
    from torsio.model.lumped import LumpedModel
    from torsio.model.modal import ModalResults, modal_analysis
    from torsio.physics.damping import RayleighDamping
    from torsio.physics.dimensionless import (
        DimensionlessGroups,
        dimensional_system,
        dimensionless_groups,
        dimensionless_system,
    )
    from torsio.physics.dynamics import Dynamics
    from torsio.physics.laws import BitRockLaw, Parameter, TuckerWang
    from torsio.physics.recorded_top import RecordedTopDrive
    from torsio.physics.system import System
    from torsio.physics.top_drive_boundary import TopDriveBoundary
    from torsio.physics.top_drives import (
        ConstantSpeedTop,
        PITopDrive,
        SoftTorqueTopDrive,
        TorqueTopDrive,
        ZTorqueTopDrive,
    )
    from torsio.plugins import top_drive_from_parameters
    from torsio.solvers.batch import simulate_batch


def __getattr__(name: str) -> Any:
    import importlib

    module = _LAZY.get(name)
    if module is not None:
        value = getattr(importlib.import_module(module), name)
        globals()[name] = value  # later uses skip this function
        return value
    if name in _SUBPACKAGES:
        return importlib.import_module(f"torsio.{name}")
    raise AttributeError(f"module 'torsio' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *_LAZY})


__all__ = list(_LAZY)  # generated from _EXPORTS, the one list of public names
