"""Prediction: the posterior mean (and latent variance) at new points, back-transformed.

The mean runs in one compiled kernel per row (distance, the exponential of
:mod:`moorlife.rbf.kernels`, weighted sums; every row by one thread in a fixed order, so the
numbers do not depend on chunk size or thread count). Outputs with the same length scales share
their kernel row. The latent variance needs one triangular solve per
output and chunk (``m^2`` per point: about 15 CPU-s per output for 271,728 hours and 1,000
training states), so it is computed only when asked for.
"""

from __future__ import annotations

import numba as nb
import numpy as np
import numpy.typing as npt
import scipy.linalg as sla

from moorlife.gp.covariance import correlation, covariance_code, exponent, prefactor
from moorlife.gp.fit import _LN10_SQ, GPModel, chord_embed
from moorlife.rbf.kernels import exp_parts

__all__ = ["predict_gp", "predict_latent"]

#: Rows per block of the variance at most (blocks of 256 x 1,000 stay in cache; a smaller
#: ``chunk_rows`` is honoured).
_CACHE_ROWS = 256
#: Rows per parallel task of the mean (each row is computed alone: the numbers do not depend on it).
_ROWS = 64


@nb.njit(parallel=True, cache=True)
def _mean_rows(
    z: np.ndarray,
    inv_l: np.ndarray,
    ct: np.ndarray,
    gptr: np.ndarray,
    gcols: np.ndarray,
    w: np.ndarray,
    code: int,
    out: np.ndarray,
) -> None:  # pragma: no cover - numba
    # out[i, o] += sum_j rho(|(z_i - c_j) / l_g|) w[o, j] for the outputs o of every length-scale
    # group g (gcols[gptr[g]:gptr[g + 1]]); ct[g] holds the centres scaled by 1 / l_g, transposed.
    # Fused per row (distance, exp, weighted sums in buffers of m that stay in cache); each row by
    # one thread in a fixed order. rho is the family `code` of moorlife.gp.covariance, its exp by
    # moorlife.rbf.kernels.exp_parts (d2 holds the exponent's argument after the distance).
    n, p = z.shape
    n_g, _, m = ct.shape
    n_blocks = (n + _ROWS - 1) // _ROWS
    for blk in nb.prange(n_blocks):
        d2 = np.empty(m)
        k = np.empty(m)
        tmp = np.empty(m)
        bits = tmp.view(np.int64)
        for i in range(blk * _ROWS, min(n, (blk + 1) * _ROWS)):
            for g in range(n_g):
                for j in range(m):
                    d2[j] = 0.0
                for d in range(p):
                    a = z[i, d] * inv_l[g, d]
                    for j in range(m):
                        u = a - ct[g, d, j]
                        d2[j] += u * u
                for j in range(m):
                    d2[j] = exponent(d2[j], code)
                    k[j], tmp[j] = exp_parts(max(d2[j], -708.0))
                for j in range(m):
                    bits[j] = ((bits[j] & 0xFFFFFFFF) + 1023) << 52
                for j in range(m):
                    k[j] = k[j] * tmp[j] * prefactor(d2[j], code) if d2[j] >= -708.0 else 0.0
                for c in range(gptr[g], gptr[g + 1]):
                    o = gcols[c]
                    acc = 0.0
                    for j in range(m):
                        acc += k[j] * w[o, j]
                    out[i, o] += acc


def _groups(length_scale: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Outputs with the same length scales, as ``gptr, gcols`` (CSR), groups in order of first output."""
    _, first, inverse = np.unique(length_scale, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.reshape(-1)
    members = [np.flatnonzero(inverse == g) for g in np.argsort(first)]
    gptr = np.concatenate([[0], np.cumsum([c.size for c in members])]).astype(np.int64)
    return gptr, np.concatenate(members).astype(np.int64)


def predict_latent(
    model: GPModel,
    points: npt.ArrayLike,
    *,
    variance_of: npt.ArrayLike | None = None,
    chunk_rows: int = 8192,
) -> tuple[np.ndarray, np.ndarray]:
    """Posterior mean and latent variance in the transformed units (``log10`` for log outputs).

    Parameters
    ----------
    model : GPModel
    points : array_like, shape (n, d)
        Physical units (directions in degrees).
    variance_of : array_like of bool, shape (n_out,), optional
        Outputs whose latent (noise-free) variance is computed; default none.
    chunk_rows : int
        Rows per block of the variance (memory ``~ 16 * chunk_rows * m`` bytes; at most 256);
        does not change the numbers.

    Returns
    -------
    mean : numpy.ndarray, shape (n, n_out)
    variance : numpy.ndarray, shape (n, n_out)
        NaN in the columns not asked for.
    """
    z = chord_embed(points, model.space)
    n = z.shape[0]
    want = np.zeros(model.n_outputs, bool) if variance_of is None else np.asarray(variance_of, bool)
    gptr, gcols = _groups(model.length_scale)
    heads = gcols[gptr[:-1]]
    inv_l = np.ascontiguousarray(1.0 / model.length_scale[heads])
    ct = np.ascontiguousarray(np.stack([(model.centres * il).T for il in inv_l]))
    mean = np.zeros((n, model.n_outputs))
    w = np.ascontiguousarray(model.weights.T)
    _mean_rows(z, inv_l, ct, gptr, gcols, w, covariance_code(model.covariance), mean)
    mean += model.mean
    if model.slope is not None:
        mean += z @ model.slope
    var = np.full((n, model.n_outputs), np.nan)
    if want.any():
        if model.slope is not None:
            raise ValueError("the latent variance of a GP with a linear prior mean is not available")
        rows = max(1, min(int(chunk_rows), _CACHE_ROWS))
        for j in np.flatnonzero(want):
            for s in range(0, n, rows):
                e = min(n, s + rows)
                k = correlation(z[s:e], model.centres, model.length_scale[j], model.covariance)
                v = sla.solve_triangular(model.chol[j], k.T, lower=True, check_finite=False)
                var[s:e, j] = np.maximum(model.signal_var[j] * (1.0 - np.einsum("ij,ij->j", v, v)), 0.0)
    return mean, var


def predict_gp(model: GPModel, points: npt.ArrayLike, *, chunk_rows: int = 8192) -> np.ndarray:
    """Every output at new points in its own units: the expected value of a new realisation.

    A linear output is its posterior mean. A ``log10`` output with posterior mean ``mu`` is
    ``10**mu`` times the back-transform factor of ``model.retransform``: 1 (``none``, the
    median), ``exp((ln 10)^2 s_n^2 / 2)`` (``noise``) or ``exp((ln 10)^2 (s_n^2 + s^2(x)) / 2)``
    (``predictive``, with the latent variance ``s^2(x)`` at each point).

    Parameters
    ----------
    model : GPModel
    points : array_like, shape (n, d)
    chunk_rows : int
        Rows per block; does not change the numbers.

    Returns
    -------
    numpy.ndarray, shape (n, n_out)
    """
    predictive = model.log_output if model.retransform == "predictive" else None
    out, var = predict_latent(model, points, variance_of=predictive, chunk_rows=chunk_rows)
    logs = model.log_output
    if logs.any():
        out[:, logs] = 10.0 ** out[:, logs] * model.log_factor[logs]
        if predictive is not None:
            out[:, logs] *= np.exp(0.5 * _LN10_SQ * var[:, logs])
    return out
