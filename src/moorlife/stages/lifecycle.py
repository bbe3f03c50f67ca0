"""Stage ``lifecycle``: every output of the simulated sea states rebuilt for every hindcast hour
(Gaussian RBF), validated on the states kept aside, and summed over the hindcast (rules
``lifecycle`` and ``lifecycle_figures``)."""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import Any

import xarray as xr

from moorlife import lifecycle as lc_mod
from moorlife import names
from moorlife.io import open_zarr, save_figure, write_zarr
from moorlife.lifecycle.validation import R_INTERVAL_LEVEL
from moorlife.selection.replicates import average_replicates
from moorlife.selection.rounds import annotate_lifecycle
from moorlife.settings import fill_section
from moorlife.stages import logged, thrust_for
from moorlife.stages.rounds import merged

__all__ = ["run", "refit", "figures"]


PathLike = str | os.PathLike[str]


def run(
    *,
    hindcast: PathLike,
    cases: PathLike,
    simulations: PathLike,
    store: PathLike,
    lifecycle: Mapping[str, Any],
    fatigue: Mapping[str, Any],
    platform_cfg: PathLike | None = None,
    wind: Mapping[str, Any] | None = None,
    rounds: Sequence[PathLike] = (),
    round_simulations: Sequence[PathLike] = (),
    replicates: Sequence[PathLike] = (),
    chunk_rows: int | None = None,
    threads: int | None = None,
    log: PathLike | None = None,
) -> xr.Dataset:
    """``results/{ms}/lifecycle.zarr`` from the hindcast, the cases and the simulations.

    Parameters
    ----------
    hindcast, cases, simulations : path-like
        The hindcast, the selected sea states and their simulations.
    rounds, round_simulations : sequence of path-like
        The picks and simulations of every adaptive round (``results/{ms}/rounds/picks_{r}.zarr``,
        ``simulations_{r}.zarr``), fitted with the training states of ``cases``; empty: none.
    store : path-like
        The output store.
    lifecycle, fatigue : mapping
        The config sections of the same names.
    platform_cfg : path-like, optional
        ``config/platform.yaml``: the thrust curve of the ``thrust`` input space, read only
        when ``lifecycle.rbf.choose`` is ``per_output`` with that space among the candidates.
    wind : mapping, optional
        ``simulation.wind``, read only for ``lifecycle.rbf.thrust.statistic: turbulent_sd``.
    chunk_rows : int, optional
        Hindcast hours per RBF prediction block (``lifecycle.rbf.chunk_rows``, read from the
        config by the adapter: memory only, never the numbers). Default: the section's value.
    threads : int, optional
        Caps the numba threads of the RBF prediction (the rule's ``threads``); the numbers do
        not depend on it.
    log : path-like, optional
        The rule's log file.
    """
    import numba

    with logged(log, __name__) as logger:
        if threads:
            numba.set_num_threads(max(1, min(int(threads), numba.config.NUMBA_NUM_THREADS)))
        rbf_cfg = dict(lifecycle.get("rbf") or {})
        if chunk_rows is not None:
            rbf_cfg["chunk_rows"] = int(chunk_rows)
        settings = lc_mod.rbf_settings(rbf_cfg, source="config.yaml")
        thrust = thrust_for(settings, platform_cfg, wind)
        cs, sims = _training(cases, simulations, rounds, round_simulations, replicates)
        if replicates:
            logger.info(
                "seed replicates: %d records of each of the cases %s averaged",
                1 + len(replicates),
                sims["case"].values[sims["n_records"].values > 1].tolist(),
            )
        ds = lc_mod.reconstruct_lifecycle(
            open_zarr(hindcast),
            cs,
            sims,
            settings=settings,
            fatigue_cfg=fatigue,
            n_suggest=int(fill_section("lifecycle.adaptive", lifecycle.get("adaptive"))["n_suggest"]),
            thrust=thrust,
        )
        if rounds:
            ds = annotate_lifecycle(ds, cs)
            logger.info(
                "training states: %d by maximum dissimilarity + %d from %d adaptive round(s)",
                ds.attrs["n_train_mda"],
                ds.attrs["n_train"] - ds.attrs["n_train_mda"],
                len(rounds),
            )
        if replicates:
            rec = sims["n_records"].sel(case=ds["train"].values).values
            ds = ds.assign(
                train_records=(
                    "train",
                    rec,
                    {"units": "1", "long_name": "simulated records averaged (seed replicates)"},
                )
            )
            ds.attrs["replicate_seeds"] = len(replicates)
        for k in ("validation_r", "validation_rmse"):
            if k in ds:
                logger.info(
                    "%s: %s", k, {str(o): round(float(v), 4) for o, v in zip(ds["output"].values, ds[k].values)}
                )
        if "validation_r_low" in ds:
            low, high = ds["validation_r_low"], ds["validation_r_high"]
            rows = zip(ds["output"].values, low.values, high.values)
            interval = {str(o): (round(float(a), 4), round(float(b), 4)) for o, a, b in rows}
            logger.info(
                "validation r, %s BCa bootstrap interval over the states: %s", f"{R_INTERVAL_LEVEL:.0%}", interval
            )
        if "lifecycle_damage" in ds:
            logger.info("life-cycle damage (curve x line):\n%s", ds["lifecycle_damage"].to_pandas())
        chunks = {names.TIME: min(ds.sizes[names.TIME], 65536)}
        enc = {
            v: {"chunks": tuple(chunks.get(d, ds.sizes[d]) for d in ds[v].dims)}
            for v in ds.data_vars
            if names.TIME in ds[v].dims
        }
        write_zarr(ds, store, encoding=enc)
        return ds


def _training(
    cases: PathLike,
    simulations: PathLike,
    rounds: Sequence[PathLike],
    round_simulations: Sequence[PathLike],
    replicates: Sequence[PathLike],
) -> tuple[xr.Dataset, xr.Dataset]:
    """The cases and simulations a reconstruction is fitted on: the MDA states, the adaptive
    rounds' picks, and the mean of the seed replicates' records where there are any."""
    cs, sims = merged(cases, simulations, rounds, round_simulations)
    if replicates:
        sims = average_replicates(sims, [open_zarr(p) for p in replicates])
    return cs, sims


def refit(
    *,
    cases: PathLike,
    simulations: PathLike,
    lifecycle: Mapping[str, Any],
    platform_cfg: PathLike | None = None,
    wind: Mapping[str, Any] | None = None,
    rounds: Sequence[PathLike] = (),
    round_simulations: Sequence[PathLike] = (),
    replicates: Sequence[PathLike] = (),
) -> lc_mod.Fitted:
    """The reconstruction :func:`run` fits, fitted again from the same stores and settings.

    For the truth comparison's records' term (:func:`moorlife.stages.truth.run`), which needs
    the model on the window's hours. Deterministic: the model of :func:`run`, bit for bit. The
    arguments are :func:`run`'s.
    """
    settings = lc_mod.rbf_settings(dict(lifecycle.get("rbf") or {}), source="config.yaml")
    cs, sims = _training(cases, simulations, rounds, round_simulations, replicates)
    return lc_mod.fit_reconstruction(cs, sims, settings=settings, thrust=thrust_for(settings, platform_cfg, wind))


def figures(
    *,
    lifecycle: PathLike,
    validation: PathLike,
    loo_map: PathLike,
    damage_metocean: PathLike,
    ms: str,
    log: PathLike | None = None,
) -> None:
    """Validation scatter (Figs. 10-13), LOO error map and damage vs metocean (Figs. 14-18) of one system.

    Parameters
    ----------
    lifecycle : path-like
        ``results/{ms}/lifecycle.zarr``.
    validation, loo_map, damage_metocean : path-like
        The three PNG files.
    ms : str
        The mooring system (figure titles).
    log : path-like, optional
        The rule's log file.
    """
    from moorlife.plots import lifecycle as plots

    with logged(log, __name__):
        ds = open_zarr(lifecycle)
        save_figure(plots.validation_scatter(ds, title=ms), validation)
        save_figure(plots.loo_error_map(ds, title=ms), loo_map)
        save_figure(plots.damage_vs_metocean(ds, title=ms), damage_metocean)
