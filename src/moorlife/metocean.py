"""Hourly metocean hindcast: a seeded synthetic generator, validation/cleaning, the contract Dataset.

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

Loaded hindcasts (ERA5, NORA3, any column map; see :mod:`moorlife.io.hindcast`) go through
:func:`validate_hindcast`, which raises :class:`HindcastError` naming the file, the column, the
first offending row and value, or applies the configured cleaning policy and logs it.
"""

from __future__ import annotations

import logging
import zlib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np
import numpy.typing as npt
import pandas as pd
import xarray as xr
from scipy import signal, special

from moorlife.names import METOCEAN_ATTRS, METOCEAN_VARS, TIME

__all__ = [
    "HindcastError",
    "SwellParams",
    "StormParams",
    "WindParams",
    "WindSeaParams",
    "SyntheticParams",
    "CleaningPolicy",
    "PlausibleLimits",
    "WAVE_VARS",
    "WIND_VARS",
    "DIRECTION_CONVENTION",
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
    "validate_hindcast",
    "hindcast_dataset",
    "build_hindcast",
]

log = logging.getLogger("moorlife.metocean")

#: Wave variables and wind variables of the contract (order of ``METOCEAN_VARS`` kept).
WAVE_VARS: tuple[str, ...] = ("hs", "tp", "wave_dir")
WIND_VARS: tuple[str, ...] = ("wind_speed", "wind_dir")
DIRECTION_CONVENTION = "nautical: degrees clockwise from north, direction the wind or waves come from"
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


class HindcastError(ValueError):
    """A hindcast is unusable; the message names the file, column, first bad row and value."""


# ----------------------------------------------------------------------------------- parameters
@dataclass(frozen=True)
class SwellParams:
    """Swell (remotely generated waves). Defaults equal ``config.yaml: hindcast.synthetic.swell``."""

    median: float = 1.32
    seasonal_amplitude: float = 0.4
    sigma: float = 0.32
    timescale_hours: float = 30.0
    direction_mean: float = 312.0
    direction_spread: float = 20.0
    direction_timescale_hours: float = 36.0
    tp_base: float = 6.0
    tp_slope: float = 4.0
    tp_sigma: float = 0.16
    tp_timescale_hours: float = 24.0


@dataclass(frozen=True)
class StormParams:
    """Storm pulses. Defaults equal ``config.yaml: hindcast.synthetic.storms``."""

    rate_per_year: float = 14.0
    seasonal_amplitude: float = 0.8
    intensity_mean: float = 0.40
    intensity_shape: float = 0.9
    intensity_max: float = 2.6
    rise_hours: float = 6.0
    decay_hours: float = 10.0
    duration_shape: float = 4.0
    direction_mean: float = 292.0
    direction_spread: float = 18.0
    swell_gain: float = 0.25
    wind_gain: float = 15.0
    regime_suppression: float = 0.5


@dataclass(frozen=True)
class WindParams:
    """Background wind at the reference height. Defaults equal ``hindcast.synthetic.wind``."""

    weibull_scale: float = 6.6
    weibull_shape: float = 2.1
    seasonal_amplitude: float = 0.12
    timescale_hours: float = 10.0
    regime_hours: float = 60.0
    regime_directions: tuple[float, ...] = (85.0, 185.0, 272.0)
    regime_spreads: tuple[float, ...] = (22.0, 22.0, 25.0)
    regime_probabilities: tuple[float, ...] = (0.34, 0.30, 0.36)
    regime_seasonal_amplitudes: tuple[float, ...] = (-0.45, 0.15, 0.3)
    regime_speed_factors: tuple[float, ...] = (1.05, 0.9, 1.1)
    veer_hours: float = 3.0
    direction_timescale_hours: float = 8.0


@dataclass(frozen=True)
class WindSeaParams:
    """Locally generated wind sea. Defaults equal ``hindcast.synthetic.wind_sea``."""

    fetch_directions: tuple[float, ...] = (0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0)
    fetch_km: tuple[float, ...] = (300.0, 150.0, 40.0, 2.0, 2.0, 5.0, 400.0, 600.0)
    response_hours: float = 6.0
    tp_sigma: float = 0.1
    tp_timescale_hours: float = 12.0


@dataclass(frozen=True)
class SyntheticParams:
    """Every parameter of the synthetic generator (``config.yaml: hindcast.synthetic``).

    Use :meth:`from_mapping` to build it from the configuration; the defaults here equal the
    configuration's, which ``tests/test_metocean.py`` checks.
    """

    reference_height: float = 10.0
    season_peak_day: float = 15.0
    max_steepness: float = 0.0666667
    tp_min: float = 3.0
    tp_max: float = 22.0
    swell: SwellParams = field(default_factory=SwellParams)
    storms: StormParams = field(default_factory=StormParams)
    wind: WindParams = field(default_factory=WindParams)
    wind_sea: WindSeaParams = field(default_factory=WindSeaParams)

    @classmethod
    def from_mapping(cls, cfg: Mapping[str, Any] | None) -> SyntheticParams:
        """Build from ``hindcast.synthetic`` (missing keys keep their defaults, lists become tuples)."""
        cfg = dict(cfg or {})
        sub = {"swell": SwellParams, "storms": StormParams, "wind": WindParams, "wind_sea": WindSeaParams}
        known = {f.name for f in fields(cls)}
        unknown = sorted(set(cfg) - known)
        if unknown:
            raise ValueError(f"hindcast.synthetic: unknown key(s) {unknown}")
        kw: dict[str, Any] = {}
        for k, v in cfg.items():
            if k in sub:
                names = {f.name for f in fields(sub[k])}
                bad = sorted(set(v or {}) - names)
                if bad:
                    raise ValueError(f"hindcast.synthetic.{k}: unknown key(s) {bad}")
                kw[k] = sub[k](**{n: tuple(x) if isinstance(x, list) else x for n, x in (v or {}).items()})
            else:
                kw[k] = v
        return cls(**kw)


@dataclass(frozen=True)
class PlausibleLimits:
    """Largest physically plausible values; beyond them the file's units are wrong (cm, km/h...)."""

    hs_max: float = 25.0
    tp_max: float = 40.0
    wind_speed_max: float = 80.0


@dataclass(frozen=True)
class CleaningPolicy:
    """What to do with imperfect input (``config.yaml: hindcast.cleaning``); default: refuse.

    Attributes
    ----------
    max_gap_hours : int
        Gaps (missing hours or NaN values) up to this length are linearly interpolated
        (directions on the circle); longer gaps, or any gap when 0, raise.
    duplicates : {"error", "first"}
        Repeated timestamps: raise, or keep the first row of each timestamp.
    unsorted : {"error", "sort"}
        Timestamps out of order: raise, or sort them.
    wrap_directions : bool
        Directions outside ``[0, 360]`` are wrapped modulo 360 instead of raising (exactly 360
        is always read as north, 0, and logged).
    limits : PlausibleLimits
        Plausibility limits catching wrong units.
    """

    max_gap_hours: int = 0
    duplicates: str = "error"
    unsorted: str = "error"
    wrap_directions: bool = False
    limits: PlausibleLimits = field(default_factory=PlausibleLimits)

    @classmethod
    def from_mapping(cls, cfg: Mapping[str, Any] | None) -> CleaningPolicy:
        """Build from ``hindcast.cleaning``."""
        cfg = dict(cfg or {})
        lim = PlausibleLimits(**dict(cfg.pop("limits", {}) or {}))
        return cls(limits=lim, **cfg)


# ------------------------------------------------------------------------------------- kernels
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


def storm_pulses(
    rng: np.random.Generator, season: np.ndarray, p: StormParams
) -> tuple[np.ndarray, np.ndarray]:
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


# ---------------------------------------------------------------------------------- validation
def _where(source: str, column: str, label: str, rows: np.ndarray, times: np.ndarray, i: int) -> str:
    col = f"column '{column}'" if label == column else f"column '{label}' (variable {column})"
    return f"{source}: {col}, row {int(rows[i])} (time {pd.Timestamp(times[i]).isoformat()})"


def _interp_gaps(values: np.ndarray, is_dir: bool) -> np.ndarray:
    ok = np.isfinite(values)
    x = np.arange(values.size)
    if is_dir:  # linear along the shorter arc between the neighbours
        return np.interp(x, x[ok], np.unwrap(values[ok], period=360.0)) % 360.0
    return np.interp(x, x[ok], values[ok])


def _gap_runs(bad: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Start indices and lengths of runs of True."""
    d = np.diff(np.concatenate([[0], bad.astype(np.int8), [0]]))
    starts = np.flatnonzero(d == 1)
    return starts, np.flatnonzero(d == -1) - starts


def validate_hindcast(
    df: pd.DataFrame | xr.Dataset,
    *,
    source: str,
    policy: CleaningPolicy | None = None,
    labels: Mapping[str, str] | None = None,
    rows: npt.ArrayLike | None = None,
    require: Sequence[str] = METOCEAN_VARS,
    period: tuple[Any, Any] | None = None,
) -> pd.DataFrame:
    """Check a loaded hindcast and return it hourly, sorted and complete, or raise.

    Parameters
    ----------
    df : pandas.DataFrame or xarray.Dataset
        Column (or dimension) ``time`` and the contract variables present (``hs``, ``tp``,
        ``wave_dir``, ``wind_speed``, ``wind_dir``), in the file's order.
    source : str
        The file, quoted in every message.
    policy : CleaningPolicy, optional
        Cleaning policy; default: refuse everything imperfect.
    labels : mapping, optional
        Variable -> name of the file's column, for messages.
    rows : array_like, optional
        Row number in the file of each row of ``df`` (e.g. the CSV line), for messages.
        Default: 0-based position.
    require : sequence of str
        Variables that must be present.
    period : (start, end), optional
        The hours the result must cover (missing hours at either end count as gaps);
        default: first to last timestamp of ``df``.

    Returns
    -------
    pandas.DataFrame
        Indexed by an hourly ``DatetimeIndex`` named ``time``, float64 columns.

    Raises
    ------
    HindcastError
        Empty data, missing columns, unparsable or non-hourly timestamps, duplicates, unsorted
        rows, NaN/missing hours beyond the allowed gap, non-positive Hs/Tp, directions outside
        ``[0, 360)``, implausible values (units), each naming the column, row and value.
    """
    policy = policy or CleaningPolicy()
    if isinstance(df, xr.Dataset):
        df = df[[v for v in METOCEAN_VARS if v in df.data_vars]].to_dataframe().reset_index()
    labels = dict(labels or {})
    lab = {v: labels.get(v, v) for v in METOCEAN_VARS}
    if len(df) == 0:
        raise HindcastError(f"{source}: the file holds no data rows")
    missing = [v for v in require if v not in df.columns]
    if missing:
        raise HindcastError(
            f"{source}: missing column(s) for {', '.join(missing)}; found {[c for c in df.columns if c != 'time']}"
        )
    rows = np.arange(len(df)) if rows is None else np.asarray(rows)
    times = pd.to_datetime(df["time"], errors="coerce").to_numpy(dtype="datetime64[ns]")
    bad_t = np.isnat(times)
    if bad_t.any():
        i = int(np.flatnonzero(bad_t)[0])
        raise HindcastError(f"{source}: column 'time', row {int(rows[i])}: {df['time'].iloc[i]!r} is not a timestamp")
    off = times != times.astype("datetime64[h]").astype("datetime64[ns]")
    if off.any():
        i = int(np.flatnonzero(off)[0])
        raise HindcastError(
            f"{source}: column 'time', row {int(rows[i])}: {pd.Timestamp(times[i])} is not on a whole hour "
            "(the hindcast must be hourly)"
        )
    data = df[[v for v in METOCEAN_VARS if v in df.columns]].apply(pd.to_numeric, errors="coerce")
    for v in data.columns:
        raw = df[v]
        if pd.api.types.is_numeric_dtype(raw.dtype):
            continue  # nothing to coerce: NaN are gaps, handled below
        nonnum = data[v].isna() & raw.notna() & (raw.astype(str).str.strip() != "")
        if nonnum.any():
            i = int(np.flatnonzero(nonnum.to_numpy())[0])
            raise HindcastError(f"{_where(source, v, lab[v], rows, times, i)}: {raw.iloc[i]!r} is not a number")
    order = np.argsort(times, kind="stable")
    if np.any(np.diff(times.astype("int64")) < 0):
        i = int(np.flatnonzero(np.diff(times.astype("int64")) < 0)[0]) + 1
        if policy.unsorted != "sort":
            raise HindcastError(
                f"{source}: column 'time', row {int(rows[i])}: {pd.Timestamp(times[i])} comes after "
                f"{pd.Timestamp(times[i - 1])} (timestamps not sorted; set hindcast.cleaning.unsorted: sort)"
            )
        log.warning("%s: timestamps not sorted (first at row %d); sorted them (cleaning.unsorted = sort)", source, rows[i])
        times, data, rows = times[order], data.iloc[order], rows[order]
    dup = np.concatenate([[False], np.diff(times.astype("int64")) == 0])
    if dup.any():
        i = int(np.flatnonzero(dup)[0])
        if policy.duplicates != "first":
            raise HindcastError(
                f"{source}: column 'time', row {int(rows[i])}: duplicated timestamp {pd.Timestamp(times[i])} "
                "(set hindcast.cleaning.duplicates: first to keep the first)"
            )
        log.warning("%s: %d duplicated timestamps (first at row %d); kept the first of each", source, dup.sum(), rows[i])
        times, data, rows = times[~dup], data.iloc[~dup], rows[~dup]
    step = np.diff(times).astype("timedelta64[h]").astype(np.int64)
    if times.size > 1:
        coarse = np.median(step) if step.size else 1
        if coarse != 1:
            raise HindcastError(
                f"{source}: column 'time': the time step is {int(coarse)} h (median), not hourly; resample the "
                "file to hourly values first"
            )
    vals = {v: data[v].to_numpy(dtype=float) for v in data.columns}
    _check_values(vals, lab, source, rows, times, policy)

    lo, hi = (times[0], times[-1]) if period is None else (pd.Timestamp(period[0]), pd.Timestamp(period[1]))
    full = pd.date_range(lo, hi, freq="h")
    out = pd.DataFrame(vals, index=pd.DatetimeIndex(times)).reindex(full)
    out.index.name = TIME
    bad = out.isna().to_numpy()
    if bad.any():
        row_of = pd.Series(rows, index=pd.DatetimeIndex(times)).reindex(full)
        for j, v in enumerate(out.columns):
            starts, lengths = _gap_runs(bad[:, j])
            if starts.size == 0:
                continue
            k = int(np.argmax(lengths > policy.max_gap_hours)) if (lengths > policy.max_gap_hours).any() else -1
            if k >= 0:
                s = int(starts[k])
                t = full[s]
                r = row_of.iloc[s]
                if np.isfinite(r):
                    where = f"row {int(r)}"
                elif s > 0 and np.isfinite(row_of.iloc[s - 1]):
                    where = f"missing row after row {int(row_of.iloc[s - 1])}"
                else:
                    where = "missing row"
                raise HindcastError(
                    f"{source}: column '{lab[v]}', {where} (time {t.isoformat()}): {int(lengths[k])} hour(s) "
                    f"missing or NaN; the cleaning policy interpolates gaps up to "
                    f"hindcast.cleaning.max_gap_hours = {policy.max_gap_hours} h"
                )
            out[v] = _interp_gaps(out[v].to_numpy(), v in ("wave_dir", "wind_dir"))
            log.warning(
                "%s: column '%s': interpolated %d gap(s), %d hour(s) in all, first at %s (max_gap_hours = %d)",
                source, lab[v], starts.size, int(lengths.sum()), full[int(starts[0])].isoformat(), policy.max_gap_hours,
            )
    return out.astype(float)


def _check_values(
    vals: dict[str, np.ndarray],
    lab: Mapping[str, str],
    source: str,
    rows: np.ndarray,
    times: np.ndarray,
    policy: CleaningPolicy,
) -> None:
    lim = policy.limits
    for v in ("hs", "tp"):
        if v not in vals:
            continue
        x = vals[v]
        bad = np.flatnonzero(x <= 0.0)
        if bad.size:
            i = int(bad[0])
            raise HindcastError(
                f"{_where(source, v, lab[v], rows, times, i)}: value {x[i]:g} is not > 0 ({bad.size} such row(s))"
            )
    for v, hi, hint in (
        ("hs", lim.hs_max, "Hs in cm instead of m?"),
        ("tp", lim.tp_max, "Tp in tenths of seconds or ms?"),
        ("wind_speed", lim.wind_speed_max, "wind speed in km/h or knots instead of m/s?"),
    ):
        if v not in vals:
            continue
        bad = np.flatnonzero(vals[v] > hi)
        if bad.size:
            i = int(bad[0])
            raise HindcastError(
                f"{_where(source, v, lab[v], rows, times, i)}: value {vals[v][i]:g} exceeds the plausible "
                f"maximum {hi:g} ({hint}); fix the units or raise hindcast.cleaning.limits"
            )
    if "wind_speed" in vals:
        bad = np.flatnonzero(vals["wind_speed"] < 0.0)
        if bad.size:
            i = int(bad[0])
            raise HindcastError(f"{_where(source, 'wind_speed', lab['wind_speed'], rows, times, i)}: value {vals['wind_speed'][i]:g} is negative")
    for v in ("wave_dir", "wind_dir"):
        if v not in vals:
            continue
        x = vals[v]
        north = x == 360.0
        if north.any():
            # WMO practice: 360 is north (0 is reserved for calm); the same direction as 0
            log.info("%s: column '%s': %d value(s) of exactly 360 read as north (0)", source, lab[v], north.sum())
            x = vals[v] = np.where(north, 0.0, x)
        bad = np.flatnonzero((x < 0.0) | (x >= 360.0))
        if bad.size:
            i = int(bad[0])
            if not policy.wrap_directions:
                raise HindcastError(
                    f"{_where(source, v, lab[v], rows, times, i)}: direction {x[i]:g} is outside [0, 360) "
                    f"({bad.size} such row(s); set hindcast.cleaning.wrap_directions: true to wrap them)"
                )
            log.warning("%s: column '%s': wrapped %d direction(s) outside [0, 360) modulo 360", source, lab[v], bad.size)
            vals[v] = np.where(np.isfinite(x), x % 360.0, x)
        fin = x[np.isfinite(x)]
        if fin.size >= 24 and fin.max() <= 2.0 * np.pi + 1e-9 and np.ptp(fin) > 1.0:
            raise HindcastError(
                f"{source}: column '{lab[v]}': every direction is <= 2 pi ({fin.max():.3f}): radians instead of degrees?"
            )


# -------------------------------------------------------------------------------- xarray adapter
def hindcast_dataset(
    time: npt.ArrayLike,
    variables: Mapping[str, npt.ArrayLike],
    *,
    source: str,
    site: str,
    lon: float,
    lat: float,
    hub_height: float,
    extra_attrs: Mapping[str, Any] | None = None,
) -> xr.Dataset:
    """Assemble the contract Dataset of ``results/metocean/hindcast.zarr``.

    Parameters
    ----------
    time : array_like of datetime64, shape (n,)
    variables : mapping
        The variables of :data:`moorlife.names.METOCEAN_VARS`, each shape (n,) (the wind may
        be absent only for a waves-only inspection); others are ignored.
    source, site : str
        Provenance (``"synthetic (seed ...)"`` or the file) and site name.
    lon, lat : float
        Degrees east / north.
    hub_height : float
        m, the height of ``wind_speed``.
    extra_attrs : mapping, optional
        Further dataset attributes (e.g. generator parameters, wind measured height).
    """
    t = np.asarray(time).astype("datetime64[ns]")
    missing = [v for v in WAVE_VARS if v not in variables]
    if missing:
        raise KeyError(f"hindcast_dataset: missing variable(s) {missing}")
    data = {
        v: (TIME, np.asarray(variables[v], dtype=np.float64), dict(METOCEAN_ATTRS[v]))
        for v in METOCEAN_VARS
        if v in variables
    }
    ds = xr.Dataset(data, coords={TIME: (TIME, t, {"long_name": "time (UTC), hourly"})})
    if "wind_speed" in ds:
        ds["wind_speed"].attrs["height"] = f"{hub_height:g} m"
    ds.attrs.update(
        {
            "Conventions": "CF-1.10",
            "title": "moorlife hourly metocean hindcast",
            "source": source,
            "site": site,
            "lon": float(lon),
            "lat": float(lat),
            "hub_height": float(hub_height),
            "direction_convention": DIRECTION_CONVENTION,
        }
    )
    ds.attrs.update(dict(extra_attrs or {}))
    return ds


def build_hindcast(cfg: Mapping[str, Any], seed: int, base_dir: str = ".") -> xr.Dataset:
    """The contract hindcast Dataset from the ``hindcast:`` configuration section.

    Dispatches on ``cfg["source"]``: ``synthetic`` runs :func:`generate_synthetic` over
    ``start``..``end``; ``file`` loads ``path`` (relative to ``base_dir``) with
    :func:`moorlife.io.hindcast.read_hindcast`, validates it and cuts it to ``start``..``end``.

    Parameters
    ----------
    cfg : mapping
        The ``hindcast`` section (schema defaults filled in); a whole study config with a
        ``hindcast`` key is accepted too.
    seed : int
        Global seed (``config.yaml: seed``).
    base_dir : str
        Directory that relative paths are resolved against.
    """
    if "hindcast" in cfg and isinstance(cfg["hindcast"], Mapping):
        cfg = cfg["hindcast"]
    site = dict(cfg.get("site", {}))
    hub, alpha = float(cfg["hub_height"]), float(cfg["shear_exponent"])
    common = {"site": site.get("name", ""), "lon": site.get("lon", np.nan), "lat": site.get("lat", np.nan), "hub_height": hub}
    if cfg.get("source", "synthetic") == "synthetic":
        params = SyntheticParams.from_mapping(cfg.get("synthetic"))
        time = hourly_time(cfg["start"], cfg["end"])
        out = generate_synthetic(time, params, seed, hub, alpha)
        log.info(
            "synthetic hindcast, seed %d: %d hours %s..%s, mean Hs %.2f m, max Hs %.2f m, mean wind %.2f m/s at %g m",
            seed, time.size, cfg["start"], cfg["end"], out["hs"].mean(), out["hs"].max(), out["wind_speed"].mean(), hub,
        )
        return hindcast_dataset(
            time, out, source=f"moorlife synthetic BiMEP-like hindcast (seed {seed})",
            extra_attrs={"wind_reference_height": params.reference_height, "shear_exponent": alpha}, **common,
        )
    if cfg.get("source") != "file":
        raise HindcastError(f"hindcast.source = {cfg.get('source')!r}: expected 'synthetic' or 'file'")
    from moorlife.io.hindcast import read_hindcast

    if not cfg.get("path"):
        raise HindcastError("hindcast.source is 'file' but hindcast.path is not set")
    return read_hindcast(
        cfg["path"],
        start=cfg["start"],
        end=cfg["end"],
        hub_height=hub,
        shear_exponent=alpha,
        columns=cfg.get("columns"),
        fmt=cfg.get("format", "auto"),
        measured_height=cfg.get("measured_height"),
        wave_dir_convention=cfg.get("wave_dir_convention", "auto"),
        cleaning=CleaningPolicy.from_mapping(cfg.get("cleaning")),
        site=common["site"],
        lon=common["lon"],
        lat=common["lat"],
        base_dir=base_dir,
    )
