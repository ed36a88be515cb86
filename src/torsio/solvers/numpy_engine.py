"""The numpy batch engine: the compiled kernel's method, vectorized across the batch.

The same chain, top drive and RODAS4 steps as :mod:`torsio.solvers.rodas` (read its module
documentation for the equations and the elimination), each point with its own step and
error control, written with numpy arrays of shape (points, nodes). It runs any bit-rock
law through the law's vectorized ``torque`` and ``slope`` (or a central difference), and
it is the engine when numba is not installed.

A chain whose nodes carry Coulomb contacts with the borehole (``CHAIN_CONTACT_*``) runs
them as :mod:`torsio.solvers.numpy_contacts` describes: each point's contact states fixed
within a step (a moving contact a constant torque, a stuck node's row of the step matrix
the identity's), a step that crosses a switch retried shortened to it, the switches made
at the step's end. Without contacts the steps are those of the chain alone.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from torsio.physics.law_slope import bit_slope
from torsio.physics.top_drive_boundary import controller_rates, motor_torque
from torsio.solvers import layouts as slot
from torsio.solvers.numpy_contacts import ContactLaw, hold_rows
from torsio.solvers.rodas import GAMMA, RODAS_A, RODAS_C

__all__ = ["extremes_numpy", "integrate_numpy"]


def _tri_mul(diag: np.ndarray, upper: np.ndarray, x: np.ndarray) -> np.ndarray:
    y = x * diag
    if diag.size > 1:
        y[:, :-1] += upper[:-1] * x[:, 1:]
        y[:, 1:] += upper[:-1] * x[:, :-1]
    return y


class _Chain:
    """The chain and top drive of :mod:`torsio.solvers.rodas`, vectorized over points."""

    def __init__(self, chain: np.ndarray, top: np.ndarray, law: Any, radius: float) -> None:
        self.md, self.mu = chain[slot.CHAIN_MASS], chain[slot.CHAIN_MASS_UPPER]
        self.kd, self.ku = chain[slot.CHAIN_STIFFNESS], chain[slot.CHAIN_STIFFNESS_UPPER]
        self.cd, self.cu = chain[slot.CHAIN_DAMPING], chain[slot.CHAIN_DAMPING_UPPER]
        self.drag, self.applied = chain[slot.CHAIN_DRAG], chain[slot.CHAIN_APPLIED]
        self.n = chain.shape[1]
        self.has_top = bool(top[slot.TOP_HAS_NODE])
        self.m = m = int(top[slot.TOP_STATES])
        self.u0, self.max_torque = top[slot.TOP_U0], top[slot.TOP_MAX_TORQUE]
        self.k1, self.c1 = top[slot.TOP_K_PIPE], top[slot.TOP_C_PIPE]
        self.kp, self.pipe_gain = top[slot.TOP_KP], top[slot.TOP_PIPE_GAIN]
        self.d = np.array([self.kp, self.pipe_gain])  # the gains on y = [e, T_pipe]
        states = slot.MAX_STATES
        self.a = top[slot.TOP_A : slot.TOP_B].reshape(states, states)[:m, :m]
        self.b = top[slot.TOP_B : slot.TOP_C].reshape(states, 2)[:m]
        self.c = top[slot.TOP_C : slot.TOP_C + m]
        self.w = top[slot.TOP_W : slot.TOP_W + m]
        self.top = top
        self.law = law
        self.radius = radius
        self.contacts: ContactLaw | None = None  # the contacts along the string, if any
        self.mpiv = np.empty(self.n)  # factors of [I], for the accelerations
        self.mlow = np.zeros(self.n)
        self.mpiv[0] = self.md[0]
        for i in range(1, self.n):
            self.mlow[i] = self.mu[i - 1] / self.mpiv[i - 1]
            self.mpiv[i] = self.md[i] - self.mlow[i] * self.mu[i - 1]

    def controller(self, om: np.ndarray, om_set: np.ndarray, phi: np.ndarray, v: np.ndarray, z):
        """Speed error, pipe torque, u and u_free per point (z: (points, m))."""
        error = np.where(np.isnan(om_set), 0.0, om_set - (om + v[:, 0]))
        pipe = self.k1 * (phi[:, 0] - phi[:, 1]) + self.c1 * (v[:, 0] - v[:, 1])
        u, free = motor_torque(
            self.u0, self.kp, self.pipe_gain, self.max_torque, self.m, self.c, z.T, error, pipe
        )
        return error, pipe, u, free

    def forces(self, om, om_set, wob, phi, v, z) -> tuple[np.ndarray, np.ndarray]:
        """Chain forces (motor and bit included) and z' per point."""
        fv = self.applied - self.drag * om[:, None]
        fv -= _tri_mul(self.kd, self.ku, phi) + _tri_mul(self.cd, self.cu, v)
        fv[:, -1] -= np.asarray(self.law.torque(om + v[:, -1], wob, self.radius), dtype=float)
        fz = np.zeros_like(z)
        if self.has_top:
            error, pipe, u, free = self.controller(om, om_set, phi, v, z)
            fv[:, 0] += u
            rates = fz.T  # (m, points), a view: written in place
            a, b = self.top[slot.TOP_A : slot.TOP_B], self.top[slot.TOP_B : slot.TOP_C]
            controller_rates(self.m, slot.MAX_STATES, a, b, self.w, z.T, error, pipe, u, free,
                             rates)  # fmt: skip
        return fv, fz

    def accelerations(self, fv: np.ndarray) -> np.ndarray:
        """[I]^-1 fv per point."""
        acc = fv.copy()
        for i in range(1, self.n):
            acc[:, i] -= self.mlow[i] * acc[:, i - 1]
        acc[:, -1] /= self.mpiv[-1]
        for i in range(self.n - 2, -1, -1):
            acc[:, i] = (acc[:, i] - self.mu[i] * acc[:, i + 1]) / self.mpiv[i]
        return acc

    def elimination(self, g, om, om_set, phi, v, z):
        """(Q, Z_y, G, r) of the controller elimination per point (rodas module doc)."""
        count, m = g.size, self.m
        _, _, u, free = self.controller(om, om_set, phi, v, z)
        saturated = (u != free)[:, None]
        uy = np.where(saturated, 0.0, self.d)
        zz = (
            self.a - saturated[:, :, None] * np.outer(self.w, self.c)
            if m
            else np.zeros((count, 0, 0))
        )
        zy = self.b - saturated[:, :, None] * np.outer(self.w, self.d)
        q = np.linalg.inv(np.eye(m) / g[:, None, None] - zz) if m else np.zeros((count, 0, 0))
        r = np.einsum("pj,pjk->pk", np.where(saturated, 0.0, self.c), q)
        gains = uy + np.einsum("pk,pkl->pl", r, zy)
        return q, zy, gains, r


def integrate_numpy(
    chain: np.ndarray,
    top: np.ndarray,
    law: Any,
    settings: np.ndarray,
    wob: np.ndarray,
    omega: np.ndarray,
    omega_set: np.ndarray,
) -> np.ndarray:
    """Every point at once, each to the end; returns ``out`` (:mod:`torsio.solvers.layouts`)."""
    t_end, t_window = settings[slot.RUN_T_END], settings[slot.RUN_WINDOW_START]
    rtol, atol = settings[slot.RUN_RTOL], settings[slot.RUN_ATOL]
    h0, hmax = settings[slot.RUN_FIRST_STEP], settings[slot.RUN_MAX_STEP]
    max_steps = settings[slot.RUN_MAX_STEPS]
    sys_ = _Chain(chain, top, law, float(settings[slot.RUN_BIT_RADIUS]))
    sys_.contacts = contacts = ContactLaw.of(chain, settings)
    n, m = sys_.n, sys_.m
    count = wob.size
    out = np.zeros((count, slot.OUT_COLUMNS))
    out[:, slot.OUT_ENDED] = t_end
    state: dict[str, np.ndarray] = {
        "idx": np.arange(count),
        "wob": wob.copy(),
        "om": omega.copy(),
        "om_set": omega_set.copy(),
        "phi": np.zeros((count, n)),
        "v": np.repeat(-omega[:, None], n, axis=1),
        "z": np.zeros((count, m)),
        "t": np.zeros(count),
        "h": np.full(count, min(h0, hmax, t_end)),
        "vmax": np.full(count, -np.inf),
        "vmin": np.full(count, np.inf),
        "top_integral": np.zeros(count),
        "steps": np.zeros(count, dtype=np.int64),
        "rejected": np.zeros(count, dtype=np.int64),
        "status": np.zeros(count, dtype=np.int64),
        "last_rejected": np.zeros(count, dtype=bool),
        "err_accepted": np.ones(count),
    }
    state["h_accepted"] = state["h"].copy()
    s = state
    s["f0v"], s["f0z"] = sys_.forces(s["om"], s["om_set"], s["wob"], s["phi"], s["v"], s["z"])
    if contacts is not None:
        free, s["f0z"] = contacts.start(s, _forces_of(sys_, s))
        s["f0v"] = free - contacts.friction(s)
    s["acc"] = sys_.accelerations(s["f0v"])
    if contacts is not None:
        s["acc"][contacts.stuck(s)] = 0.0
    tiny = 1e-12 * max(1.0, t_end)
    window = t_end - t_window

    def retire(keep: np.ndarray) -> None:
        done = ~keep
        rows = s["idx"][done]
        out[rows, slot.OUT_BIT_SPEED_MAX] = s["vmax"][done] + s["om"][done]
        out[rows, slot.OUT_BIT_SPEED_MIN] = s["vmin"][done] + s["om"][done]
        out[rows, slot.OUT_STEPS] = s["steps"][done]
        out[rows, slot.OUT_REJECTED] = s["rejected"][done]
        out[rows, slot.OUT_STATUS] = s["status"][done]
        mean = s["top_integral"][done] / window if sys_.has_top else 0.0
        out[rows, slot.OUT_TOP_SPEED_MEAN] = s["om"][done] + mean

    while s["idx"].size:
        s["status"][(s["steps"] >= max_steps) & (s["status"] == 0)] = 1
        s["status"][(s["h"] < tiny) & (s["status"] == 0)] = 2
        keep = (s["t"] < t_end) & (s["status"] == 0)
        if not keep.all():
            retire(keep)
            for key in s:
                s[key] = s[key][keep]
            if not s["idx"].size:
                break
        _step(sys_, s, t_end, t_window, rtol, atol, hmax, tiny)
    return out


def _forces_of(sys_: _Chain, s: dict[str, np.ndarray]) -> Any:
    """The chain forces (friction left out) and z' of some points, by their rows in ``s``."""

    def forces(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return sys_.forces(s["om"][rows], s["om_set"][rows], s["wob"][rows], s["phi"][rows],
                           s["v"][rows], s["z"][rows])  # fmt: skip

    return forces


def _step(sys_: _Chain, s: dict[str, np.ndarray], t_end, t_window, rtol, atol, hmax, tiny) -> None:
    """One RODAS4 step (accepted or rejected) of every point still running."""
    n, m = sys_.n, sys_.m
    md, mu, kd, ku, cd, cu = sys_.md, sys_.mu, sys_.kd, sys_.ku, sys_.cd, sys_.cu
    om, om_set, wob = s["om"], s["om_set"], s["wob"]
    phi, v, z = s["phi"], s["v"], s["z"]
    h = np.minimum(s["h"], t_end - s["t"])
    g = GAMMA * h
    slope = bit_slope(sys_.law, om + v[:, -1], wob, sys_.radius)
    count = h.size
    diag0 = np.zeros(count)
    extra01 = np.zeros(count)
    if sys_.has_top:
        q, zy, gains, r = sys_.elimination(g, om, om_set, phi, v, z)
        extra01 = gains[:, 1] * (g * sys_.k1 + sys_.c1)
        diag0 = gains[:, 0] - extra01
    upper = mu / g[:, None] + cu + g[:, None] * ku
    lower = upper.copy()
    upper[:, 0] += extra01
    piv = md / g[:, None] + cd + g[:, None] * kd
    scale = md / g[:, None] + np.abs(cd) + g[:, None] * kd
    piv[:, -1] += slope
    piv[:, 0] += diag0
    contacts = sys_.contacts
    if contacts is not None:  # moving: a constant torque; stuck: v' = 0
        friction, stuck = contacts.friction(s), contacts.stuck(s)
        hold_rows(stuck, md, g, piv, upper, lower)
    low = np.zeros_like(piv)
    for i in range(1, n):
        low[:, i] = lower[:, i - 1] / piv[:, i - 1]
        piv[:, i] -= low[:, i] * upper[:, i - 1]
    singular = ~(np.abs(piv) > 1e-13 * scale).all(axis=1)
    piv[singular] = 1.0
    kphi = np.zeros((6, count, n))
    kv = np.zeros((6, count, n))
    kz = np.zeros((6, count, m))
    aphi, av, az = phi, v, z
    for stage in range(6):
        aphi, av, az = phi.copy(), v.copy(), z.copy()
        uphi, uv, uz = np.zeros_like(phi), np.zeros_like(v), np.zeros_like(z)
        for j in range(stage):
            aphi += RODAS_A[stage, j] * kphi[j]
            av += RODAS_A[stage, j] * kv[j]
            az += RODAS_A[stage, j] * kz[j]
            uphi += RODAS_C[stage, j] * kphi[j]
            uv += RODAS_C[stage, j] * kv[j]
            uz += RODAS_C[stage, j] * kz[j]
        if stage == 0:
            fphi, fv, fz = v, s["f0v"], s["f0z"]
        else:
            fv, fz = sys_.forces(om, om_set, wob, aphi, av, az)
            if contacts is not None:
                fv = fv - friction
            fphi = av + uphi / h[:, None]
            fv = fv + _tri_mul(md, mu, uv / h[:, None])
            fz = fz + uz / h[:, None]
        x = fv - g[:, None] * _tri_mul(kd, ku, fphi)
        if sys_.has_top:
            x[:, 0] += gains[:, 1] * sys_.k1 * g * (fphi[:, 0] - fphi[:, 1])
            x[:, 0] += np.einsum("pk,pk->p", r, fz)
        if contacts is not None:
            x[stuck] = 0.0
        for i in range(1, n):
            x[:, i] -= low[:, i] * x[:, i - 1]
        x[:, -1] /= piv[:, -1]
        for i in range(n - 2, -1, -1):
            x[:, i] = (x[:, i] - upper[:, i] * x[:, i + 1]) / piv[:, i]
        kv[stage] = x
        kphi[stage] = g[:, None] * (fphi + x)
        if m:
            dy_e = -x[:, 0]
            dy_t = sys_.k1 * (kphi[stage][:, 0] - kphi[stage][:, 1]) + sys_.c1 * (x[:, 0] - x[:, 1])
            rhs = fz + zy[:, :, 0] * dy_e[:, None] + zy[:, :, 1] * dy_t[:, None]
            kz[stage] = np.einsum("pjk,pk->pj", q, rhs)
    _accept_or_reject(
        sys_, s, h, aphi, av, az, kphi[5], kv[5], kz[5], singular, t_window, rtol, atol, hmax, tiny
    )


def _accept_or_reject(
    sys_, s, h, aphi, av, az, ephi, ev, ez, singular, t_window, rtol, atol, hmax, tiny
) -> None:
    """Error control, step-size choice and the update of the accepted points."""
    n, m = sys_.n, sys_.m
    phi, v, z = s["phi"], s["v"], s["z"]
    yphi, yv, yz = aphi + ephi, av + ev, az + ez
    with np.errstate(invalid="ignore", over="ignore"):
        total = ((ephi / (atol + rtol * np.maximum(np.abs(phi), np.abs(yphi)))) ** 2).sum(axis=1)
        total += ((ev / (atol + rtol * np.maximum(np.abs(v), np.abs(yv)))) ** 2).sum(axis=1)
        total += ((ez / (atol + rtol * np.maximum(np.abs(z), np.abs(yz)))) ** 2).sum(axis=1)
        err = np.sqrt(total / (2 * n + m))
    finite = np.isfinite(err) & np.isfinite(yphi).all(axis=1) & np.isfinite(yv).all(axis=1)
    err = np.where(singular | ~finite, np.inf, err)
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        factor = np.clip(np.sqrt(np.sqrt(err)) / 0.9, 1.0 / 6.0, 5.0)
        predicted = np.clip(
            s["h_accepted"] / h * np.sqrt(np.sqrt(err * err / s["err_accepted"])) / 0.9,
            1.0 / 6.0,
            5.0,
        )
    accept = err <= 1.0
    contacts = sys_.contacts
    if contacts is not None:  # a step that crosses a switch is retried, shortened to it
        retry, shorter, end = contacts.check(sys_, s, h, accept, yphi, yv, yz)
        accept[retry] = False
    factor = np.where(accept & (s["steps"] > 0), np.maximum(factor, predicted), factor)
    h_new = np.where(singular, 0.5 * h, np.where(~finite, 0.25 * h, h / factor))
    s["h_accepted"] = np.where(accept, h, s["h_accepted"])
    s["err_accepted"] = np.where(accept, np.maximum(1e-2, err), s["err_accepted"])
    s["status"][~finite & ~singular & (h_new < tiny)] = 3
    if accept.any():
        a_ = accept
        bit0, top0 = v[a_, -1], v[a_, 0]
        phi[a_], v[a_], z[a_] = yphi[a_], yv[a_], yz[a_]
        if contacts is None:
            fv, fz = sys_.forces(s["om"][a_], s["om_set"][a_], s["wob"][a_], phi[a_], v[a_], z[a_])
        else:
            fv, fz = end[0] - contacts.friction(s, a_), end[1]
        s["f0v"][a_], s["f0z"][a_] = fv, fz
        acc1 = sys_.accelerations(fv)
        if contacts is not None:
            acc1[contacts.stuck(s, a_)] = 0.0
        acc0 = s["acc"][a_]
        t_old = s["t"][a_]
        hh = h[a_]
        s["t"][a_] = t_old + hh
        inside = s["t"][a_] > t_window
        if inside.any():
            lo = np.where(t_old < t_window, (t_window - t_old) / hh, 0.0)
            mx, mn = extremes_numpy(bit0, v[a_, -1], hh * acc0[:, -1], hh * acc1[:, -1], lo)
            sel = np.flatnonzero(a_)[inside]
            s["vmax"][sel] = np.maximum(s["vmax"][sel], mx[inside])
            s["vmin"][sel] = np.minimum(s["vmin"][sel], mn[inside])
            if sys_.has_top:
                part = hh * _integral_numpy(top0, v[a_, 0], hh * acc0[:, 0], hh * acc1[:, 0], lo)
                s["top_integral"][sel] += part[inside]
        s["acc"][a_] = acc1
        s["steps"][a_] += 1
        h_new[a_] = np.where(s["last_rejected"][a_], np.minimum(h_new[a_], hh), h_new[a_])
        h_new[a_] = np.minimum(h_new[a_], hmax)
        if contacts is not None:
            rows = np.flatnonzero(a_)
            aimed = h_new[rows]
            contacts.switch(sys_, s, rows, end, aimed, _forces_of(sys_, s))
            h_new[rows] = aimed
    s["rejected"][~accept] += 1
    if contacts is not None:  # a retry to a switch is no failure of the error control
        last = s["last_rejected"][retry]
        h_new[retry] = shorter
    s["last_rejected"] = ~accept
    if contacts is not None:
        s["last_rejected"][retry] = last
    s["h"] = h_new


def _integral_numpy(u0, u1, d0, d1, lo) -> np.ndarray:
    """Vectorized integral over [lo, 1] of the cubic Hermite interpolant (rodas module)."""
    c2 = -3.0 * u0 - 2.0 * d0 + 3.0 * u1 - d1
    c3 = 2.0 * u0 + d0 - 2.0 * u1 + d1
    upper = u0 + d0 / 2.0 + c2 / 3.0 + c3 / 4.0
    return upper - lo * (u0 + lo * (d0 / 2.0 + lo * (c2 / 3.0 + lo * c3 / 4.0)))


def extremes_numpy(
    u0: np.ndarray, u1: np.ndarray, d0: np.ndarray, d1: np.ndarray, lo: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Vectorized :func:`torsio.solvers.rodas.extremes_of_cubic` (max, min over [lo, 1])."""
    c2 = -3.0 * u0 - 2.0 * d0 + 3.0 * u1 - d1
    c3 = 2.0 * u0 + d0 - 2.0 * u1 + d1

    def at(x: np.ndarray) -> np.ndarray:
        return u0 + x * (d0 + x * (c2 + x * c3))

    ulo = at(lo)
    vmax = np.maximum(ulo, u1)
    vmin = np.minimum(ulo, u1)
    a = 3.0 * c3
    b = 2.0 * c2
    with np.errstate(invalid="ignore", divide="ignore"):
        quadratic = np.abs(a) > 1e-14 * (np.abs(b) + np.abs(d0))
        disc = b * b - 4.0 * a * d0
        sq = np.sqrt(np.maximum(disc, 0.0))
        q = -0.5 * (b + np.copysign(sq, b))
        roots = [
            np.where(quadratic & (disc >= 0), q / a, np.nan),
            np.where(quadratic & (disc >= 0) & (q != 0), d0 / q, np.nan),
            np.where(~quadratic & (b != 0), -d0 / b, np.nan),
        ]
    for root in roots:
        ok = (root > lo) & (root < 1.0)
        u = at(np.where(ok, root, 1.0))
        vmax = np.where(ok, np.maximum(vmax, u), vmax)
        vmin = np.where(ok, np.minimum(vmin, u), vmin)
    return vmax, vmin
