"""The outputs of a simulation store as matrices for the RBF, and back.

A column is ``(variable, line)``, with line ``None`` for a per-state scalar.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import xarray as xr

from moorlife import names

__all__ = ["DEFAULT_OUTPUTS", "output_columns", "stack_outputs", "unstack_outputs"]

log = logging.getLogger("moorlife.lifecycle")

#: Outputs rebuilt by default: the contract outputs of simulations.zarr.
DEFAULT_OUTPUTS: tuple[str, ...] = names.SIM_SCALAR_VARS + names.SIM_LINE_VARS


def output_columns(ds: xr.Dataset, dim: str, wanted: Sequence[str]) -> list[tuple[str, str | None]]:
    """The (variable, line) columns of a simulation store that are rebuilt.

    Parameters
    ----------
    ds : xarray.Dataset
        ``simulations.zarr`` (dims ``case``, ``line``) or ``discrete.zarr``.
    dim : str
        ``"case"`` or ``"bin"``.
    wanted : sequence of str
        Variable names; missing ones are skipped (logged), so optional extras do not fail.

    Returns
    -------
    list of (name, line or None)
    """
    cols: list[tuple[str, str | None]] = []
    for v in wanted:
        if v not in ds:
            log.info("output %r not in the simulation store: not rebuilt", v)
            continue
        dims = ds[v].dims
        if dims == (dim,):
            cols.append((v, None))
        elif set(dims) == {dim, names.LINE}:
            cols += [(v, str(line)) for line in ds[names.LINE].values]
        else:
            raise ValueError(f"variable {v!r} has dims {dims}; expected ({dim!r},) or ({dim!r}, 'line')")
    return cols


def _label(col: tuple[str, str | None]) -> str:
    return col[0] if col[1] is None else f"{col[0]}/{col[1]}"


def stack_outputs(ds: xr.Dataset, dim: str, cols: Sequence[tuple[str, str | None]]) -> np.ndarray:
    """Matrix ``(n, k)`` of the columns of :func:`output_columns` along ``dim``."""
    out = np.empty((ds.sizes[dim], len(cols)))
    for j, (v, line) in enumerate(cols):
        da = ds[v] if line is None else ds[v].sel({names.LINE: line})
        out[:, j] = da.transpose(dim).to_numpy()
    return out


def unstack_outputs(
    values: np.ndarray, cols: Sequence[tuple[str, str | None]], dim: str, coords: Mapping[str, Any], attrs_of=None
) -> xr.Dataset:
    """Inverse of :func:`stack_outputs`: a Dataset with ``(dim,)`` and ``(dim, line)`` variables."""
    data: dict[str, Any] = {}
    by_var: dict[str, list[tuple[int, str | None]]] = {}
    for j, (v, line) in enumerate(cols):
        by_var.setdefault(v, []).append((j, line))
    for v, items in by_var.items():
        attrs = (attrs_of or _attrs)(v)
        if items[0][1] is None:
            data[v] = xr.Variable((dim,), values[:, items[0][0]], attrs)
        else:
            idx = [j for j, _ in items]
            data[v] = xr.DataArray(
                values[:, idx], dims=(dim, names.LINE), coords={names.LINE: [ln for _, ln in items]}, attrs=attrs
            )
    return xr.Dataset(data, coords=dict(coords))


def _attrs(name: str) -> dict[str, str]:
    try:
        return names.attrs_for(name)
    except KeyError:
        from moorlife.simulate import output_attrs

        try:
            return output_attrs(name)
        except KeyError:
            return {"units": "1"}
