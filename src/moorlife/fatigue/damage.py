"""Miner damage of tension records on the S-N and T-N curves, per hour of sea state."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import numpy.typing as npt

from moorlife.fatigue.chain import MEAN_STRESS_METHODS, corroded_properties, mean_stress_factor, stress_area
from moorlife.fatigue.counting import RESIDUE_METHODS, _damage_records, _first_nonfinite
from moorlife.fatigue.curves import SNCurve, TNCurve, get_curves

SECONDS_PER_HOUR = 3600.0


def sn_damage(ranges_mpa: npt.ArrayLike, counts: npt.ArrayLike, curve: SNCurve | Mapping[str, float]) -> np.ndarray:
    """Miner damage on an S-N curve, ``sum(n_i * S_i**m) / a_d``, no endurance limit.

    Parameters
    ----------
    ranges_mpa : array_like, shape (..., nc)
        Stress ranges in MPa.
    counts : array_like, shape (..., nc)
        Cycle counts (1 or 0.5 from :func:`rainflow`, or any weights).
    curve : SNCurve or mapping with ``a_d`` and ``m``

    Returns
    -------
    ndarray, shape (...)
    """
    c = curve if isinstance(curve, SNCurve) else SNCurve(float(curve["a_d"]), float(curve["m"]))
    s = np.asarray(ranges_mpa, dtype=float)
    return np.sum(np.asarray(counts, dtype=float) * s**c.m, axis=-1) / c.a_d


def tn_damage(
    ranges_n: npt.ArrayLike, counts: npt.ArrayLike, rbs: npt.ArrayLike, curve: TNCurve | Mapping[str, float]
) -> np.ndarray:
    """Miner damage on a T-N curve, ``sum(n_i * (T_i / RBS)**m) / k``.

    Parameters
    ----------
    ranges_n : array_like, shape (..., nc)
        Tension ranges in N.
    counts : array_like, shape (..., nc)
    rbs : array_like, broadcastable to (...)
        Reference breaking strength (MBS) in N.
    curve : TNCurve or mapping with ``k`` and ``m``

    Returns
    -------
    ndarray, shape (...)
    """
    c = curve if isinstance(curve, TNCurve) else TNCurve(float(curve["k"]), float(curve["m"]))
    r = np.asarray(ranges_n, dtype=float) / np.asarray(rbs, dtype=float)[..., None]
    return np.sum(np.asarray(counts, dtype=float) * r**c.m, axis=-1) / c.k


def cycle_damage(
    ranges_n: np.ndarray,
    means_n: np.ndarray,
    counts: np.ndarray,
    *,
    link_diameter: float,
    mbs: float,
    chain: str = "studless",
    curves: Mapping[str, Any] | None = None,
    mean_stress: str = "none",
    ultimate: float = 960.0,
    yield_: float = 700.0,
) -> tuple[float, float]:
    """S-N and T-N Miner damage of a set of tension cycles (of one record, not scaled).

    Parameters
    ----------
    ranges_n, means_n, counts : ndarray, shape (nc,)
        Output of :func:`rainflow` on a tension record in N.
    link_diameter : float
        Link diameter in m (already corroded if relevant).
    mbs : float
        Minimum breaking strength in N (already corroded if relevant).
    chain, curves
        See :func:`get_curves`.
    mean_stress, ultimate, yield_
        See :func:`mean_stress_factor`. The correction applies to the S-N damage only,
        cycle by cycle (equivalent zero-mean range ``S / factor(mean stress of the
        cycle)``); the T-N curves of API RP 2SK carry no mean-load correction.

    Returns
    -------
    damage_sn, damage_tn : float
    """
    sn, tn = get_curves(chain, curves)
    area = float(stress_area(link_diameter))
    s = ranges_n / area * 1e-6
    if mean_stress != "none":
        s = s / mean_stress_factor(means_n / area * 1e-6, mean_stress, ultimate, yield_)
    d_sn = float(np.dot(counts, s**sn.m)) / sn.a_d
    d_tn = float(np.dot(counts, (ranges_n / float(mbs)) ** tn.m)) / tn.k
    return d_sn, d_tn


def hourly_damage(
    tension: npt.ArrayLike,
    duration: float,
    *,
    link_diameter: npt.ArrayLike,
    mbs: npt.ArrayLike,
    chain: str = "studless",
    curves: Mapping[str, Any] | None = None,
    mean_stress: str = "none",
    corrosion_years: float = 0.0,
    corrosion_rate: float = 0.2e-3,
    ultimate: float = 960.0,
    yield_: float = 700.0,
    residue: str = "half",
) -> tuple[np.ndarray, np.ndarray]:
    """Miner damage per hour of sea state from simulated fairlead tension records.

    Parameters
    ----------
    tension : array_like, shape (..., nt)
        Tension records in N (any leading dims, e.g. ``(case, line, nt)``).
    duration : float
        Duration in s that each record represents (``nt * dt``); damage is scaled by
        exactly ``3600 / duration``.
    link_diameter : array_like, broadcastable to (...)
        New link diameter in m.
    mbs : array_like, broadcastable to (...)
        New minimum breaking strength (the T-N reference breaking strength) in N.
    chain : {"studless", "stud"}
    curves : mapping, optional
        The ``fatigue.curves`` config section (default :data:`DEFAULT_CURVES`).
    mean_stress : {"none", "goodman", "soderberg", "gerber"}
        Mean-stress correction of the S-N ranges (see :func:`cycle_damage`).
    corrosion_years : float
        Age of the chain; diameter and MBS are reduced by :func:`corroded_properties`.
    corrosion_rate : float
        Diameter loss in m/year.
    ultimate, yield_ : float
        MPa, for the mean-stress correction.
    residue : {"half", "close"}
        Rainflow residue handling, see :func:`rainflow`.

    Returns
    -------
    damage_sn, damage_tn : ndarray, shape (...)
        Dimensionless Miner damage per hour.
    """
    t = np.asarray(tension, dtype=np.float64)
    if t.ndim < 1 or t.shape[-1] < 2:
        raise ValueError(f"tension must have shape (..., nt) with nt >= 2, got {t.shape}")
    if not (np.isfinite(duration) and duration > 0):
        raise ValueError(f"duration must be a positive number of seconds, got {duration!r}")
    if residue not in RESIDUE_METHODS:
        raise ValueError(f"residue must be one of {RESIDUE_METHODS}, got {residue!r}")
    if mean_stress not in MEAN_STRESS_METHODS:
        raise ValueError(f"mean_stress must be one of {MEAN_STRESS_METHODS}, got {mean_stress!r}")
    lead = t.shape[:-1]
    d, m = corroded_properties(link_diameter, mbs, corrosion_years, corrosion_rate)
    area = np.ascontiguousarray(np.broadcast_to(stress_area(d), lead), dtype=np.float64).reshape(-1)
    rbs = np.ascontiguousarray(np.broadcast_to(m, lead), dtype=np.float64).reshape(-1)
    if np.any(~(rbs > 0)):
        raise ValueError(f"mbs must be positive (N), got {mbs!r}")
    flat = np.ascontiguousarray(t.reshape(-1, t.shape[-1]))
    first_bad = _first_nonfinite(flat.reshape(-1))
    if first_bad >= 0:
        row, col = divmod(first_bad, flat.shape[1])
        rec = tuple(int(v) for v in np.unravel_index(int(row), lead))
        raise ValueError(f"tension: non-finite value at record {rec}, sample {int(col)}")
    sn, tn = get_curves(chain, curves)
    ms_n, ms_r = {"none": (0, 1.0), "goodman": (1, ultimate), "soderberg": (1, yield_), "gerber": (2, ultimate)}[
        mean_stress
    ]
    out_sn, out_tn = _damage_records(flat, area, rbs, sn.a_d, sn.m, tn.k, tn.m, ms_n, float(ms_r), residue == "close")
    if np.any(np.isinf(out_sn)):
        i = int(np.flatnonzero(np.isinf(out_sn))[0])
        rec = tuple(int(v) for v in np.unravel_index(i, lead))
        raise ValueError(
            f"tension record {rec}: a cycle mean stress reaches the {mean_stress} limit "
            f"({ms_r} MPa): no fatigue capacity left"
        )
    scale = SECONDS_PER_HOUR / float(duration)
    return (out_sn * scale).reshape(lead), (out_tn * scale).reshape(lead)


def hourly_damage_xr(tension: Any, *, dim: str = "t", **kwargs: Any) -> Any:
    """xarray adapter of :func:`hourly_damage`.

    Parameters
    ----------
    tension : xarray.DataArray
        Tension in N with a uniformly spaced time coordinate ``dim`` in s.
    dim : str
        The time dimension (core dimension, removed from the result).
    **kwargs
        Keyword arguments of :func:`hourly_damage` (``link_diameter``, ``mbs``, ...);
        ``duration`` defaults to ``n * dt`` from the coordinate.

    Returns
    -------
    xarray.Dataset
        ``damage_sn`` and ``damage_tn`` (per hour of sea state) over the other dimensions.
    """
    import xarray as xr

    if "duration" not in kwargs:
        t = np.asarray(tension[dim].values, dtype=float)
        dt = np.diff(t)
        if t.size < 2 or not np.allclose(dt, dt[0], rtol=1e-6):
            raise ValueError(f"tension: coordinate {dim!r} must be uniformly spaced seconds to infer the duration")
        kwargs["duration"] = float(t.size * dt[0])
    duration = kwargs.pop("duration")
    sn, tn = xr.apply_ufunc(
        lambda x: hourly_damage(x, duration, **kwargs),
        tension,
        input_core_dims=[[dim]],
        output_core_dims=[[], []],
        dask="parallelized",
        output_dtypes=[float, float],
    )
    ds = xr.Dataset({"damage_sn": sn, "damage_tn": tn})
    ds["damage_sn"].attrs = {"units": "1", "long_name": "S-N (DNVGL-OS-E301) Miner damage per hour of sea state"}
    ds["damage_tn"].attrs = {"units": "1", "long_name": "T-N (API RP 2SK) Miner damage per hour of sea state"}
    return ds
