"""The training records' seed noise in a reconstructed damage sum.

A reconstruction is trained on one simulated record (one seed) per training state, or the mean
of a few (seed replicates), and it is linear in those records. The RBF's and the GP's
prediction of a ``log10`` damage output at an hour ``h`` is ``f_h = sum_i A_hi y_i`` with ``y_i``
the ``log10`` damage of training state ``i`` (the GP about its constant prior mean), so a
relative seed error ``e_i`` of record ``i`` moves the sum ``S = sum_h D_h`` of the reconstructed
hourly damage by ``sum_i G_i e_i`` to first order, with ``G = A^T D``
(:func:`moorlife.rbf.training_weights`, :func:`moorlife.gp.training_weights`). For a linear
output ``f_h = sum_i A_hi d_i`` with ``d_i`` the damage itself, and ``G_i = d_i (A^T 1)_i`` over the
hours whose prediction is positive (the sums clip at 0).

With each record's seed error of relative sd ``c`` (the seed CV of one hour's damage), the
reconstructed sum has the seed scatter ``c |G| / S``, ``|G|`` with each state's ``G_i`` divided by
the square root of its records. Unlike the truth's hours, the reconstruction's hours are not
independent: every storm hour near one training state carries that one record's error. On the
1985 truth windows three storm records carried 69-91 % of October's sum, and their term was
2-3 times the truth's own scatter (``validation/reconstruction.md`` section 25).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from moorlife import gp, rbf
from moorlife.lifecycle.fit import Reconstruction
from moorlife.lifecycle.spaces import space_points

__all__ = ["carried_shares", "records_sum_cv"]


def carried_shares(
    model: Reconstruction,
    points: npt.ArrayLike,
    predicted: npt.ArrayLike,
    train_values: npt.ArrayLike,
    train_points: npt.ArrayLike,
    outputs: Sequence[int],
    *,
    chunk_rows: int = 8192,
) -> np.ndarray:
    """``G_i / S``: the share of each output's sum over ``points`` that each training record carries.

    Parameters
    ----------
    model : Reconstruction
        The fitted reconstruction; each model's centres are the training states, in order. A
        blend (``choose: stack``) is linear in each part's transformed prediction, so its shares
        are the weighted sum of the parts' (with the blend's ``predicted`` as the hours' weights).
    points : array_like, shape (n, 5)
        The hours of the sum (``names.METOCEAN_VARS`` order, physical units).
    predicted : array_like, shape (n, n_out)
        ``predict_outputs(model, points)``, or the stored reconstruction at those hours.
    train_values : array_like, shape (m, n_out)
        The training values the model was fitted on (the linear outputs' records).
    train_points : array_like, shape (m, 5)
        The training states (physical units), for a model with a trend.
    outputs : sequence of int
        The columns (damage outputs) to take.
    chunk_rows : int
        Rows per block (memory only).

    Returns
    -------
    numpy.ndarray, shape (m, len(outputs))
        ``G_i / S`` per output: a relative error ``e_i`` of record ``i`` moves the sum by
        ``sum_i (G_i / S) e_i`` of itself. NaN for an output whose sum is 0.

    Raises
    ------
    ValueError
        If the model's centres are not the training states, or for a GP with a linear prior mean.
    """
    x = np.asarray(points, dtype=float)
    p = np.clip(np.asarray(predicted, dtype=float), 0.0, None)
    yt = np.asarray(train_values, dtype=float)
    xt = np.asarray(train_points, dtype=float)
    outs = [int(j) for j in outputs]
    m = xt.shape[0]
    out = np.full((m, len(outs)), np.nan)
    where = {j: k for k, j in enumerate(outs)}
    blend = model.weights if model.weights is not None else [np.ones(c.size) for c in model.columns]
    seen = np.zeros(len(outs), dtype=bool)
    for sub, cols, name, wts in zip(model.models, model.columns, model.spaces, blend):
        here = [(int(jj), int(c)) for jj, c in enumerate(cols) if int(c) in where]
        if not here:
            continue
        if sub.centres.shape[0] != m:
            raise ValueError(f"carried_shares: the model has {sub.centres.shape[0]} centres for {m} training states")
        logs = np.asarray(sub.log_output, dtype=bool)
        # the weight of each hour: its damage for a log output, 1 where positive for a linear one
        w = np.column_stack([p[:, c] if logs[jj] else (p[:, c] > 0).astype(float) for jj, c in here])
        xs = space_points(name, x, model.thrust)
        sel = [jj for jj, _ in here]
        if model.method == "gp":
            g = gp.training_weights(sub, xs, w, outputs=sel, chunk_rows=chunk_rows)
        else:
            xts = space_points(name, xt, model.thrust)
            g = rbf.training_weights(sub, xs, w, outputs=sel, train_points=xts, chunk_rows=chunk_rows)
        for k, (jj, c) in enumerate(here):
            gi = wts[jj] * (g[:, k] if logs[jj] else g[:, k] * yt[:, c])  # a blend's sum moves by each part's
            s = p[:, c].sum()
            share = gi / s if s > 0 else np.full(m, np.nan)
            out[:, where[c]] = out[:, where[c]] + share if seen[where[c]] else share
            seen[where[c]] = True
    return out


def records_sum_cv(shares: npt.ArrayLike, records: npt.ArrayLike | None = None) -> np.ndarray:
    """The relative seed sd of a reconstructed sum per unit seed CV of one record: ``|G / sqrt(n)| / S``.

    Parameters
    ----------
    shares : array_like, shape (m, k)
        :func:`carried_shares`.
    records : array_like, shape (m,), optional
        The simulated records averaged in each training value (seed replicates; default 1).

    Returns
    -------
    numpy.ndarray, shape (k,)
        Times the seed CV ``c`` of one hour's damage: the sum's relative sd from its training records.
    """
    g = np.asarray(shares, dtype=float)
    n = np.ones(g.shape[0]) if records is None else np.asarray(records, dtype=float)
    if n.shape != (g.shape[0],) or np.any(~(n >= 1)):
        raise ValueError(f"records_sum_cv: records must be >= 1, one per training state ({g.shape[0]}); got {n!r}")
    return np.sqrt(np.sum(g * g / n[:, None], axis=0))
