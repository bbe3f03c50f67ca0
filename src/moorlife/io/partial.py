"""The partial (in-progress, resumable) store of a fanned-out stage.

:func:`moorlife.parallel.map_batches` computes batches of cases; this module is where they go.
The driver is the only writer. Finished batches are written into a *partial* store outside
the declared output (:func:`moorlife.io.partial_path`), one region per batch, aligned with
the store's chunks, followed by the batch's done flag. The store records a fingerprint of
everything that determines the numbers; a rerun with the same fingerprint computes only the
missing batches, a different one starts afresh. Scheduling settings (the batch size) are not
part of the fingerprint: a partial store keeps the batch size it was started with, so a rerun
with another batch size reuses every finished batch. When every batch is done the store is
flagged complete and renamed into place; a complete partial store whose rename failed (e.g.
``EXDEV``) is promoted by the next run without recomputing anything.
"""

from __future__ import annotations

import logging
import os
import shutil
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from moorlife import io as mio
from moorlife import names
from moorlife.parallel import batch_slices

__all__ = ["PartialStore"]

_DONE = "_batch_done"
_BATCH_DIM = "_batch"
_log = logging.getLogger("moorlife.io.partial")


def _dims_for(name: str, arr: np.ndarray, dim: str) -> tuple[str, ...]:
    if arr.ndim == 1:
        return (dim,)
    if arr.ndim == 2 and arr.shape[1] == len(names.LINES):
        return (dim, names.LINE)
    return (dim, *(f"{name}_{i}" for i in range(1, arr.ndim)))


def _template(
    first: Mapping[str, np.ndarray],
    cases: xr.Dataset,
    dim: str,
    n_batches: int,
    attrs_of: Callable[[str], Mapping[str, str]] | None = None,
) -> xr.Dataset:
    n = cases.sizes[dim]
    data: dict[str, Any] = {}
    for name, arr in first.items():
        dims = _dims_for(name, arr, dim)
        shape = (n, *arr.shape[1:])
        fill = np.nan if arr.dtype.kind == "f" else 0
        attrs = names.SIM_ATTRS.get(name, {})
        if attrs_of is not None:
            try:
                attrs = {**attrs, **attrs_of(name)}
            except KeyError:
                pass
        data[name] = xr.Variable(dims, np.full(shape, fill, dtype=arr.dtype), attrs=dict(attrs))
    data[_DONE] = xr.Variable((_BATCH_DIM,), np.zeros(n_batches, dtype="int8"))
    coords: dict[str, Any] = {dim: cases[dim].values}
    if any(names.LINE in v.dims for v in data.values()):
        coords[names.LINE] = list(names.LINES)
    return xr.Dataset(data, coords=coords)


def _open_partial(path: Path, fp: str) -> tuple[xr.Dataset | None, int | None]:
    """The partial store at ``path`` if its fingerprint is ``fp`` (and its batch size), else
    (None, None) after removing whatever is there."""
    if not path.exists():
        return None, None
    try:
        ds = xr.open_zarr(path, **mio.ZARR_KW)
        if ds.attrs.get("fingerprint") != fp:
            _log.info("partial store %s has another fingerprint: starting afresh", path)
            raise ValueError("fingerprint")
        if not ds.attrs.get(mio.COMPLETE_ATTR, False) and _DONE not in ds:
            raise ValueError("neither complete nor carrying its batch flags")
        return ds, (None if ds.attrs.get(mio.COMPLETE_ATTR, False) else int(ds.attrs["batch_size"]))
    except Exception:
        shutil.rmtree(path, ignore_errors=True)
        return None, None


def _write_batch(path: Path, dim: str, sl: slice, b: int, result: Mapping[str, np.ndarray]) -> None:
    import zarr

    region = xr.Dataset({k: (_dims_for(k, v, dim), v) for k, v in result.items()})
    region = region.drop_vars([c for c in region.coords], errors="ignore")
    region.to_zarr(
        path, region={dim: sl, **{d: slice(None) for d in region.dims if d != dim}}, mode="r+", **mio.ZARR_KW
    )
    zarr.open_group(str(path), mode="r+")[_DONE][b] = 1


class PartialStore:
    """The resumable in-progress version of one declared output store.

    Parameters
    ----------
    output : path-like
        The declared output store; the partial store lives at :func:`moorlife.io.partial_path`.
    cases : xarray.Dataset
        The sea states, along ``dim``.
    dim : str
        The case dimension (``case`` or ``bin``).
    fingerprint : str
        Digest of everything that determines the numbers (and nothing that does not).
    batch_size : int
        Cases per batch of a new store; an existing store with the same fingerprint keeps
        its own.
    attrs_of : callable, optional
        ``attrs_of(name) -> {"units": ..., ...}`` for output variables beyond the contract's
        (``KeyError`` for none); contract variables get :data:`moorlife.names.SIM_ATTRS`.
    log : logging.Logger, optional
        Progress goes here.

    Attributes
    ----------
    path : pathlib.Path
        The partial store.
    batch_size : int
        Cases per batch (the stored one when resuming).
    slices : list of slice
        The batches' case ranges.
    done : numpy.ndarray of bool
        Which batches are already written.
    complete : bool
        True when a previous run finished the store but did not promote it.
    """

    def __init__(
        self,
        output: str | os.PathLike[str],
        cases: xr.Dataset,
        *,
        dim: str,
        fingerprint: str,
        batch_size: int,
        attrs_of: Callable[[str], Mapping[str, str]] | None = None,
        log: logging.Logger | None = None,
    ) -> None:
        self.output = Path(output)
        self.path = mio.partial_path(self.output)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.cases, self.dim, self.fingerprint, self.attrs_of = cases, dim, fingerprint, attrs_of
        self.log = log or _log
        existing, stored_bs = _open_partial(self.path, fingerprint)
        self.batch_size = stored_bs or int(batch_size)
        self.slices = batch_slices(cases.sizes[dim], self.batch_size)
        self.complete = bool(existing is not None and existing.attrs.get(mio.COMPLETE_ATTR, False))
        self.done = np.zeros(len(self.slices), dtype=bool)
        self._created = existing is not None
        if self.complete:
            self.done[:] = True
            self.log.info("%s is complete (a previous run did not promote it): promoting it", self.path)
        elif existing is not None:
            self.done = np.asarray(existing[_DONE].values, dtype=bool)
            self.log.info(
                "resuming %s: %d of %d batches already done", self.path, int(self.done.sum()), len(self.slices)
            )

    def todo(self) -> list[int]:
        """Indices of the batches still to compute."""
        return [b for b in range(len(self.slices)) if not self.done[b]]

    def write(self, b: int, result: Mapping[str, np.ndarray]) -> None:
        """Write batch ``b`` (the store is created from the first batch written), then flag it done."""
        if not self._created:
            tpl = _template(result, self.cases, self.dim, len(self.slices), self.attrs_of)
            tpl.attrs.update({"fingerprint": self.fingerprint, "batch_size": self.batch_size})
            enc = {v: {"chunks": (self.batch_size, *tpl[v].shape[1:])} for v in tpl.data_vars if v != _DONE}
            enc[_DONE] = {"chunks": (1,)}
            mio.storable(tpl).to_zarr(self.path, mode="w", encoding=enc, **mio.ZARR_KW)
            self._created = True
        _write_batch(self.path, self.dim, self.slices[b], b, result)
        self.done[b] = True

    def finalise(self, attrs: Mapping[str, Any] | None = None) -> xr.Dataset:
        """Check every batch, add the case variables, flag complete, and rename into place.

        The fingerprint stays in the store's attributes throughout, so that a run killed, or
        a rename that failed, during this step is picked up by the next run without
        recomputing a batch. Returns the promoted output, loaded.
        """
        import zarr

        if not self.complete:
            group = zarr.open_group(str(self.path), mode="r+")
            if not bool(np.all(group[_DONE][:] == 1)):
                raise RuntimeError(f"{self.path}: not every batch is done; refusing to promote it")
            dim, cases = self.dim, self.cases
            extra = cases[[k for k, v in cases.data_vars.items() if v.dims == (dim,)]]
            extra = extra.reset_coords(drop=True).drop_vars(dim, errors="ignore")
            # appending replaces the root attributes: carry the fingerprint through
            # (and not the cases' own completion flag: this store is complete only below)
            kept = {k: v for k, v in extra.attrs.items() if k != mio.COMPLETE_ATTR}
            extra = extra.assign_attrs({**kept, "fingerprint": self.fingerprint, "batch_size": self.batch_size})
            mio.storable(extra).to_zarr(self.path, mode="a", **mio.ZARR_KW)
            group = zarr.open_group(str(self.path), mode="r+")
            group.attrs.update({**dict(attrs or {}), mio.COMPLETE_ATTR: True})
            del group.attrs["batch_size"]  # scheduling only: not an attribute of the result
        group = zarr.open_group(str(self.path), mode="r+")
        if _DONE in group:
            del group[_DONE]
        mio.promote(self.path, self.output)
        return mio.open_zarr(self.output)
