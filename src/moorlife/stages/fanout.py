"""A pure per-case function fanned out with Dask into a resumable, complete Zarr store.

:func:`map_cases` joins the two halves: :func:`moorlife.parallel.map_batches` (Dask, no file)
and :class:`moorlife.io.partial.PartialStore` (the store, no Dask).
"""

from __future__ import annotations

import logging
import os
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np
import xarray as xr

from moorlife import parallel
from moorlife.io.partial import PartialStore

__all__ = ["map_cases"]


def map_cases(
    func: Callable[..., Mapping[str, np.ndarray]],
    cases: xr.Dataset,
    output: str | os.PathLike[str],
    *,
    dim: str,
    func_kwargs: Mapping[str, Any],
    batch_size: int,
    fingerprint: str,
    threads: int = 1,
    log: logging.Logger | None = None,
    client: Any | None = None,
    attrs: Mapping[str, Any] | None = None,
    attrs_of: Callable[[str], Mapping[str, str]] | None = None,
) -> xr.Dataset:
    """Map a pure per-case function over the cases and write a complete Zarr store.

    Parameters
    ----------
    func : callable
        ``func(case_vars, case_ids=ids, **func_kwargs) -> {name: array (B, ...)}``
        (see :func:`moorlife.parallel.map_batches`).
    cases : xarray.Dataset
        The sea states, along ``dim`` (``case`` or ``bin``).
    output : path-like
        The declared output store.
    dim : str
        The case dimension.
    func_kwargs : mapping
        Static arguments, sent once to every worker.
    batch_size : int
        Cases per task. A partial store keeps the batch size it was started with.
    fingerprint : str
        Digest of everything that determines the numbers (config, inputs, code version), and
        of nothing that does not (the batch size, the workers).
    threads : int
        Workers of the LocalCluster when no scheduler address is set.
    log : logging.Logger, optional
        Progress goes here (the rule's log).
    client : distributed.Client, optional
        Use this client instead of creating one.
    attrs : mapping, optional
        Extra attributes of the final store.
    attrs_of : callable, optional
        ``attrs_of(name) -> {"units": ..., ...}`` for output variables beyond the contract's
        (``KeyError`` for none); contract variables get :data:`moorlife.names.SIM_ATTRS`.

    Returns
    -------
    xarray.Dataset
        The complete store, loaded: the outputs plus the case variables.
    """
    store = PartialStore(
        output, cases, dim=dim, fingerprint=fingerprint, batch_size=batch_size, attrs_of=attrs_of, log=log
    )
    parallel.map_batches(
        func, cases, store, dim=dim, func_kwargs=func_kwargs, threads=threads, log=log, client=client, label=str(output)
    )
    return store.finalise(attrs)
