"""How much the GP's 200-state draw decides its validation r, and what else moves it (issue 22).

    OMP_NUM_THREADS=1 python validation/gp_draw_spread.py --results results --systems MS1 MS2 MS3 MS6 \\
        --overlay validation/overlays/gp_matern52_wind_frozen.yaml --draws 0 1 2 3 4 5 --ensemble
    OMP_NUM_THREADS=1 python validation/gp_draw_spread.py --results results --systems MS6 MS1 MS3 MS5 \\
        --overlay validation/overlays/gp_matern52_wind_frozen.yaml --draws 0 1 --n-mda 960 \\
        --replicates REPLICATES --top 20

The GP's hyperparameters are fitted on ``lifecycle.rbf.gp.subsample`` training states drawn
with ``gp.seed`` (``numpy``'s ``choice(m, 200)``): a draw from 960 states shares nothing with
one from 1,000, so a comparison at equal cost that gives up MDA states also compares two
draws. For each system, the package's fit (``lifecycle.fit_reconstruction``, the config plus
``--overlay``, the ``damage_sn`` outputs only) on the first ``--n-mda`` MDA states (default: every
training state), once per ``--draws`` seed; printed per draw, per line:

- the validation r on the 225 validation states (``lifecycle.validation_metrics``);
- the leave-one-out RMSE of the training states in the model's units (``log10``), which the
  training data alone give: can they choose the draw?

then the range and median over the draws, the draw of the smallest leave-one-out RMSE, and with
``--ensemble`` the r of the mean of the draws' predictions. ``--replicates DIR`` fits each draw
again with the ``--top`` states ranked by ``lifecycle.replicates.rank: years`` averaged with
their records in ``DIR/<system>/replicate*.zarr`` (``validation/replicates.py``'s ``--work``):
the replicates' own effect at a fixed draw. ``validation/reconstruction.md`` section 28 has the
figures.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import xarray as xr

sys.path.insert(0, str(Path(__file__).resolve().parent))
import reconstruction as rec  # noqa: E402  (the harness's config and store loader)

from moorlife import lifecycle  # noqa: E402
from moorlife.io import open_zarr  # noqa: E402
from moorlife.selection import replicates as rep  # noqa: E402


def fit_r(cases: xr.Dataset, sims: xr.Dataset, section: dict, seed: int) -> tuple[np.ndarray, ...]:
    """Validation r and leave-one-out RMSE of the S-N damage per line; the validation states'
    predictions and records."""
    gp = {**section.get("gp", {}), "seed": seed}
    settings = lifecycle.RBFSettings.from_config({**section, "outputs": ["damage_sn"], "gp": gp})
    f = lifecycle.fit_reconstruction(cases, sims, settings=settings, context="gp_draw_spread")
    pred = lifecycle.predict_outputs(f.model, f.points[f.valid])
    r = lifecycle.validation_metrics(pred, f.values[f.valid])["r"]
    loo = np.sqrt(np.mean(f.model.loo_error**2, axis=0))  # per output, in the interpolated (log10) values
    return r, loo, pred, f.values[f.valid]


def replicated(
    cfg: dict, cases: xr.Dataset, sims: xr.Dataset, hindcast: xr.Dataset, work: Path, top: int
) -> xr.Dataset:
    """``sims`` with the ``top`` states of ``rank: years`` the mean of their records in ``work``."""
    settings = lifecycle.rbf_settings(cfg["lifecycle"]["rbf"])
    picks = rep.pick_replicates(hindcast, cases, sims, settings=settings, n=top, seeds=2, rank="years")
    ids = picks["case"].values
    reps = [open_zarr(p) for p in sorted(work.glob("replicate*.zarr"))]
    if not reps:
        raise SystemExit(f"{work}: no replicate*.zarr (run validation/replicates.py with this --work first)")
    print(f"  replicates: the top {top} by rank years, {len(reps)} more records each: {ids.tolist()}")
    return rep.average_replicates(sims, [r.sel(case=ids) for r in reps])


def row(name: str, r: np.ndarray, loo: np.ndarray | None = None) -> str:
    cells = [f"{v:.3f}" for v in r] + ([f"{v:.4f}" for v in loo] if loo is not None else [""] * r.size)
    return f"| {name} | " + " | ".join(cells) + " |"


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--results", type=Path, default=Path("results"))
    p.add_argument("--systems", nargs="+", required=True)
    p.add_argument("--overlay", action="append", default=[], help="config overlays (the GP's settings)")
    p.add_argument("--draws", type=int, nargs="+", default=[0])
    p.add_argument("--n-mda", type=int, default=0, help="fit the first N MDA states (0: every training state)")
    p.add_argument("--ensemble", action="store_true", help="also the r of the mean of the draws' predictions")
    p.add_argument("--replicates", type=Path, help="validation/replicates.py's --work, for the replicates' effect")
    p.add_argument("--top", type=int, default=20)
    a = p.parse_args(argv)
    cfg = rec.study(a.overlay)
    section = cfg["lifecycle"]["rbf"]
    if section.get("method") != "gp":
        p.error("the overlays must set lifecycle.rbf.method: gp")
    for ms in a.systems:
        st = rec.load(a.results, ms)
        if st is None:
            p.error(f"{ms}: no simulations under {a.results}")
        cases, sims = st["cases"], st["sims"]
        if a.n_mda:
            role = cases["role"].values.astype(object).astype(str)
            keep = (role == "validate") | ((role == "train") & (cases["case"].values < a.n_mda))
            cases = cases.isel(case=np.flatnonzero(keep))
        lines = [str(v) for v in sims["line"].values]
        n = int((cases["role"].values.astype(object).astype(str) == "train").sum())
        print(f"\n### {ms}: {n} training states, S-N damage validation r per line, then leave-one-out RMSE (log10)\n")
        print("| draw | " + " | ".join([f"r {ln}" for ln in lines] + [f"LOO {ln}" for ln in lines]) + " |")
        print("|---" * (1 + 2 * len(lines)) + "|")
        avg = replicated(cfg, cases, sims, st["hindcast"], a.replicates / ms, a.top) if a.replicates else None
        rs, loos, preds = [], [], []
        for seed in a.draws:
            r, loo, pred, y = fit_r(cases, sims, section, seed)
            rs.append(r)
            loos.append(loo)
            preds.append(pred)
            print(row(f"seed {seed}", r, loo), flush=True)
            if avg is not None:
                print(row(f"seed {seed} + replicates", *fit_r(cases, avg, section, seed)[:2]), flush=True)
        rs_a, loos_a = np.array(rs), np.array(loos)
        if len(a.draws) > 1:
            print(row("lowest", rs_a.min(axis=0)))
            print(row("median", np.median(rs_a, axis=0)))
            print(row("highest", rs_a.max(axis=0)))
            pick = np.argmin(loos_a, axis=0)
            print(row("smallest LOO's draw", rs_a[pick, np.arange(len(lines))]))
            print("  (its seeds: " + ", ".join(f"{ln} {a.draws[k]}" for ln, k in zip(lines, pick)) + ")")
        if a.ensemble:
            print(row("mean of the draws' predictions", lifecycle.validation_metrics(np.mean(preds, axis=0), y)["r"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
