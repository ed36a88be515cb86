"""Validated numbers: each quantity, its source, the source's value and torsio's.

The same checks run in the test suite (``tests/test_validation.py``) and generate
``docs/validation.md`` (``python -m torsio.validation --write docs/validation.md``),
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

import attrs

from torsio.continuum import continuum_modes
from torsio.discretize import StrategyA, StrategyB, StrategyC
from torsio.drillstring import DrillString
from torsio.examples import ritto2017_string
from torsio.lumped import LumpedModel
from torsio.modal import modal_analysis


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
    """

    quantity: str
    source: str
    source_value: float
    value: float
    tolerance: float
    note: str = ""

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

    from torsio.components import Bit, DrillPipe

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


def table(rows: list[Check]) -> str:
    """The checks as a Markdown table."""
    lines = [
        "| quantity | source | source value | torsio | difference | tolerance |",
        "|---|---|---:|---:|---:|---:|",
    ]
    for row in rows:
        diff = "-" if row.source_value == 0 else f"{100 * row.difference:+.3g} %"
        lines.append(
            f"| {row.quantity} | {row.source} | {row.source_value:.6g} | "
            f"{row.value:.6g} | {diff} | {row.tolerance:.2g} ({row.note}) |"
        )
    return "\n".join(lines) + "\n"


HEADER = """# Validation

Every number torsio is checked against, with its source. This page is generated by
`python -m torsio.validation --write docs/validation.md` from the same checks the test
suite runs (`tests/test_validation.py`); a test fails if this page differs from a fresh
generation. *difference* is (torsio − source)/|source|; a check passes when
|torsio − source| is within the tolerance, whose reason is given in brackets.

"""


def page() -> str:
    """The whole validation page."""
    rows = [function() for function in CHECKS.values()]
    failed = [row.quantity for row in rows if not row.passed]
    status = "All checks pass." if not failed else f"FAILING: {', '.join(failed)}"
    return HEADER + table(rows) + f"\n{status}\n"


def main(argv: list[str] | None = None) -> int:
    """``python -m torsio.validation [--write FILE]``."""
    parser = argparse.ArgumentParser(prog="python -m torsio.validation")
    parser.add_argument("--write", type=Path, help="write the page to this file")
    args = parser.parse_args(argv)
    text = page()
    if args.write:
        args.write.write_text(text, encoding="utf-8")
    else:
        sys.stdout.write(text)
    return 0 if "FAILING" not in text else 1


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())


__all__ = ["CHECKS", "Check", "check", "main", "page", "table"]
