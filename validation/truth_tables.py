"""Markdown tables of validation/truth.md from the truth comparison's CSV.

    python validation/truth_tables.py results/MS2/truth_comparison.csv

Prints the per-output agreement (r, RMSE, bias, the r of two seeds and its square root, the
ceiling of r) and the window damage per curve and
line (truth, reconstruction, bins, signed errors, seed scatter of the sum), exactly as the CSV
written by the truth_compare rule holds them.
"""

from __future__ import annotations

import sys

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


if __name__ == "__main__":
    print(tables(sys.argv[1]))
