"""Markdown tables of validation/truth.md from the truth comparison's CSV.

    python validation/truth_tables.py results/MS2/truth_comparison.csv
    python validation/truth_tables.py --summary validation/data/truth_1985_steady_MS*.csv

Prints the per-output agreement (r, RMSE, bias, the r of two seeds and its square root, the
ceiling of r) and the window damage per curve and
line (truth, reconstruction, bins, signed errors, seed scatter of the sum), exactly as the CSV
written by the truth_compare rule holds them.

``--summary`` prints one row per CSV (per window and system) for the damage of every line (S-N):
the window sum's error against the truth, its seed scatter (1 sd), z = error / seed sd (the bias
test: |z| <= 2 is within the seed noise), the per-hour r and its ceiling; then the counts.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

UNITS = {"tension": ("kN", 1e-3), "surge": ("m", 1.0), "sway": ("m", 1.0), "heave": ("m", 1.0), "accel": ("m/s2", 1.0)}


def _scale(output: str) -> tuple[str, float]:
    for prefix, (unit, k) in UNITS.items():
        if output.startswith(prefix):
            return unit, k
    return "-", 1.0


def tables(csv: str) -> str:
    df = pd.read_csv(csv)
    out = df[df["kind"] == "output"]
    lines = [
        "| output | unit | r | RMSE | bias | sum error % | r of two seeds | ceiling of r (sqrt) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for _, row in out.iterrows():
        unit, k = _scale(row["output"])
        lines.append(
            f"| {row['output']} | {unit} | {row['r']:.3f} | {row['rmse'] * k:.4g} | {row['bias'] * k:+.3g} "
            f"| {100 * row['sum_error']:+.1f} | {row['noise_r']:.3f} | {np.sqrt(max(row['noise_r'], 0.0)):.3f} |"
        )
    dam = df[df["kind"] == "damage"]
    lines += [
        "",
        "| curve | line | truth | reconstruction | bins | reconstruction error % | bins error % "
        "| seed scatter of the sum % (1 sd) | seed-2 minus seed-1 on the subset % |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for _, row in dam.iterrows():
        lines.append(
            f"| {row['curve'].upper().replace('SN', 'S-N').replace('TN', 'T-N')} | {row['line']} "
            f"| {row['truth_damage']:.4g} | {row['reconstruction_damage']:.4g} | {row['bins_damage']:.4g} "
            f"| {row['reconstruction_error_pct']:+.1f} | {row['bins_error_pct']:+.1f} "
            f"| {row['seed_sum_std_pct']:.2f} | {row['seed_sum_difference_pct']:+.1f} |"
        )
    return "\n".join(lines)


def summary(csvs: list[str]) -> str:
    """One row per CSV: the S-N damage of every line (module docstring)."""
    lines = [
        "| window | error % M1 / M2 / M3 | seed sd % | z | per-hour r | ceiling of r |",
        "|---|---|---|---|---|---|",
    ]
    n = within5 = within_noise = at98 = 0
    for csv in csvs:
        df = pd.read_csv(csv)
        dam = df[(df["kind"] == "damage") & (df["curve"] == "sn")].sort_values("line")
        out = df[df["kind"] == "output"].set_index("output")
        err, sd = dam["reconstruction_error_pct"].to_numpy(), dam["seed_sum_std_pct"].to_numpy()
        z = err / sd
        r = out.loc[[f"damage_sn/{ln}" for ln in dam["line"]], "r"].to_numpy()
        ceil = out.loc[[f"damage_sn/{ln}" for ln in dam["line"]], "ceiling_r"].to_numpy()
        n, within5 = n + err.size, within5 + int(np.sum(np.abs(err) <= 5.0))
        within_noise, at98 = within_noise + int(np.sum(np.abs(z) <= 2.0)), at98 + int(np.sum(r >= 0.98))

        def j(x: np.ndarray, f: str) -> str:
            return " / ".join(format(v, f) for v in x)

        lines.append(
            f"| {Path(csv).stem} | {j(err, '+.1f')} | {j(sd, '.2f')} | {j(z, '+.1f')} | {j(r, '.3f')} | {j(ceil, '.3f')} |"
        )
    lines += [
        "",
        f"lines with the sum within 5 %: {within5} of {n}; within the seed noise (|z| <= 2): {within_noise} of {n}; "
        f"per-hour r >= 0.98: {at98} of {n}",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    if sys.argv[1:2] == ["--summary"]:
        print(summary(sys.argv[2:]))
    else:
        print(tables(sys.argv[1]))
