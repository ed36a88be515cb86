"""A 41 x 41 severity map as a user gets it, against the loop a user would write, in one run.

Baseline (strategy A of the comparison): a lean per-point loop, one
``scipy.integrate.solve_ivp(method="RK45", rtol=1e-6, atol=1e-9)`` run per grid point with
a plain Python right-hand side of the paper's model (Eq. 1 with Rayleigh damping and the
Tucker-Wang law, Eq. 2, of the built-in Ritto et al. 2017 string), S_SS (Eq. 12) read from
the bit speed sampled every 1/200 period over the steady window. It runs on every k-th
point of the 41 x 41 grid (k coprime with 41, so the sample visits every row and column of
the grid, stable and stick-slip points alike), and its time is scaled to the 1 681 points.

torsio, on the same grid, the same runs (300 s from rest, S_SS over the last 100 s):

- **CLI**: ``torsio map --strategy A --wob 25kN:225kN:41 --rpm 40:140:41 --duration 300
  --window 100 --json`` timed as a whole new process (start-up, numba's cache, the map with
  its critical-WOB bisection and linear stability boundary, the JSON), default options (all
  cores), after one untimed run that fills numba's cache;
- **in process**: :func:`torsio.analysis.maps.severity_map` with ``refine=0`` (the grid
  only: the same runs as the baseline), default engine and tolerances, all cores;
- the 10-DOF strategy-C model, in process, against the same lean loop (numpy matrices in
  the right-hand side), sampled on every 43rd point.

Targets: CLI >= 200x and in process >= 500x (1 DOF); 10 DOF >= 150x.

Run: ``python benchmarks/bench_cli.py`` (about 2-4 minutes on 2 cores), ``--every K`` for
the 1-DOF baseline's sampling, ``--skip-10dof``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import time
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

from torsio.analysis.maps import severity_map
from torsio.examples import builtin_config
from torsio.physics.system import System

DURATION = 300.0
WINDOW = 100.0
POINTS = 41
WOB = (25e3, 225e3)
RPM = (40.0, 140.0)


def grid() -> tuple[np.ndarray, np.ndarray]:
    return np.linspace(*WOB, POINTS), np.linspace(*RPM, POINTS)


def ritto(strategy: str, dp_elements: int | None = None) -> System:
    options = {} if dp_elements is None else {"dp_elements": dp_elements}
    return builtin_config().system(strategy=strategy, **options)


# --- the baseline: what a user would write ---------------------------------------------------
def lean_model(system: System) -> dict[str, Any]:
    """Plain arrays of the paper's model: M, K, C = alpha M + beta K, the top coupling."""
    config = builtin_config()
    alpha, beta = config.damping.alpha or 0.0, config.damping.beta or 0.0
    mass = np.asarray(system.model.inertia, dtype=float)
    stiffness = np.asarray(system.model.stiffness, dtype=float)
    top_spring = stiffness.sum(axis=1)  # the held top drive is the ground of node 1's spring
    law = system.law
    return {
        "n": mass.shape[0],
        "inv_mass": np.linalg.inv(mass),
        "stiffness": stiffness,
        "damping": alpha * mass + beta * stiffness,
        "top_spring": top_spring,
        "top_damper": beta * top_spring,
        "a": (law.a0, law.a1, law.a2, law.a3),  # rad/s reading
        "radius": system.bit_radius,
    }


def lean_severity(m: dict[str, Any], wob: float, rpm: float) -> float:
    """One solve_ivp RK45 run from rest; S_SS from the sampled bit speed (Eq. 12)."""
    omega = rpm * math.pi / 30.0
    n = m["n"]
    a0, a1, a2, a3 = m["a"]
    scale = wob * m["radius"] * a0
    if n == 1:
        j = 1.0 / m["inv_mass"][0, 0]
        k, c = m["stiffness"][0, 0], m["damping"][0, 0]
        kt, ct = m["top_spring"][0], m["top_damper"][0]

        def rhs(t: float, y: np.ndarray) -> list[float]:
            theta, speed = y
            bit = scale * (math.tanh(a1 * speed) + a2 * speed / (1.0 + a3 * speed * speed))
            torque = kt * omega * t + ct * omega - k * theta - c * speed - bit
            return [speed, torque / j]

    else:
        inv_mass, stiffness, damping = m["inv_mass"], m["stiffness"], m["damping"]
        forcing = m["top_spring"] * omega, m["top_damper"] * omega

        def rhs(t: float, y: np.ndarray) -> np.ndarray:
            theta, speed = y[:n], y[n:]
            torque = forcing[0] * t + forcing[1] - stiffness @ theta - damping @ speed
            s = speed[-1]
            torque[-1] -= scale * (math.tanh(a1 * s) + a2 * s / (1.0 + a3 * s * s))
            return np.concatenate([speed, inv_mass @ torque])

    period = 2.0 * math.pi / m.get("omega1", 0.8447)
    samples = np.arange(DURATION - WINDOW, DURATION, period / 200.0)
    solution = solve_ivp(
        rhs,
        (0.0, DURATION),
        np.zeros(2 * n),
        method="RK45",
        rtol=1e-6,
        atol=1e-9,
        t_eval=samples,
    )
    if not solution.success:
        raise RuntimeError(solution.message)
    bit_speed = solution.y[-1]
    return float((bit_speed.max() - bit_speed.min()) / (2.0 * omega))


def baseline(system: System, every: int) -> tuple[float, np.ndarray, np.ndarray]:
    """(seconds scaled to the whole grid, flat indices run, S_SS there)."""
    from torsio.model.modal import modal_analysis

    m = lean_model(system)
    m["omega1"] = float(modal_analysis(system.model, 1).frequencies_rad[0])
    wob, rpm = grid()
    flat_rpm, flat_wob = (a.ravel() for a in np.meshgrid(rpm, wob, indexing="ij"))
    indices = np.arange(0, flat_wob.size, every)
    values = np.empty(indices.size)
    start = time.perf_counter()
    for i, index in enumerate(indices):
        values[i] = lean_severity(m, float(flat_wob[index]), float(flat_rpm[index]))
    seconds = time.perf_counter() - start
    return seconds * flat_wob.size / indices.size, indices, values


# --- torsio ----------------------------------------------------------------------------------
def cli_command(strategy: str = "A") -> list[str]:
    torsio = shutil.which("torsio")
    cli = [torsio] if torsio else [sys.executable, "-m", "torsio.cli"]
    return [
        *cli,
        "map",
        "--strategy",
        strategy,
        "--wob",
        f"{WOB[0] / 1e3:g}kN:{WOB[1] / 1e3:g}kN:{POINTS}",
        "--rpm",
        f"{RPM[0]:g}:{RPM[1]:g}:{POINTS}",
        "--duration",
        f"{DURATION:g}",
        "--window",
        f"{WINDOW:g}",
        "--json",
    ]


def cli_map() -> tuple[float, dict[str, Any]]:
    command = cli_command()
    # as on a user's machine: Python keeps the bytecode of torsio's modules (pip writes it at
    # install), which PYTHONDONTWRITEBYTECODE would make every process compile again (0.1 s)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    start = time.perf_counter()
    result = subprocess.run(command, check=True, capture_output=True, text=True, env=env)
    return time.perf_counter() - start, json.loads(result.stdout)


def in_process(system: System) -> tuple[float, np.ndarray, int]:
    """(seconds, S_SS, points whose run ended on its steady cycle)."""
    wob, rpm = grid()
    start = time.perf_counter()
    result = severity_map(system, wob, rpm, duration=DURATION, steady_window=WINDOW, refine=0)
    return time.perf_counter() - start, result.severity, result.info["ended_on_steady_cycle"]


def threads() -> int:
    try:
        import numba

        return int(numba.get_num_threads())
    except ImportError:  # pragma: no cover
        return 1


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--every", type=int, default=13, help="1-DOF baseline: every k-th point")
    parser.add_argument("--every-10dof", type=int, default=43, help="10-DOF baseline sampling")
    parser.add_argument("--skip-10dof", action="store_true", help="only the 1-DOF model")
    args = parser.parse_args()
    for k in (args.every, args.every_10dof):
        if math.gcd(k, POINTS) != 1:
            parser.error(f"--every {k} shares a factor with {POINTS}: it would miss columns")
    one = ritto("A")
    print(
        f"machine: {os.cpu_count()} cores, numba threads {threads()}, python "
        f"{sys.version.split()[0]}; grid {POINTS} x {POINTS} WOB {WOB[0] / 1e3:g}-"
        f"{WOB[1] / 1e3:g} kN x {RPM[0]:g}-{RPM[1]:g} rpm; runs {DURATION:g} s from rest, "
        f"S_SS over the last {WINDOW:g} s"
    )
    warm = time.perf_counter()
    cli_map()  # fills numba's cache (first compile) if needed; not timed
    in_process(one)
    print(f"warm-up (numba compile or cache load, one CLI map): {time.perf_counter() - warm:.1f} s")

    cli_seconds, cli_data = cli_map()
    inproc_seconds, severity, ended = in_process(one)
    base_seconds, indices, base_values = baseline(one, args.every)
    error = float(np.max(np.abs(severity.ravel()[indices] - base_values)))
    cli_severity = np.asarray(cli_data["severity"], dtype=float).ravel()
    cli_error = float(np.max(np.abs(cli_severity[indices] - base_values)))
    print("\n1-DOF strategy A (the paper's model)")
    print(
        f"  baseline: lean solve_ivp RK45 loop  {base_seconds:8.1f} s  (timed on "
        f"{indices.size} of {POINTS**2} points, every {args.every}th, scaled; "
        f"{base_seconds / POINTS**2 * 1e3:.0f} ms/point)"
    )
    print(
        f"  torsio map --json (CLI, new process, all cores, critical-WOB bisection included) "
        f"{cli_seconds:6.2f} s  {base_seconds / cli_seconds:6.0f}x  (target 200x)  "
        f"max |dS_SS| {cli_error:.1e}"
    )
    print(
        f"  severity_map in process (refine=0, all cores)  {inproc_seconds:6.2f} s  "
        f"{base_seconds / inproc_seconds:6.0f}x  (target 500x)  max |dS_SS| {error:.1e}"
    )
    print(f"  CLI cost besides the in-process grid: {cli_seconds - inproc_seconds:.2f} s")
    print(
        f"  runs ended on their steady cycle (steady_tolerance "
        f"{cli_data['info']['steady_tolerance']:g}): CLI "
        f"{cli_data['info']['ended_on_steady_cycle']}, in process {ended} of {POINTS**2}"
    )
    if not args.skip_10dof:
        ten = ritto("C", 10)
        in_process(ten)  # warm
        seconds10, severity10, ended10 = in_process(ten)
        base10, indices10, values10 = baseline(ten, args.every_10dof)
        error10 = float(np.max(np.abs(severity10.ravel()[indices10] - values10)))
        print("\n10-DOF strategy C")
        print(
            f"  baseline: lean solve_ivp RK45 loop  {base10:8.1f} s  (timed on "
            f"{indices10.size} points, every {args.every_10dof}th, scaled)"
        )
        print(
            f"  severity_map in process (refine=0, all cores)  {seconds10:6.2f} s  "
            f"{base10 / seconds10:6.0f}x  (target 150x)  max |dS_SS| {error10:.1e}  "
            f"({ended10} runs ended on their steady cycle)"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
