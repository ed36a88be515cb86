"""Batch engine: S_SS at many operating points of one System, integrated together.

A severity map is hundreds to tens of thousands of transient runs of the same
model at different weights on bit and rotary speeds. :func:`simulate_batch`
integrates a whole batch of operating points, each with its own adaptive step and
error control, and returns S_SS (paper Eq. 12) for each.

The method (RODAS4, the tridiagonal step matrix, the in-step extremes of the bit
speed) is described in :mod:`torsio.solvers.rodas`; the engines run it on the
chain and top drive of :mod:`torsio.physics.dynamics`.

Engines
-------
``"compiled"`` (alias ``"numba"``)
    :mod:`torsio.solvers.rodas`, compiled with numba, points shared dynamically
    between threads. Needs a bit-rock law with a compiled kernel (``kernel()``,
    :mod:`torsio.solvers.law_kernels`; the built-in laws and the bundled plugin's have one),
    or one numba compiles from the law's Python ``torque``. The only engine that takes
    Coulomb contacts along the string (a ``[well]``, :mod:`torsio.solvers.contact_kernel`).
``"numpy"``
    :mod:`torsio.solvers.numpy_engine`: the same method vectorized with numpy
    across the batch; works with any law (its vectorized ``torque``). Slower; ``"auto"``
    uses it for a law numba cannot compile, and without numba. It takes no ramp.
``"scipy"``
    One :func:`scipy.integrate.solve_ivp` run per point (:mod:`torsio.solvers.reference`).
``"auto"``
    ``"compiled"`` when numba is installed and the law has or gets a kernel, else ``"numpy"``.

:attr:`BatchResults.engine` says which one ran.

Examples
--------
>>> from torsio.examples import builtin_config
>>> system = builtin_config().system(strategy="A")
>>> result = simulate_batch(system, wob=[50e3, 200e3], rpm=[120.0, 50.0])
>>> [round(float(s), 2) for s in result.severity], result.engine
([0.0, 1.77], 'compiled')
>>> result.ok.all()
np.True_
"""

from __future__ import annotations

import math
import time
import warnings
from typing import Any

import attrs
import numpy as np

from torsio.analysis.severity import run_times, severity_of_extremes
from torsio.errors import ConfigError, SolverError
from torsio.model.modal import first_natural_frequency, highest_natural_frequency
from torsio.physics.system import System
from torsio.solvers.batch_options import ENGINES, BatchOptions, batch_threads
from torsio.solvers.batch_results import (
    STATUS_SOLVER_FAILED,
    BatchResults,
    batch_points,
)
from torsio.solvers.compiled import HAVE_NUMBA
from torsio.solvers.law_kernels import LawKernel, law_kernel, python_law_kernel
from torsio.solvers.layouts import (
    CHAIN_MASS_UPPER,
    OUT_BIT_SPEED_MAX,
    OUT_BIT_SPEED_MIN,
    OUT_COLUMNS,
    OUT_ENDED,
    OUT_REJECTED,
    OUT_STATUS,
    OUT_STEPS,
    OUT_TOP_SPEED_MEAN,
    TOP_HAS_NODE,
)
from torsio.solvers.lumped_inputs import pack_chain, pack_top, run_settings, step_limits
from torsio.solvers.reference import reference_options, reference_severity
from torsio.units import RPM_TO_RAD_S

__all__ = [
    "BatchModel",
    "resolve_engine",
    "simulate_batch",
    "simulate_lumped_batch",
]


@attrs.frozen(eq=False)
class BatchModel:
    """A System's chain, top drive and law as the batch engines use them.

    Derived from the one description of the dynamics (:class:`torsio.physics.dynamics.
    Dynamics`): with a top drive that has inertia, node 0 is the top drive.

    Attributes
    ----------
    chain : ndarray, shape (``CHAIN_ROWS``, n)
        [I], [K], [C] = [C_rel] + diag(drag) as bands, drag and applied torque per node
        (:mod:`torsio.solvers.layouts`).
    top : ndarray, shape (``TOP_SIZE``,)
        The top drive packed for the kernel (all zero: held top) at the System's own
        operating point (:meth:`top_at` gives it at another rotary speed).
    system : System
        The system (its top drive and law).
    torque_driven : bool
        Whether the top drive has no set speed (``torque``): Omega_ref from the torque
        balance, S_SS relative to the mean top-drive speed.
    first_frequency : float
        omega_1 [rad/s] of the model with the top held (:attr:`highest_frequency`: omega_n).
    """

    chain: np.ndarray
    top: np.ndarray
    system: System
    torque_driven: bool
    first_frequency: float

    @classmethod
    def from_system(cls, system: System) -> BatchModel:
        """The chain of ``system``, its contacts along the string included (ConfigError if
        the model is not a chain, or has contacts and consistent mass)."""
        dynamics = system.dynamics()
        if dynamics.contacts is not None and not dynamics.lumped_mass:
            raise ConfigError(
                "discretization.strategy",
                "friction along the string needs a lumped-mass chain (a contact holds one "
                "node's speed); use strategy A, B or C",
            )
        if not dynamics.is_chain:
            raise ConfigError(
                "model",
                "the batch engine needs tridiagonal (chain) matrices [I], [K], "
                "[C]; use engine='scipy' for other models",
            )
        chain = pack_chain(dynamics)
        return cls(
            chain,
            pack_top(dynamics.top, chain, dynamics),
            system,
            dynamics.has_top_node and not math.isfinite(dynamics.set_speed),
            first_natural_frequency(system.model),  # once per model, kept with it
        )

    @property
    def highest_frequency(self) -> float:
        """omega_n [rad/s] of the model with the top held (solved on first use, once per model)."""
        return highest_natural_frequency(self.system.model)

    @property
    def law(self) -> Any:
        """The bit-rock law."""
        return self.system.law

    @property
    def bit_radius(self) -> float:
        """R_bit [m]."""
        return float(self.system.bit_radius)

    @property
    def dofs(self) -> int:
        """Number of chain nodes (the top drive's included)."""
        return int(self.chain.shape[1])

    @property
    def lumped_mass(self) -> bool:
        """Whether [I] is diagonal."""
        return not np.any(self.chain[CHAIN_MASS_UPPER])

    def top_at(self, rpm: float) -> np.ndarray:
        """The packed top drive at set speed ``rpm`` (a controller may depend on it)."""
        if not self.top[TOP_HAS_NODE] or rpm == self.system.rpm:
            return self.top
        return pack_top(self.system.top.boundary(self.system.at(rpm=rpm)), self.chain)

    def reference_speeds(self, wob: np.ndarray, omega: np.ndarray) -> np.ndarray:
        """Omega_ref [rad/s] of each point: the set speed, or the torque balance if none."""
        if not self.torque_driven:
            return omega.copy()
        speeds = {w: self.system.at(wob=w).dynamics().reference_speed for w in set(wob.tolist())}
        return np.array([speeds[w] for w in wob.tolist()])


def resolve_engine(engine: str, law: Any) -> tuple[str, LawKernel | None]:
    """The engine that ``engine`` ("auto" or a name) means for ``law``, with its kernel.

    A law without ``kernel()`` gets one compiled from its Python ``torque`` where numba
    can (:func:`torsio.solvers.law_kernels.python_law_kernel`). With ``"auto"`` a law
    whose kernel cannot be had that way (or whose ``kernel()`` does not compile, with a
    warning saying why) runs on ``"numpy"``.
    """
    if engine not in ENGINES:
        raise ConfigError("engine", f"expected one of {', '.join(ENGINES)}, got {engine!r}")
    if engine in ("numpy", "scipy"):
        return engine, None
    if not HAVE_NUMBA:
        if engine == "auto":
            return "numpy", None
        raise ConfigError("engine", "the compiled engine needs numba (pip install numba)")
    name = getattr(law, "name", type(law).__name__)
    try:
        kernel = law_kernel(law)
    except ConfigError as exc:
        if engine != "auto":
            raise
        warnings.warn(f"{exc}; using the numpy engine", RuntimeWarning, stacklevel=3)
        return "numpy", None
    if kernel is None:  # numba may compile the law's own Python torque
        try:
            kernel = python_law_kernel(law)
        except ConfigError as exc:
            if engine == "auto":
                return "numpy", None
            raise ConfigError(
                "engine",
                f"bit-rock law {name!r} has no compiled kernel (a kernel() method, see the "
                f"plugin guide) and {exc.message.split(' and ', 1)[-1]}; use engine='numpy' "
                "(any law) or 'auto'",
            ) from None
    return "compiled", kernel


def simulate_batch(
    system: System,
    wob: Any,
    rpm: Any = None,
    options: BatchOptions | None = None,
    **values: Any,
) -> BatchResults:
    """S_SS of ``system`` at each operating point (wob[k], rpm[k]), started from rest.

    Parameters
    ----------
    system : System
        The model, damping, bit-rock law and top drive; its own operating point is ignored.
    wob : array_like or BatchPoints
        Weights on bit [N], >= 0; or points already checked
        (:class:`torsio.solvers.batch_results.BatchPoints`, ``rpm`` None), as a map's
        chunks are.
    rpm : array_like or None
        Surface rotary (set) speeds [rpm], > 0; broadcast against ``wob``. None (and
        only None) for a top drive without a set speed (``torque``): its speed follows
        from the torque balance and S_SS is relative to its mean over the window. A top
        drive's ``ramp`` raises each point's set speed from 0 to its own over the ramp (a
        start-up; a steady cycle is looked for from the ramp's end on); a top that follows
        a recording is refused (``top_drive.kind``).
    options : BatchOptions, optional
        How the points are integrated and read (:class:`torsio.solvers.batch_options.
        BatchOptions`: duration, steady window, tolerances, step limits, ``engine`` (see
        the module documentation), ``threads`` (numba's default when None; calls from
        other threads than the main one always run on one thread), ``steady_tolerance``
        (the compiled engine ends a run early once the motion is on a cycle whose bit-speed
        extremes can move by no more than this, :mod:`torsio.solvers.cycles`; not with a
        torque-driven top drive, whose mean speed needs the whole window)).
    **values
        Fields of :class:`BatchOptions` given one by one (over ``options``).

    Returns
    -------
    BatchResults
        Failed points have NaN severity and a non-zero status; they are never
        silently dropped.
    """
    from torsio.model.protocol import resolve

    run = resolve(system.model.engines.batch)  # the model names what runs it
    given = BatchOptions(**values) if options is None else options.replace(**values)
    return run(system, wob, rpm, given)


def simulate_lumped_batch(
    system: System, wob: Any, rpm: Any, options: BatchOptions
) -> BatchResults:
    """:func:`simulate_batch` of a lumped model (its batch engine,
    :data:`torsio.model.lumped.LUMPED_ENGINES`): the System, the points and the options.

    Contacts along the string whose normal force follows the weight on bit
    (:meth:`torsio.model.contacts.StringContacts.at_wob`) give each weight its own chain:
    the weights run side by side on ``options.threads`` threads, the points of each in
    turn (:func:`torsio.solvers.batch_options.batch_threads`)."""
    points = batch_points(system, wob, rpm)
    contacts = system.model.contacts
    if contacts is not None and contacts.depends_on_wob:  # one chain per weight
        weights = np.unique(points.wob)
        if weights.size > 1 or (weights.size == 1 and weights[0] != contacts.wob):
            return _weight_by_weight(system, points, weights, options)
    wob_arr, rpm_arr, torque_driven = points.wob, points.rpm, points.torque_driven
    rtol, atol, engine, threads = options.rtol, options.atol, options.engine, options.threads
    duration, steady_window = run_times(system, options.duration, options.steady_window)
    name, kernel = resolve_engine(engine, system.law)
    ramp = float(system.top.boundary(system).ramp)  # each point's, to its own set speed
    if name == "numpy" and ramp > 0.0:
        raise ConfigError(
            "top_drive.ramp",
            f"the numpy batch engine starts every point at its set speed, got a ramp of "
            f"{ramp:g} s; use engine='compiled' (numba) or 'scipy' for a map of start-ups, "
            "or ramp = 0",
        )
    if name == "scipy" and getattr(system.model, "contacts", None) is not None:
        raise ConfigError(
            "engine",
            f"the {name} batch engine takes no contacts along the string (a [well]); the "
            "compiled and numpy engines run them (engine='compiled' or 'numpy')",
        )
    model = BatchModel.from_system(system) if name != "scipy" else None
    omega1 = model.first_frequency if model is not None else first_natural_frequency(system.model)
    steps = step_limits(omega1, options.max_step)
    omega_set = rpm_arr * RPM_TO_RAD_S
    steady = 0.0 if torque_driven else options.steady_tolerance
    radius = model.bit_radius if model is not None else 0.0
    settings = run_settings(
        duration,
        steady_window,
        rtol,
        atol,
        steps,
        options.max_steps,
        radius,
        steady,
        omega1,
        ramp=ramp,
    )
    start = time.perf_counter()
    out = np.zeros((wob_arr.size, OUT_COLUMNS))
    out[:, OUT_ENDED] = duration  # the time each run ended (the compiled kernel may end earlier)
    if name == "scipy":
        reference_run = reference_options(
            duration=duration, steady_window=steady_window, rtol=rtol, atol=atol
        )
        for k in range(wob_arr.size):
            at = {} if torque_driven else {"rpm": float(rpm_arr[k])}
            point = system.at(wob=float(wob_arr[k]), **at)
            try:
                _, info = reference_severity(point, reference_run)
            except SolverError:  # one point's failure, reported by its status like the others'
                out[k, [OUT_BIT_SPEED_MAX, OUT_BIT_SPEED_MIN, OUT_TOP_SPEED_MEAN]] = math.nan
                out[k, OUT_STATUS] = STATUS_SOLVER_FAILED
                continue
            out[k, OUT_BIT_SPEED_MAX] = info["bit_speed_max"]
            out[k, OUT_BIT_SPEED_MIN] = info["bit_speed_min"]
            out[k, OUT_STEPS] = info["steps"]
            out[k, OUT_TOP_SPEED_MEAN] = info["top_speed_mean"]
    elif wob_arr.size:
        assert model is not None
        omega_ref = model.reference_speeds(wob_arr, omega_set)
        for top, rows in _groups(model, rpm_arr):
            point_settings = (settings, wob_arr[rows], omega_ref[rows], omega_set[rows])
            if name == "numpy":
                from torsio.solvers.numpy_engine import integrate_numpy

                out[rows] = integrate_numpy(model.chain, top, model.law, *point_settings)
            else:
                assert kernel is not None
                law = (kernel.torque, kernel.slope, kernel.parameters)
                part = np.zeros((rows.size, OUT_COLUMNS))
                _run_compiled((model.chain, top, *law, *point_settings, part), threads)
                out[rows] = part
    elapsed = time.perf_counter() - start
    status = out[:, OUT_STATUS].astype(np.int64)
    top_speed = out[:, OUT_TOP_SPEED_MEAN]
    reference = top_speed if torque_driven else omega_set
    bit_max, bit_min = out[:, OUT_BIT_SPEED_MAX], out[:, OUT_BIT_SPEED_MIN]
    with np.errstate(invalid="ignore", divide="ignore"):
        severity = np.where(status == 0, severity_of_extremes(bit_max, bit_min, reference), np.nan)
    return BatchResults(
        wob_arr,
        rpm_arr,
        severity,
        bit_max,
        bit_min,
        top_speed,
        out[:, OUT_STEPS].astype(np.int64),
        out[:, OUT_REJECTED].astype(np.int64),
        status,
        name,
        duration,
        steady_window,
        float(rtol),
        float(atol),
        elapsed,
        out[:, OUT_ENDED].copy(),
        steady,
    )


def _weight_by_weight(
    system: System, points: Any, weights: np.ndarray, options: BatchOptions
) -> BatchResults:
    """The points of each weight with that weight's contacts, side by side on threads
    (the compiled runs release the GIL; one thread each, so numba's pool is not shared).

    With several threads a weight's points run in pieces of at most a quarter of a
    thread's share, the heaviest weights first, so that no thread is left with a long
    column at the end; each weight's contacts are built once."""
    import threading
    from concurrent.futures import ThreadPoolExecutor

    one_thread = attrs.evolve(options, threads=1)
    start = time.perf_counter()
    workers = batch_threads(options.threads, points.size)
    piece = max(1, math.ceil(points.size / (4 * workers))) if workers > 1 else points.size
    tasks = [
        (float(weight), rows[k : k + piece])
        for weight in weights[::-1]
        for rows in [np.flatnonzero(points.wob == weight)]
        for k in range(0, rows.size, piece)
    ]
    systems: dict[float, System] = {}
    building = threading.Lock()

    def run(task: tuple[float, np.ndarray]) -> tuple[np.ndarray, BatchResults]:
        weight, rows = task
        with building:
            if weight not in systems:
                systems[weight] = system.at(wob=weight)
        return rows, simulate_lumped_batch(systems[weight], points[rows], None, one_thread)

    if workers == 1:
        parts = [run(task) for task in tasks]
    else:
        with ThreadPoolExecutor(max_workers=workers) as pool:
            parts = list(pool.map(run, tasks))
    gathered = BatchResults.gather(parts, points.size)
    return attrs.evolve(gathered, elapsed=time.perf_counter() - start)


def _groups(model: BatchModel, rpm: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """(packed top drive, indices of its points): one group unless the controller
    depends on the set speed beyond Omega_set itself."""
    if not model.top[TOP_HAS_NODE] or np.isnan(rpm).all():
        return [(model.top, np.arange(rpm.size))]
    tops = {r: model.top_at(r) for r in set(rpm.tolist())}
    groups: list[tuple[np.ndarray, list[int]]] = []
    for k, r in enumerate(rpm.tolist()):
        for top, rows in groups:
            if np.array_equal(top, tops[r]):
                rows.append(k)
                break
        else:
            groups.append((tops[r], [k]))
    return [(top, np.array(rows)) for top, rows in groups]


def _run_compiled(arguments: tuple[Any, ...], threads: int | None) -> None:
    """The compiled kernel over every point of ``arguments``, on several threads when there
    are several; the kernel releases the GIL, so the threads run side by side, and one
    compiled entry point serves one thread and many (no parallel kernel to compile).

    Points differ 100x in cost, so a free thread takes the next piece of the points left:
    a piece is an eighth of a thread's share of them (guided scheduling), down to one.
    A batch of fewer than :data:`~torsio.solvers.rodas_kernels.SMALL_BATCH` points runs
    through the single run's entry point (the same steps), which needs no compile of its
    own after a single run."""
    import threading
    from concurrent.futures import ThreadPoolExecutor

    from torsio.solvers import rodas_kernels  # each entry point is loaded on first use

    *shared, wob, omega, omega_set, out = arguments
    count = out.shape[0]  # out: a row per point
    workers = batch_threads(threads, count)
    run: Any = (
        rodas_kernels.run_points
        if count < rodas_kernels.SMALL_BATCH
        else rodas_kernels.integrate_serial
    )
    if workers == 1:
        run(*arguments)
        return
    taken = [0]
    taking = threading.Lock()

    def work() -> None:
        while True:
            with taking:
                start = taken[0]
                stop = min(count, start + max(1, (count - start) // (8 * workers)))
                taken[0] = stop
            if start >= count:
                return
            piece = slice(start, stop)
            run(*shared, wob[piece], omega[piece], omega_set[piece], out[piece])

    with ThreadPoolExecutor(max_workers=workers) as pool:
        for done in [pool.submit(work) for _ in range(workers)]:
            done.result()
