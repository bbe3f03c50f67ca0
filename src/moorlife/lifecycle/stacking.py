"""The weights of a blend of two interpolants by their leave-one-out predictions (``choose: stack``)."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = ["STACK_GRID", "stack_weights"]


#: The weights of the first candidate tried by :func:`stack_weights`, first to last (a tie keeps
#: the earlier): 1, 0.95, ..., 0.
STACK_GRID = np.linspace(1.0, 0.0, 21)


def stack_weights(
    values: npt.ArrayLike,
    loo_a: npt.ArrayLike,
    loo_b: npt.ArrayLike,
    log_output: npt.ArrayLike,
    grid: npt.ArrayLike = STACK_GRID,
    *,
    resamples: int = 0,
    seed: int = 0,
) -> tuple[np.ndarray, np.ndarray]:
    """Per output, the weight of two interpolants' blend with the smallest leave-one-out RMS error.

    Stacking (Breiman 1996, "Stacked regressions"): the blend ``w a + (1 - w) b`` of the two
    predictions, arithmetic for a linear output and geometric (``a**w b**(1 - w)``, arithmetic in
    ``log10``) for a ``log10`` one, scored in the output's own units on the leave-one-out
    predictions of the training states alone. ``w`` 1 or 0 is the choice of one candidate
    (``choose: per_output``), so the blend's leave-one-out error is never larger than it.

    With ``resamples`` N > 0 the weight is instead the mean, rounded to 0.01, of that choice over
    N bootstrap resamples of the training states (bootstrap model averaging, Buckland, Burnham
    and Augustin 1997): a preference of the leave-one-out that is within its own sampling
    scatter gives a mixed weight rather than one candidate whole. An output where some weight of
    the grid has no finite error on all states keeps the choice on all states.

    Parameters
    ----------
    values : array_like, shape (m, n_out)
        The training values (a ``log10`` output's non-positive values floored as for its fit).
    loo_a, loo_b : array_like, shape (m, n_out)
        Each candidate's leave-one-out prediction of every training state, back-transformed
        (positive for a ``log10`` output).
    log_output : array_like of bool, shape (n_out,)
    grid : array_like
        The weights of ``a`` tried, in order; the first on a tie.
    resamples : int
        Bootstrap resamples of the training states (0: none).
    seed : int
        Seed of the resamples.

    Returns
    -------
    weight : numpy.ndarray, shape (n_out,)
        The weight of ``a``.
    rmse : numpy.ndarray, shape (n_out,)
        The blend's leave-one-out RMS error in units at that weight, on all training states (inf
        where no weight gives a finite one).
    """
    y = np.asarray(values, dtype=float)
    a, b = np.asarray(loo_a, dtype=float), np.asarray(loo_b, dtype=float)
    logs = np.asarray(log_output, dtype=bool)
    w = np.asarray(grid, dtype=float)
    if y.shape != a.shape or y.shape != b.shape or logs.shape != y.shape[1:]:
        raise ValueError(f"stack_weights: values {y.shape}, loo_a {a.shape}, loo_b {b.shape}, log_output {logs.shape}")
    if resamples < 0:
        raise ValueError(f"stack_weights: resamples must be >= 0, got {resamples}")
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        ta, tb = a.copy(), b.copy()
        ta[:, logs], tb[:, logs] = np.log10(a[:, logs]), np.log10(b[:, logs])
    tried = np.repeat(w[:, None], y.shape[1], axis=1)  # every grid weight for every output
    rmse = _blend_rmse(y, ta, tb, logs, tried)
    best = np.argmin(rmse, axis=0)
    weight, score = w[best], rmse[best, np.arange(y.shape[1])]
    if resamples:
        bag = np.isfinite(rmse).all(axis=0)
        rng = np.random.default_rng(seed)
        chosen = np.empty((resamples, y.shape[1]))
        for k in range(resamples):
            i = rng.integers(0, y.shape[0], y.shape[0])
            chosen[k] = w[np.argmin(_blend_rmse(y[i], ta[i], tb[i], logs, tried), axis=0)]
        weight = np.where(bag, np.round(chosen.mean(axis=0), 2), weight)
        score = np.where(bag, _blend_rmse(y, ta, tb, logs, weight[None, :])[0], score)
    return weight, score


def _blend_rmse(y: np.ndarray, ta: np.ndarray, tb: np.ndarray, logs: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """The RMS error in units of the blends ``weights`` (k, n_out) of ``ta`` and ``tb`` (interpolated
    values; ``log10`` for the ``logs`` columns): shape (k, n_out), inf where not finite."""
    rmse = np.empty(weights.shape)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for k, wk in enumerate(weights):
            t = np.where((wk > 0.0) & (wk < 1.0), wk * ta + (1.0 - wk) * tb, np.where(wk >= 1.0, ta, tb))
            p = t.copy()
            p[:, logs] = 10.0 ** t[:, logs]
            e = y - p
            rmse[k] = np.sqrt(np.mean(e * e, axis=0))
    return np.where(np.isfinite(rmse), rmse, np.inf)
