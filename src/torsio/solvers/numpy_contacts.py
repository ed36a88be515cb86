"""Coulomb contacts along the string in the numpy batch engine, vectorized over points.

The law is :mod:`torsio.solvers.contact_law`'s event form (Aarsnes & Shor 2018): each point
carries its contacts' state codes, an array of shape (points, nodes) (0 stuck, +-1 slow,
+-2 fast; 0 too where a node has no contact); within a step they are fixed, so the
equations are smooth: a moving contact adds the constant torque -C sign w to its node, a
stuck node's speed equation is v' = 0 (:func:`hold_rows`: its row of the step matrix the
identity's, its right-hand side 0; its twist still turns at v = -Omega_ref).

After a step that passes error control, the switches' margins
(:func:`torsio.solvers.contact_law.margins`) are evaluated at its end. A margin beyond its
tolerance below 0 rejects the step: it is retried shortened to the crossing, interpolated
linearly from the margins at the step's start and end, or through the ends of two
retries (secant), aiming at half the tolerance below 0; a shorter step that falls short
is accepted and the next one aims from it. A step that ends with a margin within its
tolerance below 0 switches that contact (:func:`torsio.solvers.contact_law.switched`; a
node that sticks gets its speed set to exactly 0).

A point whose contacts do not settle at an instant, or switch more than
:data:`MAX_SWITCHES_PER_PERIOD` times per contact and first natural period (plus
:data:`MAX_SWITCHES_PER_PERIOD` per contact), ends with status
:data:`torsio.solvers.batch_results.STATUS_CHATTER`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsio.solvers import contact_law as law
from torsio.solvers import layouts as slot
from torsio.solvers.batch_results import STATUS_CHATTER

__all__ = ["CLOSEST_SWITCH", "MAX_SWITCHES_PER_PERIOD", "ContactLaw", "hold_rows"]

MAX_SWITCHES_PER_PERIOD = 50
"""Switches allowed per contact and first natural period before a point is reported as
chattering."""
CLOSEST_SWITCH = 100.0
"""The shortest step aimed at a crossing, in the engine's smallest steps (1e-12 of the
run): the compiled kernel's ``h_min`` too."""
ALL = slice(None)
KEYS = ("contact", "margin", "switches", "event_t", "event_g", "event_k")
"""The per-point arrays the contacts add to the engine's state (compacted with it)."""


def hold_rows(stuck, md, g, piv, upper, lower) -> None:
    """A stuck node's row of the step matrix becomes the identity's (times [I]_ii/(gamma h)):
    its diagonal set, its two couplings zeroed (``upper[:, i]`` couples i to i + 1,
    ``lower[:, i - 1]`` i to i - 1); the right-hand side's row is set to 0 by the caller."""
    if not stuck.any():
        return
    piv[stuck] = np.broadcast_to(md / g[:, None], piv.shape)[stuck]
    upper[stuck] = 0.0
    lower[:, :-1][stuck[:, 1:]] = 0.0


class ContactLaw:
    """The contacts of a packed chain (``CHAIN_CONTACT_*`` rows) and their switches."""

    def __init__(self, chain: np.ndarray, settings: np.ndarray) -> None:
        self.static = chain[slot.CHAIN_CONTACT_STATIC]
        self.dynamic = chain[slot.CHAIN_CONTACT_DYNAMIC]
        self.threshold = chain[slot.CHAIN_CONTACT_THRESHOLD]
        self.nodes = self.static > 0.0
        self.count = int(self.nodes.sum())
        # the shortest step aimed at a crossing [s], as the compiled kernel's
        self.h_min = CLOSEST_SWITCH * 1e-12 * max(1.0, float(settings[slot.RUN_T_END]))
        periods = settings[slot.RUN_T_END] * settings[slot.RUN_OMEGA_1] / (2.0 * math.pi)
        self.limit = MAX_SWITCHES_PER_PERIOD * self.count * (1.0 + periods)

    @classmethod
    def of(cls, chain: np.ndarray, settings: np.ndarray) -> ContactLaw | None:
        """The contacts of ``chain``, or None when it has none."""
        if not np.any(chain[slot.CHAIN_CONTACT_STATIC] > 0.0):
            return None
        return cls(chain, settings)

    # --- the equations in the present states -----------------------------------------------
    def friction(self, s: dict[str, np.ndarray], rows: Any = ALL) -> np.ndarray:
        """Friction torque on each node [N m] (points, nodes): 0 where stuck or no contact."""
        code = np.ascontiguousarray(s["contact"][rows])
        out = np.empty(code.shape)
        law.frictions(code, self.static, self.dynamic, out)
        return out

    def stuck(self, s: dict[str, np.ndarray], rows: Any = ALL) -> np.ndarray:
        """Which nodes are held (points, nodes)."""
        return (s["contact"][rows] == 0.0) & self.nodes

    # --- the switches ------------------------------------------------------------------
    def margins(self, code, om, v, free) -> np.ndarray:
        """(points, 2, nodes): :func:`law.margins` (inf where a node has no contact)."""
        out = np.empty((code.shape[0], 2, code.shape[1]))
        law.margins(np.ascontiguousarray(code), self.static, self.threshold,
                    om[:, None] + v, np.ascontiguousarray(free), out)  # fmt: skip
        return out

    def tolerances(self, code, om) -> np.ndarray:
        """(points, 2, nodes): how near 0 a margin counts as 0 (:func:`law.tolerances`)."""
        out = np.empty((code.shape[0], 2, code.shape[1]))
        law.tolerances(np.ascontiguousarray(code), self.static, self.threshold,
                       np.ascontiguousarray(om), out)  # fmt: skip
        return out

    def start(self, s: dict[str, np.ndarray], forces) -> tuple[np.ndarray, np.ndarray]:
        """The states of the initial state: at rest stuck, else on the branch of the speed;
        then the switches due at once (:meth:`settle`, whose forces it returns)."""
        count, n = s["v"].shape
        s["contact"] = np.empty((count, n))
        law.start_codes(s["om"][:, None] + s["v"], self.static, self.threshold, s["contact"])
        s["switches"] = np.zeros(count, dtype=np.int64)
        s["event_t"] = np.full(count, np.nan)
        s["event_g"] = np.zeros(count)
        s["event_k"] = np.zeros(count, dtype=np.int64)
        s["margin"] = np.zeros((count, 2, n))
        return self.settle(s, np.arange(count), forces)

    def apply(self, s, rows: np.ndarray, fire: np.ndarray, free: np.ndarray) -> None:
        """Switch the contacts of points ``rows`` whose margins ``fire`` (rows, 2, nodes), with
        holding torques ``free`` (rows, nodes); a node that sticks is set to rest exactly."""
        code = np.ascontiguousarray(s["contact"][rows])
        kinds = np.where(fire[:, 0], 1, np.where(fire[:, 1], 2, 0)).astype(np.int64)
        moving = code != 0.0
        law.switch_codes(code, kinds, np.ascontiguousarray(free), self.static, self.threshold)
        s["switches"][rows] += (kinds > 0).sum(axis=1)
        holds = moving & (code == 0.0)
        s["contact"][rows] = code
        if holds.any():
            v = s["v"][rows]
            v[holds] = np.broadcast_to(-s["om"][rows][:, None], v.shape)[holds]
            s["v"][rows] = v

    def settle(self, s, rows: np.ndarray, forces) -> tuple[np.ndarray, np.ndarray]:
        """Switch the contacts of points ``rows`` whose margins are beyond their tolerance
        below 0 until none is (status STATUS_CHATTER if they do not settle, or have
        switched too often), keep the margins for the next step and set its start's forces
        and accelerations. ``forces(rows)``: the nodes' forces without friction and z'."""
        free, fz = forces(rows)
        for _ in range(4 * self.count + 4):
            state, om = s["contact"][rows], s["om"][rows]
            margin = self.margins(state, om, s["v"][rows], free)
            fire = margin < -self.tolerances(state, om)
            if not fire.any():
                break
            self.apply(s, rows, fire, free)
            free, fz = forces(rows)
        else:
            s["status"][rows[fire.any(axis=(1, 2))]] = STATUS_CHATTER
        s["margin"][rows] = margin
        s["status"][rows[(s["switches"][rows] > self.limit) & (s["status"][rows] == 0)]] = (
            STATUS_CHATTER
        )
        return free, fz

    def events(self, s, rows, v, free) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """At the end of a step of points ``rows`` (speeds ``v``, forces without friction
        ``free``): the margins, which are beyond their tolerance below 0 (the step crossed
        a switch) and which are within it (the step ends on a switch), (rows, 2, nodes)."""
        state, om = s["contact"][rows], s["om"][rows]
        margin = self.margins(state, om, v, free)
        tolerance = self.tolerances(state, om)
        beyond = margin < -tolerance
        return margin, beyond, (margin <= 0.0) & ~beyond

    def shortened(self, s, rows, h, margin, beyond) -> np.ndarray:
        """The step to retry for points ``rows`` whose step ``h`` crossed a switch: to the
        earliest crossing, aiming at half the tolerance below 0, interpolated linearly from
        the margins at the step's start and end, or through the ends of this and the last
        retry of the same crossing (secant) where that falls inside the step; the end is
        kept for :meth:`aim`."""
        if not rows.size:
            return h
        target = -0.5 * self.tolerances(s["contact"][rows], s["om"][rows])
        g0 = (s["margin"][rows] - target).reshape(rows.size, -1)
        g1 = (margin - target).reshape(rows.size, -1)
        with np.errstate(invalid="ignore", divide="ignore"):
            theta = np.where(beyond.reshape(rows.size, -1), g0 / (g0 - g1), np.inf)
        k = np.argmin(theta, axis=1)
        pick = np.arange(rows.size)
        t0, end, g_end = s["t"][rows], s["t"][rows] + h, g1[pick, k]
        last_t, last_g = s["event_t"][rows], s["event_g"][rows]
        with np.errstate(invalid="ignore", divide="ignore"):
            secant = end - g_end * (end - last_t) / (g_end - last_g)
        inside = (s["event_k"][rows] == k) & (secant > t0) & (secant < end)
        s["event_t"][rows], s["event_g"][rows], s["event_k"][rows] = end, g_end, k
        linear = np.clip(theta[pick, k], 1e-6, 1.0) * h
        return np.where(inside, secant - t0, linear)

    def aim(self, s, rows, h: np.ndarray) -> np.ndarray:
        """The next step of points ``rows`` that fell short of a located crossing: at most
        to the crossing interpolated linearly from the new start and the retry's end;
        ``h`` elsewhere."""
        active = ~np.isnan(s["event_t"][rows])
        if not active.any() or not rows.size:
            return h
        r = rows[active]
        pick, k = np.arange(r.size), s["event_k"][r]
        target = -0.5 * self.tolerances(s["contact"][r], s["om"][r]).reshape(r.size, -1)
        g0 = (s["margin"][r].reshape(r.size, -1) - target)[pick, k]
        g1, remaining = s["event_g"][r], s["event_t"][r] - s["t"][r]
        ok = (g0 > 0.0) & (g1 < 0.0) & (remaining > 0.0) & np.isfinite(g0)
        with np.errstate(invalid="ignore", divide="ignore"):
            estimate = np.where(ok, g0 / (g0 - g1) * remaining, np.inf)
        # an estimate below h_min is the chord of a margin that curves (it would shrink
        # step after step): step on and locate the crossing afresh from here
        ok &= estimate >= self.h_min
        estimate[~ok] = np.inf
        s["event_t"][r[~ok]] = np.nan
        h = h.copy()
        h[active] = np.minimum(h[active], estimate)
        return h

    # --- a step's end ------------------------------------------------------------------
    def check(self, sys_, s, h, accept, yphi, yv, yz):
        """The points of ``accept`` (passed error control) whose step crossed a switch: they
        are retried with the returned steps; for the others, the step's end (forces
        without friction, z', margins, the switches it ends on), in order."""
        rows = np.flatnonzero(accept)
        free, fz = sys_.forces(s["om"][rows], s["om_set"][rows], s["wob"][rows], yphi[rows],
                               yv[rows], yz[rows])  # fmt: skip
        margin, beyond, fire = self.events(s, rows, yv[rows], free)
        crossed = beyond.any(axis=(1, 2))
        retry = rows[crossed]
        shorter = self.shortened(s, retry, h[retry], margin[crossed], beyond[crossed])
        keep = ~crossed
        return retry, shorter, (free[keep], fz[keep], margin[keep], fire[keep])

    def switch(self, sys_, s, rows, end, h: np.ndarray, forces) -> None:
        """After the accepted steps of points ``rows`` (``end`` from :meth:`check`): switch
        the contacts the steps end on, and set the next steps' start (forces, accelerations,
        margins) where they did; ``h`` (the next steps, of these rows) aimed elsewhere."""
        free, _, margin, fire = end
        switching = fire.any(axis=(1, 2))
        quiet = rows[~switching]
        s["margin"][quiet] = margin[~switching]
        h[~switching] = self.aim(s, quiet, h[~switching])
        moved = rows[switching]
        if not moved.size:
            return
        self.apply(s, moved, fire[switching], free[switching])
        free, fz = self.settle(s, moved, forces)
        s["event_t"][moved] = np.nan
        fv = free - self.friction(s, moved)
        acc = sys_.accelerations(fv)
        acc[self.stuck(s, moved)] = 0.0
        s["f0v"][moved], s["f0z"][moved], s["acc"][moved] = fv, fz, acc
