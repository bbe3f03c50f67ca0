"""The BDF2 line step of many lines at once: the lines of a batch in blocks of ``W`` lanes.

:func:`moorlife.mooring.dynamic.step_lines` steps one line at a time (node, then component):
its arithmetic is scalar, and its loops are too short and too branchy for the compiler to
vectorise. Here the same step runs on every line of a batch together: the lines are the lanes
of a vector, and each operation of the scalar step becomes a loop over the lanes that the
compiler turns into SIMD instructions; the per-line branches (slack segments, seabed contact,
friction) become masked selects.

Every lane does exactly the floating-point operations of the scalar step, in the same order
(no reassociation, no fused multiply-add), so the two give the same bits: the scalar step is
the strict reference, this one the fast path (``tests/test_mooring_lanes.py``). Only the
BDF2 step of a constant step length is here; the ROS2 start of :func:`step_lines` stays scalar
(:func:`moorlife.simulate.kernel._run_dynamic` takes the first step with it).

Layout, and why. The lanes come in blocks of ``W`` (a module constant; lanes past the last
line are padded with copies of the last line, whose results are ignored). Everything a block
keeps for one node, its state and the step's scratch, is one *record* of ``_NQ`` rows of ``W``
values (one value per lane), and the records follow each other, node after node, block after
block, in ONE flat array (:class:`LaneState`): the value of row ``q`` of node ``i`` of lane
``l`` of block ``blk`` is at ``(blk (N + 1) + i) _REC + q W + l`` with ``_REC = _NQ W``. The
rows of a segment (``s`` joins nodes ``s`` and ``s + 1``) are in the record of node ``s``.
Two things stopped LLVM from vectorising the lane loops of the earlier layout (one array per
quantity, ``(N + 1, 3, nl)``) at a batch's 24 lanes (``benchmarks/README.md``, 2026-12-03
and 2026-12-04): the distance between the rows of an array was the run-time lane count, so
stores to several rows might overlap; and Numba's arrays are not ``noalias``, so a loop that
touches several arrays needs run-time overlap checks, which LLVM only adds for long loops and
which cost a fixed time per loop. Here every access of a lane loop is into the same array, at
the loop's lane plus a base of the block and node plus a compile-time constant (a multiple of
``W``): LLVM's dependence analysis sees the constant distances and vectorises each lane loop
without any run-time check. The flat indices are unsigned (:func:`_u`), so that Numba leaves
out the wrap-around of negative indices, a select that would hide the indices from LLVM.

The lane loops run to the block's width read at run time (``LaneWork.fair.shape[3]``, always
``W``) rather than to the constant ``W``: Numba runs LLVM without its SLP vectoriser, and LLVM
fully unrolls a short loop of constant trip count before the loop vectoriser sees it, which
would leave the unrolled lanes scalar. Nor does a lane loop call a helper function with the
array: Numba counts the references of an array passed to an inlined function, and a loop with
those calls in it is not vectorised. LLVM reports the lane loops of the node forces, the
factorisation, the right-hand side and the solve vectorised (width 4); the few that copy the
fairlead path from ``LaneWork`` stay scalar.
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

__all__ = ["W", "LaneState", "LaneWork", "lane_state", "lane_work", "lane_arrays", "pack", "unpack", "step_lanes"]

#: lanes per block (AVX2: 4 doubles a vector)
W = 4

# The rows of a node record, as offsets in the record (row times W); a vector quantity has three
# rows (x, y, z at + _X, _Y, _Z), a 3x3 matrix nine (row-major, + (3 a + b) W).
_X, _Y, _Z = 0, W, 2 * W
_R = 0 * W  # positions (state)
_V = 3 * W  # velocities (state)
_RP = 6 * W  # previous positions (state)
_VP = 9 * W  # previous velocities (state)
_R2 = 12 * W  # predicted positions
_V2 = 15 * W  # predicted velocities
_XB = 18 * W  # BDF2 position part
_DV = 21 * W  # BDF2 velocity part, then the solution
_KX = 24 * W  # position residual
_RHS = 27 * W  # right-hand side
_F = 30 * W  # net node force
_TG = 33 * W  # node tangent
_C00, _C11, _C22, _C01, _C02, _C12 = (36 * W, 37 * W, 38 * W, 39 * W, 40 * W, 41 * W)  # damping (symmetric)
_KZ = 42 * W  # seabed stiffness in the matrix
_WI = 43 * W  # inverted block-Thomas pivot (9 rows)
_SQ = 52 * W  # segment unit vector
_SA = 55 * W  # segment axial minus geometric stiffness
_SG = 56 * W  # segment geometric stiffness
_SEGF = 57 * W  # segment axial force
_S = 58 * W  # segment coupling block (9 rows)
#: rows of a record
_NQ = 67
#: values of a record
_REC = _NQ * W
#: the first row of the node state and its four vectors (``LaneState``, :func:`lane_arrays`)
_STATE = (("r", _R), ("v", _V), ("r_prev", _RP), ("v_prev", _VP))


class LaneState(NamedTuple):
    """``nl`` lines as lanes: the node records of every block, state and scratch (module docstring).

    ``nodes`` is flat, ``nblk (N + 1) _NQ W`` values with ``nblk = ceil(nl / W)``.
    :func:`lane_arrays` gives the node state in the shapes of ``DynamicState``.
    """

    nodes: np.ndarray


class LaneWork(NamedTuple):
    """The fairlead path of :func:`step_lanes` for ``nl`` lines, ``(4, 3, nblk, W)``."""

    fair: np.ndarray  # start position and velocity, path position and velocity


def _blocks(nl: int) -> int:
    return -(-nl // W)


def lane_state(nl: int, N: int) -> LaneState:
    """An empty lane state for ``nl`` lines of ``N`` segments (no lines: an empty array)."""
    return LaneState(np.zeros(_blocks(nl) * (N + 1) * _REC))


def lane_work(nl: int, N: int) -> LaneWork:
    """The scratch of :func:`step_lanes` for ``nl`` lines of ``N`` segments."""
    return LaneWork(np.zeros((4, 3, _blocks(nl), W)))


def lane_arrays(ls: LaneState, nl: int, N: int) -> dict[str, np.ndarray]:
    """The node state of the lanes, ``r, v, r_prev, v_prev`` as ``(N + 1, 3, nl)`` copies (lane last)."""
    rec = ls.nodes.reshape(-1, N + 1, _NQ, W)
    out = {}
    for name, row in _STATE:
        q = row // W
        a = rec[:, :, q : q + 3, :].transpose(1, 2, 0, 3).reshape(N + 1, 3, -1)
        out[name] = a[:, :, :nl].copy()
    return out


@njit(cache=True, inline="always")
def _u(k):  # pragma: no cover - numba
    """The flat index ``k`` (non-negative) as unsigned: Numba then adds no wrap-around select."""
    return np.uint64(k)


@njit(cache=True, error_model="numpy")
def pack(state, lanes):  # pragma: no cover - numba
    """Copy the node state of a ``DynamicState`` ``(B, L, N + 1, 3)`` into ``lanes`` (line ``b L + k``).

    Line ``m`` is lane ``m % W`` of block ``m // W``; the lanes past the last line take copies of it.
    """
    x = lanes.nodes
    nb, nk, n1 = state.r.shape[0], state.r.shape[1], state.r.shape[2]
    nl = nb * nk
    if nl == 0:
        return
    nblk = x.shape[0] // (n1 * _REC)
    for m in range(nblk * W):
        b, k = divmod(min(m, nl - 1), nk)
        blk, l = divmod(m, W)
        for i in range(n1):
            o = (blk * n1 + i) * _REC + l
            for a in range(3):
                x[_u(o + _R + a * W)] = state.r[b, k, i, a]
                x[_u(o + _V + a * W)] = state.v[b, k, i, a]
                x[_u(o + _RP + a * W)] = state.r_prev[b, k, i, a]
                x[_u(o + _VP + a * W)] = state.v_prev[b, k, i, a]


@njit(cache=True, error_model="numpy")
def unpack(lanes, state):  # pragma: no cover - numba
    """Copy ``lanes`` back into the node state of a ``DynamicState`` (the inverse of :func:`pack`)."""
    x = lanes.nodes
    nb, nk, n1 = state.r.shape[0], state.r.shape[1], state.r.shape[2]
    for b in range(nb):
        for k in range(nk):
            blk, l = divmod(b * nk + k, W)
            for i in range(n1):
                o = (blk * n1 + i) * _REC + l
                for a in range(3):
                    state.r[b, k, i, a] = x[_u(o + _R + a * W)]
                    state.v[b, k, i, a] = x[_u(o + _V + a * W)]
                    state.r_prev[b, k, i, a] = x[_u(o + _RP + a * W)]
                    state.v_prev[b, k, i, a] = x[_u(o + _VP + a * W)]


@njit(cache=True, inline="always", error_model="numpy")
def _node_forces(x, b0, nw, p, hb):  # pragma: no cover - numba
    """``line_forces._node_forces`` with ``jac`` on the lanes of one block (the same operations per lane).

    ``b0`` is the block's first record; the forces are of the predicted state (rows ``_R2, _V2``).
    (No helper function is called within a lane loop: Numba would count its references to ``x``
    there, and the loop would not be vectorised.)
    """
    N = int(p[_N])
    l0 = p[_L0]
    cint = p[_CINT]
    kax = p[_EA] / l0
    for s in range(N):
        bs = b0 + s * _REC
        for l in range(nw):
            o = bs + l
            o1 = o + _REC
            dx = x[_u(o1 + _R2 + _X)] - x[_u(o + _R2 + _X)]
            dy = x[_u(o1 + _R2 + _Y)] - x[_u(o + _R2 + _Y)]
            dz = x[_u(o1 + _R2 + _Z)] - x[_u(o + _R2 + _Z)]
            l_ = math.sqrt(dx * dx + dy * dy + dz * dz)
            qx, qy, qz = dx / l_, dy / l_, dz / l_
            ldot = (
                qx * (x[_u(o1 + _V2 + _X)] - x[_u(o + _V2 + _X)])
                + qy * (x[_u(o1 + _V2 + _Y)] - x[_u(o + _V2 + _Y)])
                + qz * (x[_u(o1 + _V2 + _Z)] - x[_u(o + _V2 + _Z)])
            )
            T = kax * (l_ - l0) if l_ > l0 else 0.0
            x[_u(o + _SG)] = T / l_ if l_ > l0 else 0.0
            x[_u(o + _SA)] = kax - T / l_ if l_ > l0 else 0.0
            x[_u(o + _SEGF)] = T + cint * ldot
            x[_u(o + _SQ + _X)] = qx
            x[_u(o + _SQ + _Y)] = qy
            x[_u(o + _SQ + _Z)] = qz
    # the net tension and the unit tangent: at the ends the one segment's
    bN = b0 + N * _REC
    for a in range(3):
        c = a * W
        for l in range(nw):
            o, oN = b0 + c + l, bN + c + l
            q0, q1 = x[_u(o + _SQ)], x[_u(oN - _REC + _SQ)]
            x[_u(o + _F)] = 0.0 + x[_u(b0 + l + _SEGF)] * q0
            x[_u(o + _TG)] = q0
            x[_u(oN + _F)] = 0.0 - x[_u(bN - _REC + l + _SEGF)] * q1
            x[_u(oN + _TG)] = q1
    for i in range(1, N):
        bi = b0 + i * _REC
        for l in range(nw):
            o = bi + l
            op, on = o - _REC, o + _REC
            sf, sfp = x[_u(o + _SEGF)], x[_u(op + _SEGF)]
            x[_u(o + _F + _X)] = 0.0 + sf * x[_u(o + _SQ + _X)] - sfp * x[_u(op + _SQ + _X)]
            x[_u(o + _F + _Y)] = 0.0 + sf * x[_u(o + _SQ + _Y)] - sfp * x[_u(op + _SQ + _Y)]
            x[_u(o + _F + _Z)] = 0.0 + sf * x[_u(o + _SQ + _Z)] - sfp * x[_u(op + _SQ + _Z)]
            tx = x[_u(on + _R2 + _X)] - x[_u(op + _R2 + _X)]
            ty = x[_u(on + _R2 + _Y)] - x[_u(op + _R2 + _Y)]
            tz = x[_u(on + _R2 + _Z)] - x[_u(op + _R2 + _Z)]
            tn = 1.0 / math.sqrt(tx * tx + ty * ty + tz * tz)
            x[_u(o + _TG + _X)] = tx * tn
            x[_u(o + _TG + _Y)] = ty * tn
            x[_u(o + _TG + _Z)] = tz * tn
    rho = p[_RHO]
    cdn = 0.5 * rho * p[_CDN] * p[_D]
    cdt = 0.5 * rho * p[_CDT] * math.pi * p[_D]
    zbed = p[_ZBED]
    mu = p[_MU]
    kb, cb, band, vslip, dia, wlen = p[_KB], p[_CB], p[_BAND], p[_VSLIP], p[_D], p[_WLEN]
    fric = mu > 0.0
    for i in range(N + 1):
        ln = l0 if (0 < i < N) else 0.5 * l0
        cn = cdn * ln
        ct = cdt * ln
        area = dia * ln
        kba = kb * area
        cba = cb * area
        wl = wlen * ln
        bi = b0 + i * _REC
        # weight, drag, seabed and friction, with their damping matrix: one select per branch
        for l in range(nw):
            o = bi + l
            tx, ty, tz = x[_u(o + _TG + _X)], x[_u(o + _TG + _Y)], x[_u(o + _TG + _Z)]
            fx, fy, fz = x[_u(o + _F + _X)], x[_u(o + _F + _Y)], x[_u(o + _F + _Z)] - wl
            vx, vy, vz = x[_u(o + _V2 + _X)], x[_u(o + _V2 + _Y)], x[_u(o + _V2 + _Z)]
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
            rz = x[_u(o + _R2 + _Z)]
            near = rz < zbed + band + hb * max(-vz, 0.0)
            x[_u(o + _KZ)] = kba if near else 0.0
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
            x[_u(o + _C00)] = c00
            x[_u(o + _C11)] = c11
            x[_u(o + _C22)] = c22
            x[_u(o + _C01)] = ctt * tx * ty + ip * px * py
            x[_u(o + _C02)] = ctt * tx * tz + ip * px * pz
            x[_u(o + _C12)] = ctt * ty * tz + ip * py * pz
            x[_u(o + _F + _X)] = fx
            x[_u(o + _F + _Y)] = fy
            x[_u(o + _F + _Z)] = fz


@njit(cache=True, inline="always", error_model="numpy")
def _factor(x, b0, nw, N, am, bm, cs, cg, cz):  # pragma: no cover - numba
    """``dynamic._factor`` on the lanes of one block: coupling blocks and inverted block-Thomas pivots.

    ``am, bm`` are the isotropic and axial-minus-normal added mass of an interior node. Node 1
    has no predecessor to eliminate: its lanes compute the elimination from the record of node 0
    all the same (the loads stay unconditional, so that the loop vectorises) and select the
    pivot without it.
    """
    for s in range(N):
        bs = b0 + s * _REC
        for l in range(nw):
            o = bs + l
            ca = cs + cg * x[_u(o + _SA)]
            q0, q1, q2 = x[_u(o + _SQ + _X)], x[_u(o + _SQ + _Y)], x[_u(o + _SQ + _Z)]
            gs = cg * x[_u(o + _SG)]
            x[_u(o + _S + 0 * W)] = ca * q0 * q0 + gs
            x[_u(o + _S + 1 * W)] = ca * q0 * q1
            x[_u(o + _S + 2 * W)] = ca * q0 * q2
            x[_u(o + _S + 3 * W)] = ca * q1 * q0
            x[_u(o + _S + 4 * W)] = ca * q1 * q1 + gs
            x[_u(o + _S + 5 * W)] = ca * q1 * q2
            x[_u(o + _S + 6 * W)] = ca * q2 * q0
            x[_u(o + _S + 7 * W)] = ca * q2 * q1
            x[_u(o + _S + 8 * W)] = ca * q2 * q2 + gs
    for i in range(1, N):
        bi = b0 + i * _REC
        elim = i > 1
        for l in range(nw):
            o = bi + l
            oj = o - _REC  # node j = i - 1 and segment j
            t0, t1, t2 = x[_u(o + _TG + _X)], x[_u(o + _TG + _Y)], x[_u(o + _TG + _Z)]
            c00, c11, c22 = x[_u(o + _C00)], x[_u(o + _C11)], x[_u(o + _C22)]
            c01, c02, c12 = x[_u(o + _C01)], x[_u(o + _C02)], x[_u(o + _C12)]
            d00 = bm * t0 * t0 + cz * c00 + x[_u(oj + _S + 0 * W)] + x[_u(o + _S + 0 * W)]
            d01 = bm * t0 * t1 + cz * c01 + x[_u(oj + _S + 1 * W)] + x[_u(o + _S + 1 * W)]
            d02 = bm * t0 * t2 + cz * c02 + x[_u(oj + _S + 2 * W)] + x[_u(o + _S + 2 * W)]
            d10 = bm * t1 * t0 + cz * c01 + x[_u(oj + _S + 3 * W)] + x[_u(o + _S + 3 * W)]
            d11 = bm * t1 * t1 + cz * c11 + x[_u(oj + _S + 4 * W)] + x[_u(o + _S + 4 * W)]
            d12 = bm * t1 * t2 + cz * c12 + x[_u(oj + _S + 5 * W)] + x[_u(o + _S + 5 * W)]
            d20 = bm * t2 * t0 + cz * c02 + x[_u(oj + _S + 6 * W)] + x[_u(o + _S + 6 * W)]
            d21 = bm * t2 * t1 + cz * c12 + x[_u(oj + _S + 7 * W)] + x[_u(o + _S + 7 * W)]
            d22 = bm * t2 * t2 + cz * c22 + x[_u(oj + _S + 8 * W)] + x[_u(o + _S + 8 * W)]
            d00 += am
            d11 += am
            d22 += am
            d22 += cg * x[_u(o + _KZ)]
            al = cs + cg * x[_u(oj + _SA)]
            be = cg * x[_u(oj + _SG)]
            q0, q1, q2 = x[_u(oj + _SQ + _X)], x[_u(oj + _SQ + _Y)], x[_u(oj + _SQ + _Z)]
            w00, w01, w02 = x[_u(oj + _WI + 0 * W)], x[_u(oj + _WI + 1 * W)], x[_u(oj + _WI + 2 * W)]
            w10, w11, w12 = x[_u(oj + _WI + 3 * W)], x[_u(oj + _WI + 4 * W)], x[_u(oj + _WI + 5 * W)]
            w20, w21, w22 = x[_u(oj + _WI + 6 * W)], x[_u(oj + _WI + 7 * W)], x[_u(oj + _WI + 8 * W)]
            g0 = w00 * q0 + w01 * q1 + w02 * q2
            g1 = w10 * q0 + w11 * q1 + w12 * q2
            g2 = w20 * q0 + w21 * q1 + w22 * q2
            a2s = al * al * (q0 * g0 + q1 * g1 + q2 * g2)
            ab = al * be
            b2 = be * be
            a = d00 - (a2s * q0 * q0 + ab * (q0 * g0 + g0 * q0) + b2 * w00) if elim else d00
            b = d01 - (a2s * q0 * q1 + ab * (q0 * g1 + g0 * q1) + b2 * w01) if elim else d01
            c = d02 - (a2s * q0 * q2 + ab * (q0 * g2 + g0 * q2) + b2 * w02) if elim else d02
            d = d10 - (a2s * q1 * q0 + ab * (q1 * g0 + g1 * q0) + b2 * w10) if elim else d10
            e = d11 - (a2s * q1 * q1 + ab * (q1 * g1 + g1 * q1) + b2 * w11) if elim else d11
            f = d12 - (a2s * q1 * q2 + ab * (q1 * g2 + g1 * q2) + b2 * w12) if elim else d12
            g = d20 - (a2s * q2 * q0 + ab * (q2 * g0 + g2 * q0) + b2 * w20) if elim else d20
            h = d21 - (a2s * q2 * q1 + ab * (q2 * g1 + g2 * q1) + b2 * w21) if elim else d21
            k = d22 - (a2s * q2 * q2 + ab * (q2 * g2 + g2 * q2) + b2 * w22) if elim else d22
            # the inverse of the pivot [[a, b, c], [d, e, f], [g, h, k]]
            c0 = e * k - f * h
            c1 = f * g - d * k
            c2 = d * h - e * g
            det = a * c0 + b * c1 + c * c2
            rr = 1.0 / det
            x[_u(o + _WI + 0 * W)] = c0 * rr
            x[_u(o + _WI + 1 * W)] = (c * h - b * k) * rr
            x[_u(o + _WI + 2 * W)] = (b * f - c * e) * rr
            x[_u(o + _WI + 3 * W)] = c1 * rr
            x[_u(o + _WI + 4 * W)] = (a * k - c * g) * rr
            x[_u(o + _WI + 5 * W)] = (c * d - a * f) * rr
            x[_u(o + _WI + 6 * W)] = c2 * rr
            x[_u(o + _WI + 7 * W)] = (b * g - a * h) * rr
            x[_u(o + _WI + 8 * W)] = (a * e - b * d) * rr


@njit(cache=True, inline="always", error_model="numpy")
def _solve_blocks(x, b0, nw, N):  # pragma: no cover - numba
    """``dynamic._solve_blocks`` on the lanes of one block: rows ``_RHS`` in, the solution in ``_DV``."""
    for a in range(3):
        c = b0 + _REC + a * W
        for l in range(nw):
            x[_u(c + l + _DV)] = x[_u(c + l + _RHS)]
    for i in range(2, N):
        bi = b0 + i * _REC
        for l in range(nw):
            o = bi + l
            op = o - _REC
            y0, y1, y2 = x[_u(op + _DV + _X)], x[_u(op + _DV + _Y)], x[_u(op + _DV + _Z)]
            t0 = x[_u(op + _WI + 0 * W)] * y0 + x[_u(op + _WI + 1 * W)] * y1 + x[_u(op + _WI + 2 * W)] * y2
            t1 = x[_u(op + _WI + 3 * W)] * y0 + x[_u(op + _WI + 4 * W)] * y1 + x[_u(op + _WI + 5 * W)] * y2
            t2 = x[_u(op + _WI + 6 * W)] * y0 + x[_u(op + _WI + 7 * W)] * y1 + x[_u(op + _WI + 8 * W)] * y2
            s00, s01, s02 = x[_u(op + _S + 0 * W)], x[_u(op + _S + 1 * W)], x[_u(op + _S + 2 * W)]
            s10, s11, s12 = x[_u(op + _S + 3 * W)], x[_u(op + _S + 4 * W)], x[_u(op + _S + 5 * W)]
            s20, s21, s22 = x[_u(op + _S + 6 * W)], x[_u(op + _S + 7 * W)], x[_u(op + _S + 8 * W)]
            x[_u(o + _DV + _X)] = x[_u(o + _RHS + _X)] + s00 * t0 + s01 * t1 + s02 * t2
            x[_u(o + _DV + _Y)] = x[_u(o + _RHS + _Y)] + s10 * t0 + s11 * t1 + s12 * t2
            x[_u(o + _DV + _Z)] = x[_u(o + _RHS + _Z)] + s20 * t0 + s21 * t1 + s22 * t2
    bl = b0 + (N - 1) * _REC
    for l in range(nw):
        o = bl + l
        t0, t1, t2 = x[_u(o + _DV + _X)], x[_u(o + _DV + _Y)], x[_u(o + _DV + _Z)]
        x[_u(o + _DV + _X)] = x[_u(o + _WI + 0 * W)] * t0 + x[_u(o + _WI + 1 * W)] * t1 + x[_u(o + _WI + 2 * W)] * t2
        x[_u(o + _DV + _Y)] = x[_u(o + _WI + 3 * W)] * t0 + x[_u(o + _WI + 4 * W)] * t1 + x[_u(o + _WI + 5 * W)] * t2
        x[_u(o + _DV + _Z)] = x[_u(o + _WI + 6 * W)] * t0 + x[_u(o + _WI + 7 * W)] * t1 + x[_u(o + _WI + 8 * W)] * t2
    for i in range(N - 2, 0, -1):
        bi = b0 + i * _REC
        for l in range(nw):
            o = bi + l
            on = o + _REC
            n0, n1, n2 = x[_u(on + _DV + _X)], x[_u(on + _DV + _Y)], x[_u(on + _DV + _Z)]
            t0 = (
                x[_u(o + _DV + _X)]
                + x[_u(o + _S + 0 * W)] * n0
                + x[_u(o + _S + 1 * W)] * n1
                + x[_u(o + _S + 2 * W)] * n2
            )
            t1 = (
                x[_u(o + _DV + _Y)]
                + x[_u(o + _S + 3 * W)] * n0
                + x[_u(o + _S + 4 * W)] * n1
                + x[_u(o + _S + 5 * W)] * n2
            )
            t2 = (
                x[_u(o + _DV + _Z)]
                + x[_u(o + _S + 6 * W)] * n0
                + x[_u(o + _S + 7 * W)] * n1
                + x[_u(o + _S + 8 * W)] * n2
            )
            x[_u(o + _DV + _X)] = (
                x[_u(o + _WI + 0 * W)] * t0 + x[_u(o + _WI + 1 * W)] * t1 + x[_u(o + _WI + 2 * W)] * t2
            )
            x[_u(o + _DV + _Y)] = (
                x[_u(o + _WI + 3 * W)] * t0 + x[_u(o + _WI + 4 * W)] * t1 + x[_u(o + _WI + 5 * W)] * t2
            )
            x[_u(o + _DV + _Z)] = (
                x[_u(o + _WI + 6 * W)] * t0 + x[_u(o + _WI + 7 * W)] * t1 + x[_u(o + _WI + 8 * W)] * t2
            )


@njit(cache=True, inline="always", error_model="numpy")
def _bdf2(x, fair, blk, nw, h, p):  # pragma: no cover - numba
    """``dynamic._bdf2_step`` on the lanes of block ``blk``; its fairleads at the step's end in ``fair[2:4]``."""
    N = int(p[_N])
    b0 = blk * (N + 1) * _REC
    bN = b0 + N * _REC
    beta = 2.0 * h / 3.0
    for a in range(3):
        c = a * W
        for l in range(nw):
            o, oN = b0 + c + l, bN + c + l
            x[_u(o + _R2)] = x[_u(o + _R)]
            x[_u(o + _V2)] = 0.0
            x[_u(oN + _R2)] = fair[2, a, blk, l]
            x[_u(oN + _V2)] = fair[3, a, blk, l]
            x[_u(o + _KX)] = 0.0
            x[_u(oN + _KX)] = 0.0
    for i in range(1, N):
        for a in range(3):
            bc = b0 + i * _REC + a * W  # component a of node i
            for l in range(nw):
                o = bc + l
                r, rp = x[_u(o + _R)], x[_u(o + _RP)]
                v, vp = x[_u(o + _V)], x[_u(o + _VP)]
                r2 = 2.0 * r - rp
                v2 = 2.0 * v - vp
                xb = (4.0 * r - rp) / 3.0
                x[_u(o + _R2)] = r2
                x[_u(o + _V2)] = v2
                x[_u(o + _XB)] = xb
                x[_u(o + _DV)] = (4.0 * v - vp) / 3.0 - v2
                x[_u(o + _KX)] = xb + beta * v2 - r2
    _node_forces(x, b0, nw, p, h)
    l0 = p[_L0]
    A = 0.25 * math.pi * p[_D] * p[_D]
    rho = p[_RHO]
    am = p[_MLEN] * l0 + rho * A * l0 * p[_CAN]  # an interior node's
    bm = rho * A * l0 * (p[_CAT] - p[_CAN])
    _factor(x, b0, nw, N, am, bm, beta * p[_CINT], beta * beta, beta)
    for i in range(1, N):
        bi = b0 + i * _REC
        for l in range(nw):
            # dynamic._kx_times: segment springs to both neighbours + seabed spring
            o = bi + l
            op, on = o - _REC, o + _REC
            kx0, kx1, kx2 = x[_u(o + _KX + _X)], x[_u(o + _KX + _Y)], x[_u(o + _KX + _Z)]
            ax = x[_u(op + _KX + _X)] - kx0
            ay = x[_u(op + _KX + _Y)] - kx1
            az = x[_u(op + _KX + _Z)] - kx2
            bx = x[_u(on + _KX + _X)] - kx0
            by = x[_u(on + _KX + _Y)] - kx1
            bz = x[_u(on + _KX + _Z)] - kx2
            pq0, pq1, pq2 = x[_u(op + _SQ + _X)], x[_u(op + _SQ + _Y)], x[_u(op + _SQ + _Z)]
            sq0, sq1, sq2 = x[_u(o + _SQ + _X)], x[_u(o + _SQ + _Y)], x[_u(o + _SQ + _Z)]
            psg, ssg = x[_u(op + _SG)], x[_u(o + _SG)]
            qa = x[_u(op + _SA)] * (pq0 * ax + pq1 * ay + pq2 * az)
            qb = x[_u(o + _SA)] * (sq0 * bx + sq1 * by + sq2 * bz)
            k0 = qa * pq0 + psg * ax + qb * sq0 + ssg * bx
            k1 = qa * pq1 + psg * ay + qb * sq1 + ssg * by
            k2 = qa * pq2 + psg * az + qb * sq2 + ssg * bz - x[_u(o + _KZ)] * kx2
            t0, t1, t2 = x[_u(o + _TG + _X)], x[_u(o + _TG + _Y)], x[_u(o + _TG + _Z)]
            d0, d1, d2 = x[_u(o + _DV + _X)], x[_u(o + _DV + _Y)], x[_u(o + _DV + _Z)]
            tv = bm * (t0 * d0 + t1 * d1 + t2 * d2)
            x[_u(o + _RHS + _X)] = am * d0 + tv * t0 + beta * (x[_u(o + _F + _X)] + k0)
            x[_u(o + _RHS + _Y)] = am * d1 + tv * t1 + beta * (x[_u(o + _F + _Y)] + k1)
            x[_u(o + _RHS + _Z)] = am * d2 + tv * t2 + beta * (x[_u(o + _F + _Z)] + k2)
    _solve_blocks(x, b0, nw, N)
    for i in range(1, N):
        for a in range(3):
            bc = b0 + i * _REC + a * W
            for l in range(nw):
                o = bc + l
                vn = x[_u(o + _V2)] + x[_u(o + _DV)]
                x[_u(o + _RP)] = x[_u(o + _R)]
                x[_u(o + _VP)] = x[_u(o + _V)]
                x[_u(o + _V)] = vn
                x[_u(o + _R)] = x[_u(o + _XB)] + beta * vn
    for a in range(3):
        c = a * W
        for l in range(nw):
            o = bN + c + l
            x[_u(o + _RP)] = x[_u(o + _R)]
            x[_u(o + _VP)] = x[_u(o + _V)]
            x[_u(o + _R)] = fair[2, a, blk, l]
            x[_u(o + _V)] = fair[3, a, blk, l]


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
    x = ls.nodes
    fair = w.fair
    nb, nk = r_new.shape[0], r_new.shape[1]
    nl = nb * nk
    nblk, nw = fair.shape[2], fair.shape[3]  # nw == W, but not a constant to the compiler (docstring)
    N = int(p[_N])
    rN = N * _REC
    h = dt / nsub
    # block after block, each through all its substeps (the lanes are independent)
    for blk in range(nblk):
        for l in range(nw):
            o = blk * (N + 1) * _REC + rN + l
            for a in range(3):
                fair[0, a, blk, l] = x[_u(o + _R + a * W)]
                fair[1, a, blk, l] = x[_u(o + _V + a * W)]
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
            for l in range(nw):
                b, k = divmod(min(blk * W + l, nl - 1), nk)  # padded lanes follow the last line
                for a in range(3):
                    p1, v1 = r_new[b, k, a], v_new[b, k, a]
                    p0, v0 = fair[0, a, blk, l], fair[1, a, blk, l]
                    fair[2, a, blk, l] = h00 * p0 + h10 * dt * v0 + h01 * p1 + h11 * dt * v1
                    fair[3, a, blk, l] = d00 * p0 + d10 * v0 + d01 * p1 + d11 * v1
            _bdf2(x, fair, blk, nw, h, p)
    # dynamic._end_force: the net force of the fairlead node without its inertia
    l0 = p[_L0]
    ln = 0.5 * l0
    cn = 0.5 * p[_RHO] * p[_CDN] * p[_D] * ln
    for b in range(nb):
        for k in range(nk):
            blk, l = divmod(b * nk + k, W)
            o = blk * (N + 1) * _REC + rN + l
            om = o - _REC
            dx = x[_u(o + _R + _X)] - x[_u(om + _R + _X)]
            dy = x[_u(o + _R + _Y)] - x[_u(om + _R + _Y)]
            dz = x[_u(o + _R + _Z)] - x[_u(om + _R + _Z)]
            l_ = math.sqrt(dx * dx + dy * dy + dz * dz)
            qx, qy, qz = dx / l_, dy / l_, dz / l_
            vx, vy, vz = x[_u(o + _V + _X)], x[_u(o + _V + _Y)], x[_u(o + _V + _Z)]
            ldot = qx * (vx - x[_u(om + _V + _X)]) + qy * (vy - x[_u(om + _V + _Y)]) + qz * (vz - x[_u(om + _V + _Z)])
            T = p[_EA] / l0 * (l_ - l0) if l_ > l0 else 0.0
            f = T + p[_CINT] * ldot
            vt = vx * qx + vy * qy + vz * qz
            px, py, pz = vx - vt * qx, vy - vt * qy, vz - vt * qz
            vp = math.sqrt(px * px + py * py + pz * pz)
            ct = 0.5 * p[_RHO] * p[_CDT] * math.pi * p[_D] * ln * abs(vt)
            out = forces[b, k]
            out[0] = -f * qx - cn * vp * px - ct * vt * qx
            out[1] = -f * qy - cn * vp * py - ct * vt * qy
            out[2] = -f * qz - cn * vp * pz - ct * vt * qz - p[_WLEN] * ln
            rz = x[_u(o + _R + _Z)]
            if rz < p[_ZBED]:
                out[2] += ((p[_ZBED] - rz) * p[_KB] - vz * p[_CB]) * p[_D] * ln
            tension[b, k] = math.sqrt(out[0] ** 2 + out[1] ** 2 + out[2] ** 2)
            if not math.isfinite(tension[b, k]):
                raise FloatingPointError("non-finite fairlead tension")
