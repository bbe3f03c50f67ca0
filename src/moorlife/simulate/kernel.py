"""The Numba kernels of the coupled simulator: rigid-body kinematics, loads, RK4 step, record loops.

The kernels take their inputs as records (``typing.NamedTuple`` of arrays and scalars, which
Numba compiles as heterogeneous tuples): :class:`State` (what the step advances),
:class:`Body`, :class:`Radiation`, :class:`Strips`, :class:`Rotor` (the platform model),
:class:`Excitation` (the forcing on the grid), :class:`MooringLink` (the mooring forces of the
step) and :class:`Recorder` (where the kept record goes). The mooring lines are advanced by the
compiled step of their model (:mod:`moorlife.mooring`).
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numba
import numpy as np

from moorlife.mooring.dynamic import step_lines as _step_dynamic_lines
from moorlife.mooring.lanes import pack as _pack_lanes
from moorlife.mooring.lanes import step_lanes as _step_lanes
from moorlife.mooring.lanes import unpack as _unpack_lanes
from moorlife.mooring.quasistatic import step_lines as _step_quasistatic_lines

__all__ = [
    "rotation_matrix",
    "State",
    "Body",
    "Radiation",
    "Strips",
    "Rotor",
    "Excitation",
    "MooringLink",
    "DynamicLines",
    "Recorder",
]


class State(NamedTuple):
    """What a step advances, for a batch of ``B`` cases (arrays updated in place)."""

    #: (B, 6) platform displacement about the origin, m and rad
    displacement: np.ndarray
    #: (B, 6) platform velocity
    velocity: np.ndarray
    #: (B, nr) radiation states (state-space memory; empty with a kernel)
    radiation: np.ndarray
    #: (B, nf) states of the pitch-band filter of the rotor's relative wind
    filter: np.ndarray
    #: (B, 3, 3) mooring forces at the start of the step (then their mean with the end's)
    mooring_force: np.ndarray
    #: (B, 6) load held constant over the step (scratch: mooring, trim, convolution)
    held_load: np.ndarray
    #: (B, 6) accelerations at the start of the step (scratch)
    acceleration: np.ndarray
    #: (stride, 6, 2 nlag, B) velocity history of the radiation convolution (:func:`_convolve`)
    history: np.ndarray
    #: (npairs, B) sums of the radiation convolution (scratch of :func:`_convolve`)
    convolution: np.ndarray
    #: (B, 3, 3) fairlead positions predicted for the end of the step (scratch)
    fairlead_position: np.ndarray
    #: (B, 3, 3) fairlead velocities (scratch)
    fairlead_velocity: np.ndarray


class Body(NamedTuple):
    """The rigid platform."""

    #: (6, 6) inverse of mass plus added mass (zero rows and columns for locked DOFs)
    inverse_mass: np.ndarray
    #: (6, 6) hydrostatic stiffness with gravity (plus the linear verification mooring)
    stiffness: np.ndarray
    #: (6, 6) extra linear damping
    damping: np.ndarray
    #: (6,) constant trim load
    trim_load: np.ndarray
    #: (3,) hub position, body frame, m
    hub: np.ndarray
    #: (3, 3) fairlead positions, body frame (line, xyz), m
    fairleads: np.ndarray


class Radiation(NamedTuple):
    """The radiation memory: state space (CSR matrix) or retardation kernel (one is empty)."""

    #: (nr + 1,) row pointers of the state matrix A (compressed sparse rows)
    ss_row_start: np.ndarray
    #: column of each non-zero of A
    ss_column: np.ndarray
    #: value of each non-zero of A
    ss_value: np.ndarray
    #: (nr, 6) input matrix B (velocity to state derivative)
    ss_input: np.ndarray
    #: (6, nr) output matrix C (state to force)
    ss_output: np.ndarray
    #: (npairs, nlag) kernel with trapezoid weights, oldest lag first (:func:`_convolve`)
    kernel: np.ndarray
    #: the kernel's step in integration steps
    kernel_stride: int
    #: (npairs,) DOF of the force of each kernel pair
    kernel_force_dof: np.ndarray
    #: (npairs,) DOF of the velocity of each kernel pair
    kernel_velocity_dof: np.ndarray


class Strips(NamedTuple):
    """Morison drag strips, strips along the last axis."""

    #: (3, ns) centres, body frame, m
    position: np.ndarray
    #: (3, ns) unit axes
    axis: np.ndarray
    #: (ns,) normal drag factor 0.5 rho Cd D L, kg/m
    drag_normal: np.ndarray
    #: (ns,) axial drag factor, kg/m
    drag_axial: np.ndarray
    #: (6, ns) force and moment of each strip (scratch of :func:`_rhs`)
    loads: np.ndarray


class Rotor(NamedTuple):
    """Rotor thrust: the thrust curve and the pitch-band filter (SISO state space) on the relative wind."""

    #: (nv,) relative wind speeds of the thrust table, m/s
    wind_speed: np.ndarray
    #: (nv,) thrust, N
    thrust: np.ndarray
    #: (nf, nf) filter state matrix
    filter_a: np.ndarray
    #: (nf, 1) filter input matrix
    filter_b: np.ndarray
    #: (1, nf) filter output matrix
    filter_c: np.ndarray
    #: (1, 1) filter feed-through
    filter_d: np.ndarray


class Excitation(NamedTuple):
    """The external forcing of the batch on the integration grid (see ``simulate.Forcing``)."""

    #: (B, n + 1, 6) wave force, N and N m
    force: np.ndarray
    #: (B, n + 1) hub wind speed, m/s
    wind: np.ndarray
    #: (B, 2) unit vector of the wind's direction of travel
    wind_dir: np.ndarray
    #: (B, nk, 3, ns) wave particle velocity at the strips
    kinematics: np.ndarray
    #: sampling of the kinematics, in steps
    kin_every: int


class MooringLink(NamedTuple):
    """The mooring forces of a step, as the line model left them."""

    #: False for the linear verification mooring (folded into the stiffness)
    coupled: bool
    #: (B, 3, 3) fairlead forces on the platform at the end of the step, N
    forces: np.ndarray
    #: (B, 3) fairlead tensions at the end of the step, N
    tension: np.ndarray


class DynamicLines(NamedTuple):
    """The dynamic lines of the batch as the record loop steps them."""

    #: the ``moorlife.mooring.dynamic.DynamicState`` of the lines (updated in place)
    state: Any
    #: the line model (``moorlife.mooring.dynamic.LineKernel``)
    kernel: Any
    #: the same lines as lanes (``moorlife.mooring.lanes.LaneState``; no lanes: the one-line step)
    lanes: Any
    #: the lanes' scratch (``moorlife.mooring.lanes.LaneWork``)
    work: Any


class Recorder(NamedTuple):
    """Where the kept record goes: step ``j`` is kept as sample ``j - start``."""

    #: first kept step (the transient is discarded)
    start: int
    #: (B, 6, nt) displacement
    motion: np.ndarray
    #: (B, 3, nt) hub acceleration
    accel: np.ndarray
    #: (B, 3, nt) fairlead tension
    tension: np.ndarray


def rotation_matrix(rot: np.ndarray) -> np.ndarray:
    """Rotation matrix ``Rz(yaw) Ry(pitch) Rx(roll)`` of ``rot (..., 3)`` rad -> ``(..., 3, 3)``."""
    r = np.asarray(rot, dtype=float)
    out = np.empty(r.shape[:-1] + (3, 3))
    _rotation(r.reshape(-1, 3), out.reshape(-1, 3, 3))
    return out


@numba.njit(cache=True, inline="always")
def _rotation_entries(roll, pitch, yaw):  # pragma: no cover - numba
    """The nine entries of ``Rz(yaw) Ry(pitch) Rx(roll)``, row by row."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return (
        cy * cp,
        cy * sp * sr - sy * cr,
        cy * sp * cr + sy * sr,
        sy * cp,
        sy * sp * sr + cy * cr,
        sy * sp * cr - cy * sr,
        -sp,
        cp * sr,
        cp * cr,
    )


@numba.njit(cache=True)
def _rotation(rot, out):  # pragma: no cover - numba
    for i in range(rot.shape[0]):
        e = _rotation_entries(rot[i, 0], rot[i, 1], rot[i, 2])
        out[i, 0, 0], out[i, 0, 1], out[i, 0, 2] = e[0], e[1], e[2]
        out[i, 1, 0], out[i, 1, 1], out[i, 1, 2] = e[3], e[4], e[5]
        out[i, 2, 0], out[i, 2, 1], out[i, 2, 2] = e[6], e[7], e[8]


@numba.njit(cache=True, inline="always")
def _rotated(q, b, f):  # pragma: no cover - numba
    """``R(q[b, 3:6]) f`` for a 3-vector ``f`` (the matrix of :func:`_rotation`)."""
    e = _rotation_entries(q[b, 3], q[b, 4], q[b, 5])
    px = e[0] * f[0] + e[1] * f[1] + e[2] * f[2]
    py = e[3] * f[0] + e[4] * f[1] + e[5] * f[2]
    pz = e[6] * f[0] + e[7] * f[1] + e[8] * f[2]
    return px, py, pz


@numba.njit(cache=True)
def _fairlead_motion(q, v, fair, r_out, v_out):  # pragma: no cover - numba
    """Fairlead positions and velocities ``(B, 3, 3)`` from the platform state."""
    for b in range(q.shape[0]):
        for i in range(fair.shape[0]):
            px, py, pz = _rotated(q, b, fair[i])
            r_out[b, i, 0] = q[b, 0] + px
            r_out[b, i, 1] = q[b, 1] + py
            r_out[b, i, 2] = q[b, 2] + pz
            wx, wy, wz = v[b, 3], v[b, 4], v[b, 5]
            v_out[b, i, 0] = v[b, 0] + wy * pz - wz * py
            v_out[b, i, 1] = v[b, 1] + wz * px - wx * pz
            v_out[b, i, 2] = v[b, 2] + wx * py - wy * px


@numba.njit(cache=True)
def _moor_generalised(q, fmoor, fair, out):  # pragma: no cover - numba
    """6-DOF mooring load about the (displaced) origin from fairlead forces ``(B, 3, 3)``."""
    for b in range(q.shape[0]):
        for d in range(6):
            out[b, d] = 0.0
        for i in range(fair.shape[0]):
            px, py, pz = _rotated(q, b, fair[i])
            fx, fy, fz = fmoor[b, i, 0], fmoor[b, i, 1], fmoor[b, i, 2]
            out[b, 0] += fx
            out[b, 1] += fy
            out[b, 2] += fz
            out[b, 3] += py * fz - pz * fy
            out[b, 4] += pz * fx - px * fz
            out[b, 5] += px * fy - py * fx


@numba.njit(cache=True, inline="always")
def _rhs(b, t_frac, j, y, dy, held, F, body, rad, strips, rotor, wave):  # pragma: no cover - numba
    """Time derivative ``dy`` of case ``b``'s state ``y = (q, v, xr, zf)`` at ``t = (j + t_frac) dt``.

    ``held (B, 6)`` is the load held over the step; ``F (6,)`` is scratch.
    """
    nr = rad.ss_input.shape[0]
    ny = 12 + nr + rotor.filter_a.shape[0]
    q, v, xr, zf = y[0:6], y[6:12], y[12 : 12 + nr], y[12 + nr : ny]
    dq, dv, dxr, dzf = dy[0:6], dy[6:12], dy[12 : 12 + nr], dy[12 + nr : ny]
    fmoor6, force, wind, wdir, kin, kin_every = (
        held,
        wave.force,
        wave.wind,
        wave.wind_dir,
        wave.kinematics,
        wave.kin_every,
    )
    minv, K, D, hub = body.inverse_mass, body.stiffness, body.damping, body.hub
    ra_ptr, ra_idx, ra_val, rb, rc = rad.ss_row_start, rad.ss_column, rad.ss_value, rad.ss_input, rad.ss_output
    spos, saxis, scdn, scda = strips.position, strips.axis, strips.drag_normal, strips.drag_axial
    tv, tf = rotor.wind_speed, rotor.thrust
    fa, fb, fc, fd = rotor.filter_a, rotor.filter_b, rotor.filter_c, rotor.filter_d
    # external wave force, linear in time between samples j and j+1
    for d in range(6):
        F[d] = (1.0 - t_frac) * force[b, j, d] + t_frac * force[b, j + 1, d] + fmoor6[b, d]
    # hydrostatics + gravity, linear damping
    for d in range(6):
        acc = 0.0
        for e in range(6):
            acc += K[d, e] * q[e] + D[d, e] * v[e]
        F[d] -= acc
    # radiation memory
    for d in range(6):
        acc = 0.0
        for r in range(nr):
            acc += rc[d, r] * xr[r]
        F[d] -= acc
    for r in range(nr):
        acc = 0.0
        for p in range(ra_ptr[r], ra_ptr[r + 1]):
            acc += ra_val[p] * xr[ra_idx[p]]
        for e in range(6):
            acc += rb[r, e] * v[e]
        dxr[r] = acc
    # Morison drag on the relative velocity; strips along the last axis (unit stride, SIMD): the
    # loads of the strips first, then their sums in strip order (a sum cannot be vectorised)
    ns = spos.shape[1]
    if ns > 0:
        tk = (j + t_frac) / kin_every
        jk = int(tk)
        wk = tk - jk
        k0 = kin[b, jk]
        k1 = kin[b, jk + 1]
        vx, vy, vz = v[0], v[1], v[2]
        wx, wy, wz = v[3], v[4], v[5]
        sl = strips.loads
        for s in range(ns):  # every strip's load, independently (vectorised)
            px, py, pz = spos[0, s], spos[1, s], spos[2, s]
            ux = (1 - wk) * k0[0, s] + wk * k1[0, s] - (vx + wy * pz - wz * py)
            uy = (1 - wk) * k0[1, s] + wk * k1[1, s] - (vy + wz * px - wx * pz)
            uz = (1 - wk) * k0[2, s] + wk * k1[2, s] - (vz + wx * py - wy * px)
            ax, ay, az = saxis[0, s], saxis[1, s], saxis[2, s]
            ua = ux * ax + uy * ay + uz * az
            nx, ny, nz = ux - ua * ax, uy - ua * ay, uz - ua * az
            un = math.sqrt(nx * nx + ny * ny + nz * nz)
            ca = scda[s] * abs(ua) * ua
            fx = scdn[s] * un * nx + ca * ax
            fy = scdn[s] * un * ny + ca * ay
            fz = scdn[s] * un * nz + ca * az
            sl[0, s] = fx
            sl[1, s] = fy
            sl[2, s] = fz
            sl[3, s] = py * fz - pz * fy
            sl[4, s] = pz * fx - px * fz
            sl[5, s] = px * fy - py * fx
        f0 = f1 = f2 = m3 = m4 = m5 = 0.0
        for s in range(ns):  # their sums, in strip order
            f0 += sl[0, s]
            f1 += sl[1, s]
            f2 += sl[2, s]
            m3 += sl[3, s]
            m4 += sl[4, s]
            m5 += sl[5, s]
        F[0] += f0
        F[1] += f1
        F[2] += f2
        F[3] += m3
        F[4] += m4
        F[5] += m5
    # thrust at the hub, along the wind, from the filtered relative wind
    uw = (1.0 - t_frac) * wind[b, j] + t_frac * wind[b, j + 1]
    ex, ey = wdir[b, 0], wdir[b, 1]
    hx, hy, hz = hub[0], hub[1], hub[2]
    vhx = v[0] + v[4] * hz - v[5] * hy
    vhy = v[1] + v[5] * hx - v[3] * hz
    vrel = uw - (vhx * ex + vhy * ey)
    nf = zf.shape[0]
    vf = fd[0, 0] * vrel
    for r in range(nf):
        vf += fc[0, r] * zf[r]
    for r in range(nf):
        acc = fb[r, 0] * vrel
        for e in range(nf):
            acc += fa[r, e] * zf[e]
        dzf[r] = acc
    thrust = np.interp(vf, tv, tf)
    tx, ty = thrust * ex, thrust * ey
    F[0] += tx
    F[1] += ty
    F[3] += -hz * ty
    F[4] += hz * tx
    F[5] += hx * ty - hy * tx
    # accelerations
    for d in range(6):
        dq[d] = v[d]
        acc = 0.0
        for e in range(6):
            acc += minv[d, e] * F[e]
        dv[d] = acc


@numba.njit(cache=True)
def _rk4_step(j, dt, state, body, rad, strips, rotor, wave):  # pragma: no cover - numba
    """Advance every case of the batch from step ``j`` to ``j + 1`` (classical RK4, in place).

    ``state.acceleration (B, 6)`` receives the accelerations at the start of the step.
    """
    q, v, xr, zf = state.displacement, state.velocity, state.radiation, state.filter
    fmoor6, acc_out = state.held_load, state.acceleration
    nb = q.shape[0]
    nr = xr.shape[1]
    nf = zf.shape[1]
    ny = 12 + nr + nf
    k = np.empty((4, ny))
    y0 = np.empty(ny)
    ys = np.empty(ny)
    F = np.empty(6)
    for b in range(nb):
        for d in range(6):
            y0[d] = q[b, d]
            y0[6 + d] = v[b, d]
        for r in range(nr):
            y0[12 + r] = xr[b, r]
        for r in range(nf):
            y0[12 + nr + r] = zf[b, r]
        for stage in range(4):
            if stage == 0:
                c, frac = 0.0, 0.0
            elif stage == 3:
                c, frac = 1.0, 1.0
            else:
                c, frac = 0.5, 0.5
            for i in range(ny):
                ys[i] = y0[i] + (c * dt * k[stage - 1, i] if stage > 0 else 0.0)
            _rhs(b, frac, j, ys, k[stage], fmoor6, F, body, rad, strips, rotor, wave)
        for d in range(6):
            acc_out[b, d] = k[0, 6 + d]
        for i in range(ny):
            y0[i] += dt / 6.0 * (k[0, i] + 2.0 * k[1, i] + 2.0 * k[2, i] + k[3, i])
        for d in range(6):
            q[b, d] = y0[d]
            v[b, d] = y0[6 + d]
        for r in range(nr):
            xr[b, r] = y0[12 + r]
        for r in range(nf):
            zf[b, r] = y0[12 + nr + r]


@numba.njit(cache=True)
def _advance(j, dt, state, body, rad, strips, rotor, wave, moor, rec):  # pragma: no cover - numba
    """One coupled step ``j -> j + 1`` of the batch, with recording (kept sample ``i = j - rec.start``).

    The load held constant over the step (``state.held_load``) is the mooring force, the trim
    load and, with a kernel, the radiation convolution. The platform is driven by the mean of the
    mooring forces at the start (``state.mooring_force``) and at the predicted end
    (``moor.forces``); ``state.mooring_force`` then takes ``moor.forces``. ``moor.tension`` is the
    line tension at ``t_{j+1}`` (kept as sample ``i + 1``).
    """
    i = j - rec.start
    q, v, f_prev, fmoor6, acc = (
        state.displacement,
        state.velocity,
        state.mooring_force,
        state.held_load,
        state.acceleration,
    )
    coupled, f_new, ten = moor.coupled, moor.forces, moor.tension
    static, fair, hub = body.trim_load, body.fairleads, body.hub
    motion, accel, tension = rec.motion, rec.accel, rec.tension
    nb = q.shape[0]
    nt = motion.shape[2]
    for b in range(nb):
        for d in range(6):
            fmoor6[b, d] = 0.0
    if coupled:
        for b in range(nb):
            for l in range(f_prev.shape[1]):
                for c in range(3):
                    f_prev[b, l, c] = 0.5 * (f_prev[b, l, c] + f_new[b, l, c])
        _moor_generalised(q, f_prev, fair, fmoor6)
        for b in range(nb):
            for l in range(f_prev.shape[1]):
                for c in range(3):
                    f_prev[b, l, c] = f_new[b, l, c]
        if 0 <= i + 1 < nt:
            for b in range(nb):
                for l in range(ten.shape[1]):
                    tension[b, l, i + 1] = ten[b, l]
    for b in range(nb):
        for d in range(6):
            fmoor6[b, d] += static[d]
    if rad.kernel.shape[1] > 0:
        _convolve(j, v, state.history, rad, state.convolution, fmoor6)
    if i >= 0:
        for b in range(nb):
            for d in range(6):
                motion[b, d, i] = q[b, d]
    _rk4_step(j, dt, state, body, rad, strips, rotor, wave)
    if i >= 0:
        hx, hy, hz = hub[0], hub[1], hub[2]
        for b in range(nb):
            accel[b, 0, i] = acc[b, 0] + acc[b, 4] * hz - acc[b, 5] * hy
            accel[b, 1, i] = acc[b, 1] + acc[b, 5] * hx - acc[b, 3] * hz
            accel[b, 2, i] = acc[b, 2] + acc[b, 3] * hy - acc[b, 4] * hx


@numba.njit(cache=True)
def _convolve(j, v, hist, rad, acc, out):  # pragma: no cover - numba
    """Subtract the radiation convolution ``sum_k K[k] v(t_j - k stride dt)`` from ``out (B, 6)``.

    ``rad.kernel (npairs, nlag)`` (``ker``) holds the kernel with the trapezoid weights and its step ``stride dt``
    folded in, oldest lag first (``ker[p, nlag - 1 - k] = w_k K_p(k stride dt)``).
    ``hist (stride, 6, 2 nlag, B)`` is the velocity history of every step, split by the
    step's residue modulo ``stride`` and stored twice (slot and slot + nlag) so that the
    ``nlag`` samples of a convolution are one contiguous window, the cases innermost. ``v`` is
    stored first. Pair ``p`` is the force in DOF ``kpi[p]`` from the velocity in DOF ``kpj[p]``;
    ``stride`` is ``rad.kernel_stride``.

    Every sum ``acc[p, b]`` (``acc (npairs, B)``, scratch) is the plain sum oldest lag first
    (so the bits do not depend on the batch), but four at a time: four cases of one pair (one
    vector of adjacent cases), or, for the cases left over, four pairs of one case. A single sum
    waits on each addition; four independent ones do not.
    """
    ker, stride, kpi, kpj = rad.kernel, rad.kernel_stride, rad.kernel_force_dof, rad.kernel_velocity_dof
    npair, nlag = ker.shape
    nb = v.shape[0]
    c = j % stride
    slot = (j // stride) % nlag
    for d in range(6):
        for b in range(nb):
            hist[c, d, slot, b] = v[b, d]
            hist[c, d, slot + nlag, b] = v[b, d]
    s = slot + 1
    hc = hist[c]
    b = 0
    while b + 4 <= nb:  # four cases at a time, one pair
        for p in range(npair):
            k = ker[p]
            h = hc[kpj[p]]
            a0 = a1 = a2 = a3 = 0.0
            for i in range(nlag):
                a0 += k[i] * h[s + i, b]
                a1 += k[i] * h[s + i, b + 1]
                a2 += k[i] * h[s + i, b + 2]
                a3 += k[i] * h[s + i, b + 3]
            acc[p, b] = a0
            acc[p, b + 1] = a1
            acc[p, b + 2] = a2
            acc[p, b + 3] = a3
        b += 4
    while b < nb:  # the other cases one by one, four pairs at a time
        p = 0
        while p + 4 <= npair:
            k0, k1, k2, k3 = ker[p], ker[p + 1], ker[p + 2], ker[p + 3]
            h0, h1, h2, h3 = hc[kpj[p]], hc[kpj[p + 1]], hc[kpj[p + 2]], hc[kpj[p + 3]]
            a0 = a1 = a2 = a3 = 0.0
            for i in range(nlag):
                a0 += k0[i] * h0[s + i, b]
                a1 += k1[i] * h1[s + i, b]
                a2 += k2[i] * h2[s + i, b]
                a3 += k3[i] * h3[s + i, b]
            acc[p, b] = a0
            acc[p + 1, b] = a1
            acc[p + 2, b] = a2
            acc[p + 3, b] = a3
            p += 4
        while p < npair:
            k = ker[p]
            h = hc[kpj[p]]
            a0 = 0.0
            for i in range(nlag):
                a0 += k[i] * h[s + i, b]
            acc[p, b] = a0
            p += 1
        b += 1
    for p in range(npair):
        for b in range(nb):
            out[b, kpi[p]] -= acc[p, b]


@numba.njit(cache=True)
def _predict_fairleads(q, v, fair, dt, r_out, v_out):  # pragma: no cover - numba
    """Fairlead positions extrapolated to ``t + dt`` and velocities, ``(B, 3, 3)``."""
    _fairlead_motion(q, v, fair, r_out, v_out)
    for b in range(q.shape[0]):
        for l in range(fair.shape[0]):
            for c in range(3):
                r_out[b, l, c] += dt * v_out[b, l, c]


@numba.njit(cache=True)
def _run_dynamic(n, dt, nsub, state, body, rad, strips, rotor, wave, rec, lines):  # pragma: no cover
    """The whole record with dynamic lines, in one compiled loop (no per-step dispatch).

    Each step is exactly the Python loop of ``integrate``: predict the fairleads, advance the
    lines (the compiled step ``moorlife.mooring.dynamic.step_lines`` of ``lines.state`` with the
    model's ``lines.kernel``, ``nsub`` substeps), then :func:`_advance` the platform.

    With the BDF2 scheme and lanes (:class:`DynamicLines`), the first step is taken as above (it
    starts the BDF2 history), and the others by ``moorlife.mooring.lanes.step_lanes``: the same
    bits, every line of the batch at once. Empty lanes keep the one-line step throughout.
    """
    ls, kernel, lanes, work = lines.state, lines.kernel, lines.lanes, lines.work
    moor = MooringLink(True, ls.forces, ls.tension)
    fast = kernel.scheme == 1 and lanes.nodes.shape[0] > 0
    fp, fv = state.fairlead_position, state.fairlead_velocity
    for j in range(n):
        _predict_fairleads(state.displacement, state.velocity, body.fairleads, dt, fp, fv)
        if fast and j > 0:
            _step_lanes(lanes, fp, fv, dt, nsub, kernel.params, work, ls.forces, ls.tension)
        else:
            _step_dynamic_lines(ls, fp, fv, dt, nsub, kernel)
            if fast:
                _pack_lanes(ls, lanes)
        _advance(j, dt, state, body, rad, strips, rotor, wave, moor, rec)
    if fast and n > 1:
        _unpack_lanes(lanes, ls)


@numba.njit(cache=True)
def _run_quasistatic(n, dt, state, body, rad, strips, rotor, wave, rec, lines, anchors, table):  # pragma: no cover
    """The whole record with quasi-static lines, in one compiled loop (see :func:`_run_dynamic`).

    The lines are ``moorlife.mooring.quasistatic.step_lines`` of the state ``lines`` on the
    force table ``table``.
    """
    moor = MooringLink(True, lines.forces, lines.tension)
    for j in range(n):
        _predict_fairleads(
            state.displacement, state.velocity, body.fairleads, dt, state.fairlead_position, state.fairlead_velocity
        )
        _step_quasistatic_lines(lines, state.fairlead_position, anchors, table)
        _advance(j, dt, state, body, rad, strips, rotor, wave, moor, rec)
