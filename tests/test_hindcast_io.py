"""Tests of moorlife.io.hindcast: ERA5/NORA3 CSV, NetCDF and Zarr loaders, the column map, and
every bad-input class of issue 3, on small files written here (never /work/shared).

The CSV layouts copy the metocean-api exports of MET-OM/metocean-stats tests/data (header lines,
column names and order), with made-up values."""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from moorlife.io.hindcast import plan_columns, read_hindcast
from moorlife.metocean import CleaningPolicy, HindcastError

HUB, ALPHA = 90.0, 0.14
N = 48
START, END = "2000-01-01T00:00", "2000-01-02T23:00"

NORA3_HEADER = (
    "#NORA3_wave_sub DATA. LONGITUDE:1.3358, LATITUDE:53.3249\n#NORA3_wind_sub DATA. LONGITUDE:1.32, LATITUDE:53.3237\n"
)
ERA5_HEADER = (
    "#ERA5,LONGITUDE:109.939,LATITUDE:15.509,\n"
    "#Variable_name,standard_name,long_name,units\n"
    "#pp1d,-,Peak wave period,s\n"
    "#swh,-,Significant height of combined wind waves and swell,m\n"
    "#mwd,-,Mean wave direction,Degree true\n"
)


def nora3_frame(n: int = N) -> pd.DataFrame:
    """A NORA3-like table: wind at 10/100/250 m, Pdir (going to), hs, tp, and sea parts."""
    k = np.arange(n)
    t = pd.date_range("2000-01-01", periods=n, freq="h")
    return pd.DataFrame(
        {
            "time": t.strftime("%Y-%m-%d %H:%M:%S"),
            "wind_speed_10m": 8.0 + 0.05 * k,
            "wind_direction_10m": (200.0 + k) % 360,
            "wind_speed_100m": 10.0 + 0.05 * k,
            "wind_direction_100m": (205.0 + k) % 360,
            "wind_speed_250m": 12.0 + 0.05 * k,
            "wind_direction_250m": (210.0 + k) % 360,
            "Pdir": (100.0 + 2 * k) % 360,
            "hs": 1.0 + 0.02 * k,
            "hs_sea": 0.8 + 0.01 * k,
            "thq": (95.0 + k) % 360,
            "tp": 6.0 + 0.05 * k,
        }
    )


def write_csv(path: Path, df: pd.DataFrame, header: str = NORA3_HEADER) -> Path:
    path.write_text(header + df.to_csv(index=False))
    return path


def load(path, **kw):
    kw.setdefault("start", START)
    kw.setdefault("end", END)
    # several fixtures below hold a constant column (a 48-hour table); the constant-input check
    # is tested on its own (test_constant_input_refused)
    kw.setdefault("require_varying", False)
    return read_hindcast(path, hub_height=HUB, shear_exponent=ALPHA, **kw)


def data_line(path: Path, row_in_frame: int, header: str = NORA3_HEADER) -> int:
    """1-based file line of a data row."""
    return header.count("\n") + 2 + row_in_frame


# ------------------------------------------------------------------------------ happy paths
def test_nora3_csv_nearest_height_and_direction_convention(tmp_path):
    df = nora3_frame()
    p = write_csv(tmp_path / "nora3.csv", df)
    ds = load(p)
    assert ds.sizes["time"] == N
    np.testing.assert_allclose(ds["hs"], df["hs"])
    np.testing.assert_allclose(ds["tp"], df["tp"])
    # 100 m is the height nearest 90 m, lifted with the power law
    np.testing.assert_allclose(ds["wind_speed"], df["wind_speed_100m"] * 0.9**ALPHA, rtol=1e-12)
    np.testing.assert_allclose(ds["wind_dir"], df["wind_direction_100m"])
    # NORA3 Pdir is "going to": turned into "coming from"
    np.testing.assert_allclose(ds["wave_dir"], (df["Pdir"] + 180.0) % 360.0)
    assert ds.attrs["wind_measured_height"] == 100.0
    assert ds.attrs["lon"] == pytest.approx(1.3358) and ds.attrs["lat"] == pytest.approx(53.3249)
    assert ds["time"].dtype == np.dtype("datetime64[ns]")
    # a low hub picks the 10 m wind instead
    low = read_hindcast(p, start=START, end=END, hub_height=15.0, shear_exponent=ALPHA)
    np.testing.assert_allclose(low["wind_speed"], df["wind_speed_10m"] * 1.5**ALPHA, rtol=1e-12)
    # the convention can be forced
    same = load(p, wave_dir_convention="from")
    np.testing.assert_allclose(same["wave_dir"], df["Pdir"])


def test_csv_cut_to_period_and_outside_period(tmp_path):
    p = write_csv(tmp_path / "nora3.csv", nora3_frame())
    ds = load(p, start="2000-01-01T06:00", end="2000-01-01T17:00")
    assert ds.sizes["time"] == 12
    assert str(ds["time"].values[0])[:16] == "2000-01-01T06:00"
    with pytest.raises(HindcastError, match=r"not inside the file's span 2000-01-01 00:00:00 \.\. 2000-01-02 23:00:00"):
        load(p, start="1999-12-31T00:00", end="2000-01-01T05:00")
    with pytest.raises(HindcastError, match="nora3.csv"):
        load(p, start="2000-01-02T00:00", end="2000-01-03T00:00")


def test_era5_waves_only_needs_wind(tmp_path):
    t = pd.date_range("2000-01-01", periods=N, freq="h")
    df = pd.DataFrame({"time": t.strftime("%Y-%m-%d %H:%M:%S"), "pp1d": 7.2, "swh": 1.3, "mwd": 49.7})
    p = write_csv(tmp_path / "era5.csv", df, ERA5_HEADER)
    with pytest.raises(
        HindcastError, match=r"era5\.csv: the file holds waves only .*wind speed and direction are required"
    ):
        load(p)
    ds = load(p, require_wind=False)
    assert set(ds.data_vars) == {"hs", "tp", "wave_dir"}
    np.testing.assert_allclose(ds["wave_dir"], 49.7)  # ERA5 mwd is already "coming from"


def _era5_netcdf(tmp_path: Path, *, grid: bool = False, time_name: str = "time") -> tuple[Path, dict]:
    t = pd.date_range("2000-01-01", periods=N, freq="h")
    k = np.arange(N, dtype=float)
    v = {
        "swh": 1.0 + 0.01 * k,
        "pp1d": 8.0 + 0.01 * k,
        "mwd": np.full(N, 315.0),
        "u10": np.full(N, 6.0),
        "v10": np.full(N, 8.0),
        "u100": np.full(N, 9.0),
        "v100": np.full(N, 12.0),
    }
    if grid:
        lat, lon = np.array([43.0, 43.5, 44.0]), np.array([-3.5, -3.0, -2.5])
        shape = (N, 3, 3)
        data = {}
        for name, x in v.items():
            arr = np.zeros(shape) + x[:, None, None]
            arr[:, 1, 1] = x  # the site's grid point
            arr[:, 0, 0] = -999.0  # another point, must not be picked
            data[name] = ((time_name, "latitude", "longitude"), arr)
        ds = xr.Dataset(data, coords={time_name: t, "latitude": lat, "longitude": lon})
    else:
        ds = xr.Dataset({name: (time_name, x) for name, x in v.items()}, coords={time_name: t})
    p = tmp_path / "era5.nc"
    ds.to_netcdf(p)
    return p, v


def test_era5_netcdf_uv_nearest_height(tmp_path):
    p, v = _era5_netcdf(tmp_path)
    ds = load(p)
    np.testing.assert_allclose(ds["wind_speed"], 15.0 * 0.9**ALPHA)  # |(9, 12)| at 100 m
    np.testing.assert_allclose(ds["wind_dir"], (np.degrees(np.arctan2(-9.0, -12.0))) % 360.0)
    assert ds["wind_dir"].values[0] == pytest.approx(216.87, abs=0.01)
    np.testing.assert_allclose(ds["hs"], v["swh"])
    assert ds.attrs["wind_measured_height"] == 100.0


def test_netcdf_gridded_valid_time_picks_site(tmp_path):
    p, v = _era5_netcdf(tmp_path, grid=True, time_name="valid_time")
    ds = load(p, lon=-2.9, lat=43.55)
    np.testing.assert_allclose(ds["hs"], v["swh"])
    assert ds.attrs["lon"] == -3.0 and ds.attrs["lat"] == 43.5
    with pytest.raises(HindcastError, match="more than one point"):
        load(p)  # no site position given


def test_netcdf_era5_expver_merged(tmp_path):
    t = pd.date_range("2000-01-01", periods=N, freq="h")
    half = N // 2

    def two(x):
        a = np.full((N, 2), np.nan)
        a[:half, 0], a[half:, 1] = x[:half], x[half:]  # ERA5 then ERA5T
        return (("time", "expver"), a)

    k = np.arange(N, dtype=float)
    ds0 = xr.Dataset(
        {
            "swh": two(1.0 + 0.01 * k),
            "pp1d": two(np.full(N, 9.0)),
            "mwd": two(np.full(N, 300.0)),
            "u10": two(np.full(N, 3.0)),
            "v10": two(np.full(N, 4.0)),
        },
        coords={"time": t, "expver": [1, 5]},
    )
    p = tmp_path / "expver.nc"
    ds0.to_netcdf(p)
    ds = load(p)
    np.testing.assert_allclose(ds["hs"], 1.0 + 0.01 * k)
    np.testing.assert_allclose(ds["wind_speed"], 5.0 * 9.0**ALPHA)


def test_zarr_generic_speed_direction_needs_height(tmp_path):
    t = pd.date_range("2000-01-01", periods=N, freq="h")
    ds0 = xr.Dataset(
        {
            "hs": ("time", np.full(N, 2.0)),
            "tp": ("time", np.full(N, 10.0)),
            "mwd": ("time", np.full(N, 300.0)),
            "wind_speed": ("time", np.full(N, 10.0)),
            "wind_direction": ("time", np.full(N, 270.0)),
        },
        coords={"time": t},
    )
    p = tmp_path / "h.zarr"
    ds0.to_zarr(p, consolidated=False)
    with pytest.raises(HindcastError, match="measured_height"):
        load(p)
    ds = load(p, measured_height=10.0)
    np.testing.assert_allclose(ds["wind_speed"], 10.0 * 9.0**ALPHA)
    np.testing.assert_allclose(ds["wind_dir"], 270.0)


def test_column_map(tmp_path):
    t = pd.date_range("2000-01-01", periods=N, freq="h")
    df = pd.DataFrame(
        {"time": t.strftime("%Y-%m-%dT%H:%M"), "Hsig": 1.5, "Tpeak": 11.0, "Dir": 310.0, "U": 3.0, "V": -4.0}
    )
    p = write_csv(tmp_path / "custom.csv", df, "")
    cols = {"hs": "Hsig", "tp": "Tpeak", "wave_dir": "Dir", "wind_u": "U", "wind_v": "V"}
    ds = load(p, columns=cols, measured_height=90.0)
    np.testing.assert_allclose(ds["wind_speed"], 5.0)
    np.testing.assert_allclose(ds["wind_dir"], (np.degrees(np.arctan2(-3.0, 4.0))) % 360)
    np.testing.assert_allclose(ds["hs"], 1.5)
    with pytest.raises(HindcastError, match=r"hindcast.columns.tp = 'Tp_missing' is not a column"):
        load(p, columns=dict(cols, tp="Tp_missing"), measured_height=90.0)
    with pytest.raises(HindcastError, match="measured_height"):
        load(p, columns=cols)


def test_plan_columns_prefers_speed_direction_and_nearest():
    cols = ["hs", "tp", "Pdir", "wind_speed_10m", "wind_direction_10m", "wind_speed_150m", "wind_direction_150m"]
    plan = plan_columns(cols, None, hub_height=90.0)
    assert plan.wind.first == "wind_speed_150m" and plan.wind.height == 150.0
    assert plan.wind_heights == (10.0, 150.0)
    plan = plan_columns(cols, None, hub_height=60.0)
    assert plan.wind.first == "wind_speed_10m"  # |60-10| = 50 < |60-150| = 90


# ------------------------------------------------------------------------- bad inputs
def _bad(tmp_path, df, header=NORA3_HEADER, name="bad.csv"):
    return write_csv(tmp_path / name, df, header)


def test_nan_value_error_and_gap_policy(tmp_path, caplog):
    df = nora3_frame()
    df.loc[10, "hs"] = np.nan
    p = _bad(tmp_path, df)
    line = data_line(p, 10)
    with pytest.raises(
        HindcastError,
        match=rf"bad\.csv: column 'hs', row {line} \(time 2000-01-01T10:00:00\): 1 hour\(s\) missing or NaN",
    ):
        load(p)
    with caplog.at_level(logging.WARNING, logger="moorlife"):
        ds = load(p, cleaning=CleaningPolicy.from_config({"max_gap_hours": 1}))
    assert "interpolated 1 gap(s)" in caplog.text and "'hs'" in caplog.text
    assert ds["hs"].values[10] == pytest.approx(0.5 * (df["hs"][9] + df["hs"][11]))


def test_missing_rows_error_and_gap_policy(tmp_path):
    df = nora3_frame().drop(index=[20, 21, 22]).reset_index(drop=True)
    p = _bad(tmp_path, df)
    with pytest.raises(
        HindcastError, match=rf"missing row after row {data_line(p, 19)} \(time 2000-01-01T20:00:00\): 3 hour\(s\)"
    ):
        load(p)
    with pytest.raises(HindcastError, match="max_gap_hours = 2"):
        load(p, cleaning=CleaningPolicy.from_config({"max_gap_hours": 2}))
    ds = load(p, cleaning=CleaningPolicy.from_config({"max_gap_hours": 3}))
    assert ds.sizes["time"] == N
    full = nora3_frame()
    np.testing.assert_allclose(ds["hs"].values[20:23], full["hs"].values[20:23])  # linear data: exact
    # directions interpolate on the circle (wind_direction_100m crosses no wrap here: still linear)
    np.testing.assert_allclose(ds["wind_dir"].values[20:23], full["wind_direction_100m"].values[20:23], atol=1e-9)


def test_direction_interpolation_across_north(tmp_path):
    df = nora3_frame()
    df["wind_direction_100m"] = np.where(np.arange(N) < 11, 350.0, 20.0)
    df.loc[11:12, "wind_direction_100m"] = np.nan  # 350 -> ?, ? -> 20: shorter arc through north
    ds = load(_bad(tmp_path, df), cleaning=CleaningPolicy.from_config({"max_gap_hours": 2}))
    np.testing.assert_allclose(ds["wind_dir"].values[10:14], [350.0, 0.0, 10.0, 20.0], atol=1e-9)


@pytest.mark.parametrize(
    ("column", "value", "pattern"),
    [
        ("hs", 0.0, "value 0 is not > 0"),
        ("hs", -0.5, "value -0.5 is not > 0"),
        ("tp", -3.0, "value -3 is not > 0"),
        ("Pdir", 400.0, r"direction 400 is outside \[0, 360\)"),
        ("wind_direction_100m", -10.0, r"direction -10 is outside \[0, 360\)"),
        ("wind_speed_100m", -1.0, "value -1 is negative"),
        ("hs", "abc", "'abc' is not a number"),
    ],
)
def test_bad_values_name_file_column_row_value(tmp_path, column, value, pattern):
    df = nora3_frame()
    df[column] = df[column].astype(object)
    df.loc[7, column] = value
    p = _bad(tmp_path, df)
    with pytest.raises(HindcastError) as err:
        load(p)
    msg = str(err.value)
    assert str(p) in msg and f"'{column}'" in msg and f"row {data_line(p, 7)}" in msg, msg
    assert "2000-01-01T07:00:00" in msg
    import re

    assert re.search(pattern, msg), msg


def test_wrap_directions_policy_and_360_is_north(tmp_path, caplog):
    df = nora3_frame()
    df.loc[3, "wind_direction_100m"] = 370.0
    df.loc[4, "wind_direction_100m"] = 360.0
    p = _bad(tmp_path, df)
    with pytest.raises(HindcastError, match="wrap_directions"):
        load(p)
    with caplog.at_level(logging.INFO, logger="moorlife"):
        ds = load(p, cleaning=CleaningPolicy.from_config({"wrap_directions": True}))
    assert ds["wind_dir"].values[3] == pytest.approx(10.0)
    assert ds["wind_dir"].values[4] == 0.0
    assert "wrapped 1 direction(s)" in caplog.text and "read as north" in caplog.text


def test_duplicated_timestamps(tmp_path):
    df = nora3_frame()
    df = pd.concat([df.iloc[:6], df.iloc[5:6], df.iloc[6:]], ignore_index=True)
    p = _bad(tmp_path, df)
    with pytest.raises(
        HindcastError, match=rf"column 'time', row {data_line(p, 6)}: duplicated timestamp 2000-01-01 05:00:00"
    ):
        load(p)
    ds = load(p, cleaning=CleaningPolicy.from_config({"duplicates": "first"}))
    assert ds.sizes["time"] == N


def test_unsorted_timestamps(tmp_path):
    df = nora3_frame()
    df = pd.concat([df.iloc[:5], df.iloc[[6, 5]], df.iloc[7:]], ignore_index=True)
    p = _bad(tmp_path, df)
    with pytest.raises(
        HindcastError, match=rf"row {data_line(p, 6)}: 2000-01-01 05:00:00 comes after 2000-01-01 06:00:00"
    ):
        load(p)
    ds = load(p, cleaning=CleaningPolicy.from_config({"unsorted": "sort"}))
    np.testing.assert_allclose(ds["hs"], nora3_frame()["hs"])


def test_non_hourly_steps(tmp_path):
    df = nora3_frame(3 * N)
    t = pd.date_range("2000-01-01", periods=3 * N, freq="3h")
    df["time"] = t.strftime("%Y-%m-%d %H:%M:%S")
    with pytest.raises(HindcastError, match="time step is 3 h"):
        load(_bad(tmp_path, df))
    df = nora3_frame()
    df.loc[9, "time"] = "2000-01-01 09:30:00"
    p = _bad(tmp_path, df, name="half.csv")
    with pytest.raises(
        HindcastError,
        match=rf"half\.csv: column 'time', row {data_line(p, 9)}: 2000-01-01 09:30:00 is not on a whole hour",
    ):
        load(p)


def test_unparsable_time(tmp_path):
    df = nora3_frame()
    df.loc[4, "time"] = "yesterday"
    p = _bad(tmp_path, df)
    with pytest.raises(HindcastError, match=rf"column 'time', row {data_line(p, 4)}: 'yesterday' is not a timestamp"):
        load(p)


def test_empty_and_header_only_files(tmp_path):
    p = tmp_path / "empty.csv"
    p.write_text("")
    with pytest.raises(HindcastError, match=r"empty\.csv: the file is empty"):
        load(p)
    p = tmp_path / "comments.csv"
    p.write_text(NORA3_HEADER)
    with pytest.raises(HindcastError, match=r"comments\.csv: the file is empty"):
        load(p)
    p = tmp_path / "header_only.csv"
    p.write_text(NORA3_HEADER + ",".join(nora3_frame().columns) + "\n")
    with pytest.raises(HindcastError, match=r"header_only\.csv: the file holds no data rows"):
        load(p)


def test_missing_columns(tmp_path):
    p = _bad(tmp_path, nora3_frame().drop(columns=["tp"]))
    with pytest.raises(HindcastError, match=r"bad\.csv: missing column\(s\): tp \(looked for tp, pp1d, Tp, VTPK\)"):
        load(p)
    p = _bad(tmp_path, nora3_frame().drop(columns=["time"]), name="notime.csv")
    with pytest.raises(HindcastError, match=r"notime\.csv: missing column 'time'"):
        load(p)


def test_absurd_units(tmp_path):
    df = nora3_frame()
    df["hs"] = df["hs"] * 100.0  # cm
    p = _bad(tmp_path, df)
    with pytest.raises(
        HindcastError,
        match=rf"column 'hs', row {data_line(p, 0)} .*value 100 exceeds the plausible maximum 25 \(Hs in cm",
    ):
        load(p)
    df = nora3_frame()
    df["wind_speed_100m"] = df["wind_speed_100m"] * 3.6 * 3  # nonsense, e.g. km/h of a storm
    with pytest.raises(HindcastError, match="km/h"):
        load(_bad(tmp_path, df, name="kmh.csv"))
    df = nora3_frame()
    df["Pdir"] = np.radians(df["Pdir"])
    with pytest.raises(HindcastError, match="radians instead of degrees"):
        load(_bad(tmp_path, df, name="rad.csv"))


def test_missing_file_and_unknown_format(tmp_path):
    with pytest.raises(HindcastError, match="no such hindcast file"):
        load(tmp_path / "nope.csv")
    p = tmp_path / "h.xyz"
    p.write_text("x")
    with pytest.raises(HindcastError, match="hindcast.format"):
        load(p)


# ------------------------------------------------------------------ issue 20: policies, UTC, BOM
def _impossible(df):
    df = df.copy()
    df.loc[5, "tp"] = 0.01  # below the Tp floor
    df.loc[9, ["hs", "tp"]] = [20.0, 3.0]  # steepness 1.42
    return df


def test_impossible_sea_states_refused_dropped_or_clipped(tmp_path, caplog):
    from moorlife.cleaning import BREAKING_STEEPNESS, TP_FLOOR, check_sea_states

    df = nora3_frame()
    p = write_csv(tmp_path / "bad.csv", _impossible(df))
    with pytest.raises(
        HindcastError, match=rf"bad\.csv: columns 'hs'/'tp', row {data_line(p, 5)} .*tp = 0\.01 s .*\(2 such row"
    ):
        load(p)
    # drop: the rows become gaps, interpolated within max_gap_hours (else refused as gaps)
    with pytest.raises(HindcastError, match=r"1 hour\(s\) missing or NaN"):
        load(p, sea_states="drop")
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="moorlife.io.hindcast"):
        ds = load(p, sea_states="drop", cleaning=CleaningPolicy.from_config({"max_gap_hours": 1}))
    assert sum("dropped" in r.getMessage() for r in caplog.records) == 2
    np.testing.assert_allclose(ds["tp"][5], 0.5 * (df["tp"][4] + df["tp"][6]))
    np.testing.assert_allclose(ds["hs"][9], 0.5 * (df["hs"][8] + df["hs"][10]))
    # clip: Hs kept, Tp raised to the smallest possible period
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="moorlife.io.hindcast"):
        ds = load(p, sea_states="clip")
    assert sum("clipped tp" in r.getMessage() for r in caplog.records) == 2
    g2pi = 9.80665 / (2 * np.pi)
    assert float(ds["hs"][5]) == df["hs"][5] and float(ds["hs"][9]) == 20.0
    for i, h in ((5, df["hs"][5]), (9, 20.0)):  # the breaking limit binds (above the floor)
        np.testing.assert_allclose(
            float(ds["tp"][i]), max(TP_FLOOR, np.sqrt(h / (g2pi * BREAKING_STEEPNESS))), rtol=1e-12
        )
    assert not check_sea_states(ds["hs"].values, ds["tp"].values).bad.any()
    np.testing.assert_array_equal(np.delete(ds["tp"].values, [5, 9]), np.delete(df["tp"].values, [5, 9]))
    with pytest.raises(HindcastError, match=r"hindcast\.cleaning\.sea_states = 'maybe': expected one of"):
        load(p, sea_states="maybe")


def test_steepness_kernel_limits():
    from moorlife.cleaning import check_sea_states, clipped_tp, steepness

    hs = np.array([1.0, 20.0, 0.1, np.nan, -1.0, 5.0])
    tp = np.array([8.0, 3.0, 0.9, 5.0, 6.0, 4.0])
    rep = check_sea_states(hs, tp)
    np.testing.assert_array_equal(rep.too_steep, [False, True, False, False, False, True])
    np.testing.assert_array_equal(rep.too_short, [False, False, True, False, False, False])
    assert np.isnan(rep.steepness[3]) and np.isnan(rep.steepness[4])  # left to the range checks
    s = steepness(hs, clipped_tp(hs, tp))
    assert np.nanmax(s) <= 1 / 7 and np.isnan(s[3]) and clipped_tp(hs, tp)[4] == 6.0


@pytest.mark.parametrize(
    "stamp",
    [
        lambda t: t.strftime("%Y-%m-%dT%H:%M:%SZ"),  # ERA5 style "Z"
        lambda t: (t + pd.Timedelta(hours=1)).strftime("%Y-%m-%d %H:%M:%S+01:00"),
        # CET/CEST: the offset changes at the end of March (mixed DST offsets in one file)
        lambda t: t.tz_localize("UTC").tz_convert("Europe/Madrid").isoformat(),
    ],
    ids=["Z", "plus_0100", "dst_offsets"],
)
def test_timezone_aware_timestamps_converted_to_utc(tmp_path, stamp):
    t = pd.date_range("2000-03-25", periods=N, freq="h")
    df = nora3_frame().assign(time=[stamp(x) for x in t])
    p = write_csv(tmp_path / "tz.csv", df)
    ds = load(p, start="2000-03-25T00:00", end="2000-03-26T23:00")
    np.testing.assert_array_equal(ds["time"].values, t.values)
    np.testing.assert_allclose(ds["hs"], df["hs"])


def test_bom_before_header_lines(tmp_path):
    """A byte-order mark before the '#' lines (Excel, Windows tools) used to give a ParserError."""
    p = tmp_path / "bom.csv"
    p.write_bytes(b"\xef\xbb\xbf" + (NORA3_HEADER + nora3_frame().to_csv(index=False)).encode())
    ds = load(p)
    assert ds.sizes["time"] == N and ds.attrs["lon"] == 1.3358  # the '#' lines were read


def test_constant_input_refused(tmp_path):
    df = nora3_frame().assign(wind_speed_10m=0.0, wind_speed_100m=0.0, wind_speed_250m=0.0)
    p = write_csv(tmp_path / "calm.csv", df)
    with pytest.raises(
        HindcastError, match=r"calm\.csv: column 'wind_speed_100m' \(variable wind_speed\) is constant, 0"
    ):
        load(p, require_varying=True)
    assert load(p, require_wind=False)["hs"].size == N  # waves-only inspection: not checked
