"""Runs of a lumped chain with Coulomb contacts along the string: scipy between switches.

Each contact of :attr:`torsio.physics.dynamics.Dynamics.contacts` follows the event form of
:mod:`torsio.solvers.contact_law` (Aarsnes & Shor 2018): stuck, slipping slowly on C_s or
sliding on C_d. Between switches the equations are smooth and ``solve_ivp`` integrates
them; every switch is an event it locates (a speed reaching 0 or w_th, a stuck node's
holding torque reaching C_s), where the run restarts in the new states. A node that sticks
gets a speed of exactly 0 and the equation w' = 0: nothing creeps or leaks past it. Lumped
mass only (a contact's friction acts on its node alone).

The compiled RODAS4 engine runs the same law (:mod:`torsio.solvers.contact_kernel`) and
is what ``simulate`` uses by default; this module is the path of the scipy methods
(``method="LSODA"``, ``"Radau"``, ``"BDF"``, ...) and the reference the compiled engine is
tested against. The friction's work is exact: while a contact slides its torque
is constant, so its work over a piece of the run is C |theta(t1) - theta(t0)|; stuck, it
does none.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np
import scipy.integrate
import scipy.sparse

from torsio.analysis.budget import BudgetExceeded, EvaluationBudget
from torsio.analysis.simulation_options import SimulationOptions
from torsio.errors import ConfigError, SolverError
from torsio.physics.dynamics import Dynamics
from torsio.solvers import contact_law as law
from torsio.stop_signals import raise_if_stopped

__all__ = ["contact_method", "integrate_with_contacts"]

MAX_SWITCHES_PER_SAMPLE = 50
"""Contact switches allowed per output sample before a run is reported as chattering."""


class _Contacts:
    """The contacts' states over one run and the equations they give (mutable)."""

    def __init__(self, dynamics: Dynamics) -> None:
        contacts = dynamics.contacts
        self.dynamics = dynamics
        self.nodes = np.flatnonzero(np.asarray(contacts.static) > 0.0)
        self.static = np.asarray(contacts.static, dtype=float)[self.nodes]
        self.dynamic = np.asarray(contacts.dynamic, dtype=float)[self.nodes]
        self.threshold = float(contacts.threshold_speed)
        self.thresholds = np.full(self.nodes.size, self.threshold)
        self.mass = np.diag(dynamics.mass_matrix)[self.nodes]
        self.rows = dynamics.states + 1 + 2 * self.nodes  # v of each contact node in y
        self.reference = float(dynamics.reference_speed)
        self.codes = np.zeros((1, self.nodes.size))  # law's state codes, one point's
        self.code = self.codes.reshape(-1)  # the same, per contact
        self._cache: tuple[float, np.ndarray, np.ndarray] | None = None
        self.offsets = np.zeros((2, self.nodes.size))
        self.switches = 0

    # --- the equations -------------------------------------------------------------------
    def free_rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt without friction (cached for the events of one step)."""
        cache = self._cache
        if cache is not None and cache[0] == t and np.array_equal(cache[1], y):
            return cache[2]
        dy = self.dynamics.rhs(t, y)
        self._cache = (t, y.copy(), dy)
        return dy

    def holding(self, t: float, y: np.ndarray) -> np.ndarray:
        """The torque on each contact node from everything but its friction [N m]."""
        return self.free_rhs(t, y)[self.rows] * self.mass

    def friction(self) -> np.ndarray:
        """Friction torque of each moving contact [N m] (0 where stuck)."""
        out = np.empty((1, self.nodes.size))
        law.frictions(self.codes, self.static, self.dynamic, out)
        return out.reshape(-1)

    @property
    def stuck(self) -> np.ndarray:
        """Which contacts hold their node."""
        return self.code == 0.0

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        dy = self.free_rhs(t, y).copy()
        dy[self.rows] -= self.friction() / self.mass
        dy[self.rows[self.stuck]] = 0.0
        return dy

    def jacobian(self, t: float, y: np.ndarray) -> Any:
        """d(dy/dt)/dy in the present states: a stuck node's row is zero (sparse)."""
        keep = np.ones(self.dynamics.size)
        keep[self.rows[self.stuck]] = 0.0
        return (scipy.sparse.diags(keep) @ self.dynamics.jacobian(t, y)).tocsc()

    def speeds(self, y: np.ndarray) -> np.ndarray:
        """Absolute speed of each contact node [rad/s]."""
        return self.reference + y[self.rows]

    # --- the switches --------------------------------------------------------------------
    def start(self, y: np.ndarray) -> None:
        """States at the initial state: at rest stuck (until :meth:`prepare` finds it pushed
        beyond C_s), moving on the branch of its speed."""
        law.start_codes(self.speeds(y)[None, :], self.static, self.thresholds, self.codes)
        self.prepare(0.0, y)

    def tolerances(self) -> np.ndarray:
        """How near 0 a margin counts as 0 (:meth:`margins`), (2, contacts)."""
        out = np.empty((1, 2, self.nodes.size))
        law.tolerances(self.codes, self.static, self.thresholds, np.array([self.reference]), out)
        return out.reshape(2, -1)

    def apply(self, row: int, j: int, t: float, y: np.ndarray) -> None:
        """The switch of contact j whose margin ``row`` (:meth:`margins`) falls through 0; a
        node that sticks gets its speed set to exactly 0 in ``y``."""
        self.switches += 1
        now = self.code[j]
        holding = float(self.holding(t, y)[j])
        self.code[j] = law.switched(now, row + 1, holding, self.static[j], self.threshold)
        if self.code[j] == 0.0 and now != 0.0:
            y[self.rows[j]] = -self.reference
        self._cache = None

    def prepare(self, t: float, y: np.ndarray) -> None:
        """Before a piece of the run from ``(t, y)``: switch every contact whose margin is
        below 0, or at 0 and falling (found along the motion over a short time), until none
        is; then offset the margins at 0 to their tolerance, so that the event function
        starts positive (a switch is then found where a margin falls through minus its
        tolerance: 1e-9 of its scale)."""
        for _ in range(4 * self.nodes.size + 4):
            margins = self.margins(t, y)
            tolerance = self.tolerances()
            lapse = 1e-9 * (1.0 + abs(t))
            ahead = self.margins(t + lapse, y + lapse * self.rhs(t, y))
            falling = (margins < -tolerance) | ((margins <= tolerance) & (ahead < margins))
            if not falling.any():
                break
            row, j = np.unravel_index(int(np.argmin(np.where(falling, margins, np.inf))),
                                      margins.shape)  # fmt: skip
            self.apply(int(row), int(j), t, y)
        else:
            raise SolverError(
                f"the contacts along the string do not settle at t = {t:.6g} s: they switch "
                "back and forth at one instant"
            )
        self.offsets = np.where(margins <= tolerance, tolerance - margins, 0.0)

    def margins(self, t: float, y: np.ndarray) -> np.ndarray:
        """Per contact, the two margins of :func:`law.margin` (2, contacts): (a) a moving
        contact's speed reaching 0, a stuck one's holding torque reaching C_s [N m]; (b) a
        moving contact's speed crossing the threshold (1 where it cannot)."""
        holding = self.holding(t, y) if self.stuck.any() else np.zeros(self.nodes.size)
        out = np.empty((1, 2, self.nodes.size))
        law.margins(self.codes, self.static, self.thresholds, self.speeds(y)[None, :],
                    holding[None, :], out)  # fmt: skip
        return out.reshape(2, -1)

    def event(self) -> Callable[[float, np.ndarray], float]:
        """One event function for every contact: the least margin (:meth:`margins`, offset
        by :meth:`prepare`), which falls through 0 when any contact switches."""

        def least(t: float, y: np.ndarray) -> float:
            if not self.nodes.size:
                return 1.0
            return float(np.min(self.margins(t, y) + self.offsets))

        least.terminal = True  # type: ignore[attr-defined]
        least.direction = -1.0  # type: ignore[attr-defined]
        return least

    def work(self, t0: float, y0: np.ndarray, t1: float, y1: np.ndarray) -> float:
        """The friction's work [J] over a piece of the run in the present states (exact)."""
        angle0 = y0[self.rows - 1] + self.reference * t0
        angle1 = y1[self.rows - 1] + self.reference * t1
        return float(np.sum(self.friction() * (angle1 - angle0)))


def contact_method(method: Any) -> str:
    """The scipy method that runs contacts for ``simulation.method`` (``"auto"``: LSODA).

    >>> contact_method("auto"), contact_method("Radau")
    ('LSODA', 'Radau')
    """
    if method == "RODAS4":
        raise ConfigError(
            "simulation.method",
            "RODAS4 runs on the compiled engine (torsio.solvers.single_run), not between "
            "scipy's located switches; expected auto, LSODA, Radau or BDF here",
        )
    if method == "auto":
        return "LSODA"
    if not isinstance(method, str):
        raise ConfigError(
            "simulation.method", f"a run with contacts takes a scipy method name, got {method!r}"
        )
    return method


def _jacobian_arguments(contacts: _Contacts, method: str) -> dict[str, Any]:
    """The Jacobian as each scipy method takes it (LSODA: packed bands where it has them)."""
    if method in ("RK45", "RK23", "DOP853"):
        return {}
    if method != "LSODA":
        return {"jac": contacts.jacobian}
    bands = contacts.dynamics.jacobian_bands
    if bands is None:
        return {"jac": lambda t, y: contacts.jacobian(t, y).toarray()}
    lower, upper = bands
    size = contacts.dynamics.size

    def packed(t: float, y: np.ndarray) -> np.ndarray:
        coo = contacts.jacobian(t, y).tocoo()
        out = np.zeros((lower + upper + 1, size))
        out[upper + coo.row - coo.col, coo.col] = coo.data
        return out

    return {"jac": packed, "lband": lower, "uband": upper}


def integrate_with_contacts(
    dynamics: Dynamics,
    y0: np.ndarray,
    time_grid: np.ndarray,
    options: SimulationOptions,
    where: str,
    progress: Callable[[int, int], None] | None,
) -> tuple[np.ndarray, dict[str, Any]]:
    """The states (size, samples) on the grid of a run with contacts, and the solver's record
    (``contact_switches``, ``friction_work`` [J] and ``fallback`` (None: the caller says why
    the compiled engine did not run) besides the usual keys)."""
    if not dynamics.lumped_mass:
        raise ConfigError(
            "discretization.strategy", "friction along the string needs a lumped-mass chain"
        )
    method = contact_method(options.method)
    contacts = _Contacts(dynamics)
    run = float(time_grid[-1])
    budget = EvaluationBudget.for_samples(time_grid.size - 1)
    rhs = budget.wrap(contacts.rhs)
    jac = _jacobian_arguments(contacts, method)
    events = [contacts.event()]
    states = np.empty((dynamics.size, time_grid.size))
    y = np.array(y0, dtype=float)
    contacts.start(y)
    states[:, 0] = y
    filled, t, work = 1, float(time_grid[0]), 0.0
    counts = {"nfev": 0, "njev": 0, "nlu": 0}
    limit = MAX_SWITCHES_PER_SAMPLE * time_grid.size
    start = time.perf_counter()
    while True:
        with np.errstate(all="ignore"):
            try:
                piece = scipy.integrate.solve_ivp(
                    rhs, (t, run), y, method=method, t_eval=time_grid[filled:],
                    events=events, rtol=options.rtol, atol=options.atol, **jac,
                )  # fmt: skip
            except BudgetExceeded:
                raise budget.error(method, run, where) from None
        for key in counts:
            counts[key] += int(getattr(piece, key))
        if piece.status < 0:
            raise SolverError(
                f"the {method} integrator failed at t = {t:.6g} s of {run:.6g} s between "
                f"contact switches: {piece.message} (operating point {where})"
            )
        samples = np.asarray(piece.y, dtype=float).reshape(dynamics.size, -1)
        taken = samples.shape[1]
        states[:, filled : filled + taken] = samples
        filled += taken
        raise_if_stopped()  # a stop signal whose KeyboardInterrupt Python lost
        if progress is not None:
            progress(filled, time_grid.size)
        if piece.status == 0:
            work += contacts.work(t, y, run, samples[:, -1] if taken else y)
            break
        t_event = float(piece.t_events[0][0])
        y_event = np.array(piece.y_events[0][0], dtype=float)
        work += contacts.work(t, y, t_event, y_event)
        contacts.prepare(t_event, y_event)
        t, y = t_event, y_event
        if contacts.switches > limit:
            raise SolverError(
                f"more than {limit} contact switches by t = {t:.6g} s of {run:.6g} s "
                f"(operating point {where}): the contacts chatter; try a larger "
                "threshold_speed or another discretization"
            )
    if filled != time_grid.size:
        raise SolverError(f"the {method} run with contacts ended at t = {t:.6g} s of {run:.6g} s")
    info = {
        "engine": "scipy",
        "method": method,
        "rtol": options.rtol,
        "atol": options.atol,
        **counts,
        "status": 0,
        "message": "integrated between the contacts' switches",
        "contact_switches": contacts.switches,
        "friction_work": work,
        "fallback": None,
        "wall_time_s": time.perf_counter() - start,
    }
    return states, info
