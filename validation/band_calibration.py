"""The coverage factor of the life band, calibrated on the truth windows (issue 22).

    python validation/band_calibration.py results/MS2/truth_comparison.csv [more ...]
    python validation/band_calibration.py validation/data/truth_1985_MS2.csv=results/MS2/lifecycle.zarr
    python validation/band_calibration.py --results results [CSV ...]

Each argument is a truth comparison's CSV (the ``truth_compare`` rule's
``results/{ms}/truth_comparison.csv``). A CSV written before the comparison carried the band
(``band_sigma_pct``, ``coverage_needed``) takes ``=LIFECYCLE``, the ``lifecycle.zarr`` of the same
reconstruction, whose validation states give the band's reconstruction term; the seed term is
the CSV's measured ``seed_sum_std_pct``. The arithmetic is the comparison's own
(``moorlife.lifecycle.band_sigma_of``, ``coverage_needed``). A CSV written since the comparison
carried the training records' seed scatter (``records_sum_std_pct``, 514a31d) has it in its band;
an older one, and the ``=LIFECYCLE`` route, leave it out: their coverage needed is an upper bound.

``--results DIR`` first prints, for every ``DIR/{ms}/lifecycle.zarr``, the band of the life-cycle
damage (S-N): the seed scatter of the sum per line, the validation term, and the band's sd with
one hour's seed CV (the model before) and with the sum's (``lifecycle.band_sigma``); the seed CV
is that of ``DIR/sensitivity/seeds.zarr``, as the compare stage reads it.

Prints one row per window, line and curve (error, band sd, coverage needed), how many cases the
band holds at ``config/config.yaml``'s ``lifecycle.uncertainty.coverage``, and the calibrated factor: the
smallest that holds every measured case (``moorlife.lifecycle.calibrate_coverage``).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]


def cases(arg: str) -> pd.DataFrame:
    from moorlife import lifecycle
    from moorlife.io import open_zarr

    csv, _, lc_path = arg.partition("=")
    df = pd.read_csv(csv)
    df = df[df["kind"] == "damage"].copy()
    if lc_path:
        lc = open_zarr(lc_path)
        val = df["curve"].map(lambda cv: 100.0 * lifecycle.validation_sum_term(lc, cv))
        df["band_sigma_pct"] = lifecycle.band_sigma_of(df["seed_sum_std_pct"].to_numpy(), val.to_numpy())
        df["coverage_needed"] = lifecycle.coverage_needed(df["reconstruction_error_pct"], df["band_sigma_pct"])
    elif "coverage_needed" not in df:
        raise SystemExit(f"{csv}: no coverage_needed column; give the lifecycle.zarr of its reconstruction: {csv}=LC")
    df.insert(0, "window", Path(csv).stem)
    return df


def life_bands(results: Path) -> None:
    """The table of the life-cycle band per system (module docstring)."""
    from moorlife import lifecycle
    from moorlife.io import open_zarr
    from moorlife.stages.compare import _seed_cv

    cv = _seed_cv(results / "sensitivity" / "seeds.zarr")
    print(f"seed CV of one hour's damage: {100 * cv['sn']:.1f} %\n")
    print(
        "| system | seed scatter of the sum M1 / M2 / M3 % | max \\|validation sum error\\| % | band sd before / now % |"
    )
    print("|---|---|---|---|")
    for path in sorted(results.glob("MS*/lifecycle.zarr")):
        lc = open_zarr(path)
        seed = [
            100 * float(lifecycle.sum_seed_cv(lc["damage_sn"].sel(line=ln).values, cv["sn"]))
            for ln in lc["line"].values
        ]
        val = 100 * lifecycle.validation_sum_term(lc, "sn")
        before, now = 100 * np.hypot(cv["sn"], val / 100), 100 * lifecycle.band_sigma(lc, "sn", cv)
        print(f"| {path.parent.name} | {' / '.join(f'{x:.2f}' for x in seed)} | {val:.1f} | {before:.1f} / {now:.1f} |")
    print()


def main(argv: list[str]) -> int:
    from moorlife import lifecycle
    from moorlife.io import read_yaml

    if argv[:1] == ["--results"] and len(argv) >= 2:
        life_bands(Path(argv[1]))
        argv = argv[2:]
        if not argv:
            return 0
    if not argv:
        print(__doc__)
        return 2
    df = pd.concat([cases(a) for a in argv], ignore_index=True)
    k_now = float(read_yaml(ROOT / "config" / "config.yaml")["lifecycle"]["uncertainty"]["coverage"])
    if "records_sum_std_pct" not in df:
        df["records_sum_std_pct"] = np.nan
    print(
        "| window | curve | line | error % | seed scatter of the sum % | records' sd % | band sd % | coverage needed |"
    )
    print("|---|---|---|---|---|---|---|---|")
    for _, r in df.iterrows():
        print(
            f"| {r['window']} | {r['curve']} | {r['line']} | {r['reconstruction_error_pct']:+.1f} "
            f"| {r['seed_sum_std_pct']:.2f} | {r['records_sum_std_pct']:.2f} | {r['band_sigma_pct']:.1f} "
            f"| {r['coverage_needed']:.2f} |"
        )
    k = df["coverage_needed"].to_numpy(dtype=float)
    inside = int(np.sum(k <= k_now))
    print(f"\ninside the band at the default coverage {k_now:g}: {inside} of {k.size} cases")
    print(f"calibrated coverage (smallest that holds every case, step 0.05): {lifecycle.calibrate_coverage(k):.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
