"""Does a kernel written out for one degree of freedom pay? Measured in one run.

torsio has one compiled kernel for every chain length (``torsio.solvers.rodas``). Until
the dynamics were written once it also had a hand copy of it for one DOF, with the state
in scalars instead of arrays. This script keeps that copy (below, the candidate, adapted
to the law's first-class functions) and measures, on the 1-DOF (strategy A) built-in
Ritto et al. (2017) string, WOB 20..250 kN x 30..150 rpm, default run length and
tolerances:

1. the kernel alone on a 41 x 41 grid, one thread: the generic kernel at n = 1 against
   the 1-DOF candidate (same method, same steps; the bit-speed extremes agree to
   round-off);
2. the whole ``torsio map`` on the same 41 x 41 grid through the CLI (caches warm), which
   is what a user waits for: the kernel's share of it decides whether the copy pays.

Run: ``python benchmarks/bench_one_dof.py [--repeat 3]``. The machine is often shared:
compare the ratios, which are taken within the run.
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import subprocess
import sys
import time

import numpy as np

from torsio.examples import builtin_config
from torsio.solvers import batch, layouts, rodas, rodas_kernels
from torsio.solvers.compiled import njit
from torsio.solvers.cycles import extremes_of_cubic
from torsio.solvers.law_kernels import law_type
from torsio.solvers.lumped_inputs import run_settings, step_limits

GRID = 41


def _signature():  # type: ignore[no-untyped-def]
    from numba import types

    f8, law, vector = types.float64, law_type(), types.float64[::1]
    return types.void(f8, f8, f8, f8, law, law, vector, vector, vector, vector, f8[:, ::1])


@njit(_signature(), cache=True)
def one_dof_serial(m, k, c, drag, torque, slope, p, settings, wobs, omegas, outs) -> None:  # noqa: C901
    """The 1-DOF candidate: RODAS4 with the state in scalars, every point in turn."""
    t_end, t_window = settings[layouts.RUN_T_END], settings[layouts.RUN_WINDOW_START]
    rtol, atol = settings[layouts.RUN_RTOL], settings[layouts.RUN_ATOL]
    h0, hmax = settings[layouts.RUN_FIRST_STEP], settings[layouts.RUN_MAX_STEP]
    max_steps, radius = int(settings[layouts.RUN_MAX_STEPS]), settings[layouts.RUN_BIT_RADIUS]
    a_coef, c_coef = rodas.RODAS_A, rodas.RODAS_C
    for point in range(wobs.size):
        wob, omega, out = wobs[point], omegas[point], outs[point]
        kphi = np.zeros(6)
        kv = np.zeros(6)
        phi, v = 0.0, -omega
        tiny = 1e-12 * max(1.0, t_end)
        f0v = -k * phi - c * v - omega * drag - torque(p, omega + v, wob, radius)
        acc0 = f0v / m
        t, h = 0.0, min(h0, hmax, t_end)
        vmax, vmin = -np.inf, np.inf
        steps = rejected = status = 0
        last_rejected = False
        h_accepted, err_accepted = h, 1.0
        aphi, av = phi, v
        while t < t_end:
            if steps >= max_steps:
                status = 1
                break
            if h < tiny:
                status = 2
                break
            if t + h > t_end:
                h = t_end - t
            g = rodas.GAMMA * h
            a = m / g + c + g * k + slope(p, omega + v, wob, radius)
            if not abs(a) > 1e-13 * (m / g + abs(c) + g * k):
                h *= 0.5
                rejected += 1
                last_rejected = True
                continue
            ia = 1.0 / a
            for stage in range(6):
                aphi, av, uphi, uv = phi, v, 0.0, 0.0
                for j in range(stage):
                    aphi += a_coef[stage, j] * kphi[j]
                    av += a_coef[stage, j] * kv[j]
                    uphi += c_coef[stage, j] * kphi[j]
                    uv += c_coef[stage, j] * kv[j]
                if stage == 0:
                    fphi, fv = v, f0v
                else:
                    fphi = av + uphi / h
                    fv = -k * aphi - c * av - omega * drag - torque(p, omega + av, wob, radius)
                    fv += m * uv / h
                x = (fv - g * k * fphi) * ia
                kv[stage] = x
                kphi[stage] = g * (fphi + x)
            yp, yv = aphi + kphi[5], av + kv[5]
            ep = kphi[5] / (atol + rtol * max(abs(phi), abs(yp)))
            ev = kv[5] / (atol + rtol * max(abs(v), abs(yv)))
            err = math.sqrt(0.5 * (ep * ep + ev * ev))
            if not math.isfinite(err):
                h *= 0.25
                rejected += 1
                last_rejected = True
                if h < tiny:
                    status = 3
                    break
                continue
            factor = max(1.0 / 6.0, min(5.0, math.sqrt(math.sqrt(err)) / 0.9))
            h_new = h / factor
            if err <= 1.0:
                if steps > 0:
                    predicted = h_accepted / h * math.sqrt(math.sqrt(err * err / err_accepted))
                    h_new = h / max(factor, max(1.0 / 6.0, min(5.0, predicted / 0.9)))
                h_accepted, err_accepted = h, max(1e-2, err)
                u0 = v
                phi, v = yp, yv
                f0v = -k * phi - c * v - omega * drag - torque(p, omega + v, wob, radius)
                acc1 = f0v / m
                if t + h > t_window:
                    lo = (t_window - t) / h if t < t_window else 0.0
                    vmax, vmin = extremes_of_cubic(u0, v, h * acc0, h * acc1, lo, 1.0, vmax, vmin)
                acc0 = acc1
                t += h
                steps += 1
                if last_rejected:
                    h_new = min(h_new, h)
                last_rejected = False
                h = min(h_new, hmax)
            else:
                rejected += 1
                last_rejected = True
                h = h_new
        out[layouts.OUT_BIT_SPEED_MAX] = vmax + omega
        out[layouts.OUT_BIT_SPEED_MIN] = vmin + omega
        out[layouts.OUT_STEPS] = steps
        out[layouts.OUT_REJECTED] = rejected
        out[layouts.OUT_STATUS] = status


def part_kernel(repeat: int) -> float:
    system = builtin_config().system(strategy="A")
    model = batch.BatchModel.from_system(system)
    torque, slope, parameters = system.law.kernel()
    ww, rr = np.meshgrid(np.linspace(20e3, 250e3, GRID), np.linspace(30.0, 150.0, GRID))
    wob = np.ascontiguousarray(ww.ravel())
    omega = np.ascontiguousarray(rr.ravel() * math.pi / 30.0)
    duration, window = batch.run_times(system, None, None)
    # the kernel's settings: every run to the end, no steady-cycle stop
    steps = step_limits(model.first_frequency)
    settings = run_settings(duration, window, 1e-5, 1e-6, steps, 2_000_000, 0.108, 0.0, 0.0)
    chain = model.chain[:, 0]
    m, k = chain[layouts.CHAIN_MASS], chain[layouts.CHAIN_STIFFNESS]
    c, drag = chain[layouts.CHAIN_DAMPING], chain[layouts.CHAIN_DRAG]
    runs = {
        "generic kernel, n = 1": lambda out: rodas_kernels.integrate_serial(
            model.chain, model.top, torque, slope, parameters, settings, wob, omega, omega, out
        ),
        "1-DOF candidate": lambda out: one_dof_serial(
            m, k, c, drag, torque, slope, parameters, settings, wob, omega, out
        ),
    }
    outputs = {name: np.zeros((wob.size, layouts.OUT_COLUMNS)) for name in runs}
    times: dict[str, list[float]] = {name: [] for name in runs}
    for name, run in runs.items():
        run(outputs[name])  # compile or load
    for _ in range(repeat):
        for name, run in runs.items():
            start = time.perf_counter()
            run(outputs[name])
            times[name].append(time.perf_counter() - start)
    print(f"1. the kernel alone, 1 DOF, {GRID} x {GRID}, one thread (median of {repeat})")
    base = statistics.median(times["1-DOF candidate"])
    for name, values in times.items():
        seconds = statistics.median(values)
        steps = int(outputs[name][:, 2].sum())
        print(f"   {name:24s} {seconds:6.2f} s  x{seconds / base:4.2f}  ({steps} steps)")
    generic, candidate = outputs.values()
    print(f"   max |d extreme| [rad/s]: {np.max(np.abs(generic[:, :2] - candidate[:, :2])):.1e}")
    return statistics.median(times["generic kernel, n = 1"]) - base


def part_cli(repeat: int, saving: float) -> None:
    command = [sys.executable, "-m", "torsio", "map", "--strategy", "A", "--json"]
    command += ["--wob", f"20e3:250e3:{GRID}", "--rpm", f"30:150:{GRID}"]
    subprocess.run(command, capture_output=True, check=True)  # warm the caches
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        done = subprocess.run(command, capture_output=True, text=True, check=True)
        times.append(time.perf_counter() - start)
    seconds = statistics.median(times)
    engine = json.loads(done.stdout)["engine"]
    print(f"2. torsio map, 1 DOF, {GRID} x {GRID} ({engine}, all cores): {seconds:.2f} s")
    print(
        f"   the candidate would save at most {saving:.2f} s of one thread's kernel time, "
        f"{saving / seconds:.0%} of the map's wall time on one core"
    )


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="timed runs of each case")
    args = parser.parse_args(argv)
    saving = part_kernel(args.repeat)
    part_cli(args.repeat, saving)


if __name__ == "__main__":
    main()
