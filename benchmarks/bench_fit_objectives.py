"""Which objective recovers what: fits to start-ups that torsio recorded from known factors.

The built-in deviated well (open hole mu_s 0.35, mu_d 0.3, threshold 0.5 rad/s,
alpha 0.35 1/s), wave strategy, bit off bottom; 60 s start-ups to 120 and 150 rpm by a
SoftTorque top drive (J = 2900 kg m^2, ramp 5 s), sampled every 0.0103 s; noise: Gaussian,
sample by sample, the given fraction on the torque and half of it on the speed. Prints a
Markdown table (docs/calibration.md, "What each objective recovers").

    PYTHONPATH=src python benchmarks/bench_fit_objectives.py
"""

from __future__ import annotations

import warnings

import attrs

from torsio.analysis.wave import wave_response
from torsio.calibration.fit import fit_recordings
from torsio.calibration.recording import Recording
from torsio.config.top_drive import TopDriveConfig
from torsio.examples import deviated_well_config
from torsio.physics.top_drives import SoftTorqueTopDrive

TRUTH = {"friction_static": 0.35, "friction_dynamic": 0.3, "threshold_speed": 0.5, "alpha": 0.35}
SPEEDS = (120.0, 150.0)


def startup(rpm: float, noise: float) -> Recording:
    system = deviated_well_config().system(strategy="wave")
    system = system.with_top(SoftTorqueTopDrive(inertia=2900.0, ramp=5.0)).at(wob=0.0, rpm=rpm)
    tr = wave_response(
        system, duration=60.0, steady_window=6.0, output_step=0.01, progress=False
    ).transient
    return Recording.from_transient(
        tr, torque_noise=noise, speed_noise=0.5 * noise, seed=int(rpm), name=f"{rpm:g} rpm"
    )


def main() -> None:
    warnings.simplefilter("ignore")
    config = deviated_well_config()
    soft = attrs.evolve(
        config, top_drive=TopDriveConfig("soft-torque", {"inertia": 2900.0, "ramp": 5.0})
    )
    cases = [
        (objective, top, noise, names)
        for names in (["friction_static", "friction_dynamic"],)
        for noise in (0.0, 0.01, 0.02)
        for objective, top in (
            ("torque", "recorded"),
            ("features", "recorded"),
            ("torque", "configured"),
        )
    ]
    cases += [
        ("torque", "recorded", noise, ["friction_dynamic", extra])
        for extra in ("threshold_speed", "alpha")
        for noise in (0.0, 0.02)
    ]
    print(
        "| objective | top | noise | parameter | fitted | error | sigma | 2-sigma interval "
        "contains truth | start | runs | s |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    records = {noise: [startup(rpm, noise) for rpm in SPEEDS] for noise in (0.0, 0.01, 0.02)}
    for objective, top, noise, names in cases:
        cfg = soft if top == "configured" else config
        rpm = SPEEDS if top == "configured" else None
        result = fit_recordings(cfg, records[noise], names, objective=objective, top=top, rpm=rpm)
        for name, value, spread, start in zip(
            result.names, result.values, result.uncertainty, result.start, strict=True
        ):
            low, high = spread.interval
            inside = "yes" if low <= TRUTH[name] <= high else "**no**"
            print(
                f"| {objective} | {top} | {noise:.0%} | {name} | {value:.5f} | "
                f"{value - TRUTH[name]:+.1e} | {spread.sigma:.1e} | {inside} | "
                f"{start:.4f} | {result.runs} | {result.seconds:.0f} |",
                flush=True,
            )


if __name__ == "__main__":
    main()
