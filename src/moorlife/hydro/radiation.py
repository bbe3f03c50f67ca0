"""Radiation memory: the retardation kernel, the infinite-frequency added mass (Ogilvie) and
the state-space fit of the radiation force."""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

log = logging.getLogger(__name__)


def _extended_damping(omega: np.ndarray, damping: np.ndarray, n_fine: int) -> tuple[np.ndarray, np.ndarray]:
    # B(0) = 0 and a cosine taper over the last 10 % of the grid to 0 at omega_max: limits the
    # Gibbs ringing of the truncated transform (B(omega_max) of a semi is small but non-zero)
    w = np.concatenate([[0.0], omega])
    b = np.concatenate([np.zeros((1,) + damping.shape[1:]), damping], axis=0)
    wf = np.linspace(0.0, w[-1], n_fine)
    bf = np.empty((n_fine,) + damping.shape[1:])
    flat = b.reshape(len(w), -1)
    from scipy.interpolate import PchipInterpolator

    bf.reshape(n_fine, -1)[:] = PchipInterpolator(w, flat, axis=0)(wf)
    w_taper = 0.9 * w[-1]
    taper = np.where(wf > w_taper, 0.5 * (1 + np.cos(np.pi * (wf - w_taper) / (w[-1] - w_taper))), 1.0)
    return wf, bf * taper.reshape((-1,) + (1,) * (damping.ndim - 1))


def retardation_kernel(
    omega: npt.ArrayLike, damping: npt.ArrayLike, t: npt.ArrayLike, n_fine: int = 4000
) -> np.ndarray:
    """Radiation impulse response ``K(t) = (2/pi) int_0^inf B(w) cos(w t) dw``.

    ``B`` is interpolated (monotone cubic) on a fine grid with ``B(0) = 0`` and tapered to
    zero over the last 10 % of the frequency range; the radiation force of the Cummins
    equation is ``-int_0^t K(t - s) xdot(s) ds``.

    Parameters
    ----------
    omega : array_like ``(nw,)`` rad/s, increasing.
    damping : array_like ``(nw, ...)``, e.g. ``(nw, 6, 6)``.
    t : array_like ``(nt,)`` s.

    Returns
    -------
    numpy.ndarray ``(nt, ...)``
    """
    omega = np.asarray(omega, dtype=float)
    damping = np.asarray(damping, dtype=float)
    t = np.asarray(t, dtype=float)
    wf, bf = _extended_damping(omega, damping, n_fine)
    c = np.cos(np.outer(t, wf))  # (nt, nf)
    wts = np.full(wf.size, wf[1] - wf[0])
    wts[[0, -1]] *= 0.5
    K = (2.0 / np.pi) * np.tensordot(c * wts, bf, axes=(1, 0))
    return K


def added_mass_infinite_ogilvie(omega: np.ndarray, added_mass: np.ndarray, t: np.ndarray, K: np.ndarray) -> np.ndarray:
    """Ogilvie's relation ``A_inf = A(w) + (1/w) int_0^inf K(t) sin(w t) dt``, averaged over w.

    Returns ``(6, 6)``; a cross-check of the BEM's infinite-frequency solve.
    """
    s = np.sin(np.outer(omega, t))  # (nw, nt)
    integ = np.trapezoid(s[:, :, None, None] * K[None], t, axis=1)
    est = added_mass + integ / omega[:, None, None]
    return est.mean(axis=0)


@dataclass(frozen=True)
class StateSpace:
    """Continuous-time radiation state space: ``dx/dt = A x + B xdot``, ``F_rad = -C x``.

    Attributes
    ----------
    A : ``(n, n)``; B : ``(n, 6)``; C : ``(6, n)``.
    kernel_error : float
        ``max |K_fit - K| / max |K|`` over the fitted kernel (all 36 terms).
    damping_error : float
        ``max_w |B_fit - B| / max |B|`` over the BEM grid below 90 % of its top frequency
        (all 36 terms; above that the kernel's damping is tapered to 0).
    """

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    kernel_error: float = float("nan")
    damping_error: float = float("nan")


def state_space_kernel(ss: StateSpace, t: npt.ArrayLike) -> np.ndarray:
    """Impulse response ``C exp(A t) B``, ``(nt, 6, 6)`` (by eigen-decomposition of ``A``)."""
    t = np.asarray(t, dtype=float)
    lam, V = np.linalg.eig(ss.A)
    CV = ss.C @ V
    VB = np.linalg.solve(V, ss.B)
    return np.einsum("in,tn,nj->tij", CV, np.exp(np.outer(t, lam)), VB).real


def state_space_response(ss: StateSpace, omega: npt.ArrayLike) -> np.ndarray:
    """Frequency response ``K(iw) = C (iw - A)^-1 B = B(w) + i w (A(w) - A_inf)``, ``(nw, 6, 6)``."""
    omega = np.asarray(omega, dtype=float)
    n = ss.A.shape[0]
    return np.stack([ss.C @ np.linalg.solve(1j * w * np.eye(n) - ss.A, ss.B) for w in omega])


def fit_state_space(
    t: np.ndarray,
    K: np.ndarray,
    order: int = 24,
    *,
    omega: np.ndarray | None = None,
    damping: np.ndarray | None = None,
    hankel_rows: int | None = None,
) -> StateSpace:
    """Fit a stable MIMO state space to the retardation kernel (ERA / Kung realisation).

    The kernel sampled at ``t_k = k dt`` is ``K(t_k) = C Ad^k B`` with ``Ad = exp(A dt)``; the
    block Hankel matrix of the samples is factored by SVD and truncated to ``order`` states
    (Kung 1978; Kristiansen et al. 2005 for radiation). Unstable discrete poles are reflected
    inside the unit circle. The continuous ``A = log(Ad) / dt``.

    Parameters
    ----------
    t : numpy.ndarray ``(nt,)``, equally spaced from 0.
    K : numpy.ndarray ``(nt, 6, 6)``.
    order : int
        Number of states.
    omega, damping : optional ``(nw,)``, ``(nw, 6, 6)``
        The BEM damping, to report the frequency-domain fit error.

    Returns
    -------
    StateSpace
    """
    t = np.asarray(t, dtype=float)
    dt = t[1] - t[0]
    if not np.allclose(np.diff(t), dt) or abs(t[0]) > 1e-12:
        raise ValueError("fit_state_space: t must be equally spaced and start at 0")
    nt, p, q = K.shape
    r = hankel_rows or min((nt - 1) // 2, max(order // p + 10, 30))
    c = nt - 1 - r
    H0 = np.empty((r * p, c * q))
    H1 = np.empty((r * p, c * q))
    for i in range(r):
        for j in range(c):
            H0[i * p : (i + 1) * p, j * q : (j + 1) * q] = K[i + j]
            H1[i * p : (i + 1) * p, j * q : (j + 1) * q] = K[i + j + 1]
    U, s, Vt = np.linalg.svd(H0, full_matrices=False)
    n = int(min(order, np.sum(s > s[0] * 1e-12)))
    U, s, Vt = U[:, :n], s[:n], Vt[:n]
    sq = np.sqrt(s)
    Ad = (U / sq).T @ H1 @ (Vt.T / sq)
    Bd = (sq[:, None] * Vt)[:, :q]
    Cd = (U * sq)[:p, :]
    lam, V = np.linalg.eig(Ad)
    lam = np.where(np.abs(lam) >= 1.0, 1.0 / np.conj(lam) * 0.999, lam)  # reflect unstable poles
    lam = np.where(np.abs(lam) < 1e-12, 1e-12, lam)
    Ac = V @ np.diag(np.log(lam) / dt) @ np.linalg.inv(V)
    if np.max(np.abs(Ac.imag)) > 1e-6 * max(1.0, np.max(np.abs(Ac.real))):
        log.warning("fit_state_space: complex residue in log(Ad) (%.2e), real part kept", np.max(np.abs(Ac.imag)))
    ss = StateSpace(Ac.real, Bd, Cd)
    Kf = state_space_kernel(ss, t)
    kerr = float(np.max(np.abs(Kf - K)) / np.max(np.abs(K)))
    derr = float("nan")
    if omega is not None and damping is not None:
        # compared below 90 % of the top frequency: above it the kernel's B is tapered to 0
        band = omega <= 0.9 * omega[-1]
        Bf = state_space_response(ss, omega[band]).real
        derr = float(np.max(np.abs(Bf - damping[band])) / np.max(np.abs(damping[band])))
    return StateSpace(ss.A, ss.B, ss.C, kerr, derr)
