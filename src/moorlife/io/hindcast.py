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
    with path.open("r", encoding="utf-8", errors="replace") as fh:
        for line in fh:
            if line.startswith("#"):
                header.append(line.rstrip("\n"))
            else:
                break
    try:
        df = pd.read_csv(path, skiprows=len(header), skip_blank_lines=False, dtype={"time": str})
    except pd.errors.EmptyDataError as exc:
        raise HindcastError(f"{path}: the file is empty (no header row, no data)") from exc
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
            path, lon, lat, float(ds[lon_name]), float(ds[lat_name]),
        )
        extra = [d for d in ds.dims if d != tname and ds.sizes[d] > 1]
        if extra:
            raise HindcastError(f"{path}: dimension(s) {extra} remain after selecting the site; expected time only")
    return ds.squeeze(drop=False)


def _read_xarray(path: Path, fmt: str, lon: float | None, lat: float | None) -> tuple[pd.DataFrame, np.ndarray, dict[str, Any]]:
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
            raise HindcastError(f"{p}: missing column 'time' (columns: {list(df.columns)})")
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
                    raise HindcastError(
                        f"wind columns '{s}'/'{d}' carry no height: set hindcast.measured_height (m)"
                    )
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
        raise HindcastError(
            f"missing column(s): {'; '.join(missing)}; found {columns}. Map them with hindcast.columns"
        )
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
    site: str = "",
    lon: float | None = None,
    lat: float | None = None,
    base_dir: str | os.PathLike[str] = ".",
    require_wind: bool = True,
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
    site, lon, lat :
        The configured site; ``lon``/``lat`` pick the grid point of gridded files and are
        replaced by the file's position when it states one.
    require_wind : bool
        Raise when the file has no wind (the 5-D selection needs it); if False, return waves only.

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

    times = pd.to_datetime(df["time"], errors="coerce")
    t0, t1 = pd.Timestamp(start), pd.Timestamp(end)
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
    clean = validate_hindcast(
        std, source=str(p), policy=cleaning, labels=labels, rows=rows[keep], require=require, period=(t0, t1)
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
            p, plan.wind.label, h, ", ".join(f"{x:g}" for x in plan.wind_heights), hub_height, shear_exponent,
        )
    flon, flat = meta.get("lon"), meta.get("lat")
    if flon is not None and flat is not None:
        if lon is not None and lat is not None and np.hypot(float(lon) - flon, float(lat) - flat) > 0.5:
            log.warning("%s: file position (%.3f E, %.3f N) differs from hindcast.site (%.3f E, %.3f N)", p, flon, flat, lon, lat)
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
        p, ds.sizes["time"], clean.index[0], clean.index[-1], float(ds["hs"].mean()),
        f", mean wind {float(ds['wind_speed'].mean()):.2f} m/s at {hub_height:g} m" if "wind_speed" in ds else "",
    )
    return ds
