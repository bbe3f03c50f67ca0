"""Disk side of the life-cycle, comparison and sensitivity stages.

Each function reads its inputs, calls the pure kernels of :mod:`moorlife.lifecycle` and the
figures of :mod:`moorlife.plots.lifecycle`, and writes its outputs; the workflow scripts
are thin adapters over them.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr
import yaml

from moorlife import names
from moorlife.io import open_zarr, read_mooring_systems, save_figure, write_zarr

__all__ = [
    "lifecycle_store",
    "lifecycle_figures",
    "compare_outputs",
    "compare_figures",
    "seed_cases_store",
    "sensitivity_outputs",
]

PathLike = str | os.PathLike[str]
log = logging.getLogger(__name__)


def _write_csv(df: pd.DataFrame, path: PathLike) -> None:
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    df.to_csv(p, index=False, float_format="%.6g")


def lifecycle_store(
    hindcast: PathLike,
    cases: PathLike,
    simulations: PathLike,
    output: PathLike,
    *,
    lifecycle_cfg: Mapping[str, Any],
    fatigue_cfg: Mapping[str, Any],
    threads: int | None = None,
) -> xr.Dataset:
    """``results/{ms}/lifecycle.zarr`` from the hindcast, the cases and the simulations.

    ``threads`` caps the numba threads of the RBF prediction (the rule's ``threads``); the
    numbers do not depend on it.
    """
    import numba

    from moorlife import lifecycle

    if threads:
        numba.set_num_threads(max(1, min(int(threads), numba.config.NUMBA_NUM_THREADS)))

    settings = lifecycle.rbf_settings(lifecycle_cfg.get("rbf"), source="config.yaml")
    hc = open_zarr(hindcast)
    cs = open_zarr(cases)
    sims = open_zarr(simulations)
    ds = lifecycle.reconstruct_lifecycle(
        hc, cs, sims, settings=settings, fatigue_cfg=fatigue_cfg,
        n_suggest=int(lifecycle_cfg.get("adaptive", {}).get("n_suggest", 50)),
    )
    for k in ("validation_r", "validation_rmse"):
        if k in ds:
            log.info("%s: %s", k, {str(o): round(float(v), 4) for o, v in zip(ds["output"].values, ds[k].values)})
    if "lifecycle_damage" in ds:
        log.info("life-cycle damage (curve x line):\n%s", ds["lifecycle_damage"].to_pandas())
    chunks = {names.TIME: min(ds.sizes[names.TIME], 65536)}
    enc = {v: {"chunks": tuple(chunks.get(d, ds.sizes[d]) for d in ds[v].dims)}
           for v in ds.data_vars if names.TIME in ds[v].dims}
    write_zarr(ds, output, encoding=enc)
    return ds


def lifecycle_figures(lifecycle_path: PathLike, outputs: Mapping[str, PathLike], *, mooring_system: str) -> None:
    """Validation scatter (Figs. 10-13), LOO error map and damage vs metocean (Figs. 14-18) of one system."""
    from moorlife.plots import lifecycle as plots

    ds = open_zarr(lifecycle_path)
    save_figure(plots.validation_scatter(ds, title=mooring_system), outputs["validation"])
    save_figure(plots.loo_error_map(ds, title=mooring_system), outputs["loo_map"])
    save_figure(plots.damage_vs_metocean(ds, title=mooring_system), outputs["damage_metocean"])


def _seed_cv(seeds: PathLike | None) -> dict[str, float]:
    if not seeds:
        return {}
    ds = open_zarr(seeds)
    out = {}
    for curve, var in (("sn", "damage_sn"), ("tn", "damage_tn")):
        if var in ds:
            d = ds[var].values
            out[curve] = float(np.max(np.std(d, axis=0, ddof=1) / np.mean(d, axis=0)))
    return out


def compare_outputs(
    lifecycles: Sequence[PathLike],
    discretes: Sequence[PathLike],
    bins: PathLike,
    mooring_table: PathLike,
    summary_csv: PathLike,
    recommendation_yaml: PathLike,
    *,
    systems: Sequence[str],
    lifecycle_cfg: Mapping[str, Any],
    fatigue_cfg: Mapping[str, Any] | None = None,
    seeds: PathLike | None = None,
) -> pd.DataFrame:
    """``results/comparison/summary.csv`` and the recommendation across mooring systems."""
    from moorlife import lifecycle

    mooring = read_mooring_systems(mooring_table)
    states = open_zarr(bins)
    lcs, dds = {}, {}
    for ms, lp, dp in zip(systems, lifecycles, discretes, strict=True):
        lc = open_zarr(lp, load=False)
        lcs[ms] = lc.drop_vars([v for v in lc.data_vars if names.TIME in lc[v].dims and v not in ("surge_mpm", "tension_mpm")]).load()
        dds[ms] = lifecycle.discrete_damage_table(states, open_zarr(dp), lc.attrs["n_hours"])
    from moorlife import fatigue

    cv = _seed_cv(seeds)
    rec_cfg = dict(lifecycle_cfg.get("recommendation", {}))
    corr = fatigue.fatigue_settings(fatigue_cfg) if rec_cfg.get("corrosion", False) else None
    table = lifecycle.summary_table(lcs, dds, mooring, seed_cv=cv, corrosion=corr,
                                    coverage=float(lifecycle_cfg.get("uncertainty", {}).get("coverage", 1.0)))
    curves = list(rec_cfg.get("curves", ["sn", "tn"]))
    rec = lifecycle.recommend(table, curves=curves)
    _write_csv(table, summary_csv)
    info = {
        "recommended": rec,
        "curves": curves,
        "rule": (f"lightest system with DFF x design-life damage <= 1 on every line for curves {curves}"
                 + (" (corroding chain)" if corr is not None else "")),
        "seed_cv": cv,
        "max_utilisation": {ms: float(g["utilisation"].max()) for ms, g in table[table.curve.isin(curves)].groupby("mooring_system")},
        "mean_difference_pct": {f"{c}/{ln}": float(g["difference_pct"].mean()) for (c, ln), g in table.groupby(["curve", "line"])},
    }
    with open(recommendation_yaml, "w", encoding="utf-8") as fh:
        yaml.safe_dump(info, fh, sort_keys=False)
    log.info("recommendation: %s", info)
    return table


def compare_figures(
    summary_csv: PathLike,
    recommendation_yaml: PathLike,
    lifecycles: Sequence[PathLike],
    outputs: Mapping[str, PathLike],
    *,
    systems: Sequence[str],
) -> None:
    """Fig. 20 (damage vs line mass), Table 7 analogue, offsets and tensions, recommendation."""
    from moorlife.io import read_yaml
    from moorlife.plots import lifecycle as plots

    table = pd.read_csv(summary_csv)
    rec = read_yaml(recommendation_yaml)
    dists = {}
    for ms, lp in zip(systems, lifecycles, strict=True):
        lc = open_zarr(lp, load=False)
        dists[ms] = {v: lc[v].load() for v in ("surge_mpm", "sway_mpm", "tension_mpm") if v in lc}
    save_figure(plots.damage_vs_mass(table), outputs["damage_mass"])
    save_figure(plots.difference_bars(table), outputs["difference"])
    save_figure(plots.offsets_tensions(dists), outputs["offsets"])
    save_figure(plots.recommendation_table(table, rec), outputs["recommendation"])


def seed_cases_store(output: PathLike, *, sea_state: Mapping[str, float], n_seeds: int, case_offset: int) -> xr.Dataset:
    """A ``cases`` store with ``n_seeds`` copies of one sea state (distinct case ids = random streams)."""
    ids = np.arange(int(n_seeds), dtype=np.int64) + int(case_offset)
    ds = xr.Dataset(
        {v: ("case", np.full(ids.size, float(sea_state[v])), names.attrs_for(v)) for v in names.METOCEAN_VARS},
        coords={"case": ids},
    )
    ds["role"] = ("case", np.array(["seed"] * ids.size))
    ds.attrs["description"] = "random-phase realisations of one sea state (paper section 4.2)"
    write_zarr(ds, output)
    return ds


def sensitivity_outputs(
    seeds: PathLike,
    lifecycle_path: PathLike,
    lifecycles: Sequence[PathLike],
    mooring_table: PathLike,
    outputs: Mapping[str, PathLike],
    *,
    systems: Sequence[str],
    mooring_system: str,
    corrosion_line: str,
    fatigue_cfg: Mapping[str, Any],
) -> None:
    """Seed spread (Fig. 21), corrosion evolution (Fig. 22) and mean-stress factors (Table 8)."""
    from moorlife import fatigue, lifecycle
    from moorlife.plots import lifecycle as plots

    fs = fatigue.fatigue_settings(fatigue_cfg)
    mooring = read_mooring_systems(mooring_table)
    sd = open_zarr(seeds)
    lives = {c: lifecycle.seed_lives(sd[v].transpose("case", names.LINE).values)
             for c, v in lifecycle.DAMAGE_VARS.items() if v in sd}
    lines = [str(v) for v in sd[names.LINE].values]
    rows = [{"seed": int(k), "curve": c, "line": ln, "hourly_damage": float(sd[lifecycle.DAMAGE_VARS[c]].values[i, j]),
             "life_years": float(lv[i, j])}
            for c, lv in lives.items() for i, k in enumerate(sd["case"].values) for j, ln in enumerate(lines)]
    seeds_df = pd.DataFrame(rows)
    _write_csv(seeds_df, outputs["seeds_csv"])
    save_figure(plots.seed_spread(seeds_df, title=f"{mooring_system}, one sea state, {sd.sizes['case']} seeds"),
                outputs["seeds_fig"])

    lc = open_zarr(lifecycle_path, load=False)
    d0 = float(mooring.loc[mooring_system, "link_diameter_mm"]) * 1e-3
    years = max(float(fs.design_life), 30.0)
    ev = []
    for curve in [str(c) for c in lc[names.CURVE].values]:
        py = float(lc["damage_per_year"].sel({names.CURVE: curve, names.LINE: corrosion_line}))
        mt = float(lc["tension_mean"].sel({names.LINE: corrosion_line}).mean()) if "tension_mean" in lc else float(
            mooring.loc[mooring_system, "pretension_kN"]) * 1e3
        e = lifecycle.corrosion_evolution(py, d0, years, curve=curve, settings=fs, mean_tension=mt)
        ev += [{"curve": curve, "years": y, "corroded": c, "intact": i} for y, c, i in zip(e["years"], e["corroded"], e["intact"])]
    ev_df = pd.DataFrame(ev)
    _write_csv(ev_df, outputs["corrosion_csv"])
    save_figure(plots.corrosion_evolution(ev_df, title=f"{mooring_system} {corrosion_line}, "
                                          f"{fs.corrosion_rate * 1e3:g} mm/year, step {fs.corrosion_step:g} years"),
                outputs["corrosion_fig"])

    mean_t = {}
    for ms, lp in zip(systems, lifecycles, strict=True):
        lci = open_zarr(lp, load=False)
        if "tension_mean" in lci:
            mean_t[ms] = float(lci["tension_mean"].mean(names.TIME).max())
    ms_df = lifecycle.mean_stress_table(mooring.loc[list(systems)], mean_t, ultimate=fs.ultimate, yield_=fs.yield_)
    _write_csv(ms_df, outputs["mean_stress_csv"])
    save_figure(plots.mean_stress_table(ms_df), outputs["mean_stress_fig"])
