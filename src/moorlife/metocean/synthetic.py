"""The seeded synthetic hindcast generator: its vectorised kernels and :func:`generate_synthetic`.

The paper's BiMEP reanalysis (Barrera et al. 2019, section 2) is not public, so the default
study runs on a *synthetic* hindcast with a BiMEP-like (Bay of Biscay) climate. It is built from
a few physically motivated, vectorised pieces, every parameter coming from
``config.yaml: hindcast.synthetic`` (mirrored by :class:`SyntheticParams`):

* **Swell** (waves generated far away): log-normal height whose log has an annual cycle and a
  smooth Gaussian synoptic anomaly (double-pole autoregressive filter, so the hourly series
  is smooth: lag-1 autocorrelation > 0.98), boosted by a **storm process**; direction about
  315 deg (north-west); peak period growing with the square root of the swell height.
* **Storms**: a seasonally modulated Poisson process; each storm is a smooth pulse that builds
  up and decays (asymmetric Gaussian shape), with a Weibull peak intensity (saturating) and a
  west/north-west direction. The storm intensity raises the swell *and* adds a storm wind
  vector, so westerly/north-westerly storms bring high wind and high waves together.
* **Wind** at a reference height (10 m): three prevailing direction regimes (east, south,
  west) drawn as seasonal, persistent segments, a Weibull speed obtained by transforming a
  smooth Gaussian process, a seasonal cycle, plus the storm wind vector. It is lifted to hub
  height with the power law ``U(z) = U(z_ref) (z / z_ref) ** alpha``.
* **Wind sea**: JONSWAP fetch-limited growth capped by the Pierson-Moskowitz fully developed
  sea (Coastal Engineering Manual form), with the fetch of the wind direction (open Atlantic
  to the west and north-west, land to the south), relaxed in time so waves lag the wind.
* **Total sea state**: ``Hs = sqrt(Hs_swell**2 + Hs_sea**2)``; ``Tp`` and the wave direction
  are those of the component with the larger spectral peak (``Hs**2 * Tp``); ``Tp`` is
  finally bounded below by the steepness limit ``Hs / (1.56 Tp**2) <= s_max`` and clipped to
  the configured range (3-22 s).
"""

from __future__ import annotations

import logging
import zlib

import numpy as np
import numpy.typing as npt
import pandas as pd
from scipy import signal, special

from moorlife.metocean.errors import HindcastError
from moorlife.metocean.params import (
    StormParams,
    SyntheticParams,
    WindParams,
    WindSeaParams,
)

__all__ = [
    "G_2PI",
    "hourly_time",
    "smooth_noise",
    "annual_cycle",
    "storm_pulses",
    "regime_series",
    "weibull_from_gaussian",
    "relax",
    "power_law_lift",
    "wind_from_uv",
    "fetch_limited_sea",
    "wind_sea",
    "steepness_limited_tp",
    "generate_synthetic",
]

log = logging.getLogger("moorlife.metocean")

#: Deep-water wavelength factor g / (2 pi) in m s-2: L0 = G_2PI * Tp**2 (= 1.56 Tp**2).
_G = 9.80665
G_2PI = _G / (2.0 * np.pi)
#: Fetch-limited growth and fully developed limits, deep water (Coastal Engineering Manual,
#: EM 1110-2-1100, Part II-2, eqs. II-2-36 to II-2-39): g Hs / U^2 = 0.0016 (g X / U^2)^(1/2)
#: <= 0.2433, g Tp / U = 0.2857 (g X / U^2)^(1/3) <= 8.134.
JONSWAP_HS = 0.0016
JONSWAP_TP = 0.2857
PM_HS_STAR = 0.2433
PM_TP_STAR = 8.134
_HOURS_PER_YEAR = 365.2425 * 24.0


def hourly_time(start: str, end: str) -> np.ndarray:
    """Hourly ``datetime64[ns]`` axis from ``start`` to ``end`` inclusive.

    Raises
    ------
    HindcastError
        If the period is empty or the bounds are not on whole hours.
    """
    t0, t1 = pd.Timestamp(start), pd.Timestamp(end)
    for name, t in (("start", t0), ("end", t1)):
        if t != t.floor("h"):
            raise HindcastError(f"hindcast.{name} = {t} is not on a whole hour")
    if t1 < t0:
        raise HindcastError(f"hindcast.end = {t1} is before hindcast.start = {t0}")
    return pd.date_range(t0, t1, freq="h").values.astype("datetime64[ns]")


def smooth_noise(rng: np.random.Generator, n: int, timescale: float) -> np.ndarray:
    """Stationary, smooth, unit-variance Gaussian noise (double-pole autoregressive filter).

    ``y[t] = 2 a y[t-1] - a**2 y[t-2] + e[t]`` with ``a = exp(-1 / timescale)``; its variance is
    ``(1 + a**2) / (1 - a**2)**3`` (divided out) and its lag-1 autocorrelation ``2 a / (1 + a**2)``.
    A burn-in of ``10 * timescale`` samples removes the start-up transient.

    Parameters
    ----------
    rng : numpy.random.Generator
    n : int
        Number of samples (hours).
    timescale : float
        E-folding time of the pole, in samples (hours), > 0.

    Returns
    -------
    numpy.ndarray, shape (n,)
    """
    a = float(np.exp(-1.0 / timescale))
    burn = int(np.ceil(10.0 * timescale))
    e = rng.standard_normal(n + burn)
    y = signal.lfilter([1.0], [1.0, -2.0 * a, a * a], e)[burn:]
    return y * np.sqrt((1.0 - a * a) ** 3 / (1.0 + a * a))


def annual_cycle(time: np.ndarray, peak_day: float) -> np.ndarray:
    """``cos(2 pi (t - peak) / year)`` for a ``datetime64`` array: +1 at ``peak_day`` (day of year)."""
    t = pd.DatetimeIndex(time)
    doy = t.dayofyear.to_numpy() - 1.0 + t.hour.to_numpy() / 24.0
    return np.cos(2.0 * np.pi * (doy - (peak_day - 1.0)) * 24.0 / _HOURS_PER_YEAR)


def storm_pulses(rng: np.random.Generator, season: np.ndarray, p: StormParams) -> tuple[np.ndarray, np.ndarray]:
    """Storm intensity and storm direction, hourly.

    Storm peaks occur as a Poisson process of rate ``rate_per_year * (1 + a * season)``
    (thinning); each has a Weibull peak intensity (mean ``intensity_mean``, shape
    ``intensity_shape``), gamma-distributed rise and decay times (means ``rise_hours``,
    ``decay_hours``, shape ``duration_shape``), a smooth asymmetric Gaussian shape, and a
    direction ``N(direction_mean, direction_spread)``. The summed pulses saturate smoothly at
    ``intensity_max`` (``I_max * tanh(I / I_max)``): storms have a finite strength, which
    bounds the 31-year extremes.

    Parameters
    ----------
    rng : numpy.random.Generator
    season : numpy.ndarray, shape (n,)
        Annual cycle, +1 in mid-winter (:func:`annual_cycle`).
    p : StormParams

    Returns
    -------
    intensity : numpy.ndarray, shape (n,)
        Saturated sum of the pulses (dimensionless, in ``[0, intensity_max)``).
    direction : numpy.ndarray, shape (n,)
        Intensity-weighted circular mean direction of the active storms, degrees; the mean
        direction where no storm is active.
    """
    n = season.size
    rate_max = p.rate_per_year * (1.0 + abs(p.seasonal_amplitude)) / _HOURS_PER_YEAR
    n_cand = rng.poisson(rate_max * n)
    t_cand = rng.uniform(0.0, n, n_cand)
    accept = rng.uniform(0.0, 1.0, n_cand) * rate_max
    rate = p.rate_per_year * (1.0 + p.seasonal_amplitude * season[np.minimum(t_cand.astype(int), n - 1)])
    t_peak = np.sort(t_cand[accept < rate / _HOURS_PER_YEAR])
    k = t_peak.size
    amp = p.intensity_mean / special.gamma(1.0 + 1.0 / p.intensity_shape) * rng.weibull(p.intensity_shape, k)
    rise = rng.gamma(p.duration_shape, p.rise_hours / p.duration_shape, k)
    decay = rng.gamma(p.duration_shape, p.decay_hours / p.duration_shape, k)
    dirs = rng.normal(p.direction_mean, p.direction_spread, k)
    intensity = np.zeros(n)
    vx, vy = np.zeros(n), np.zeros(n)
    if k:
        half = int(np.ceil(4.0 * max(rise.max(), decay.max())))
        idx = np.round(t_peak).astype(int)[:, None] + np.arange(-half, half + 1)[None, :]
        tau = idx - t_peak[:, None]
        width = np.where(tau < 0.0, rise[:, None], decay[:, None])
        g = amp[:, None] * np.exp(-0.5 * (tau / width) ** 2)
        ok = (idx >= 0) & (idx < n)
        rad = np.deg2rad(dirs)[:, None] * np.ones_like(g)
        np.add.at(intensity, idx[ok], g[ok])
        np.add.at(vx, idx[ok], (g * np.sin(rad))[ok])
        np.add.at(vy, idx[ok], (g * np.cos(rad))[ok])
    intensity = p.intensity_max * np.tanh(intensity / p.intensity_max)
    direction = np.where(intensity > 0.0, np.rad2deg(np.arctan2(vx, vy)) % 360.0, p.direction_mean % 360.0)
    return intensity, direction


def regime_series(
    rng: np.random.Generator, season: np.ndarray, p: WindParams
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Persistent wind-direction regimes (e.g. east, south, west).

    Segments of exponential length (mean ``regime_hours``) each take one regime, drawn with
    probabilities ``regime_probabilities * (1 + regime_seasonal_amplitudes * season)``
    (renormalised) at the segment start. Transitions are smoothed over ``veer_hours`` by
    filtering the unit vector, so the wind veers rather than jumps.

    Returns
    -------
    direction : numpy.ndarray, shape (n,)
        Smoothed regime mean direction, degrees.
    spread : numpy.ndarray, shape (n,)
        Direction spread (std, degrees) of the current regime.
    speed_factor : numpy.ndarray, shape (n,)
        Speed multiplier of the current regime (smoothed).
    """
    n = season.size
    mean_dirs = np.asarray(p.regime_directions, float)
    probs = np.asarray(p.regime_probabilities, float)
    amps = np.asarray(p.regime_seasonal_amplitudes, float)
    n_seg = int(np.ceil(2.0 * n / p.regime_hours)) + 16
    lengths = rng.exponential(p.regime_hours, n_seg)
    starts = np.concatenate([[0.0], np.cumsum(lengths)[:-1]])
    starts = starts[starts < n]
    w = probs[None, :] * (1.0 + amps[None, :] * season[starts.astype(int)][:, None])
    cum = np.cumsum(np.clip(w, 0.0, None), axis=1)
    u = rng.uniform(0.0, 1.0, starts.size) * cum[:, -1]
    label_seg = (u[:, None] >= cum).sum(axis=1)
    seg_of_hour = np.searchsorted(starts, np.arange(n), side="right") - 1
    label = label_seg[seg_of_hour]
    rad = np.deg2rad(mean_dirs[label])
    sx, sy = relax(np.sin(rad), p.veer_hours), relax(np.cos(rad), p.veer_hours)
    direction = np.rad2deg(np.arctan2(sx, sy)) % 360.0
    spread = relax(np.asarray(p.regime_spreads, float)[label], p.veer_hours)
    speed_factor = relax(np.asarray(p.regime_speed_factors, float)[label], p.veer_hours)
    return direction, spread, speed_factor


def weibull_from_gaussian(z: npt.ArrayLike, scale: npt.ArrayLike, shape: float) -> np.ndarray:
    """Map standard Gaussian values to a Weibull marginal (probability integral transform).

    ``x = scale * (-ln(1 - Phi(z))) ** (1 / shape)``, computed with ``log_ndtr(-z)`` so the
    upper tail is exact.
    """
    return np.asarray(scale) * (-special.log_ndtr(-np.asarray(z, float))) ** (1.0 / shape)


def relax(x: npt.ArrayLike, timescale: float) -> np.ndarray:
    """First-order relaxation ``y[t] = y[t-1] + (x[t] - y[t-1]) / timescale`` (y[0] = x[0]).

    A causal lag of about ``timescale`` samples (waves responding to the wind). ``timescale``
    <= 1 returns ``x`` unchanged.
    """
    x = np.asarray(x, float)
    if timescale <= 1.0 or x.size == 0:
        return x.copy()
    b = 1.0 / timescale
    y, _ = signal.lfilter([b], [1.0, b - 1.0], x, zi=[x[0] * (1.0 - b)])
    return y


def power_law_lift(speed: npt.ArrayLike, from_height: float, to_height: float, exponent: float) -> np.ndarray:
    """Lift wind speed with the power law ``U(z2) = U(z1) * (z2 / z1) ** exponent``.

    Parameters
    ----------
    speed : array_like
        Wind speed at ``from_height``, m/s.
    from_height, to_height : float
        Heights above sea level, m (> 0).
    exponent : float
        Shear exponent (paper: 0.14).
    """
    if from_height <= 0 or to_height <= 0:
        raise ValueError(f"heights must be > 0, got {from_height} and {to_height}")
    return np.asarray(speed, float) * (to_height / from_height) ** exponent


def wind_from_uv(u: npt.ArrayLike, v: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Speed and nautical "coming from" direction of wind components.

    Parameters
    ----------
    u, v : array_like
        Eastward and northward wind components (ERA5 ``u10``/``v10``), m/s.

    Returns
    -------
    speed : numpy.ndarray
        m/s.
    direction : numpy.ndarray
        Degrees clockwise from north the wind blows from, in ``[0, 360)``; a wind blowing
        toward the east (u > 0, v = 0) comes from 270.
    """
    u, v = np.asarray(u, float), np.asarray(v, float)
    return np.hypot(u, v), np.rad2deg(np.arctan2(-u, -v)) % 360.0


def fetch_limited_sea(u10: npt.ArrayLike, fetch: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Fetch-limited wind-sea height and period (JONSWAP growth, CEM/SPM deep-water form).

    With ``X* = g X / U**2``: ``g Hs / U**2 = min(0.0016 X***(1/2), 0.2433)`` and
    ``g Tp / U = min(0.2857 X***(1/3), 8.134)``; the caps are the fully developed
    (Pierson-Moskowitz) sea (U.S. Army Corps of Engineers, Coastal Engineering Manual
    EM 1110-2-1100, Part II-2, eqs. II-2-36 to II-2-39).

    Parameters
    ----------
    u10 : array_like, shape (n,)
        Wind speed at 10 m, m/s.
    fetch : array_like, shape (n,)
        Fetch, m (> 0).

    Returns
    -------
    hs, tp : numpy.ndarray, shape (n,)
        m and s (0 where the wind is calm).
    """
    u = np.maximum(np.asarray(u10, float), 1e-6)
    x_star = _G * np.asarray(fetch, float) / u**2
    hs = np.minimum(JONSWAP_HS * np.sqrt(x_star), PM_HS_STAR) * u**2 / _G
    tp = np.minimum(JONSWAP_TP * np.cbrt(x_star), PM_TP_STAR) * u / _G
    return hs, tp


def wind_sea(
    u10: np.ndarray, wind_dir: np.ndarray, p: WindSeaParams, tp_noise: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Wind sea of a 10-m wind over the site's fetches.

    The fetch is interpolated (periodically, in log) from ``fetch_km`` at the wind direction;
    wind speed, fetch and direction are relaxed over ``response_hours`` (waves lag the wind);
    height and period follow :func:`fetch_limited_sea`; the period is scattered by
    ``exp(tp_sigma * tp_noise)`` (real seas are not on one growth curve).

    Parameters
    ----------
    u10, wind_dir : numpy.ndarray, shape (n,)
        Wind speed at 10 m (m/s) and direction (deg, coming from).
    p : WindSeaParams
    tp_noise : numpy.ndarray, shape (n,), optional
        Standard Gaussian noise (e.g. :func:`smooth_noise`); none if omitted.

    Returns
    -------
    hs, tp, direction : numpy.ndarray, shape (n,)
        m, s, degrees (coming from).
    """
    log_x = np.interp(wind_dir, np.asarray(p.fetch_directions), np.log(np.asarray(p.fetch_km) * 1e3), period=360.0)
    fetch = np.exp(relax(log_x, p.response_hours))
    hs, tp = fetch_limited_sea(relax(u10, p.response_hours), fetch)
    if tp_noise is not None:
        tp = tp * np.exp(p.tp_sigma * tp_noise)
    rad = np.deg2rad(wind_dir)
    direction = np.rad2deg(np.arctan2(relax(np.sin(rad), p.response_hours), relax(np.cos(rad), p.response_hours)))
    return hs, tp, direction % 360.0


def steepness_limited_tp(hs: npt.ArrayLike, tp: npt.ArrayLike, max_steepness: float) -> np.ndarray:
    """Raise ``tp`` where the sea would be steeper than ``Hs / (1.56 Tp**2) = max_steepness``.

    ``Tp >= sqrt(Hs / (g / (2 pi) * max_steepness))``; 1/15 is the usual breaking limit of
    a short-crested sea (DNV-RP-C205 uses 1/15 for Tp < 8 s and 1/25 for Tp > 15 s).
    """
    hs = np.asarray(hs, float)
    return np.maximum(np.asarray(tp, float), np.sqrt(hs / (G_2PI * max_steepness)))


def _rng_streams(seed: int, n: int) -> list[np.random.Generator]:
    ss = np.random.SeedSequence([int(seed), zlib.crc32(b"moorlife.metocean.synthetic")])
    return [np.random.default_rng(s) for s in ss.spawn(n)]


def generate_synthetic(
    time: np.ndarray, params: SyntheticParams, seed: int, hub_height: float, shear_exponent: float
) -> dict[str, np.ndarray]:
    """Generate the synthetic hindcast.

    Parameters
    ----------
    time : numpy.ndarray of datetime64, shape (n,)
        Hourly time axis (:func:`hourly_time`).
    params : SyntheticParams
    seed : int
        Global seed; the same seed and period give bit-identical output.
    hub_height : float
        m; the wind is generated at ``params.reference_height`` and lifted to it.
    shear_exponent : float
        Power-law exponent.

    Returns
    -------
    dict
        ``hs`` m, ``tp`` s, ``wave_dir`` deg, ``wind_speed`` m/s at hub height, ``wind_dir`` deg,
        plus diagnostic components ``hs_swell``, ``hs_sea``, ``storm_intensity``, each shape (n,).
    """
    n = int(time.size)
    r_storm, r_regime, r_w, r_wdir, r_sw, r_swdir, r_tp, r_tps = _rng_streams(seed, 8)
    season = annual_cycle(time, params.season_peak_day)
    sp, wp = params.swell, params.wind

    intensity, storm_dir = storm_pulses(r_storm, season, params.storms)

    # background wind (reference height): regimes, Weibull speed, seasonal cycle
    reg_dir, reg_spread, reg_speed = regime_series(r_regime, season, wp)
    base_dir = reg_dir + reg_spread * smooth_noise(r_wdir, n, wp.direction_timescale_hours)
    scale = wp.weibull_scale * (1.0 + wp.seasonal_amplitude * season) * reg_speed
    base_speed = weibull_from_gaussian(smooth_noise(r_w, n, wp.timescale_hours), scale, wp.weibull_shape)
    base_speed = base_speed * np.exp(-intensity / params.storms.regime_suppression)
    # storm wind vector added to the background ("coming from" unit vectors)
    storm_speed = params.storms.wind_gain * intensity
    bx = base_speed * np.sin(np.deg2rad(base_dir)) + storm_speed * np.sin(np.deg2rad(storm_dir))
    by = base_speed * np.cos(np.deg2rad(base_dir)) + storm_speed * np.cos(np.deg2rad(storm_dir))
    u_ref = np.hypot(bx, by)
    wind_dir = np.rad2deg(np.arctan2(bx, by)) % 360.0

    # swell
    log_hs = (
        np.log(sp.median)
        + sp.seasonal_amplitude * season
        + sp.sigma * smooth_noise(r_sw, n, sp.timescale_hours)
        + params.storms.swell_gain * intensity
    )
    hs_sw = np.exp(log_hs)
    tp_sw = (sp.tp_base + sp.tp_slope * np.sqrt(hs_sw)) * np.exp(
        sp.tp_sigma * smooth_noise(r_tp, n, sp.tp_timescale_hours)
    )
    dir_sw = sp.direction_mean + sp.direction_spread * smooth_noise(r_swdir, n, sp.direction_timescale_hours)

    # local wind sea (from the 10-m-equivalent wind; the generator's reference height)
    u10 = power_law_lift(u_ref, params.reference_height, 10.0, shear_exponent)
    tp_noise = smooth_noise(r_tps, n, params.wind_sea.tp_timescale_hours)
    hs_sea, tp_sea, dir_sea = wind_sea(u10, wind_dir, params.wind_sea, tp_noise)

    hs = np.hypot(hs_sw, hs_sea)
    sea_dominates = hs_sea**2 * tp_sea > hs_sw**2 * tp_sw
    tp = np.where(sea_dominates, tp_sea, tp_sw)
    tp = np.clip(steepness_limited_tp(hs, tp, params.max_steepness), params.tp_min, params.tp_max)
    wave_dir = np.where(sea_dominates, dir_sea, dir_sw) % 360.0
    wind_speed = power_law_lift(u_ref, params.reference_height, hub_height, shear_exponent)
    return {
        "hs": hs,
        "tp": tp,
        "wave_dir": wave_dir,
        "wind_speed": wind_speed,
        "wind_dir": wind_dir,
        "hs_swell": hs_sw,
        "hs_sea": hs_sea,
        "storm_intensity": intensity,
    }
