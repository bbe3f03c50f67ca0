"""Lumped-mass line kernels: node forces, the parameter vector and the work buffer.

The numerics that :mod:`moorlife.mooring.dynamic` steps in time: the net force on every node
(tension, internal damping, weight, drag, seabed contact and friction) with the pieces of the
implicit matrix, the fairlead end force, and the flat work buffer of one line step.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

# indices into the parameter vector of the kernels
_N, _L0, _EA, _CINT, _MLEN, _D, _RHO, _WLEN, _CDN, _CDT, _CAN, _CAT, _KB, _CB, _MU, _VSLIP, _ZBED, _BAND = range(18)
_NPAR = 18


# --------------------------------------------------------------------------- 3x3 helpers
@njit(cache=True, inline="always", error_model="numpy")
def _inv3(A, out):
    a, b, c = A[0, 0], A[0, 1], A[0, 2]
    d, e, f = A[1, 0], A[1, 1], A[1, 2]
    g, h, i = A[2, 0], A[2, 1], A[2, 2]
    c0 = e * i - f * h
    c1 = f * g - d * i
    c2 = d * h - e * g
    det = a * c0 + b * c1 + c * c2
    r = 1.0 / det
    out[0, 0] = c0 * r
    out[0, 1] = (c * h - b * i) * r
    out[0, 2] = (b * f - c * e) * r
    out[1, 0] = c1 * r
    out[1, 1] = (a * i - c * g) * r
    out[1, 2] = (c * d - a * f) * r
    out[2, 0] = c2 * r
    out[2, 1] = (b * g - a * h) * r
    out[2, 2] = (a * e - b * d) * r


# --------------------------------------------------------------------------- forces
@njit(cache=True, inline="always", error_model="numpy")
def _node_forces(r, v, p, hb, jac, ws):
    """Net node forces and, if ``jac``, the pieces of the implicit matrix.

    ``ws = (F, segf, sq, sa, sg, tang, am, bm, C, Kz)``: net node force (N+1, 3); per segment
    the axial force, unit vector, axial-minus-geometric and geometric stiffness (N/m); per
    node the unit tangent, the mass matrix ``am I + bm t t'`` and, for the matrix, the local
    damping matrix C = -dF/dv (drag, seabed, friction) and seabed stiffness Kz.
    """
    F, segf, sq, sa, sg, tang, am, bm, C, Kz = ws
    N = int(p[_N])
    l0 = p[_L0]
    cint = p[_CINT]
    kax = p[_EA] / l0
    for s in range(N):
        dx = r[s + 1, 0] - r[s, 0]
        dy = r[s + 1, 1] - r[s, 1]
        dz = r[s + 1, 2] - r[s, 2]
        l = math.sqrt(dx * dx + dy * dy + dz * dz)
        qx, qy, qz = dx / l, dy / l, dz / l
        ldot = qx * (v[s + 1, 0] - v[s, 0]) + qy * (v[s + 1, 1] - v[s, 1]) + qz * (v[s + 1, 2] - v[s, 2])
        if l > l0:
            T = kax * (l - l0)
            sg[s] = T / l
            sa[s] = kax - T / l
        else:
            T = 0.0
            sg[s] = 0.0
            sa[s] = 0.0
        segf[s] = T + cint * ldot
        sq[s, 0] = qx
        sq[s, 1] = qy
        sq[s, 2] = qz
    A = 0.25 * math.pi * p[_D] * p[_D]
    rho = p[_RHO]
    cdn = 0.5 * rho * p[_CDN] * p[_D]
    cdt = 0.5 * rho * p[_CDT] * math.pi * p[_D]
    zbed = p[_ZBED]
    mu = p[_MU]
    for i in range(N + 1):
        ln = l0 if (0 < i < N) else 0.5 * l0
        fx = fy = fz = 0.0
        if i < N:
            fx += segf[i] * sq[i, 0]
            fy += segf[i] * sq[i, 1]
            fz += segf[i] * sq[i, 2]
        if i > 0:
            fx -= segf[i - 1] * sq[i - 1, 0]
            fy -= segf[i - 1] * sq[i - 1, 1]
            fz -= segf[i - 1] * sq[i - 1, 2]
        if i == 0:
            tx, ty, tz = sq[0, 0], sq[0, 1], sq[0, 2]
        elif i == N:
            tx, ty, tz = sq[N - 1, 0], sq[N - 1, 1], sq[N - 1, 2]
        else:
            tx = r[i + 1, 0] - r[i - 1, 0]
            ty = r[i + 1, 1] - r[i - 1, 1]
            tz = r[i + 1, 2] - r[i - 1, 2]
            tn = 1.0 / math.sqrt(tx * tx + ty * ty + tz * tz)
            tx, ty, tz = tx * tn, ty * tn, tz * tn
        tang[i, 0] = tx
        tang[i, 1] = ty
        tang[i, 2] = tz
        fz -= p[_WLEN] * ln
        am[i] = p[_MLEN] * ln + rho * A * ln * p[_CAN]
        bm[i] = rho * A * ln * (p[_CAT] - p[_CAN])
        vx, vy, vz = v[i, 0], v[i, 1], v[i, 2]
        vt = vx * tx + vy * ty + vz * tz
        px, py, pz = vx - vt * tx, vy - vt * ty, vz - vt * tz
        vp = math.sqrt(px * px + py * py + pz * pz)
        avt = abs(vt)
        cn = cdn * ln
        ct = cdt * ln
        fx -= cn * vp * px + ct * avt * vt * tx
        fy -= cn * vp * py + ct * avt * vt * ty
        fz -= cn * vp * pz + ct * avt * vt * tz
        if jac:
            # C = cn (|vp| (I - tt') + vp vp' / |vp|) + 2 ct |vt| tt'
            ip = cn / vp if vp > 0.0 else 0.0
            ctt = 2.0 * ct * avt - cn * vp
            cI = cn * vp
            C[i, 0, 0] = cI + ctt * tx * tx + ip * px * px
            C[i, 1, 1] = cI + ctt * ty * ty + ip * py * py
            C[i, 2, 2] = cI + ctt * tz * tz + ip * pz * pz
            c01 = ctt * tx * ty + ip * px * py
            c02 = ctt * tx * tz + ip * px * pz
            c12 = ctt * ty * tz + ip * py * pz
            C[i, 0, 1] = c01
            C[i, 1, 0] = c01
            C[i, 0, 2] = c02
            C[i, 2, 0] = c02
            C[i, 1, 2] = c12
            C[i, 2, 1] = c12
            Kz[i] = 0.0
            # the matrix sees the seabed spring-damper already within a band above it (and
            # the distance a descending node covers in a step), so that a landing node does
            # not bounce (W-method: only the matrix changes, not the forces)
            if r[i, 2] < zbed + p[_BAND] + hb * max(-vz, 0.0):
                area = p[_D] * ln
                Kz[i] = p[_KB] * area
                C[i, 2, 2] += p[_CB] * area
        if r[i, 2] < zbed:
            area = p[_D] * ln
            Bz = ((zbed - r[i, 2]) * p[_KB] - vz * p[_CB]) * area
            fz += Bz
            if mu > 0.0:
                fmax = mu * abs(Bz)
                vh = math.sqrt(vx * vx + vy * vy)
                if vh > 0.0:
                    ff = fmax * min(vh / p[_VSLIP], 1.0)
                    fx -= ff * vx / vh
                    fy -= ff * vy / vh
                if jac:
                    cf = fmax / max(vh, p[_VSLIP])
                    C[i, 0, 0] += cf
                    C[i, 1, 1] += cf
        F[i, 0] = fx
        F[i, 1] = fy
        F[i, 2] = fz


@njit(cache=True, error_model="numpy")
def _end_force(r, v, p, out):
    """Net force of the fairlead node (N) without its inertia, i.e. the force on the platform."""
    N = int(p[_N])
    l0 = p[_L0]
    dx = r[N, 0] - r[N - 1, 0]
    dy = r[N, 1] - r[N - 1, 1]
    dz = r[N, 2] - r[N - 1, 2]
    l = math.sqrt(dx * dx + dy * dy + dz * dz)
    qx, qy, qz = dx / l, dy / l, dz / l
    ldot = qx * (v[N, 0] - v[N - 1, 0]) + qy * (v[N, 1] - v[N - 1, 1]) + qz * (v[N, 2] - v[N - 1, 2])
    T = p[_EA] / l0 * (l - l0) if l > l0 else 0.0
    f = T + p[_CINT] * ldot
    ln = 0.5 * l0
    vx, vy, vz = v[N, 0], v[N, 1], v[N, 2]
    vt = vx * qx + vy * qy + vz * qz
    px, py, pz = vx - vt * qx, vy - vt * qy, vz - vt * qz
    vp = math.sqrt(px * px + py * py + pz * pz)
    cn = 0.5 * p[_RHO] * p[_CDN] * p[_D] * ln
    ct = 0.5 * p[_RHO] * p[_CDT] * math.pi * p[_D] * ln * abs(vt)
    out[0] = -f * qx - cn * vp * px - ct * vt * qx
    out[1] = -f * qy - cn * vp * py - ct * vt * qy
    out[2] = -f * qz - cn * vp * pz - ct * vt * qz - p[_WLEN] * ln
    if r[N, 2] < p[_ZBED]:
        out[2] += ((p[_ZBED] - r[N, 2]) * p[_KB] - vz * p[_CB]) * p[_D] * ln


def _work_size(N: int) -> int:
    n1 = N + 1
    stage = 3 * n1 + N + 3 * N + N + N + 3 * n1 + n1 + n1 + 9 * n1 + n1
    return 2 * stage + 9 * N + 9 * n1 + 9 + 9 + 7 * 3 * n1 + 3 + 6 * 3


@njit(cache=True, error_model="numpy")
def _take(buf, o, n):
    return buf[o : o + n], o + n


@njit(cache=True, error_model="numpy")
def _stage_views(buf, o, N):
    n1 = N + 1
    F, o = _take(buf, o, 3 * n1)
    segf, o = _take(buf, o, N)
    sq, o = _take(buf, o, 3 * N)
    sa, o = _take(buf, o, N)
    sg, o = _take(buf, o, N)
    tang, o = _take(buf, o, 3 * n1)
    am, o = _take(buf, o, n1)
    bm, o = _take(buf, o, n1)
    C, o = _take(buf, o, 9 * n1)
    Kz, o = _take(buf, o, n1)
    ws = (
        F.reshape((n1, 3)),
        segf,
        sq.reshape((N, 3)),
        sa,
        sg,
        tang.reshape((n1, 3)),
        am,
        bm,
        C.reshape((n1, 3, 3)),
        Kz,
    )
    return ws, o


@njit(cache=True, error_model="numpy")
def _views(buf, N):
    """Work arrays of one line step as views into one flat buffer (see :func:`_work_size`).

    ``(stage1, stage2, S, Winv, D, tmpm, rhs, kx1, kv1, kx2, kv2, r2, v2, tmp3)`` and the
    six 3-vectors used by :func:`_step_batch`. One flat buffer keeps the dispatch of the
    numba entry point cheap (a few plain arrays instead of nested tuples).
    """
    n1 = N + 1
    ws1, o = _stage_views(buf, 0, N)
    ws2, o = _stage_views(buf, o, N)
    S, o = _take(buf, o, 9 * N)
    Winv, o = _take(buf, o, 9 * n1)
    D, o = _take(buf, o, 9)
    tmpm, o = _take(buf, o, 9)
    rhs, o = _take(buf, o, 3 * n1)
    kx1, o = _take(buf, o, 3 * n1)
    kv1, o = _take(buf, o, 3 * n1)
    kx2, o = _take(buf, o, 3 * n1)
    kv2, o = _take(buf, o, 3 * n1)
    r2, o = _take(buf, o, 3 * n1)
    v2, o = _take(buf, o, 3 * n1)
    tmp3, o = _take(buf, o, 3)
    vec, o = _take(buf, o, 18)
    w = (
        ws1,
        ws2,
        S.reshape((N, 3, 3)),
        Winv.reshape((n1, 3, 3)),
        D.reshape((3, 3)),
        tmpm.reshape((3, 3)),
        rhs.reshape((n1, 3)),
        kx1.reshape((n1, 3)),
        kv1.reshape((n1, 3)),
        kx2.reshape((n1, 3)),
        kv2.reshape((n1, 3)),
        r2.reshape((n1, 3)),
        v2.reshape((n1, 3)),
        tmp3,
    )
    return w, vec.reshape((6, 3))


def _workspace(N: int) -> np.ndarray:
    """Flat work buffer of one line step, allocated once per model."""
    return np.zeros(_work_size(N))
