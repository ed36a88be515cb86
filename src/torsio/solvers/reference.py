"""The reference of the batch engine: one :func:`scipy.integrate.solve_ivp` run per point."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from torsio.analysis.severity import run_times, severity_of_extremes
from torsio.errors import SolverError
from torsio.physics.system import System

if TYPE_CHECKING:
    from torsio.analysis.simulation_options import SimulationOptions

__all__ = ["reference_options", "reference_severity"]


def reference_severity(
    system: System, options: SimulationOptions | None = None, samples_per_step: int = 16
) -> tuple[float, dict[str, Any]]:
    """S_SS of one operating point with :func:`scipy.integrate.solve_ivp` (the reference).

    ``options``: the run length, window, integrator and tolerances, as for
    :func:`torsio.simulate`; by default :func:`reference_options` (Radau, rtol 1e-8,
    atol 1e-10), a scipy method in any case.

    Integrates :class:`torsio.physics.equations.TwistEquations` from rest (the exact
    Jacobian for implicit methods) and reads the extremes of the bit speed from
    the dense output, sampled ``samples_per_step`` times in every step of the
    window. This is the per-point method the batch engine is measured against.
    S_SS is relative to the set speed, or for a top drive without one (``torque``)
    to the mean top-drive speed over the window.

    Returns
    -------
    severity : float
        S_SS.
    info : dict
        ``nfev``, ``steps``, ``status`` and ``message`` of the solver, the
        extremes ``bit_speed_max``, ``bit_speed_min`` and ``top_speed_mean`` [rad/s]
        over the window.
    """
    from scipy.integrate import solve_ivp

    from torsio.physics.equations import TwistEquations

    if options is None:
        options = reference_options()
    method, rtol, atol = options.method, options.rtol, options.atol
    equations = TwistEquations(system)
    duration, steady_window = run_times(system, options.duration, options.steady_window)
    implicit = method in ("Radau", "BDF", "LSODA")
    jacobian: dict[str, Any] = {"jac": equations.jacobian} if implicit else {}
    try:
        solution = solve_ivp(
            equations.rhs,
            (0.0, duration),
            equations.rest_state(),
            method=method,
            rtol=rtol,
            atol=atol,
            dense_output=True,
            **jacobian,
        )
    except (ArithmeticError, ValueError, RuntimeError, np.linalg.LinAlgError) as exc:
        from torsio.plugins import describe_bit_law

        # e.g. a singular step matrix after a law returned NaN: name the point and the law
        raise SolverError(
            f"solve_ivp ({method}) failed at wob={system.wob:g} N, rpm={system.rpm:g} with the "
            f"bit-rock law {describe_bit_law(system.law)} ({type(exc).__name__}: {exc}); "
            "a law torque that is NaN or infinite, or an unstable model"
        ) from None
    info: dict[str, Any] = {
        "nfev": int(solution.nfev),
        "steps": int(solution.t.size - 1),
        "status": int(solution.status),
        "message": str(solution.message),
    }
    if solution.status != 0:
        raise SolverError(
            f"solve_ivp ({method}) failed at wob={system.wob:g} N, "
            f"rpm={system.rpm:g}: {solution.message}"
        )
    start = duration - steady_window
    nodes = solution.t
    inside = nodes[(nodes > start) & (nodes < duration)]
    edges = np.concatenate(([start], inside, [duration]))
    fractions = np.linspace(0.0, 1.0, samples_per_step + 1)[:-1]
    times = (edges[:-1, None] + np.diff(edges)[:, None] * fractions).ravel()
    times = np.append(times, duration)
    dynamics = equations.dynamics
    states = solution.sol(times)
    bit_speed = states[-1] + dynamics.reference_speed
    info["bit_speed_max"] = float(bit_speed.max())
    info["bit_speed_min"] = float(bit_speed.min())
    top_speed = states[dynamics.states + 1] + dynamics.reference_speed
    if not dynamics.has_top_node:
        top_speed = np.full_like(times, dynamics.reference_speed)
    info["top_speed_mean"] = float(np.trapezoid(top_speed, times) / steady_window)
    speed = dynamics.set_speed if np.isfinite(dynamics.set_speed) else info["top_speed_mean"]
    return float(severity_of_extremes(bit_speed.max(), bit_speed.min(), speed)), info


def reference_options(**overrides: Any) -> SimulationOptions:
    """The reference run's options: Radau, rtol 1e-8, atol 1e-10, and ``overrides``.

    Examples
    --------
    >>> reference_options(duration=20.0).method
    'Radau'
    """
    from torsio.analysis.simulation_options import SimulationOptions

    return SimulationOptions(**{"method": "Radau", "rtol": 1e-8, "atol": 1e-10, **overrides})
