"""Stage ``simulate``: every sea state of a store, coupled time-domain simulation, for one
mooring system (rules ``simulate_cases``, ``simulate_discrete`` and ``sensitivity_seeds``).

Batches of sea states are fanned out with Dask (:func:`moorlife.stages.fanout.map_cases`); a
killed run resumes from its partial store.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any

import xarray as xr

import moorlife
from moorlife import simulate
from moorlife.config import fingerprint
from moorlife.io import open_zarr
from moorlife.io.platform import open_platform_nc, read_platform_config
from moorlife.parallel import dataset_digest
from moorlife.settings import SimulationSettings
from moorlife.stages import logged, scheduling_free
from moorlife.stages.fanout import map_cases

__all__ = ["run", "store_fingerprint"]

PathLike = str | os.PathLike[str]


def store_fingerprint(
    *,
    dim: str,
    ms: str,
    row: Mapping[str, Any],
    seed: int,
    simulation: Mapping[str, Any],
    mooring: Mapping[str, Any] | None,
    fatigue: Mapping[str, Any] | None,
    statistics: Mapping[str, Any] | None,
    platform_cfg: Mapping[str, Any],
    cases: xr.Dataset,
    platform: xr.Dataset,
    stream: str | None = None,
) -> str:
    """The digest of everything that determines the numbers of a simulation store.

    Scheduling settings (``simulation.batch_size``) are left out, so changing them keeps a
    partial store. ``row`` is the mooring-system table row including ``mooring_system``;
    ``stream`` another random stream than the dimension (the truth target).
    """
    return fingerprint(
        "simulate-v2",
        dim if stream in (None, dim) else f"{dim}/{stream}",
        moorlife.__version__,
        ms,
        dict(row),
        int(seed),
        scheduling_free("simulation", simulation),
        dict(mooring or {}),
        dict(fatigue or {}),
        dict(statistics or {}),
        platform_cfg,
        dataset_digest(cases),
        dataset_digest(platform),
    )


def run(
    *,
    cases: PathLike,
    platform: PathLike,
    platform_cfg: PathLike,
    store: PathLike,
    dim: str,
    ms: str,
    row: Mapping[str, Any],
    seed: int,
    simulation: Mapping[str, Any],
    mooring: Mapping[str, Any] | None = None,
    fatigue: Mapping[str, Any] | None = None,
    statistics: Mapping[str, Any] | None = None,
    batch_size: int | None = None,
    stream: str | None = None,
    threads: int = 1,
    log: PathLike | None = None,
) -> xr.Dataset:
    """Simulate every sea state of a store (along ``case`` or ``bin``) for one mooring system.

    Parameters
    ----------
    cases : path-like
        The sea states (``results/selection/cases.zarr``, ``discrete.zarr`` or the seed cases).
    platform : path-like
        The hydrodynamic model, ``results/hydro/platform.nc``.
    platform_cfg : path-like
        ``config/platform.yaml``.
    store : path-like
        The output store (``results/{ms}/simulations.zarr`` or ``discrete.zarr``).
    dim : str
        The case dimension of ``cases``: ``case`` or ``bin``.
    ms : str
        The mooring system.
    row : mapping
        Its row of the mooring-system table.
    seed : int
        Global seed (``config.yaml: seed``).
    simulation, mooring, fatigue, statistics : mapping
        The config sections of the same names (``mooring``, ``fatigue`` and ``statistics``
        may be None or empty: defaults).
    batch_size : int, optional
        Sea states per Dask task (``simulation.batch_size``, read from the config by the
        adapter; scheduling only). Default: ``simulation["batch_size"]``.
    stream : str, optional
        The random stream of the phases (:func:`moorlife.conventions.case_rng`); the default is
        the dimension, as for ``simulations.zarr`` and ``discrete.zarr``. Another name (the truth
        target's ``"truth"``) gives every id phases independent of the case or bin with that id.
    threads : int
        Dask workers of the LocalCluster (the rule's threads).
    log : path-like, optional
        The rule's log file.

    Returns
    -------
    xarray.Dataset
        The completed store (also written to ``store``).
    """
    sim_cfg = scheduling_free("simulation", simulation)
    settings = SimulationSettings.from_config(simulation, source="simulation")
    bs = int(batch_size if batch_size is not None else settings.batch_size)
    with logged(log, __name__) as logger:
        cs = open_zarr(cases)
        if dim not in cs.dims:
            raise ValueError(f"{cases}: expected a dimension {dim!r}, found {tuple(cs.dims)}")
        platform_ds = open_platform_nc(platform)
        pcfg = read_platform_config(platform_cfg)
        full_row = {**dict(row), "mooring_system": ms}
        model = simulate.prepare_model(platform_ds, pcfg, full_row, mooring, sim_cfg)
        logger.info("%s: %s mooring, %d sea states along %r", ms, model.mooring_kind, cs.sizes[dim], dim)
        fp = store_fingerprint(
            dim=dim,
            ms=ms,
            row=full_row,
            seed=seed,
            simulation=sim_cfg,
            mooring=mooring,
            fatigue=fatigue,
            statistics=statistics,
            platform_cfg=pcfg,
            cases=cs,
            platform=platform_ds,
            stream=stream,
        )
        kwargs = dict(
            mooring_system=ms,
            seed=int(seed),
            stream=dim if stream is None else str(stream),
            model_inputs=model,
            sim_cfg=sim_cfg,
            fatigue_cfg=dict(fatigue or {}),
            stats_cfg=dict(statistics or {}),
        )
        attrs = {
            "mooring_system": ms,
            "mooring_model": model.mooring_kind,
            "seed": int(seed),
            "duration": settings.duration,
            "dt": settings.dt,
        }
        if stream not in (None, dim):  # the default stores keep their attributes unchanged
            attrs["random_stream"] = str(stream)
        return map_cases(
            simulate.simulate_batch,
            cs,
            store,
            dim=dim,
            func_kwargs=kwargs,
            batch_size=bs,
            fingerprint=fp,
            threads=threads,
            log=logger,
            attrs=attrs,
            attrs_of=simulate.output_attrs,
        )
