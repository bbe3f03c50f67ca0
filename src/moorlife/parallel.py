"""Dask fan-out of a pure per-case function over batches of cases.

This module holds Dask only and touches no file: :func:`map_batches` sends each batch still to
do (one Dask task per batch) to the workers and hands every finished batch to a sink in the
driver, which is the only writer. The resumable Zarr store that is the sink of the workflow's
stages is :class:`moorlife.io.partial.PartialStore`; :func:`moorlife.stages.fanout.map_cases`
puts the two together.

The cluster is either a :class:`distributed.LocalCluster` sized from the rule's threads (one
single-threaded worker process per thread, BLAS pinned to one thread, bound to 127.0.0.1), or an
existing scheduler named by the ``DASK_SCHEDULER_ADDRESS`` environment variable. The address is
read from the environment, not from the config, so changing it reruns nothing.
"""

from __future__ import annotations

import contextlib
import hashlib
import logging
import os
import time
import uuid
from collections.abc import Callable, Iterator, Mapping
from typing import Any, Protocol

import numpy as np
import xarray as xr

__all__ = [
    "BLAS_ENV",
    "SCHEDULER_ENV",
    "pin_blas_threads",
    "restore_env",
    "dask_client",
    "batch_slices",
    "dataset_digest",
    "BatchSink",
    "map_batches",
]

SCHEDULER_ENV = "DASK_SCHEDULER_ADDRESS"
#: Environment variables that size BLAS / OpenMP thread pools; all set to 1 for workers.
BLAS_ENV: tuple[str, ...] = (
    "OMP_NUM_THREADS",
    "OPENBLAS_NUM_THREADS",
    "MKL_NUM_THREADS",
    "VECLIB_MAXIMUM_THREADS",
    "NUMEXPR_NUM_THREADS",
    "NUMBA_NUM_THREADS",
)
_log = logging.getLogger("moorlife.parallel")


def pin_blas_threads() -> dict[str, str | None]:
    """Set every BLAS/OpenMP thread variable to 1 in this process's environment.

    Snakemake exports ``OMP_NUM_THREADS`` equal to the rule's threads; worker processes
    inherit the environment when they start, so this must run before the cluster starts.
    Returns the previous values (None: unset), for :func:`restore_env`.
    """
    old = {k: os.environ.get(k) for k in BLAS_ENV}
    os.environ.update({k: "1" for k in BLAS_ENV})
    return old


def restore_env(old: Mapping[str, str | None]) -> None:
    """Put environment variables back as :func:`pin_blas_threads` found them (None: unset).

    The driver must not keep the pinned values: Numba reads ``NUMBA_NUM_THREADS`` again at
    every later compilation and refuses a value that differs from its running thread pool.
    """
    for k, v in old.items():
        if v is None:
            os.environ.pop(k, None)
        else:
            os.environ[k] = v


@contextlib.contextmanager
def dask_client(threads: int = 1, *, address: str | None = None) -> Iterator[Any]:
    """A :class:`distributed.Client` on an existing scheduler or a private LocalCluster.

    Parameters
    ----------
    threads : int
        Worker processes of the LocalCluster (one thread each). Ignored with a scheduler.
    address : str, optional
        Scheduler address; defaults to ``$DASK_SCHEDULER_ADDRESS``. Workers of an external
        cluster must be able to ``import moorlife`` (install the package on them).
    """
    from distributed import Client, LocalCluster

    address = address or os.environ.get(SCHEDULER_ENV) or None
    if address:
        _log.info("joining the Dask scheduler at %s", address)
        with Client(address, timeout="60s") as client:
            yield client
        return
    old = pin_blas_threads()
    n = max(1, int(threads))
    env = {k: "1" for k in BLAS_ENV}
    try:
        with LocalCluster(
            n_workers=n,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            scheduler_port=0,
            dashboard_address="127.0.0.1:0",
            silence_logs=logging.WARNING,
            env=env,
        ) as cluster, Client(cluster) as client:
            _log.info("LocalCluster with %d worker(s), dashboard %s", n, client.dashboard_link)
            yield client
    finally:
        restore_env(old)


def batch_slices(n: int, batch_size: int) -> list[slice]:
    """Contiguous slices of at most ``batch_size`` covering ``range(n)``."""
    if batch_size < 1:
        raise ValueError(f"batch_size must be >= 1, got {batch_size}")
    return [slice(a, min(a + batch_size, n)) for a in range(0, n, batch_size)]


def dataset_digest(ds: xr.Dataset) -> str:
    """SHA-256 of a Dataset's variable names, dims and values (attrs excluded)."""
    h = hashlib.sha256()
    for name in sorted(map(str, ds.variables)):
        var = ds.variables[name]
        h.update(name.encode())
        h.update(repr(var.dims).encode())
        values = np.asarray(var.values)
        if values.dtype.kind in "OUS":
            h.update("\x1f".join(map(str, values.ravel())).encode())
        else:
            h.update(np.ascontiguousarray(values).tobytes())
    return h.hexdigest()


def _run_batch(func: Callable[..., Mapping[str, np.ndarray]], kwargs: Mapping[str, Any],
               case_vars: Mapping[str, np.ndarray], case_ids: np.ndarray) -> dict[str, np.ndarray]:
    out = func(dict(case_vars), case_ids=case_ids, **kwargs)
    return {k: np.asarray(v) for k, v in out.items()}


class BatchSink(Protocol):
    """Where finished batches go (:class:`moorlife.io.partial.PartialStore` is the store one)."""

    slices: list[slice]

    def todo(self) -> list[int]:
        """Indices of the batches still to compute."""
        ...

    def write(self, b: int, result: Mapping[str, np.ndarray]) -> None:
        """Keep the result of batch ``b``."""
        ...


def map_batches(
    func: Callable[..., Mapping[str, np.ndarray]],
    cases: xr.Dataset,
    sink: BatchSink,
    *,
    dim: str,
    func_kwargs: Mapping[str, Any],
    threads: int = 1,
    log: logging.Logger | None = None,
    client: Any | None = None,
) -> None:
    """Map a pure per-case function over the batches still to do, handing each result to the sink.

    Parameters
    ----------
    func : callable
        ``func(case_vars, case_ids=ids, **func_kwargs) -> {name: array (B, ...)}``, where
        ``case_vars`` maps each numeric data variable of ``cases`` with only ``dim`` to a
        ``(B,)`` array. It must be importable by the workers and depend only on its arguments.
    cases : xarray.Dataset
        The sea states, along ``dim`` (``case`` or ``bin``).
    sink : BatchSink
        Gives the batches (``sink.slices``, ``sink.todo()``) and takes each finished one
        (``sink.write(b, result)``, called in this process only: the driver is the only writer).
    dim : str
        The case dimension.
    func_kwargs : mapping
        Static arguments, sent once to every worker.
    threads : int
        Workers of the LocalCluster when no scheduler address is set.
    log : logging.Logger, optional
        Progress goes here (the rule's log).
    client : distributed.Client, optional
        Use this client instead of creating one.

    Raises
    ------
    Exception
        The first batch failure, after every batch that does finish has been handed over.
    """
    log = log or _log
    todo = sink.todo()
    if not todo:
        return
    slices = sink.slices
    ids = np.asarray(cases[dim].values)
    case_names = [k for k, v in cases.data_vars.items() if v.dims == (dim,) and v.dtype.kind in "fiub"]
    t0 = time.perf_counter()

    def _submit_all(cl: Any) -> None:
        [kw] = cl.scatter([dict(func_kwargs)], broadcast=True, hash=False)
        run = uuid.uuid4().hex[:12]
        futures = {}
        for b in todo:
            sl = slices[b]
            payload = {k: np.asarray(cases[k].values[sl]) for k in case_names}
            fut = cl.submit(_run_batch, func, kw, payload, ids[sl], key=f"moorlife-{run}-b{b}", pure=False)
            futures[fut] = b
        from distributed import as_completed

        failure: BaseException | None = None
        for k, fut in enumerate(as_completed(futures), start=1):
            b = futures[fut]
            try:
                result = fut.result()
            except Exception as exc:  # keep writing the batches that do finish, then raise
                log.error("batch %d/%d failed: %s", b + 1, len(slices), exc)
                failure = failure or exc
                continue
            sink.write(b, result)
            log.info("batch %d/%d done (%d of %d this run, %.1f s)", b + 1, len(slices), k, len(todo),
                     time.perf_counter() - t0)
            fut.release()
        if failure is not None:
            raise failure

    if client is not None:
        _submit_all(client)
    else:
        with dask_client(threads) as cl:
            _submit_all(cl)
