"""Rippa's (1999) leave-one-out criterion: the choice of the shape parameter and the ridge.

The closed form ``e_k = a_k / (M^{-1})_{kk}`` for the augmented matrix ``M`` (Fasshauer &
Zhang 2007), over a geometric grid of shape parameters, with an optional ridge ``lambda`` on
the kernel diagonal chosen jointly; outputs whose curve is flat can share a grid value
(``share_tol``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import scipy.linalg as sla

from moorlife.rbf.kernels import gaussian
from moorlife.rbf.system import _cholesky

__all__ = [
    "MIN_RCOND",
    "LOOCurve",
    "rippa_errors",
    "loo_residuals",
    "choose_candidates",
    "choose_shapes_and_smoothing",
    "loo_curve",
    "choose_shapes",
    "shape_grid",
]

#: Reciprocal condition number below which a shape parameter is rejected by Rippa's search
#: (the inverse and hence the leave-one-out estimate are not trustworthy there).
MIN_RCOND = 1e-14


@dataclass(frozen=True)
class LOOCurve:
    """Rippa's leave-one-out cost over a grid of shape parameters.

    Attributes
    ----------
    shapes : numpy.ndarray, shape (g,)
        Candidate ``q0``.
    rms : numpy.ndarray, shape (g, n_out)
        Root-mean-square leave-one-out error per candidate and output (``inf`` where the
        system is too ill-conditioned, see ``MIN_RCOND``).
    rcond : numpy.ndarray, shape (g,)
        Reciprocal condition number estimate of the kernel matrix (0: not positive definite).
    """

    shapes: np.ndarray
    rms: np.ndarray
    rcond: np.ndarray


def loo_residuals(kernel: np.ndarray, basis: np.ndarray, values: np.ndarray) -> tuple[np.ndarray | None, float]:
    """Rippa's leave-one-out residuals without forming the inverse (the search's inner loop).

    Same result as ``rippa_errors(kernel_block_inverse(kernel, basis)[0], values)`` at about half
    the cost: with the Cholesky factor ``K = U^T U``, ``diag(K^-1)`` is the row sums of squares
    of ``U^-1`` (one triangular inverse) and ``K^-1 y`` two triangular solves; the polynomial
    block enters through the Schur complement ``G = P^T K^-1 P``:
    ``H y = K^-1 y - K^-1 P G^-1 P^T K^-1 y``, ``diag(H) = diag(K^-1) - rowsum((K^-1 P) G^-1 * K^-1 P)``.

    Parameters
    ----------
    kernel : numpy.ndarray, shape (m, m)
        ``K`` (plus any smoothing on the diagonal), symmetric.
    basis : numpy.ndarray, shape (m, p)
    values : numpy.ndarray, shape (m, n_out)

    Returns
    -------
    errors : numpy.ndarray, shape (m, n_out), or None
        ``y_k - f^{(-k)}(x_k)``; None when ``K`` is not numerically positive definite.
    rcond : float
        LAPACK estimate of the reciprocal 1-norm condition number of ``K`` (0 when singular).
    """
    chol, rcond = _cholesky(kernel)
    if chol is None:
        return None, 0.0
    uinv, info = sla.lapack.dtrtri(chol, lower=0)
    if info != 0:
        return None, 0.0
    diag = np.einsum("ij,ij->i", uinv, uinv)
    rhs = np.concatenate([values, basis], axis=1)
    sol = sla.cho_solve((chol, False), rhs, check_finite=False)
    ky, kp = sol[:, : values.shape[1]], sol[:, values.shape[1] :]
    try:
        g_inv_pt = np.linalg.solve(basis.T @ kp, np.concatenate([kp.T, basis.T @ ky], axis=1))
    except np.linalg.LinAlgError:
        return None, 0.0
    m = kernel.shape[0]
    a = ky - kp @ g_inv_pt[:, m:]
    diag = diag - np.einsum("ij,ji->i", kp, g_inv_pt[:, :m])
    return a / diag[:, None], float(rcond)


def rippa_errors(inverse: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Leave-one-out residuals in Rippa's closed form.

    For the augmented system, the error of the interpolant built without centre ``k``,
    evaluated at ``x_k``, is ``e_k = a_k / (M^{-1})_{kk}`` with ``a = M^{-1} [y; 0]``
    restricted to the kernel weights (Rippa 1999; Fasshauer & Zhang 2007).

    Parameters
    ----------
    inverse : numpy.ndarray, shape (m + p, m + p) or (m, m)
        Inverse of the augmented matrix, or its kernel block (:func:`kernel_block_inverse`).
    values : numpy.ndarray, shape (m, n_out)

    Returns
    -------
    numpy.ndarray, shape (m, n_out)
        ``y_k - f^{(-k)}(x_k)``.
    """
    m = values.shape[0]
    a = inverse[:m, :m] @ values
    return a / np.diag(inverse)[:m, None]


def shape_grid(lo: float, hi: float, n: int) -> np.ndarray:
    """A geometric grid of ``n`` shape parameters from ``lo`` to ``hi`` (normalised units)."""
    if not (0 < lo < hi) or n < 2:
        raise ValueError(f"shape grid needs 0 < lo < hi and n >= 2, got lo={lo}, hi={hi}, n={n}")
    return np.geomspace(lo, hi, int(n))


def loo_curve(
    d2: np.ndarray,
    basis: np.ndarray,
    values: np.ndarray,
    shapes: npt.ArrayLike,
    smoothing: float = 0.0,
) -> LOOCurve:
    """Rippa's leave-one-out RMS error for every output on a grid of shape parameters.

    One matrix inverse per grid value serves every output.

    Parameters
    ----------
    d2 : numpy.ndarray, shape (m, m)
    basis : numpy.ndarray, shape (m, p)
    values : numpy.ndarray, shape (m, n_out)
        Training values (already transformed, e.g. ``log10``).
    shapes : array_like, shape (g,)
    smoothing : float

    Returns
    -------
    LOOCurve
    """
    q = np.asarray(shapes, dtype=float)
    rms = np.full((q.size, values.shape[1]), np.inf)
    rcond = np.zeros(q.size)
    m = d2.shape[0]
    for i, qi in enumerate(q):
        k = gaussian(d2, qi)
        if smoothing:
            k[np.arange(m), np.arange(m)] += smoothing
        e, rc = loo_residuals(k, basis, values)
        rcond[i] = rc
        if e is None or rc < MIN_RCOND:
            continue
        rms[i] = np.sqrt(np.mean(e * e, axis=0))
    return LOOCurve(shapes=q, rms=rms, rcond=rcond)


def choose_shapes(curve: LOOCurve, share_tol: float = 0.0) -> np.ndarray:
    """Pick one shape parameter per output from a leave-one-out curve.

    With ``share_tol = 0`` each output gets its own minimiser. With ``share_tol > 0``
    an output accepts any grid value whose leave-one-out RMS is within ``(1 + share_tol)``
    of its minimum, and a greedy cover picks as few distinct values as possible (fewer
    kernel evaluations at prediction); each output then takes its best accepted value.

    Parameters
    ----------
    curve : LOOCurve
    share_tol : float
        Accepted relative increase of the leave-one-out RMS (e.g. 0.02).

    Returns
    -------
    numpy.ndarray, shape (n_out,)

    Raises
    ------
    ValueError
        If no grid value gives a usable (well-conditioned) system.
    """
    rms = curve.rms
    if not np.isfinite(rms).any(axis=0).all():
        bad = int(np.flatnonzero(~np.isfinite(rms).any(axis=0))[0])
        raise ValueError(
            f"output {bad}: no shape parameter in [{curve.shapes[0]:.4g}, {curve.shapes[-1]:.4g}] gives a "
            "well-conditioned RBF system; lower the shape grid or add smoothing"
        )
    return curve.shapes[choose_candidates(rms, share_tol)]


def choose_candidates(rms: np.ndarray, share_tol: float = 0.0) -> np.ndarray:
    """Index of the chosen candidate per output from leave-one-out RMS errors.

    Parameters
    ----------
    rms : numpy.ndarray, shape (c, n_out)
        Leave-one-out RMS per candidate (rows in order of preference on ties) and output. A
        non-finite entry (an unusable candidate, ``inf`` or NaN) is never chosen.
    share_tol : float
        See :func:`choose_shapes`: a greedy cover picks as few distinct candidates as possible
        among those within ``(1 + share_tol)`` of each output's minimum.

    Returns
    -------
    numpy.ndarray of int, shape (n_out,)

    Raises
    ------
    ValueError
        If an output has no finite entry (the callers name the grid first).
    """
    # a NaN would propagate through the minimum, match no candidate, and the cover never end
    rms = np.where(np.isfinite(rms), rms, np.inf)
    unusable = np.isinf(rms).all(axis=0)
    if unusable.any():
        bad = int(np.flatnonzero(unusable)[0])
        raise ValueError(f"output {bad}: no candidate has a finite leave-one-out RMS")
    best = np.min(rms, axis=0)
    ok = rms <= best * (1.0 + share_tol) if share_tol > 0 else rms == best
    chosen: list[int] = []
    uncovered = np.ones(rms.shape[1], dtype=bool)
    while uncovered.any():
        counts = (ok & uncovered).sum(axis=1)
        g = int(np.argmax(counts))  # ties -> first candidate, deterministic
        chosen.append(g)
        uncovered &= ~ok[g]
    sub = rms[chosen]
    sub = np.where(ok[chosen], sub, np.inf)
    return np.asarray(chosen)[np.argmin(sub, axis=0)]


def choose_shapes_and_smoothing(
    d2: np.ndarray,
    basis: np.ndarray,
    values: np.ndarray,
    shapes: npt.ArrayLike,
    smoothings: npt.ArrayLike,
    share_tol: float = 0.0,
) -> tuple[np.ndarray, np.ndarray]:
    """Shape parameter and smoothing per output, jointly, by Rippa's leave-one-out error.

    The closed form ``e_k = a_k / (M^{-1})_{kk}`` holds for the smoothed system
    ``K + lambda I`` too (it is the exact leave-one-out residual of that linear smoother), so
    each ``(q0, lambda)`` pair costs one matrix inverse for all outputs. Smoothing helps the
    outputs whose simulated values carry the realisation noise of a one-hour record (maxima,
    the damage of lightly loaded lines): an exact interpolant reproduces the noise.

    Parameters
    ----------
    d2 : numpy.ndarray, shape (m, m)
    basis : numpy.ndarray, shape (m, p)
    values : numpy.ndarray, shape (m, n_out)
        Training values (already transformed).
    shapes : array_like, shape (g,)
        Candidate ``q0``; a single value keeps it fixed (per-output fixed values: call per value).
    smoothings : array_like, shape (s,)
        Candidate ridge terms (non-negative; 0 is exact interpolation and wins ties).
    share_tol : float
        See :func:`choose_shapes`.

    Returns
    -------
    shape, smoothing : numpy.ndarray, shape (n_out,)

    Raises
    ------
    ValueError
        If no candidate gives a well-conditioned system for some output.
    """
    q = np.atleast_1d(np.asarray(shapes, dtype=float))
    lam = np.atleast_1d(np.asarray(smoothings, dtype=float))
    if lam.size == 0 or np.any(~(lam >= 0)):
        raise ValueError(f"smoothing candidates must be non-negative, got {lam}")
    lam = np.sort(lam)
    rms = np.concatenate([loo_curve(d2, basis, values, q, float(s)).rms for s in lam])  # (s*g, n_out)
    if not np.isfinite(rms).any(axis=0).all():
        bad = int(np.flatnonzero(~np.isfinite(rms).any(axis=0))[0])
        raise ValueError(
            f"output {bad}: no shape parameter in [{q[0]:.4g}, {q[-1]:.4g}] with smoothing in "
            f"[{lam[0]:.3g}, {lam[-1]:.3g}] gives a well-conditioned RBF system; lower the shape grid "
            "or add smoothing"
        )
    idx = choose_candidates(rms, share_tol)
    return q[idx % q.size], lam[idx // q.size]
