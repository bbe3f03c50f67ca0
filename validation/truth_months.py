"""Month by month: the reconstructed damage of a truth window against its truth (issue 22).

    python validation/truth_months.py results/MS6/truth_comparison.zarr [--curve sn]

Reads the ``truth_compare`` rule's store (its cumulative damage of the truth, of the
reconstruction and of the 35 bins, hour by hour) and prints, per calendar month and line, the
share of the window's truth damage the month holds, the reconstruction's and the bins' error
against the month's truth, and the error the month adds to the window's sum (its error in units
of the window's truth damage, so the rows add up to the window's error). A closing row per line
gives the window, and how much of its error the largest ``--top`` truth hours carry.
"""

from __future__ import annotations

import argparse

import numpy as np
import pandas as pd

from moorlife.io import open_zarr


def monthly(path: str, curve: str, top: int) -> pd.DataFrame:
    ds = open_zarr(path)
    time = pd.DatetimeIndex(ds["time"].values)
    lines = [str(x) for x in ds["line"].values.astype(object)]
    rows = []
    for li, line in enumerate(lines):
        per_hour = {
            k: np.diff(np.concatenate([[0.0], ds[f"{k}_cumulative"].sel(curve=curve).values[:, li].astype(float)]))
            for k in ("truth", "reconstruction", "bins")
        }
        total = per_hour["truth"].sum()
        for month, idx in pd.Series(np.arange(time.size), index=time).groupby(time.to_period("M")):
            t, r, b = (per_hour[k][idx.values].sum() for k in ("truth", "reconstruction", "bins"))
            rows.append(
                {
                    "line": line,
                    "month": str(month),
                    "share_pct": 100 * t / total,
                    "reconstruction_pct": 100 * (r / t - 1),
                    "bins_pct": 100 * (b / t - 1),
                    "adds_to_window_pct": 100 * (r - t) / total,
                }
            )
        worst = np.argsort(per_hour["truth"])[::-1][:top]
        err = per_hour["reconstruction"] - per_hour["truth"]
        rows.append(
            {
                "line": line,
                "month": "window",
                "share_pct": 100.0,
                "reconstruction_pct": 100 * (per_hour["reconstruction"].sum() / total - 1),
                "bins_pct": 100 * (per_hour["bins"].sum() / total - 1),
                "adds_to_window_pct": 100 * err.sum() / total,
                f"top{top}_share_pct": 100 * per_hour["truth"][worst].sum() / total,
                f"top{top}_error_pct": 100 * err[worst].sum() / total,
            }
        )
    return pd.DataFrame(rows)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("store", help="results/{ms}/truth_comparison.zarr")
    ap.add_argument("--curve", default="sn", choices=["sn", "tn"])
    ap.add_argument("--top", type=int, default=50, help="the largest truth hours of the window")
    args = ap.parse_args()
    df = monthly(args.store, args.curve, args.top)
    print(df.to_markdown(index=False, floatfmt=".1f"))


if __name__ == "__main__":
    main()
