"""A custom bit-rock law as a plugin, used through the same hook as the built-in ones.

The law (a velocity-weakening friction that saturates at a sliding level, with a
smooth sign) is defined here, registered in-process with the plugin manager, and
then found by name like any law a distribution registers under the ``torsio``
entry-point group (see docs/plugins.md for the packaged version). Its formula is
written once with numpy ufuncs and serves both the vectorized ``torque`` and the
compiled kernel (``kernel()``) that severity maps run. The script compares the bit
response of the built-in string at 150 kN, 60 rpm under Tucker-Wang and under this
law, writes their bit speeds, and runs a small severity map with the law (the
compiled engine, as the map reports).

Usage: python examples/custom_bit_law.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import attrs
import numpy as np

import torsio
from torsio.physics.laws import BitRockLaw, Parameter
from torsio.plotting import pyplot, save_figure
from torsio.plugins import get_bit_law, plugin_manager
from torsio.solvers.law_kernels import compile_law_function


def weakening_torque(p: Any, w: Any, wob: Any, radius: Any) -> Any:
    """W R [mu_c + (mu_s - mu_c)/(1 + |w|/w_s)] tanh(w/eps), p = (mu_s, mu_c, w_s, eps)."""
    return wob * radius * (p[1] + (p[0] - p[1]) / (1.0 + np.abs(w) / p[2])) * np.tanh(w / p[3])


def weakening_slope(p: Any, w: Any, wob: Any, radius: Any) -> Any:
    """d torque / d speed of :func:`weakening_torque` [N m s/rad]."""
    mu = p[1] + (p[0] - p[1]) / (1.0 + np.abs(w) / p[2])
    d_mu = -(p[0] - p[1]) / (p[2] * (1.0 + np.abs(w) / p[2]) ** 2)
    sign = np.tanh(w / p[3])
    return wob * radius * (d_mu * np.abs(sign) + mu * (1.0 - sign**2) / p[3])


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

    def _vector(self) -> np.ndarray:
        return np.array([self.mu_s, self.mu_c, self.w_s, self.eps])

    def torque(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        w = np.asarray(speed, dtype=float)
        return weakening_torque(self._vector(), w, np.asarray(wob), np.asarray(radius))

    def slope(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        w = np.asarray(speed, dtype=float)
        return weakening_slope(self._vector(), w, np.asarray(wob), np.asarray(radius))

    def kernel(self) -> tuple[Any, Any, np.ndarray]:
        """The compiled torque and slope that severity maps run (docs/plugins.md)."""
        return (
            compile_law_function(weakening_torque),
            compile_law_function(weakening_slope),
            self._vector(),
        )


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
    base = torsio.builtin_config().system(**strategy).at(wob=150e3, rpm=60)
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

    steps = 3 if args.quick else 11
    law_map = torsio.severity_map(
        attrs.evolve(base, law=law),
        wob=np.linspace(50e3, 250e3, steps),
        rpm=np.linspace(40.0, 120.0, steps),
        refine=0 if args.quick else 4,
    )
    print(
        f"severity map with the custom law: {law_map.shape[0]} x {law_map.shape[1]} points, "
        f"{law_map.engine} engine, {law_map.info['elapsed_s']:.2f} s"
    )


if __name__ == "__main__":
    main()
