"""Rigid body and hydrostatics: mass matrices, system mass properties, gravity stiffness,
motion RAOs and natural periods."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import numpy.typing as npt


def rigid_body_mass_matrix(mass: float, cm: npt.ArrayLike, inertia_cm: npt.ArrayLike) -> np.ndarray:
    """6x6 rigid-body mass matrix about the origin.

    Parameters
    ----------
    mass : float
        kg.
    cm : array_like
        ``(3,)`` centre of mass, m.
    inertia_cm : array_like
        ``(3,)`` principal moments about the CM (axes parallel to x, y, z) or ``(3, 3)``, kg m^2.

    Returns
    -------
    numpy.ndarray
        ``(6, 6)``: ``[[m I, -m S(r)], [m S(r), I_cm - m S(r) S(r)]]`` with ``S(r)`` the
        cross-product matrix of the CM position.
    """
    r = np.asarray(cm, dtype=float)
    Ic = np.asarray(inertia_cm, dtype=float)
    Ic = np.diag(Ic) if Ic.ndim == 1 else Ic
    S = np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])
    M = np.zeros((6, 6))
    M[:3, :3] = mass * np.eye(3)
    M[:3, 3:] = -mass * S
    M[3:, :3] = mass * S
    M[3:, 3:] = Ic - mass * S @ S
    return M


def system_mass_properties(
    platform_cfg: Mapping, source: str = "platform.yaml"
) -> tuple[np.ndarray, float, np.ndarray]:
    """Mass matrix of platform + ballast + tower + RNA about the origin.

    Returns
    -------
    mass_matrix : numpy.ndarray ``(6, 6)``
    total_mass : float, kg
    cg : numpy.ndarray ``(3,)``, m
    """
    M = np.zeros((6, 6))
    tot, mom = 0.0, np.zeros(3)
    for key in ("platform", "tower", "rna"):
        if key not in platform_cfg:
            raise ValueError(f"{source}: block '{key}' (mass, cm, inertia_cm) is missing")
        b = platform_cfg[key]
        for f in ("mass", "cm", "inertia_cm"):
            if f not in b:
                raise ValueError(f"{source}: {key}.{f} is missing")
        m = float(b["mass"])
        if not m > 0:
            raise ValueError(f"{source}: {key}.mass = {b['mass']!r} must be > 0")
        M += rigid_body_mass_matrix(m, b["cm"], b["inertia_cm"])
        tot += m
        mom += m * np.asarray(b["cm"], dtype=float)
    return M, tot, mom / tot


def gravity_stiffness(mass: float, cg: npt.ArrayLike, g: float) -> np.ndarray:
    """Restoring of the weight about the origin: ``-m g z_G`` in roll and pitch, and the
    roll/pitch-yaw coupling ``m g x_G``, ``m g y_G`` (WAMIT manual eq. 3.3 gravity terms).

    Returns
    -------
    numpy.ndarray ``(6, 6)``
    """
    x, y, z = np.asarray(cg, dtype=float)
    C = np.zeros((6, 6))
    C[3, 3] = C[4, 4] = -mass * g * z
    C[3, 5] = mass * g * x
    C[4, 5] = mass * g * y
    return C


def motion_rao(
    omega: np.ndarray,
    mass: np.ndarray,
    added_mass: np.ndarray,
    damping: np.ndarray,
    stiffness: np.ndarray,
    excitation: np.ndarray,
) -> np.ndarray:
    """Linear motion per unit wave amplitude, exp(+i w t) convention.

    Solves ``(-w^2 (M + A(w)) + i w B(w) + C) xi = X`` for every frequency and heading.

    Parameters
    ----------
    omega : ``(nw,)``; mass, stiffness : ``(6, 6)``; added_mass, damping : ``(nw, 6, 6)``;
    excitation : ``(nw, nh, 6)`` complex.

    Returns
    -------
    numpy.ndarray ``(nw, nh, 6)`` complex (m/m, rad/m).
    """
    w = np.asarray(omega, dtype=float)[:, None, None]
    Z = -(w**2) * (mass[None] + added_mass) + 1j * w * damping + stiffness[None]
    return np.linalg.solve(Z[:, None], excitation[..., None])[..., 0]


def natural_periods(
    mass: np.ndarray,
    omega: np.ndarray,
    added_mass: np.ndarray,
    stiffness: np.ndarray,
    dofs: Sequence[int] = (0, 2, 4),
    tol: float = 1e-8,
) -> np.ndarray:
    """Uncoupled natural periods with frequency-dependent added mass (fixed point).

    ``T_i = 2 pi sqrt((M_ii + A_ii(w_i)) / C_ii)``, iterated on ``w_i = 2 pi / T_i`` with
    ``A_ii`` interpolated in omega (held constant outside the grid).

    Returns
    -------
    numpy.ndarray ``(len(dofs),)`` periods in s.
    """
    out = []
    for i in dofs:
        if not stiffness[i, i] > 0:
            raise ValueError(f"natural_periods: stiffness[{i},{i}] = {stiffness[i, i]} is not positive")
        wn = np.sqrt(stiffness[i, i] / (mass[i, i] + added_mass[0, i, i]))
        for _ in range(200):
            a = np.interp(wn, omega, added_mass[:, i, i])
            new = np.sqrt(stiffness[i, i] / (mass[i, i] + a))
            if abs(new - wn) < tol * wn:
                break
            wn = new
        out.append(2.0 * np.pi / wn)
    return np.array(out)
