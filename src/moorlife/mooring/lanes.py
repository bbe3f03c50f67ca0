"""The BDF2 line step of many lines at once: every line of a batch is one lane of a vector.

:func:`moorlife.mooring.dynamic.step_lines` steps one line at a time (node, then component):
its arithmetic is scalar, and its loops are too short and too branchy for the compiler to
vectorise. Here the same step runs on every line of a batch together, with the lines along the
last axis of every array (``(N + 1, 3, nl)`` for the nodes). Each operation of the scalar
step becomes a loop over the lines of unit stride that the compiler turns into SIMD
instructions; the per-line branches (slack segments, seabed contact, friction) become masked
selects.

Every lane does exactly the floating-point operations of the scalar step, in the same order
(no reassociation, no fused multiply-add), so the two give the same bits: the scalar step is
the strict reference, this one the fast path (``tests/test_mooring_lanes.py``). Only the
BDF2 step of a constant step length is here; the ROS2 start of :func:`step_lines` stays scalar
(:func:`moorlife.simulate.kernel._run_dynamic` takes the first step with it).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from moorlife.mooring.line_forces import (
    _BAND,
    _CAN,
    _CAT,
    _CB,
    _CDN,
    _CDT,
    _CINT,
    _D,
    _EA,
    _KB,
    _L0,
    _MLEN,
    _MU,
    _N,
    _RHO,
    _VSLIP,
    _WLEN,
    _ZBED,
)

__all__ = ["LaneState", "LaneWork", "lane_state", "lane_work", "pack", "unpack", "step_lanes"]


class LaneState(NamedTuple):
    """Node state of ``nl`` lines, the lines last: ``(N + 1, 3, nl)`` each (see ``DynamicState``)."""

    r: np.ndarray
    v: np.ndarray
    r_prev: np.ndarray
    v_prev: np.ndarray


class LaneWork(NamedTuple):
    """Scratch of :func:`step_lanes` for ``nl`` lines of ``N`` segments (lines last)."""

    F: np.ndarray  # (N + 1, 3, nl) net node force
    segf: np.ndarray  # (N, nl) segment axial force
    sq: np.ndarray  # (N, 3, nl) segment unit vector
    sa: np.ndarray  # (N, nl) axial minus geometric stiffness
    sg: np.ndarray  # (N, nl) geometric stiffness
    tang: np.ndarray  # (N + 1, 3, nl) node tangent
    am: np.ndarray  # (N + 1,) isotropic node mass (the same for every line)
    bm: np.ndarray  # (N + 1,) axial minus normal added mass
    C: np.ndarray  # (N + 1, 3, 3, nl) local damping matrix
    Kz: np.ndarray  # (N + 1, nl) seabed stiffness in the matrix
    S: np.ndarray  # (N, 3, 3, nl) coupling blocks
    Winv: np.ndarray  # (N + 1, 3, 3, nl) inverted pivots
    D: np.ndarray  # (3, 3, nl) pivot
    rhs: np.ndarray  # (N + 1, 3, nl)
    xb: np.ndarray  # (N + 1, 3, nl) BDF2 position part
    dv: np.ndarray  # (N + 1, 3, nl) BDF2 velocity part, then the solution
    kx: np.ndarray  # (N + 1, 3, nl) position residual
    r2: np.ndarray  # (N + 1, 3, nl) predicted positions
    v2: np.ndarray  # (N + 1, 3, nl) predicted velocities
    fair: np.ndarray  # (4, 3, nl) start position and velocity, path position and velocity


def lane_state(nl: int, N: int) -> LaneState:
    """An empty lane state for ``nl`` lines of ``N`` segments."""
    return LaneState(*(np.zeros((N + 1, 3, nl)) for _ in range(4)))


def lane_work(nl: int, N: int) -> LaneWork:
    """The scratch of :func:`step_lanes` for ``nl`` lines of ``N`` segments."""
    n1 = N + 1
    return LaneWork(
        F=np.zeros((n1, 3, nl)),
        segf=np.zeros((N, nl)),
        sq=np.zeros((N, 3, nl)),
        sa=np.zeros((N, nl)),
        sg=np.zeros((N, nl)),
        tang=np.zeros((n1, 3, nl)),
        am=np.zeros(n1),
        bm=np.zeros(n1),
        C=np.zeros((n1, 3, 3, nl)),
        Kz=np.zeros((n1, nl)),
        S=np.zeros((N, 3, 3, nl)),
        Winv=np.zeros((n1, 3, 3, nl)),
        D=np.zeros((3, 3, nl)),
        rhs=np.zeros((n1, 3, nl)),
        xb=np.zeros((n1, 3, nl)),
        dv=np.zeros((n1, 3, nl)),
        kx=np.zeros((n1, 3, nl)),
        r2=np.zeros((n1, 3, nl)),
        v2=np.zeros((n1, 3, nl)),
        fair=np.zeros((4, 3, nl)),
    )


@njit(cache=True, error_model="numpy")
def pack(state, lanes):  # pragma: no cover - numba
    """Copy the node state of a ``DynamicState`` ``(B, L, N + 1, 3)`` into ``lanes`` (line ``b L + k``)."""
    nb, nl = state.r.shape[0], state.r.shape[1]
    for b in range(nb):
        for k in range(nl):
            m = b * nl + k
            for i in range(state.r.shape[2]):
                for a in range(3):
                    lanes.r[i, a, m] = state.r[b, k, i, a]
                    lanes.v[i, a, m] = state.v[b, k, i, a]
                    lanes.r_prev[i, a, m] = state.r_prev[b, k, i, a]
                    lanes.v_prev[i, a, m] = state.v_prev[b, k, i, a]


@njit(cache=True, error_model="numpy")
def unpack(lanes, state):  # pragma: no cover - numba
    """Copy ``lanes`` back into the node state of a ``DynamicState`` (the inverse of :func:`pack`)."""
    nb, nl = state.r.shape[0], state.r.shape[1]
    for b in range(nb):
        for k in range(nl):
            m = b * nl + k
            for i in range(state.r.shape[2]):
                for a in range(3):
                    state.r[b, k, i, a] = lanes.r[i, a, m]
                    state.v[b, k, i, a] = lanes.v[i, a, m]
                    state.r_prev[b, k, i, a] = lanes.r_prev[i, a, m]
                    state.v_prev[b, k, i, a] = lanes.v_prev[i, a, m]


@njit(cache=True, inline="always", error_model="numpy")
def _node_forces(r, v, p, hb, w):  # pragma: no cover - numba
    """``line_forces._node_forces`` with ``jac`` on every lane (the same operations per lane)."""
    F, segf, sq, sa, sg, tang, am, bm, C, Kz = w.F, w.segf, w.sq, w.sa, w.sg, w.tang, w.am, w.bm, w.C, w.Kz
    nl = r.shape[2]
    N = int(p[_N])
    l0 = p[_L0]
    cint = p[_CINT]
    kax = p[_EA] / l0
    for s in range(N):
        for m in range(nl):
            dx = r[s + 1, 0, m] - r[s, 0, m]
            dy = r[s + 1, 1, m] - r[s, 1, m]
            dz = r[s + 1, 2, m] - r[s, 2, m]
            l = math.sqrt(dx * dx + dy * dy + dz * dz)
            qx, qy, qz = dx / l, dy / l, dz / l
            ldot = (
                qx * (v[s + 1, 0, m] - v[s, 0, m])
                + qy * (v[s + 1, 1, m] - v[s, 1, m])
                + qz * (v[s + 1, 2, m] - v[s, 2, m])
            )
            T = kax * (l - l0) if l > l0 else 0.0
            sg[s, m] = T / l if l > l0 else 0.0
            sa[s, m] = kax - T / l if l > l0 else 0.0
            segf[s, m] = T + cint * ldot
            sq[s, 0, m] = qx
            sq[s, 1, m] = qy
            sq[s, 2, m] = qz
    A = 0.25 * math.pi * p[_D] * p[_D]
    rho = p[_RHO]
    cdn = 0.5 * rho * p[_CDN] * p[_D]
    cdt = 0.5 * rho * p[_CDT] * math.pi * p[_D]
    zbed = p[_ZBED]
    mu = p[_MU]
    kb, cb, band, vslip, dia, wlen = p[_KB], p[_CB], p[_BAND], p[_VSLIP], p[_D], p[_WLEN]
    fric = mu > 0.0
    for i in range(N + 1):
        ln = l0 if (0 < i < N) else 0.5 * l0
        am[i] = p[_MLEN] * ln + rho * A * ln * p[_CAN]
        bm[i] = rho * A * ln * (p[_CAT] - p[_CAN])
        # the net tension, and the unit tangent (the segment's at the ends)
        if i == 0:
            for m in range(nl):
                F[0, 0, m] = 0.0 + segf[0, m] * sq[0, 0, m]
                F[0, 1, m] = 0.0 + segf[0, m] * sq[0, 1, m]
                F[0, 2, m] = 0.0 + segf[0, m] * sq[0, 2, m]
                tang[0, 0, m] = sq[0, 0, m]
                tang[0, 1, m] = sq[0, 1, m]
                tang[0, 2, m] = sq[0, 2, m]
        elif i == N:
            for m in range(nl):
                F[N, 0, m] = 0.0 - segf[N - 1, m] * sq[N - 1, 0, m]
                F[N, 1, m] = 0.0 - segf[N - 1, m] * sq[N - 1, 1, m]
                F[N, 2, m] = 0.0 - segf[N - 1, m] * sq[N - 1, 2, m]
                tang[N, 0, m] = sq[N - 1, 0, m]
                tang[N, 1, m] = sq[N - 1, 1, m]
                tang[N, 2, m] = sq[N - 1, 2, m]
        else:
            for m in range(nl):
                F[i, 0, m] = 0.0 + segf[i, m] * sq[i, 0, m] - segf[i - 1, m] * sq[i - 1, 0, m]
                F[i, 1, m] = 0.0 + segf[i, m] * sq[i, 1, m] - segf[i - 1, m] * sq[i - 1, 1, m]
                F[i, 2, m] = 0.0 + segf[i, m] * sq[i, 2, m] - segf[i - 1, m] * sq[i - 1, 2, m]
                tx = r[i + 1, 0, m] - r[i - 1, 0, m]
                ty = r[i + 1, 1, m] - r[i - 1, 1, m]
                tz = r[i + 1, 2, m] - r[i - 1, 2, m]
                tn = 1.0 / math.sqrt(tx * tx + ty * ty + tz * tz)
                tang[i, 0, m] = tx * tn
                tang[i, 1, m] = ty * tn
                tang[i, 2, m] = tz * tn
        cn = cdn * ln
        ct = cdt * ln
        area = dia * ln
        kba = kb * area
        cba = cb * area
        wl = wlen * ln
        # weight, drag, seabed and friction, with their damping matrix: one select per branch
        for m in range(nl):
            tx, ty, tz = tang[i, 0, m], tang[i, 1, m], tang[i, 2, m]
            fx, fy, fz = F[i, 0, m], F[i, 1, m], F[i, 2, m] - wl
            vx, vy, vz = v[i, 0, m], v[i, 1, m], v[i, 2, m]
            vt = vx * tx + vy * ty + vz * tz
            px, py, pz = vx - vt * tx, vy - vt * ty, vz - vt * tz
            vp = math.sqrt(px * px + py * py + pz * pz)
            avt = abs(vt)
            fx -= cn * vp * px + ct * avt * vt * tx
            fy -= cn * vp * py + ct * avt * vt * ty
            fz -= cn * vp * pz + ct * avt * vt * tz
            ip = cn / vp if vp > 0.0 else 0.0
            ctt = 2.0 * ct * avt - cn * vp
            cI = cn * vp
            c00 = cI + ctt * tx * tx + ip * px * px
            c11 = cI + ctt * ty * ty + ip * py * py
            c22 = cI + ctt * tz * tz + ip * pz * pz
            rz = r[i, 2, m]
            near = rz < zbed + band + hb * max(-vz, 0.0)
            Kz[i, m] = kba if near else 0.0
            c22 = c22 + cba if near else c22
            below = rz < zbed
            Bz = ((zbed - rz) * kb - vz * cb) * area
            fz = fz + Bz if below else fz
            fmax = mu * abs(Bz)
            vh = math.sqrt(vx * vx + vy * vy)
            ff = fmax * min(vh / vslip, 1.0)
            slide = below and fric and vh > 0.0
            fx = fx - ff * vx / vh if slide else fx
            fy = fy - ff * vy / vh if slide else fy
            cf = fmax / max(vh, vslip)
            c00 = c00 + cf if below and fric else c00
            c11 = c11 + cf if below and fric else c11
            C[i, 0, 0, m] = c00
            C[i, 1, 1, m] = c11
            C[i, 2, 2, m] = c22
            C[i, 0, 1, m] = C[i, 1, 0, m] = ctt * tx * ty + ip * px * py
            C[i, 0, 2, m] = C[i, 2, 0, m] = ctt * tx * tz + ip * px * pz
            C[i, 1, 2, m] = C[i, 2, 1, m] = ctt * ty * tz + ip * py * pz
            F[i, 0, m] = fx
            F[i, 1, m] = fy
            F[i, 2, m] = fz


@njit(cache=True, inline="always", error_model="numpy")
def _factor(w, N, cs, cg, cz):  # pragma: no cover - numba
    """``dynamic._factor`` on every lane: coupling blocks and inverted block-Thomas pivots."""
    sq, sa, sg, tang, am, bm, C, Kz, S, Winv, D = w.sq, w.sa, w.sg, w.tang, w.am, w.bm, w.C, w.Kz, w.S, w.Winv, w.D
    nl = sq.shape[2]
    for s in range(N):
        for a in range(3):
            for b in range(3):
                for m in range(nl):
                    S[s, a, b, m] = (cs + cg * sa[s, m]) * sq[s, a, m] * sq[s, b, m]
        for a in range(3):
            for m in range(nl):
                S[s, a, a, m] += cg * sg[s, m]
    for i in range(1, N):
        for a in range(3):
            for b in range(3):
                for m in range(nl):
                    D[a, b, m] = (
                        bm[i] * tang[i, a, m] * tang[i, b, m] + cz * C[i, a, b, m] + S[i - 1, a, b, m] + S[i, a, b, m]
                    )
            for m in range(nl):
                D[a, a, m] += am[i]
        for m in range(nl):
            D[2, 2, m] += cg * Kz[i, m]
        if i > 1:
            j = i - 1
            for m in range(nl):
                al = cs + cg * sa[j, m]
                be = cg * sg[j, m]
                q0, q1, q2 = sq[j, 0, m], sq[j, 1, m], sq[j, 2, m]
                W = Winv[j]
                g0 = W[0, 0, m] * q0 + W[0, 1, m] * q1 + W[0, 2, m] * q2
                g1 = W[1, 0, m] * q0 + W[1, 1, m] * q1 + W[1, 2, m] * q2
                g2 = W[2, 0, m] * q0 + W[2, 1, m] * q1 + W[2, 2, m] * q2
                a2s = al * al * (q0 * g0 + q1 * g1 + q2 * g2)
                ab = al * be
                b2 = be * be
                D[0, 0, m] -= a2s * q0 * q0 + ab * (q0 * g0 + g0 * q0) + b2 * W[0, 0, m]
                D[0, 1, m] -= a2s * q0 * q1 + ab * (q0 * g1 + g0 * q1) + b2 * W[0, 1, m]
                D[0, 2, m] -= a2s * q0 * q2 + ab * (q0 * g2 + g0 * q2) + b2 * W[0, 2, m]
                D[1, 0, m] -= a2s * q1 * q0 + ab * (q1 * g0 + g1 * q0) + b2 * W[1, 0, m]
                D[1, 1, m] -= a2s * q1 * q1 + ab * (q1 * g1 + g1 * q1) + b2 * W[1, 1, m]
                D[1, 2, m] -= a2s * q1 * q2 + ab * (q1 * g2 + g1 * q2) + b2 * W[1, 2, m]
                D[2, 0, m] -= a2s * q2 * q0 + ab * (q2 * g0 + g2 * q0) + b2 * W[2, 0, m]
                D[2, 1, m] -= a2s * q2 * q1 + ab * (q2 * g1 + g2 * q1) + b2 * W[2, 1, m]
                D[2, 2, m] -= a2s * q2 * q2 + ab * (q2 * g2 + g2 * q2) + b2 * W[2, 2, m]
        out = Winv[i]
        for m in range(nl):
            a, b, c = D[0, 0, m], D[0, 1, m], D[0, 2, m]
            d, e, f = D[1, 0, m], D[1, 1, m], D[1, 2, m]
            g, h, k = D[2, 0, m], D[2, 1, m], D[2, 2, m]
            c0 = e * k - f * h
            c1 = f * g - d * k
            c2 = d * h - e * g
            det = a * c0 + b * c1 + c * c2
            rr = 1.0 / det
            out[0, 0, m] = c0 * rr
            out[0, 1, m] = (c * h - b * k) * rr
            out[0, 2, m] = (b * f - c * e) * rr
            out[1, 0, m] = c1 * rr
            out[1, 1, m] = (a * k - c * g) * rr
            out[1, 2, m] = (c * d - a * f) * rr
            out[2, 0, m] = c2 * rr
            out[2, 1, m] = (b * g - a * h) * rr
            out[2, 2, m] = (a * e - b * d) * rr


@njit(cache=True, inline="always", error_model="numpy")
def _solve_blocks(S, Winv, b, x, N):  # pragma: no cover - numba
    """``dynamic._solve_blocks`` on every lane."""
    nl = b.shape[2]
    for a in range(3):
        for m in range(nl):
            x[1, a, m] = b[1, a, m]
    for i in range(2, N):
        W, Si = Winv[i - 1], S[i - 1]
        for m in range(nl):
            t0 = W[0, 0, m] * x[i - 1, 0, m] + W[0, 1, m] * x[i - 1, 1, m] + W[0, 2, m] * x[i - 1, 2, m]
            t1 = W[1, 0, m] * x[i - 1, 0, m] + W[1, 1, m] * x[i - 1, 1, m] + W[1, 2, m] * x[i - 1, 2, m]
            t2 = W[2, 0, m] * x[i - 1, 0, m] + W[2, 1, m] * x[i - 1, 1, m] + W[2, 2, m] * x[i - 1, 2, m]
            x[i, 0, m] = b[i, 0, m] + Si[0, 0, m] * t0 + Si[0, 1, m] * t1 + Si[0, 2, m] * t2
            x[i, 1, m] = b[i, 1, m] + Si[1, 0, m] * t0 + Si[1, 1, m] * t1 + Si[1, 2, m] * t2
            x[i, 2, m] = b[i, 2, m] + Si[2, 0, m] * t0 + Si[2, 1, m] * t1 + Si[2, 2, m] * t2
    W = Winv[N - 1]
    for m in range(nl):
        t0, t1, t2 = x[N - 1, 0, m], x[N - 1, 1, m], x[N - 1, 2, m]
        x[N - 1, 0, m] = W[0, 0, m] * t0 + W[0, 1, m] * t1 + W[0, 2, m] * t2
        x[N - 1, 1, m] = W[1, 0, m] * t0 + W[1, 1, m] * t1 + W[1, 2, m] * t2
        x[N - 1, 2, m] = W[2, 0, m] * t0 + W[2, 1, m] * t1 + W[2, 2, m] * t2
    for i in range(N - 2, 0, -1):
        W, Si = Winv[i], S[i]
        for m in range(nl):
            t0 = x[i, 0, m] + Si[0, 0, m] * x[i + 1, 0, m] + Si[0, 1, m] * x[i + 1, 1, m] + Si[0, 2, m] * x[i + 1, 2, m]
            t1 = x[i, 1, m] + Si[1, 0, m] * x[i + 1, 0, m] + Si[1, 1, m] * x[i + 1, 1, m] + Si[1, 2, m] * x[i + 1, 2, m]
            t2 = x[i, 2, m] + Si[2, 0, m] * x[i + 1, 0, m] + Si[2, 1, m] * x[i + 1, 1, m] + Si[2, 2, m] * x[i + 1, 2, m]
            x[i, 0, m] = W[0, 0, m] * t0 + W[0, 1, m] * t1 + W[0, 2, m] * t2
            x[i, 1, m] = W[1, 0, m] * t0 + W[1, 1, m] * t1 + W[1, 2, m] * t2
            x[i, 2, m] = W[2, 0, m] * t0 + W[2, 1, m] * t1 + W[2, 2, m] * t2


@njit(cache=True, inline="always", error_model="numpy")
def _bdf2(ls, rf1, vf1, h, p, w):  # pragma: no cover - numba
    """``dynamic._bdf2_step`` on every lane; fairleads at ``rf1, vf1 (3, nl)`` at the step's end."""
    r, v, rp, vp = ls.r, ls.v, ls.r_prev, ls.v_prev
    r2, v2, xb, dv, kx, rhs = w.r2, w.v2, w.xb, w.dv, w.kx, w.rhs
    sq, sa, sg, Kz, tang, am, bm, F = w.sq, w.sa, w.sg, w.Kz, w.tang, w.am, w.bm, w.F
    nl = r.shape[2]
    N = int(p[_N])
    beta = 2.0 * h / 3.0
    for a in range(3):
        for m in range(nl):
            r2[0, a, m] = r[0, a, m]
            v2[0, a, m] = 0.0
            r2[N, a, m] = rf1[a, m]
            v2[N, a, m] = vf1[a, m]
            kx[0, a, m] = 0.0
            kx[N, a, m] = 0.0
    for i in range(1, N):
        for a in range(3):
            for m in range(nl):
                r2[i, a, m] = 2.0 * r[i, a, m] - rp[i, a, m]
                v2[i, a, m] = 2.0 * v[i, a, m] - vp[i, a, m]
                xb[i, a, m] = (4.0 * r[i, a, m] - rp[i, a, m]) / 3.0
                dv[i, a, m] = (4.0 * v[i, a, m] - vp[i, a, m]) / 3.0 - v2[i, a, m]
                kx[i, a, m] = xb[i, a, m] + beta * v2[i, a, m] - r2[i, a, m]
    _node_forces(r2, v2, p, h, w)
    _factor(w, N, beta * p[_CINT], beta * beta, beta)
    for i in range(1, N):
        for m in range(nl):
            # dynamic._kx_times: segment springs to both neighbours + seabed spring
            ax = kx[i - 1, 0, m] - kx[i, 0, m]
            ay = kx[i - 1, 1, m] - kx[i, 1, m]
            az = kx[i - 1, 2, m] - kx[i, 2, m]
            bx = kx[i + 1, 0, m] - kx[i, 0, m]
            by = kx[i + 1, 1, m] - kx[i, 1, m]
            bz = kx[i + 1, 2, m] - kx[i, 2, m]
            qa = sa[i - 1, m] * (sq[i - 1, 0, m] * ax + sq[i - 1, 1, m] * ay + sq[i - 1, 2, m] * az)
            qb = sa[i, m] * (sq[i, 0, m] * bx + sq[i, 1, m] * by + sq[i, 2, m] * bz)
            k0 = qa * sq[i - 1, 0, m] + sg[i - 1, m] * ax + qb * sq[i, 0, m] + sg[i, m] * bx
            k1 = qa * sq[i - 1, 1, m] + sg[i - 1, m] * ay + qb * sq[i, 1, m] + sg[i, m] * by
            k2 = qa * sq[i - 1, 2, m] + sg[i - 1, m] * az + qb * sq[i, 2, m] + sg[i, m] * bz - Kz[i, m] * kx[i, 2, m]
            t0, t1, t2 = tang[i, 0, m], tang[i, 1, m], tang[i, 2, m]
            d0, d1, d2 = dv[i, 0, m], dv[i, 1, m], dv[i, 2, m]
            tv = bm[i] * (t0 * d0 + t1 * d1 + t2 * d2)
            rhs[i, 0, m] = am[i] * d0 + tv * t0 + beta * (F[i, 0, m] + k0)
            rhs[i, 1, m] = am[i] * d1 + tv * t1 + beta * (F[i, 1, m] + k1)
            rhs[i, 2, m] = am[i] * d2 + tv * t2 + beta * (F[i, 2, m] + k2)
    _solve_blocks(w.S, w.Winv, rhs, dv, N)
    for i in range(1, N):
        for a in range(3):
            for m in range(nl):
                vn = v2[i, a, m] + dv[i, a, m]
                rp[i, a, m] = r[i, a, m]
                vp[i, a, m] = v[i, a, m]
                v[i, a, m] = vn
                r[i, a, m] = xb[i, a, m] + beta * vn
    for a in range(3):
        for m in range(nl):
            rp[N, a, m] = r[N, a, m]
            vp[N, a, m] = v[N, a, m]
            r[N, a, m] = rf1[a, m]
            v[N, a, m] = vf1[a, m]


@njit(cache=True, error_model="numpy")
def step_lanes(ls, r_new, v_new, dt, nsub, p, w, forces, tension):  # pragma: no cover - numba
    """Advance every line by ``dt`` with ``nsub`` BDF2 substeps (the history must be of that length).

    The bits of :func:`moorlife.mooring.dynamic.step_lines` with ``scheme`` 1 when every line's
    previous step was ``dt / nsub`` long.

    Parameters
    ----------
    ls : LaneState
        The lines, ``nl = B L`` lanes (line ``k`` of case ``b`` is lane ``b L + k``).
    r_new, v_new : numpy.ndarray, shape (B, L, 3)
        Fairlead positions and velocities at the end of the step (cubic Hermite path within it).
    dt : float
        Step, s.
    nsub : int
        Substeps.
    p : numpy.ndarray
        The line model's parameter vector (``LineModel.params``).
    w : LaneWork
        Scratch.
    forces : numpy.ndarray, shape (B, L, 3)
        Takes the fairlead forces on the platform at the end of the step, N.
    tension : numpy.ndarray, shape (B, L)
        Takes their magnitudes, N.

    Raises
    ------
    FloatingPointError
        On a non-finite fairlead tension.
    """
    r, v = ls.r, ls.v
    nb, nk = r_new.shape[0], r_new.shape[1]
    nl = r.shape[2]
    N = int(p[_N])
    fair = w.fair
    p0, v0, fb, vb = fair[0], fair[1], fair[2], fair[3]
    for a in range(3):
        for m in range(nl):
            p0[a, m] = r[N, a, m]
            v0[a, m] = v[N, a, m]
    h = dt / nsub
    for j in range(nsub):
        s = (j + 1) / nsub
        s2 = s * s
        s3 = s2 * s
        h00 = 2 * s3 - 3 * s2 + 1
        h10 = s3 - 2 * s2 + s
        h01 = -2 * s3 + 3 * s2
        h11 = s3 - s2
        d00 = (6 * s2 - 6 * s) / dt
        d10 = 3 * s2 - 4 * s + 1
        d01 = (-6 * s2 + 6 * s) / dt
        d11 = 3 * s2 - 2 * s
        for b in range(nb):
            for k in range(nk):
                m = b * nk + k
                for a in range(3):
                    p1, v1 = r_new[b, k, a], v_new[b, k, a]
                    fb[a, m] = h00 * p0[a, m] + h10 * dt * v0[a, m] + h01 * p1 + h11 * dt * v1
                    vb[a, m] = d00 * p0[a, m] + d10 * v0[a, m] + d01 * p1 + d11 * v1
        _bdf2(ls, fb, vb, h, p, w)
    # dynamic._end_force: the net force of the fairlead node without its inertia
    l0 = p[_L0]
    ln = 0.5 * l0
    cn = 0.5 * p[_RHO] * p[_CDN] * p[_D] * ln
    for b in range(nb):
        for k in range(nk):
            m = b * nk + k
            dx = r[N, 0, m] - r[N - 1, 0, m]
            dy = r[N, 1, m] - r[N - 1, 1, m]
            dz = r[N, 2, m] - r[N - 1, 2, m]
            l = math.sqrt(dx * dx + dy * dy + dz * dz)
            qx, qy, qz = dx / l, dy / l, dz / l
            ldot = (
                qx * (v[N, 0, m] - v[N - 1, 0, m])
                + qy * (v[N, 1, m] - v[N - 1, 1, m])
                + qz * (v[N, 2, m] - v[N - 1, 2, m])
            )
            T = p[_EA] / l0 * (l - l0) if l > l0 else 0.0
            f = T + p[_CINT] * ldot
            vx, vy, vz = v[N, 0, m], v[N, 1, m], v[N, 2, m]
            vt = vx * qx + vy * qy + vz * qz
            px, py, pz = vx - vt * qx, vy - vt * qy, vz - vt * qz
            vp = math.sqrt(px * px + py * py + pz * pz)
            ct = 0.5 * p[_RHO] * p[_CDT] * math.pi * p[_D] * ln * abs(vt)
            out = forces[b, k]
            out[0] = -f * qx - cn * vp * px - ct * vt * qx
            out[1] = -f * qy - cn * vp * py - ct * vt * qy
            out[2] = -f * qz - cn * vp * pz - ct * vt * qz - p[_WLEN] * ln
            if r[N, 2, m] < p[_ZBED]:
                out[2] += ((p[_ZBED] - r[N, 2, m]) * p[_KB] - vz * p[_CB]) * p[_D] * ln
            tension[b, k] = math.sqrt(out[0] ** 2 + out[1] ** 2 + out[2] ** 2)
            if not math.isfinite(tension[b, k]):
                raise FloatingPointError("non-finite fairlead tension")
