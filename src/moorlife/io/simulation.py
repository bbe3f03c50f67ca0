"""Disk side of the simulation stage: read the sea states and the platform model, fan the
batches out with :func:`moorlife.parallel.map_cases`, and finish the store's attributes."""

from __future__ import annotations

import logging
import os
from collections.abc import Mapping
from typing import Any

import xarray as xr

import moorlife
from moorlife.io import open_zarr
from moorlife.io.platform import open_platform_nc, read_platform_config

__all__ = ["simulate_store"]


def simulate_store(
    cases_path: str | os.PathLike[str],
    platform_nc: str | os.PathLike[str],
    platform_yaml: str | os.PathLike[str],
    output: str | os.PathLike[str],
    *,
    dim: str,
    mooring_system: str,
    mooring_row: Mapping[str, Any],
    seed: int,
    sim_cfg: Mapping[str, Any],
    mooring_cfg: Mapping[str, Any] | None,
    fatigue_cfg: Mapping[str, Any] | None,
    stats_cfg: Mapping[str, Any] | None,
    threads: int = 1,
    log: logging.Logger | None = None,
    stream: str | None = None,
) -> xr.Dataset:
    """Simulate every sea state of a store (``case`` or ``bin``) for one mooring system.

    ``stream`` names the random stream of the phases (:func:`moorlife.conventions.case_rng`);
    the default ``None`` is the dimension, as for ``simulations.zarr`` and ``discrete.zarr``.
    Another name (the truth target's ``"truth"``) gives every id phases independent of the
    case or bin with the same id.

    Returns the completed output store (also written to ``output``; resumable through the
    partial store of :mod:`moorlife.parallel`).
    """
    from moorlife import simulate
    from moorlife.config import fingerprint
    from moorlife.parallel import dataset_digest, map_cases

    log = log or logging.getLogger(__name__)
    stream = dim if stream is None else str(stream)
    cases = open_zarr(cases_path)
    if dim not in cases.dims:
        raise ValueError(f"{cases_path}: expected a dimension {dim!r}, found {tuple(cases.dims)}")
    platform_ds = open_platform_nc(platform_nc)
    platform_cfg = read_platform_config(platform_yaml)
    row = {**dict(mooring_row), "mooring_system": mooring_system}
    model = simulate.prepare_model(platform_ds, platform_cfg, row, mooring_cfg, sim_cfg)
    log.info("%s: %s mooring, %d sea states along %r", mooring_system, model.mooring_kind, cases.sizes[dim], dim)
    fp = fingerprint(
        "simulate-v2", dim if stream == dim else f"{dim}/{stream}", moorlife.__version__, mooring_system, row, int(seed), dict(sim_cfg), dict(mooring_cfg or {}), dict(fatigue_cfg or {}),
        dict(stats_cfg or {}), platform_cfg, dataset_digest(cases), dataset_digest(platform_ds),
    )
    kwargs = dict(mooring_system=mooring_system, seed=int(seed), stream=stream, model_inputs=model, sim_cfg=dict(sim_cfg),
                  fatigue_cfg=dict(fatigue_cfg or {}), stats_cfg=dict(stats_cfg or {}))
    attrs = {"mooring_system": mooring_system, "mooring_model": model.mooring_kind, "seed": int(seed),
             "duration": float(sim_cfg.get("duration", 3600.0)), "dt": float(sim_cfg.get("dt", 0.1))}
    if stream != dim:  # the default stores keep their attributes unchanged
        attrs["random_stream"] = stream
    ds = map_cases(simulate.simulate_batch, cases, output, dim=dim, func_kwargs=kwargs,
                   batch_size=int(sim_cfg.get("batch_size", 8)), fingerprint=fp, threads=threads, log=log, attrs=attrs,
                   attrs_of=simulate.output_attrs)
    return ds
