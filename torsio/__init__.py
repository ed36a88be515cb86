"""torsio: torsional dynamics of oil-well drill-strings with lumped-parameter models.

>>> import torsio
>>> model = torsio.StrategyA().discretize(torsio.ritto2017_string())
>>> round(float(torsio.modal_analysis(model).frequencies_hz[0]), 4)
0.1344
"""

from torsio.components import (
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
from torsio.config import Config, builtin_config, load_config, parse_config
from torsio.continuum import ContinuumModes, continuum_modes
from torsio.damping import RayleighDamping
from torsio.dimensionless import (
    DimensionlessGroups,
    dimensional_system,
    dimensionless_groups,
    dimensionless_system,
)
from torsio.discretize import ConsistentMass, MixedMass, StrategyA, StrategyB, StrategyC
from torsio.drillstring import DrillString
from torsio.energy import EnergyBalance, energy_balance
from torsio.errors import ConfigError, PluginError, SolverError, TorsioError
from torsio.examples import ritto2017_config, ritto2017_string
from torsio.hookspecs import hookimpl
from torsio.laws import BitRockLaw, Parameter, TuckerWang
from torsio.lumped import LumpedModel
from torsio.modal import ModalResults, modal_analysis
from torsio.system import ConstantSpeedTop, System
from torsio.transient import SimulationOptions, TransientResults, simulate, simulate_config

__version__ = "0.1.0"

# Severity maps and the batch engine load numba: imported on first use, not with torsio.
_LAZY = {
    "SeverityMap": "torsio.maps",
    "severity_map": "torsio.maps",
    "dimensionless_map": "torsio.maps",
    "load_map": "torsio.maps",
    "simulate_batch": "torsio.batch",
    "StabilityBoundary": "torsio.stability",
    "stability_boundary": "torsio.stability",
    "critical_bit_damping": "torsio.stability",
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
