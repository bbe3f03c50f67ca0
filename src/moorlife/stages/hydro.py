"""Stage ``hydro``: the platform's hydrodynamic coefficients, from a BEM run (Capytaine) or
WAMIT files, -> ``results/hydro/platform.nc`` (rule ``hydro``)."""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any

import xarray as xr

from moorlife import hydro
from moorlife.io.platform import write_platform_nc
from moorlife.io.wamit import read_wamit_dataset
from moorlife.stages import logged

__all__ = ["run"]

PathLike = str | os.PathLike[str]


def run(
    *,
    store: PathLike,
    bem: Mapping[str, Any],
    threads: int = 1,
    log: PathLike | None = None,
) -> xr.Dataset:
    """The hydrodynamic model of the platform.

    Parameters
    ----------
    store : path-like
        The output NetCDF file.
    bem : mapping
        :func:`moorlife.hydro.bem_settings` of the ``hydro`` section and ``platform.yaml``:
        exactly what changes the result.
    threads : int
        BEM worker processes (the rule's threads).
    log : path-like, optional
        The rule's log file.
    """
    env = bem["environment"]
    with logged(log, __name__) as logger:
        if bem["source"] == "wamit":
            logger.info("hydro: WAMIT files %s.*", bem["wamit_prefix"])
            ds = read_wamit_dataset(
                bem["wamit_prefix"], rho=env["rho_water"], g=env["gravity"], water_depth=env["water_depth"]
            )
        else:
            ds = hydro.bem_from_settings(bem, n_jobs=threads)
        write_platform_nc(ds, store)
        return ds
