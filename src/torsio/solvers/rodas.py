"""The compiled kernel: RODAS4 on the chain of :mod:`torsio.physics.dynamics`.

One kernel for every chain length, bit-rock law and top drive, for batches of points
(:func:`point`) and single runs sampled on an output grid (:func:`advance`;
:mod:`torsio.solvers.single_run`); the entry points that numba compiles with explicit
signatures are in :mod:`torsio.solvers.rodas_kernels`.
The chain (n nodes, node n-1 the bit) in twist coordinates about Omega_ref, with
[C] = [C_rel] + diag(drag)::

    phi' = v
    [I] v' = applied - drag Omega_ref - [K] phi - [C] v - T_bit(Omega_ref + v_{n-1}) e_{n-1} + u e_0
    z'     = a z + b y + w (u - u_free),   u_free = u0 + c.z + d.y,   u = clip(u_free, +-max)

with y = [e, T_pipe], e = Omega_set - Omega_0, T_pipe = k_1 (phi_0 - phi_1) + c_1 (v_0 - v_1);
u, z and y only with a top-drive node. Coulomb contacts along the string (lumped mass) add
a constant friction torque to each moving contact's node and hold a stuck one's speed
(v_i' = 0); a step through a switch is retried shortened to it
(:mod:`torsio.solvers.contact_kernel`). Without contacts the steps are those of the chain
alone.

RODAS4 (Hairer and Wanner, *Solving ODEs II*, IV.7; ``rodas.f``, METH = 1): six stages, each
a linear solve with ``M/(gamma h) - J`` (J exact at the start of the step). Eliminating the
twist increments and the controller increments (m <= 3: they act on nodes 0 and 1 only)
leaves an n x n tridiagonal matrix, factored once per step in O(n) without pivoting.
Per-point step control: RMS of ``err_i / (atol + rtol max(|y_i|, |y_new_i|))`` over every
state <= 1, Gustafsson's predictive controller, steps capped at ``hmax``.

The extremes of the bit speed in the steady window, the mean top-drive speed and the end
of a run on a steady cycle come from the cubic Hermite interpolant of each step
(:mod:`torsio.solvers.cycles`). The step loop allocates nothing and counts no references.

The law enters through two first-class functions of signature
:data:`torsio.solvers.law_kernels.LAW_SIGNATURE`; the kernels below have explicit
signatures, so numba compiles and caches them once for every law.
"""

from __future__ import annotations

import math

import numpy as np

from torsio.solvers import contact_kernel as contact
from torsio.solvers import layouts as slot
from torsio.solvers.chain_kernel import (
    controller_solve,
    finish_run,
    forces,
    mass_factors,
    sample_state,
    saturated,
    set_speed_rates,
    store_carry,
    store_window,
)
from torsio.solvers.compiled import njit, njit_inner
from torsio.solvers.cycles import extremes_of_cubic, hermite, integral_of_cubic, track_cycle
from torsio.solvers.set_speed import (
    fill_twists,
    next_table_time,
    table_rate,
    table_speed,
    table_twist,
)

__all__ = [
    "GAMMA",
    "RODAS_A",
    "RODAS_ALPHA",
    "RODAS_C",
    "RODAS_D",
    "advance",
    "point",
    "start",
]

# --- RODAS4 (Hairer and Wanner, Solving ODEs II, Sec. IV.7; rodas.f, METH = 1) --------------
GAMMA = 0.25
RODAS_A = np.zeros((6, 6))
RODAS_A[1, 0] = 1.544
RODAS_A[2, :2] = (0.9466785280815826, 0.2557011698983284)
RODAS_A[3, :3] = (3.314825187068521, 2.896124015972201, 0.9986419139977817)
RODAS_A[4, :4] = (1.221224509226641, 6.019134481288629, 12.53708332932087, -0.687886036105895)
RODAS_A[5, :5] = (*RODAS_A[4, :4], 1.0)
RODAS_C = np.zeros((6, 6))
RODAS_C[1, 0] = -5.6688
RODAS_C[2, :2] = (-2.430093356833875, -0.2063599157091915)
RODAS_C[3, :3] = (-0.1073529058151375, -9.594562251023355, -20.47028614809616)
RODAS_C[4, :4] = (7.496443313967647, -10.24680431464352, -33.99990352819905, 11.70890893206160)
RODAS_C[5, :5] = (
    8.083246795921522,
    -7.981132988064893,
    -31.52159432874371,
    16.31930543123136,
    -6.058818238834054,
)
# y_new = (argument of stage 6) + k6, the embedded error estimate k6. A set speed changing in
# time: stage i at t + RODAS_ALPHA[i] h takes h RODAS_D[i] df/dt (rodas.f: C2-C4, D1-D4)
RODAS_ALPHA = np.array([0.0, 0.386, 0.21, 0.63, 1.0, 1.0])
RODAS_D = np.array([0.25, -0.1043, 0.1035, -0.03620000000000023, 0.0, 0.0])


@njit_inner(cache=True, nogil=True, error_model="numpy", _nrt=False)
def start(chain, top, torque, p, settings, wob, omega, table, vectors, small) -> None:
    """Prepare a run (:func:`advance`'s first call) from the state (phi, v, z) in the work
    space, at t = 0. ``table``: the set speed against time (rows ``TABLE_*``,
    :mod:`torsio.solvers.set_speed`; one column for a constant set speed, NaN: none).
    ``vectors`` and ``small``: the work space (:mod:`torsio.solvers.layouts`), zero but for
    the state; the run's scalars are carried in rows ``SMALL_CARRY`` and ``SMALL_WINDOW``."""
    n = chain.shape[1]
    mpiv, mlow = vectors[slot.VEC_MASS_PIVOTS], vectors[slot.VEC_MASS_LOWER]
    f0v = vectors[slot.VEC_F0_V]
    mass_factors(chain, mpiv, mlow)
    radius = settings[slot.RUN_BIT_RADIUS]
    z = small[slot.SMALL_Z, : slot.SECOND_BLOCK]
    f0z = small[slot.SMALL_F_Z, slot.SECOND_BLOCK : slot.BLOCKS_END]
    phi, v, state = vectors[slot.VEC_PHI], vectors[slot.VEC_V], vectors[slot.VEC_CONTACT_STATE]
    contacts = contact.start_contacts(chain, omega, v, state)
    small[slot.SMALL_FRICTION, slot.FRICTION_ANY] = 1.0 if contacts else 0.0
    set0, twist0 = table_speed(table, 0.0), table_twist(table, 0.0, omega)
    contact.restart(chain, top, torque, p, wob, radius, omega, set0, twist0, phi, v, z, f0v, f0z,
                    mpiv, mlow, vectors[slot.VEC_ACC], state, contacts)  # fmt: skip
    t_end = settings[slot.RUN_T_END]
    cycle_settings = small[slot.SMALL_CYCLE_SETTINGS, : slot.CYCLE_SETTINGS_SIZE]
    cycle_settings[slot.CYCLE_SET_TWICE_OMEGA] = 2.0 * abs(omega)
    cycle_settings[slot.CYCLE_SET_OMEGA_1] = settings[slot.RUN_OMEGA_1]
    cycle_settings[slot.CYCLE_SET_T_END] = t_end
    cycle_settings[slot.CYCLE_SET_WINDOW] = t_end - settings[slot.RUN_WINDOW_START]
    cycle_settings[slot.CYCLE_SET_TOLERANCE] = settings[slot.RUN_STEADY_TOLERANCE]
    h = min(settings[slot.RUN_FIRST_STEP], settings[slot.RUN_MAX_STEP], t_end)
    store_carry(small[slot.SMALL_CARRY], 0.0, h, h, 1.0, False, 0, 0, 0)
    store_window(small[slot.SMALL_WINDOW], -np.inf, np.inf, 0.0, 0, n == 0)


@njit(cache=True, nogil=True, error_model="numpy", _nrt=False)
def advance(
    chain, top, torque, slope, p, settings, wob, omega, table, vectors, small, grid,
    samples, stop,
) -> None:  # fmt: skip
    """RODAS4 steps from the carried state until t_end, a steady cycle, a failure, or (with
    an output grid) until the samples up to index ``stop`` are written. The first call on
    a fresh work space (zero but for the state) prepares the run (:func:`start`).

    A set speed that changes in time (``table`` of more than one point, see :func:`start`)
    enters each stage at its time with the stage's df/dt term, and no step crosses a point
    of the table (where the speed's slope may jump).

    ``grid`` (times [s], ascending, within [0, t_end]) and ``samples`` (grid.size, 2n + m):
    the state ``[z, phi_0, v_0, ...]`` at each grid time, from the cubic Hermite interpolant
    of the step that covers it; empty arrays for none. Chunked calls take the same steps
    as one call: the state, the step and the controller's memory are carried in ``small``.
    """
    if small[slot.SMALL_CARRY, slot.CARRY_H] == 0.0:  # a new run (a prepared one has h > 0)
        start(chain, top, torque, p, settings, wob, omega, table, vectors, small)
    t_end = settings[slot.RUN_T_END]
    t_window = settings[slot.RUN_WINDOW_START]
    rtol = settings[slot.RUN_RTOL]
    atol = settings[slot.RUN_ATOL]
    hmax = settings[slot.RUN_MAX_STEP]
    max_steps = int(settings[slot.RUN_MAX_STEPS])
    radius = settings[slot.RUN_BIT_RADIUS]
    n = chain.shape[1]
    md, mu = chain[slot.CHAIN_MASS], chain[slot.CHAIN_MASS_UPPER]
    kd, ku = chain[slot.CHAIN_STIFFNESS], chain[slot.CHAIN_STIFFNESS_UPPER]
    cd, cu = chain[slot.CHAIN_DAMPING], chain[slot.CHAIN_DAMPING_UPPER]
    has_top = top[slot.TOP_HAS_NODE] != 0.0
    m = int(top[slot.TOP_STATES])
    k1, c1 = top[slot.TOP_K_PIPE], top[slot.TOP_C_PIPE]
    size = 2 * n + m
    kphi = vectors[slot.VEC_K_PHI : slot.VEC_K_V]
    kv = vectors[slot.VEC_K_V : slot.VEC_PHI]
    phi, v = vectors[slot.VEC_PHI], vectors[slot.VEC_V]
    aphi, av = vectors[slot.VEC_A_PHI], vectors[slot.VEC_A_V]
    fphi, fv, f0v = vectors[slot.VEC_F_PHI], vectors[slot.VEC_F_V], vectors[slot.VEC_F0_V]
    uphi, uv, x = vectors[slot.VEC_U_PHI], vectors[slot.VEC_U_V], vectors[slot.VEC_X]
    ipiv, low, band = vectors[slot.VEC_PIVOTS], vectors[slot.VEC_LOWER], vectors[slot.VEC_BAND]
    acc, mpiv = vectors[slot.VEC_ACC], vectors[slot.VEC_MASS_PIVOTS]
    mlow = vectors[slot.VEC_MASS_LOWER]
    phi0, v0, acc0 = vectors[slot.VEC_PHI0], vectors[slot.VEC_V0], vectors[slot.VEC_ACC0]
    cross = vectors[slot.VEC_CROSS : slot.VEC_CONTACT_STATE]
    state, pending = vectors[slot.VEC_CONTACT_STATE], vectors[slot.VEC_CONTACT_PENDING]
    friction = small[slot.SMALL_FRICTION]
    contacts = friction[slot.FRICTION_ANY] != 0.0
    work, switches = friction[slot.FRICTION_WORK], int(friction[slot.FRICTION_SWITCHES])
    max_switches, instant, h_resume = settings[slot.RUN_MAX_SWITCHES], 0, 0.0
    track = settings[slot.RUN_STEADY_TOLERANCE] > 0.0
    varying = table.shape[1] > 1
    ramp_end = table[slot.TABLE_TIME, table.shape[1] - 1]
    set_speed, twist = table_speed(table, 0.0), 0.0  # a constant set speed (psi = 0)
    force_rate = 0.0  # d/dt of node 0's force and of z' of the set speed's change
    fz_rate = small[slot.SMALL_SET_RATE, slot.FIRST_BLOCK : slot.SECOND_BLOCK]
    dense = grid.size > 0
    cycle = small[slot.SMALL_CYCLE, : slot.CYCLE_SIZE]
    cycle_settings = small[slot.SMALL_CYCLE_SETTINGS, : slot.CYCLE_SETTINGS_SIZE]
    first, second, end = slot.FIRST_BLOCK, slot.SECOND_BLOCK, slot.BLOCKS_END
    kz = small[slot.SMALL_K_Z : slot.SMALL_Z, first:second]
    z, az = small[slot.SMALL_Z, first:second], small[slot.SMALL_Z, second:end]
    fz, f0z = small[slot.SMALL_F_Z, first:second], small[slot.SMALL_F_Z, second:end]
    uz = small[slot.SMALL_U_Z, first:second]
    q = small[slot.SMALL_Q : slot.SMALL_GAINS, first:second]
    zy = small[slot.SMALL_Q : slot.SMALL_GAINS, second : second + 2]
    gains = small[slot.SMALL_GAINS, : slot.GAIN_STATES + slot.MAX_STATES]
    solve_work = small[slot.SMALL_SOLVE : slot.SMALL_CYCLE]
    z0, fz0 = small[slot.SMALL_START, first:second], small[slot.SMALL_START, second:end]
    carry, window = small[slot.SMALL_CARRY], small[slot.SMALL_WINDOW]
    t, h = carry[slot.CARRY_T], carry[slot.CARRY_H]
    h_accepted, err_accepted = carry[slot.CARRY_H_ACCEPTED], carry[slot.CARRY_ERR_ACCEPTED]
    last_rejected = carry[slot.CARRY_LAST_REJECTED] != 0.0
    steps, rejected = int(carry[slot.CARRY_STEPS]), int(carry[slot.CARRY_REJECTED])
    status = int(carry[slot.CARRY_STATUS])
    vmax, vmin = window[slot.WINDOW_BIT_MAX], window[slot.WINDOW_BIT_MIN]
    top_integral = window[slot.WINDOW_TOP_INTEGRAL]
    next_sample = int(window[slot.WINDOW_NEXT_SAMPLE])
    done = window[slot.WINDOW_DONE] != 0.0
    tiny = 1e-12 * max(1.0, t_end)
    bit_acc0 = acc[n - 1]
    top_acc0 = acc[0]
    while next_sample < grid.size and grid[next_sample] <= t:  # samples at the current time
        sample_state(samples[next_sample], phi, v, z, n, m)
        next_sample += 1
    while t < t_end and status == 0 and not done and not (dense and next_sample >= stop):
        if steps >= max_steps:
            status = 1
            break
        if switches > max_switches or instant > 4 * n + 4:  # the contacts chatter
            status = 5
            break
        if h < tiny:
            status = 2
            break
        if t + h > t_end:
            h = t_end - t
        if varying:  # the step ends at the table's next point
            h = min(h, next_table_time(table, t + tiny) - t)
        g = GAMMA * h
        bit_stuck = contacts and contact.is_stuck(chain, state, n - 1)
        s = 0.0 if bit_stuck else slope(p, omega + v[n - 1], wob, radius)
        if not math.isfinite(s):  # the law's slope, not the step, is at fault
            status = 3
            break
        diag0 = 0.0
        extra01 = 0.0
        limited = False
        if varying:
            set_speed = table_speed(table, t)
        if has_top:  # eliminate the controller increments into rows 0 and 1
            limited = saturated(top, omega, set_speed, phi, v, z)
            controller_solve(top, g, limited, q, zy, gains, solve_work)
            extra01 = gains[slot.GAIN_PIPE] * (g * k1 + c1)
            diag0 = gains[slot.GAIN_E] - extra01
        # factor [I]/g + [C] + g [K] + s e_N e_N^T (+ the top drive's row-0 terms)
        singular = False
        for i in range(n):
            band[i] = mu[i] / g + cu[i] + g * ku[i]
        if contacts:  # a stuck node's row is the identity, its couplings zero
            contact.decouple(chain, state, band)
        for i in range(n):
            a = md[i] / g + cd[i] + g * kd[i]
            scale = md[i] / g + abs(cd[i]) + g * kd[i]
            if i == n - 1:
                a += s
            if i == 0:
                a += diag0
            if i > 0:
                low[i] = band[i - 1] * ipiv[i - 1]
                a -= low[i] * (band[i - 1] + (extra01 if i == 1 else 0.0))
            if contacts and contact.is_stuck(chain, state, i):
                a = scale
            if not abs(a) > 1e-13 * scale:
                singular = True
                a = 1.0
            ipiv[i] = 1.0 / a
        if singular:
            h *= 0.5
            rejected += 1
            last_rejected = True
            continue
        if varying:
            rate = table_rate(table, t)
            force_rate = set_speed_rates(top, omega, set_speed, rate, limited, fz_rate)
        for stage in range(6):
            # argument y0 + sum_j a_ij k_j and mass-matrix term sum_j c_ij k_j / h
            for i in range(n):
                aphi[i] = phi[i]
                av[i] = v[i]
                uphi[i] = 0.0
                uv[i] = 0.0
            for i in range(m):
                az[i] = z[i]
                uz[i] = 0.0
            for j in range(stage):
                a_ij = RODAS_A[stage, j]
                c_ij = RODAS_C[stage, j] / h
                for i in range(n):
                    aphi[i] += a_ij * kphi[j, i]
                    av[i] += a_ij * kv[j, i]
                    uphi[i] += c_ij * kphi[j, i]
                    uv[i] += c_ij * kv[j, i]
                for i in range(m):
                    az[i] += a_ij * kz[j, i]
                    uz[i] += c_ij * kz[j, i]
            if stage == 0:
                for i in range(n):
                    fphi[i] = v[i]
                    fv[i] = f0v[i]
                for i in range(m):
                    fz[i] = f0z[i]
            else:
                if varying:
                    time = t + RODAS_ALPHA[stage] * h
                    set_speed, twist = table_speed(table, time), table_twist(table, time, omega)
                forces(chain, top, torque, p, wob, radius, omega, set_speed, twist, aphi, av, az,
                       fv, fz)  # fmt: skip
                if contacts:
                    contact.add_friction(chain, state, fv)
                for i in range(n):
                    fphi[i] = av[i] + uphi[i]
                    fv[i] += md[i] * uv[i]
                for i in range(n - 1):
                    fv[i] += mu[i] * uv[i + 1]
                    fv[i + 1] += mu[i] * uv[i]
                for i in range(m):
                    fz[i] += uz[i]
            if varying:  # the stage's h d_i df/dt
                fv[0] += h * RODAS_D[stage] * force_rate
                for i in range(m):
                    fz[i] += h * RODAS_D[stage] * fz_rate[i]
            # speeds: A x = f_v - g [K] f_phi (+ top-drive terms); twists: k_phi = g (f_phi + x)
            for i in range(n):
                x[i] = fv[i] - g * kd[i] * fphi[i]
            for i in range(n - 1):
                x[i] -= g * ku[i] * fphi[i + 1]
                x[i + 1] -= g * ku[i] * fphi[i]
            if has_top:
                x[0] += gains[slot.GAIN_PIPE] * k1 * g * (fphi[0] - fphi[1])
                for k in range(m):
                    x[0] += gains[slot.GAIN_STATES + k] * fz[k]
            if contacts:
                contact.zero_stuck(chain, state, x)
            for i in range(1, n):
                x[i] -= low[i] * x[i - 1]
            x[n - 1] *= ipiv[n - 1]
            for i in range(n - 2, -1, -1):
                x[i] = (x[i] - (band[i] + (extra01 if i == 0 else 0.0)) * x[i + 1]) * ipiv[i]
            for i in range(n):
                kv[stage, i] = x[i]
                kphi[stage, i] = g * (fphi[i] + x[i])
            if m:
                dy_e = -x[0]
                dy_t = k1 * (kphi[stage, 0] - kphi[stage, 1]) + c1 * (x[0] - x[1])
                for j in range(m):
                    total = 0.0
                    for k in range(m):
                        total += q[j, k] * (fz[k] + zy[k, 0] * dy_e + zy[k, 1] * dy_t)
                    kz[stage, j] = total
        # y_new = argument of stage 6 + k6; k6 is the error estimate
        err = 0.0
        for i in range(n):
            ep = kphi[5, i] / (atol + rtol * max(abs(phi[i]), abs(aphi[i] + kphi[5, i])))
            ev = kv[5, i] / (atol + rtol * max(abs(v[i]), abs(av[i] + kv[5, i])))
            err += ep * ep + ev * ev
        for i in range(m):
            ez = kz[5, i] / (atol + rtol * max(abs(z[i]), abs(az[i] + kz[5, i])))
            err += ez * ez
        err = math.sqrt(err / size)
        if not math.isfinite(err):
            h *= 0.25
            rejected += 1
            last_rejected = True
            if h < tiny:
                status = 3
                break
            continue
        factor = max(1.0 / 6.0, min(5.0, math.sqrt(math.sqrt(err)) / 0.9))
        h_new = h / factor
        if varying:  # the set speed and the top's twist at the step's end
            set_speed, twist = table_speed(table, t + h), table_twist(table, t + h, omega)
        if err <= 1.0 and contacts:
            theta = contact.check_step(
                chain, top, torque, p, wob, radius, omega, set_speed, twist, v, f0v, aphi, av,
                az, kphi[5], kv[5], kz[5], acc, uphi, uv, uz, fv, fz, state, pending, h,
                100.0 * tiny,
            )  # fmt: skip
            if theta < 0.0:  # a contact switches at the step's start: retry in its new state
                switches += contact.switch(chain, state, omega, v, f0v, pending)
                instant += 1
                if varying:
                    set_speed, twist = table_speed(table, t), table_twist(table, t, omega)
                contact.restart(chain, top, torque, p, wob, radius, omega, set_speed, twist, phi,
                                v, z, f0v, f0z, mpiv, mlow, acc, state, contacts)  # fmt: skip
                bit_acc0, top_acc0 = acc[n - 1], acc[0]
                continue
            if theta < 1.0:  # retry the step up to the located switch
                h_resume = max(h_resume, h)
                h *= theta
                rejected += 1
                continue
            work += contact.friction_work(chain, state, phi, uphi, omega, h)
        if err <= 1.0:
            if steps > 0:  # Gustafsson's predictive controller (as in rodas.f)
                predicted = h_accepted / h * math.sqrt(math.sqrt(err * err / err_accepted)) / 0.9
                predicted = max(1.0 / 6.0, min(5.0, predicted))
                h_new = h / max(factor, predicted)
            h_accepted = h
            err_accepted = max(1e-2, err)
            bit0 = v[n - 1]
            top0 = v[0]
            if dense or (track and bit0 < 0.0 <= av[n - 1] + kv[5, n - 1]):  # the step's start
                for i in range(n):
                    phi0[i] = phi[i]
                    v0[i] = v[i]
                    acc0[i] = acc[i]
                for i in range(m):
                    z0[i] = z[i]
                    fz0[i] = f0z[i]
            for i in range(n):
                phi[i] = aphi[i] + kphi[5, i]
                v[i] = av[i] + kv[5, i]
            for i in range(m):
                z[i] = az[i] + kz[5, i]
            if contacts:  # the forces at the step's end are check_step's
                contact.restart_at_end(chain, fv, fz, f0v, f0z, mpiv, mlow, acc, state)
            else:
                contact.restart(chain, top, torque, p, wob, radius, omega, set_speed, twist, phi,
                                v, z, f0v, f0z, mpiv, mlow, acc, state, contacts)  # fmt: skip
            t_new = t + h
            while next_sample < grid.size and grid[next_sample] <= t_new:
                position = (grid[next_sample] - t) / h
                if position >= 1.0:
                    sample_state(samples[next_sample], phi, v, z, n, m)
                else:
                    row = samples[next_sample]
                    for i in range(m):
                        row[i] = hermite(z0[i], z[i], h * fz0[i], h * f0z[i], position)
                    for i in range(n):
                        row[m + 2 * i] = hermite(phi0[i], phi[i], h * v0[i], h * v[i], position)
                        row[m + 2 * i + 1] = hermite(v0[i], v[i], h * acc0[i], h * acc[i], position)
                next_sample += 1
            if t_new > t_window:
                lo = (t_window - t) / h if t < t_window else 0.0
                vmax, vmin = extremes_of_cubic(
                    bit0, v[n - 1], h * bit_acc0, h * acc[n - 1], lo, 1.0, vmax, vmin
                )
                if has_top:
                    top_integral += h * integral_of_cubic(top0, v[0], h * top_acc0, h * acc[0], lo)
            if (
                track
                and t >= ramp_end
                and track_cycle(  # a cycle once the table is over
                    cycle, t, h, bit0, bit_acc0, phi0, v0, acc0, phi, v, acc, cross, cycle_settings
                )
            ):  # on a steady cycle: its extremes are those of the rest of the window
                vmax = max(vmax, cycle[slot.CYCLE_MAX])
                vmin = min(vmin, cycle[slot.CYCLE_MIN])
                t = t_new
                steps += 1
                done = True
                break
            made = contact.switch(chain, state, omega, v, f0v, pending) if contacts else 0
            if made:  # the switches at the step's end
                switches += made
                contact.restart(chain, top, torque, p, wob, radius, omega, set_speed, twist, phi,
                                v, z, f0v, f0z, mpiv, mlow, acc, state, contacts)  # fmt: skip
            instant = 0
            bit_acc0 = acc[n - 1]
            top_acc0 = acc[0]
            t = t_new
            steps += 1
            if last_rejected:
                h_new = min(h_new, h)
            last_rejected = False
            h = min(max(h_new, h_resume - h), hmax)  # back to the step before a location
            h_resume = 0.0
        else:
            rejected += 1
            last_rejected = True
            h = h_new
    store_carry(carry, t, h, h_accepted, err_accepted, last_rejected, steps, rejected, status)
    store_window(window, vmax, vmin, top_integral, next_sample, done)
    friction[slot.FRICTION_WORK] = work
    friction[slot.FRICTION_SWITCHES] = switches


@njit(cache=True, nogil=True, error_model="numpy", inline="always")
def point(chain, top, torque, slope, p, settings, wob, omega, omega_set, out, k) -> None:
    """Point k from rest at its set speed (ramped over ``RUN_RAMP``), with its own zeroed
    work space; ``stop`` an int64 as a single run passes it (a literal 0 would compile
    :func:`advance` a second time for the literal's own type)."""
    vectors = np.zeros((slot.VECTOR_ROWS, chain.shape[1]))
    small = np.zeros((slot.SMALL_ROWS, slot.SMALL_COLUMNS))
    ramp = settings[slot.RUN_RAMP]
    table = np.zeros((slot.TABLE_ROWS, 2 if ramp > 0.0 else 1))
    table[slot.TABLE_TIME, table.shape[1] - 1] = ramp
    table[slot.TABLE_SPEED, table.shape[1] - 1] = omega_set[k]
    fill_twists(table, omega[k])
    for i in range(chain.shape[1]):
        vectors[slot.VEC_V, i] = -omega[k]  # start-up from rest: theta' = 0, controller states 0
    advance(chain, top, torque, slope, p, settings, wob[k], omega[k], table, vectors, small,
            np.zeros(0), np.zeros((0, 1)), np.int64(0))  # fmt: skip
    finish_run(settings, omega[k], top[slot.TOP_HAS_NODE] != 0.0, small, out[k])
