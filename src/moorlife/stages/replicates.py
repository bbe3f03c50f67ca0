"""Stage ``replicates``: the training states one mooring system simulates again with other seeds
(rule ``replicate_picks``; ``workflow/rules/replicates.smk``).

Fits on the MDA states and every adaptive round and writes ``results/{ms}/replicates/picks.zarr``
(:func:`moorlife.selection.replicates.pick_replicates`); the rule ``simulate_replicate``
simulates it once per seed (:func:`moorlife.stages.simulate.run`, streams ``replicate1`` ..)
into ``results/{ms}/replicates/simulations_{j}.zarr``, and the ``lifecycle`` stage fits the mean
of each picked state's records (:func:`moorlife.selection.replicates.average_replicates`).
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import Any

import xarray as xr

from moorlife import lifecycle as lc_mod
from moorlife.io import open_zarr, write_zarr
from moorlife.selection import replicates as rep_mod
from moorlife.stages import logged, thrust_for
from moorlife.stages.rounds import merged

__all__ = ["run"]

PathLike = str | os.PathLike[str]


def run(
    *,
    hindcast: PathLike,
    cases: PathLike,
    simulations: PathLike,
    store: PathLike,
    rbf: Mapping[str, Any],
    states: int,
    seeds: int,
    rank: str = "damage",
    rounds: Sequence[PathLike] = (),
    round_simulations: Sequence[PathLike] = (),
    platform_cfg: PathLike | None = None,
    wind: Mapping[str, Any] | None = None,
    log: PathLike | None = None,
) -> xr.Dataset:
    """The states to replicate -> ``results/{ms}/replicates/picks.zarr``.

    Parameters
    ----------
    hindcast, cases, simulations : path-like
        The hindcast, the selection and its simulations for this system.
    store : path-like
        The output store.
    rbf : mapping
        ``lifecycle.rbf`` (the fit, as the ``lifecycle`` stage fits).
    states, seeds : int
        ``lifecycle.replicates.states`` and ``seeds``.
    rank : str
        ``lifecycle.replicates.rank`` (:func:`moorlife.selection.replicates.pick_replicates`).
    rounds, round_simulations : sequence of path-like
        The picks and simulations of every adaptive round.
    platform_cfg : path-like, optional
        ``config/platform.yaml``, for the thrust space of ``lifecycle.rbf.choose: per_output``.
    wind : mapping, optional
        ``simulation.wind``, read only for ``lifecycle.rbf.thrust.statistic: turbulent_sd``.
    log : path-like, optional
        The rule's log file.
    """
    with logged(log, __name__) as logger:
        cs, sims = merged(cases, simulations, rounds, round_simulations)
        settings = lc_mod.rbf_settings(rbf, source="config.yaml")
        ds = rep_mod.pick_replicates(
            open_zarr(hindcast),
            cs,
            sims,
            settings=settings,
            n=int(states),
            seeds=int(seeds),
            thrust=thrust_for(settings, platform_cfg, wind),
            rank=str(rank),
        )
        logger.info(
            "replicated cases %s (hindcast hours %s)", ds["case"].values.tolist(), ds["hindcast_index"].values.tolist()
        )
        write_zarr(ds, store)
        return ds
