"""Gaussian radial basis function interpolation on the normalised sea-state space.

The method of Barrera et al. (2019, eq. 15) and Camus et al. (2011): every output of the
simulated sea states is rebuilt at any hindcast hour by

.. math::

    f(x) = \\sum_j w_j \\, \\exp\\big(-(r(x, x_j) / q_0)^2\\big) + p(x),

with ``r`` the normalised 5-D distance of the selection (each scalar divided by its range,
each direction compared on the circle: folded difference, at most 180 deg, divided by 180),
``q0`` the shape parameter and ``p`` a first-degree polynomial. For a direction the
first-degree trend is ``cos`` and ``sin`` of the angle (a linear term in the angle itself
would jump at north); scalar-only data get exactly the classical linear polynomial, so the
interpolant is the one of :class:`scipy.interpolate.RBFInterpolator` with
``kernel="gaussian", epsilon=1/q0, degree=1``.

The weights solve the augmented system ``[[K, P], [P^T, 0]] [w; c] = [y; 0]``. The shape
parameter is chosen per output by Rippa's (1999) leave-one-out criterion in closed form,
``e_k = a_k / (M^{-1})_{kk}`` for the augmented matrix ``M`` (Fasshauer & Zhang 2007), over
a geometric grid, or fixed (the paper: 0.1 for damage, 0.175 for tension). An optional ridge
``lambda`` on the kernel diagonal (``K + lambda I``) is chosen the same way, jointly with
``q0``: the closed form is the exact leave-one-out residual of the smoothed system too, and a
one-hour record's maximum or light-line damage carries seed noise that exact interpolation
would reproduce. Outputs whose leave-one-out curve is flat can share a grid value
(``share_tol``), so prediction evaluates one kernel block per *distinct* shape parameter.

Prediction runs in row chunks (bounded memory), float64, in numba kernels (distance, kernel
block, weighted sums); every row is computed independently in a fixed order, so the numbers do
not depend on chunk size or thread count. The fit uses LAPACK (Cholesky, LU), whose last bit can
depend on the number of BLAS threads: the workflow's ``lifecycle`` rule pins BLAS to one thread.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba as nb
import numpy as np
import numpy.typing as npt
import scipy.linalg as sla

from moorlife.selection import normalise as _sel_normalise
from moorlife.selection import scaling_from

__all__ = [
    "Space",
    "RBFModel",
    "LOOCurve",
    "fit_space",
    "normalise",
    "squared_distances",
    "gaussian",
    "polynomial_basis",
    "augmented_matrix",
    "solve_weights",
    "kernel_block_inverse",
    "rippa_errors",
    "loo_residuals",
    "choose_candidates",
    "choose_shapes_and_smoothing",
    "loo_curve",
    "choose_shapes",
    "shape_grid",
    "fit_rbf",
    "predict_rbf",
    "nearest_centre",
]

#: Reciprocal condition number below which a shape parameter is rejected by Rippa's search
#: (the inverse and hence the leave-one-out estimate are not trustworthy there).
MIN_RCOND = 1e-14


@dataclass(frozen=True)
class Space:
    """Normalisation of the input space.

    Attributes
    ----------
    lower : numpy.ndarray, shape (d,)
        Subtracted from each scalar coordinate (0 for directions).
    scale : numpy.ndarray, shape (d,)
        Each scalar's range; 180 for directions (degrees).
    is_direction : numpy.ndarray of bool, shape (d,)
        Which coordinates are directions in degrees (compared on the circle).
    """

    lower: np.ndarray
    scale: np.ndarray
    is_direction: np.ndarray


@dataclass(frozen=True)
class RBFModel:
    """A fitted multi-output Gaussian RBF interpolant (immutable arrays).

    Attributes
    ----------
    space : Space
        The input normalisation.
    centres : numpy.ndarray, shape (m, d)
        Normalised training points.
    shape : numpy.ndarray, shape (n_out,)
        Shape parameter ``q0`` per output (normalised distance units).
    weights : numpy.ndarray, shape (m, n_out)
        Kernel weights.
    poly_coef : numpy.ndarray, shape (p, n_out)
        Polynomial coefficients on :func:`polynomial_basis`.
    log_output : numpy.ndarray of bool, shape (n_out,)
        Outputs interpolated as ``log10`` (back-transformed on prediction).
    loo_error : numpy.ndarray, shape (m, n_out)
        Leave-one-out residuals at the chosen shape, in the transformed space
        (``log10`` units for log outputs).
    smoothing : numpy.ndarray, shape (n_out,)
        Ridge term added to the kernel diagonal per output (0: exact interpolation).
    """

    space: Space
    centres: np.ndarray
    shape: np.ndarray
    weights: np.ndarray
    poly_coef: np.ndarray
    log_output: np.ndarray
    loo_error: np.ndarray
    smoothing: np.ndarray

    @property
    def n_outputs(self) -> int:
        return int(self.weights.shape[1])


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


# --------------------------------------------------------------------------- space


def fit_space(
    points: npt.ArrayLike,
    is_direction: npt.ArrayLike,
    *,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
) -> Space:
    """The normalisation of methodology step 2: scalars by range, directions by 180 deg.

    The same embedding as the selection (:func:`moorlife.selection.scaling_from`), so the
    RBF distance is exactly the maximum-dissimilarity distance.

    Parameters
    ----------
    points : array_like, shape (n, d)
        Points in physical units (directions in degrees).
    is_direction : array_like of bool, shape (d,)
        Which columns are directions.
    lo, span : array_like, shape (d,), optional
        Offset and range of each scalar, e.g. the hindcast's as stored in
        ``cases.zarr`` (``norm_lo``, ``norm_span``); default from ``points``.

    Returns
    -------
    Space

    Raises
    ------
    ValueError
        If a scalar span is not positive and finite, or shapes disagree.
    """
    x = _as_points(points)
    isdir = np.asarray(is_direction, dtype=bool)
    if isdir.shape != (x.shape[1],):
        raise ValueError(f"is_direction has shape {isdir.shape}, expected ({x.shape[1]},)")
    lo_d, span_d = scaling_from(x, isdir)
    lo_a = lo_d if lo is None else np.broadcast_to(np.asarray(lo, dtype=float), isdir.shape).copy()
    span_a = span_d if span is None else np.broadcast_to(np.asarray(span, dtype=float), isdir.shape).copy()
    lo_a[isdir] = 0.0
    span_a[isdir] = 180.0
    bad = ~(np.isfinite(span_a) & (span_a > 0))
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise ValueError(f"input column {k} has span {span_a[k]!r}; a scalar needs a positive range")
    return Space(lower=lo_a, scale=span_a, is_direction=isdir)


def normalise(points: npt.ArrayLike, space: Space) -> np.ndarray:
    """Map physical points to the normalised space (:func:`moorlife.selection.normalise`).

    Scalars become ``(x - lower) / range``; directions become ``(x mod 360) / 180`` in
    ``[0, 2)``, so that the folded circular difference divided by 180 is
    ``min(|a - b|, 2 - |a - b|)``.

    Parameters
    ----------
    points : array_like, shape (n, d)
    space : Space

    Returns
    -------
    numpy.ndarray, shape (n, d), C-contiguous float64
    """
    x = _as_points(points)
    if x.shape[1] != space.scale.size:
        raise ValueError(f"points have {x.shape[1]} columns, the space has {space.scale.size}")
    z = _sel_normalise(x, space.is_direction, space.lower, space.scale, dtype=np.float64)
    return np.ascontiguousarray(z)


def _as_points(points: npt.ArrayLike) -> np.ndarray:
    x = np.asarray(points, dtype=float)
    if x.ndim == 1:
        x = x[:, None]
    if x.ndim != 2:
        raise ValueError(f"points must be a 2-D array (n, d), got shape {x.shape}")
    if not np.all(np.isfinite(x)):
        row, col = np.argwhere(~np.isfinite(x))[0]
        raise ValueError(f"points are not finite: row {row}, column {col} = {x[row, col]!r}")
    return x


# --------------------------------------------------------------------------- kernels


@nb.njit(parallel=True, cache=True)
def _sq_dist_block(zq: np.ndarray, zc_t: np.ndarray, isdir: np.ndarray, out: np.ndarray) -> None:  # pragma: no cover - numba
    n, d = zq.shape
    m = zc_t.shape[1]
    for i in nb.prange(n):
        for j in range(m):
            out[i, j] = 0.0
        for k in range(d):
            a = zq[i, k]
            if isdir[k]:
                for j in range(m):
                    t = abs(a - zc_t[k, j])
                    t = min(t, 2.0 - t)
                    out[i, j] += t * t
            else:
                for j in range(m):
                    t = a - zc_t[k, j]
                    out[i, j] += t * t


# exp(-t) for the kernel block: Cody-Waite reduction t = k ln2 + r, |r| <= ln2 / 2, a
# degree-13 Taylor polynomial (truncation < 1e-17) and 2^k assembled from the bits of the
# rounding shifter. Written as plain loops so LLVM vectorises them (libm exp does not);
# within 1 ulp of numpy.exp, exactly 0 below exp(-708) (tests/test_rbf.py checks both).
_LN2_HI = 6.93147180369123816490e-01
_LN2_LO = 1.90821492927058770002e-10
_INV_LN2 = 1.44269504088896338700e00
_SHIFTER = 6755399441055744.0  # 1.5 * 2**52: x + SHIFTER rounds x to an integer in the low bits


@nb.njit(parallel=True, cache=True)
def _gaussian_block(d2: np.ndarray, inv_q2: float, out: np.ndarray, tmp: np.ndarray) -> None:  # pragma: no cover - numba
    n, m = d2.shape
    bits = tmp.view(np.int64)
    for i in nb.prange(n):
        for j in range(m):
            x = max(-d2[i, j] * inv_q2, -708.0)
            t = x * _INV_LN2 + _SHIFTER
            k = t - _SHIFTER
            r = (x - k * _LN2_HI) - k * _LN2_LO
            p = 1.6059043836821613e-10
            p = p * r + 2.08767569878681e-09
            p = p * r + 2.505210838544172e-08
            p = p * r + 2.755731922398589e-07
            p = p * r + 2.7557319223985893e-06
            p = p * r + 2.48015873015873e-05
            p = p * r + 0.0001984126984126984
            p = p * r + 0.001388888888888889
            p = p * r + 0.008333333333333333
            p = p * r + 0.041666666666666664
            p = p * r + 0.16666666666666666
            p = p * r + 0.5
            p = p * r + 1.0
            p = p * r + 1.0
            out[i, j] = p
            tmp[i, j] = t
        for j in range(m):
            bits[i, j] = ((bits[i, j] & 0xFFFFFFFF) + 1023) << 52
        for j in range(m):
            out[i, j] = out[i, j] * tmp[i, j] if d2[i, j] * inv_q2 <= 708.0 else 0.0


def gaussian(d2: npt.ArrayLike, shape: float) -> np.ndarray:
    """The Gaussian kernel ``exp(-r^2 / q0^2)`` on squared distances (the fast path).

    Parameters
    ----------
    d2 : array_like, shape (n, m)
        Squared normalised distances (non-negative).
    shape : float
        ``q0``.

    Returns
    -------
    numpy.ndarray, shape (n, m)
    """
    a = np.ascontiguousarray(np.atleast_2d(np.asarray(d2, dtype=float)))
    out = np.empty_like(a)
    _gaussian_block(a, 1.0 / (shape * shape), out, np.empty_like(a))
    return out


@nb.njit(parallel=True, cache=True, fastmath=True)
def _weighted_sum(k: np.ndarray, w_t: np.ndarray, cols: np.ndarray, out: np.ndarray) -> None:  # pragma: no cover - numba
    # out[i, cols[o]] += sum_j k[i, j] * w_t[o, j]; each row by one thread in a fixed order, so
    # the numbers do not depend on the thread count (multi-threaded BLAS may change the last bit).
    n, m = k.shape
    for i in nb.prange(n):
        for o in range(w_t.shape[0]):
            acc = 0.0
            for j in range(m):
                acc += k[i, j] * w_t[o, j]
            out[i, cols[o]] += acc


@nb.njit(parallel=True, cache=True)
def _min_dist(zq: np.ndarray, zc_t: np.ndarray, isdir: np.ndarray, dmin: np.ndarray, imin: np.ndarray) -> None:  # pragma: no cover - numba
    n, d = zq.shape
    m = zc_t.shape[1]
    for i in nb.prange(n):
        row = np.zeros(m)
        for k in range(d):  # dimension-outer, like _sq_dist_block, so the j loop vectorises
            a = zq[i, k]
            if isdir[k]:
                for j in range(m):
                    t = abs(a - zc_t[k, j])
                    t = min(t, 2.0 - t)
                    row[j] += t * t
            else:
                for j in range(m):
                    t = a - zc_t[k, j]
                    row[j] += t * t
        ib = 0
        for j in range(1, m):
            if row[j] < row[ib]:
                ib = j
        dmin[i] = math.sqrt(row[ib])
        imin[i] = ib


def squared_distances(zq: npt.ArrayLike, zc: npt.ArrayLike, is_direction: npt.ArrayLike) -> np.ndarray:
    """Squared normalised distances between two sets of normalised points.

    Parameters
    ----------
    zq : array_like, shape (n, d)
        Normalised query points (see :func:`normalise`).
    zc : array_like, shape (m, d)
        Normalised centres.
    is_direction : array_like of bool, shape (d,)

    Returns
    -------
    numpy.ndarray, shape (n, m)
        ``r^2``: scalar differences squared plus, for directions,
        ``min(|a - b|, 2 - |a - b|)^2``.
    """
    a = np.ascontiguousarray(zq, dtype=float)
    b_t = np.ascontiguousarray(np.asarray(zc, dtype=float).T)
    out = np.empty((a.shape[0], b_t.shape[1]))
    _sq_dist_block(a, b_t, np.asarray(is_direction, dtype=np.bool_), out)
    return out


def polynomial_basis(z: npt.ArrayLike, is_direction: npt.ArrayLike) -> np.ndarray:
    """First-degree trend basis on normalised points.

    Parameters
    ----------
    z : array_like, shape (n, d)
        Normalised points.
    is_direction : array_like of bool, shape (d,)

    Returns
    -------
    numpy.ndarray, shape (n, 1 + n_scalar + 2 * n_direction)
        Columns ``1``, each scalar, then ``cos(pi z)`` and ``sin(pi z)`` of each direction
        (``z`` in units of 180 deg).
    """
    z = np.asarray(z, dtype=float)
    isdir = np.asarray(is_direction, dtype=bool)
    cols = [np.ones((z.shape[0], 1)), z[:, ~isdir]]
    if isdir.any():
        ang = np.pi * z[:, isdir]
        cols += [np.cos(ang), np.sin(ang)]
    return np.hstack(cols)


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
    ky, kp = sol[:, :values.shape[1]], sol[:, values.shape[1]:]
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
        Leave-one-out RMS per candidate (rows in order of preference on ties) and output;
        every output has at least one finite entry.
    share_tol : float
        See :func:`choose_shapes`: a greedy cover picks as few distinct candidates as possible
        among those within ``(1 + share_tol)`` of each output's minimum.

    Returns
    -------
    numpy.ndarray of int, shape (n_out,)
    """
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


# --------------------------------------------------------------------------- fit / predict


def fit_rbf(
    points: npt.ArrayLike,
    values: npt.ArrayLike,
    *,
    is_direction: npt.ArrayLike,
    shape: float | npt.ArrayLike | None = None,
    shapes: npt.ArrayLike | None = None,
    log_output: bool | npt.ArrayLike = False,
    smoothing: float | npt.ArrayLike = 0.0,
    share_tol: float = 0.0,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
) -> RBFModel:
    """Fit a multi-output Gaussian RBF with a first-degree polynomial.

    Parameters
    ----------
    points : array_like, shape (m, d)
        Training sea states in physical units (directions in degrees).
    values : array_like, shape (m, n_out) or (m,)
        Simulated outputs.
    is_direction : array_like of bool, shape (d,)
    shape : float or array_like (n_out,), optional
        Fixed ``q0`` per output. If omitted, Rippa's criterion picks it from ``shapes``.
    shapes : array_like, optional
        Candidate grid for Rippa; default ``shape_grid(0.02, 1.0, 20)``.
    log_output : bool or array_like of bool (n_out,)
        Interpolate ``log10`` of these outputs (they must be positive).
    smoothing : float or array_like
        Ridge term (0: exact interpolation, the paper's choice). Several values are candidates:
        each output then takes the one with the smallest leave-one-out error, jointly with its
        shape (:func:`choose_shapes_and_smoothing`).
    share_tol : float
        See :func:`choose_shapes`.
    lo, span : array_like (d,), optional
        Normalisation offset and range of the scalars (e.g. the hindcast's, see
        :func:`fit_space`); default from the points.

    Returns
    -------
    RBFModel

    Raises
    ------
    ValueError
        On non-finite values, non-positive values of a log output (naming output and row),
        or mismatched shapes.
    """
    x = _as_points(points)
    y = np.asarray(values, dtype=float)
    if y.ndim == 1:
        y = y[:, None]
    if y.shape[0] != x.shape[0]:
        raise ValueError(f"values have {y.shape[0]} rows, points have {x.shape[0]}")
    if not np.all(np.isfinite(y)):
        row, col = np.argwhere(~np.isfinite(y))[0]
        raise ValueError(f"values are not finite: output {col}, row {row} = {y[row, col]!r}")
    n_out = y.shape[1]
    logs = np.broadcast_to(np.asarray(log_output, dtype=bool), (n_out,)).copy()
    if logs.any():
        sub = y[:, logs]
        if np.any(sub <= 0):
            row, col = np.argwhere(sub <= 0)[0]
            out = int(np.flatnonzero(logs)[col])
            raise ValueError(
                f"output {out} is log-transformed but row {row} = {sub[row, col]!r} is not positive"
            )
        y = y.copy()
        y[:, logs] = np.log10(sub)
    space = fit_space(x, is_direction, lo=lo, span=span)
    z = normalise(x, space)
    d2 = squared_distances(z, z, space.is_direction)
    basis = polynomial_basis(z, space.is_direction)
    if z.shape[0] < basis.shape[1] + 1:
        raise ValueError(f"{z.shape[0]} training points are too few for {basis.shape[1]} polynomial terms")
    lam_grid = np.atleast_1d(np.asarray(smoothing, dtype=float))
    if lam_grid.size == 0 or np.any(~(lam_grid >= 0)):
        raise ValueError(f"smoothing must be non-negative, got {smoothing!r}")
    if shape is None:
        grid = shape_grid(0.02, 1.0, 20) if shapes is None else np.asarray(shapes, dtype=float)
        q, lam = choose_shapes_and_smoothing(d2, basis, y, grid, lam_grid, share_tol)
    else:
        q = np.broadcast_to(np.asarray(shape, dtype=float), (n_out,)).copy()
        if np.any(~(q > 0)):
            raise ValueError(f"shape parameters must be positive, got {q}")
        lam = np.full(n_out, lam_grid[0])
        if lam_grid.size > 1:  # fixed shapes, smoothing by leave-one-out per shape
            for qi in np.unique(q):
                cols = np.flatnonzero(q == qi)
                lam[cols] = choose_shapes_and_smoothing(d2, basis, y[:, cols], [qi], lam_grid, share_tol)[1]
    m = z.shape[0]
    weights = np.empty_like(y)
    poly = np.empty((basis.shape[1], n_out))
    loo = np.empty_like(y)
    for qi, li in sorted(set(zip(q.tolist(), lam.tolist()))):
        cols = np.flatnonzero((q == qi) & (lam == li))
        mat = augmented_matrix(d2, basis, float(qi), float(li))
        w, c = solve_weights(mat, y[:, cols])
        weights[:, cols] = w
        poly[:, cols] = c
        h, _ = kernel_block_inverse(mat[:m, :m], basis)
        if h is None:  # not numerically positive definite: fall back on the full inverse
            h, _ = _inverse(mat)
        loo[:, cols] = rippa_errors(h, y[:, cols])
    return RBFModel(
        space=space,
        centres=z,
        shape=q,
        weights=weights,
        poly_coef=poly,
        log_output=logs,
        loo_error=loo,
        smoothing=lam,
    )


def predict_rbf(model: RBFModel, points: npt.ArrayLike, *, chunk_rows: int = 8192) -> np.ndarray:
    """Evaluate the interpolant at new points.

    Parameters
    ----------
    model : RBFModel
    points : array_like, shape (n, d)
        Physical units (directions in degrees).
    chunk_rows : int
        Rows per block (memory ``~ 16 * chunk_rows * m`` bytes); does not change the numbers.

    Returns
    -------
    numpy.ndarray, shape (n, n_out)
        Back-transformed (``10**``) for log outputs.
    """
    z = normalise(points, model.space)
    n = z.shape[0]
    m = model.centres.shape[0]
    zc_t = np.ascontiguousarray(model.centres.T)
    isdir = model.space.is_direction.astype(np.bool_)
    groups = [(float(q), np.flatnonzero(model.shape == q)) for q in np.unique(model.shape)]
    w_t = {q: np.ascontiguousarray(model.weights[:, cols].T) for q, cols in groups}
    basis = polynomial_basis(z, isdir)
    out = np.zeros((n, model.n_outputs))
    _weighted_sum(basis, np.ascontiguousarray(model.poly_coef.T), np.arange(model.n_outputs), out)
    rows = max(1, int(chunk_rows))
    d2 = np.empty((min(rows, n), m))
    k = np.empty_like(d2)
    tmp = np.empty_like(d2)
    for s in range(0, n, rows):
        e = min(n, s + rows)
        b = e - s
        _sq_dist_block(z[s:e], zc_t, isdir, d2[:b])
        for q, cols in groups:
            _gaussian_block(d2[:b], 1.0 / (q * q), k[:b], tmp[:b])
            _weighted_sum(k[:b], w_t[q], cols, out[s:e])
    if model.log_output.any():
        out[:, model.log_output] = 10.0 ** out[:, model.log_output]
    return out


def nearest_centre(model: RBFModel, points: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Distance to, and index of, the nearest training point of each query point.

    Parameters
    ----------
    model : RBFModel
    points : array_like, shape (n, d)

    Returns
    -------
    distance : numpy.ndarray, shape (n,)
        Normalised distance.
    index : numpy.ndarray of int64, shape (n,)
    """
    z = normalise(points, model.space)
    dmin = np.empty(z.shape[0])
    imin = np.empty(z.shape[0], dtype=np.int64)
    _min_dist(z, np.ascontiguousarray(model.centres.T), model.space.is_direction.astype(np.bool_), dmin, imin)
    return dmin, imin
