"""Dynamic lumped-mass mooring lines, linearly implicit (Rosenbrock ROS2) time stepping.

Model (the MoorDyn formulation, Hall & Goupee 2015, without bending): each line of
unstretched length ``L`` is cut into ``N`` equal segments joined at ``N + 1`` nodes (node 0
at the anchor, node ``N`` at the fairlead). Per segment: axial tension
``EA (l - l0) / l0`` (zero when slack) and internal damping ``c * dl/dt`` with
``c = zeta * sqrt(EA * m)`` (MoorDyn's ``BA = -zeta``). Per node (half segments at the ends):
submerged weight (mass minus displaced water of the equivalent diameter), Morison drag on
the velocity relative to still water, normal ``0.5 rho Cd D l |v_n| v_n`` and tangential
``0.5 rho CdAx pi D l |v_t| v_t``, added mass ``rho V (Ca (I - t t') + CaAx t t')``, and
seabed contact below ``z = -depth``: a vertical spring-damper ``(kb * penetration - cb * v_z)
* D * l`` and horizontal friction ``min(mu Fn |v_h| / v_slip, mu Fn)`` against the sliding
velocity (Coulomb friction regularised below ``v_slip``).

Integrator and why. The chain is axially very stiff: the highest axial mode of a 42 m
segment of MS2 chain has ``omega = 2 c / l0 ~ 120 rad/s`` (``c = sqrt(EA/m) ~ 2400 m/s``)
and the seabed spring-damper adds ``cb D l / m ~ 300 1/s``. An explicit scheme (MoorDyn's
RK2) must resolve those with ``dt ~ 1-5 ms`` (MoorDyn diverges at 10 ms on MS2), although
the response that matters (waves, slow drift) lives below ~2 rad/s. We integrate the stiff
ODE implicitly, linearising the node forces once per step (no Newton loop): the matrix
``M - b C - b^2 K`` (mass, damping and stiffness Jacobians of the node forces) is block
tridiagonal (3x3 blocks) for a line and is factorised by block Thomas elimination in O(N).
Two L-stable second-order schemes are available (``mooring.integrator``):

* ``bdf2`` (default): linearly implicit BDF2, forces linearised about the extrapolated state
  ``2 y_n - y_n-1``; one force evaluation, one factorisation and one solve per step. It is
  started (and restarted when the step length changes) by one ROS2 step.
* ``ros2``: the two-stage Rosenbrock method of Verwer et al. (1999), ``gamma = 1 + 1/sqrt 2``;
  two force evaluations and two solves with one factorisation; order 2 with an approximate
  Jacobian (W-method).

The unresolved axial modes are damped out (L-stability) instead of limiting the step, so the
step is set by accuracy only: ``max_time_step`` (default 0.05 s, 100 steps per 5 s wave
period). A stiff term left out of the matrix acts explicitly, so the seabed spring-damper
enters the matrix for nodes in contact or about to land within the step (else landing nodes
bounce), and only for those (a spring in the matrix of a node in free flight slows it down,
measured). Before the dynamics, the nodes are put in static equilibrium by Newton iterations
(same block-tridiagonal solver) starting from the elastic catenary, then relaxed with the
fairleads held still.

Validation against MoorDyn (``tests/test_mooring_dynamic.py``, MS2 with friction and MS5
without, 5 m surge at 100 s + 1 m at 10 s): mean, standard deviation and range of fairlead
tension within 3 % at 0.05 s. Cost: ``benchmarks/bench_mooring.py``, ``benchmarks/README.md``.

The fairlead force returned to the platform is the net force of the line's end node
(minus its inertia), as MoorDyn's coupled-point force: ``-(T + c dl/dt) t_end`` plus the end
node's weight, drag and seabed force.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import njit

from moorlife.mooring.line_forces import (  # the parameter indices, the node forces, the work buffer
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
    _NPAR,
    _RHO,
    _VSLIP,
    _WLEN,
    _ZBED,
    _end_force,
    _inv3,
    _node_forces,
    _views,
    _workspace,
)
from moorlife.mooring.lines import Layout, LineProperties, MooringSettings
from moorlife.mooring.quasistatic import catenary_profile, catenary_solve

__all__ = [
    "node_forces",
    "LineModel",
    "DynamicState",
    "LineKernel",
    "step_lines",
    "DynamicMooring",
    "line_model",
    "initial_nodes",
    "hermite",
]

GAMMA = 1.0 + 1.0 / math.sqrt(2.0)
#: Height above the seabed (m) below which the implicit matrix includes the seabed contact,
#: on top of the distance a descending node covers in one step.
CONTACT_BAND = 0.01


@dataclass(frozen=True)
class LineModel:
    """Discretised line: the parameter vector of the numba kernels.

    Attributes
    ----------
    params : numpy.ndarray, shape (18,)
        ``N, l0, EA, c_int, m, D, rho_w, w, Cd, CdAx, Ca, CaAx, kb, cb, mu, v_slip, z_bed, band``
        (SI units; ``c_int`` internal damping N s, ``w`` wet weight N/m, ``kb`` Pa/m, ``cb``
        Pa s/m, ``z_bed = -depth``).
    """

    params: np.ndarray

    @property
    def n_segments(self) -> int:
        """Number of segments ``N``."""
        return int(self.params[_N])


def line_model(props: LineProperties, layout: Layout, settings: MooringSettings) -> LineModel:
    """The lumped-mass parameters of one line type on the given layout and settings."""
    N = settings.n_segments
    p = np.zeros(_NPAR)
    p[_N] = N
    p[_L0] = layout.length / N
    p[_EA] = props.EA
    p[_CINT] = settings.internal_damping_ratio * math.sqrt(props.EA * props.mass)
    p[_MLEN] = props.mass
    p[_D] = props.equivalent_diameter
    p[_RHO] = settings.water_density
    p[_WLEN] = (props.mass - settings.water_density * math.pi / 4 * props.equivalent_diameter**2) * settings.gravity
    p[_CDN] = settings.cd_normal
    p[_CDT] = settings.cd_axial
    p[_CAN] = settings.ca_normal
    p[_CAT] = settings.ca_axial
    p[_KB] = settings.seabed_stiffness
    p[_CB] = settings.seabed_damping
    p[_MU] = settings.friction_coefficient
    p[_VSLIP] = settings.friction_slip_velocity
    p[_ZBED] = -layout.depth
    p[_BAND] = CONTACT_BAND
    p.setflags(write=False)
    return LineModel(p)


# --------------------------------------------------------------------------- ROS2 step
@njit(cache=True, inline="always", error_model="numpy")
def _kx_times(sq, sa, sg, Kz, rx, i, out):
    """(K_x rx)_i for interior node i: segment springs to both neighbours + seabed spring."""
    ax = rx[i - 1, 0] - rx[i, 0]
    ay = rx[i - 1, 1] - rx[i, 1]
    az = rx[i - 1, 2] - rx[i, 2]
    bx = rx[i + 1, 0] - rx[i, 0]
    by = rx[i + 1, 1] - rx[i, 1]
    bz = rx[i + 1, 2] - rx[i, 2]
    qa = sa[i - 1] * (sq[i - 1, 0] * ax + sq[i - 1, 1] * ay + sq[i - 1, 2] * az)
    qb = sa[i] * (sq[i, 0] * bx + sq[i, 1] * by + sq[i, 2] * bz)
    out[0] = qa * sq[i - 1, 0] + sg[i - 1] * ax + qb * sq[i, 0] + sg[i] * bx
    out[1] = qa * sq[i - 1, 1] + sg[i - 1] * ay + qb * sq[i, 1] + sg[i] * by
    out[2] = qa * sq[i - 1, 2] + sg[i - 1] * az + qb * sq[i, 2] + sg[i] * bz - Kz[i] * rx[i, 2]


@njit(cache=True, inline="always", error_model="numpy")
def _solve_blocks(S, Winv, b, x, N, tmp):
    """Solve the factorised block-tridiagonal system (interior nodes 1..N-1)."""
    for a in range(3):
        x[1, a] = b[1, a]
    for i in range(2, N):
        for a in range(3):
            tmp[a] = Winv[i - 1, a, 0] * x[i - 1, 0] + Winv[i - 1, a, 1] * x[i - 1, 1] + Winv[i - 1, a, 2] * x[i - 1, 2]
        for a in range(3):
            x[i, a] = b[i, a] + S[i - 1, a, 0] * tmp[0] + S[i - 1, a, 1] * tmp[1] + S[i - 1, a, 2] * tmp[2]
    for a in range(3):
        tmp[a] = x[N - 1, a]
    for a in range(3):
        x[N - 1, a] = Winv[N - 1, a, 0] * tmp[0] + Winv[N - 1, a, 1] * tmp[1] + Winv[N - 1, a, 2] * tmp[2]
    for i in range(N - 2, 0, -1):
        for a in range(3):
            tmp[a] = x[i, a] + S[i, a, 0] * x[i + 1, 0] + S[i, a, 1] * x[i + 1, 1] + S[i, a, 2] * x[i + 1, 2]
        for a in range(3):
            x[i, a] = Winv[i, a, 0] * tmp[0] + Winv[i, a, 1] * tmp[1] + Winv[i, a, 2] * tmp[2]


@njit(cache=True, inline="always", error_model="numpy")
def _factor(ws, S, Winv, D, tmpm, N, cs, cg, cz):
    """Coupling blocks and block-Thomas inverses of ``M + cz C + (segments) + cg Kz``.

    Segment s couples its nodes with ``S_s = (cs + cg * sa_s) q q' + cg * sg_s I`` (internal
    damping ``cs = b * c_int``, axial and geometric stiffness ``cg = b**2``); ``Winv[i]`` are
    the inverted pivots ``W_i = D_i - S_{i-1} W_{i-1}^-1 S_{i-1}``, computed with the rank-one
    structure of ``S``: ``S W^-1 S = al^2 (q'g) q q' + al be (q g' + g q') + be^2 W^-1``,
    ``g = W^-1 q``.
    """
    F, segf, sq, sa, sg, tang, am, bm, C, Kz = ws
    for s in range(N):
        al = cs + cg * sa[s]
        be = cg * sg[s]
        for a in range(3):
            for b in range(3):
                S[s, a, b] = al * sq[s, a] * sq[s, b]
            S[s, a, a] += be
    for i in range(1, N):
        for a in range(3):
            for b in range(3):
                D[a, b] = bm[i] * tang[i, a] * tang[i, b] + cz * C[i, a, b] + S[i - 1, a, b] + S[i, a, b]
            D[a, a] += am[i]
        D[2, 2] += cg * Kz[i]
        if i > 1:
            j = i - 1
            al = cs + cg * sa[j]
            be = cg * sg[j]
            q0, q1, q2 = sq[j, 0], sq[j, 1], sq[j, 2]
            g0 = Winv[j, 0, 0] * q0 + Winv[j, 0, 1] * q1 + Winv[j, 0, 2] * q2
            g1 = Winv[j, 1, 0] * q0 + Winv[j, 1, 1] * q1 + Winv[j, 1, 2] * q2
            g2 = Winv[j, 2, 0] * q0 + Winv[j, 2, 1] * q1 + Winv[j, 2, 2] * q2
            a2s = al * al * (q0 * g0 + q1 * g1 + q2 * g2)
            ab = al * be
            b2 = be * be
            qv = (q0, q1, q2)
            gv = (g0, g1, g2)
            for a in range(3):
                for b in range(3):
                    D[a, b] -= a2s * qv[a] * qv[b] + ab * (qv[a] * gv[b] + gv[a] * qv[b]) + b2 * Winv[j, a, b]
        _inv3(D, Winv[i])


@njit(cache=True, error_model="numpy")
def _ros2_step(r, v, rf0, vf0, rf1, vf1, h, p, w):
    """One ROS2 step of one line; r, v (N+1, 3) updated in place, fairlead moved rf0 -> rf1."""
    ws1, ws2, S, Winv, D, tmpm, rhs, kx1, kv1, kx2, kv2, r2, v2, tmp3 = w
    F, segf, sq, sa, sg, tang, am, bm, C, Kz = ws1
    F2 = ws2[0]
    tang2, am2, bm2 = ws2[5], ws2[6], ws2[7]
    N = int(p[_N])
    cint = p[_CINT]
    gh = GAMMA * h
    gh2 = gh * gh
    for a in range(3):
        r[N, a] = rf0[a]
        v[N, a] = vf0[a]
    anx, any_, anz = (vf1[0] - vf0[0]) / h, (vf1[1] - vf0[1]) / h, (vf1[2] - vf0[2]) / h
    _node_forces(r, v, p, h, True, ws1)
    _factor(ws1, S, Winv, D, tmpm, N, gh * cint, gh2, gh)
    # internal damping coupling of the last interior node to the fairlead acceleration
    qa = cint * (sq[N - 1, 0] * anx + sq[N - 1, 1] * any_ + sq[N - 1, 2] * anz)
    # ---- stage 1: x-part of f is v; fairlead k-values (time as a state): v_f, a_f
    for a in range(3):
        kx1[0, a] = 0.0
        kx1[N, a] = vf0[a]
    for i in range(1, N):
        for a in range(3):
            kx1[i, a] = v[i, a]
    for i in range(1, N):
        _kx_times(sq, sa, sg, Kz, kx1, i, tmp3)
        for a in range(3):
            rhs[i, a] = F[i, a] + gh * tmp3[a]
    for a in range(3):
        rhs[N - 1, a] += gh * qa * sq[N - 1, a]
    _solve_blocks(S, Winv, rhs, kv1, N, tmp3)
    for i in range(1, N):
        for a in range(3):
            kx1[i, a] = v[i, a] + gh * kv1[i, a]
    # ---- stage 2 at t + h, y + h k1
    for a in range(3):
        r2[0, a] = r[0, a]
        v2[0, a] = 0.0
        r2[N, a] = rf1[a]
        v2[N, a] = vf1[a]
    for i in range(1, N):
        for a in range(3):
            r2[i, a] = r[i, a] + h * kx1[i, a]
            v2[i, a] = v[i, a] + h * kv1[i, a]
    _node_forces(r2, v2, p, h, False, ws2)
    # rx2 = v + h kv1 - 2 kx1 (stored in kx2); fairlead: -v_f, -a_f
    for a in range(3):
        kx2[0, a] = 0.0
        kx2[N, a] = -vf0[a]
    for i in range(1, N):
        for a in range(3):
            kx2[i, a] = v[i, a] + h * kv1[i, a] - 2.0 * kx1[i, a]
    for i in range(1, N):
        # rv2 = M2^-1 F2 - 2 kv1, with M = am I + bm t t' inverted in closed form
        tf = tang2[i, 0] * F2[i, 0] + tang2[i, 1] * F2[i, 1] + tang2[i, 2] * F2[i, 2]
        c2 = bm2[i] / (am2[i] + bm2[i]) * tf
        y0 = (F2[i, 0] - c2 * tang2[i, 0]) / am2[i] - 2.0 * kv1[i, 0]
        y1 = (F2[i, 1] - c2 * tang2[i, 1]) / am2[i] - 2.0 * kv1[i, 1]
        y2 = (F2[i, 2] - c2 * tang2[i, 2]) / am2[i] - 2.0 * kv1[i, 2]
        ty = bm[i] * (tang[i, 0] * y0 + tang[i, 1] * y1 + tang[i, 2] * y2)
        _kx_times(sq, sa, sg, Kz, kx2, i, tmp3)
        rhs[i, 0] = am[i] * y0 + ty * tang[i, 0] + gh * tmp3[0]
        rhs[i, 1] = am[i] * y1 + ty * tang[i, 1] + gh * tmp3[1]
        rhs[i, 2] = am[i] * y2 + ty * tang[i, 2] + gh * tmp3[2]
    for a in range(3):
        rhs[N - 1, a] -= gh * qa * sq[N - 1, a]
    _solve_blocks(S, Winv, rhs, kv2, N, tmp3)
    # ---- update
    for i in range(1, N):
        for a in range(3):
            kxa = kx2[i, a] + gh * kv2[i, a]
            r[i, a] += h * (1.5 * kx1[i, a] + 0.5 * kxa)
            v[i, a] += h * (1.5 * kv1[i, a] + 0.5 * kv2[i, a])
    for a in range(3):
        r[N, a] = rf1[a]
        v[N, a] = vf1[a]


@njit(cache=True, inline="always", error_model="numpy")
def _bdf2_step(r, v, rp, vp, rf1, vf1, h, p, w):
    """One linearly implicit BDF2 step of one line (constant step h; rp, vp the previous state).

    ``x' = 4/3 x_n - 1/3 x_n-1 + 2/3 h v'`` and ``M (v' - 4/3 v_n + 1/3 v_n-1) = 2/3 h F(x', v')``
    with F linearised once about the extrapolation ``(2 y_n - y_n-1)``; the fairlead is
    at its prescribed position. One force evaluation, one factorisation, one solve.
    On return (r, v) hold the new state and (rp, vp) the old one.
    """
    ws1, ws2, S, Winv, D, tmpm, rhs, kx1, kv1, kx2, kv2, r2, v2, tmp3 = w
    F, segf, sq, sa, sg, tang, am, bm, C, Kz = ws1
    N = int(p[_N])
    beta = 2.0 * h / 3.0
    for a in range(3):
        r2[0, a] = r[0, a]
        v2[0, a] = 0.0
        r2[N, a] = rf1[a]
        v2[N, a] = vf1[a]
        kx2[0, a] = 0.0
        kx2[N, a] = 0.0
    for i in range(1, N):
        for a in range(3):
            r2[i, a] = 2.0 * r[i, a] - rp[i, a]  # predictor x*
            v2[i, a] = 2.0 * v[i, a] - vp[i, a]  # predictor v*
            kx1[i, a] = (4.0 * r[i, a] - rp[i, a]) / 3.0  # xb
            kv1[i, a] = (4.0 * v[i, a] - vp[i, a]) / 3.0 - v2[i, a]  # vb - v*
            kx2[i, a] = kx1[i, a] + beta * v2[i, a] - r2[i, a]  # xb + beta v* - x*
    _node_forces(r2, v2, p, h, True, ws1)
    _factor(ws1, S, Winv, D, tmpm, N, beta * p[_CINT], beta * beta, beta)
    for i in range(1, N):
        _kx_times(sq, sa, sg, Kz, kx2, i, tmp3)
        tv = bm[i] * (tang[i, 0] * kv1[i, 0] + tang[i, 1] * kv1[i, 1] + tang[i, 2] * kv1[i, 2])
        for a in range(3):
            rhs[i, a] = am[i] * kv1[i, a] + tv * tang[i, a] + beta * (F[i, a] + tmp3[a])
    _solve_blocks(S, Winv, rhs, kv2, N, tmp3)
    for i in range(1, N):
        for a in range(3):
            vn = v2[i, a] + kv2[i, a]
            rp[i, a] = r[i, a]
            vp[i, a] = v[i, a]
            v[i, a] = vn
            r[i, a] = kx1[i, a] + beta * vn
    for a in range(3):
        rp[N, a] = r[N, a]
        vp[N, a] = v[N, a]
        r[N, a] = rf1[a]
        v[N, a] = vf1[a]


@njit(cache=True, error_model="numpy")
def _static_solve(r, p, w, iters, tol):
    """Newton iterations on the static node equilibrium of one line (fairlead and anchor fixed).

    Returns the largest remaining interior force imbalance, N.
    """
    ws1, ws2, S, Winv, D, tmpm, rhs, kx1, kv1, kx2, kv2, r2, v2, tmp3 = w
    F = ws1[0]
    N = int(p[_N])
    for i in range(N + 1):
        for a in range(3):
            v2[i, a] = 0.0
    res = 0.0
    for _ in range(iters):
        _node_forces(r, v2, p, 0.0, True, ws1)
        res = 0.0
        for i in range(1, N):
            for a in range(3):
                res = max(res, abs(F[i, a]))
        if res < tol:
            break
        # Newton matrix: segment and seabed stiffness only (no mass, no damping)
        am, bm = ws1[6], ws1[7]
        for i in range(N + 1):
            am[i] = 0.0
            bm[i] = 0.0
        _factor(ws1, S, Winv, D, tmpm, N, 0.0, 1.0, 0.0)
        _solve_blocks(S, Winv, F, kx1, N, tmp3)
        big = 0.0
        for i in range(1, N):
            for a in range(3):
                big = max(big, abs(kx1[i, a]))
        scale = min(1.0, 1.0 / big) if big > 0.0 else 1.0
        for i in range(1, N):
            for a in range(3):
                r[i, a] += scale * kx1[i, a]
    return res


@njit(cache=True, inline="always", error_model="numpy")
def _hermite(p0, v0, p1, v1, T, s, pos, vel):
    """Cubic Hermite position and velocity at fraction s of an interval of length T."""
    s2 = s * s
    s3 = s2 * s
    h00 = 2 * s3 - 3 * s2 + 1
    h10 = s3 - 2 * s2 + s
    h01 = -2 * s3 + 3 * s2
    h11 = s3 - s2
    d00 = (6 * s2 - 6 * s) / T
    d10 = 3 * s2 - 4 * s + 1
    d01 = (-6 * s2 + 6 * s) / T
    d11 = 3 * s2 - 2 * s
    for a in range(3):
        pos[a] = h00 * p0[a] + h10 * T * v0[a] + h01 * p1[a] + h11 * T * v1[a]
        vel[a] = d00 * p0[a] + d10 * v0[a] + d01 * p1[a] + d11 * v1[a]


class DynamicState(NamedTuple):
    """State of a batch of line sets (arrays updated in place by :func:`step_lines`).

    A record of arrays that the compiled step takes as it is (a ``NamedTuple``).

    Attributes
    ----------
    r, v : numpy.ndarray, shape (B, L, N + 1, 3)
        Node positions (m) and velocities (m/s); node 0 anchor, node N fairlead.
    forces : numpy.ndarray, shape (B, L, 3)
        Force of each line on the platform at its fairlead, N (global frame).
    tension : numpy.ndarray, shape (B, L)
        Its magnitude, N.
    r_prev, v_prev : numpy.ndarray, shape (B, L, N + 1, 3)
        The previous step's node state (BDF2 history).
    step_prev : numpy.ndarray, shape (B, L)
        Length of the previous internal step, s (0: no history, the next step is ROS2).
    """

    r: np.ndarray
    v: np.ndarray
    forces: np.ndarray
    tension: np.ndarray
    r_prev: np.ndarray
    v_prev: np.ndarray
    step_prev: np.ndarray


class LineKernel(NamedTuple):
    """What :func:`step_lines` needs of a line model besides the state (fixed for a model).

    Attributes
    ----------
    params : numpy.ndarray, shape (18,)
        The parameter vector of :class:`LineModel`.
    work : numpy.ndarray
        The flat work buffer of one line step (one per model instance and thread).
    scheme : int
        0: ROS2 every step; 1: BDF2 (``mooring.integrator``).
    """

    params: np.ndarray
    work: np.ndarray
    scheme: int


@njit(cache=True, error_model="numpy")
def step_lines(state, r_new, v_new, dt, nsub, kernel):
    """The compiled step of the dynamic model: advance every line of every batch member by ``dt``.

    Parameters
    ----------
    state : DynamicState
        Updated in place; ``state.forces`` and ``state.tension`` take the fairlead forces on the
        platform and their magnitudes at the end of the step.
    r_new, v_new : numpy.ndarray, shape (B, L, 3)
        Fairlead positions and velocities at the end of the step (the path within the step is
        the cubic Hermite curve from the previous ones).
    dt : float
        Step, s (> 0).
    nsub : int
        Internal substeps, :meth:`DynamicMooring.substeps`.
    kernel : LineKernel
        The line model (``DynamicMooring.kernel``). ``scheme`` 0: ROS2 every step; 1: BDF2
        whenever the previous step had the same length (``state.step_prev[b, k]``), ROS2
        otherwise (first step, changed step).

    Raises
    ------
    FloatingPointError
        On a non-finite fairlead tension.
    """
    r, v, rp, vp, hist = state.r, state.v, state.r_prev, state.v_prev, state.step_prev
    forces, tension = state.forces, state.tension
    p, buf, scheme = kernel.params, kernel.work, kernel.scheme
    nb, nl = r.shape[0], r.shape[1]
    N = int(p[_N])
    w, vec = _views(buf, N)
    fa, fb, va, vb, p0, v0 = vec[0], vec[1], vec[2], vec[3], vec[4], vec[5]
    h = dt / nsub
    for b in range(nb):
        for k in range(nl):
            rr = r[b, k]
            vv = v[b, k]
            for a in range(3):
                fa[a] = rr[N, a]
                va[a] = vv[N, a]
                p0[a] = rr[N, a]
                v0[a] = vv[N, a]
            for j in range(nsub):
                _hermite(p0, v0, r_new[b, k], v_new[b, k], dt, (j + 1) / nsub, fb, vb)
                if scheme == 1 and hist[b, k] == h:
                    _bdf2_step(rr, vv, rp[b, k], vp[b, k], fb, vb, h, p, w)
                else:
                    if scheme == 1:
                        for i in range(N + 1):
                            for a in range(3):
                                rp[b, k, i, a] = rr[i, a]
                                vp[b, k, i, a] = vv[i, a]
                    _ros2_step(rr, vv, fa, va, fb, vb, h, p, w)
                    hist[b, k] = h
                for a in range(3):
                    fa[a] = fb[a]
                    va[a] = vb[a]
            _end_force(rr, vv, p, forces[b, k])
            tension[b, k] = math.sqrt(forces[b, k, 0] ** 2 + forces[b, k, 1] ** 2 + forces[b, k, 2] ** 2)
            if not math.isfinite(tension[b, k]):
                raise FloatingPointError("non-finite fairlead tension")


@njit(cache=True, error_model="numpy")
def _step_batch(state, r_new, v_new, dt, nsub, kernel):
    """:func:`step_lines` called from Python with plain tuples (a cheaper dispatch than records)."""
    step_lines(DynamicState(*state), r_new, v_new, dt, nsub, LineKernel(*kernel))


@njit(cache=True, error_model="numpy")
def _node_forces_flat(r, v, p, buf):
    w, _ = _views(buf, int(p[_N]))
    ws = w[0]
    _node_forces(r, v, p, 0.0, True, ws)
    return ws[0].copy(), ws[5].copy(), ws[6].copy(), ws[7].copy()


@njit(cache=True, error_model="numpy")
def _static_solve_flat(r, p, buf, iters, tol):
    w, _ = _views(buf, int(p[_N]))
    return _static_solve(r, p, w, iters, tol)


def node_forces(model: LineModel, r: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Net force on every node and the node mass matrices (for checks and diagnostics).

    Parameters
    ----------
    model : LineModel
    r, v : numpy.ndarray, shape (N + 1, 3)
        Node positions (m) and velocities (m/s).

    Returns
    -------
    F : numpy.ndarray, shape (N + 1, 3)
        Net force (tension, internal damping, weight, drag, seabed), N.
    M : numpy.ndarray, shape (N + 1, 3, 3)
        Mass plus added mass, kg.
    """
    buf = _workspace(model.n_segments)
    F, tang, am, bm = _node_forces_flat(
        np.ascontiguousarray(r, float), np.ascontiguousarray(v, float), model.params, buf
    )
    M = am[:, None, None] * np.eye(3) + bm[:, None, None] * tang[:, :, None] * tang[:, None, :]
    return F, M


def hermite(
    p0: np.ndarray, v0: np.ndarray, p1: np.ndarray, v1: np.ndarray, T: float, s: float
) -> tuple[np.ndarray, np.ndarray]:
    """Cubic Hermite interpolation of a 3-D motion, position and velocity at fraction ``s``."""
    pos = np.empty(3)
    vel = np.empty(3)
    _hermite(
        np.asarray(p0, float),
        np.asarray(v0, float),
        np.asarray(p1, float),
        np.asarray(v1, float),
        float(T),
        float(s),
        pos,
        vel,
    )
    return pos, vel


def initial_nodes(
    model: LineModel, anchor: np.ndarray, fairlead: np.ndarray, length: float, props: LineProperties
) -> np.ndarray:
    """Node positions ``(N + 1, 3)`` on the static frictionless catenary between anchor and fairlead."""
    p = model.params
    N = int(p[_N])
    d = np.asarray(fairlead, float) - np.asarray(anchor, float)
    X = float(np.hypot(d[0], d[1]))
    Z = float(d[2])
    H, V = catenary_solve(X, Z, length, props.EA, p[_WLEN])
    prof = catenary_profile(np.linspace(0.0, length, N + 1), H, V, length, props.EA, p[_WLEN])
    e = d[:2] / X
    out = np.empty((N + 1, 3))
    out[:, 0] = anchor[0] + prof[:, 0] * e[0]
    out[:, 1] = anchor[1] + prof[:, 0] * e[1]
    out[:, 2] = anchor[2] + prof[:, 1]
    out[0] = anchor
    out[N] = fairlead
    return out


class DynamicMooring:
    """Lumped-mass lines with the simulator interface (see :mod:`moorlife.mooring`).

    One instance holds one work buffer: use one instance per thread (Dask workers are
    processes, so this is the default). States from :meth:`init` are independent.
    """

    kind = "dynamic"

    def __init__(
        self, model: LineModel, props: LineProperties, layout: Layout, settings: MooringSettings, batch: int
    ) -> None:
        self.model = model
        self.props = props
        self.layout = layout
        self.settings = settings
        self.batch = int(batch)
        #: The line model as :func:`step_lines` takes it.
        self.kernel = LineKernel(
            model.params, _workspace(model.n_segments), {"ros2": 0, "bdf2": 1}[settings.integrator]
        )
        self._w = self.kernel.work
        self._kernel_args = tuple(self.kernel)

    def init(self, r_fair: np.ndarray, relax: float | None = None) -> DynamicState:
        """Static catenary shape at fairlead positions ``r_fair (B, L, 3)``, then relaxed.

        The lines start on the frictionless elastic catenary and are integrated with the
        fairleads held still for ``relax`` s (default ``settings.relaxation_time``), which
        settles the discretisation and seabed-spring differences.
        """
        r_fair = np.asarray(r_fair, dtype=float)
        B, L = r_fair.shape[:2]
        N = self.model.n_segments
        r = np.empty((B, L, N + 1, 3))
        for b in range(B):
            for k in range(L):
                r[b, k] = initial_nodes(
                    self.model, self.layout.anchors[k], r_fair[b, k], self.layout.length, self.props
                )
        tol = 1e-6 * self.props.wet_weight * self.layout.length
        for b in range(B):
            for k in range(L):
                shape = r[b, k].copy()
                _static_solve_flat(r[b, k], self.model.params, self._w, 200, tol)
                if not np.isfinite(r[b, k]).all():
                    # Newton on a slack line with most of it on the seabed can meet a singular
                    # matrix: the relaxation below settles the line from its catenary instead
                    r[b, k] = shape
        state = DynamicState(
            r=r,
            v=np.zeros_like(r),
            forces=np.zeros((B, L, 3)),
            tension=np.zeros((B, L)),
            r_prev=r.copy(),
            v_prev=np.zeros_like(r),
            step_prev=np.zeros((B, L)),
        )
        relax = self.settings.relaxation_time if relax is None else float(relax)
        zero = np.zeros((B, L, 3))
        fixed = np.ascontiguousarray(r_fair)
        dt_relax = 4.0 * self.settings.max_time_step
        n = int(math.ceil(relax / dt_relax))
        for _ in range(n):
            self.step(state, fixed, zero, dt_relax)
        if n == 0:
            self.step(state, fixed, zero, 0.0)
        state.v[...] = 0.0
        state.step_prev[...] = 0.0
        return state

    def step(self, state: DynamicState, r_fair: np.ndarray, v_fair: np.ndarray, dt: float):
        """Advance by ``dt`` to fairlead positions/velocities ``(B, L, 3)``; return ``(forces, state)``.

        The fairlead path within the step is the cubic Hermite curve between the previous
        and the new position and velocity; the step is cut into ``ceil(dt / max_time_step)``
        ROS2 substeps. ``forces (B, L, 3)`` is a view into the state (overwritten next call).
        """
        r_fair = np.ascontiguousarray(r_fair, dtype=float)
        v_fair = np.ascontiguousarray(v_fair, dtype=float)
        if r_fair.shape != state.forces.shape or v_fair.shape != state.forces.shape:
            raise ValueError(
                f"fairlead positions {r_fair.shape} and velocities {v_fair.shape} must have the state's "
                f"shape (batch, lines, 3) = {state.forces.shape}"
            )
        nsub = self.substeps(dt)
        if dt <= 0.0:
            nsub, dt = 1, 1e-6
        try:
            _step_batch(tuple(state), r_fair, v_fair, float(dt), nsub, self._kernel_args)
        except FloatingPointError:
            bad = np.argwhere(~np.isfinite(r_fair).all(axis=-1) | ~np.isfinite(v_fair).all(axis=-1))
            where = (
                f"non-finite fairlead input at (batch, line) {bad[0].tolist()}" if bad.size else "line state diverged"
            )
            raise FloatingPointError(
                f"dynamic mooring ({self.props.name}): non-finite fairlead tension; {where} (dt = {dt} s)"
            ) from None
        return state.forces, state

    def substeps(self, dt: float) -> int:
        """Number of internal substeps of a step ``dt``: ``ceil(dt / max_time_step)``, at least 1."""
        return max(1, int(math.ceil(dt / self.settings.max_time_step - 1e-9)))

    def tension(self, state: DynamicState) -> np.ndarray:
        """Fairlead tension magnitude ``(B, L)``, N."""
        return state.tension

    def forces(self, state: DynamicState) -> np.ndarray:
        """Force on the platform ``(B, L, 3)``, N."""
        return state.forces
