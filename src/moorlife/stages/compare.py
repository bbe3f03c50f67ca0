"""Stage ``compare``: life cycle vs the discrete scatter matrix (paper section 4.1, Table 7) and
the comparison across mooring systems (Fig. 20) with the recommendation (rules ``compare``
and ``compare_figures``)."""

from __future__ import annotations

import logging
import os
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

from moorlife import fatigue as fatigue_mod
from moorlife import lifecycle as lc_mod
from moorlife import names
from moorlife.io import (
    open_zarr,
    read_csv_table,
    read_mooring_systems,
    read_yaml,
    save_figure,
    write_csv,
    write_yaml,
)
from moorlife.settings import fill_section
from moorlife.stages import logged

__all__ = ["run", "figures"]

PathLike = str | os.PathLike[str]
_log = logging.getLogger("moorlife.stages.compare")


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


def run(
    *,
    lifecycles: Sequence[PathLike],
    discretes: Sequence[PathLike],
    bins: PathLike,
    mooring_systems: PathLike,
    summary: PathLike,
    recommendation: PathLike,
    systems: Sequence[str],
    lifecycle: Mapping[str, Any],
    fatigue: Mapping[str, Any] | None = None,
    seeds: Sequence[PathLike] | PathLike | None = None,
    log: PathLike | None = None,
) -> pd.DataFrame:
    """``results/comparison/summary.csv`` and the recommendation across mooring systems.

    Parameters
    ----------
    lifecycles, discretes : sequence of path-like
        ``results/{ms}/lifecycle.zarr`` and ``discrete.zarr``, in the order of ``systems``.
    bins : path-like
        The discrete scatter-matrix states, ``results/selection/discrete.zarr``.
    mooring_systems : path-like
        The mooring-system table.
    summary, recommendation : path-like
        The output CSV and YAML.
    systems : sequence of str
        The mooring systems.
    lifecycle, fatigue : mapping
        The config sections of the same names.
    seeds : path-like or a sequence of at most one, optional
        The seed realisations (``results/sensitivity/seeds.zarr``): the fatigue-life band.
    log : path-like, optional
        The rule's log file.
    """
    if seeds is not None and not isinstance(seeds, (str, os.PathLike)):
        seeds = (list(seeds) or [None])[0]
    with logged(log, __name__):
        mooring = read_mooring_systems(mooring_systems)
        states = open_zarr(bins)
        lcs, dds = {}, {}
        for ms, lp, dp in zip(systems, lifecycles, discretes, strict=True):
            lc = open_zarr(lp, load=False)
            # the hourly damage stays: the band's seed term is the scatter of its sum (band_sigma)
            keep = ("surge_mpm", "tension_mpm", *lc_mod.DAMAGE_VARS.values())
            lcs[ms] = lc.drop_vars([v for v in lc.data_vars if names.TIME in lc[v].dims and v not in keep]).load()
            dds[ms] = lc_mod.discrete_damage_table(states, open_zarr(dp), lc.attrs["n_hours"])
        cv = _seed_cv(seeds)
        rec_cfg = fill_section("lifecycle.recommendation", lifecycle.get("recommendation"))
        coverage = float(fill_section("lifecycle.uncertainty", lifecycle.get("uncertainty"))["coverage"])
        corr = fatigue_mod.fatigue_settings(fatigue) if rec_cfg["corrosion"] else None
        table = lc_mod.summary_table(lcs, dds, mooring, seed_cv=cv, corrosion=corr, coverage=coverage)
        curves = list(rec_cfg["curves"])
        rec = lc_mod.recommend(table, curves=curves)
        write_csv(table, summary)
        info = {
            "recommended": rec,
            "curves": curves,
            "rule": (
                f"lightest system with DFF x design-life damage <= 1 on every line for curves {curves}"
                + (" (corroding chain)" if corr is not None else "")
            ),
            "seed_cv": cv,
            "max_utilisation": {
                ms: float(g["utilisation"].max()) for ms, g in table[table.curve.isin(curves)].groupby("mooring_system")
            },
            "mean_difference_pct": {
                f"{c}/{ln}": float(g["difference_pct"].mean()) for (c, ln), g in table.groupby(["curve", "line"])
            },
        }
        write_yaml(info, recommendation)
        _log.info("recommendation: %s", info)
        return table


def figures(
    *,
    summary: PathLike,
    recommendation: PathLike,
    lifecycles: Sequence[PathLike],
    damage_mass: PathLike,
    difference: PathLike,
    offsets: PathLike,
    recommendation_fig: PathLike,
    systems: Sequence[str],
    log: PathLike | None = None,
) -> None:
    """Fig. 20 (damage vs line mass), Table 7 analogue, offsets and tensions, recommendation.

    Parameters
    ----------
    summary, recommendation : path-like
        The outputs of :func:`run`.
    lifecycles : sequence of path-like
        ``results/{ms}/lifecycle.zarr``, in the order of ``systems``.
    damage_mass, difference, offsets, recommendation_fig : path-like
        The four PNG files.
    systems : sequence of str
        The mooring systems.
    log : path-like, optional
        The rule's log file.
    """
    from moorlife.plots import lifecycle as plots

    with logged(log, __name__):
        table = read_csv_table(summary)
        rec = read_yaml(recommendation)
        dists = {}
        for ms, lp in zip(systems, lifecycles, strict=True):
            lc = open_zarr(lp, load=False)
            dists[ms] = {v: lc[v].load() for v in ("surge_mpm", "sway_mpm", "tension_mpm") if v in lc}
        save_figure(plots.damage_vs_mass(table), damage_mass)
        save_figure(plots.difference_bars(table), difference)
        save_figure(plots.offsets_tensions(dists), offsets)
        save_figure(plots.recommendation_table(table, rec), recommendation_fig)
