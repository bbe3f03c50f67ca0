"""Statistics of a simulated record: the per-case outputs of a batch and their attributes."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from moorlife import names
from moorlife.settings import StatisticsSettings
from moorlife.simulate.integration import Record

__all__ = ["EXTRA_SCALAR_VARS", "EXTRA_LINE_VARS", "EXTRA_ATTRS", "TIMESERIES_VARS", "output_attrs", "summarise"]

#: The output names and attributes live in the registry :mod:`moorlife.names`; these are its entries.
EXTRA_SCALAR_VARS: tuple[str, ...] = names.SIM_EXTRA_SCALAR_VARS
EXTRA_LINE_VARS: tuple[str, ...] = names.SIM_EXTRA_LINE_VARS
EXTRA_ATTRS: dict[str, dict[str, str]] = names.SIM_EXTRA_ATTRS
TIMESERIES_VARS: tuple[str, ...] = names.SIM_TIMESERIES_VARS


def output_attrs(name: str) -> dict[str, str]:
    """Attributes of any output of :func:`simulate_batch` (contract or extra): :func:`moorlife.names.output_attrs`."""
    return names.output_attrs(name)


def summarise(
    record: Record,
    *,
    line_info: Mapping[str, Any],
    fatigue_cfg: Mapping[str, Any] | None,
    statistics: StatisticsSettings,
    mpm_duration: float,
    keep_timeseries: bool = False,
) -> dict[str, np.ndarray]:
    """The per-case outputs of a batch of records.

    Parameters
    ----------
    record : Record
        Kept records, ``(B, ..., nt)``.
    line_info : mapping
        ``link_diameter`` (m), ``mbs`` (N), ``chain`` of the lines.
    fatigue_cfg : mapping or None
        The ``fatigue:`` config section (curves, mean stress, residue); None skips damage.
    statistics : StatisticsSettings
        The ``statistics:`` section (``block``: GEV block length in s, ``method``).
    mpm_duration : float
        Duration in s the most probable maxima refer to (``simulation.mpm_duration``).
    keep_timeseries : bool
        Also return the records (``ts_*``).

    Returns
    -------
    dict of numpy.ndarray
        ``names.SIM_SCALAR_VARS`` ``(B,)``, ``names.SIM_LINE_VARS`` ``(B, 3)``,
        ``gev_corr_<v>`` for ``v`` in ``names.GEV_VARS``, and :data:`EXTRA_SCALAR_VARS`,
        :data:`EXTRA_LINE_VARS`. Magnitudes: surge, sway and heave MPMs are of ``|x|``; the
        acceleration is the horizontal magnitude at the hub.
    """
    from moorlife import stats

    block, method = statistics.block, statistics.method
    dt = record.dt
    mo = record.motion
    nt = mo.shape[-1]
    out: dict[str, np.ndarray] = {}

    def gev(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return stats.gev_mpm(x, dt, block=block, duration=mpm_duration, method=method)

    mpm, corr = gev(np.abs(mo[:, :3, :]))
    for i, name in enumerate(("surge_mpm", "sway_mpm", "heave_mpm")):
        out[name] = mpm[:, i]
        out[f"gev_corr_{name}"] = corr[:, i]
    acc = np.hypot(record.accel[:, 0, :], record.accel[:, 1, :])
    out["accel_mpm"], out["gev_corr_accel_mpm"] = gev(acc)
    pct = stats.percentiles(acc, [90.0, 95.0, 99.0])
    out["accel_p90"], out["accel_p95"], out["accel_p99"] = pct[:, 0], pct[:, 1], pct[:, 2]
    ten = record.tension
    if np.all(np.isfinite(ten)):
        out["tension_mpm"], out["gev_corr_tension_mpm"] = gev(ten)
        out["tension_mean"] = ten.mean(axis=-1)
        out["tension_std"] = ten.std(axis=-1)
        out["tension_max"] = ten.max(axis=-1)
        if fatigue_cfg is not None:
            from moorlife import fatigue

            settings = fatigue.fatigue_settings(fatigue_cfg, source="config.yaml")
            d_sn, d_tn = fatigue.hourly_damage(
                ten,
                nt * dt,
                link_diameter=line_info["link_diameter"],
                mbs=line_info["mbs"],
                chain=line_info["chain"],
                **settings.damage_kwargs(),
            )
            out["damage_sn"], out["damage_tn"] = np.asarray(d_sn), np.asarray(d_tn)
    else:
        nan3 = np.full(ten.shape[:2], np.nan)
        for name in (
            "tension_mpm",
            "gev_corr_tension_mpm",
            "tension_mean",
            "tension_std",
            "tension_max",
            "damage_sn",
            "damage_tn",
        ):
            out[name] = nan3.copy()
    out["surge_mean"] = mo[:, 0].mean(axis=-1)
    out["sway_mean"] = mo[:, 1].mean(axis=-1)
    out["heave_mean"] = mo[:, 2].mean(axis=-1)
    out["pitch_mean"] = np.rad2deg(mo[:, 4].mean(axis=-1))
    out["surge_std"] = mo[:, 0].std(axis=-1)
    out["pitch_mpm"], out["gev_corr_pitch_mpm"] = gev(np.rad2deg(np.abs(mo[:, 4])))
    out["offset_max"] = np.hypot(mo[:, 0], mo[:, 1]).max(axis=-1)
    if keep_timeseries:
        for i, name in enumerate(("ts_surge", "ts_sway", "ts_heave", "ts_roll", "ts_pitch", "ts_yaw")):
            out[name] = mo[:, i].astype(np.float32)
        out["ts_accel"] = acc.astype(np.float32)
        out["ts_tension"] = ten.astype(np.float32)
    return out
