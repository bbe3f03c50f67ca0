"""Prediction: the interpolant at new points, and the nearest training point.

Runs in row chunks (bounded memory), float64, in numba kernels (distance, kernel block,
weighted sums); every row is computed independently in a fixed order, so the numbers do not
depend on chunk size or thread count.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
import scipy.linalg as sla

from moorlife.rbf.fit import RBFModel, model_basis
from moorlife.rbf.kernels import _gaussian_block, _weighted_sum, gaussian, polynomial_basis
from moorlife.rbf.system import augmented_matrix
from moorlife.space import as_points, embed, nearest_block, sq_dist_block, squared_distances

__all__ = ["predict_rbf", "nearest_centre"]


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
        Back-transformed for log outputs: ``c 10**f`` with ``c`` the model's ``log_factor``.
    """
    z = embed(points, model.space)
    n = z.shape[0]
    m = model.centres.shape[0]
    zc_t = np.ascontiguousarray(model.centres.T)
    isdir = model.space.is_direction.astype(np.bool_)
    groups = [(float(q), np.flatnonzero(model.shape == q)) for q in np.unique(model.shape)]
    w_t = {q: np.ascontiguousarray(model.weights[:, cols].T) for q, cols in groups}
    x = np.asarray(points, dtype=float)
    poly_t = np.ascontiguousarray(model.poly_coef.T)
    every = np.arange(model.n_outputs)
    out = np.zeros((n, model.n_outputs))
    rows = max(1, int(chunk_rows))
    d2 = np.empty((min(rows, n), m))
    k = np.empty_like(d2)
    tmp = np.empty_like(d2)
    for s in range(0, n, rows):
        e = min(n, s + rows)
        b = e - s
        # the trend first, then the kernel sums: per row the same order as one block of every row
        _weighted_sum(model_basis(x[s:e], z[s:e], isdir, model.trend), poly_t, every, out[s:e])
        sq_dist_block(z[s:e], zc_t, isdir, d2[:b])
        for q, cols in groups:
            _gaussian_block(d2[:b], 1.0 / (q * q), k[:b], tmp[:b])
            _weighted_sum(k[:b], w_t[q], cols, out[s:e])
    if model.log_output.any():
        out[:, model.log_output] = 10.0 ** out[:, model.log_output]
        corrected = model.log_output & (model.log_factor != 1.0)
        if corrected.any():  # the back-transform correction c 10**f (moorlife.rbf.transform)
            out[:, corrected] *= model.log_factor[corrected]
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
    z = embed(points, model.space)
    dmin = np.empty(z.shape[0])
    imin = np.empty(z.shape[0], dtype=np.int64)
    nearest_block(z, np.ascontiguousarray(model.centres.T), model.space.is_direction.astype(np.bool_), dmin, imin)
    return dmin, imin


def sum_columns(
    weights: npt.ArrayLike, n: int, n_outputs: int, outputs: npt.ArrayLike | None
) -> tuple[np.ndarray, np.ndarray]:
    """The outputs of a weighted sum (default all) and its weights, one column per output.

    Raises
    ------
    ValueError
        If ``weights`` is neither ``(n,)`` nor ``(n, len(outputs))``.
    """
    outs = np.arange(n_outputs) if outputs is None else np.asarray(outputs, dtype=np.int64).reshape(-1)
    w = np.asarray(weights, dtype=float)
    w = np.repeat(w[:, None], outs.size, axis=1) if w.ndim == 1 else w
    if w.shape != (n, outs.size):
        raise ValueError(f"weights have shape {np.shape(weights)}; expected ({n},) or ({n}, {outs.size})")
    return outs, w


def training_weights(
    model: RBFModel,
    points: npt.ArrayLike,
    weights: npt.ArrayLike,
    *,
    outputs: npt.ArrayLike | None = None,
    train_points: npt.ArrayLike | None = None,
    chunk_rows: int = 8192,
) -> np.ndarray:
    """The weight of each training value in a weighted sum of the interpolant's values.

    The interpolant is linear in its training values ``y`` (transformed: ``log10`` for a log
    output): ``f(x_h) = sum_i A_hi y_i``, with ``A = [K_* P_*] M^-1`` restricted to the ``y``
    rows, ``M`` the augmented matrix of the output's shape and ridge. So a weighted sum of its
    values is ``sum_h w_h f(x_h) = sum_i G_i y_i`` with ``G = A^T w``: ``G_i`` is the part of the
    sum that training value ``i`` carries. One symmetric solve per shape and ridge, and one pass
    over ``points`` as in a prediction. With ``w_h`` the predicted hourly damage of a log
    output, a relative error ``e_i`` of training record ``i`` moves the damage sum by
    ``sum_i G_i e_i`` to first order: the records' seed noise in a sum.

    Parameters
    ----------
    model : RBFModel
    points : array_like, shape (n, d)
        Physical units (directions in degrees).
    weights : array_like, shape (n,) or (n, k)
        The weights of the sum: one column for each output of ``outputs``, or one for all.
    outputs : array_like of int, optional
        The outputs (default every one).
    train_points : array_like, shape (m, d), optional
        The training states in physical units; required when the model has a trend
        (``model.trend``), whose columns at the centres need them.
    chunk_rows : int
        Rows per block; does not change the result beyond rounding.

    Returns
    -------
    numpy.ndarray, shape (m, k)

    Raises
    ------
    ValueError
        On weights of the wrong shape, or a trend without ``train_points``.
    """
    z = embed(points, model.space)
    n, m = z.shape[0], model.centres.shape[0]
    outs, w = sum_columns(weights, n, model.n_outputs, outputs)
    isdir = model.space.is_direction.astype(np.bool_)
    if model.trend is None:  # the polynomial needs only the normalised centres
        basis_c = polynomial_basis(model.centres, isdir)
    elif train_points is None:
        raise ValueError("training_weights: the model has a trend; pass its train_points (physical units)")
    else:
        basis_c = model_basis(as_points(train_points), model.centres, isdir, model.trend)
    d2_c = squared_distances(model.centres, model.centres, isdir)
    x = np.asarray(points, dtype=float)
    zc_t = np.ascontiguousarray(model.centres.T)
    out = np.zeros((m, outs.size))
    rows = max(1, int(chunk_rows))
    shape, ridge = model.shape[outs], model.smoothing[outs]
    for q, lam in sorted(set(zip(shape.tolist(), ridge.tolist()))):
        cols = np.flatnonzero((shape == q) & (ridge == lam))
        rhs = np.zeros((m + basis_c.shape[1], cols.size))
        for s in range(0, n, rows):
            e = min(n, s + rows)
            d2 = np.empty((e - s, m))
            sq_dist_block(z[s:e], zc_t, isdir, d2)
            rhs[:m] += gaussian(d2, q).T @ w[s:e, cols]
            rhs[m:] += model_basis(x[s:e], z[s:e], isdir, model.trend).T @ w[s:e, cols]
        mat = augmented_matrix(d2_c, basis_c, float(q), float(lam))
        out[:, cols] = sla.solve(mat, rhs, assume_a="sym")[:m]
    return out
