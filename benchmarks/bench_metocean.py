"""Benchmark: generating and loading the paper's 271,728-hour hindcast (target: < 10 s each).

There is no peer library that builds this hindcast, so the reference times are the floors of
the same work: ``pandas.read_csv`` / ``xarray.open_dataset(...).load()`` of the same file, with
no validation, column planning, wind lifting or Dataset building. Our loaders must stay a small
multiple of them.

Run: ``.venv/bin/python benchmarks/bench_metocean.py``
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

from moorlife.io.hindcast import read_hindcast
from moorlife.metocean import SyntheticParams, build_hindcast, generate_synthetic, hourly_time

START, END = "1985-01-01T00:00", "2015-12-31T23:00"
TARGET_S = 10.0
HEIGHTS = (10, 20, 50, 100, 250, 500, 750)  # as in a NORA3 export


def best_of(fn, repeat: int = 3) -> tuple[float, object]:
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def nora3_like(ds: xr.Dataset) -> pd.DataFrame:
    """A NORA3-shaped table (28 columns) of the synthetic hindcast."""
    t = pd.DatetimeIndex(ds["time"].values)
    cols: dict[str, np.ndarray] = {"time": t.strftime("%Y-%m-%d %H:%M:%S")}
    w90 = ds["wind_speed"].values
    for h in HEIGHTS:
        cols[f"wind_speed_{h}m"] = np.round(w90 * (h / 90.0) ** 0.14, 2)
        cols[f"wind_direction_{h}m"] = np.round(ds["wind_dir"].values, 1)
    cols["Pdir"] = np.round((ds["wave_dir"].values + 180.0) % 360.0, 2)
    for name in ("hs", "hs_sea", "hs_swell", "thq", "thq_sea", "thq_swell", "tm1", "tm2", "tmp"):
        cols[name] = np.round(ds["hs"].values, 2)
    cols["tp"] = np.round(ds["tp"].values, 2)
    for name in ("tp_sea", "tp_swell"):
        cols[name] = cols["tp"]
    return pd.DataFrame(cols)


def main() -> None:
    cfg = {
        "source": "synthetic",
        "start": START,
        "end": END,
        "hub_height": 90.0,
        "shear_exponent": 0.14,
        "site": {"name": "BiMEP", "lon": -2.894, "lat": 43.563},
    }
    time_axis = hourly_time(START, END)
    n = time_axis.size
    print(f"hindcast: {n:,} hourly sea states ({START} .. {END}); target < {TARGET_S:.0f} s each")
    t_gen, _ = best_of(lambda: generate_synthetic(time_axis, SyntheticParams.from_config({}), 20190601, 90.0, 0.14))
    t_build, ds = best_of(lambda: build_hindcast(cfg, 20190601))
    print(f"generate_synthetic (kernel)          {t_gen:7.3f} s")
    print(f"build_hindcast (synthetic + Dataset) {t_build:7.3f} s")

    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        csv = tmp / "nora3_like.csv"
        csv.write_text("#NORA3_wave_sub DATA. LONGITUDE:-2.894, LATITUDE:43.563\n" + nora3_like(ds).to_csv(index=False))
        nc = tmp / "era5_like.nc"
        era5 = xr.Dataset(
            {
                "swh": ds["hs"],
                "pp1d": ds["tp"],
                "mwd": ds["wave_dir"],
                "u100": -ds["wind_speed"] * np.sin(np.deg2rad(ds["wind_dir"])),
                "v100": -ds["wind_speed"] * np.cos(np.deg2rad(ds["wind_dir"])),
            }
        ).drop_attrs()
        era5.to_netcdf(nc)
        zarr_path = tmp / "era5_like.zarr"
        era5.to_zarr(zarr_path, consolidated=False)
        kw = {"start": START, "end": END, "hub_height": 90.0, "shear_exponent": 0.14}
        rows = [
            (
                "CSV (NORA3 layout, 28 columns)",
                lambda: read_hindcast(csv, **kw),
                lambda: pd.read_csv(csv, comment="#"),
                csv.stat().st_size,
            ),
            (
                "NetCDF (ERA5 names, u100/v100)",
                lambda: read_hindcast(nc, **kw),
                lambda: xr.open_dataset(nc).load(),
                nc.stat().st_size,
            ),
            (
                "Zarr (ERA5 names, u100/v100)",
                lambda: read_hindcast(zarr_path, **kw),
                lambda: xr.open_zarr(zarr_path, consolidated=False).load(),
                0,
            ),
        ]
        print(f"{'loader':34s} {'moorlife':>9s} {'raw read':>9s} {'ratio':>6s}")
        for name, ours, floor, size in rows:
            t_ours, out = best_of(ours)
            t_floor, _ = best_of(floor)
            assert out.sizes["time"] == n
            extra = f"  ({size / 1e6:.0f} MB)" if size else ""
            print(f"{name:34s} {t_ours:8.3f}s {t_floor:8.3f}s {t_ours / t_floor:6.2f}{extra}")
            assert t_ours < TARGET_S, f"{name}: {t_ours:.1f} s exceeds the {TARGET_S} s target"
    assert t_build < TARGET_S


if __name__ == "__main__":
    main()
