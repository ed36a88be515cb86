"""Validated numbers: each quantity, its source, the source's value and torsio's.

The same checks run in the test suite (``tests/test_validation.py``) and generate
``docs/validation.md`` (``python -m torsio.report.validation --write docs/validation.md``),
and a test compares that page with a fresh generation, so it cannot drift.

Examples
--------
>>> row = CHECKS["continuum_f1"]()
>>> row.source_value, round(row.value, 4), row.passed
(0.1307, 0.1307, True)
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import attrs

from torsio.examples import ritto2017_string
from torsio.model.continuum import continuum_modes
from torsio.model.discretize import StrategyA, StrategyB, StrategyC
from torsio.model.drillstring import DrillString
from torsio.model.lumped import LumpedModel
from torsio.model.modal import modal_analysis
from torsio.output_files import write_text
from torsio.report import validation_page


@attrs.frozen
class Check:
    """One validated quantity.

    Attributes
    ----------
    quantity : str
        What is compared, with its unit.
    source : str
        Where the expected value comes from (paper, exact continuum, closed form, ...).
    source_value : float
        The source's value.
    value : float
        torsio's value.
    tolerance : float
        Allowed |value - source_value| (absolute, in the quantity's unit).
    note : str
        How the tolerance follows from the source (digits quoted, "about", ...).
    digits : int
        Significant digits of ``value`` on the page: 6, fewer for a value whose later
        digits are round-off that changes with the CPU and the BLAS (a residual).
    """

    quantity: str
    source: str
    source_value: float
    value: float
    tolerance: float
    note: str = ""
    digits: int = 6

    @property
    def difference(self) -> float:
        """Relative difference (value - source) / |source|."""
        return (self.value - self.source_value) / abs(self.source_value)

    @property
    def passed(self) -> bool:
        """Whether |value - source_value| <= tolerance."""
        return abs(self.value - self.source_value) <= self.tolerance


CHECKS: dict[str, Callable[[], Check]] = {}
"""Every check, by name, in the order of the table."""


def check(function: Callable[[], Check]) -> Callable[[], Check]:
    """Register a check function under its name."""
    function.__doc__ = function.__doc__ or (
        "A validation check: compute torsio's value and return it as a :class:`Check`."
    )
    CHECKS[function.__name__] = function
    return function


def _first_hz(string: DrillString, discretizer: object, mode: int = 1) -> float:
    model = discretizer.discretize(string)  # type: ignore[attr-defined]
    return float(modal_analysis(model, mode).frequencies_hz[mode - 1])


# --- the paper's numbers ------------------------------------------------------------------------
@check
def continuum_f1() -> Check:
    value = float(continuum_modes(ritto2017_string(), 1).frequencies_hz[0])
    return Check(
        "first natural frequency, exact continuum [Hz]",
        "paper Sec. 3: FEM, 2430 elements",
        0.1307,
        value,
        5e-5,
        "4 digits quoted",
    )


@check
def strategy_a_stiffness() -> Check:
    value = float(StrategyA().discretize(ritto2017_string()).stiffness[0, 0])
    return Check(
        "strategy A stiffness G J_DP / L_DP [N m/rad]",
        "ERRATA 1 (recomputed)",
        324.86,
        value,
        0.005,
        "2 decimals quoted",
    )


@check
def strategy_a_inertia() -> Check:
    value = float(StrategyA().discretize(ritto2017_string()).inertia[0, 0])
    return Check(
        "strategy A inertia I_DP/3 + I_BHA [kg m^2]",
        "ERRATA 1 (recomputed, Eq. 5)",
        455.65,
        value,
        0.005,
        "2 decimals quoted",
    )


@check
def strategy_a_f1() -> Check:
    value = _first_hz(ritto2017_string(), StrategyA())
    return Check(
        "strategy A first frequency [Hz]",
        "paper Sec. 3 with ERRATA 1",
        0.1344,
        value,
        5e-5,
        "4 digits quoted",
    )


@check
def strategy_a_error() -> Check:
    string = ritto2017_string()
    exact = float(continuum_modes(string, 1).frequencies_hz[0])
    value = 100 * (_first_hz(string, StrategyA()) / exact - 1)
    return Check(
        "strategy A error against the reference [%]",
        "paper Sec. 3",
        2.8,
        value,
        0.05,
        "1 decimal quoted",
    )


@check
def strategy_b_one_dp_dof_f1_error() -> Check:
    string = ritto2017_string()
    exact = float(continuum_modes(string, 1).frequencies_hz[0])
    value = 100 * (_first_hz(string, StrategyB(dp_elements=1, bha_elements=50)) / exact - 1)
    return Check(
        "strategy B, 1 DP + 50 BHA DOFs: first-frequency error [%]",
        "paper Sec. 3 (Fig. 4): 'a difference of 8 %'",
        -8.0,
        value,
        0.5,
        "'8 %' read as 7.5-8.5 %",
    )


@check
def strategy_b_mode15_error() -> Check:
    return _mode_error_check(15)


@check
def strategy_b_mode25_error() -> Check:
    return _mode_error_check(25)


def _mode_error_check(mode: int) -> Check:
    string = ritto2017_string()
    exact = float(continuum_modes(string, mode).frequencies_hz[mode - 1])
    value = 100 * (_first_hz(string, StrategyB(dp_elements=120, bha_elements=30), mode) / exact - 1)
    return Check(
        f"strategy B, 120 + 30 DOFs: mode {mode} error [%]",
        "paper Fig. 5: 'good prediction quality'",
        0.0,
        value,
        2.0,
        "'close' read as within 2 %",
    )


# --- closed forms and analytic results -----------------------------------------------------------
@check
def tip_inertia_closed_form() -> Check:
    from scipy.optimize import brentq

    from torsio.model.components import Bit, DrillPipe

    string = DrillString(
        [DrillPipe(od=0.14, id=0.1, length=3000.0), Bit(od=0.3, id=0.05, length=0.5)]
    )
    shaft, bit = string.sections
    ratio = shaft.inertia / bit.inertia
    beta = brentq(
        lambda b: b * math.sin(b) - ratio * math.cos(b), 20 * math.pi, 20.5 * math.pi, xtol=1e-15
    )
    expected = beta * shaft.material.wave_speed / shaft.length / (2 * math.pi)
    value = float(continuum_modes(string, 21).frequencies_hz[20])
    return Check(
        "uniform shaft + tip inertia, 21st frequency [Hz]",
        "closed form beta tan beta = I_shaft/I_tip",
        expected,
        value,
        1e-12 * expected,
        "to machine precision",
    )


@check
def one_dof_frequency() -> Check:
    model = LumpedModel.from_chain([455.65], [324.86])
    expected = math.sqrt(324.86 / 455.65)
    value = float(modal_analysis(model).frequencies_rad[0])
    return Check(
        "1-DOF natural frequency [rad/s]",
        "analytic sqrt(k/I)",
        expected,
        value,
        1e-14 * expected,
        "to machine precision",
    )


@check
def strategy_c_order() -> Check:
    string = ritto2017_string()
    exact = float(continuum_modes(string, 1, rigid_bha=True).frequencies_hz[0])
    errors = [_first_hz(string, StrategyC(dp_elements=n)) / exact - 1 for n in (20, 40)]
    value = math.log2(errors[0] / errors[1])
    return Check(
        "strategy C, mode 1: observed convergence order (20 -> 40 DOFs)",
        "analytic: lumped-mass linear elements are 2nd order",
        2.0,
        value,
        0.05,
        "asymptotic order",
    )


# --- dynamics: analytic results and conservation laws ------------------------------------
def _ritto_system(strategy: str = "C", **options: Any) -> Any:
    from torsio.examples import builtin_config

    return builtin_config().system(strategy=strategy, **options)


@check
def static_twist() -> Check:
    import attrs

    from torsio.analysis.transient import simulate
    from torsio.physics.damping import RayleighDamping
    from torsio.physics.laws import ConstantTorque

    torque = 2000.0
    system = attrs.evolve(
        _ritto_system(),
        law=ConstantTorque(torque_on_bit=torque),
        damping=RayleighDamping(alpha=0.0, beta=0.06),
    )
    # beta damping alone gives zeta_1 = 0.025: 2000 s leave e^-40 of the start-up transient
    results = simulate(system, duration=2000.0, steady_window=100.0, rtol=1e-9, atol=1e-12)
    expected = -torque / system.model.equivalent_stiffness
    return Check(
        "bit twist under a constant bit torque of 2 kN m [rad]",
        "Eq. 9: steady twist -T/k_eq (beta damping only)",
        expected,
        float(results.bit_twist[-1]),
        1e-6 * abs(expected),
        "to the solver tolerance",
    )


@check
def static_surface_torque() -> Check:
    import attrs

    from torsio.analysis.transient import simulate
    from torsio.physics.damping import RayleighDamping
    from torsio.physics.laws import ConstantTorque

    system = attrs.evolve(
        _ritto_system(),
        law=ConstantTorque(torque_on_bit=2000.0),
        damping=RayleighDamping(alpha=0.0, beta=0.06),
    )
    results = simulate(system, duration=2000.0, steady_window=100.0, rtol=1e-9, atol=1e-12)
    return Check(
        "surface torque under a constant bit torque of 2 kN m [N m]",
        "static equilibrium: equals the bit torque",
        2000.0,
        float(results.surface_torque[-1]),
        2000.0 * 1e-6,
        "to the solver tolerance",
    )


@check
def energy_balance_stick_slip() -> Check:
    from torsio.analysis.energy import energy_balance
    from torsio.analysis.transient import simulate

    results = simulate(_ritto_system().at(wob=150e3, rpm=60.0))
    return Check(
        "energy balance residual, stick-slip at 150 kN, 60 rpm [-]",
        "conservation of energy (work in = dissipated + bit work + stored)",
        0.0,
        energy_balance(results).relative_residual,
        1e-4,
        "quadrature of the output, relative to the work in",
        digits=2,  # the residual of a stick-slip run: its third digit is round-off
    )


@check
def one_dof_severity_reference() -> Check:
    from scipy.integrate import solve_ivp

    from torsio.analysis.transient import simulate

    system = _ritto_system("A").at(wob=100e3, rpm=60.0)
    results = simulate(system)
    inertia = float(system.model.inertia[0, 0])
    stiffness = float(system.model.stiffness[0, 0])
    alpha, beta, omega = system.damping.alpha, system.damping.beta, system.omega

    def rhs(t: float, y: list[float]) -> list[float]:  # Eq. 1 written out, theta absolute
        angle, speed = y
        torque = float(system.law.torque(speed, system.wob, system.bit_radius))
        acceleration = (
            -(alpha * inertia + beta * stiffness) * speed
            - stiffness * (angle - omega * t)
            + beta * stiffness * omega
            - torque
        )
        return [speed, acceleration / inertia]

    time = results.time
    reference = solve_ivp(
        rhs,
        (0.0, float(time[-1])),
        [0.0, 0.0],
        method="DOP853",
        rtol=1e-11,
        atol=1e-11,
        t_eval=time[results.window_mask],
    )
    expected = float((reference.y[1].max() - reference.y[1].min()) / (2 * omega))
    return Check(
        "S_SS, 1 DOF at 100 kN, 60 rpm [-]",
        "independent integration of Eq. 1 (DOP853, rtol 1e-11)",
        expected,
        results.severity,
        1e-3,
        "issue tolerance",
    )


@check
def dimensionless_severity() -> Check:
    from torsio.analysis.transient import simulate
    from torsio.physics.dimensionless import dimensionless_system

    system = _ritto_system().at(wob=150e3, rpm=60.0)
    dimensional = simulate(system, rtol=1e-10, atol=1e-12)
    scaled = simulate(dimensionless_system(system), rtol=1e-10, atol=1e-12)
    return Check(
        "S_SS, dimensionless (Eq. 11) against dimensional run [-]",
        "the same equations scaled by omega_1 and k_eq",
        dimensional.severity,
        scaled.severity,
        1e-6,
        "issue tolerance",
    )


@check
def stability_one_dof() -> Check:
    from torsio.analysis.stability import stability_boundary

    system = _ritto_system("A")
    rpm = 100.0
    omega = rpm * math.pi / 30
    damping = system.damping.alpha * float(
        system.model.inertia[0, 0]
    ) + system.damping.beta * float(system.model.stiffness[0, 0])
    slope = float(system.law.slope(omega, 1.0, 1.0))  # d(T / (W R)) / d speed
    expected = -damping / (system.bit_radius * slope)
    value = float(stability_boundary(system, [rpm]).critical_wob[0])
    return Check(
        "1-DOF linear stability boundary at 100 rpm [N]",
        "analytic c + W_ob R_bit T'(Omega) = 0",
        expected,
        value,
        1e-6 * expected,
        "root of a polynomial",
    )


@check
def map_point_against_single_run() -> Check:
    from torsio.analysis.maps import severity_map
    from torsio.analysis.transient import simulate

    system = _ritto_system()
    result = severity_map(system, wob=[150e3], rpm=[60.0], refine=0)
    single = simulate(system.at(wob=150e3, rpm=60.0), method="LSODA", rtol=1e-9, atol=1e-12)
    return Check(
        "S_SS of a map point (batch engine), 5 DOF at 150 kN, 60 rpm [-]",
        "single transient run, LSODA rtol 1e-9",
        single.severity,
        float(result.severity[0, 0]),
        0.01,
        "issue tolerance",
    )


def page() -> str:
    """The whole validation page (``docs/validation.md``): every check of :data:`CHECKS`."""
    return validation_page.page(CHECKS)


def main(argv: list[str] | None = None) -> int:
    """``python -m torsio.report.validation [--write FILE]``."""
    parser = argparse.ArgumentParser(prog="python -m torsio.report.validation")
    parser.add_argument("--write", type=Path, help="write the page to this file")
    args = parser.parse_args(argv)
    text = page()
    if args.write:
        write_text(args.write, text)
    else:
        sys.stdout.write(text)
    return 0 if "FAILING" not in text else 1


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())


__all__ = ["CHECKS", "Check", "check", "main", "page"]  # the table: torsio.report.validation_page
