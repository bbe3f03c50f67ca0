"""Stage ``metocean``: the hourly hindcast (paper section 2, Fig. 3), synthetic or read from a
file (rules ``metocean`` and ``metocean_figures``)."""

from __future__ import annotations

import logging
import os
from collections.abc import Mapping
from typing import Any

import xarray as xr

from moorlife import metocean
from moorlife.io import open_zarr, save_figure, write_zarr
from moorlife.io.hindcast import read_hindcast
from moorlife.settings import fill_section
from moorlife.stages import logged

__all__ = ["build_hindcast", "run", "figures"]

PathLike = str | os.PathLike[str]
log = logging.getLogger("moorlife.metocean")


def build_hindcast(cfg: Mapping[str, Any], seed: int, base_dir: str = ".") -> xr.Dataset:
    """The contract hindcast Dataset from the ``hindcast:`` configuration section.

    Dispatches on ``cfg["source"]``: ``synthetic`` runs :func:`moorlife.metocean.generate_synthetic`
    over ``start``..``end``; ``file`` loads ``path`` (relative to ``base_dir``) with
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
    cfg = fill_section("hindcast", cfg, source="hindcast")  # missing keys: the schema's defaults
    site = cfg["site"]
    hub, alpha = float(cfg["hub_height"]), float(cfg["shear_exponent"])
    common = {"site": site["name"], "lon": site["lon"], "lat": site["lat"], "hub_height": hub}
    if cfg["source"] == "synthetic":
        params = metocean.SyntheticParams.from_config(cfg["synthetic"])
        time = metocean.hourly_time(cfg["start"], cfg["end"])
        out = metocean.generate_synthetic(time, params, seed, hub, alpha)
        log.info(
            "synthetic hindcast, seed %d: %d hours %s..%s, mean Hs %.2f m, max Hs %.2f m, mean wind %.2f m/s at %g m",
            seed,
            time.size,
            cfg["start"],
            cfg["end"],
            out["hs"].mean(),
            out["hs"].max(),
            out["wind_speed"].mean(),
            hub,
        )
        return metocean.hindcast_dataset(
            time,
            out,
            source=f"moorlife synthetic BiMEP-like hindcast (seed {seed})",
            extra_attrs={"wind_reference_height": params.reference_height, "shear_exponent": alpha},
            **common,
        )
    if cfg["source"] != "file":
        raise metocean.HindcastError(f"hindcast.source = {cfg.get('source')!r}: expected 'synthetic' or 'file'")
    if not cfg.get("path"):
        raise metocean.HindcastError("hindcast.source is 'file' but hindcast.path is not set")
    return read_hindcast(
        cfg["path"],
        start=cfg["start"],
        end=cfg["end"],
        hub_height=hub,
        shear_exponent=alpha,
        columns=cfg.get("columns"),
        fmt=cfg["format"],
        measured_height=cfg.get("measured_height"),
        wave_dir_convention=cfg["wave_dir_convention"],
        cleaning=metocean.CleaningPolicy.from_config(cfg["cleaning"]),
        site=common["site"],
        lon=common["lon"],
        lat=common["lat"],
        base_dir=base_dir,
    )


def run(
    *,
    store: PathLike,
    hindcast: Mapping[str, Any],
    seed: int,
    base_dir: str = ".",
    log: PathLike | None = None,
) -> xr.Dataset:
    """Build the hourly hindcast and write it as ``results/metocean/hindcast.zarr``.

    Parameters
    ----------
    store : path-like
        The output store.
    hindcast : mapping
        The ``hindcast`` config section.
    seed : int
        Global seed (``config.yaml: seed``).
    base_dir : str
        Directory that a relative ``hindcast.path`` is resolved against.
    log : path-like, optional
        The rule's log file.
    """
    with logged(log, __name__):
        ds = build_hindcast(dict(hindcast), int(seed), base_dir=base_dir)
        write_zarr(ds, store)
        return ds


def figures(
    *,
    hindcast: PathLike,
    wind_rose: PathLike,
    wave_rose: PathLike,
    hs_tp: PathLike,
    log: PathLike | None = None,
) -> None:
    """Wind rose, wave rose and Hs-Tp scatter of the hindcast (paper Fig. 3).

    Parameters
    ----------
    hindcast : path-like
        ``results/metocean/hindcast.zarr``.
    wind_rose, wave_rose, hs_tp : path-like
        The three PNG files.
    log : path-like, optional
        The rule's log file.
    """
    import matplotlib

    matplotlib.use("Agg")
    from moorlife.plots.metocean import plot_hs_tp, plot_wave_rose, plot_wind_rose

    with logged(log, __name__):
        ds = open_zarr(hindcast)
        save_figure(plot_wind_rose(ds), wind_rose)
        save_figure(plot_wave_rose(ds), wave_rose)
        save_figure(plot_hs_tp(ds), hs_tp)
