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

Modules: :mod:`~moorlife.metocean.params` (the typed parameters),
:mod:`~moorlife.metocean.synthetic` (the generator's kernels),
:mod:`~moorlife.metocean.validation` (validation and cleaning),
:mod:`~moorlife.metocean.adapters` (the contract Dataset) and :mod:`~moorlife.metocean.errors`.
Building the study's hindcast from its config section (generate, or read a file through
:mod:`moorlife.io.hindcast`) is the stage's job: :func:`moorlife.stages.metocean.build_hindcast`.
"""

from __future__ import annotations

from moorlife.metocean.adapters import (
    DIRECTION_CONVENTION,
    WAVE_VARS,
    WIND_VARS,
    hindcast_dataset,
)
from moorlife.metocean.errors import HindcastError
from moorlife.metocean.params import (
    CleaningPolicy,
    PlausibleLimits,
    StormParams,
    SwellParams,
    SyntheticParams,
    WindParams,
    WindSeaParams,
)
from moorlife.metocean.synthetic import (
    G_2PI,
    annual_cycle,
    fetch_limited_sea,
    generate_synthetic,
    hourly_time,
    power_law_lift,
    regime_series,
    relax,
    smooth_noise,
    steepness_limited_tp,
    storm_pulses,
    weibull_from_gaussian,
    wind_from_uv,
    wind_sea,
)
from moorlife.metocean.validation import validate_hindcast

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
]
