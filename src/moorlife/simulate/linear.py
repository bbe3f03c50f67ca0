"""Linear analysis of the model (verification): radiation impedance, RAOs, natural periods."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace

import numpy as np
import scipy.linalg

from moorlife.simulate.forcing import _interp_heading, _interp_omega
from moorlife.simulate.model import ModelInputs

__all__ = ["without_radiation_memory", "radiation_impedance", "frequency_response", "linear_natural_periods"]


def _free_dofs(locked: Sequence[int]) -> np.ndarray:
    """The DOFs not in ``locked``, ``(nfree,)`` sorted; ``locked`` is validated and read once."""
    lk = sorted({int(d) for d in locked})
    if any(d < 0 or d > 5 for d in lk):
        raise ValueError(f"locked DOFs {lk}: each must be 0-5 (surge..yaw)")
    free = np.setdiff1d(np.arange(6), lk)
    if free.size == 0:
        raise ValueError("locked DOFs: at least one DOF must stay free")
    return free


def _inverse_mass(mass: np.ndarray, free: np.ndarray) -> np.ndarray:
    """``(6, 6)`` inverse of the ``free`` block of ``mass``, zero in the other rows and columns."""
    minv = np.zeros((6, 6))
    minv[np.ix_(free, free)] = np.linalg.inv(np.asarray(mass, dtype=float)[np.ix_(free, free)])
    return minv


def without_radiation_memory(model: ModelInputs) -> ModelInputs:
    """The model with its radiation memory removed: constant added mass ``A_inf``, no wave damping.

    This is the convention of published natural periods such as the OC4 definition's
    (``T = 2 pi sqrt((M + A_inf) / C)``, the added mass of FAST's linearisation), used to check a
    decay test against them like for like; the simulation itself always keeps the memory. The
    linear and viscous damping, the mooring and everything else are unchanged.
    """
    return replace(
        model,
        rad_a=np.zeros((0, 0)),
        rad_b=np.zeros((0, 6)),
        rad_c=np.zeros((6, 0)),
        kernel=np.zeros((0, 0)),
        kernel_pairs=np.zeros((0, 2), dtype=np.int64),
        kernel_dt=0.0,
    )


def radiation_impedance(model: ModelInputs, omega: np.ndarray) -> np.ndarray:
    """Frequency response of the model's radiation memory, ``Z(omega)``, ``(nw, 6, 6)`` complex.

    The radiation force on a harmonic velocity ``v exp(-i omega t)`` is ``-Z(omega) v``, so
    ``Re(Z) = B(omega)`` and ``-Im(Z) / omega = A(omega) - A_inf``. State space:
    ``Z = C (-i omega I - A)^-1 B``; kernel: ``Z = int_0^T K(t) exp(i omega t) dt`` (trapezoid).
    """
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    out = np.zeros((w.size, 6, 6), dtype=complex)
    nr = model.rad_a.shape[0]
    if nr:
        eye = np.eye(nr)
        for i, wi in enumerate(w):
            out[i] = model.rad_c @ np.linalg.solve(-1j * wi * eye - model.rad_a, model.rad_b)
    if model.kernel.size:
        t = np.arange(model.kernel.shape[0]) * model.kernel_dt
        e = np.exp(1j * np.outer(w, t))  # (nw, nt)
        z = np.trapezoid(e[:, :, None] * model.kernel[None, :, :], t, axis=1)  # (nw, npairs)
        for p, (i, j) in enumerate(model.kernel_pairs):
            out[:, i, j] += z[:, p]
    return out


def frequency_response(
    model: ModelInputs,
    omega: np.ndarray,
    theta: float,
    *,
    mooring_stiffness: np.ndarray | None = None,
    added_mass: np.ndarray | None = None,
    radiation_damping: np.ndarray | None = None,
) -> np.ndarray:
    """Linear response amplitude operator (RAO) per metre of wave amplitude.

    Solves ``[-omega^2 (M + A_inf + a(omega)) - i omega B(omega) + K + K_m] xi = X(omega, theta)``
    in the ``exp(-i omega t)`` convention. By default the radiation terms come from the model's
    own state space (the exact frequency-domain counterpart of the time integrator).

    Parameters
    ----------
    model : ModelInputs
    omega : (nw,)
        Frequencies, rad/s.
    theta : float
        Propagation angle, rad.
    mooring_stiffness : (6, 6), optional
        Default ``model.mooring_stiffness``.
    added_mass, radiation_damping : (nw, 6, 6), optional
        BEM ``A(omega) - A_inf`` and ``B(omega)`` instead of the state space.

    Returns
    -------
    numpy.ndarray, shape (nw, 6), complex
        Motion per metre of amplitude (m/m, rad/m).
    """
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    km = model.mooring_stiffness if mooring_stiffness is None else np.asarray(mooring_stiffness)
    x = _interp_omega(_interp_heading(model.excitation, model.headings, theta), model.omega, w)
    if added_mass is None:
        z = radiation_impedance(model, w)
    else:
        z = np.asarray(radiation_damping) - 1j * w[:, None, None] * np.asarray(added_mass)
    out = np.empty((w.size, 6), dtype=complex)
    for i, wi in enumerate(w):
        h = -(wi**2) * model.mass + model.stiffness + km - 1j * wi * (model.damping + z[i])
        out[i] = np.linalg.solve(h, x[i])
    return out


def linear_natural_periods(
    model: ModelInputs, mooring_stiffness: np.ndarray | None = None, locked: Sequence[int] = ()
) -> np.ndarray:
    """Natural periods (s) of the coupled linear system, one per DOF.

    For each DOF the search starts at its uncoupled estimate ``2 pi sqrt((M + a)_dd / K_dd)``
    and iterates the generalised eigenproblem ``(K + K_m) x = w^2 (M + A_inf + a(w)) x`` with
    the frequency-dependent added mass of the model's own radiation memory, following the
    eigenvalue nearest the current frequency (so surge-pitch and sway-roll coupling through the
    mass matrix is included, as in a decay test). ``locked`` DOFs are held (see
    :func:`integrate`): the eigenproblem is that of the free block. Returns ``(6,)``, ``inf``
    without restoring or for a locked DOF.
    """
    km = model.mooring_stiffness if mooring_stiffness is None else np.asarray(mooring_stiffness)
    free = _free_dofs(locked)
    ix = np.ix_(free, free)
    kk = model.stiffness + km
    out = np.full(6, np.inf)
    for d in free:
        if kk[d, d] <= 0:
            continue
        w = math.sqrt(kk[d, d] / model.mass[d, d])
        for _ in range(40):
            a = model.mass - radiation_impedance(model, np.array([w]))[0].imag / w
            ev = scipy.linalg.eigvals(kk[ix], a[ix])
            ws = np.sqrt(np.abs(ev.real))
            w_new = float(ws[np.argmin(np.abs(ws - w))])
            if abs(w_new - w) < 1e-10 * w:
                break
            w = w_new
        out[d] = 2 * math.pi / w
    return out
