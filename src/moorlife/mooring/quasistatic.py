"""Quasi-static mooring: elastic catenary with seabed contact and friction, and a fast
precomputed force-displacement surface.

The catenary is the classic elastic formulation (Jonkman 2007, FAST v7 / MAP / MoorPy
``catenary``): an extensible line of submerged weight ``w`` per unit length and axial
stiffness ``EA`` hangs from its fairlead; the part lying on the seabed may carry axial
(Coulomb) friction ``CB * w`` per unit length. Given the horizontal span ``XF`` and vertical
height ``ZF`` of the fairlead above the anchor, Newton's method solves for the fairlead
horizontal and vertical force ``(HF, VF)``.

For the time-domain simulator the solution is tabulated once per line type on a regular
``(span, height)`` grid around the rest position (the "force-displacement surface") and
interpolated bilinearly in a numba kernel; points outside the grid fall back on the exact
Newton solve, so the model is never extrapolated.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from moorlife.mooring.lines import Layout, LineProperties, MooringSettings

__all__ = [
    "ForceTable",
    "QuasiStaticState",
    "step_lines",
    "QuasiStaticMooring",
    "catenary_solve",
    "catenary",
    "catenary_profile",
    "force_table",
    "table_lookup",
    "fairlead_forces",
    "line_stiffness",
]


# --------------------------------------------------------------------------- records
class ForceTable(NamedTuple):
    """Fairlead force on a regular ``(span, height)`` grid for one line type (a record the
    compiled :func:`step_lines` takes as it is).

    Attributes
    ----------
    span0, height0 : float
        First grid span and height, m.
    d_span, d_height : float
        Grid spacing, m.
    H, V : numpy.ndarray, shape (n_span, n_height)
        Horizontal and vertical fairlead force, N.
    length, EA, w, friction : float
        The line (m, N, N/m, -) used outside the grid.
    """

    span0: float
    height0: float
    d_span: float
    d_height: float
    H: np.ndarray
    V: np.ndarray
    length: float
    EA: float
    w: float
    friction: float

    def args(self) -> tuple:
        """Positional arguments of the numba kernels after the geometry."""
        return (
            self.span0,
            self.height0,
            self.d_span,
            self.d_height,
            self.H,
            self.V,
            self.length,
            self.EA,
            self.w,
            self.friction,
        )


class QuasiStaticState(NamedTuple):
    """State of the quasi-static model: the last fairlead forces and tensions (updated in place).

    Attributes
    ----------
    forces : numpy.ndarray, shape (B, L, 3)
        Force of each line on the platform, N.
    tension : numpy.ndarray, shape (B, L)
        Fairlead tension magnitude, N.
    """

    forces: np.ndarray
    tension: np.ndarray


# --------------------------------------------------------------------------- kernels
@njit(cache=True)
def _catenary_eqs(H, V, L, EA, w, CB):
    """Span, height and their Jacobian w.r.t. (H, V) for fairlead forces (H, V)."""
    vh = V / H
    sv = math.sqrt(1.0 + vh * vh)
    if V >= w * L:  # fully suspended
        Va = V - w * L
        ah = Va / H
        sa = math.sqrt(1.0 + ah * ah)
        X = H / w * (math.asinh(vh) - math.asinh(ah)) + H * L / EA
        Z = H / w * (sv - sa) + (V * L - 0.5 * w * L * L) / EA
        dXdH = (math.asinh(vh) - math.asinh(ah)) / w - (vh / sv - ah / sa) / w + L / EA
        dXdV = (1.0 / sv - 1.0 / sa) / w
        dZdH = (sv - sa) / w - (vh * vh / sv - ah * ah / sa) / w
        dZdV = (vh / sv - ah / sa) / w + L / EA
    else:  # part of the line rests on the seabed
        LB = L - V / w
        X = LB + H / w * math.asinh(vh) + H * L / EA
        dXdH = math.asinh(vh) / w - vh / (w * sv) + L / EA
        dXdV = -1.0 / w + 1.0 / (w * sv)
        if CB > 0.0:
            x0 = LB - H / (CB * w)
            if x0 > 0.0:
                X += CB * w / (2.0 * EA) * (-LB * LB + x0 * x0)
                dXdH += -x0 / EA
                dXdV += H / (EA * w)
            else:
                X += CB * w / (2.0 * EA) * (-LB * LB)
                dXdV += CB * LB / EA
        Z = H / w * (sv - 1.0) + V * V / (2.0 * EA * w)
        dZdH = (sv - 1.0 - vh * vh / sv) / w
        dZdV = vh / sv / w + V / (EA * w)
    return X, Z, dXdH, dXdV, dZdH, dZdV


@njit(cache=True)
def _initial_guess(XF, ZF, L, w):
    if XF <= 0.0:
        lam = 1.0e6
    elif L * L <= XF * XF + ZF * ZF:
        lam = 0.2
    else:
        lam = math.sqrt(3.0 * ((L * L - ZF * ZF) / (XF * XF) - 1.0))
    H = max(abs(w * XF / (2.0 * lam)), 1e-3 * w * L)
    V = 0.5 * w * (ZF / math.tanh(lam) + L)
    return H, V


@njit(cache=True)
def _solve(XF, ZF, L, EA, w, CB, H0, V0, tol, maxiter):
    """Newton solve of the catenary equations; returns (H, V, converged)."""
    if H0 > 0.0:
        H, V = H0, V0
    else:
        H, V = _initial_guess(XF, ZF, L, w)
    for _ in range(maxiter):
        X, Z, a, b, c, d = _catenary_eqs(H, V, L, EA, w, CB)
        rx = X - XF
        rz = Z - ZF
        if abs(rx) < tol and abs(rz) < tol:
            return H, V, True
        det = a * d - b * c
        if det == 0.0 or not math.isfinite(det):
            return H, V, False
        dH = -(d * rx - b * rz) / det
        dV = -(-c * rx + a * rz) / det
        # keep H positive and damp large steps
        if H + dH < 0.1 * H:
            s = 0.9 * H / abs(dH)
            dH *= s
            dV *= s
        H += dH
        V += dV
    X, Z, a, b, c, d = _catenary_eqs(H, V, L, EA, w, CB)
    return H, V, abs(X - XF) < 1e3 * tol and abs(Z - ZF) < 1e3 * tol


@njit(cache=True)
def _solve_robust(XF, ZF, L, EA, w, CB, H0, V0, tol):
    H, V, ok = _solve(XF, ZF, L, EA, w, CB, H0, V0, tol, 60)
    if not ok and H0 > 0.0:
        H, V, ok = _solve(XF, ZF, L, EA, w, CB, 0.0, 0.0, tol, 200)
    return H, V, ok


@njit(cache=True)
def _build_table(table, tol, ok):
    """Fill ``table.H`` and ``table.V`` (and ``ok``, converged) at every grid node."""
    x0, z0, dx, dz, H, V = table.span0, table.height0, table.d_span, table.d_height, table.H, table.V
    L, EA, w, CB = table.length, table.EA, table.w, table.friction
    nx, nz = H.shape
    Hr, Vr = 0.0, 0.0
    for j in range(nz):
        Hp, Vp = Hr, Vr
        for i in range(nx):
            h, v, good = _solve_robust(x0 + i * dx, z0 + j * dz, L, EA, w, CB, Hp, Vp, tol)
            H[i, j] = h
            V[i, j] = v
            ok[i, j] = good
            Hp, Vp = h, v
            if i == 0:
                Hr, Vr = h, v


@njit(cache=True)
def _lookup(XF, ZF, x0, z0, dx, dz, H, V, L, EA, w, CB):
    nx, nz = H.shape
    fx = (XF - x0) / dx
    fz = (ZF - z0) / dz
    i = int(math.floor(fx))
    j = int(math.floor(fz))
    if i < 0 or j < 0 or i >= nx - 1 or j >= nz - 1 or not (math.isfinite(XF) and math.isfinite(ZF)):
        h, v, ok = _solve_robust(XF, ZF, L, EA, w, CB, 0.0, 0.0, 1e-8 * L)
        if not ok:
            raise FloatingPointError("catenary did not converge outside the force table")
        return h, v
    tx = fx - i
    tz = fz - j
    h = (
        (1 - tx) * (1 - tz) * H[i, j]
        + tx * (1 - tz) * H[i + 1, j]
        + (1 - tx) * tz * H[i, j + 1]
        + tx * tz * H[i + 1, j + 1]
    )
    v = (
        (1 - tx) * (1 - tz) * V[i, j]
        + tx * (1 - tz) * V[i + 1, j]
        + (1 - tx) * tz * V[i, j + 1]
        + tx * tz * V[i + 1, j + 1]
    )
    return h, v


@njit(cache=True)
def step_lines(state, r_fair, anchors, table):
    """The compiled step of the quasi-static model: the fairlead forces at ``r_fair``.

    Parameters
    ----------
    state : QuasiStaticState
        Its ``forces (B, L, 3)`` (on the platform, N) and ``tension (B, L)`` (N) are overwritten.
    r_fair : numpy.ndarray, shape (B, L, 3)
        Fairlead positions (global frame), m.
    anchors : numpy.ndarray, shape (L, 3)
        Anchor positions, m.
    table : ForceTable
        The force-displacement surface (exact catenary outside it).
    """
    forces, tension = state.forces, state.tension
    x0, z0, dx, dz, H, V = table.span0, table.height0, table.d_span, table.d_height, table.H, table.V
    L, EA, w, CB = table.length, table.EA, table.w, table.friction
    nb = r_fair.shape[0]
    nl = r_fair.shape[1]
    for b in range(nb):
        for k in range(nl):
            ex = r_fair[b, k, 0] - anchors[k, 0]
            ey = r_fair[b, k, 1] - anchors[k, 1]
            XF = math.sqrt(ex * ex + ey * ey)
            ZF = r_fair[b, k, 2] - anchors[k, 2]
            h, v = _lookup(XF, ZF, x0, z0, dx, dz, H, V, L, EA, w, CB)
            forces[b, k, 0] = -h * ex / XF
            forces[b, k, 1] = -h * ey / XF
            forces[b, k, 2] = -v
            tension[b, k] = math.sqrt(h * h + v * v)


@njit(cache=True)
def _fairlead_forces(r_fair, anchors, table, forces, tension):
    """:func:`step_lines` called from Python with a plain tuple ``table`` (a cheaper dispatch)."""
    step_lines(QuasiStaticState(forces, tension), r_fair, anchors, ForceTable(*table))


# --------------------------------------------------------------------------- public API
def catenary_solve(
    span: float, height: float, length: float, EA: float, w: float, friction: float = 0.0, tol: float | None = None
) -> tuple[float, float]:
    """Fairlead horizontal and vertical force of an elastic catenary with seabed contact.

    Parameters
    ----------
    span : float
        Horizontal distance anchor -> fairlead ``XF``, m.
    height : float
        Fairlead height above the anchor ``ZF``, m (anchor on the seabed).
    length : float
        Unstretched line length, m.
    EA : float
        Axial stiffness, N.
    w : float
        Submerged weight per unit length, N/m.
    friction : float
        Seabed axial friction coefficient ``CB`` (0: no friction).
    tol : float, optional
        Geometric tolerance, m (default ``1e-9 * length``).

    Returns
    -------
    (HF, VF) : tuple of float
        Horizontal and vertical force the line exerts on its fairlead support (magnitudes), N.

    Raises
    ------
    RuntimeError
        If Newton's method does not converge (naming the span and height).
    """
    tol = 1e-9 * length if tol is None else tol
    H, V, ok = _solve_robust(
        float(span), float(height), float(length), float(EA), float(w), float(friction), 0.0, 0.0, tol
    )
    if not ok:
        raise RuntimeError(f"catenary did not converge for span={span} m, height={height} m, length={length} m")
    return float(H), float(V)


def catenary(
    span: float, height: float, props: LineProperties, length: float, friction: float = 0.0
) -> dict[str, float]:
    """Catenary solution with tension and 2x2 stiffness, for a line type.

    Returns
    -------
    dict
        ``H, V`` (N), ``tension`` (N, at the fairlead), ``anchor_tension`` (N, without
        friction: ``sqrt(H**2 + max(V - wL, 0)**2)``), ``touchdown_length`` (m of line on the
        seabed), and the stiffness ``dH/dX, dH/dZ, dV/dX, dV/dZ`` (N/m).
    """
    H, V = catenary_solve(span, height, length, props.EA, props.wet_weight, friction)
    _, _, a, b, c, d = _catenary_eqs(H, V, length, props.EA, props.wet_weight, friction)
    det = a * d - b * c
    w = props.wet_weight
    return {
        "H": H,
        "V": V,
        "tension": float(np.hypot(H, V)),
        "anchor_tension": float(np.hypot(H, max(V - w * length, 0.0))),
        "touchdown_length": float(max(length - V / w, 0.0)),
        "dH/dX": d / det,
        "dH/dZ": -b / det,
        "dV/dX": -c / det,
        "dV/dZ": a / det,
    }


def catenary_profile(s: np.ndarray, H: float, V: float, length: float, EA: float, w: float) -> np.ndarray:
    """Shape of a frictionless catenary at unstretched arc lengths ``s`` from the anchor.

    Parameters
    ----------
    s : numpy.ndarray, shape (n,)
        Unstretched arc lengths in ``[0, length]``, m.
    H, V : float
        Fairlead forces from :func:`catenary_solve` (with ``friction=0``), N.
    length, EA, w : float
        m, N, N/m.

    Returns
    -------
    numpy.ndarray, shape (n, 2)
        Horizontal distance from the anchor and height above it, m.
    """
    s = np.asarray(s, dtype=float)
    out = np.zeros((s.size, 2))
    if V >= w * length:
        Va = V - w * length
        out[:, 0] = H / w * (np.arcsinh((Va + w * s) / H) - np.arcsinh(Va / H)) + H * s / EA
        out[:, 1] = (
            H / w * (np.sqrt(1 + ((Va + w * s) / H) ** 2) - np.sqrt(1 + (Va / H) ** 2)) + (Va * s + 0.5 * w * s**2) / EA
        )
        return out
    LB = length - V / w
    on = s <= LB
    out[on, 0] = s[on] * (1.0 + H / EA)
    sl = s[~on] - LB
    out[~on, 0] = LB * (1.0 + H / EA) + H / w * np.arcsinh(w * sl / H) + H * sl / EA
    out[~on, 1] = H / w * (np.sqrt(1 + (w * sl / H) ** 2) - 1.0) + w * sl**2 / (2 * EA)
    return out


def force_table(props: LineProperties, layout: Layout, settings: MooringSettings) -> ForceTable:
    """Tabulate the catenary fairlead force around the rest position.

    The grid spans ``rest span +- settings.table_span_range`` and ``rest height +-
    settings.table_height_range`` at ``settings.table_resolution`` m (bilinear error below
    1e-4 of the tension at 0.1-0.25 m; see ``tests/test_mooring_quasistatic.py``).

    Raises
    ------
    RuntimeError
        If the catenary fails to converge at any grid node.
    """
    fair = layout.fairleads_body[0]
    anch = layout.anchors[0]
    X0 = float(np.hypot(*(fair[:2] - anch[:2])))
    Z0 = float(fair[2] - anch[2])
    res = settings.table_resolution
    nx = int(round(2 * settings.table_span_range / res)) + 1
    nz = int(round(2 * settings.table_height_range / res)) + 1
    x0 = X0 - settings.table_span_range
    z0 = max(Z0 - settings.table_height_range, res)
    H = np.empty((nx, nz))
    V = np.empty((nx, nz))
    ok = np.empty((nx, nz), dtype=np.bool_)
    mu = settings.friction_coefficient
    table = ForceTable(x0, z0, res, res, H, V, layout.length, props.EA, props.wet_weight, mu)
    _build_table(table, 1e-9 * layout.length, ok)
    if not ok.all():
        i, j = np.argwhere(~ok)[0]
        raise RuntimeError(
            f"{props.name}: catenary did not converge at span {x0 + i * res:.3f} m, height {z0 + j * res:.3f} m"
        )
    H.setflags(write=False)
    V.setflags(write=False)
    return table


def table_lookup(table: ForceTable, span: np.ndarray, height: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Interpolated ``(H, V)`` (N) at arrays of spans and heights (m), same shape."""
    span = np.asarray(span, dtype=float)
    height = np.broadcast_to(np.asarray(height, dtype=float), span.shape)
    H = np.empty(span.shape)
    V = np.empty(span.shape)
    for idx in np.ndindex(span.shape):
        H[idx], V[idx] = _lookup(span[idx], height[idx], *table.args())
    return H, V


def fairlead_forces(
    table: ForceTable,
    anchors: np.ndarray,
    r_fair: np.ndarray,
    forces: np.ndarray | None = None,
    tension: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Force on the platform at each fairlead from the force-displacement surface.

    Parameters
    ----------
    table : ForceTable
    anchors : numpy.ndarray, shape (L, 3)
        Anchor positions, m.
    r_fair : numpy.ndarray, shape (B, L, 3)
        Fairlead positions (global frame), m.
    forces, tension : numpy.ndarray, optional
        Output buffers ``(B, L, 3)`` and ``(B, L)``.

    Returns
    -------
    forces : numpy.ndarray, shape (B, L, 3)
        Force of each line on the platform, N (points towards the anchor and down).
    tension : numpy.ndarray, shape (B, L)
        Fairlead tension magnitude, N.
    """
    r_fair = np.ascontiguousarray(r_fair, dtype=float)
    if forces is None:
        forces = np.empty(r_fair.shape)
    if tension is None:
        tension = np.empty(r_fair.shape[:2])
    _fairlead_forces(r_fair, np.ascontiguousarray(anchors, dtype=float), tuple(table), forces, tension)
    return QuasiStaticState(forces, tension)


def line_stiffness(
    span: float, height: float, direction: np.ndarray, props: LineProperties, length: float, friction: float = 0.0
) -> np.ndarray:
    """3x3 stiffness ``-dF/dr`` (N/m) of one line's force on the platform w.r.t. its fairlead.

    Parameters
    ----------
    span, height : float
        Fairlead span and height above the anchor, m.
    direction : numpy.ndarray, shape (2,)
        Horizontal unit vector from the anchor to the fairlead.
    """
    c = catenary(span, height, props, length, friction)
    e = np.asarray(direction, dtype=float)
    e = e / np.linalg.norm(e)
    K = np.zeros((3, 3))
    P = np.outer(e, e)
    K[:2, :2] = c["dH/dX"] * P + c["H"] / span * (np.eye(2) - P)
    K[:2, 2] = c["dH/dZ"] * e
    K[2, :2] = c["dV/dX"] * e
    K[2, 2] = c["dV/dZ"]
    return K


class QuasiStaticMooring:
    """Quasi-static model with the simulator interface (see :mod:`moorlife.mooring`).

    The state is the last force and tension, ``(forces (B, L, 3), tension (B, L))``;
    velocities and ``dt`` are ignored (no line dynamics).
    """

    kind = "quasistatic"

    def __init__(self, table: ForceTable, layout: Layout, batch: int) -> None:
        self.table = table
        self._table_args = tuple(table)
        self.anchors = np.ascontiguousarray(layout.anchors, dtype=float)
        self.batch = int(batch)
        self.n_lines = layout.n_lines

    def init(self, r_fair: np.ndarray) -> QuasiStaticState:
        """State at fairlead positions ``r_fair (B, L, 3)``."""
        return fairlead_forces(self.table, self.anchors, r_fair)

    def step(self, state, r_fair, v_fair, dt):  # noqa: ARG002 - same signature as the dynamic model
        """Forces ``(B, L, 3)`` on the platform at ``r_fair``; returns ``(forces, state)``."""
        forces, tension = state
        _fairlead_forces(np.ascontiguousarray(r_fair, dtype=float), self.anchors, self._table_args, forces, tension)
        return forces, state

    def tension(self, state) -> np.ndarray:
        """Fairlead tension magnitude ``(B, L)``, N."""
        return state[1]

    def forces(self, state) -> np.ndarray:
        """Force on the platform ``(B, L, 3)``, N."""
        return state[0]
