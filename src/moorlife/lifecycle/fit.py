"""The RBF of every output column (:func:`fit_outputs`) and its validation metrics."""

from __future__ import annotations

import logging
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from moorlife import rbf
from moorlife.lifecycle.outputs import _label
from moorlife.lifecycle.settings import RBFSettings
from moorlife.space import direction_mask

__all__ = ["validation_metrics", "fit_outputs"]

log = logging.getLogger("moorlife.lifecycle")


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
        nrmse = np.sqrt(np.mean((p - s) ** 2, axis=0)) / s.std(axis=0)
        sum_err = p.sum(axis=0) / s.sum(axis=0) - 1.0
    return {
        "r": r,
        "rmse": np.sqrt(np.mean((p - s) ** 2, axis=0)),
        "bias": np.mean(p - s, axis=0),
        "nrmse": nrmse,
        "slope": slope,
        "intercept": p.mean(axis=0) - slope * s.mean(axis=0),
        "sum_error": sum_err,
    }


def fit_outputs(
    points: np.ndarray,
    values: np.ndarray,
    cols: Sequence[tuple[str, str | None]],
    settings: RBFSettings,
    *,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
    log_damage: bool | None = None,
) -> rbf.RBFModel:
    """Fit the RBF of every output column with the configured shape rule.

    Parameters
    ----------
    points : numpy.ndarray, shape (m, 5)
        Training sea states in ``names.METOCEAN_VARS`` order.
    values : numpy.ndarray, shape (m, k)
    cols : sequence of (name, line)
    settings : RBFSettings
    lo, span : array_like (5,), optional
        Normalisation of the selection (``cases.zarr`` attributes ``norm_lo``/``norm_span``).
    log_damage : bool, optional
        Overrides ``settings.log_damage`` (used to compare both transforms).

    Returns
    -------
    moorlife.rbf.RBFModel
    """
    is_dmg = np.array([c[0].startswith("damage") for c in cols])
    use_log = settings.log_damage if log_damage is None else log_damage
    logs = is_dmg & bool(use_log)
    if logs.any():
        values = values.copy()
        for j in np.flatnonzero(logs):
            bad = ~(values[:, j] > 0)
            if bad.any():  # a calm state with no counted cycle: floor at the smallest positive damage
                pos = values[values[:, j] > 0, j]
                floor = pos.min() if pos.size else 1e-30
                log.warning(
                    "%s: %d non-positive damage value(s) floored at %.3g for the log transform",
                    _label(cols[j]),
                    int(bad.sum()),
                    floor,
                )
                values[bad, j] = floor
    mask = direction_mask()
    common = dict(is_direction=mask, log_output=logs, smoothing=settings.smoothing, lo=lo, span=span)
    if settings.shape_mode == "fixed":
        q = np.array(
            [
                settings.fixed_damage
                if c[0].startswith("damage")
                else settings.fixed_tension
                if c[0].startswith("tension")
                else settings.fixed_other
                for c in cols
            ]
        )
        return rbf.fit_rbf(points, values, shape=q, **common)
    grid = rbf.shape_grid(settings.grid_min, settings.grid_max, settings.grid_n)
    return rbf.fit_rbf(points, values, shapes=grid, share_tol=settings.share_tol, **common)
