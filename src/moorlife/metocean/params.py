"""The parameters of the synthetic generator and of the cleaning policy, as typed records.

:class:`SyntheticParams` mirrors ``config.yaml: hindcast.synthetic``; :class:`CleaningPolicy`
and :class:`PlausibleLimits` mirror ``hindcast.cleaning``.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from typing import Any

__all__ = [
    "SwellParams",
    "StormParams",
    "WindParams",
    "WindSeaParams",
    "SyntheticParams",
    "CleaningPolicy",
    "PlausibleLimits",
]


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
