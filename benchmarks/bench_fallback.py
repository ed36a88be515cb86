"""Maps of a law numba cannot compile: the numpy engine against one scipy run per point.

Such a law (here a regularized Coulomb-Stribeck law whose ``torque`` goes through
``np.asarray(..., dtype=float)``, which numba does not type) has no compiled kernel, so a
map runs on the numpy engine or on scipy (``engine="scipy"``: Radau per point at the map's
tolerances). The script times both on the same 11 x 11 grid (25-225 kN x 20-140 rpm, the
default run from rest) of the built-in string, 1 DOF (strategy A) and 5 DOFs (strategy C),
and prints the ratio and max |dS_SS|.

    python benchmarks/bench_fallback.py            # about 4 minutes on 2 cores
    python benchmarks/bench_fallback.py --quick    # 1 DOF only, about 2 minutes
"""

from __future__ import annotations

import argparse
import time
from typing import Any

import attrs
import numpy as np

from torsio.examples import builtin_config
from torsio.solvers.batch import simulate_batch


class AsarrayStribeck:
    """W R [mu_c + (mu_s - mu_c) exp(-|w|/w_s)] tanh(w/eps), through np.asarray."""

    name = "asarray-stribeck"

    def __init__(self) -> None:
        self.mu_static, self.mu_coulomb, self.stribeck_speed, self.smoothing = (
            0.8,
            0.5,
            1 / 0.9,
            0.01,
        )

    def torque(self, speed: Any, wob: Any, radius: Any) -> Any:
        w = np.asarray(speed, dtype=float)
        drop = (self.mu_static - self.mu_coulomb) * np.exp(-np.abs(w) / self.stribeck_speed)
        return wob * radius * (self.mu_coulomb + drop) * np.tanh(w / self.smoothing)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="the 1-DOF model only")
    args = parser.parse_args()
    models = [("1 DOF (A)", {"strategy": "A"})]
    if not args.quick:
        models.append(("5 DOF (C)", {"strategy": "C"}))
    wob, rpm = np.meshgrid(np.linspace(25e3, 225e3, 11), np.linspace(20.0, 140.0, 11))
    for label, options in models:
        system = attrs.evolve(builtin_config().system(**options), law=AsarrayStribeck())
        times, results = {}, {}
        for engine in ("numpy", "scipy"):
            start = time.perf_counter()
            results[engine] = simulate_batch(system, wob.ravel(), rpm.ravel(), engine=engine)
            times[engine] = time.perf_counter() - start
            assert results[engine].engine == engine and results[engine].ok.all()
        difference = np.max(np.abs(results["numpy"].severity - results["scipy"].severity))
        print(
            f"{label}, 121 points: numpy {times['numpy']:.2f} s, scipy {times['scipy']:.1f} s, "
            f"numpy {times['scipy'] / times['numpy']:.0f}x faster, max |dS_SS| {difference:.1e}"
        )


if __name__ == "__main__":
    main()
