"""torsio: torsional dynamics of oil-well drill-strings with lumped-parameter models.

>>> import torsio
>>> model = torsio.StrategyA().discretize(torsio.ritto2017_string())
>>> round(float(torsio.modal_analysis(model).frequencies_hz[0]), 4)
0.1344
"""

from torsio.analysis.energy import EnergyBalance, energy_balance
from torsio.analysis.transient import SimulationOptions, TransientResults, simulate, simulate_config
from torsio.errors import ConfigError, PluginError, SolverError, TorsioError
from torsio.examples import ritto2017_config, ritto2017_string
from torsio.hookspecs import hookimpl
from torsio.io.config import Config, builtin_config, load_config, parse_config
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
from torsio.physics.system import System
from torsio.physics.top_drives import (
    ConstantSpeedTop,
    PITopDrive,
    SoftTorqueTopDrive,
    TopDriveBoundary,
    TorqueTopDrive,
    ZTorqueTopDrive,
    top_drive_from_parameters,
)

__version__ = "0.1.0"

# Severity maps and the batch engine load numba: imported on first use, not with torsio.
_LAZY = {
    "SeverityMap": "torsio.analysis.maps",
    "severity_map": "torsio.analysis.maps",
    "dimensionless_map": "torsio.analysis.maps",
    "load_map": "torsio.analysis.maps",
    "simulate_batch": "torsio.solvers.batch",
    "StabilityBoundary": "torsio.analysis.stability",
    "stability_boundary": "torsio.analysis.stability",
    "critical_bit_damping": "torsio.analysis.stability",
}


def __getattr__(name: str) -> object:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'torsio' has no attribute {name!r}")
    import importlib

    return getattr(importlib.import_module(module), name)


__all__ = [
    "LWD",
    "MWD",
    "STEEL",
    "BHASection",
    "Bit",
    "BitRockLaw",
    "Config",
    "ConfigError",
    "ConsistentMass",
    "ContinuumModes",
    "DrillCollar",
    "DrillPipe",
    "DrillString",
    "HeavyWeightDrillPipe",
    "LumpedModel",
    "Material",
    "MixedMass",
    "ModalResults",
    "Parameter",
    "PluginError",
    "Section",
    "SolverError",
    "Stabilizer",
    "StrategyA",
    "StrategyB",
    "StrategyC",
    "TorsioError",
    "TuckerWang",
    "builtin_config",
    "continuum_modes",
    "hookimpl",
    "load_config",
    "modal_analysis",
    "parse_config",
    "ritto2017_config",
    "ritto2017_string",
    "SimulationOptions",
    "TransientResults",
    "simulate",
    "simulate_config",
    "EnergyBalance",
    "energy_balance",
    "ConstantSpeedTop",
    "Dynamics",
    "PITopDrive",
    "SoftTorqueTopDrive",
    "TopDriveBoundary",
    "TorqueTopDrive",
    "ZTorqueTopDrive",
    "top_drive_from_parameters",
    "RayleighDamping",
    "System",
    "DimensionlessGroups",
    "dimensional_system",
    "dimensionless_groups",
    "dimensionless_system",
    "SeverityMap",
    "severity_map",
    "dimensionless_map",
    "load_map",
    "simulate_batch",
    "StabilityBoundary",
    "stability_boundary",
    "critical_bit_damping",
]
