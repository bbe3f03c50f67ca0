"""Stage ``sensitivity``: the sensitivities of paper section 4, random seeds (Fig. 21),
corrosion (Fig. 22) and mean-stress factors (Table 8) (rules ``sensitivity_cases``,
``sensitivity_seeds`` (:func:`moorlife.stages.simulate.run`) and ``sensitivity``)."""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd
import xarray as xr

from moorlife import fatigue as fatigue_mod
from moorlife import lifecycle as lc_mod
from moorlife import names
from moorlife.io import (
    open_zarr,
    read_mooring_systems,
    save_figure,
    write_csv,
    write_zarr,
)
from moorlife.stages import logged

__all__ = ["cases", "run"]

PathLike = str | os.PathLike[str]


def cases(
    *,
    store: PathLike,
    sea_state: Mapping[str, float],
    n_seeds: int,
    case_offset: int,
    log: PathLike | None = None,
) -> xr.Dataset:
    """A ``cases`` store with ``n_seeds`` copies of one sea state (distinct case ids = random streams).

    Parameters
    ----------
    store : path-like
        ``results/sensitivity/seed_cases.zarr``.
    sea_state : mapping
        The sea state (``lifecycle.sensitivity.sea_state``: every metocean variable).
    n_seeds : int
        The realisations.
    case_offset : int
        The first case id (keeps the random streams apart from those of the selected cases).
    log : path-like, optional
        The rule's log file.
    """
    with logged(log, __name__):
        ids = np.arange(int(n_seeds), dtype=np.int64) + int(case_offset)
        ds = xr.Dataset(
            {v: ("case", np.full(ids.size, float(sea_state[v])), names.attrs_for(v)) for v in names.METOCEAN_VARS},
            coords={"case": ids},
        )
        ds["role"] = ("case", np.array(["seed"] * ids.size))
        ds.attrs["description"] = "random-phase realisations of one sea state (paper section 4.2)"
        write_zarr(ds, store)
        return ds


def run(
    *,
    seeds: PathLike,
    lifecycle: PathLike,
    lifecycles: Sequence[PathLike],
    mooring_systems: PathLike,
    seeds_csv: PathLike,
    corrosion_csv: PathLike,
    mean_stress_csv: PathLike,
    seeds_fig: PathLike,
    corrosion_fig: PathLike,
    mean_stress_fig: PathLike,
    systems: Sequence[str],
    ms: str,
    line: str,
    fatigue: Mapping[str, object],
    log: PathLike | None = None,
) -> None:
    """Seed spread (Fig. 21), corrosion evolution (Fig. 22) and mean-stress factors (Table 8).

    Parameters
    ----------
    seeds : path-like
        The simulated seed realisations, ``results/sensitivity/seeds.zarr``.
    lifecycle : path-like
        ``results/{ms}/lifecycle.zarr`` of the sensitivity system ``ms``.
    lifecycles : sequence of path-like
        Every system's ``lifecycle.zarr``, in the order of ``systems``.
    mooring_systems : path-like
        The mooring-system table.
    seeds_csv, corrosion_csv, mean_stress_csv : path-like
        The output tables.
    seeds_fig, corrosion_fig, mean_stress_fig : path-like
        The output figures.
    systems : sequence of str
        The mooring systems.
    ms : str
        The sensitivity system (``lifecycle.sensitivity.mooring_system``).
    line : str
        The line of the corrosion evolution (``lifecycle.sensitivity.corrosion_line``).
    fatigue : mapping
        The ``fatigue`` config section.
    log : path-like, optional
        The rule's log file.
    """
    from moorlife.plots import lifecycle as plots

    with logged(log, __name__):
        fs = fatigue_mod.fatigue_settings(fatigue)
        mooring = read_mooring_systems(mooring_systems)
        sd = open_zarr(seeds)
        lives = {
            c: lc_mod.seed_lives(sd[v].transpose("case", names.LINE).values)
            for c, v in lc_mod.DAMAGE_VARS.items()
            if v in sd
        }
        lines = [str(v) for v in sd[names.LINE].values]
        rows = [
            {
                "seed": int(k),
                "curve": c,
                "line": ln,
                "hourly_damage": float(sd[lc_mod.DAMAGE_VARS[c]].values[i, j]),
                "life_years": float(lv[i, j]),
            }
            for c, lv in lives.items()
            for i, k in enumerate(sd["case"].values)
            for j, ln in enumerate(lines)
        ]
        seeds_df = pd.DataFrame(rows)
        write_csv(seeds_df, seeds_csv)
        save_figure(plots.seed_spread(seeds_df, title=f"{ms}, one sea state, {sd.sizes['case']} seeds"), seeds_fig)

        lc = open_zarr(lifecycle, load=False)
        d0 = float(mooring.loc[ms, "link_diameter_mm"]) * 1e-3
        years = max(float(fs.design_life), 30.0)
        ev = []
        for curve in [str(c) for c in lc[names.CURVE].values]:
            py = float(lc["damage_per_year"].sel({names.CURVE: curve, names.LINE: line}))
            mt = (
                float(lc["tension_mean"].sel({names.LINE: line}).mean())
                if "tension_mean" in lc
                else float(mooring.loc[ms, "pretension_kN"]) * 1e3
            )
            e = lc_mod.corrosion_evolution(py, d0, years, curve=curve, settings=fs, mean_tension=mt)
            ev += [
                {"curve": curve, "years": y, "corroded": c, "intact": i}
                for y, c, i in zip(e["years"], e["corroded"], e["intact"])
            ]
        ev_df = pd.DataFrame(ev)
        write_csv(ev_df, corrosion_csv)
        save_figure(
            plots.corrosion_evolution(
                ev_df, title=f"{ms} {line}, {fs.corrosion_rate * 1e3:g} mm/year, step {fs.corrosion_step:g} years"
            ),
            corrosion_fig,
        )

        mean_t = {}
        for other, lp in zip(systems, lifecycles, strict=True):
            lci = open_zarr(lp, load=False)
            if "tension_mean" in lci:
                mean_t[other] = float(lci["tension_mean"].mean(names.TIME).max())
        ms_df = lc_mod.mean_stress_table(mooring.loc[list(systems)], mean_t, ultimate=fs.ultimate, yield_=fs.yield_)
        write_csv(ms_df, mean_stress_csv)
        save_figure(plots.mean_stress_table(ms_df), mean_stress_fig)
