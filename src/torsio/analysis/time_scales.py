"""Time scales of the top drive and of a chain's nodes, checked before a run starts.

A top drive (node 0 of the chain) or a ``[chain]`` node whose parameters are far out of
scale makes equations that no integrator finishes in double precision: LSODA stops
with "Unexpected istate", or spends its whole budget resolving an oscillation ten
thousand times faster than the string's. :func:`check_time_scales` finds such a node
once, where the top drive and the chain meet (:class:`torsio.physics.dynamics.Dynamics`),
and raises a :class:`~torsio.errors.ConfigError` naming the key (``top_drive.ki``,
``chain.drag[2]``), its value and the range that works, before any integration.

Each node i is read as an oscillator with its neighbours held: inertia I, stiffness
K (its springs; for the top drive also ki and the Z-Torque torque feedback) and
damping C (its dampers, drag; for the top drive also kp). Three limits:

* relaxation: the run may last at most :data:`MAX_RELAXATION_RATIO` times I/C, and
  at most as many times a controller state's own time constant (the Z-Torque
  high-pass highpass_period/(2 pi), and zeta/(alpha ki)). Measured on the paper's
  1-DOF string with a PI top drive (J = 2900 kg m^2, default run 297.7 s): kp = 1e12
  (run/(J/kp) = 1.0e11) runs in 4 s; kp = 1e13 (1.0e12) fails at t = 65 s.
* oscillation: an underdamped node (C < 2 sqrt(K I)) must not oscillate faster than
  :data:`MAX_FREQUENCY_RATIO` times omega_1: the integrator resolves every cycle
  (about 33 right-hand-side evaluations each) and its budget allows 50 evaluations per
  output sample, 200 samples per first period. Measured as above: ki = 3e8
  (sqrt(ki/J) = 380 omega_1) runs in 28 s; ki = 1e9 (690 omega_1) exhausts the budget.
* spin-up (a torque-driven top drive): at full motor torque and with nothing resisting,
  the whole string must reach the balance speed within the run:
  (J + sum I) Omega_ref / torque <= run length.

Which key is named: of the node's inertia and the terms that make most of its K or
C, the one furthest (in decades) from the string's own scale: I_eq for inertias,
k_eq for stiffnesses, omega_1 I_eq for dampings (the groups of
:func:`torsio.physics.dimensionless.top_drive_groups`).

Examples
--------
>>> from torsio.examples import builtin_config
>>> from torsio.physics.top_drives import PITopDrive
>>> system = builtin_config().system(strategy="A")
>>> check_time_scales(system.with_top(PITopDrive(inertia=2900.0, kp=23250.0, ki=14500.0)), 300.0)
>>> check_time_scales(system.with_top(PITopDrive(inertia=2900.0, kp=23250.0, ki=1e12)), 300.0)
Traceback (most recent call last):
...
torsio.errors.ConfigError: top_drive.ki: 1e+12 N m/rad makes the top drive (node 0) oscillate ...
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np

from torsio.errors import ConfigError

__all__ = ["MAX_FREQUENCY_RATIO", "MAX_RELAXATION_RATIO", "check_time_scales"]

MAX_RELAXATION_RATIO = 3e11
"""Largest ratio of the run length to a node's relaxation time I/C (see the module doc)."""

MAX_FREQUENCY_RATIO = 400.0
"""Largest natural frequency of an underdamped node, in multiples of omega_1."""

_UNITS = {"inertia": "kg m^2", "stiffness": "N m/rad", "damping": "N m s/rad", "time": "s"}


@attrs.frozen
class _Term:
    """A parameter's part in a node's stiffness, damping or inertia."""

    key: str
    value: float  # the parameter's own value
    dimension: str  # inertia | stiffness | damping | time
    contribution: float  # what it adds to the node's K or C (its value for an inertia)


@attrs.frozen
class _Rate:
    """A controller rate or loop frequency [1/s], proportional to each term's value**power."""

    rate: float
    terms: tuple[tuple[_Term, float], ...]

    def refuse(self, limit: float, scales: dict[str, float], reason: str) -> None:
        """ConfigError on the term furthest from its scale, with its bound for ``limit``."""
        term = _blame([t for t, _ in self.terms], scales, every=True)
        power = dict((t.key, p) for t, p in self.terms)[term.key]
        bound = term.value * (limit / self.rate) ** (1.0 / power)
        side = "at most" if power > 0 else "at least"
        _refuse(term, f"{reason}; expected {side} {bound:.3g} {_UNITS[term.dimension]}")


def check_time_scales(system: Any, duration: float) -> None:
    """ConfigError if the top drive or a chain node is out of scale for a run of ``duration`` s.

    Checks the top drive's node (any top drive with inertia) and every node of a
    ``[chain]`` model (strategy ``chain``); a discretized string's nodes come from
    validated sections and are not checked here, nor is the wave model (no nodes; its
    top drive is stepped by the trapezoidal rule).
    """
    from torsio.physics.dimensionless import dimensionless_groups

    if not system.model.linearizable:  # no chain of nodes (the wave model): nothing to read
        return
    dynamics = system.dynamics()
    chain = system.model.strategy == "chain"
    if dynamics.top.held and not chain:
        return
    groups = dimensionless_groups(system)
    scales = {
        "inertia": groups.i_eq,
        "stiffness": groups.k_eq,
        "damping": groups.k_eq / groups.omega1,
        "time": 2.0 * math.pi / groups.omega1,
    }
    first = 1 if dynamics.has_top_node else 0
    if dynamics.has_top_node:
        _check_spin_up(system, dynamics, duration)
        _check_node(_top_terms(system, dynamics, chain), duration, groups.omega1, scales)
        _check_top_loop(system, dynamics, duration)
    if chain:
        for i in range(first, dynamics.dofs):
            terms = _chain_terms(dynamics, i, i - first)
            _check_node(terms, duration, groups.omega1, scales)


def _top_terms(system: Any, dynamics: Any, chain: bool) -> dict[str, list[Any]]:
    """The top drive's node: J; K = k_1 (1 + kp g) + ki; C = c_1 (1 + kp g) + kp + drag."""
    top = dynamics.top
    k1 = float(dynamics.stiffness_matrix[0, 0])
    c1 = float(dynamics.relative_damping_matrix[0, 0])
    spring = "chain.stiffnesses[0]" if chain else "the model's top spring k_1"
    damper = "chain.dampings[0]" if chain else "damping.beta"
    d_e, d_t = (float(x) for x in np.asarray(top.d, dtype=float))
    c = np.asarray(top.c, dtype=float)
    b = np.asarray(top.b, dtype=float)
    ki = float(c[0] * b[0, 0]) if top.states else 0.0
    params = _parameters(system)
    terms: dict[str, list[Any]] = {
        "inertia": [_Term("top_drive.inertia", float(top.inertia), "inertia", float(top.inertia))],
        "stiffness": [_Term(spring, k1, "stiffness", k1)],
        "damping": [
            _Term(damper, c1, "damping", c1),
            _Term("top_drive.drag", float(top.drag), "damping", float(top.drag)),
        ],
        "rates": [],
        "loops": [],
    }
    if d_e:
        terms["damping"].append(_Term("top_drive.kp", d_e, "damping", d_e))
    if ki:
        terms["stiffness"].append(_Term("top_drive.ki", ki, "stiffness", ki))
    if d_t:  # Z-Torque: the pipe torque fed back through kp alpha / zeta
        zeta = params.get("zeta", math.nan)
        terms["stiffness"].append(_Term("top_drive.zeta", zeta, "damping", -d_t * k1))
        terms["damping"].append(_Term("top_drive.zeta", zeta, "damping", -d_t * c1))
    for j in range(top.states):  # the controller's own rates
        own = abs(float(np.asarray(top.a, dtype=float)[j, j]))
        if own:
            period = params.get("highpass_period", 2.0 * math.pi / own)
            hp = _Term("top_drive.highpass_period", period, "time", own)
            terms["rates"].append(_Rate(own, ((hp, -1.0),)))
        through_torque = abs(float(c[j] * b[j, 1])) if j == 0 else 0.0
        if through_torque:  # z' = e - g T_pipe, u = ki z: a rate ki alpha / zeta
            impedance = _Term("top_drive.zeta", params.get("zeta", math.nan), "damping", 0.0)
            gain = _Term("top_drive.ki", float(c[j]), "stiffness", 0.0)
            terms["rates"].append(_Rate(through_torque, ((impedance, -1.0), (gain, 1.0))))
            # and a third-order loop, J phi_0 (3rd derivative) = -ki alpha/zeta k_1 phi_0
            loop = (through_torque * k1 / float(top.inertia)) ** (1.0 / 3.0)
            terms["loops"].append(_Rate(loop, ((impedance, -1.0 / 3.0), (gain, 1.0 / 3.0))))
    return terms


def _parameters(system: Any) -> dict[str, float]:
    """The top drive's resolved parameters that name a term (zeta, highpass_period)."""
    top = system.top
    values: dict[str, float] = {}
    if hasattr(top, "parameters") and hasattr(top, "highpass_period"):
        values["zeta"] = float(top.parameters(system)[2])
        values["highpass_period"] = float(top.highpass_period)
    return values


def _chain_terms(dynamics: Any, i: int, node: int) -> dict[str, list[Any]]:
    """Chain node ``node`` (dynamics node i): its inertia, its two springs and dampers, drag."""
    n = dynamics.dofs
    below_k = -float(dynamics.stiffness_matrix[i, i + 1]) if i + 1 < n else 0.0
    below_c = -float(dynamics.relative_damping_matrix[i, i + 1]) if i + 1 < n else 0.0
    above_k = float(dynamics.stiffness_matrix[i, i]) - below_k
    above_c = float(dynamics.relative_damping_matrix[i, i]) - below_c
    inertia = float(dynamics.mass_matrix[i, i])
    stiffness = [_Term(f"chain.stiffnesses[{node}]", above_k, "stiffness", above_k)]
    damping = [
        _Term(f"chain.dampings[{node}]", above_c, "damping", above_c),
        _Term(f"chain.drag[{node}]", float(dynamics.drag[i]), "damping", float(dynamics.drag[i])),
    ]
    if i + 1 < n:
        stiffness.append(_Term(f"chain.stiffnesses[{node + 1}]", below_k, "stiffness", below_k))
        damping.append(_Term(f"chain.dampings[{node + 1}]", below_c, "damping", below_c))
    return {
        "inertia": [_Term(f"chain.inertias[{node}]", inertia, "inertia", inertia)],
        "stiffness": stiffness,
        "damping": damping,
        "rates": [],
        "loops": [],
    }


def _check_node(
    terms: dict[str, list[Any]],
    duration: float,
    omega1: float,
    scales: dict[str, float],
) -> None:
    inertia = terms["inertia"][0].value
    stiffness = sum(t.contribution for t in terms["stiffness"])
    damping = sum(t.contribution for t in terms["damping"])
    key = terms["inertia"][0].key
    node = "the top drive (node 0)" if key.startswith("top") else f"chain node {key[15:-1]}"
    if damping > 0 and duration * damping / inertia > MAX_RELAXATION_RATIO:
        term = _blame(terms["inertia"] + terms["damping"], scales)
        most = inertia * MAX_RELAXATION_RATIO / duration  # I/C >= run / ratio
        bound = _bound(term, damping, most, damping * duration / MAX_RELAXATION_RATIO)
        _refuse(
            term,
            f"gives {node} a relaxation time I/C = {inertia:.3g} kg m^2 / {damping:.3g} N m s/rad"
            f" = {inertia / damping:.3g} s, {duration * damping / inertia:.3g} times shorter than "
            f"the run of {duration:.4g} s (runs of more than {MAX_RELAXATION_RATIO:.0e} relaxation "
            f"times fail in double precision); expected {bound}",
        )
    slowest = MAX_RELAXATION_RATIO / duration  # the largest rate [1/s] a run integrates
    for rate in terms["rates"]:
        if rate.rate > slowest:
            rate.refuse(
                slowest,
                scales,
                f"gives the top drive's controller a time constant of {1 / rate.rate:.3g} s, "
                f"{duration * rate.rate:.3g} times shorter than the run of {duration:.4g} s (at "
                f"most {MAX_RELAXATION_RATIO:.0e} can be integrated)",
            )
    for loop in terms["loops"]:
        if loop.rate > MAX_FREQUENCY_RATIO * omega1:
            loop.refuse(
                MAX_FREQUENCY_RATIO * omega1,
                scales,
                f"closes the torque feedback (ki alpha/zeta through the top spring) at "
                f"{loop.rate:.3g} rad/s, {loop.rate / omega1:.3g} times the string's first "
                f"natural frequency ({omega1:.3g} rad/s); the integrator resolves every cycle "
                f"and affords at most {MAX_FREQUENCY_RATIO:g} omega_1",
            )
    if stiffness <= 0 or damping >= 2.0 * math.sqrt(stiffness * inertia):
        return  # overdamped: its fast scale is the relaxation checked above
    frequency = math.sqrt(stiffness / inertia)
    if frequency <= MAX_FREQUENCY_RATIO * omega1:
        return
    term = _blame(terms["inertia"] + terms["stiffness"], scales)
    limit = (MAX_FREQUENCY_RATIO * omega1) ** 2
    bound = _bound(term, stiffness, limit * inertia, stiffness / limit)
    _refuse(
        term,
        f"makes {node} oscillate at sqrt(K/I) = sqrt({stiffness:.3g} N m/rad / {inertia:.3g} "
        f"kg m^2) = {frequency:.3g} rad/s, {frequency / omega1:.3g} times the string's first "
        f"natural frequency ({omega1:.3g} rad/s), lightly damped (C = {damping:.3g} N m s/rad); "
        f"the integrator resolves every cycle and affords at most {MAX_FREQUENCY_RATIO:g} "
        f"omega_1; expected {bound}",
    )


def _blame(candidates: list[_Term], scales: dict[str, float], every: bool = False) -> _Term:
    """The inertia or a dominant term (``every``: any term): the one furthest in decades
    from the string's scale."""
    others = [t for t in candidates if t.dimension != "inertia"]
    total = sum(abs(t.contribution) for t in others)
    dominant = [
        t
        for t in candidates
        if every
        or t.dimension == "inertia"
        or (t.contribution > 0 and t.contribution >= 0.1 * total)
    ]

    def decades(term: _Term) -> float:
        ratio = abs(term.value) / scales[term.dimension]
        return abs(math.log10(ratio)) if ratio > 0 and math.isfinite(ratio) else math.inf

    return max(dominant, key=decades)


def _bound(term: _Term, total: float, most: float, inertia_least: float) -> str:
    """The range that works for the blamed term, the node's other terms as given."""
    unit = _UNITS[term.dimension]
    if term.dimension == "inertia":
        return f"at least {inertia_least:.3g} {unit}"
    allowed = most - (total - term.contribution)
    if allowed <= 0:
        return "a smaller value (the node's other terms already reach the limit)"
    if term.contribution == term.value:
        return f"at most {allowed:.3g} {unit}"
    share = f"{allowed:.3g} (now {term.contribution:.3g})"
    return f"a value whose share of the node's sum is at most {share}"


def _refuse(term: _Term, reason: str) -> None:
    raise ConfigError(term.key, f"{term.value:.6g} {_UNITS[term.dimension]} {reason}")


def _check_spin_up(system: Any, dynamics: Any, duration: float) -> None:
    """A torque-driven top: the string must reach its balance speed within the run."""
    top = dynamics.top
    if math.isfinite(top.set_speed) or top.u0 <= 0:
        return
    string_inertia = float(np.trace(np.asarray(system.model.inertia, dtype=float)))
    total = float(top.inertia) + string_inertia
    speed = float(dynamics.reference_speed)
    spin_up = total * speed / float(top.u0)
    if math.isfinite(spin_up) and spin_up <= duration:
        return
    most = float(top.u0) * duration / speed - string_inertia if speed > 0 else math.inf
    blame_inertia = float(top.inertia) >= string_inertia
    key = "top_drive.inertia" if blame_inertia else "top_drive.torque"
    value = f"{float(top.inertia):.6g} kg m^2" if blame_inertia else f"{float(top.u0):.6g} N m"
    expected = (
        f"an inertia of at most {most:.3g} kg m^2"
        if blame_inertia and most > 0
        else f"a torque of at least {total * speed / duration:.3g} N m, or a longer run"
    )
    raise ConfigError(
        key,
        f"{value}: at full motor torque ({float(top.u0):.6g} N m) and with nothing resisting, "
        f"the top drive and the string ({total:.3g} kg m^2) need {spin_up:.3g} s to reach "
        f"the balance speed {speed:.4g} rad/s, longer than the run of {duration:.4g} s, so "
        f"the top never reaches a steady speed; expected {expected}",
    )


MAX_LOOP_STATES = 1000
"""Largest state size whose eigenvalues the loop check computes (dense, O(size^3))."""


def _loop_growth(dynamics: Any) -> float:
    """Largest growth rate [1/s] of the string with its top drive, the bit law's slope 0.

    The linearization about steady rotation (:meth:`Dynamics.linearized`) with the bit
    neither feeding nor damping the motion: what grows then is the controller's own doing,
    not stick-slip.
    """
    with np.errstate(all="ignore"):
        matrix = np.asarray(dynamics.linearized(bit_slope=0.0), dtype=float)
        if not np.all(np.isfinite(matrix)):
            return math.inf
        return float(np.linalg.eigvals(matrix).real.max())


def _check_top_loop(system: Any, dynamics: Any, duration: float) -> None:
    """ConfigError if a controller that feeds the pipe torque back destabilises the string.

    Z-Torque (alpha/zeta) can make the string grow by itself, the bit aside: with
    J = 2900 kg m^2 on the paper's 1-DOF string it grows for zeta <= 50 N m s/rad (a run
    at 50 gave S_SS = 2336 and a top drive at -571 rad/s), and is stable at 80 (S_SS
    2e-14). Refused when the linearization with the bit law's slope 0 grows by more than
    a factor e over the run (skipped above :data:`MAX_LOOP_STATES` states).
    """
    top = dynamics.top
    feeds_back = np.any(np.asarray(top.d, dtype=float)[1:]) or np.any(
        np.asarray(top.b, dtype=float)[:, 1]
    )
    if not feeds_back or dynamics.size > MAX_LOOP_STATES:
        return
    growth = _loop_growth(dynamics)
    if growth * duration <= 1.0:
        return
    drive = system.top
    if not hasattr(drive, "zeta") or not hasattr(drive, "parameters"):
        raise ConfigError(
            "top_drive",
            f"the controller of {getattr(drive, 'name', drive)!r} makes the string unstable (with "
            f"the bit aside, it grows at {growth:.3g}/s, by e^{growth * duration:.3g} "
            f"over the run of {duration:.4g} s); expected a stable tuning",
        )
    zeta = float(drive.parameters(system)[2])

    def grows(value: float) -> bool:
        trial = system.with_top(attrs.evolve(drive, zeta=value)).dynamics()
        return _loop_growth(trial) * duration > 1.0

    low, high = math.log10(zeta), math.log10(zeta) + 12.0
    bound = ""
    if not grows(10.0**high):
        for _ in range(50):
            middle = 0.5 * (low + high)
            low, high = (middle, high) if grows(10.0**middle) else (low, middle)
        bound = f"; expected at least {10.0**high:.3g} N m s/rad with the other values as given"
    raise ConfigError(
        "top_drive.zeta",
        f"{zeta:.6g} N m s/rad makes the Z-Torque loop (the pipe torque fed back through "
        f"alpha/zeta = {drive.alpha / zeta:.3g} rad/s per N m) unstable: with the bit aside, "
        f"the string and top drive grow at {growth:.3g}/s, by e^{growth * duration:.3g}"
        f" over the run of {duration:.4g} s, and the run means nothing{bound}",
    )
