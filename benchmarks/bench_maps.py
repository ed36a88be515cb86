"""Severity maps: the batch engine against one solve_ivp run per grid point, in one run.

Baseline: ``torsio.analysis.transient.simulate`` per point with ``method="RK45", rtol=1e-6``
(atol 1e-9), i.e. one ``scipy.integrate.solve_ivp`` call per operating point.
Batch: ``torsio.analysis.maps.severity_map`` on the same grid (``refine=0``: the grid only,
the same work as the baseline), default engine and tolerances.

Both use runs of 300 s from rest and read S_SS over the last 100 s, on the
21 x 21 grid WOB 25..225 kN x 40..140 rpm (the range of the Ritto et al. 2017
group's code), for the 1-DOF strategy-A model and the 10-DOF strategy-C model of
the built-in Ritto et al. (2017) string.

The baseline is slow (minutes), so by default it runs on every 8th grid point
(56 of 441; 8 and 21 are coprime, so the subset visits every row and column of
the grid, stable and stick-slip points alike) and its time is extrapolated to the
441 points; ``--baseline-every 1`` runs it everywhere. max |dS_SS| is taken over
the points the baseline ran.

Run: ``python benchmarks/bench_maps.py`` (about 3 minutes on 2 cores),
``--quick`` for a short check (fewer baseline points, no 10 201-point map).
"""

from __future__ import annotations

import argparse
import cProfile
import io
import os
import pstats
import sys
import time

import numpy as np

from torsio.analysis.maps import severity_map
from torsio.analysis.transient import simulate
from torsio.examples import builtin_config
from torsio.physics.system import System
from torsio.solvers import batch, batch_options

DURATION = 300.0
WINDOW = 100.0


def ritto(strategy: str, dp_elements: int | None = None) -> System:
    options = {} if dp_elements is None else {"dp_elements": dp_elements}
    return builtin_config().system(strategy=strategy, **options)


def grid(points: int) -> tuple[np.ndarray, np.ndarray]:
    return np.linspace(25e3, 225e3, points), np.linspace(40.0, 140.0, points)


def batch_map(system: System, points: int, **options: object) -> tuple[float, np.ndarray, dict]:
    wob, rpm = grid(points)
    start = time.perf_counter()
    result = severity_map(
        system, wob, rpm, duration=DURATION, steady_window=WINDOW, refine=0, **options
    )
    return time.perf_counter() - start, result.severity, result.info


def baseline(
    system: System, points: int, every: int, limit: int | None = None
) -> tuple[float, int, np.ndarray, np.ndarray]:
    """Per-point RK45 runs on every ``every``-th point: (seconds, runs, indices, S_SS)."""
    wob, rpm = grid(points)
    ww, rr = np.meshgrid(wob, rpm)
    indices = np.arange(0, ww.size, every)
    if limit is not None:
        indices = indices[:limit]
    values = np.empty(indices.size)
    start = time.perf_counter()
    for k, index in enumerate(indices):
        point = system.at(wob=float(ww.flat[index]), rpm=float(rr.flat[index]))
        values[k] = simulate(
            point, duration=DURATION, steady_window=WINDOW, method="RK45", rtol=1e-6, atol=1e-9
        ).severity
    return time.perf_counter() - start, indices.size, indices, values


def compare(label: str, system: System, every: int) -> dict[str, float]:
    points = 21
    seconds, severity, info = batch_map(system, points)
    base_seconds, runs, indices, base_values = baseline(system, points, every)
    extrapolated = base_seconds * points * points / runs
    error = float(np.max(np.abs(severity.ravel()[indices] - base_values)))
    print(f"{label}: 21 x 21 map, {system.model.dofs} DOF")
    print(
        f"  batch engine ({info['executor']}, {batch_options.DEFAULT_RTOL:g} rtol): "
        f"{seconds:8.3f} s"
    )
    note = (
        ""
        if runs == points * points
        else (f" (timed on {runs} of {points * points} points, x {points * points / runs:.2f})")
    )
    print(f"  per-point solve_ivp RK45 rtol 1e-6:   {extrapolated:8.1f} s{note}")
    print(
        f"  speed-up: {extrapolated / seconds:7.0f} x     max |dS_SS| = {error:.2e} "
        f"over {runs} points"
    )
    return {
        "speedup": extrapolated / seconds,
        "error": error,
        "batch": seconds,
        "baseline": extrapolated,
    }


def engines(system: System) -> None:
    wob, rpm = grid(21)
    ww, rr = np.meshgrid(wob, rpm)
    rows = []
    for engine, threads in (("compiled", 1), ("compiled", 2), ("numpy", None)):
        result = batch.simulate_batch(
            system, ww, rr, duration=DURATION, steady_window=WINDOW, engine=engine, threads=threads
        )
        rows.append(
            (f"{engine}" + (f", {threads} thread(s)" if threads else ""), result.elapsed, result)
        )
    reference = rows[0][2].severity
    for name, seconds, result in rows:
        print(
            f"  {name:22s} {seconds:8.3f} s   max |dS| vs compiled(1): "
            f"{np.nanmax(np.abs(result.severity - reference)):.1e}"
        )


def scaling_grid(system: System, sizes: list[int]) -> None:
    for points in sizes:
        seconds, severity, _ = batch_map(system, points)
        print(
            f"  {points:3d} x {points:3d} = {points * points:6d} points: {seconds:7.2f} s "
            f"({seconds / points**2 * 1e3:.3f} ms/point), severe: "
            f"{int((severity > 0.8).sum())}"
        )


def scaling_dofs(dofs: list[int], quick: bool) -> None:
    for n in dofs:
        system = ritto("A") if n == 1 else ritto("C", n)
        wob, rpm = grid(21)
        ww, rr = np.meshgrid(wob, rpm)
        result = batch.simulate_batch(system, ww, rr, duration=DURATION, steady_window=WINDOW)
        attempts = int(result.steps.sum() + result.rejected.sum())
        # baseline per point on two points (a stable and a stick-slip one), extrapolated
        # (stiff models: RK45 over the first 30 s only, its time x 10; its step is set by
        # the stability limit of the overdamped high modes, the same all along the run)
        base = []
        span = DURATION if n <= 50 else 30.0
        for w, r in ((50e3, 120.0), (150e3, 60.0)):
            if n > 50 and quick:
                continue
            start = time.perf_counter()
            simulate(
                system.at(wob=w, rpm=r),
                duration=span,
                steady_window=span / 3,
                method="RK45",
                rtol=1e-6,
                atol=1e-9,
            )
            base.append((time.perf_counter() - start) * DURATION / span)
        severe = float((result.severity > 0.8).mean())
        if base:
            estimate = (1 - severe) * base[0] + severe * base[-1]
            how = "2 points" + (", 30 s x 10" if n > 50 else "")
            base_text = (
                f"~{estimate * ww.size:8.0f} s (from {how})  speed-up "
                f"~{estimate * ww.size / result.elapsed:5.0f} x"
            )
        else:
            base_text = "(not run with --quick)"
        print(
            f"  {n:4d} DOF: batch {result.elapsed:7.2f} s, "
            f"{attempts / ww.size:7.0f} steps/point, "
            f"{result.elapsed / attempts * 1e9 * _threads():7.0f} ns/step/thread; "
            f"RK45 baseline {base_text}; highest mode "
            f"{batch.BatchModel.from_system(system).highest_frequency:7.1f} rad/s"
        )


def _threads() -> int:
    try:
        import numba

        return int(numba.get_num_threads())
    except ImportError:  # pragma: no cover
        return 1


def profile(system: System) -> None:
    wob, rpm = grid(21)
    profiler = cProfile.Profile()
    start = time.perf_counter()
    profiler.enable()
    result = severity_map(system, wob, rpm, duration=DURATION, steady_window=WINDOW)
    profiler.disable()
    total = time.perf_counter() - start
    stats = pstats.Stats(profiler, stream=io.StringIO())
    kernel = _cumulative(stats, "_run_compiled") or _cumulative(stats, "integrate_numpy")
    modal = _cumulative(stats, "modal_analysis")
    stability = _cumulative(stats, "stability_boundary")
    grid_runs = result.wob.size * result.rpm.size
    extra = result.info["extra_runs"]
    steps = result.steps
    severe = result.severity > 0.8
    print(f"  full map with critical-WOB bisection: {total:.3f} s")
    print(
        f"    integration kernel: {kernel:.3f} s ({kernel / total:.0%}) for {grid_runs} grid "
        f"runs + {extra} bisection runs"
    )
    print(
        f"    modal analysis / stability boundary / rest: {modal:.3f} s / {stability:.3f} s "
        f"/ {total - kernel - modal - stability:.3f} s"
    )
    print(
        f"    steps per point: stable {np.median(steps[~severe]):.0f} (median), stick-slip "
        f"{np.median(steps[severe]):.0f}: stick-slip points take "
        f"{steps[severe].sum() / steps.sum():.0%} of the steps"
    )


def _cumulative(stats: pstats.Stats, name: str) -> float:
    total = 0.0
    for (_, _, function), (_, _, _, cumulative, _) in stats.stats.items():  # type: ignore
        if function == name:
            total += cumulative
    return total


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--baseline-every",
        type=int,
        default=8,
        help="time the baseline on every k-th grid point (default 8)",
    )
    parser.add_argument("--quick", action="store_true", help="a short run")
    args = parser.parse_args()
    every = args.baseline_every if not args.quick else 20
    print(
        f"machine: {os.cpu_count()} cores; numba {'yes' if batch.HAVE_NUMBA else 'no'}; "
        f"python {sys.version.split()[0]}"
    )
    start = time.perf_counter()
    for system in (ritto("A"), ritto("C", 10)):  # the 1-DOF and the n-DOF kernels
        severity_map(system, [1e5, 2e5], [60.0, 80.0], duration=10.0, steady_window=5.0, refine=1)
        batch.simulate_batch(
            system, [1e5, 2e5], [60.0, 80.0], duration=10.0, steady_window=5.0, threads=1
        )
    print(
        f"first calls (numba compile, or load from its cache): "
        f"{time.perf_counter() - start:.2f} s\n"
    )

    one = compare("1-DOF strategy A", ritto("A"), every)
    ten = compare("10-DOF strategy C", ritto("C", 10), every)
    print()
    met = (
        one["speedup"] >= 200 and ten["speedup"] >= 100 and max(one["error"], ten["error"]) <= 0.01
    )
    print(
        "targets: >= 200 x (1 DOF), >= 100 x (10 DOF), max |dS_SS| <= 0.01: "
        f"{'met' if met else 'NOT met'}"
    )
    print("\nengines on the 1-DOF 21 x 21 grid (with and without numba):")
    engines(ritto("A"))
    print("\nengines on the 10-DOF 21 x 21 grid:")
    engines(ritto("C", 10))
    print("\nscaling with grid size (1 DOF):")
    scaling_grid(ritto("A"), [21, 41] if args.quick else [21, 41, 101])
    print("\nscaling with DOFs (strategy C, 21 x 21):")
    scaling_dofs([1, 10, 50] if args.quick else [1, 10, 50, 150], args.quick)
    print("\nwhere the time goes (1-DOF 21 x 21 map):")
    profile(ritto("A"))
    print("\nwhere the time goes (10-DOF 21 x 21 map):")
    profile(ritto("C", 10))
    return 0


if __name__ == "__main__":
    sys.exit(main())
