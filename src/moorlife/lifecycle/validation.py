"""The agreement of rebuilt and simulated values on the validation states, and its sampling precision."""

from __future__ import annotations

import warnings

import numpy as np
import numpy.typing as npt

__all__ = ["R_INTERVAL_LEVEL", "pearson_r", "validation_metrics", "validation_r_interval"]


def validation_metrics(predicted: npt.ArrayLike, simulated: npt.ArrayLike) -> dict[str, np.ndarray]:
    """Per-output agreement of rebuilt and simulated values (paper Figs. 10-13).

    Parameters
    ----------
    predicted, simulated : array_like, shape (n, k)

    Returns
    -------
    dict
        ``r`` (Pearson correlation), ``rmse``, ``bias`` (mean of predicted - simulated),
        ``nrmse`` (RMSE / standard deviation of simulated), ``slope`` and ``intercept``
        of the least-squares line simulated -> predicted, ``sum_error`` (relative error of
        the sum, the quantity that matters for life damage); each shape (k,).
    """
    p = np.atleast_2d(np.asarray(predicted, dtype=float).T).T
    s = np.atleast_2d(np.asarray(simulated, dtype=float).T).T
    if p.shape != s.shape:
        raise ValueError(f"predicted {p.shape} and simulated {s.shape} differ in shape")
    pc = p - p.mean(axis=0)
    sc = s - s.mean(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        r = (pc * sc).sum(axis=0) / np.sqrt((pc**2).sum(axis=0) * (sc**2).sum(axis=0))
        slope = (pc * sc).sum(axis=0) / (sc**2).sum(axis=0)
        rmse = np.sqrt(np.mean((p - s) ** 2, axis=0))
        nrmse = rmse / s.std(axis=0)
        sum_err = p.sum(axis=0) / s.sum(axis=0) - 1.0
    return {
        "r": r,
        "rmse": rmse,
        "bias": np.mean(p - s, axis=0),
        "nrmse": nrmse,
        "slope": slope,
        "intercept": p.mean(axis=0) - slope * s.mean(axis=0),
        "sum_error": sum_err,
    }


def pearson_r(a: np.ndarray, b: np.ndarray, axis: int = -1) -> np.ndarray:
    """Pearson r of ``a`` and ``b`` along ``axis``, every other axis kept (resamples, outputs);
    NaN where either is constant. The ``r`` of :func:`validation_metrics` along axis 0."""
    ac = a - a.mean(axis=axis, keepdims=True)
    bc = b - b.mean(axis=axis, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        return (ac * bc).sum(axis=axis) / np.sqrt((ac * ac).sum(axis=axis) * (bc * bc).sum(axis=axis))


#: Resamples, confidence level and seed of :func:`validation_r_interval`.
R_INTERVAL_RESAMPLES = 2000
R_INTERVAL_LEVEL = 0.90
R_INTERVAL_SEED = 0


def validation_r_interval(
    predicted: npt.ArrayLike,
    simulated: npt.ArrayLike,
    *,
    level: float = R_INTERVAL_LEVEL,
    n_resamples: int = R_INTERVAL_RESAMPLES,
    seed: int = R_INTERVAL_SEED,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The sampling precision of each output's validation r: its bootstrap interval over the states.

    The validation states are a sample of the hindcast's hours, and a light line's r rests on its
    few largest states, so ``r`` from 225 states carries a sampling scatter. The states are
    resampled in pairs (predicted with simulated, every output with the same draws;
    :func:`scipy.stats.bootstrap`, ``paired=True``), and the bias-corrected and accelerated (BCa)
    interval of the Pearson r is returned with the bootstrap standard error. Deterministic: the
    draws come from ``seed`` alone.

    Parameters
    ----------
    predicted, simulated : array_like, shape (n, k)
    level : float
        Confidence level of the two-sided interval.
    n_resamples : int
    seed : int

    Returns
    -------
    low, high, standard_error : numpy.ndarray, shape (k,)
        NaN for an output whose simulated or predicted values are constant (r undefined).
    """
    from scipy.stats import DegenerateDataWarning, bootstrap

    p = np.atleast_2d(np.asarray(predicted, dtype=float).T).T
    s = np.atleast_2d(np.asarray(simulated, dtype=float).T).T
    if p.shape != s.shape:
        raise ValueError(f"predicted {p.shape} and simulated {s.shape} differ in shape")
    if not 0.0 < level < 1.0:
        raise ValueError(f"validation_r_interval: level must be in (0, 1), got {level}")
    out = np.full((3, p.shape[1]), np.nan)
    ok = (np.ptp(p, axis=0) > 0) & (np.ptp(s, axis=0) > 0) & np.isfinite(p).all(axis=0) & np.isfinite(s).all(axis=0)
    if p.shape[0] < 3 or not ok.any():
        return out[0], out[1], out[2]

    with warnings.catch_warnings():  # a degenerate resample distribution (r = 1 exactly): handled below
        warnings.simplefilter("ignore", DegenerateDataWarning)
        warnings.simplefilter("ignore", RuntimeWarning)
        res = bootstrap(
            (p[:, ok].T, s[:, ok].T),
            pearson_r,
            paired=True,
            vectorized=True,
            n_resamples=n_resamples,
            confidence_level=level,
            method="BCa",
            axis=-1,
            rng=np.random.default_rng(seed),
        )
    out[:, ok] = res.confidence_interval.low, res.confidence_interval.high, res.standard_error
    flat = ok & ~np.isfinite(out[0])  # every resample the same r: the interval is that r
    out[0, flat] = out[1, flat] = pearson_r(p[:, flat].T, s[:, flat].T)
    return out[0], out[1], out[2]
