"""Prediction: the interpolant at new points, and the nearest training point.

Runs in row chunks (bounded memory), float64, in numba kernels (distance, kernel block,
weighted sums); every row is computed independently in a fixed order, so the numbers do not
depend on chunk size or thread count.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from moorlife.rbf.fit import RBFModel, model_basis
from moorlife.rbf.kernels import _gaussian_block, _weighted_sum
from moorlife.space import embed, nearest_block, sq_dist_block

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
