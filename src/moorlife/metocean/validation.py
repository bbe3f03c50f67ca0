"""Validation and cleaning of a loaded hindcast (:func:`validate_hindcast`).

Loaded hindcasts (ERA5, NORA3, any column map; see :mod:`moorlife.io.hindcast`) go through
:func:`validate_hindcast`, which raises :class:`HindcastError` naming the file, the column, the
first offending row and value, or applies the configured cleaning policy and logs it.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import numpy.typing as npt
import pandas as pd
import xarray as xr

from moorlife.metocean.errors import HindcastError
from moorlife.metocean.params import CleaningPolicy
from moorlife.names import METOCEAN_VARS, TIME

__all__ = ["validate_hindcast"]

log = logging.getLogger("moorlife.metocean")


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
    policy = policy or CleaningPolicy.from_config({})
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
        log.warning(
            "%s: timestamps not sorted (first at row %d); sorted them (cleaning.unsorted = sort)", source, rows[i]
        )
        times, data, rows = times[order], data.iloc[order], rows[order]
    dup = np.concatenate([[False], np.diff(times.astype("int64")) == 0])
    if dup.any():
        i = int(np.flatnonzero(dup)[0])
        if policy.duplicates != "first":
            raise HindcastError(
                f"{source}: column 'time', row {int(rows[i])}: duplicated timestamp {pd.Timestamp(times[i])} "
                "(set hindcast.cleaning.duplicates: first to keep the first)"
            )
        log.warning(
            "%s: %d duplicated timestamps (first at row %d); kept the first of each", source, dup.sum(), rows[i]
        )
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
                source,
                lab[v],
                starts.size,
                int(lengths.sum()),
                full[int(starts[0])].isoformat(),
                policy.max_gap_hours,
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
            raise HindcastError(
                f"{_where(source, 'wind_speed', lab['wind_speed'], rows, times, i)}: value {vals['wind_speed'][i]:g} is negative"
            )
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
            log.warning(
                "%s: column '%s': wrapped %d direction(s) outside [0, 360) modulo 360", source, lab[v], bad.size
            )
            vals[v] = np.where(np.isfinite(x), x % 360.0, x)
        fin = x[np.isfinite(x)]
        if fin.size >= 24 and fin.max() <= 2.0 * np.pi + 1e-9 and np.ptp(fin) > 1.0:
            raise HindcastError(
                f"{source}: column '{lab[v]}': every direction is <= 2 pi ({fin.max():.3f}): radians instead of degrees?"
            )
