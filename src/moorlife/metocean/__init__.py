"""Hourly metocean hindcast: a seeded synthetic generator, validation/cleaning, the contract Dataset.

The paper's BiMEP reanalysis (Barrera et al. 2019, section 2) is not public, so the default
study runs on a *synthetic* hindcast with a BiMEP-like (Bay of Biscay) climate:
:mod:`moorlife.metocean.synthetic` describes its swell, storms, wind and wind sea, every
parameter coming from ``config.yaml: hindcast.synthetic`` (mirrored by :class:`SyntheticParams`).

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
