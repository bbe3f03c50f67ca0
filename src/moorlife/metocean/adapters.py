"""The contract hindcast Dataset (:func:`hindcast_dataset`)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import numpy.typing as npt
import xarray as xr

from moorlife.names import METOCEAN_ATTRS, METOCEAN_VARS, TIME

__all__ = ["WAVE_VARS", "WIND_VARS", "DIRECTION_CONVENTION", "hindcast_dataset"]

#: Wave variables and wind variables of the contract (order of ``METOCEAN_VARS`` kept).
WAVE_VARS: tuple[str, ...] = ("hs", "tp", "wave_dir")
WIND_VARS: tuple[str, ...] = ("wind_speed", "wind_dir")
DIRECTION_CONVENTION = "nautical: degrees clockwise from north, direction the wind or waves come from"


def hindcast_dataset(
    time: npt.ArrayLike,
    variables: Mapping[str, npt.ArrayLike],
    *,
    source: str,
    site: str,
    lon: float,
    lat: float,
    hub_height: float,
    extra_attrs: Mapping[str, Any] | None = None,
) -> xr.Dataset:
    """Assemble the contract Dataset of ``results/metocean/hindcast.zarr``.

    Parameters
    ----------
    time : array_like of datetime64, shape (n,)
    variables : mapping
        The variables of :data:`moorlife.names.METOCEAN_VARS`, each shape (n,) (the wind may
        be absent only for a waves-only inspection); others are ignored.
    source, site : str
        Provenance (``"synthetic (seed ...)"`` or the file) and site name.
    lon, lat : float
        Degrees east / north.
    hub_height : float
        m, the height of ``wind_speed``.
    extra_attrs : mapping, optional
        Further dataset attributes (e.g. generator parameters, wind measured height).
    """
    t = np.asarray(time).astype("datetime64[ns]")
    missing = [v for v in WAVE_VARS if v not in variables]
    if missing:
        raise KeyError(f"hindcast_dataset: missing variable(s) {missing}")
    data = {
        v: (TIME, np.asarray(variables[v], dtype=np.float64), dict(METOCEAN_ATTRS[v]))
        for v in METOCEAN_VARS
        if v in variables
    }
    ds = xr.Dataset(data, coords={TIME: (TIME, t, {"long_name": "time (UTC), hourly"})})
    if "wind_speed" in ds:
        ds["wind_speed"].attrs["height"] = f"{hub_height:g} m"
    ds.attrs.update(
        {
            "Conventions": "CF-1.10",
            "title": "moorlife hourly metocean hindcast",
            "source": source,
            "site": site,
            "lon": float(lon),
            "lat": float(lat),
            "hub_height": float(hub_height),
            "direction_convention": DIRECTION_CONVENTION,
        }
    )
    ds.attrs.update(dict(extra_attrs or {}))
    return ds
