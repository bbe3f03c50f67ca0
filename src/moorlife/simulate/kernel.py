"""The Numba kernels of the coupled simulator: rigid-body kinematics, loads, RK4 step, record loops."""

from __future__ import annotations

import math

import numba
import numpy as np

from moorlife.mooring.dynamic import _step_batch as _dyn_step_batch
from moorlife.mooring.quasistatic import _fairlead_forces as _qs_fairlead_forces

__all__ = ["rotation_matrix"]


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
    return (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
            sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
            -sp, cp * sr, cp * cr)


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


@numba.njit(cache=True)
def _rhs(b, t_frac, j, q, v, xr, zf, fmoor6, force, wind, wdir, kin, kin_every,
         minv, K, D, ra_ptr, ra_idx, ra_val, rb, rc,
         spos, saxis, scdn, scda, hub, tv, tf, fa, fb, fc, fd,
         dq, dv, dxr, dzf, F):  # pragma: no cover - numba
    """Time derivative of one case's state at ``t = (j + t_frac) dt`` (``F (6,)`` scratch)."""
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
    nr = xr.shape[0]
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
    # Morison drag on the relative velocity; strips along the last axis (unit stride, SIMD)
    ns = spos.shape[1]
    if ns > 0:
        tk = (j + t_frac) / kin_every
        jk = int(tk)
        wk = tk - jk
        k0 = kin[b, jk]
        k1 = kin[b, jk + 1]
        vx, vy, vz = v[0], v[1], v[2]
        wx, wy, wz = v[3], v[4], v[5]
        f0 = f1 = f2 = m3 = m4 = m5 = 0.0
        for s in range(ns):
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
            f0 += fx
            f1 += fy
            f2 += fz
            m3 += py * fz - pz * fy
            m4 += pz * fx - px * fz
            m5 += px * fy - py * fx
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
def _rk4_step(j, dt, q, v, xr, zf, fmoor6, force, wind, wdir, kin, kin_every,
              minv, K, D, ra_ptr, ra_idx, ra_val, rb, rc,
              spos, saxis, scdn, scda, hub, tv, tf, fa, fb, fc, fd, acc_out):  # pragma: no cover
    """Advance every case of the batch from step ``j`` to ``j + 1`` (classical RK4, in place).

    ``acc_out (B, 6)`` receives the accelerations at the start of the step.
    """
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
            _rhs(b, frac, j, ys[0:6], ys[6:12], ys[12:12 + nr], ys[12 + nr:ny], fmoor6, force, wind, wdir,
                 kin, kin_every, minv, K, D, ra_ptr, ra_idx, ra_val, rb, rc, spos, saxis, scdn, scda, hub,
                 tv, tf, fa, fb, fc, fd,
                 k[stage, 0:6], k[stage, 6:12], k[stage, 12:12 + nr], k[stage, 12 + nr:ny], F)
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
def _advance(j, i, dt, q, v, xr, zf, f_prev, f_new, coupled, static, fair, ten, motion, accel, tension, fmoor6, acc,
             hist, stride, ker, kpi, kpj,
             force, wind, wdir, kin, kin_every, minv, K, D, ra_ptr, ra_idx, ra_val, rb, rc,
             spos, saxis, scdn, scda, hub, tv, tf, fa, fb, fc, fd):  # pragma: no cover - numba
    """One coupled step ``j -> j + 1`` of the batch, with recording (kept sample ``i``).

    The load held constant over the step (``fmoor6``) is the mooring force, the trim load and,
    with a kernel, the radiation convolution. The platform is driven by the mean of the
    mooring forces at the start (``f_prev``) and at the predicted end (``f_new``); ``f_prev``
    then takes ``f_new``. ``ten`` is the line tension at ``t_{j+1}`` (kept as sample ``i + 1``).
    ``hist (B, stride, 6, 2 nlag)`` is the velocity history of the convolution (:func:`_convolve`).
    """
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
    if ker.shape[1] > 0:
        _convolve(j, stride, v, hist, ker, kpi, kpj, fmoor6)
    if i >= 0:
        for b in range(nb):
            for d in range(6):
                motion[b, d, i] = q[b, d]
    _rk4_step(j, dt, q, v, xr, zf, fmoor6, force, wind, wdir, kin, kin_every, minv, K, D, ra_ptr, ra_idx,
              ra_val, rb, rc, spos, saxis, scdn, scda, hub, tv, tf, fa, fb, fc, fd, acc)
    if i >= 0:
        hx, hy, hz = hub[0], hub[1], hub[2]
        for b in range(nb):
            accel[b, 0, i] = acc[b, 0] + acc[b, 4] * hz - acc[b, 5] * hy
            accel[b, 1, i] = acc[b, 1] + acc[b, 5] * hx - acc[b, 3] * hz
            accel[b, 2, i] = acc[b, 2] + acc[b, 3] * hy - acc[b, 4] * hx


@numba.njit(cache=True)
def _convolve(j, stride, v, hist, ker, kpi, kpj, out):  # pragma: no cover - numba
    """Subtract the radiation convolution ``sum_k K[k] v(t_j - k stride dt)`` from ``out (B, 6)``.

    ``ker (npairs, nlag)`` holds the kernel with the trapezoid weights and its step ``stride dt``
    folded in, oldest lag first (``ker[p, nlag - 1 - k] = w_k K_p(k stride dt)``).
    ``hist (B, stride, 6, 2 nlag)`` is the velocity history of every step, split by the
    step's residue modulo ``stride`` and stored twice (slot and slot + nlag) so that the
    ``nlag`` samples of a convolution are one contiguous window: each pair is a unit-stride
    dot product, which the compiler vectorises. ``v`` is stored first.
    """
    npair, nlag = ker.shape
    c = j % stride
    slot = (j // stride) % nlag
    for b in range(v.shape[0]):
        for d in range(6):
            hist[b, c, d, slot] = v[b, d]
            hist[b, c, d, slot + nlag] = v[b, d]
    for p in range(npair):  # one kernel row at a time, for every case (it stays in cache)
        k = ker[p]
        for b in range(v.shape[0]):
            h = hist[b, c, kpj[p]]
            acc = 0.0
            for i in range(nlag):
                acc += k[i] * h[slot + 1 + i]
            out[b, kpi[p]] -= acc


@numba.njit(cache=True)
def _predict_fairleads(q, v, fair, dt, r_out, v_out):  # pragma: no cover - numba
    """Fairlead positions extrapolated to ``t + dt`` and velocities, ``(B, 3, 3)``."""
    _fairlead_motion(q, v, fair, r_out, v_out)
    for b in range(q.shape[0]):
        for l in range(fair.shape[0]):
            for c in range(3):
                r_out[b, l, c] += dt * v_out[b, l, c]


@numba.njit(cache=True)
def _run_dynamic(n, j0, dt, fair, r_f, v_f, mr, mv, mrp, mvp, mhist, nsub, scheme, mparams, mwork, forces, ten,
                 q, v, xr, zf, f_prev, static, motion, accel, tension, fmoor6, acc, hist, stride, ker, kpi, kpj,
                 *platform):  # pragma: no cover - numba
    """The whole record with dynamic lines, in one compiled loop (no per-step dispatch).

    Each step is exactly the Python loop of :func:`integrate`: predict the fairleads, advance
    the lines (``moorlife.mooring.dynamic._step_batch``, whose ``forces`` and ``ten`` are the
    state's arrays), then :func:`_advance` the platform.
    """
    for j in range(n):
        _predict_fairleads(q, v, fair, dt, r_f, v_f)
        _dyn_step_batch(mr, mv, mrp, mvp, mhist, r_f, v_f, dt, nsub, scheme, mparams, mwork, forces, ten)
        _advance(j, j - j0, dt, q, v, xr, zf, f_prev, forces, True, static, fair, ten, motion, accel, tension,
                 fmoor6, acc, hist, stride, ker, kpi, kpj, *platform)


@numba.njit(cache=True)
def _run_quasistatic(n, j0, dt, fair, r_f, v_f, anchors, table, forces, ten,
                     q, v, xr, zf, f_prev, static, motion, accel, tension, fmoor6, acc, hist, stride, ker, kpi, kpj,
                     *platform):  # pragma: no cover - numba
    """The whole record with quasi-static lines, in one compiled loop (see :func:`_run_dynamic`)."""
    for j in range(n):
        _predict_fairleads(q, v, fair, dt, r_f, v_f)
        _qs_fairlead_forces(r_f, anchors, *table, forces, ten)
        _advance(j, j - j0, dt, q, v, xr, zf, f_prev, forces, True, static, fair, ten, motion, accel, tension,
                 fmoor6, acc, hist, stride, ker, kpi, kpj, *platform)
