"""One run with ``scipy.integrate.solve_ivp`` over an output grid (for ``simulate``).

The independent check of the compiled engine (:mod:`torsio.solvers.single_run`), and
the integrator of what it cannot run. LSODA gets the analytic Jacobian in its banded
format (``lband``, ``uband``), Radau and BDF the sparse one, explicit methods none; the
right-hand side evaluations are capped (:class:`torsio.analysis.budget.EvaluationBudget`).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np
import scipy.integrate

from torsio.analysis.budget import BudgetExceeded, EvaluationBudget
from torsio.analysis.simulation_options import IMPLICIT_METHODS, SimulationOptions
from torsio.errors import SolverError
from torsio.physics.dynamics import Dynamics
from torsio.stop_signals import raise_if_stopped

__all__ = ["integrate_scipy"]


def _band_jacobian(dynamics: Dynamics, lower: int, upper: int) -> Any:
    """The Jacobian in LSODA's packed banded format: packed[upper + i - j, j] = J[i, j]."""
    size = dynamics.size

    def jac(t: float, y: np.ndarray) -> np.ndarray:
        coo = dynamics.jacobian(t, y).tocoo()
        packed = np.zeros((lower + upper + 1, size))
        packed[upper + coo.row - coo.col, coo.col] = coo.data
        return packed

    return jac


def integrate_scipy(
    dynamics: Dynamics,
    y0: np.ndarray,
    time_grid: np.ndarray,
    chosen: Any,
    options: SimulationOptions,
    where: str,
    progress: Callable[[int, int], None] | None,
) -> tuple[np.ndarray, dict[str, Any]]:
    """solve_ivp over the grid with the Jacobian each method can use."""
    solver_kwargs: dict[str, Any] = {}
    name = chosen if isinstance(chosen, str) else chosen.__name__
    bands = dynamics.jacobian_bands
    if chosen == "LSODA":
        if bands is not None:
            lower, upper = bands
            solver_kwargs.update(
                lband=lower, uband=upper, jac=_band_jacobian(dynamics, lower, upper)
            )
        else:
            solver_kwargs["jac"] = lambda t, y: dynamics.jacobian(t, y).toarray()
    elif chosen in IMPLICIT_METHODS or (
        isinstance(chosen, type) and issubclass(chosen, scipy.integrate.Radau | scipy.integrate.BDF)
    ):
        solver_kwargs["jac"] = dynamics.jacobian
    run = float(time_grid[-1])
    budget = EvaluationBudget.for_samples(time_grid.size - 1)
    rhs = _reporting(budget.wrap(dynamics.rhs), run, time_grid.size, progress)
    start = time.perf_counter()
    with np.errstate(all="ignore"):
        try:
            solution = scipy.integrate.solve_ivp(
                rhs,
                (0.0, run),
                y0,
                method=chosen,
                t_eval=time_grid,
                rtol=options.rtol,
                atol=options.atol,
                **solver_kwargs,
            )
        except BudgetExceeded:
            raise budget.error(name, run, where) from None
    elapsed = time.perf_counter() - start
    times = np.asarray(solution.t, dtype=float)
    reached = float(times[-1]) if times.size else 0.0
    states = np.asarray(solution.y, dtype=float)
    if solution.status < 0 or states.ndim != 2 or states.shape[1] != time_grid.size:
        raise SolverError(
            f"the {name} integrator failed at t = {reached:.6g} s of {run:.6g} s: "
            f"{solution.message} (operating point {where}; try another method or tighter "
            "tolerances)"
        )
    info = {
        "engine": "scipy",
        "method": name,
        "rtol": options.rtol,
        "atol": options.atol,
        "nfev": int(solution.nfev),
        "njev": int(solution.njev),
        "nlu": int(solution.nlu),
        "status": int(solution.status),
        "message": str(solution.message),
        "wall_time_s": elapsed,
    }
    return states, info


def _reporting(
    rhs: Callable[[float, np.ndarray], np.ndarray],
    run: float,
    samples: int,
    progress: Callable[[int, int], None] | None,
) -> Callable[[float, np.ndarray], np.ndarray]:
    """``rhs`` that every 0.2 s raises a stop signal whose KeyboardInterrupt Python lost
    (:mod:`torsio.stop_signals`) and reports the output samples reached (by its time)."""
    last = [time.perf_counter()]

    def wrapped(t: float, y: np.ndarray) -> np.ndarray:
        now = time.perf_counter()
        if now - last[0] > 0.2:
            last[0] = now
            raise_if_stopped()
            if progress is not None:
                progress(min(samples, 1 + int(float(t) / run * (samples - 1))), samples)
        return rhs(t, y)

    return wrapped
