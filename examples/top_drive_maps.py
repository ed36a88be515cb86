"""Top drives against stick-slip: severity maps side by side, and a torque-driven string.

(a-d) Severity maps S_SS (Eq. 12) of the paper's string (the built-in configuration,
strategy C with 5 drill-pipe elements, Tucker-Wang in the rpm reading, alpha = 0.35 1/s,
beta = 0.06 s) turned by four top drives of inertia J = 2900 kg m^2 (NORCE/OSDC
Simulator4nDOF): held at constant speed (the paper), a stiff PI (kp = 50 zeta,
ki = 5 J, Simulator4nDOF), SoftTorque (kp = zeta, ki = omega_1^2 J, Kyllingstad and
Nessjoen 2009) and Z-Torque (stiff PI with alpha = 0.25 and a 20 s torque high-pass,
Dwars 2015), each with its critical weight-on-bit curve; (e) the four critical curves
together. (f) The torque-driven 4-DOF string of Navarro-Lopez and Cortes (2007) at its
stick-slip weight on bit, 97,347 N, and at 50 kN, where it rotates steadily at the speed
of the torque balance (needs the torsio-friction-laws plugin).

Every point is a start-up from rest (see docs/maps.md); the maps say which engine ran.

Usage: python examples/top_drive_maps.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from torsio import System, builtin_config
from torsio.analysis.map_results import SeverityMap
from torsio.analysis.maps import severity_map
from torsio.config.reading import parse_config_text
from torsio.physics.top_drives import (
    PITopDrive,
    SoftTorqueTopDrive,
    ZTorqueTopDrive,
    top_pipe_impedance,
)
from torsio.plotting import pyplot, save_figure

TOP_DRIVE_INERTIA = 2900.0
"""J [kg m^2], the Simulator4nDOF default."""


def top_drives(system: System) -> dict[str, Any]:
    """The four top drives compared, with their tuning on ``system``."""
    zeta = top_pipe_impedance(system)
    return {
        "constant speed (paper)": system.top,
        "stiff PI (kp = 50 ζ, ki = 5 J)": PITopDrive(
            inertia=TOP_DRIVE_INERTIA, kp=50.0 * zeta, ki=5.0 * TOP_DRIVE_INERTIA
        ),
        "SoftTorque (kp = ζ, ki = ω₁² J)": SoftTorqueTopDrive(inertia=TOP_DRIVE_INERTIA),
        "Z-Torque (α = 0.25, 20 s)": ZTorqueTopDrive(inertia=TOP_DRIVE_INERTIA),
    }


def navarro_lopez_cortes(wob: float, quick: bool) -> Any:
    """The torque-driven 4-DOF run at ``wob`` (None without the friction-law plugin)."""
    from torsio.analysis.transient import simulate_config

    try:
        import torsio_friction_laws  # noqa: F401
    except ImportError:
        return None
    text = resources.files("torsio").joinpath("data/navarro_lopez_cortes_2007.toml")
    data = text.read_text(encoding="utf-8").replace("wob = 97347.0", f"wob = {wob!r}")
    config = parse_config_text(data, source="navarro_lopez_cortes_2007.toml")
    duration = 60.0 if quick else 150.0
    return simulate_config(config, duration=duration, steady_window=duration / 3)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", type=Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced sizes (CI)")
    args = parser.parse_args(argv)

    if args.quick:
        rpm = np.linspace(50.0, 130.0, 3)
        wob = np.linspace(50e3, 250e3, 3)
        refine, overrides = 0, {"strategy": "A"}
    else:
        rpm = np.linspace(40.0, 140.0, 11)
        wob = np.linspace(25e3, 325e3, 13)
        refine, overrides = 5, {}
    base = builtin_config().system(**overrides)
    maps: dict[str, SeverityMap] = {}
    for name, top in top_drives(base).items():
        maps[name] = severity_map(base.with_top(top), wob=wob, rpm=rpm, refine=refine)
        critical = ", ".join(f"{w / 1e3:.0f}" for w in maps[name].critical_wob)
        print(f"{name:34s} critical WOB [kN] at {rpm.tolist()} rpm: {critical}")

    plt = pyplot()
    fig, axes = plt.subplot_mosaic(
        [["a", "b", "c", "d"], ["e", "e", "f", "f"]], figsize=(16.0, 8.6), layout="constrained"
    )
    map_axes = [axes[key] for key in "abcd"]
    for ax, (name, m) in zip(map_axes, maps.items(), strict=True):
        mesh = ax.pcolormesh(
            m.wob / 1e3, m.rpm, m.severity, vmin=0.0, vmax=1.6, cmap="viridis", shading="nearest"
        )
        ax.plot(m.critical_wob / 1e3, m.rpm, "w-o", ms=3, lw=1.5)
        ax.set(xlabel="weight on bit [kN]", ylabel="surface speed [rpm]")
        ax.set_title(name, fontsize="medium")
    fig.colorbar(mesh, ax=map_axes, label="S_SS [-]", shrink=0.9)
    ax = axes["e"]
    for name, m in maps.items():
        ax.plot(m.critical_wob / 1e3, m.rpm, marker="o", label=name)
    ax.set(xlabel="critical weight on bit [kN]", ylabel="surface speed [rpm]")
    ax.set_title("critical WOB: S_SS > 0.8 to the right")
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize="x-small")

    ax = axes["f"]
    for wob_nlc, style in ((97347.0, "-"), (50.0e3, "--")):
        results = navarro_lopez_cortes(wob_nlc, args.quick)
        if results is None:
            ax.text(0.5, 0.5, "needs torsio-friction-laws", ha="center", transform=ax.transAxes)
            break
        label = f"{wob_nlc / 1e3:.4g} kN"
        ax.plot(results.time, results.bit_speed, style, lw=0.9, label=f"bit, {label}")
        ax.plot(results.time, results.top_speed, style, lw=0.9, label=f"table, {label}")
        window = results.window_mask
        print(
            f"Navarro-Lopez and Cortes at {label}: bit speed "
            f"{results.bit_speed[window].min():.3f} .. {results.bit_speed[window].max():.3f} "
            f"rad/s, mean table speed {results.top_speed_mean:.3f} rad/s, "
            f"S_SS = {results.severity:.3f}"
        )
    ax.set(xlabel="time [s]", ylabel="speed [rad/s]")
    ax.set_title("Navarro-López & Cortés (2007), u = 10 kN m")
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize="x-small")
    fig.suptitle("Top drives against stick-slip: the paper's string and a torque-driven one")
    print(f"wrote {save_figure(fig, args.out / 'top_drive_maps.png', palette=True)}")


if __name__ == "__main__":
    main()
