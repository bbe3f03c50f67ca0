"""Ground truth: every hour of a window simulated, and the life-cycle method measured against it.

The truth target simulates every hindcast hour of a configured window (``truth.window``, every
``truth.stride``-th hour) with the simulate stage as it is, each hour with random phases of its
own stream (``"truth"``, case id = the hour's position in the hindcast), and a second seed
(stream ``"truth_seed2"``) on an evenly spaced subset of ``truth.n_second_seed`` hours. This
module holds the arithmetic of that comparison, numpy in and numpy out:

* the hours of the window (:func:`window_indices`) and the check of the ``truth`` keys against
  the study period (:func:`check_window`), run before any simulation;
* the second-seed subset (:func:`second_seed_subset`);
* the per-hour agreement of the reconstruction with the truth (:func:`hourly_agreement`:
  Pearson r, RMSE, bias = mean of reconstruction - truth);
* the 35-bin method applied to the window's own hours (:func:`hour_bins`,
  :func:`bin_damage_per_hour`, :func:`window_bin_damage`): each hour takes the hourly damage of
  the scatter-matrix bin it falls in, with the bin rule of :func:`moorlife.selection.scatter_matrix`;
* signed errors in % (:func:`signed_error_pct`) and the seed noise floor
  (:func:`noise_floor`).

:func:`compare_window` is the xarray adapter used by :mod:`moorlife.stages.truth`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import numpy.typing as npt
import pandas as pd
import xarray as xr

from moorlife import lifecycle, names, selection

__all__ = [
    "TRUTH_STREAM",
    "SEED2_STREAM",
    "check_window",
    "window_indices",
    "second_seed_subset",
    "strata_weights",
    "hourly_agreement",
    "hour_bins",
    "bin_damage_per_hour",
    "window_bin_damage",
    "signed_error_pct",
    "noise_floor",
    "WINDOW_DAMAGE_VARS",
    "compare_window",
]

#: Random stream of the truth hours (``moorlife.conventions.case_rng``): independent of the
#: ``"case"`` stream of the training and validation states and of the ``"bin"`` stream.
TRUTH_STREAM = "truth"
#: Random stream of the second seed of the noise-floor subset.
SEED2_STREAM = "truth_seed2"
_HOUR = np.timedelta64(1, "h")


def _timestamp(value: object, key: str, source: str) -> pd.Timestamp:
    try:
        t = pd.Timestamp(str(value))
    except (ValueError, TypeError) as exc:
        raise ValueError(f"{source}: config key '{key}' = {value!r} is not an ISO 8601 time ({exc})") from None
    if t is pd.NaT:
        raise ValueError(f"{source}: config key '{key}' = {value!r} is not an ISO 8601 time")
    return t


def check_window(
    start: object,
    end: object,
    stride: int,
    n_second_seed: int,
    *,
    hindcast_start: object,
    hindcast_end: object,
    source: str = "config",
    second_seed_storm: int = 0,
) -> int:
    """Check the ``truth`` keys against the study period; return the number of truth hours.

    Parameters
    ----------
    start, end : str
        ``truth.window.start`` / ``truth.window.end`` (ISO 8601, UTC, both inclusive).
    stride : int
        ``truth.stride``: every ``stride``-th hour of the window is simulated.
    n_second_seed : int
        ``truth.n_second_seed``: hours simulated with a second seed.
    second_seed_storm : int
        ``truth.second_seed_storm``: how many of them are the storm stratum (below ``n_second_seed``).
    hindcast_start, hindcast_end : str
        ``hindcast.start`` / ``hindcast.end``, the hourly study period.
    source : str
        Where the configuration came from, quoted in the message.

    Returns
    -------
    int
        The hours of the hourly study period inside the window, every ``stride``-th.

    Raises
    ------
    ValueError
        Naming the key and its value: a window outside the hindcast, an empty window (end
        before start, or no whole hour inside), a stride below 1, more second-seed hours
        than truth hours, or a storm stratum not below the second-seed hours.
    """
    if isinstance(stride, bool) or int(stride) != stride or int(stride) < 1:
        raise ValueError(f"{source}: config key 'truth.stride' = {stride!r} is invalid: it must be an integer >= 1")
    t0 = _timestamp(start, "truth.window.start", source)
    t1 = _timestamp(end, "truth.window.end", source)
    h0 = _timestamp(hindcast_start, "hindcast.start", source)
    h1 = _timestamp(hindcast_end, "hindcast.end", source)
    if t1 < t0:
        raise ValueError(
            f"{source}: config key 'truth.window.end' = {end!r} is before truth.window.start = "
            f"{start!r}: the truth window is empty"
        )
    if t0 < h0 or t0 > h1:
        raise ValueError(
            f"{source}: config key 'truth.window.start' = {start!r} is outside the hindcast "
            f"{hindcast_start} .. {hindcast_end} (hindcast.start/end)"
        )
    if t1 > h1:
        raise ValueError(
            f"{source}: config key 'truth.window.end' = {end!r} is outside the hindcast "
            f"{hindcast_start} .. {hindcast_end} (hindcast.start/end)"
        )
    hours = h0.to_datetime64() + np.arange(int((h1 - h0) / pd.Timedelta(hours=1)) + 1) * _HOUR
    n = window_indices(hours, t0.to_datetime64(), t1.to_datetime64(), int(stride), source=source).size
    n2 = int(n_second_seed)
    if n2 > n:
        raise ValueError(
            f"{source}: config key 'truth.n_second_seed' = {n_second_seed!r} is larger than the "
            f"{n} hours of the truth window"
        )
    storm = second_seed_storm
    if isinstance(storm, bool) or int(storm) != storm or not 0 <= int(storm) < n2:
        raise ValueError(
            f"{source}: config key 'truth.second_seed_storm' = {storm!r} is invalid: it must be an integer "
            f"from 0 to truth.n_second_seed - 1 = {n2 - 1} (the default, 100, needs n_second_seed above 100)"
        )
    return n


def window_indices(
    times: npt.ArrayLike, start: np.datetime64, end: np.datetime64, stride: int = 1, *, source: str = "hindcast"
) -> np.ndarray:
    """Positions along the hindcast's ``time`` of the truth hours.

    Parameters
    ----------
    times : array_like of datetime64, shape (N,)
        The hindcast's hourly time stamps, increasing.
    start, end : numpy.datetime64
        The window, both ends inclusive.
    stride : int
        Every ``stride``-th hour of the window, from its first.

    Returns
    -------
    numpy.ndarray of int64
        Increasing positions into ``times``.

    Raises
    ------
    ValueError
        If the stride is below 1 or no hour of ``times`` lies in the window.
    """
    if int(stride) < 1:
        raise ValueError(f"config key 'truth.stride' = {stride!r} is invalid: it must be >= 1")
    t = np.asarray(times, dtype="datetime64[ns]")
    inside = np.flatnonzero((t >= np.datetime64(start, "ns")) & (t <= np.datetime64(end, "ns")))
    if inside.size == 0:
        raise ValueError(
            f"{source}: no hour of the hindcast lies in the truth window {start} .. {end} (truth.window.start/end)"
        )
    return inside[:: int(stride)].astype(np.int64)


def second_seed_subset(n: int, k: int, *, hs: npt.ArrayLike | None = None, storm: int = 0) -> np.ndarray:
    """Positions in ``range(n)`` of the second-seed hours: ``k`` evenly spaced, or a storm stratum
    and evenly spaced calm hours.

    With ``storm = 0``: position ``i`` is ``round(i (n - 1) / (k - 1))`` in exact integer
    arithmetic (halves up), first and last included, so the subset depends only on ``n`` and ``k``.
    With ``storm > 0``: the ``storm`` hours of largest ``hs`` (ties: the earlier hour), plus
    ``k - storm`` evenly spaced (the rule above) among the other ``n - storm`` hours; sorted.
    A damage sum's seed variance sits in the storm hours, which an evenly spaced subset rarely
    holds (``validation/reconstruction.md`` section 16); :func:`strata_weights` gives the
    window hours each subset hour stands for.

    Raises
    ------
    ValueError
        If ``k`` is not in ``1..n``, ``storm`` not in ``0..k - 1``, or ``hs`` is missing or not
        of length ``n`` when ``storm > 0``.
    """
    n, k, storm = int(n), int(k), int(storm)
    if not 1 <= k <= n:
        raise ValueError(f"config key 'truth.n_second_seed' = {k} must be between 1 and the {n} truth hours")
    if not 0 <= storm < k:
        raise ValueError(
            f"config key 'truth.second_seed_storm' = {storm} must be between 0 and truth.n_second_seed - 1 = {k - 1}"
        )
    if storm == 0:
        if k == 1:
            return np.zeros(1, dtype=np.int64)
        i = np.arange(k, dtype=np.int64)
        return (2 * i * (n - 1) + (k - 1)) // (2 * (k - 1))
    top = _storm_hours(n, hs, storm)
    rest = np.setdiff1d(np.arange(n, dtype=np.int64), top)
    return np.sort(np.concatenate([top, rest[second_seed_subset(rest.size, k - storm)]])).astype(np.int64)


def _storm_hours(n: int, hs: npt.ArrayLike | None, storm: int) -> np.ndarray:
    """The ``storm`` positions of largest ``hs`` (ties: the earlier hour), sorted."""
    h = None if hs is None else np.asarray(hs, dtype=float).reshape(-1)
    if h is None or h.size != n:
        raise ValueError(f"the storm stratum of the second seed needs the Hs of the {n} truth hours")
    return np.sort(np.argsort(-h, kind="stable")[:storm])


def strata_weights(n: int, pick: npt.ArrayLike, *, hs: npt.ArrayLike, storm: int) -> np.ndarray:
    """The window hours each second-seed hour stands for: 1 for a storm hour, ``(n - storm) /
    (k - storm)`` for a calm one (``pick`` from :func:`second_seed_subset` with the same ``hs`` and
    ``storm``; all equal to ``n / k`` with ``storm = 0``). They sum to ``n``.

    Raises
    ------
    ValueError
        If ``pick`` is not the subset :func:`second_seed_subset` draws with these settings (the
        second seed was drawn with another ``truth.second_seed_storm`` or ``truth.n_second_seed``).
    """
    pick = np.asarray(pick, dtype=np.int64)
    k = pick.size
    want = second_seed_subset(n, k, hs=hs, storm=storm)
    if not np.array_equal(np.sort(pick), want):
        raise ValueError(
            f"truth_seed2.zarr's {k} hours are not the subset of truth.n_second_seed = {k}, "
            f"truth.second_seed_storm = {storm}: rebuild it (results/truth/hours_seed2.zarr and results/{{ms}}/truth_seed2.zarr)"
        )
    w = np.full(k, (n - storm) / (k - storm))
    if storm:
        w[np.isin(pick, _storm_hours(n, hs, storm))] = 1.0
    return w


def hourly_agreement(truth: npt.ArrayLike, reconstruction: npt.ArrayLike) -> dict[str, np.ndarray]:
    """Per-output agreement of the reconstruction with the simulated truth.

    Parameters
    ----------
    truth, reconstruction : array_like, shape (n, k)
        ``n`` hours, ``k`` outputs.

    Returns
    -------
    dict
        ``r`` (Pearson correlation), ``rmse``, ``bias`` (mean of reconstruction - truth),
        ``sum_error`` (reconstruction sum / truth sum - 1); each shape ``(k,)``. The same
        definitions as the validation metrics of :func:`moorlife.lifecycle.validation_metrics`.
    """
    m = lifecycle.validation_metrics(reconstruction, truth)
    return {k: m[k] for k in ("r", "rmse", "bias", "sum_error")}


def hour_bins(
    hs: npt.ArrayLike,
    wind_speed: npt.ArrayLike,
    tp: npt.ArrayLike,
    *,
    hs_edges: Sequence[float],
    wind_edges: Sequence[float],
    tp_edges: Sequence[float],
    bin_classes: npt.ArrayLike,
) -> np.ndarray:
    """The scatter-matrix bin of each hour.

    Parameters
    ----------
    hs, wind_speed, tp : array_like, shape (n,)
        The hours' sea states (m, m/s, s).
    hs_edges, wind_edges, tp_edges : sequence of float
        The lower class edges of ``results/selection/discrete.zarr`` (its attributes).
    bin_classes : array_like of int, shape (K, 3)
        The (Hs, W, Tp) class indices of the K non-empty bins (``hs_class``, ``wind_class``,
        ``tp_class`` of ``discrete.zarr``).

    Returns
    -------
    numpy.ndarray of int64, shape (n,)
        Position of each hour's bin in ``bin_classes``. Classes follow
        :func:`moorlife.selection.scatter_matrix`: ``edges[k] <= value < edges[k + 1]``,
        the last class open.

    Raises
    ------
    ValueError
        If an hour falls in a class that is not one of the bins (it was not in the hindcast
        the bins were made from), or below the first edge.
    """
    e = [
        selection.check_edges(v, k)
        for v, k in ((hs_edges, "hs_edges"), (wind_edges, "wind_edges"), (tp_edges, "tp_edges"))
    ]
    cls = [
        selection.classify(np.asarray(a, dtype=float).reshape(-1), ee, name)
        for a, ee, name in ((hs, e[0], "hs"), (wind_speed, e[1], "wind_speed"), (tp, e[2], "tp"))
    ]
    shape = tuple(ee.size for ee in e)
    flat = np.ravel_multi_index(tuple(cls), shape)
    bc = np.asarray(bin_classes, dtype=np.int64).reshape(-1, 3)
    lookup = np.full(int(np.prod(shape)), -1, dtype=np.int64)
    lookup[np.ravel_multi_index(tuple(bc.T), shape)] = np.arange(bc.shape[0])
    out = lookup[flat]
    if (out < 0).any():
        i = int(np.flatnonzero(out < 0)[0])
        raise ValueError(
            f"hour {i} (hs {float(np.ravel(hs)[i])!r}, wind_speed {float(np.ravel(wind_speed)[i])!r}, "
            f"tp {float(np.ravel(tp)[i])!r}) falls in a class with no bin of the scatter matrix"
        )
    return out


def bin_damage_per_hour(bins: npt.ArrayLike, bin_damage: npt.ArrayLike) -> np.ndarray:
    """The hourly damage the 35-bin method gives each hour: its bin's, shape ``(n, ...)``."""
    return np.asarray(bin_damage, dtype=float)[np.asarray(bins, dtype=np.int64)]


def window_bin_damage(bins: npt.ArrayLike, bin_damage: npt.ArrayLike) -> np.ndarray:
    """The 35-bin damage of a window: ``sum_b (window hours in bin b) x hourly damage of bin b``.

    Parameters
    ----------
    bins : array_like of int, shape (n,)
        The bin of each window hour (:func:`hour_bins`).
    bin_damage : array_like, shape (K, ...)
        Hourly damage of each bin's representative state (``results/{ms}/discrete.zarr``).

    Returns
    -------
    numpy.ndarray, shape (...)
    """
    d = np.asarray(bin_damage, dtype=float)
    hours = np.bincount(np.asarray(bins, dtype=np.int64), minlength=d.shape[0]).astype(float)
    return np.tensordot(hours, d, axes=(0, 0))


#: The window-damage variables of :func:`compare_window`, per curve and line, in table order.
WINDOW_DAMAGE_VARS: tuple[str, ...] = (
    "truth_damage",
    "reconstruction_damage",
    "bins_damage",
    "reconstruction_error_pct",
    "bins_error_pct",
    "seed_sum_std_pct",
    "seed_sum_difference_pct",
    "records_sum_std_pct",
    "bias_z",
    "band_sigma_pct",
    "coverage_needed",
)


def signed_error_pct(estimate: npt.ArrayLike, truth: npt.ArrayLike) -> np.ndarray:
    """``100 (estimate - truth) / truth``: > 0 when the estimate overestimates the truth."""
    t = np.asarray(truth, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return 100.0 * (np.asarray(estimate, dtype=float) - t) / t


def noise_floor(
    seed1: npt.ArrayLike,
    seed2: npt.ArrayLike,
    n_window: int | None = None,
    window: npt.ArrayLike | None = None,
    weights: npt.ArrayLike | None = None,
) -> dict[str, np.ndarray]:
    """The noise floor of one realisation per hour, from two seeds of the same hours.

    Parameters
    ----------
    seed1, seed2 : array_like, shape (m, k)
        The same ``m`` hours simulated with two independent random streams.
    n_window : int, optional
        Hours of the whole window; default ``m``.
    window : array_like, shape (n_window, k), optional
        The truth of every window hour. With it the seed scatter of the window's sum follows
        the window's own values (below); without it, the subset's mean variance.
    weights : array_like, shape (m,), optional
        The window hours each subset hour stands for (:func:`strata_weights`), for a stratified
        subset; needs ``window``. Then ``r`` and the ceiling are the window's (below).

    Returns
    -------
    dict
        ``r`` (k,): correlation of the two seeds; ``r_ceiling`` (k,): ``sqrt(r)``, the
        per-hour r of a perfect reconstruction against one realisation per hour (below);
        ``sum_difference_pct`` (k,):
        ``100 (sum seed2 - sum seed1) / sum seed1`` over the subset; ``sum_std_pct`` (k,):
        the seed scatter (one standard deviation) of a sum over the window, in %; ``hour_cv``
        (k,): with ``window``, the relative seed sd ``c`` of one hour (below; NaN without it).

    Notes
    -----
    One realisation of an hour is ``x = s + e``: its expected value ``s`` (what a perfect
    reconstruction returns) plus a seed error ``e`` of zero mean, independent between seeds.
    Two seeds correlate at ``r = var(s) / (var(s) + E var(e))``, and ``s`` correlates with one
    realisation at ``cov(s, x) / sqrt(var(s) var(x)) = sqrt(r)``. So ``sqrt(r)``, not ``r``, is
    the ceiling of the per-hour r against the truth: a reconstruction may exceed ``r`` (it
    averages the noise of the training states out), never ``sqrt(r)`` but by sampling.

    Without ``window``: ``100 sqrt(n mean((x1 - x2)^2 / 2)) / (n mean(x1, x2))``, the subset's
    mean per-hour seed variance times the window's hours. That is right for outputs of even
    size; the damage is not: a year's damage sits in a few storm hours (in the MS2 truth year
    the 50 largest hours hold 37-50 % of it), which an evenly spaced subset of 200 hours
    rarely holds, so the subset's mean variance misses where the variance is. With ``window``
    the seed scatter is taken as relative, ``var(x_h) = c^2 x_h^2``, with ``c^2 = sum((x1 -
    x2)^2 / 2) / sum(((x1 + x2) / 2)^2)`` over the subset (each hour weighted by its size, as
    it weighs in a sum), and ``sum_std_pct = 100 c sqrt(sum_h x_h^2) / sum_h x_h`` over the
    window's truth ``x_h``.

    With ``weights`` ``w_i`` (a subset with a storm stratum): the window's mean seed variance is
    ``v = sum w (x1 - x2)^2 / 2 / sum w``, the two-seed correlation the window would show is
    ``r = 1 - v / var(x_h)`` (``var`` over the window's truth), the ceiling ``sqrt(r)``, and ``c^2``
    weights both of its sums by ``w``. An evenly spaced subset gives the ceiling of its own,
    mostly calm, hours; on MS6's year 1985 that read 0.999 where four records of every storm
    hour give 0.971.
    """
    a = np.atleast_2d(np.asarray(seed1, dtype=float).T).T
    b = np.atleast_2d(np.asarray(seed2, dtype=float).T).T
    if a.shape != b.shape:
        raise ValueError(f"seed1 {a.shape} and seed2 {b.shape} differ in shape")
    n = a.shape[0] if n_window is None else int(n_window)
    if weights is not None and window is None:
        raise ValueError("a weighted noise floor needs the window's truth (window=)")
    # each subset hour's weight in the window (1.0, an exact no-op, for an evenly spaced subset)
    wt = 1.0 if weights is None else np.asarray(weights, dtype=float).reshape(-1, 1)
    if weights is not None and wt.shape[0] != a.shape[0]:
        raise ValueError(f"weights {wt.shape[0]} and seeds {a.shape} differ in hours")
    with np.errstate(divide="ignore", invalid="ignore"):
        if window is None:
            r = lifecycle.validation_metrics(b, a)["r"]
            var = 0.5 * np.mean((a - b) ** 2, axis=0)
            mean = 0.5 * (a.mean(axis=0) + b.mean(axis=0))
            std_pct = 100.0 * np.sqrt(n * var) / (n * mean)
        else:
            w = np.atleast_2d(np.asarray(window, dtype=float).T).T
            if w.shape[1] != a.shape[1]:
                raise ValueError(f"window {w.shape} and seeds {a.shape} differ in outputs")
            nv = wt * (0.5 * (a - b) ** 2)
            if weights is None:
                r = lifecycle.validation_metrics(b, a)["r"]
            else:  # the window's two-seed correlation, from its weighted mean seed variance
                r = 1.0 - np.sum(nv, axis=0) / np.sum(wt) / w.var(axis=0)
            c2 = np.sum(nv, axis=0) / np.sum(wt * (0.5 * (a + b)) ** 2, axis=0)
            std_pct = 100.0 * np.sqrt(c2 * np.sum(w * w, axis=0)) / np.sum(w, axis=0)
    ceiling = np.sqrt(np.clip(r, 0.0, 1.0))
    return {
        "r": r,
        "r_ceiling": ceiling,
        "sum_difference_pct": signed_error_pct(b.sum(axis=0), a.sum(axis=0)),
        "sum_std_pct": std_pct,
        "hour_cv": np.full(a.shape[1], np.nan) if window is None else np.sqrt(c2),
    }


# --------------------------------------------------------------------------- xarray adapter


def _a(long_name: str, units: str = "1") -> dict[str, str]:
    return {"units": units, "long_name": long_name}


def _band_vars(out: xr.Dataset, reconstruction: xr.Dataset, curves: Sequence[str]) -> xr.Dataset:
    """The bias test and the life band on the window, and the coverage factor the band needs.

    Two seed scatters of the window's sum: the truth's, ``seed_sum_std_pct`` (its hours are
    independent realisations), and the reconstruction's, ``records_sum_std_pct`` (its training
    records, shared by the hours near each; :mod:`moorlife.lifecycle.records`). Either is 0 when
    not measured. ``bias_z = reconstruction_error_pct / hypot(both)``: the error in units of the
    noise of the difference of two noisy sums; ``|bias_z| <= 2`` is within the seed noise.

    The band's sd on the window is ``sqrt(seed^2 + records^2 + validation^2)``
    (:func:`moorlife.lifecycle.band_sigma_of` of the two scatters and the fit's
    :func:`moorlife.lifecycle.validation_sum_term`, the life band's terms);
    ``coverage_needed`` is ``|reconstruction_error_pct| / band_sigma_pct``, what
    ``lifecycle.uncertainty.coverage`` must be for the truth to lie inside the band.
    """
    cd = (names.CURVE, names.LINE)
    err = out["reconstruction_error_pct"].values
    val = np.array([100.0 * lifecycle.validation_sum_term(reconstruction, cv) for cv in curves])[:, None]
    zero = np.zeros_like(err)
    seed = out["seed_sum_std_pct"].values if "seed_sum_std_pct" in out else zero
    rec = out["records_sum_std_pct"].values if "records_sum_std_pct" in out else zero
    noise = np.hypot(seed, rec)
    if "seed_sum_std_pct" in out:
        with np.errstate(divide="ignore", invalid="ignore"):
            z = err / noise  # +-inf for an error beside no noise, NaN for neither
        text = "reconstruction_error_pct / hypot(seed_sum_std_pct, records_sum_std_pct): the bias test"
        out["bias_z"] = (cd, z, _a(text))
    sigma = lifecycle.band_sigma_of(noise, np.broadcast_to(val, err.shape))
    out["band_sigma_pct"] = (
        cd,
        sigma,
        _a("life band sd on the window: sqrt(seed^2 + records^2 + max |validation sum error|^2)", "%"),
    )
    out["coverage_needed"] = (
        cd,
        lifecycle.coverage_needed(err, sigma),
        _a("|reconstruction error| / band_sigma_pct: the coverage factor that holds the truth"),
    )
    return out


def compare_window(
    truth: xr.Dataset,
    reconstruction: xr.Dataset,
    discrete_states: xr.Dataset,
    discrete_sims: xr.Dataset,
    *,
    outputs: Sequence[str],
    seed2: xr.Dataset | None = None,
    second_seed_storm: int = 0,
    records: Mapping[str, float] | None = None,
) -> xr.Dataset:
    """Compare the reconstruction with the simulated truth on the window.

    Parameters
    ----------
    truth : xarray.Dataset
        ``results/{ms}/truth.zarr`` (dims ``case``, ``line``; ``hindcast_index``).
    reconstruction : xarray.Dataset
        ``results/{ms}/lifecycle.zarr`` (dims ``time``, ``line``).
    discrete_states, discrete_sims : xarray.Dataset
        ``results/selection/discrete.zarr`` and ``results/{ms}/discrete.zarr``.
    outputs : sequence of str
        The outputs compared (``lifecycle.rbf.outputs``); those missing from either store are skipped.
    seed2 : xarray.Dataset, optional
        ``results/{ms}/truth_seed2.zarr``: a subset of the hours with a second seed.
    second_seed_storm : int
        ``truth.second_seed_storm``: the subset's storm stratum (:func:`second_seed_subset`);
        with it the noise floor is weighted by :func:`strata_weights` and is the window's.
    records : mapping of str to float, optional
        Per damage output (``"damage_sn/M1"``), the reconstructed window sum's seed sd from its
        training records per unit seed CV of one record
        (:func:`moorlife.lifecycle.records_term` on the window's hours). With ``seed2``, times
        the window's measured CV of one hour (``hour_cv`` of :func:`noise_floor`) it is
        ``records_sum_std_pct``, in the bias test and the band (:func:`_band_vars`).

    Returns
    -------
    xarray.Dataset
        Per ``output``: ``r``, ``rmse``, ``bias``, ``sum_error``, the r of two seeds
        ``noise_r`` and the ceiling of ``r``, ``ceiling_r = sqrt(noise_r)`` (:func:`noise_floor`); per ``curve`` and ``line``: ``truth_damage``, ``reconstruction_damage``,
        ``bins_damage``, ``reconstruction_error_pct``, ``bins_error_pct``,
        ``seed_sum_std_pct`` and ``seed_sum_difference_pct``, the life band's sd on the window
        ``band_sigma_pct`` and the ``coverage_needed`` to hold the truth (:func:`_band_vars`);
        per ``hour``: the truth and
        reconstructed values and the cumulative damage of the three.
    """
    c = names.CASE
    idx = np.asarray(truth["hindcast_index"].values, dtype=np.int64)
    n_time = reconstruction.sizes[names.TIME]
    if idx.size == 0 or idx.min() < 0 or idx.max() >= n_time:
        raise ValueError(
            f"truth hours' hindcast_index span {idx.min()}..{idx.max()} is outside the reconstruction's {n_time} hours"
        )
    rec = reconstruction.isel({names.TIME: idx})
    for v in names.METOCEAN_VARS:  # the truth hours are the reconstruction's hours
        if v in rec and not np.allclose(rec[v].values, truth[v].values, rtol=1e-6, atol=1e-9):
            raise ValueError(
                f"truth.zarr and lifecycle.zarr disagree on {v} at the same hindcast hours: "
                "built from different hindcasts"
            )
    cols = [col for col in lifecycle.output_columns(truth, c, outputs) if col[0] in reconstruction]
    labels = [lifecycle._label(col) for col in cols]
    y_true = lifecycle.stack_outputs(truth, c, cols)
    y_rec = lifecycle.stack_outputs(rec.rename({names.TIME: c}), c, cols)
    agree = hourly_agreement(y_true, y_rec)

    hour_coords = {"hour": np.arange(idx.size), "hindcast_index": ("hour", idx)}
    if names.TIME in rec.coords:
        hour_coords[names.TIME] = ("hour", rec[names.TIME].values)
    out = xr.Dataset(coords={"output": labels, **hour_coords})
    for k, text in (
        ("r", "Pearson r of reconstruction and truth over the window's hours"),
        ("rmse", "RMSE of reconstruction - truth"),
        ("bias", "mean of reconstruction - truth"),
        ("sum_error", "reconstruction sum / truth sum - 1"),
    ):
        out[k] = ("output", agree[k], _a(text))
    out["truth"] = (("hour", "output"), y_true, _a("simulated truth of each output at each window hour"))
    out["reconstruction"] = (("hour", "output"), y_rec, _a("reconstructed value (lifecycle.zarr) at each window hour"))

    noise = None
    if seed2 is not None and seed2.sizes.get(c, 0) >= 2:
        pos = np.searchsorted(idx, np.asarray(seed2["hindcast_index"].values, dtype=np.int64))
        if np.any(pos >= idx.size) or np.any(idx[np.minimum(pos, idx.size - 1)] != seed2["hindcast_index"].values):
            raise ValueError("truth_seed2.zarr holds hours that are not truth hours")
        y2 = lifecycle.stack_outputs(seed2, c, cols)
        storm = int(second_seed_storm)
        w = strata_weights(idx.size, pos, hs=truth["hs"].values, storm=storm) if storm else None
        noise = noise_floor(y_true[pos], y2, n_window=idx.size, window=y_true, weights=w)
        out = out.assign_coords(seed2_hour=("seed2_hour", idx[pos]))
        how = (
            f"{storm} storm hours (largest Hs) and {pos.size - storm} evenly spaced, weighted"
            if storm
            else "evenly spaced"
        )
        out["noise_r"] = ("output", noise["r"], _a(f"r of two seeds on {pos.size} hours ({how})"))
        out["ceiling_r"] = (
            "output",
            noise["r_ceiling"],
            _a("sqrt(noise_r): the per-hour r of a perfect reconstruction against one realisation"),
        )

    curves = [cv for cv in names.CURVES if lifecycle.DAMAGE_VARS[cv] in truth and lifecycle.DAMAGE_VARS[cv] in rec]
    if curves:
        a = discrete_states.attrs
        classes = np.column_stack([discrete_states[f"{ax}_class"].values for ax in ("hs", "wind", "tp")])
        bins = hour_bins(
            truth["hs"].values,
            truth["wind_speed"].values,
            truth["tp"].values,
            hs_edges=a["hs_edges"],
            wind_edges=a["wind_edges"],
            tp_edges=a["tp_edges"],
            bin_classes=classes,
        )
        lines = [str(v) for v in truth[names.LINE].values]
        b = names.BIN
        sims = discrete_sims.sel({b: discrete_states[b].values})
        t_h, r_h, b_h, tot = [], [], [], {"truth": [], "rec": [], "bins": []}
        for cv in curves:
            var = lifecycle.DAMAGE_VARS[cv]
            th = truth[var].transpose(c, names.LINE).sel({names.LINE: lines}).values
            rh = np.clip(rec[var].transpose(names.TIME, names.LINE).sel({names.LINE: lines}).values, 0, None)
            bd = sims[var].transpose(b, names.LINE).sel({names.LINE: lines}).values
            bh = bin_damage_per_hour(bins, bd)
            t_h.append(th), r_h.append(rh), b_h.append(bh)
            tot["truth"].append(lifecycle.life_damage(th))
            tot["rec"].append(lifecycle.life_damage(rh))
            tot["bins"].append(window_bin_damage(bins, bd))
        cd = (names.CURVE, names.LINE)
        out = out.assign_coords({names.CURVE: curves, names.LINE: lines})
        out["bin"] = ("hour", bins, _a("scatter-matrix bin of each window hour (results/selection/discrete.zarr)"))
        t_tot, r_tot, b_tot = (np.stack(tot[k]) for k in ("truth", "rec", "bins"))
        out["truth_damage"] = (cd, t_tot, _a(f"damage summed over the {idx.size} truth hours (simulated)"))
        out["reconstruction_damage"] = (
            cd,
            r_tot,
            _a("damage summed over the truth hours (lifecycle.zarr, clipped at 0)"),
        )
        out["bins_damage"] = (cd, b_tot, _a("35-bin method: window hours in each bin x the bin's hourly damage"))
        out["reconstruction_error_pct"] = (
            cd,
            signed_error_pct(r_tot, t_tot),
            _a("100 (reconstruction - truth) / truth", "%"),
        )
        out["bins_error_pct"] = (cd, signed_error_pct(b_tot, t_tot), _a("100 (bins - truth) / truth", "%"))
        hcd = (names.CURVE, "hour", names.LINE)
        for key, arr, text in (
            ("truth_cumulative", t_h, "cumulative truth damage"),
            ("reconstruction_cumulative", r_h, "cumulative reconstructed damage"),
            ("bins_cumulative", b_h, "cumulative 35-bin damage"),
        ):
            out[key] = (hcd, np.cumsum(np.stack(arr), axis=1), _a(text))
        if noise is not None:
            pos_of = {lab: j for j, lab in enumerate(labels)}
            for key, text in (
                ("sum_std_pct", "seed scatter (1 sd) of the window's damage sum, % of the sum"),
                ("sum_difference_pct", "100 (seed2 - seed1) / seed1 of the damage sum over the seed2 hours"),
            ):
                vals = np.array(
                    [[noise[key][pos_of[f"{lifecycle.DAMAGE_VARS[cv]}/{ln}"]] for ln in lines] for cv in curves]
                )
                out[f"seed_{key}"] = (cd, vals, _a(text, "%"))
            if records is not None:
                cv = {lab: noise["hour_cv"][j] for lab, j in pos_of.items()}
                keys = [[f"{lifecycle.DAMAGE_VARS[c_]}/{ln}" for ln in lines] for c_ in curves]
                missing = [k for row in keys for k in row if k not in records]
                if missing:
                    raise ValueError(f"records' term: no value for {missing}")
                vals = np.array([[100.0 * cv[k] * records[k] for k in row] for row in keys])
                text = "seed scatter (1 sd) of the reconstructed sum from its training records, % of the sum"
                out["records_sum_std_pct"] = (cd, vals, _a(text, "%"))
        out = _band_vars(out, reconstruction, curves)
    out.attrs.update(
        {
            "n_hours": int(idx.size),
            "n_seed2": int(0 if noise is None else out.sizes["seed2_hour"]),
            "second_seed_storm": int(second_seed_storm) if noise is not None else 0,
            "mooring_system": str(truth.attrs.get("mooring_system", "")),
            "random_stream": str(truth.attrs.get("random_stream", "")),
        }
    )
    return out
