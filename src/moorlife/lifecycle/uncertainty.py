"""Where the reconstruction is least certain, the states to simulate next, and the life band."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from moorlife import gp, rbf
from moorlife.lifecycle.spaces import space_points

__all__ = [
    "error_indicator",
    "suggest_states",
    "life_band",
    "sum_seed_cv",
    "band_sigma_of",
    "coverage_needed",
    "calibrate_coverage",
]


def error_indicator(
    model: rbf.RBFModel,
    points: npt.ArrayLike,
    scale: npt.ArrayLike,
    loo: npt.ArrayLike | None = None,
    population: bool = False,
) -> tuple[np.ndarray, np.ndarray]:
    """Where the reconstruction is least certain: nearest training state's LOO error x distance.

    ``indicator = max_k |e_k(nearest)| / scale_k x (d_nearest / d_typical)``, with ``e`` the
    leave-one-out residuals of the training states, ``scale`` a per-output normaliser and
    ``d_typical`` the median nearest-neighbour spacing of the training states. High where the
    surface varies fast (large LOO error) and training states are sparse.

    The residuals should be in each output's own units (``loo``, from
    :func:`moorlife.lifecycle.loo_errors_in_units`) with ``scale`` the standard deviation of the
    training values: then a damage error counts by its size in damage, which is what the
    life-cycle sum and the per-hour agreement weigh. In ``log10`` units (the model's own
    residuals, the default when ``loo`` is omitted) every calm state with a tiny, badly
    interpolated damage would look as uncertain as the states that carry the damage.

    A Gaussian-process :class:`moorlife.lifecycle.Reconstruction` with ``indicator == "sd"``
    (``lifecycle.rbf.gp.indicator``) gives instead ``max_k s_k(x) / scale_k``, ``s_k`` the
    latent posterior standard deviation of output ``k`` (transformed units; the noise left
    out, as more simulations cannot reduce it): one triangular solve per hour and output.

    Parameters
    ----------
    model : moorlife.rbf.RBFModel or moorlife.lifecycle.Reconstruction
        Its ``centres``, ``space`` and (when ``loo`` is omitted) ``loo_error``.
    points : array_like, shape (n, 5)
    scale : array_like, shape (k,)
    loo : array_like, shape (m, k), optional
        Leave-one-out residuals of the training states (default ``model.loo_error``).
    population : bool
        Weigh each training state's error by the hours of ``points`` whose nearest training
        state it is (over their mean): the error mass of its cell, which is what the
        life-cycle sum and the per-hour agreement over the hindcast feel. Without it the
        largest errors sit at the rare extremes of the cloud, where few hours are.

    Returns
    -------
    indicator : numpy.ndarray, shape (n,)
    distance : numpy.ndarray, shape (n,)
        Normalised distance to the nearest training state.
    """
    dist, idx = rbf.nearest_centre(model, points)
    s = np.asarray(scale, dtype=float)
    s = np.where(s > 0, s, 1.0)
    if getattr(model, "indicator", "loo") == "sd":
        worst = np.zeros(dist.shape)
        for m, cols, name in zip(model.models, model.columns, model.spaces):
            x = space_points(name, points, model.thrust)
            _, var = gp.predict_latent(m, x, variance_of=np.ones(cols.size, bool))
            worst = np.maximum(worst, np.max(np.sqrt(var) / s[cols], axis=1))
        return worst, dist
    typical = _typical_spacing(model)
    e = np.asarray(model.loo_error if loo is None else loo, dtype=float)
    worst = np.max(np.abs(e) / s, axis=1)  # (m,)
    if population:
        counts = np.bincount(idx, minlength=worst.size).astype(float)
        worst = worst * counts / counts.mean()
    return worst[idx] * dist / typical, dist


def _typical_spacing(model: rbf.RBFModel) -> float:
    z = model.centres
    d2 = rbf.squared_distances(z, z, model.space.is_direction)
    np.fill_diagonal(d2, np.inf)
    t = float(np.median(np.sqrt(d2.min(axis=1))))
    return t if t > 0 else 1.0


def suggest_states(
    model: rbf.RBFModel,
    points: npt.ArrayLike,
    indicator: npt.ArrayLike,
    n: int,
    distance: npt.ArrayLike | None = None,
) -> np.ndarray:
    """Adaptive selection: the ``n`` hours to simulate next, greedily, most uncertain first.

    Each pick maximises ``indicator x min(1, d_set / d_nearest)`` where ``d_set`` is the
    distance to the training states and the picks so far, so that one uncertain region does
    not take every pick (the running-minimum update of maximum dissimilarity).

    Parameters
    ----------
    model : moorlife.rbf.RBFModel
    points : array_like, shape (n_hours, 5)
    indicator : array_like, shape (n_hours,)
        From :func:`error_indicator`.
    n : int
    distance : array_like, shape (n_hours,), optional
        Distance to the nearest training state (from :func:`error_indicator`); computed if omitted.

    Returns
    -------
    numpy.ndarray of int64, shape (n,)
        Row indices into ``points``, in pick order (ties: lowest index).
    """
    z = rbf.normalise(points, model.space)
    ind = np.asarray(indicator, dtype=float)
    d0 = rbf.nearest_centre(model, points)[0] if distance is None else np.asarray(distance, dtype=float)
    dset = d0.copy()
    picks: list[int] = []
    with np.errstate(invalid="ignore", divide="ignore"):
        for _ in range(min(int(n), z.shape[0])):
            score = ind * np.where(d0 > 0, np.minimum(1.0, dset / d0), 0.0)
            k = int(np.argmax(score))
            if score[k] <= 0:
                break
            picks.append(k)
            dk = np.sqrt(rbf.squared_distances(z, z[k : k + 1], model.space.is_direction)[:, 0])
            dset = np.minimum(dset, dk)
    return np.asarray(picks, dtype=np.int64)


def life_band(life_years: npt.ArrayLike, rel_sigma: npt.ArrayLike, k: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """Band on fatigue life from a relative damage uncertainty.

    ``life / (1 + k sigma)`` to ``life / max(1 - k sigma, 0)`` (infinite when ``k sigma >= 1``).

    Parameters
    ----------
    life_years : array_like
    rel_sigma : array_like
        Relative standard uncertainty of the damage, e.g. ``sqrt(cv_seed^2 + err_rbf^2)``.
    k : float
        Coverage factor (1: one standard deviation).
    """
    life = np.asarray(life_years, dtype=float)
    s = k * np.asarray(rel_sigma, dtype=float)
    with np.errstate(divide="ignore"):
        hi = np.where(s < 1, life / np.where(s < 1, 1 - s, 1.0), np.inf)
    return life / (1 + s), hi


def sum_seed_cv(hourly: npt.ArrayLike, hour_cv: float, axis: int = 0) -> np.ndarray:
    """Seed scatter (relative, one sd) of a sum of hourly damages, from the seed CV of one hour.

    Each hour's damage is one realisation of its sea state, with an independent seed error of
    relative size ``hour_cv`` (``var(x_h) = c^2 x_h^2``, the model of
    :func:`moorlife.truth.noise_floor`). The sum's relative sd is then
    ``c sqrt(sum x_h^2) / sum x_h``: ``c`` for one hour, ``c / sqrt(n)`` for ``n`` equal hours,
    and in between for a sum that a few storm hours dominate.

    Parameters
    ----------
    hourly : array_like
        Hourly damages (>= 0) along ``axis``.
    hour_cv : float
        Seed CV of one hour's damage (the seed sensitivity).
    axis : int

    Returns
    -------
    numpy.ndarray
        The relative sd of the sum (0 where the sum is 0).
    """
    x = np.clip(np.asarray(hourly, dtype=float), 0.0, None)
    total = x.sum(axis=axis)
    root = np.sqrt(np.sum(x * x, axis=axis))
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(total > 0, float(hour_cv) * root / np.where(total > 0, total, 1.0), 0.0)


def band_sigma_of(seed_sum_cv: npt.ArrayLike, validation_error: npt.ArrayLike) -> np.ndarray:
    """Relative sd of a damage sum: ``hypot(seed scatter of the sum, |validation sum error|)``.

    The seed term is :func:`sum_seed_cv` (or a measured one); the reconstruction term is the
    relative error of the validation states' damage sum, the fit's own error estimate.
    """
    return np.hypot(np.asarray(seed_sum_cv, dtype=float), np.abs(np.asarray(validation_error, dtype=float)))


def coverage_needed(error: npt.ArrayLike, sigma: npt.ArrayLike) -> np.ndarray:
    """The coverage factor a band of sd ``sigma`` needs to hold a measured relative ``error``.

    ``|error| / sigma`` (both relative, or both in %): the truth lies inside the band
    ``k sigma`` exactly when ``k`` is at least this.
    """
    e, s = np.abs(np.asarray(error, dtype=float)), np.asarray(sigma, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(s > 0, e / np.where(s > 0, s, 1.0), np.where(e > 0, np.inf, 0.0))


def calibrate_coverage(needed: npt.ArrayLike, step: float = 0.05) -> float:
    """The coverage factor calibrated on measured cases: the smallest that holds every one.

    Parameters
    ----------
    needed : array_like
        :func:`coverage_needed` of each case measured against a truth (NaN: not measured).
    step : float
        Rounded up to a multiple of ``step``.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        With no finite case.
    """
    k = np.asarray(needed, dtype=float).ravel()
    k = k[np.isfinite(k)]
    if k.size == 0:
        raise ValueError("calibrate_coverage: no measured case (every coverage_needed is NaN or infinite)")
    return float(np.ceil(k.max() / step - 1e-9) * step)
