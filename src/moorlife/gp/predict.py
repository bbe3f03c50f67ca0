"""Prediction: the posterior mean (and latent variance) at new points, back-transformed.

The mean runs in one compiled kernel per row (the squared differences of every coordinate, once
for all outputs; then per length-scale group the scaled distance, the exponential of
:mod:`moorlife.rbf.kernels` and the weighted sums in eight fixed partial sums; every row by one
thread in a fixed order, so the numbers do not depend on chunk size, thread count or the
machine's vector width). Outputs with the same length scales share their kernel row. The latent
variance needs one triangular solve per output and chunk (``m^2`` per point: about 15 CPU-s per
output for 271,728 hours and 1,000 training states), so it is computed only when asked for.
"""

from __future__ import annotations

import numba as nb
import numpy as np
import numpy.typing as npt
import scipy.linalg as sla

from moorlife.gp.covariance import correlation, covariance_code, exponent, prefactor
from moorlife.gp.fit import _LN10_SQ, GPModel, chord_embed
from moorlife.rbf.kernels import exp_parts
from moorlife.rbf.predict import sum_columns

__all__ = ["predict_gp", "predict_latent"]

#: Rows per block of the variance at most (blocks of 256 x 1,000 stay in cache; a smaller
#: ``chunk_rows`` is honoured).
_CACHE_ROWS = 256
#: Rows per parallel task of the mean (each row is computed alone: the numbers do not depend on it).
_ROWS = 64


#: Partial sums of the weighted sum of a kernel row: lane ``l`` adds the centres ``j = l (mod 8)``
#: in order, then the lanes are added in order. A fixed order, whatever the vector width of the
#: machine, that breaks the serial dependency of one accumulator (a quarter of the prediction's time).
_LANES = 8


@nb.njit(inline="always", cache=True)
def _kernel_row(d2: np.ndarray, k: np.ndarray, tmp: np.ndarray, code: int) -> None:  # pragma: no cover - numba
    # k = rho(d2) of the family `code` in three vectorised passes (moorlife.rbf.kernels.exp_parts);
    # d2 holds the exponent's argument afterwards. Called with a literal code, so that each family
    # compiles to its own branch-free loops.
    m = d2.shape[0]
    bits = tmp.view(np.int64)
    for j in range(m):
        d2[j] = exponent(d2[j], code)
        k[j], tmp[j] = exp_parts(max(d2[j], -708.0))
    for j in range(m):
        bits[j] = ((bits[j] & 0xFFFFFFFF) + 1023) << 52
    for j in range(m):
        k[j] = k[j] * tmp[j] * prefactor(d2[j], code) if d2[j] >= -708.0 else 0.0


@nb.njit(inline="always", cache=True)
def _dot(k: np.ndarray, w: np.ndarray, o: int, acc: np.ndarray) -> float:  # pragma: no cover - numba
    # sum_j k[j] w[o, j] in the fixed lane order of _LANES
    m = k.shape[0]
    mm = m - m % _LANES
    for lane in range(_LANES):
        acc[lane] = 0.0
    for j0 in range(0, mm, _LANES):
        for lane in range(_LANES):
            acc[lane] += k[j0 + lane] * w[o, j0 + lane]
    for j in range(mm, m):
        acc[j - mm] += k[j] * w[o, j]
    s = 0.0
    for lane in range(_LANES):
        s += acc[lane]
    return s


@nb.njit(parallel=True, cache=True)
def _mean_rows(
    z: np.ndarray,
    s2: np.ndarray,
    c_t: np.ndarray,
    gptr: np.ndarray,
    gcols: np.ndarray,
    w: np.ndarray,
    code: int,
    out: np.ndarray,
) -> None:  # pragma: no cover - numba
    # out[i, o] += sum_j rho(d2_g(z_i, c_j)) w[o, j] for the outputs o of every length-scale group g
    # (gcols[gptr[g]:gptr[g + 1]]), d2_g = sum_d s2[g, d] (z_id - c_jd)^2 with s2 = 1 / l_g^2 and
    # c_t the centres transposed. Per row, the squared differences of every coordinate are computed
    # once for all groups; every buffer (p x m) stays in cache. Each row by one thread in a fixed
    # order, so the numbers do not depend on chunk size or thread count.
    n, p = z.shape
    n_g = s2.shape[0]
    m = c_t.shape[1]
    n_blocks = (n + _ROWS - 1) // _ROWS
    for blk in nb.prange(n_blocks):
        sq = np.empty((p, m))
        d2 = np.empty(m)
        k = np.empty(m)
        tmp = np.empty(m)
        acc = np.empty(_LANES)
        for i in range(blk * _ROWS, min(n, (blk + 1) * _ROWS)):
            for d in range(p):
                a = z[i, d]
                for j in range(m):
                    u = a - c_t[d, j]
                    sq[d, j] = u * u
            for g in range(n_g):
                s = s2[g, 0]
                for j in range(m):
                    d2[j] = s * sq[0, j]
                for d in range(1, p):
                    s = s2[g, d]
                    for j in range(m):
                        d2[j] += s * sq[d, j]
                if code == 0:  # a literal per family: branch-free loops
                    _kernel_row(d2, k, tmp, 0)
                elif code == 1:
                    _kernel_row(d2, k, tmp, 1)
                else:
                    _kernel_row(d2, k, tmp, 2)
                for c in range(gptr[g], gptr[g + 1]):
                    o = gcols[c]
                    out[i, o] += _dot(k, w, o, acc)


def _groups(length_scale: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Outputs with the same length scales, as ``gptr, gcols`` (CSR), groups in order of first output."""
    _, first, inverse = np.unique(length_scale, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.reshape(-1)
    members = [np.flatnonzero(inverse == g) for g in np.argsort(first)]
    gptr = np.concatenate([[0], np.cumsum([c.size for c in members])]).astype(np.int64)
    return gptr, np.concatenate(members).astype(np.int64)


def _cross_correlation(
    model: GPModel, z: np.ndarray, j: int, gate_centres: np.ndarray | None
) -> tuple[np.ndarray, np.ndarray | None]:
    """Correlation of embedded points ``z`` with the centres for output ``j``, the gated wind term
    included (``gate_centres``: the sea gate at the centres; ``None`` without the term), and the
    gate at the points (``None`` without the term)."""
    k = correlation(z, model.centres, model.length_scale[j], model.covariance)
    if gate_centres is None:
        return k, None
    gi = model.gates(z, [j])[:, 0]
    rw = correlation(z, model.centres, model.wind_length_scale[j], model.covariance)
    k += model.wind_ratio[j] * np.outer(gi, gate_centres) * rw
    return k, gi


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
    n_out = model.n_outputs
    want = np.zeros(n_out, bool) if variance_of is None else np.asarray(variance_of, bool)
    wr = model.wind_ratio
    add = np.flatnonzero(wr > 0)
    # the additive term as more outputs of the compiled kernel: its length scales (inf: a
    # coordinate it does not see, so 1 / l^2 = 0) and the weights times wind_var / signal_var
    # and the sea gate at the centres; times the gate at the point, added to their output afterwards
    ls_all = model.length_scale if add.size == 0 else np.vstack([model.length_scale, model.wind_length_scale[add]])
    w_all = model.weights
    if add.size:
        w_all = np.hstack([model.weights, model.weights[:, add] * wr[add] * model.gates(model.centres, add)])
    gptr, gcols = _groups(ls_all)
    s2 = np.ascontiguousarray(ls_all[gcols[gptr[:-1]]] ** -2.0)
    mean = np.zeros((n, ls_all.shape[0]))
    w = np.ascontiguousarray(w_all.T)
    _mean_rows(z, s2, np.ascontiguousarray(model.centres.T), gptr, gcols, w, covariance_code(model.covariance), mean)
    if add.size:
        mean[:, add] += mean[:, n_out:] * model.gates(z, add)
        mean = np.ascontiguousarray(mean[:, :n_out])
    mean += model.mean
    if model.slope is not None:
        mean += z @ model.slope
    var = np.full((n, n_out), np.nan)
    if want.any():
        if model.slope is not None:
            raise ValueError("the latent variance of a GP with a linear prior mean is not available")
        rows = max(1, min(int(chunk_rows), _CACHE_ROWS))
        for j in np.flatnonzero(want):
            gc = model.gates(model.centres, [j])[:, 0] if wr[j] > 0 else None  # the sea gate at the centres, once
            for s in range(0, n, rows):
                e = min(n, s + rows)
                k, gi = _cross_correlation(model, z[s:e], j, gc)
                prior = 1.0 if gi is None else 1.0 + wr[j] * gi**2
                v = sla.solve_triangular(model.chol[j], k.T, lower=True, check_finite=False)
                var[s:e, j] = np.maximum(model.signal_var[j] * (prior - np.einsum("ij,ij->j", v, v)), 0.0)
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


def training_weights(
    model: GPModel,
    points: npt.ArrayLike,
    weights: npt.ArrayLike,
    *,
    outputs: npt.ArrayLike | None = None,
    chunk_rows: int = 8192,
) -> np.ndarray:
    """The weight of each training value in a weighted sum of the posterior means.

    With a constant prior mean ``m`` the posterior mean is linear in the training values ``y``
    (transformed units: ``log10`` for a log output): ``mu(x_h) - m = sum_i A_hi (y_i - m)``, with
    ``A = K_* B^-1`` in correlation units (``B`` the training correlation with the noise ratio
    and any wind term, ``model.chol``). So ``sum_h w_h (mu(x_h) - m) = sum_i G_i (y_i - m)`` with
    ``G = B^-1 K_*^T w``: ``G_i`` is the part of the sum that training value ``i`` carries. One
    pass over ``points`` per output and one triangular solve pair. With ``w_h`` the predicted
    hourly damage of a log output, a relative error ``e_i`` of training record ``i`` moves the
    damage sum by ``sum_i G_i e_i`` to first order: the records' seed noise in a sum.

    Parameters
    ----------
    model : GPModel
    points : array_like, shape (n, d)
        Physical units (directions in degrees).
    weights : array_like, shape (n,) or (n, k)
        The weights of the sum: one column for each output of ``outputs``, or one for all.
    outputs : array_like of int, optional
        The outputs (default every one).
    chunk_rows : int
        Rows per block; does not change the result beyond rounding.

    Returns
    -------
    numpy.ndarray, shape (m, k)

    Raises
    ------
    ValueError
        With a linear prior mean (its slope is itself fitted to ``y``), or weights of the wrong shape.
    """
    if model.slope is not None:
        raise ValueError("training_weights: a GP with a linear prior mean is not supported")
    z = chord_embed(points, model.space)
    n = z.shape[0]
    outs, w = sum_columns(weights, n, model.n_outputs, outputs)
    wr = model.wind_ratio
    rows = max(1, int(chunk_rows))
    out = np.zeros((model.centres.shape[0], outs.size))
    for group in _shared_correlation(model, outs):  # one pass over the points per shared correlation
        j = int(outs[group[0]])
        gc = model.gates(model.centres, [j])[:, 0] if wr[j] > 0 else None
        acc = np.zeros((model.centres.shape[0], len(group)))
        for s in range(0, n, rows):
            e = min(n, s + rows)
            acc += _cross_correlation(model, z[s:e], j, gc)[0].T @ w[s:e, group]
        out[:, group] = sla.cho_solve((model.chol[j], True), acc, check_finite=False)
    return out


def _shared_correlation(model: GPModel, outs: np.ndarray) -> list[list[int]]:
    """Positions in ``outs`` grouped by the outputs' correlation: the same length scales, wind term
    and Cholesky factor (the outputs of one hyperparameter group, e.g. a line's S-N and T-N)."""
    wr = model.wind_ratio
    groups: list[list[int]] = []
    for c, j in enumerate(outs.tolist()):
        for g in groups:
            k = int(outs[g[0]])
            same = np.array_equal(model.length_scale[j], model.length_scale[k]) and wr[j] == wr[k]
            if same and wr[j] > 0:
                same = np.array_equal(model.wind_length_scale[j], model.wind_length_scale[k]) and np.array_equal(
                    model.gates(model.centres, [j]), model.gates(model.centres, [k])
                )
            if same and np.array_equal(model.chol[j], model.chol[k]):
                g.append(c)
                break
        else:
            groups.append([c])
    return groups
