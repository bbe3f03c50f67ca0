"""Stage ``rounds``: adaptive selection, the sea states of round ``r`` for one mooring system
(rule ``adaptive_picks``; ``workflow/rules/rounds.smk``).

Round ``r`` fits on the MDA states and the rounds before ``r`` and writes
``results/{ms}/rounds/picks_{r}.zarr`` (:func:`moorlife.selection.rounds.pick_round`); the rule
``simulate_round`` simulates it (:func:`moorlife.stages.simulate.run`) into
``results/{ms}/rounds/simulations_{r}.zarr``. :func:`merged` joins the stores of the rounds to
``cases.zarr`` and ``simulations.zarr``, for the next round and for the ``lifecycle`` stage.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import Any

import xarray as xr

from moorlife import lifecycle as lc_mod
from moorlife.io import open_zarr, write_zarr
from moorlife.selection import rounds as rounds_mod
from moorlife.stages import logged, thrust_for

__all__ = ["run", "merged"]

PathLike = str | os.PathLike[str]


def merged(
    cases: PathLike,
    simulations: PathLike,
    rounds: Sequence[PathLike] = (),
    round_simulations: Sequence[PathLike] = (),
) -> tuple[xr.Dataset, xr.Dataset]:
    """``cases.zarr`` and ``simulations.zarr`` followed by the picks and simulations of the rounds.

    Parameters
    ----------
    cases, simulations : path-like
        ``results/selection/cases.zarr`` and ``results/{ms}/simulations.zarr``.
    rounds, round_simulations : sequence of path-like
        ``results/{ms}/rounds/picks_{r}.zarr`` and ``simulations_{r}.zarr``, the same rounds in
        the same order (empty: the two stores as they are).
    """
    if len(rounds) != len(round_simulations):
        raise ValueError(
            f"adaptive rounds: {len(rounds)} picks store(s) but {len(round_simulations)} simulation store(s)"
        )
    cs = rounds_mod.with_rounds(open_zarr(cases), [open_zarr(p) for p in rounds])
    sims = rounds_mod.with_rounds(open_zarr(simulations), [open_zarr(p) for p in round_simulations])
    return cs, sims


def run(
    *,
    hindcast: PathLike,
    cases: PathLike,
    simulations: PathLike,
    store: PathLike,
    rbf: Mapping[str, Any],
    per_round: int,
    number: int,
    rounds: Sequence[PathLike] = (),
    round_simulations: Sequence[PathLike] = (),
    platform_cfg: PathLike | None = None,
    wind: Mapping[str, Any] | None = None,
    log: PathLike | None = None,
) -> xr.Dataset:
    """The sea states of adaptive round ``number`` -> ``results/{ms}/rounds/picks_{number}.zarr``.

    Parameters
    ----------
    hindcast, cases, simulations : path-like
        The hindcast, the selection and its simulations for this system.
    store : path-like
        The output store.
    rbf : mapping
        ``lifecycle.rbf`` (the fit of the round, as the ``lifecycle`` stage fits).
    per_round : int
        ``lifecycle.adaptive.per_round``.
    number : int
        The round, 1-based (the rule's wildcard ``r``).
    rounds, round_simulations : sequence of path-like
        The picks and simulations of rounds ``1 .. number - 1``.
    platform_cfg : path-like, optional
        ``config/platform.yaml``, for the thrust space of ``lifecycle.rbf.choose: per_output``.
    wind : mapping, optional
        ``simulation.wind``, read only for ``lifecycle.rbf.thrust.statistic: turbulent_sd``.
    log : path-like, optional
        The rule's log file.
    """
    with logged(log, __name__) as logger:
        if len(rounds) != int(number) - 1:
            raise ValueError(
                f"adaptive round {number} needs the {int(number) - 1} round(s) before it, got {len(rounds)}"
            )
        cs, sims = merged(cases, simulations, rounds, round_simulations)
        settings = lc_mod.rbf_settings(rbf, source="config.yaml")
        ds = rounds_mod.pick_round(
            open_zarr(hindcast),
            cs,
            sims,
            settings=settings,
            n=int(per_round),
            number=int(number),
            thrust=thrust_for(settings, platform_cfg, wind),
        )
        logger.info("round %d: hindcast hours %s", int(number), ds["hindcast_index"].values.tolist())
        write_zarr(ds, store)
        return ds
