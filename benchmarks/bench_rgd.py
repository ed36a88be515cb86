"""The axial-torsional engine with the RGD bit against a plain numba loop of the same step.

1. A 300 s run of the 2-DOF RGD model (docs/axial.md's example: I = 455.65 kg m²,
   k = 324.857 N m/rad, c = 19.49 N m s/rad, M = 29981.3 kg; the reference bit; 100 kN,
   60 rpm, from rest) on ``torsio.analysis.axial_transient.simulate_axial`` (no signals kept)
   against the loop below: the same scheme and step written out for this one model with
   the state in scalars and its own history search (cubic Hermite, as the engine). Both
   give the same S_SS and ROP (printed); the ratio engine / loop is the engine's price for
   being general (chains, hooks, prescribed rotation, signals). Target: within 3x.
2. A 21 x 21 map, WOB 80..200 kN x 30..200 rpm, default run length (40 periods of the
   torsional mode, 298 s) on ``torsio.analysis.axial_maps.axial_map``, serial. Target: under 60 s.

Run: ``python benchmarks/bench_rgd.py [--repeat 5] [--skip-map]``. Times are the median
of the repeats (compiled functions warm).
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

import numpy as np

from torsio.analysis.axial_maps import axial_map
from torsio.analysis.axial_transient import simulate_axial
from torsio.axial.rgd import rgd_example
from torsio.model.axial_assembly import rgd_two_dof_example
from torsio.solvers.axial_run_setup import RunOptions, run_setup
from torsio.solvers.compiled import njit

WOB, RPM, DURATION, WINDOW = 100e3, 60.0, 300.0, 100.0


@njit(cache=True)
def plain_loop(p, h, steps, window_start, past, hist):  # noqa: C901
    """The 2-DOF model stepped like torsio.solvers.axial_kernel; returns (S_SS, ROP, stuck)."""
    inertia, k, c, mass, wob, top = p[0], p[1], p[2], p[3], p[4], p[5]
    wc1, tc1, wf_max, tf1, blade, n = p[6], p[7], p[8], p[9], p[10], p[11]
    capacity = hist.shape[1]
    theta, omega, u, v = 0.0, 0.0, 0.0, 0.0
    for j in range(past + 1):  # a flat bottom, the bit at rest
        tj = (j - past) * h
        hist[0, j], hist[1, j], hist[2, j], hist[3, j], hist[4, j] = tj, top * tj, top, 0.0, 0.0
    hist[2, past] = 0.0
    written, seg = past + 1, 0
    wmax, wmin, stuck, u_start = -1e300, 1e300, 0, 0.0
    for step in range(steps):
        t = step * h
        if step == window_start:
            u_start = u
        angle = theta - blade
        while seg + 1 < written - 1 and hist[1, (seg + 1) % capacity] <= angle:
            seg += 1
        a, b = seg % capacity, (seg + 1) % capacity
        p0, p1, t0 = hist[1, a], hist[1, b], hist[0, a]
        dt = hist[0, b] - t0
        m0, m1 = hist[2, a] * dt, hist[2, b] * dt
        s = (angle - p0) / (p1 - p0)
        lo, hi = 0.0, 1.0
        for _ in range(30):
            s2 = s * s
            s3 = s2 * s
            f = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0
            f += (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1 - angle
            if f > 0:
                hi = s
            else:
                lo = s
            g = (6 * s2 - 6 * s) * (p0 - p1) + (3 * s2 - 4 * s + 1) * m0 + (3 * s2 - 2 * s) * m1
            new = s - f / g if g > 0 else 2.0
            if not (lo <= new <= hi):
                new = 0.5 * (lo + hi)
            done = abs(new - s) <= 1e-16
            s = new
            if done:
                break
        s2 = s * s
        s3 = s2 * s
        w0, w1 = hist[4, a] * dt, hist[4, b] * dt
        surface = (2 * s3 - 3 * s2 + 1) * hist[3, a] + (s3 - 2 * s2 + s) * w0
        surface += (-2 * s3 + 3 * s2) * hist[3, b] + (s3 - s2) * w1
        depth = n * (u - surface)
        newest = (written - 1) % capacity
        kept = max(u, surface)
        if kept != hist[3, newest]:
            hist[4, newest] = (kept - hist[3, (written - 2) % capacity]) / h
            hist[3, newest] = kept
        cut = depth > 0.0
        wc = wc1 * depth if cut else 0.0
        tc = tc1 * depth if cut else 0.0
        free = v + h * (wob - wc) / mass
        wf = 0.0
        if cut:
            if free - h * wf_max / mass > 0.0:
                wf = wf_max
                free -= h * wf_max / mass
            elif free >= 0.0:
                wf = free * mass / h
                free = 0.0
        v = free
        torque = k * (top * t - theta) + c * (top - omega)
        spin = omega + h * (torque - tc - tf1 * wf) / inertia
        omega = spin if spin > 0.0 else 0.0
        theta += h * omega
        u += h * v
        j = written % capacity
        hist[0, j], hist[1, j], hist[2, j], hist[3, j], hist[4, j] = t + h, theta, omega, u, v
        written += 1
        if step >= window_start:
            wmax = max(wmax, omega)
            wmin = min(wmin, omega)
            if abs(omega) < 0.1 * top:  # stuck below 0.1 Ω₀, torsio's stick threshold
                stuck += 1
    count = steps - window_start
    return (wmax - wmin) / (2 * top), (u - u_start) / (count * h), stuck / count


def _median(function, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--skip-map", action="store_true")
    args = parser.parse_args()
    assembly, bit = rgd_two_dof_example(), rgd_example()
    setup = run_setup(assembly, bit, WOB, RPM, RunOptions(DURATION, WINDOW))
    p = np.array(
        [
            455.65,
            324.857,
            19.49,
            29981.3,
            WOB,
            RPM * math.pi / 30,
            *setup.bit[:4],
            setup.bit[4],
            setup.bit[5],
        ]
    )
    past = int(math.ceil(1.5 * setup.steady.delay / setup.step)) + 4
    hist = np.zeros((5, setup.steps + past + 2))
    window_start = setup.steps - setup.window_steps

    def engine():
        return simulate_axial(
            assembly, bit, WOB, RPM, duration=DURATION, window=WINDOW, samples=0, growth_rate=False
        )

    def loop():
        return plain_loop(p, setup.step, setup.steps, window_start, past, hist)

    run, reference = engine(), loop()  # compile (or load the cache)
    print(
        f"2-DOF RGD, {WOB / 1e3:g} kN, {RPM:g} rpm, {DURATION:g} s from rest, "
        f"h = {setup.step * 1e3:.4f} ms ({setup.steps} steps)"
    )
    print(
        f"  engine: S_SS {run.severity:.6f}  ROP {run.axial.rop_mean * 3600:.4f} m/h  "
        f"stuck {run.stick_fraction:.4f}"
    )
    print(
        f"  loop:   S_SS {reference[0]:.6f}  ROP {reference[1] * 3600:.4f} m/h  "
        f"stuck {reference[2]:.4f}"
    )
    t_engine, t_loop = _median(engine, args.repeat), _median(loop, args.repeat)
    print(
        f"  engine {t_engine * 1e3:.1f} ms, plain loop {t_loop * 1e3:.1f} ms, "
        f"ratio {t_engine / t_loop:.2f} (median of {args.repeat})"
    )
    if args.skip_map:
        return
    axial_map(assembly, bit, [WOB], [RPM], duration=2.0, window=1.0)
    start = time.perf_counter()
    grid = axial_map(assembly, bit, np.linspace(80e3, 200e3, 21), np.linspace(30.0, 200.0, 21))
    elapsed = time.perf_counter() - start
    print(
        f"21 x 21 map, 80..200 kN x 30..200 rpm, {grid.info['duration']:.1f} s runs, serial: "
        f"{elapsed:.1f} s ({elapsed / 441 * 1e3:.1f} ms per run)"
    )


if __name__ == "__main__":
    main()
