"""The augmented interpolation system ``[[K + s I, P], [P^T, 0]] [w; c] = [y; 0]`` and its inverses."""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from moorlife.rbf.kernels import gaussian

__all__ = ["augmented_matrix", "solve_weights", "kernel_block_inverse"]


def augmented_matrix(d2: np.ndarray, basis: np.ndarray, shape: float, smoothing: float = 0.0) -> np.ndarray:
    """The interpolation matrix ``[[K + s I, P], [P^T, 0]]``.

    Parameters
    ----------
    d2 : numpy.ndarray, shape (m, m)
        Squared distances between the centres.
    basis : numpy.ndarray, shape (m, p)
        :func:`polynomial_basis` at the centres.
    shape : float
        ``q0`` (normalised distance).
    smoothing : float
        Ridge term on the kernel diagonal.

    Returns
    -------
    numpy.ndarray, shape (m + p, m + p)
    """
    m, p = basis.shape
    out = np.zeros((m + p, m + p))
    out[:m, :m] = gaussian(d2, shape)
    if smoothing:
        out[np.arange(m), np.arange(m)] += smoothing
    out[:m, m:] = basis
    out[m:, :m] = basis.T
    return out


def solve_weights(matrix: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solve the augmented system for every output.

    Parameters
    ----------
    matrix : numpy.ndarray, shape (m + p, m + p)
        :func:`augmented_matrix`.
    values : numpy.ndarray, shape (m, n_out)

    Returns
    -------
    weights : numpy.ndarray, shape (m, n_out)
    poly_coef : numpy.ndarray, shape (p, n_out)

    Raises
    ------
    numpy.linalg.LinAlgError
        If the system is singular (duplicate centres, or too few for the polynomial).
    """
    m = values.shape[0]
    rhs = np.zeros((matrix.shape[0], values.shape[1]))
    rhs[:m] = values
    sol = sla.solve(matrix, rhs, assume_a="sym")
    return sol[:m], sol[m:]


def _inverse(matrix: np.ndarray) -> tuple[np.ndarray, float]:
    """Inverse and exact reciprocal 1-norm condition number ``1 / (|M|_1 |M^-1|_1)``."""
    inv = np.linalg.inv(matrix)
    rcond = 1.0 / (np.linalg.norm(matrix, 1) * np.linalg.norm(inv, 1))
    return inv, float(rcond) if np.isfinite(rcond) else 0.0


def _cholesky(kernel: np.ndarray) -> tuple[np.ndarray | None, float]:
    """Upper Cholesky factor of ``kernel`` and LAPACK's reciprocal 1-norm condition estimate.

    ``(None, 0.0)`` when ``kernel`` is not numerically positive definite.
    """
    chol, info = sla.lapack.dpotrf(kernel, lower=0, clean=1)
    if info != 0:
        return None, 0.0
    rcond, _ = sla.lapack.dpocon(chol, np.linalg.norm(kernel, 1))
    return chol, float(rcond)


def kernel_block_inverse(kernel: np.ndarray, basis: np.ndarray) -> tuple[np.ndarray | None, float]:
    """The kernel block ``(M^{-1})_{11}`` of the inverse augmented matrix, via Cholesky.

    ``H = K^-1 - K^-1 P (P^T K^-1 P)^-1 P^T K^-1`` (Schur complement): one Cholesky
    factorisation and its solve against the identity, cheaper than inverting ``M``. A
    Gaussian kernel matrix is positive definite in exact arithmetic, so a failed Cholesky
    flags a numerically singular system.

    Parameters
    ----------
    kernel : numpy.ndarray, shape (m, m)
        ``K`` (plus any smoothing on the diagonal), symmetric.
    basis : numpy.ndarray, shape (m, p)

    Returns
    -------
    H : numpy.ndarray, shape (m, m), or None
        None when ``K`` is not numerically positive definite.
    rcond : float
        LAPACK estimate of the reciprocal 1-norm condition number of ``K`` (0 when singular).
    """
    chol, rcond = _cholesky(kernel)
    if chol is None:
        return None, 0.0
    kinv = sla.cho_solve((chol, False), np.eye(kernel.shape[0]), check_finite=False)
    kp = kinv @ basis
    try:
        s = np.linalg.solve(basis.T @ kp, kp.T)
    except np.linalg.LinAlgError:
        return None, 0.0
    kinv -= kp @ s
    return kinv, float(rcond)
