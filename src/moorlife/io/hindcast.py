"""Read real hindcasts (ERA5, NORA3, any column map) into the contract Dataset.

Supported files
---------------
* **CSV** in the metocean-api style of ERA5/NORA3 exports: leading ``#`` header lines (the
  position is read from ``LONGITUDE:``/``LATITUDE:`` when present), then a header row with a
  ``time`` column.
* **NetCDF** (``.nc``, ``.nc4``, ``.cdf``) and **Zarr** (``.zarr`` directory) with a ``time``
  or ``valid_time`` dimension; extra ``latitude``/``longitude`` dimensions are reduced to the
  grid point nearest the configured site.

Column names are recognised automatically (first match wins):

========== =====================================================================
variable   names
========== =====================================================================
hs         ``hs``, ``swh``, ``Hs``, ``hm0``, ``VHM0``
tp         ``tp``, ``pp1d``, ``Tp``, ``VTPK``
wave_dir   ``Pdir``, ``mwd``, ``wave_dir``, ``thq``, ``VMDR``, ``mdir``
wind       ``wind_speed_<h>m`` + ``wind_direction_<h>m`` (NORA3), ``u<h>`` + ``v<h>``
           (ERA5 ``u10``/``v10``, ``u100``/``v100``), ``si10`` + ``dwi``; generic
           ``wind_speed`` + ``wind_dir``/``wind_direction``, ``ws`` + ``wd`` (height from
           ``hindcast.measured_height``)
========== =====================================================================

Timestamps with a UTC offset (``...Z``, ``+01:00``, daylight-saving offsets that change within
the file) are converted to UTC; timestamps without one are taken as UTC; a file mixing both is
refused. A byte-order mark before the ``#`` lines is ignored. Physically impossible sea states
(beyond the breaking steepness, Tp under 1 s: :mod:`moorlife.cleaning`) are refused, or dropped
or clipped (``sea_states``), and a constant Hs, Tp or wind speed is refused.

``hindcast.columns`` maps any other naming (keys ``hs``, ``tp``, ``wave_dir``, ``wind_speed``,
``wind_dir``, ``wind_u``, ``wind_v``). When several wind heights exist, the one nearest the
hub height is used and lifted to it with the power law.

NORA3 (WAM) wave directions are stored "going to" (checked on the reference file: in winds
above 14 m/s the NORA3 ``Pdir``/``thq`` differ from the wind direction by 150-210 deg), so
``wave_dir_convention: auto`` turns them by 180 deg for NORA3 files and keeps other files as
"coming from" (ERA5 ``mwd`` is "coming from").
"""

from __future__ import annotations

import logging
import os
import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

from moorlife.cleaning import (
    BREAKING_STEEPNESS,
    SEA_STATE_POLICIES,
    TP_FLOOR,
    check_sea_states,
    clipped_tp,
    constant_columns,
)
from moorlife.metocean import (
    WAVE_VARS,
    WIND_VARS,
    CleaningPolicy,
    HindcastError,
    hindcast_dataset,
    power_law_lift,
    validate_hindcast,
    wind_from_uv,
)

__all__ = [
    "WindColumns",
    "ColumnPlan",
    "WAVE_ALIASES",
    "read_table",
    "plan_columns",
    "read_hindcast",
    "period_bounds",
]

log = logging.getLogger("moorlife.io.hindcast")

#: Recognised names of the wave variables, in order of preference.
WAVE_ALIASES: dict[str, tuple[str, ...]] = {
    "hs": ("hs", "swh", "Hs", "hm0", "VHM0"),
    "tp": ("tp", "pp1d", "Tp", "VTPK"),
    "wave_dir": ("Pdir", "mwd", "wave_dir", "thq", "VMDR", "mdir"),
}
_SPEED_DIR_GENERIC: tuple[tuple[str, str], ...] = (
    ("wind_speed", "wind_dir"),
    ("wind_speed", "wind_direction"),
    ("ws", "wd"),
)
_MAP_KEYS = frozenset({"hs", "tp", "wave_dir", "wind_speed", "wind_dir", "wind_u", "wind_v"})
_SUFFIX_FORMAT = {".csv": "csv", ".txt": "csv", ".nc": "netcdf", ".nc4": "netcdf", ".cdf": "netcdf", ".zarr": "zarr"}


@dataclass(frozen=True)
class WindColumns:
    """Where the wind is in a file: speed + direction columns, or u + v components."""

    kind: str  # "speed_dir" or "uv"
    first: str  # speed or u
    second: str  # direction or v
    height: float  # m above sea level

    @property
    def label(self) -> str:
        return f"{self.first}/{self.second}"


@dataclass(frozen=True)
class ColumnPlan:
    """The file columns chosen for each contract variable."""

    waves: dict[str, str]
    wind: WindColumns | None
    wind_heights: tuple[float, ...]


# ------------------------------------------------------------------------------------ reading
def _header_position(lines: list[str]) -> tuple[float | None, float | None]:
    text = " ".join(lines)
    lon = re.search(r"LONGITUDE\s*:\s*(-?[\d.]+)", text, re.I)
    lat = re.search(r"LATITUDE\s*:\s*(-?[\d.]+)", text, re.I)
    return (float(lon.group(1)) if lon else None, float(lat.group(1)) if lat else None)


def _read_csv(path: Path) -> tuple[pd.DataFrame, np.ndarray, dict[str, Any]]:
    header: list[str] = []
    columns: list[str] | None = None
    try:
        # utf-8-sig: a byte-order mark before the first '#' line is not part of the text
        with path.open("r", encoding="utf-8-sig") as fh:
            for line in fh:
                if line.startswith("#"):
                    header.append(line.rstrip("\r\n"))
                else:
                    columns = [c.strip() for c in line.rstrip("\r\n").split(",")]
                    break
    except UnicodeDecodeError:
        raise HindcastError(
            f"{path}: not a CSV text file (not UTF-8 text); give a CSV, NetCDF or Zarr hindcast (hindcast.format)"
        ) from None
    if columns is not None:
        dup = sorted({c for c in columns if c and columns.count(c) > 1})
        if dup:
            raise HindcastError(
                f"{path}: duplicated column name(s) {dup} in the header row; each column must be named once"
            )
    try:
        df = pd.read_csv(path, skiprows=len(header), skip_blank_lines=False, dtype={"time": str}, encoding="utf-8-sig")
    except pd.errors.EmptyDataError as exc:
        raise HindcastError(f"{path}: the file is empty (no header row, no data)") from exc
    except pd.errors.ParserError as exc:
        m = re.search(r"Expected (\d+) fields in line (\d+), saw (\d+)", str(exc))
        if m:
            line = int(m.group(2))  # pandas counts the skipped header lines too
            raise HindcastError(
                f"{path}: line {line} has {m.group(3)} comma-separated fields, the header row {m.group(1)} "
                "(a ragged row: a missing or extra comma)"
            ) from None
        raise HindcastError(f"{path}: not a comma-separated table (the CSV parser gave up); check the file") from None
    df.columns = [str(c).strip() for c in df.columns]
    lon, lat = _header_position(header)
    meta = {"header": header, "lon": lon, "lat": lat, "row_kind": "line"}
    # file line numbers (1-based): header lines, the column header, then the data rows
    rows = np.arange(len(df)) + len(header) + 2
    return df, rows, meta


def _nearest_point(ds: xr.Dataset, lon: float | None, lat: float | None, path: Path) -> xr.Dataset:
    tname = "time" if "time" in ds.dims else "valid_time"
    if "expver" in ds.dims:  # CDS downloads mixing final ERA5 (expver 1) and preliminary ERA5T (5)
        parts = [ds.isel(expver=i, drop=True) for i in range(ds.sizes["expver"])]
        merged = parts[0]
        for part in parts[1:]:
            merged = merged.combine_first(part)
        log.info("%s: merged the %d 'expver' versions (first non-missing value wins)", path, len(parts))
        ds = merged
    extra = [d for d in ds.dims if d != tname and ds.sizes[d] > 1]
    if extra:
        lat_name = next((n for n in ("latitude", "lat") if n in ds.coords), None)
        lon_name = next((n for n in ("longitude", "lon") if n in ds.coords), None)
        if lat_name is None or lon_name is None or lon is None or lat is None:
            raise HindcastError(
                f"{path}: dimension(s) {extra} have more than one point and no latitude/longitude "
                "coordinates to pick the site's point; extract a single point first"
            )
        lon_c = float(lon) % 360.0 if float(ds[lon_name].max()) > 180.0 else float(lon)
        ds = ds.sel({lat_name: lat, lon_name: lon_c}, method="nearest")
        log.info(
            "%s: took the grid point nearest the site (%.3f E, %.3f N): %.3f E, %.3f N",
            path,
            lon,
            lat,
            float(ds[lon_name]),
            float(ds[lat_name]),
        )
        extra = [d for d in ds.dims if d != tname and ds.sizes[d] > 1]
        if extra:
            raise HindcastError(f"{path}: dimension(s) {extra} remain after selecting the site; expected time only")
    return ds.squeeze(drop=False)


def _read_xarray(
    path: Path, fmt: str, lon: float | None, lat: float | None
) -> tuple[pd.DataFrame, np.ndarray, dict[str, Any]]:
    try:
        if fmt == "zarr":
            ds = xr.open_zarr(path, consolidated=False)
        else:
            ds = xr.open_dataset(path)
    except Exception as exc:
        raise HindcastError(f"{path}: cannot be read as {fmt} ({exc})") from exc
    with ds:
        tname = next((n for n in ("time", "valid_time") if n in ds.dims), None)
        if tname is None:
            raise HindcastError(f"{path}: no 'time' or 'valid_time' dimension (dimensions: {dict(ds.sizes)})")
        ds = _nearest_point(ds, lon, lat, path)
        names = [v for v in ds.data_vars if ds[v].dims == (tname,)]
        df = pd.DataFrame({v: ds[v].values for v in names})
        df.insert(0, "time", ds[tname].values)
        plon = next((float(ds[n]) for n in ("longitude", "lon") if n in ds.coords and ds[n].size == 1), None)
        plat = next((float(ds[n]) for n in ("latitude", "lat") if n in ds.coords and ds[n].size == 1), None)
    return df, np.arange(len(df)), {"header": [], "lon": plon, "lat": plat, "row_kind": "time index"}


def read_table(
    path: str | os.PathLike[str], fmt: str = "auto", lon: float | None = None, lat: float | None = None
) -> tuple[pd.DataFrame, np.ndarray, dict[str, Any]]:
    """Read a hindcast file into a raw table, with no interpretation of the columns.

    Returns
    -------
    df : pandas.DataFrame
        A ``time`` column and the file's columns (CSV values as strings).
    rows : numpy.ndarray of int, shape (len(df),)
        Each row's position in the file (CSV: 1-based line number; NetCDF/Zarr: time index).
    meta : dict
        ``header`` (CSV ``#`` lines), ``lon``/``lat`` found in the file (or None), ``format``.
    """
    p = Path(path)
    if not p.exists():
        raise HindcastError(f"{p}: no such hindcast file")
    if fmt == "auto":
        fmt = _SUFFIX_FORMAT.get(p.suffix.lower(), "")
        if not fmt:
            raise HindcastError(
                f"{p}: cannot tell the format from the suffix {p.suffix!r}; set hindcast.format (csv, netcdf, zarr)"
            )
    if fmt == "csv":
        df, rows, meta = _read_csv(p)
        if "time" not in df.columns:
            # the header is not echoed: a wrong path may name a file with secrets in it
            raise HindcastError(
                f"{p}: missing column 'time': expected a header row with a 'time' column and the wave and "
                f"wind columns (e.g. time, hs, tp, Pdir, wind_speed_100m, wind_direction_100m; see "
                f"moorlife.io.hindcast), after any '#' header lines; the file's header has {len(df.columns)} "
                "field(s), none of them 'time'"
            )
    elif fmt in ("netcdf", "zarr"):
        df, rows, meta = _read_xarray(p, fmt, lon, lat)
    else:
        raise HindcastError(f"{p}: unknown hindcast.format {fmt!r} (csv, netcdf, zarr)")
    if len(df) == 0:
        raise HindcastError(f"{p}: the file holds no data rows")
    meta["format"] = fmt
    return df, rows, meta


# ---------------------------------------------------------------------------- column planning
def _find(cols: list[str], names: tuple[str, ...]) -> str | None:
    for n in names:
        if n in cols:
            return n
    lower = {c.lower(): c for c in cols}
    for n in names:
        if n.lower() in lower:
            return lower[n.lower()]
    return None


def _wind_candidates(cols: list[str], measured_height: float | None) -> list[WindColumns]:
    cset = set(cols)
    out: list[WindColumns] = []
    for c in cols:
        m = re.fullmatch(r"wind_speed_(\d+(?:\.\d+)?)m", c)
        if m and f"wind_direction_{m.group(1)}m" in cset:
            out.append(WindColumns("speed_dir", c, f"wind_direction_{m.group(1)}m", float(m.group(1))))
        m = re.fullmatch(r"u(\d+)", c)
        if m and f"v{m.group(1)}" in cset:
            out.append(WindColumns("uv", c, f"v{m.group(1)}", float(m.group(1))))
    if "si10" in cset and "dwi" in cset:
        out.append(WindColumns("speed_dir", "si10", "dwi", 10.0))
    if not out:
        for s, d in _SPEED_DIR_GENERIC:
            if s in cset and d in cset:
                if measured_height is None:
                    raise HindcastError(f"wind columns '{s}'/'{d}' carry no height: set hindcast.measured_height (m)")
                out.append(WindColumns("speed_dir", s, d, float(measured_height)))
                break
    return out


def plan_columns(
    columns: list[str],
    column_map: Mapping[str, str] | None,
    hub_height: float,
    measured_height: float | None = None,
) -> ColumnPlan:
    """Choose the file column of each contract variable (pure: names in, plan out).

    Parameters
    ----------
    columns : list of str
        The file's column names.
    column_map : mapping, optional
        ``hindcast.columns``: explicit names, which win over the recognised ones.
    hub_height : float
        m; among several wind heights the nearest is chosen.
    measured_height : float, optional
        Height (m) of mapped or generic wind columns.

    Raises
    ------
    HindcastError
        A mapped column is absent, or a wave variable cannot be found.
    """
    cmap = {k: v for k, v in dict(column_map or {}).items() if v}
    bad = sorted(set(cmap) - _MAP_KEYS)
    if bad:
        raise HindcastError(f"hindcast.columns: unknown key(s) {bad}; allowed {sorted(_MAP_KEYS)}")
    for k, c in cmap.items():
        if c not in columns:
            raise HindcastError(f"hindcast.columns.{k} = {c!r} is not a column of the file; found {columns}")
    waves: dict[str, str] = {}
    missing = []
    for v in WAVE_VARS:
        c = cmap.get(v) or _find(columns, WAVE_ALIASES[v])
        if c is None:
            missing.append(f"{v} (looked for {', '.join(WAVE_ALIASES[v])})")
        else:
            waves[v] = c
    if missing:
        raise HindcastError(f"missing column(s): {'; '.join(missing)}; found {columns}. Map them with hindcast.columns")
    wind: WindColumns | None = None
    heights: tuple[float, ...] = ()
    if "wind_speed" in cmap or "wind_dir" in cmap or "wind_u" in cmap or "wind_v" in cmap:
        pair = ("wind_speed", "wind_dir") if ("wind_speed" in cmap or "wind_dir" in cmap) else ("wind_u", "wind_v")
        if not all(k in cmap for k in pair):
            raise HindcastError(f"hindcast.columns: give both {pair[0]} and {pair[1]}")
        if measured_height is None:
            raise HindcastError("hindcast.columns maps the wind: set hindcast.measured_height (m) too")
        kind = "speed_dir" if pair[0] == "wind_speed" else "uv"
        wind = WindColumns(kind, cmap[pair[0]], cmap[pair[1]], float(measured_height))
        heights = (wind.height,)
    else:
        cands = _wind_candidates(columns, measured_height)
        if cands:
            heights = tuple(sorted({c.height for c in cands}))
            wind = min(cands, key=lambda c: (abs(c.height - hub_height), -c.height, c.kind != "speed_dir"))
    return ColumnPlan(waves=waves, wind=wind, wind_heights=heights)


def _is_nora3(meta: Mapping[str, Any], columns: list[str]) -> bool:
    return any("NORA3" in h.upper() for h in meta.get("header", [])) or {"thq", "Pdir", "hs_swell"} <= set(columns)


# ------------------------------------------------------------------------------------ checks
#: a UTC offset after the time of day (a date alone, 2000-01-01, ends in "-01" but has none)
_TZ = re.compile(r"\d{2}:\d{2}(?::\d{2}(?:\.\d+)?)?\s*(?:Z|UTC|GMT|[+-]\d{2}(?::?\d{2})?)$", re.I)


def period_bounds(start: Any, end: Any) -> tuple[pd.Timestamp, pd.Timestamp]:
    """``hindcast.start`` and ``hindcast.end`` as naive UTC timestamps, naming the key when unreadable."""
    out = []
    for key, value in (("start", start), ("end", end)):
        try:
            t = pd.Timestamp(value)
        except (ValueError, TypeError):
            raise HindcastError(
                f"config key 'hindcast.{key}' = {value!r} is not an ISO 8601 time (e.g. '2000-01-01T00:00')"
            ) from None
        if t is pd.NaT:
            raise HindcastError(f"config key 'hindcast.{key}' = {value!r} is not an ISO 8601 time")
        if t.tzinfo is not None:
            t = t.tz_convert("UTC").tz_localize(None)
        out.append(t)
    return out[0], out[1]


def _utc_times(col: pd.Series, p: Path, rows: np.ndarray) -> pd.Series:
    """Timestamps with a UTC offset converted to naive UTC (ISO text); others unchanged.

    Unparsable values are kept as they are, for the validation to name.
    """
    if pd.api.types.is_datetime64_any_dtype(col.dtype):
        if getattr(col.dt, "tz", None) is not None:
            return col.dt.tz_convert("UTC").dt.tz_localize(None)
        return col
    text = col.astype(str).str.strip()
    aware = text.str.contains(_TZ) & col.notna().to_numpy()
    if not aware.any():
        return col
    naive = ~aware & col.notna() & (text != "")
    if naive.any():
        i, j = int(np.flatnonzero(aware.to_numpy())[0]), int(np.flatnonzero(naive.to_numpy())[0])
        raise HindcastError(
            f"{p}: column 'time' mixes timestamps with a UTC offset (row {rows[i]}: {text.iloc[i]!r}) and without "
            f"one (row {rows[j]}: {text.iloc[j]!r}); give every timestamp in UTC"
        )
    parsed = pd.to_datetime(text, utc=True, errors="coerce", format="mixed")
    out = col.astype(object).copy()
    ok = parsed.notna().to_numpy()
    out[ok] = parsed[ok].dt.tz_localize(None).dt.strftime("%Y-%m-%dT%H:%M:%S").to_numpy()
    log.info("%s: column 'time': %d timestamp(s) with a UTC offset converted to UTC", p, int(ok.sum()))
    return out


def _refuse_infinite(std: pd.DataFrame, labels: Mapping[str, str], p: Path, rows: np.ndarray) -> None:
    """Infinite values are not gaps and would survive the cleaning (a wrapped inf is NaN)."""
    for v in std.columns:
        if v == "time":
            continue
        x = pd.to_numeric(pd.Series(std[v]), errors="coerce").to_numpy(dtype=float)
        inf = np.isinf(x)
        if inf.any():
            i = int(np.flatnonzero(inf)[0])
            raise HindcastError(
                f"{p}: column '{labels.get(v, v)}' (variable {v}), row {rows[i]}: value {x[i]:g} is not finite "
                f"({int(inf.sum())} such row(s))"
            )


def _apply_sea_state_policy(
    std: pd.DataFrame,
    labels: Mapping[str, str],
    p: Path,
    rows: np.ndarray,
    policy: str,
    cleaning: CleaningPolicy | None,
) -> pd.DataFrame:
    """Refuse, drop (make gaps of) or clip the sea states beyond the breaking steepness or the Tp floor."""
    if policy not in SEA_STATE_POLICIES:
        raise HindcastError(f"hindcast.cleaning.sea_states = {policy!r}: expected one of {list(SEA_STATE_POLICIES)}")
    hs = pd.to_numeric(pd.Series(std["hs"]), errors="coerce").to_numpy(dtype=float)
    tp = pd.to_numeric(pd.Series(std["tp"]), errors="coerce").to_numpy(dtype=float)
    lim = getattr(cleaning, "limits", None)
    with np.errstate(invalid="ignore"):  # values beyond the unit limits: the validation names them
        units = (hs > getattr(lim, "hs_max", np.inf)) | (tp > getattr(lim, "tp_max", np.inf))
    rep = check_sea_states(np.where(units, np.nan, hs), tp)
    bad = np.flatnonzero(rep.bad)
    if bad.size == 0:
        return std
    where = f"columns '{labels.get('hs', 'hs')}'/'{labels.get('tp', 'tp')}'"
    if policy == "error":
        i = int(bad[0])
        raise HindcastError(
            f"{p}: {where}, row {rows[i]} (time {std['time'].iloc[i]}): hs = {hs[i]:g} m, tp = {tp[i]:g} s is not "
            f"a possible sea state: {rep.reason(i)} ({bad.size} such row(s); Tp floor {TP_FLOOR:g} s, "
            f"breaking steepness 1/{1 / BREAKING_STEEPNESS:g}; set hindcast.cleaning.sea_states: drop or clip)"
        )
    out = std.copy()
    if policy == "drop":
        for i in bad:
            log.warning(
                "%s: row %s (time %s): dropped hs = %g m, tp = %g s (%s); the hour becomes a gap",
                p,
                rows[i],
                std["time"].iloc[i],
                hs[i],
                tp[i],
                rep.reason(int(i)),
            )
        out["hs"] = np.where(rep.bad, np.nan, hs)
        out["tp"] = np.where(rep.bad, np.nan, tp)
        return out
    new_tp = clipped_tp(hs, tp)
    for i in bad:
        log.warning(
            "%s: row %s (time %s): clipped tp %g -> %.4g s for hs = %g m (%s)",
            p,
            rows[i],
            std["time"].iloc[i],
            tp[i],
            new_tp[i],
            hs[i],
            rep.reason(int(i)),
        )
    keep_raw = ~rep.bad  # leave the untouched cells as they were (their own checks name them)
    out["tp"] = np.where(keep_raw, std["tp"].to_numpy(dtype=object), new_tp)
    return out


# -------------------------------------------------------------------------------------- public
def read_hindcast(
    path: str | os.PathLike[str],
    *,
    start: str,
    end: str,
    hub_height: float,
    shear_exponent: float,
    columns: Mapping[str, str] | None = None,
    fmt: str = "auto",
    measured_height: float | None = None,
    wave_dir_convention: str = "auto",
    cleaning: CleaningPolicy | None = None,
    sea_states: str | None = None,
    site: str = "",
    lon: float | None = None,
    lat: float | None = None,
    base_dir: str | os.PathLike[str] = ".",
    require_wind: bool = True,
    require_varying: bool = True,
) -> xr.Dataset:
    """Load a hindcast file as the contract Dataset over ``start``..``end``.

    Parameters
    ----------
    path : path-like
        CSV, NetCDF or Zarr (relative paths are resolved against ``base_dir``).
    start, end : str
        The study period (ISO 8601, inclusive); the file must cover it and is cut to it.
    hub_height, shear_exponent : float
        Wind is lifted from its (nearest) height to ``hub_height`` with the power law.
    columns : mapping, optional
        ``hindcast.columns`` column map.
    fmt : {"auto", "csv", "netcdf", "zarr"}
    measured_height : float, optional
        Height (m) of mapped or generically named wind columns.
    wave_dir_convention : {"auto", "from", "to"}
        Convention of the file's wave direction; "to" is turned by 180 deg. "auto": "to" for
        NORA3 files, else "from".
    cleaning : CleaningPolicy, optional
        What to do with gaps, duplicates, unsorted rows and out-of-range directions.
    sea_states : {"error", "drop", "clip"}, optional
        What to do with physically impossible sea states (beyond the breaking steepness or below
        the Tp floor, :mod:`moorlife.cleaning`); default ``cleaning.sea_states`` if the policy has
        it, else "error". Every row dropped or clipped is logged.
    site, lon, lat :
        The configured site; ``lon``/``lat`` pick the grid point of gridded files and are
        replaced by the file's position when it states one.
    require_wind : bool
        Raise when the file has no wind (the 5-D selection needs it); if False, return waves only.
    require_varying : bool
        Raise when Hs, Tp or the wind speed is constant over the period (the selection and the
        RBF need each to vary); only with ``require_wind``.

    Timestamps with a UTC offset (``2000-01-01T00:00Z``, ``+01:00``, mixed daylight-saving
    offsets) are converted to UTC; timestamps without one are read as UTC. A file mixing both
    is refused.

    Raises
    ------
    HindcastError
        Every problem, naming the file, the column, the first offending row and the value.
    """
    p = Path(path)
    if not p.is_absolute():
        p = Path(base_dir) / p
    df, rows, meta = read_table(p, fmt, lon, lat)
    cols = [c for c in df.columns if c != "time"]
    try:
        plan = plan_columns(cols, columns, hub_height, measured_height)
    except HindcastError as exc:
        raise HindcastError(f"{p}: {exc}") from None
    if plan.wind is None and require_wind:
        raise HindcastError(
            f"{p}: the file holds waves only (columns {cols}); wind speed and direction are required "
            "(hub-height wind is one of the five sea-state variables). Use a file with wind "
            "(wind_speed_<h>m/wind_direction_<h>m, u10/v10, u100/v100) or map its wind columns with "
            "hindcast.columns and hindcast.measured_height"
        )

    df = df.assign(time=_utc_times(df["time"], p, rows))
    times = pd.to_datetime(df["time"], errors="coerce")
    t0, t1 = period_bounds(start, end)
    valid = times.dropna()
    if valid.empty:
        raise HindcastError(f"{p}: column 'time': no parsable timestamp (first value {df['time'].iloc[0]!r})")
    if valid.min() > t0 or valid.max() < t1:
        raise HindcastError(
            f"{p}: the study period {t0} .. {t1} (hindcast.start/end) is not inside the file's span "
            f"{valid.min()} .. {valid.max()}; change hindcast.start/end or use a longer file"
        )
    keep = (times.isna() | ((times >= t0) & (times <= t1))).to_numpy()
    sub = df.loc[keep]
    std = pd.DataFrame({"time": sub["time"].to_numpy()})
    labels: dict[str, str] = {}
    for v, c in plan.waves.items():
        std[v], labels[v] = sub[c].to_numpy(), c
    if plan.wind is not None:
        w = plan.wind
        a = pd.to_numeric(sub[w.first], errors="coerce").to_numpy(dtype=float)
        b = pd.to_numeric(sub[w.second], errors="coerce").to_numpy(dtype=float)
        if w.kind == "uv":
            for c, x in ((w.first, a), (w.second, b)):
                nonnum = np.isnan(x) & sub[c].notna().to_numpy()
                if nonnum.any():
                    i = int(np.flatnonzero(nonnum)[0])
                    raise HindcastError(f"{p}: column '{c}', row {rows[keep][i]}: {sub[c].iloc[i]!r} is not a number")
            speed, direction = wind_from_uv(a, b)
            std["wind_speed"], std["wind_dir"] = speed, direction
            labels["wind_speed"] = labels["wind_dir"] = w.label
        else:
            std["wind_speed"], std["wind_dir"] = sub[w.first].to_numpy(), sub[w.second].to_numpy()
            labels["wind_speed"], labels["wind_dir"] = w.first, w.second
    require = WAVE_VARS + (WIND_VARS if plan.wind is not None else ())
    _refuse_infinite(std, labels, p, rows[keep])
    policy = sea_states if sea_states is not None else getattr(cleaning, "sea_states", "error")
    std = _apply_sea_state_policy(std, labels, p, rows[keep], policy, cleaning or CleaningPolicy.from_config({}))
    clean = validate_hindcast(
        std, source=str(p), policy=cleaning, labels=labels, rows=rows[keep], require=require, period=(t0, t1)
    )
    # the scalar coordinates of the 5-D selection (a constant direction is harmless: its scale is fixed)
    const = constant_columns({v: clean[v].to_numpy() for v in ("hs", "tp", "wind_speed") if v in clean})
    if const and require_wind and require_varying:
        v = const[0]
        raise HindcastError(
            f"{p}: column '{labels.get(v, v)}' (variable {v}) is constant, {float(clean[v].iloc[0]):g}, over "
            f"the study period {t0} .. {t1}: Hs, Tp and the wind speed must vary (the selection "
            "normalises each by its range and the RBF reconstruction cannot fit a constant coordinate); "
            "check the file's column, or hindcast.columns"
        )

    convention = wave_dir_convention
    if convention == "auto":
        convention = "to" if _is_nora3(meta, cols) else "from"
    if convention == "to":
        clean["wave_dir"] = (clean["wave_dir"] + 180.0) % 360.0
        log.info("%s: wave direction '%s' is 'going to': turned by 180 deg to 'coming from'", p, plan.waves["wave_dir"])
    elif convention != "from":
        raise HindcastError(f"hindcast.wave_dir_convention = {wave_dir_convention!r}: expected auto, from or to")

    extra: dict[str, Any] = {
        "source_file": str(p),
        "source_format": meta["format"],
        "source_columns": ", ".join(f"{v}={labels[v]}" for v in labels),
        "source_wave_dir_convention": convention,
        "shear_exponent": float(shear_exponent),
    }
    if plan.wind is not None:
        h = plan.wind.height
        clean["wind_speed"] = power_law_lift(clean["wind_speed"].to_numpy(), h, hub_height, shear_exponent)
        extra["wind_measured_height"] = h
        log.info(
            "%s: wind %s at %g m (heights available: %s) lifted to %g m with exponent %g",
            p,
            plan.wind.label,
            h,
            ", ".join(f"{x:g}" for x in plan.wind_heights),
            hub_height,
            shear_exponent,
        )
    flon, flat = meta.get("lon"), meta.get("lat")
    if flon is not None and flat is not None:
        if lon is not None and lat is not None and np.hypot(float(lon) - flon, float(lat) - flat) > 0.5:
            log.warning(
                "%s: file position (%.3f E, %.3f N) differs from hindcast.site (%.3f E, %.3f N)",
                p,
                flon,
                flat,
                lon,
                lat,
            )
        lon, lat = flon, flat
    ds = hindcast_dataset(
        clean.index.to_numpy(),
        {c: clean[c].to_numpy() for c in clean.columns},
        source=f"file {p}",
        site=site,
        lon=np.nan if lon is None else float(lon),
        lat=np.nan if lat is None else float(lat),
        hub_height=hub_height,
        extra_attrs=extra,
    )
    log.info(
        "%s: %d hours %s .. %s, mean Hs %.2f m%s",
        p,
        ds.sizes["time"],
        clean.index[0],
        clean.index[-1],
        float(ds["hs"].mean()),
        f", mean wind {float(ds['wind_speed'].mean()):.2f} m/s at {hub_height:g} m" if "wind_speed" in ds else "",
    )
    return ds
