"""Configurations the axial tests share: the built-in 2-DOF file and a [[section]] string
with its RGD bit (1000 m of 5 in drill pipe above 150 m of 6 3/4 in collars and the bit)."""

from __future__ import annotations

import tomllib
from importlib import resources
from typing import Any

TEXT = resources.files("torsio").joinpath("data/rgd_2dof.toml").read_text(encoding="utf-8")
BASE: dict[str, Any] = tomllib.loads(TEXT)

STRING: dict[str, Any] = {
    "material": {"shear_modulus": "79.3 GPa", "density": 7850, "youngs_modulus": "207 GPa"},
    "section": [
        {"kind": "drill_pipe", "od": "5 in", "id": "4.276 in", "length": "1000 m"},
        {"kind": "drill_collar", "od": "6.75 in", "id": "2.8125 in", "length": "150 m"},
        {"kind": "bit", "od": "8.5 in", "id": 0.0, "length": 0.3},
    ],
    "damping": {"beta": 0.06},
    "bit_rock": dict(BASE["bit_rock"]),
    "operation": {"wob": "100 kN", "rpm": 60},
}
