"""Print the README's results tables (Markdown) from a finished run's outputs.

Usage::

    .venv/bin/python validation/paper_results.py [results] [--against OTHER_RESULTS]

Reads ``results/{ms}/lifecycle.zarr``, ``results/comparison/summary.csv`` and
``results/comparison/recommendation.yaml`` (nothing is recomputed), so every number in the
README's results section can be traced to the stores of one run. With ``--against``, a last table
compares the life-cycle damage and the validation r with another run's (a change of default).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

from moorlife.io import open_zarr, read_yaml

GROUPS = {
    "surge / sway / heave MPM": ["surge_mpm", "sway_mpm", "heave_mpm"],
    "nacelle acceleration MPM / p90 / p95 / p99": ["accel_mpm", "accel_p90", "accel_p95", "accel_p99"],
    "tension MPM M1 / M2 / M3": ["tension_mpm/M1", "tension_mpm/M2", "tension_mpm/M3"],
    "hourly damage M1 / M2 / M3 (S-N = T-N, m = 3)": ["damage_sn/M1", "damage_sn/M2", "damage_sn/M3"],
    "mean tension M1 / M2 / M3": ["tension_mean/M1", "tension_mean/M2", "tension_mean/M3"],
    "mean surge / sway": ["surge_mean", "sway_mean"],
}


def _table(header: list[str], rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(lines)


def validation_table(results: Path, systems: list[str]) -> str:
    """Validation r on the 225 states per output group (rows) and system (columns)."""
    r = {ms: open_zarr(results / ms / "lifecycle.zarr")["validation_r"].to_series() for ms in systems}
    rows = [[g] + [" / ".join(f"{r[ms][o]:.3f}" for o in outs) for ms in systems] for g, outs in GROUPS.items()]
    worst = [f"{min(r[ms].values):.3f} ({r[ms].idxmin()})" for ms in systems]
    return _table(["output"] + systems, rows + [["lowest"] + worst])


def damage_table(summary: pd.DataFrame) -> str:
    """Life-cycle damage per line and fatigue life, S-N / T-N, one row per system."""
    rows = []
    for ms, d in summary.groupby("mooring_system", sort=False):
        cell = {(r.line, r.curve): r for r in d.itertuples()}
        dmg = [
            f"{cell[(ln, 'sn')].lifecycle_damage:.3g} / {cell[(ln, 'tn')].lifecycle_damage:.3g}"
            for ln in ("M1", "M2", "M3")
        ]
        life = min(d[d.curve == "sn"].fatigue_life_years), min(d[d.curve == "tn"].fatigue_life_years)
        ok = "yes" if d.passes.all() else "no"
        rows.append(
            [
                f"{ms} ({d.mass_kg_per_m.iloc[0]:g} kg/m)",
                *dmg,
                f"{life[0]:.3g} / {life[1]:.3g}",
                f"{d.utilisation.max():.2f}",
                ok,
            ]
        )
    return _table(
        ["system", "M1 damage", "M2 damage", "M3 damage", "shortest life (y)", "max DFF x damage", "passes"], rows
    )


def table7(summary: pd.DataFrame) -> str:
    """Difference of the life-cycle damage from the 35-bin damage, % (the paper's Table 7)."""
    rows = []
    for ms, d in summary.groupby("mooring_system", sort=False):
        cell = {(r.line, r.curve): r.difference_pct for r in d.itertuples()}
        rows.append([ms] + [f"{cell[(ln, c)]:+.1f}" for c in ("sn", "tn") for ln in ("M1", "M2", "M3")])
    mean = summary.groupby(["curve", "line"]).difference_pct.mean()
    rows.append(["mean"] + [f"{mean[(c, ln)]:+.1f}" for c in ("sn", "tn") for ln in ("M1", "M2", "M3")])
    return _table(["system", "S-N M1", "S-N M2", "S-N M3", "T-N M1", "T-N M2", "T-N M3"], rows)


def changes_table(results: Path, other: Path) -> str:
    """Per system: the S-N life-cycle damage change of each line against ``other``, % (T-N alike),
    with the life band's half-width ``k sigma`` of ``other`` (its fatigue-life band:
    ``(high - low) / (high + low)``), and the largest validation r change over the outputs."""
    new = pd.read_csv(results / "comparison" / "summary.csv")
    old = pd.read_csv(other / "comparison" / "summary.csv")
    key = ["mooring_system", "line", "curve"]
    m = new.merge(old, on=key, suffixes=("", "_old"))
    m["change_pct"] = 100 * (m.lifecycle_damage / m.lifecycle_damage_old - 1)
    m["band_pct"] = (
        100 * (m.fatigue_life_high_old - m.fatigue_life_low_old) / (m.fatigue_life_high_old + m.fatigue_life_low_old)
    )
    rows = []
    for ms, d in m[m.curve == "sn"].groupby("mooring_system", sort=False):
        c = {r.line: r for r in d.itertuples()}
        r_new = open_zarr(results / ms / "lifecycle.zarr")["validation_r"].to_series()
        r_old = open_zarr(other / ms / "lifecycle.zarr")["validation_r"].to_series()
        dr = (r_new - r_old).abs()
        rows.append(
            [ms]
            + [f"{c[ln].change_pct:+.1f}" for ln in ("M1", "M2", "M3")]
            + [" / ".join(f"{c[ln].band_pct:.1f}" for ln in ("M1", "M2", "M3"))]
            + [f"{dr.max():.3f} ({dr.idxmax()})"]
        )
    return _table(
        ["system", "M1 damage change %", "M2", "M3", "life band half-width k sigma %, before", "largest |r change|"],
        rows,
    )


def main(results: str = "results", *rest: str) -> None:
    root = Path(results)
    summary = pd.read_csv(root / "comparison" / "summary.csv")
    systems = list(dict.fromkeys(summary.mooring_system))
    rec = read_yaml(root / "comparison" / "recommendation.yaml")
    print("### RBF validation r (225 states)\n\n" + validation_table(root, systems))
    print("\n### Life-cycle damage (31 years), S-N / T-N\n\n" + damage_table(summary))
    print("\n### Life cycle vs 35 bins, % (Table 7 analogue)\n\n" + table7(summary))
    print(f"\nrecommended: {rec.get('recommended')}  ({rec.get('rule')})")
    print("max utilisation: " + ", ".join(f"{k} {v:.2f}" for k, v in rec.get("max_utilisation", {}).items()))
    print("seed CV of life: " + ", ".join(f"{k} {v:.3f}" for k, v in rec.get("seed_cv", {}).items()))
    print(
        "validation r below 0.98: "
        + str(
            int(
                np.sum(
                    [(open_zarr(root / ms / "lifecycle.zarr")["validation_r"].values < 0.98).sum() for ms in systems]
                )
            )
        )
    )
    if rest:
        if len(rest) != 2 or rest[0] != "--against":
            raise SystemExit("usage: paper_results.py [results] [--against OTHER_RESULTS]")
        other = Path(rest[1])
        old_rec = read_yaml(other / "comparison" / "recommendation.yaml")
        print(f"\n### Against {other} (recommended there: {old_rec.get('recommended')})\n")
        print(changes_table(root, other))


if __name__ == "__main__":
    main(*sys.argv[1:])
