"""A custom bit-rock law as a plugin, used through the same hook as the built-in ones.

The law (a velocity-weakening friction that saturates at a sliding level, with a
smooth sign) is defined here, registered in-process with the plugin manager, and
then found by name like any law a distribution registers under the ``torsio``
entry-point group (see docs/plugins.md for the packaged version). The script
compares the bit response of the built-in string at 150 kN, 60 rpm under
Tucker-Wang and under this law, and writes their bit speeds.

Usage: python examples/custom_bit_law.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import attrs
import numpy as np

import torsio
from torsio.io.plotting import pyplot, save_figure
from torsio.physics.laws import BitRockLaw, Parameter
from torsio.plugins import get_bit_law, plugin_manager


class SaturatedWeakening(BitRockLaw):
    """T = W R [mu_c + (mu_s - mu_c) / (1 + w / w_s)] tanh(w / eps)."""

    name = "saturated-weakening"
    description = "W R [mu_c + (mu_s - mu_c)/(1 + w/w_s)] tanh(w/eps)"
    parameters = {
        "mu_s": Parameter("-", "static friction coefficient", minimum=0.0, strict=True),
        "mu_c": Parameter("-", "sliding friction coefficient", minimum=0.0, strict=True),
        "w_s": Parameter("rad/s", "weakening speed", minimum=0.0, strict=True, speed_power=-1),
        "eps": Parameter(
            "rad/s",
            "regularization of the sign",
            default=0.05,
            minimum=0.0,
            strict=True,
            speed_power=-1,
        ),
    }
    mu_s: float
    mu_c: float
    w_s: float
    eps: float

    def torque(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        w = np.asarray(speed, dtype=float)
        weakening = self.mu_c + (self.mu_s - self.mu_c) / (1.0 + np.abs(w) / self.w_s)
        return np.asarray(wob) * np.asarray(radius) * weakening * np.tanh(w / self.eps)


class Plugin:
    """What a plugin module provides: the hook implementation."""

    @torsio.hookimpl
    def torsio_bit_laws(self) -> list[type[BitRockLaw]]:
        return [SaturatedWeakening]


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", type=Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced sizes (CI)")
    args = parser.parse_args(argv)

    plugin_manager().register(Plugin(), name="example-saturated-weakening")
    law = get_bit_law("saturated-weakening")(mu_s=0.6, mu_c=0.15, w_s=6.0)
    print(f"registered laws: {', '.join(sorted(torsio.plugins.bit_laws()))}")
    print(f"custom law: {law!r}")

    strategy = {"strategy": "A"} if args.quick else {}
    base = torsio.System.from_config(torsio.builtin_config(), **strategy).at(wob=150e3, rpm=60)
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8.0, 3.8))
    for label, system in (
        ("Tucker-Wang (rpm reading)", base),
        ("saturated weakening", attrs.evolve(base, law=law)),
    ):
        results = torsio.simulate(system)
        print(
            f"{label:28s} S_SS = {results.severity:.3f}, stick fraction "
            f"{results.stick_fraction:.2f}"
        )
        ax.plot(results.time, results.bit_speed * 30 / np.pi, lw=0.8, label=label)
    ax.axhline(60.0, color="0.3", ls=":", lw=0.8, label="top drive")
    ax.set(xlabel="time [s]", ylabel="bit speed [rpm]", title="150 kN, 60 rpm, start-up from rest")
    ax.legend(fontsize="small", loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=3)
    fig.tight_layout()
    print(f"wrote {save_figure(fig, args.out / 'custom_bit_law.png', palette=True)}")


if __name__ == "__main__":
    main()
