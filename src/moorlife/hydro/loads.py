"""Wave loads on the platform: first-order excitation and mean drift at a heading, Newman's
slow drift, and Morison drag on the members' strips."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from moorlife.hydro.mesh import Member

if TYPE_CHECKING:  # annotations only: the model module imports this one
    from moorlife.hydro.model import PlatformModel


# ----------------------------------------------------------- excitation and drift


def interp_heading(headings: np.ndarray, values: np.ndarray, heading: float) -> np.ndarray:
    """Linear interpolation in heading on the circle.

    Parameters
    ----------
    headings : ``(nh,)`` rad, increasing, any covering of the circle (wraps around).
    values : ``(nw, nh, ...)``.
    heading : float, rad (propagation angle).

    Returns
    -------
    numpy.ndarray ``(nw, ...)``
    """
    h = np.mod(np.asarray(headings, dtype=float), 2 * np.pi)
    order = np.argsort(h)
    h = h[order]
    v = np.take(values, order, axis=1)
    x = float(np.mod(heading, 2 * np.pi))
    hh = np.concatenate([h[-1:] - 2 * np.pi, h, h[:1] + 2 * np.pi])
    vv = np.concatenate([v[:, -1:], v, v[:, :1]], axis=1)
    j = int(np.searchsorted(hh, x, side="right")) - 1
    j = min(max(j, 0), hh.size - 2)
    f = (x - hh[j]) / (hh[j + 1] - hh[j])
    return (1 - f) * vv[:, j] + f * vv[:, j + 1]


def excitation_at(model: PlatformModel, heading_rad: float) -> np.ndarray:
    """First-order excitation per unit amplitude ``(nw, 6)`` (complex, exp(+i w t)) at a heading.

    Real and imaginary parts are interpolated linearly in heading (the OC4 grid is 15 deg).
    """
    return interp_heading(model.headings, model.excitation, heading_rad)


def drift_at(model: PlatformModel, heading_rad: float) -> np.ndarray:
    """Mean drift coefficients ``(nw, 6)`` (N/m^2) at a heading."""
    return interp_heading(model.headings, model.drift, heading_rad)


def newman_drift_force(
    t: npt.ArrayLike,
    amplitudes: npt.ArrayLike,
    omegas: npt.ArrayLike,
    phases: npt.ArrayLike,
    drift_coefficients: npt.ArrayLike,
    chunk: int = 4096,
) -> np.ndarray:
    """Slow-drift force by Newman's approximation.

    ``F(t) = sum_i sum_j a_i a_j T_ij cos((w_i - w_j) t + phi_i - phi_j)`` with
    ``T_ij = (T_ii + T_jj) / 2``, which is exactly ``Re[P(t) conj(Q(t))]`` with
    ``P = sum_i T_ii a_i exp(i(w_i t + phi_i))`` and ``Q = sum_j a_j exp(i(w_j t + phi_j))``:
    O(N) per time step, no sum-frequency content, sign changes of ``T_ii`` handled.

    Parameters
    ----------
    t : ``(nt,)`` s.
    amplitudes, omegas, phases : ``(nc,)`` wave components (m, rad/s, rad), elevation
        ``sum a cos(w t + phi)`` at the origin.
    drift_coefficients : ``(nc, ndof)`` mean drift per amplitude^2 at each component.

    Returns
    -------
    numpy.ndarray ``(nt, ndof)`` N (N m). Its time mean is ``sum a_i^2 T_ii``.
    """
    t = np.asarray(t, dtype=float)
    a = np.asarray(amplitudes, dtype=float)
    w = np.asarray(omegas, dtype=float)
    ph = np.asarray(phases, dtype=float)
    T = np.asarray(drift_coefficients, dtype=float)
    if T.ndim == 1:
        T = T[:, None]
    if not (a.shape == w.shape == ph.shape == T.shape[:1]):
        raise ValueError(
            f"newman_drift_force: shapes differ: a {a.shape}, omega {w.shape}, phase {ph.shape}, drift {T.shape}"
        )
    out = np.empty((t.size, T.shape[1]))
    for s in range(0, t.size, chunk):
        e = np.exp(1j * (np.outer(t[s : s + chunk], w) + ph)) * a  # (nt, nc)
        Q = e.sum(axis=1)
        P = e @ T
        out[s : s + chunk] = (P * np.conj(Q)[:, None]).real
    return out


# ------------------------------------------------------------------------ Morison drag


def morison_elements(members: Sequence[Member], strip_length: float = 1.0) -> dict[str, np.ndarray]:
    """Split the submerged part (z < 0) of every member into drag strips.

    Returns
    -------
    dict with ``points (ne, 3)`` strip centres (m), ``axis (ne, 3)`` unit vectors,
    ``length (ne,)`` m, ``diameter (ne,)`` m, ``cd (ne,)``, and the axial (heave-plate) drag
    ``axial_points (np, 3)``, ``axial_axis (np, 3)``, ``axial_area (np,)`` m^2, ``axial_cd (np,)``.
    """
    pts, axs, lens, dias, cds = [], [], [], [], []
    ap, aa, aar, acd = [], [], [], []
    for m in members:
        a, b = m.a, m.b
        za, zb = a[2], b[2]
        if min(za, zb) >= 0.0:
            continue
        # clip to z <= 0
        s0, s1 = 0.0, 1.0
        if za > 0.0:
            s0 = za / (za - zb)
        if zb > 0.0:
            s1 = za / (za - zb)
        p0, p1 = a + s0 * (b - a), a + s1 * (b - a)
        L = float(np.linalg.norm(p1 - p0))
        n = max(1, int(np.ceil(L / strip_length)))
        f = (np.arange(n) + 0.5) / n
        pts.append(p0 + f[:, None] * (p1 - p0))
        axs.append(np.repeat(m.axis[None], n, 0))
        lens.append(np.full(n, L / n))
        dias.append(np.full(n, m.diameter))
        cds.append(np.full(n, m.cd))
        if m.axial_cd > 0 and a[2] < 0.0:
            ap.append(a)
            aa.append(m.axis)
            aar.append(0.25 * np.pi * m.diameter**2)
            acd.append(m.axial_cd)
    return {
        "points": np.concatenate(pts),
        "axis": np.concatenate(axs),
        "length": np.concatenate(lens),
        "diameter": np.concatenate(dias),
        "cd": np.concatenate(cds),
        "axial_points": np.asarray(ap, dtype=float).reshape(-1, 3),
        "axial_axis": np.asarray(aa, dtype=float).reshape(-1, 3),
        "axial_area": np.asarray(aar, dtype=float),
        "axial_cd": np.asarray(acd, dtype=float),
    }


def point_velocity(points: np.ndarray, xdot: np.ndarray) -> np.ndarray:
    """Rigid-body velocity at points, small rotations: ``v = v0 + Omega x r``.

    Parameters
    ----------
    points : ``(ne, 3)`` m; xdot : ``(..., 6)`` (m/s, rad/s).

    Returns
    -------
    numpy.ndarray ``(..., ne, 3)``
    """
    xdot = np.asarray(xdot, dtype=float)
    return xdot[..., None, :3] + np.cross(xdot[..., None, 3:], points)


def morison_drag_force(
    u_rel: np.ndarray,
    axis: np.ndarray,
    length: np.ndarray,
    diameter: np.ndarray,
    cd: np.ndarray,
    rho: float,
    *,
    axial_area: np.ndarray | None = None,
    axial_cd: np.ndarray | None = None,
) -> np.ndarray:
    """Quadratic drag on members (transverse) or on heave plates (axial).

    Transverse: ``f = 0.5 rho Cd D L |u_n| u_n`` with ``u_n = u - (u.e) e``.
    Axial (if ``axial_area`` is given): ``f = 0.5 rho Cd_ax A |u_a| u_a e`` with ``u_a = u.e``.

    Parameters
    ----------
    u_rel : ``(..., ne, 3)`` fluid minus structure velocity at the elements, m/s.
    axis : ``(ne, 3)`` unit vectors; length, diameter, cd : ``(ne,)`` (ignored when axial).
    rho : float, kg/m^3.

    Returns
    -------
    numpy.ndarray ``(..., ne, 3)`` N.
    """
    u = np.asarray(u_rel, dtype=float)
    e = np.asarray(axis, dtype=float)
    ua = np.einsum("...k,...k->...", u, e)
    if axial_area is not None:
        coef = 0.5 * rho * np.asarray(axial_cd) * np.asarray(axial_area)
        return (coef * np.abs(ua) * ua)[..., None] * e
    un = u - ua[..., None] * e
    speed = np.linalg.norm(un, axis=-1)
    coef = 0.5 * rho * np.asarray(cd) * np.asarray(diameter) * np.asarray(length)
    return (coef * speed)[..., None] * un


def generalised_force(points: np.ndarray, forces: np.ndarray) -> np.ndarray:
    """Sum of point forces as a 6-dof load about the origin, ``(..., 6)`` (N, N m)."""
    f = np.asarray(forces, dtype=float)
    return np.concatenate([f.sum(axis=-2), np.cross(points, f).sum(axis=-2)], axis=-1)
