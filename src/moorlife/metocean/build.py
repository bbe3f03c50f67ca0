"""The contract hindcast from the ``hindcast:`` configuration section (:func:`build_hindcast`).

Kept apart because it reads files through :mod:`moorlife.io.hindcast` (which imports this
package): the import is deferred to the ``file`` branch.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from moorlife.metocean.adapters import hindcast_dataset
from moorlife.metocean.errors import HindcastError
from moorlife.metocean.params import CleaningPolicy, SyntheticParams
from moorlife.metocean.synthetic import generate_synthetic, hourly_time

__all__ = ["build_hindcast"]

log = logging.getLogger("moorlife.metocean")


def build_hindcast(cfg: Mapping[str, Any], seed: int, base_dir: str = ".") -> xr.Dataset:
    """The contract hindcast Dataset from the ``hindcast:`` configuration section.

    Dispatches on ``cfg["source"]``: ``synthetic`` runs :func:`generate_synthetic` over
    ``start``..``end``; ``file`` loads ``path`` (relative to ``base_dir``) with
    :func:`moorlife.io.hindcast.read_hindcast`, validates it and cuts it to ``start``..``end``.

    Parameters
    ----------
    cfg : mapping
        The ``hindcast`` section (schema defaults filled in); a whole study config with a
        ``hindcast`` key is accepted too.
    seed : int
        Global seed (``config.yaml: seed``).
    base_dir : str
        Directory that relative paths are resolved against.
    """
    if "hindcast" in cfg and isinstance(cfg["hindcast"], Mapping):
        cfg = cfg["hindcast"]
    site = dict(cfg.get("site", {}))
    hub, alpha = float(cfg["hub_height"]), float(cfg["shear_exponent"])
    common = {"site": site.get("name", ""), "lon": site.get("lon", np.nan), "lat": site.get("lat", np.nan), "hub_height": hub}
    if cfg.get("source", "synthetic") == "synthetic":
        params = SyntheticParams.from_mapping(cfg.get("synthetic"))
        time = hourly_time(cfg["start"], cfg["end"])
        out = generate_synthetic(time, params, seed, hub, alpha)
        log.info(
            "synthetic hindcast, seed %d: %d hours %s..%s, mean Hs %.2f m, max Hs %.2f m, mean wind %.2f m/s at %g m",
            seed, time.size, cfg["start"], cfg["end"], out["hs"].mean(), out["hs"].max(), out["wind_speed"].mean(), hub,
        )
        return hindcast_dataset(
            time, out, source=f"moorlife synthetic BiMEP-like hindcast (seed {seed})",
            extra_attrs={"wind_reference_height": params.reference_height, "shear_exponent": alpha}, **common,
        )
    if cfg.get("source") != "file":
        raise HindcastError(f"hindcast.source = {cfg.get('source')!r}: expected 'synthetic' or 'file'")
    from moorlife.io.hindcast import read_hindcast

    if not cfg.get("path"):
        raise HindcastError("hindcast.source is 'file' but hindcast.path is not set")
    return read_hindcast(
        cfg["path"],
        start=cfg["start"],
        end=cfg["end"],
        hub_height=hub,
        shear_exponent=alpha,
        columns=cfg.get("columns"),
        fmt=cfg.get("format", "auto"),
        measured_height=cfg.get("measured_height"),
        wave_dir_convention=cfg.get("wave_dir_convention", "auto"),
        cleaning=CleaningPolicy.from_mapping(cfg.get("cleaning")),
        site=common["site"],
        lon=common["lon"],
        lat=common["lat"],
        base_dir=base_dir,
    )
