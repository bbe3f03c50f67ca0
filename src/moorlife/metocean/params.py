"""The parameters of the synthetic generator and of the cleaning policy, as typed records.

:class:`SyntheticParams` mirrors ``config.yaml: hindcast.synthetic``; :class:`CleaningPolicy`
and :class:`PlausibleLimits` mirror ``hindcast.cleaning``. Every record is built with
``X.from_config(section)``: missing keys take the defaults of the config schema (the records
have none of their own), lists become tuples.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, fields
from typing import Any, ClassVar, TypeVar

from moorlife.settings import fill_section

__all__ = [
    "SwellParams",
    "StormParams",
    "WindParams",
    "WindSeaParams",
    "SyntheticParams",
    "CleaningPolicy",
    "PlausibleLimits",
]

_R = TypeVar("_R", bound="_Record")

_SCALARS: dict[str, Any] = {"float": float, "int": int, "bool": bool, "str": str}


class _Record:
    """``from_config`` shared by the records of this module: schema-filled, then typed."""

    #: Dotted config section the record mirrors.
    SECTION: ClassVar[str]

    @classmethod
    def from_config(cls: type[_R], section: Mapping[str, Any] | None, source: str = "config") -> _R:
        """Build from the config section :attr:`SECTION` (missing keys take the schema defaults).

        Raises
        ------
        moorlife.config.ConfigError
            For an unknown key or a wrong type or value, naming the dotted key.
        """
        return cls._from_filled(fill_section(cls.SECTION, section, source))

    @classmethod
    def _from_filled(cls: type[_R], s: Mapping[str, Any]) -> _R:
        kw: dict[str, Any] = {}
        for f in fields(cls):  # type: ignore[arg-type]
            v, kind = s[f.name], str(f.type)
            if kind in _SCALARS:
                kw[f.name] = _SCALARS[kind](v)
            elif kind.startswith("tuple["):
                kw[f.name] = tuple(float(x) for x in v)
            else:  # a nested record
                kw[f.name] = _NESTED[kind]._from_filled(v)
        return cls(**kw)

    @classmethod
    def from_mapping(cls: type[_R], cfg: Mapping[str, Any] | None) -> _R:
        """Alias of :meth:`from_config` (kept for its callers)."""
        return cls.from_config(cfg)


@dataclass(frozen=True)
class SwellParams(_Record):
    """Swell (remotely generated waves). Mirrors ``hindcast.synthetic.swell``."""

    SECTION = "hindcast.synthetic.swell"

    median: float
    seasonal_amplitude: float
    sigma: float
    timescale_hours: float
    direction_mean: float
    direction_spread: float
    direction_timescale_hours: float
    tp_base: float
    tp_slope: float
    tp_sigma: float
    tp_timescale_hours: float


@dataclass(frozen=True)
class StormParams(_Record):
    """Storm pulses. Mirrors ``hindcast.synthetic.storms``."""

    SECTION = "hindcast.synthetic.storms"

    rate_per_year: float
    seasonal_amplitude: float
    intensity_mean: float
    intensity_shape: float
    intensity_max: float
    rise_hours: float
    decay_hours: float
    duration_shape: float
    direction_mean: float
    direction_spread: float
    swell_gain: float
    wind_gain: float
    regime_suppression: float


@dataclass(frozen=True)
class WindParams(_Record):
    """Background wind at the reference height. Mirrors ``hindcast.synthetic.wind``."""

    SECTION = "hindcast.synthetic.wind"

    weibull_scale: float
    weibull_shape: float
    seasonal_amplitude: float
    timescale_hours: float
    regime_hours: float
    regime_directions: tuple[float, ...]
    regime_spreads: tuple[float, ...]
    regime_probabilities: tuple[float, ...]
    regime_seasonal_amplitudes: tuple[float, ...]
    regime_speed_factors: tuple[float, ...]
    veer_hours: float
    direction_timescale_hours: float


@dataclass(frozen=True)
class WindSeaParams(_Record):
    """Locally generated wind sea. Mirrors ``hindcast.synthetic.wind_sea``."""

    SECTION = "hindcast.synthetic.wind_sea"

    fetch_directions: tuple[float, ...]
    fetch_km: tuple[float, ...]
    response_hours: float
    tp_sigma: float
    tp_timescale_hours: float


@dataclass(frozen=True)
class SyntheticParams(_Record):
    """Every parameter of the synthetic generator (``config.yaml: hindcast.synthetic``).

    Build it with :meth:`from_config`; the defaults are the schema's.
    """

    SECTION = "hindcast.synthetic"

    reference_height: float
    season_peak_day: float
    max_steepness: float
    tp_min: float
    tp_max: float
    swell: SwellParams
    storms: StormParams
    wind: WindParams
    wind_sea: WindSeaParams


@dataclass(frozen=True)
class PlausibleLimits(_Record):
    """Largest physically plausible values; beyond them the file's units are wrong (cm, km/h...)."""

    SECTION = "hindcast.cleaning.limits"

    hs_max: float
    tp_max: float
    wind_speed_max: float


@dataclass(frozen=True)
class CleaningPolicy(_Record):
    """What to do with imperfect input (``config.yaml: hindcast.cleaning``); schema default: refuse.

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
    sea_states : {"error", "drop", "clip"}
        Physically impossible sea states (beyond the breaking steepness or below the Tp floor of
        :mod:`moorlife.cleaning`): raise, turn them into gaps, or raise Tp to the limit.
    limits : PlausibleLimits
        Plausibility limits catching wrong units.
    """

    SECTION = "hindcast.cleaning"

    max_gap_hours: int
    duplicates: str
    unsorted: str
    wrap_directions: bool
    sea_states: str
    limits: PlausibleLimits


_NESTED: dict[str, type[_Record]] = {
    c.__name__: c for c in (SwellParams, StormParams, WindParams, WindSeaParams, PlausibleLimits)
}
