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
from pathlib import Path
from typing import Any, Protocol

import numpy as np
import xarray as xr

__all__ = [
    "BLAS_ENV",
    "SCHEDULER_ENV",
    "pin_blas_threads",
    "restore_env",
    "dask_client",
    "check_scheduler_address",
    "temporary_security",
    "batch_slices",
    "dataset_digest",
    "BatchSink",
    "map_batches",
    "Progress",
    "format_duration",
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
#: glibc's allocator in the workers of a LocalCluster: keep freed memory for the next batch. A
#: batch allocates arrays of hundreds of MB (the wave kinematics of every strip); by default
#: glibc maps each afresh and unmaps it when freed (Dask also sets ``MALLOC_TRIM_THRESHOLD_`` to
#: 64 kB), so that the kernel faults in and clears every page again, batch after batch: 15-20 %
#: of a worker's CPU, measured. The worker's memory stays at its peak until the rule ends.
WORKER_MALLOC_ENV: dict[str, str] = {"MALLOC_MMAP_MAX_": "0", "MALLOC_TRIM_THRESHOLD_": str(4 << 30)}
_log = logging.getLogger("moorlife.parallel")
#: The progress lines for the terminal (:func:`moorlife.io.logs.log_to` shows them there).
_progress = logging.getLogger("moorlife.progress")
_progress.propagate = False  # the rule's log has the batch line already


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


def check_scheduler_address(address: str) -> str:
    """Refuse a scheduler address that cannot be one, naming where it came from.

    Returns the address unchanged. Accepted: ``tcp://host:port``, ``tls://host:port``, or
    ``host:port`` (TCP), with a port number 1-65535.
    """
    from distributed.comm import parse_address
    from distributed.comm.addressing import parse_host_port

    where = f"environment variable {SCHEDULER_ENV}" if address == os.environ.get(SCHEDULER_ENV) else "scheduler address"
    try:
        scheme, loc = parse_address(address)
        if scheme not in ("tcp", "tls", "inproc", "ucx", "ws", "wss"):
            raise ValueError(scheme)
        if scheme in ("tcp", "tls", "ws", "wss"):
            _, port = parse_host_port(loc)
            if not 0 < int(port) < 65536:
                raise ValueError(port)
    except (ValueError, TypeError):
        raise ValueError(
            f"{where} = {address!r} is not a Dask scheduler address; expected tls://host:port (or tcp://host:port)"
        ) from None
    return address


def _openssl_security(folder: Path) -> Any:
    """A :class:`distributed.security.Security` from a self-signed certificate made by ``openssl``."""
    import subprocess

    from distributed.security import Security

    key, cert = folder / "key.pem", folder / "cert.pem"
    subprocess.run(
        [
            "openssl",
            "req",
            "-x509",
            "-newkey",
            "ec",
            "-pkeyopt",
            "ec_paramgen_curve:prime256v1",
            "-nodes",
            "-keyout",
            str(key),
            "-out",
            str(cert),
            "-days",
            "7",
            "-subj",
            "/CN=moorlife-dask",
        ],
        check=True,
        capture_output=True,
        timeout=60,
    )
    os.chmod(key, 0o600)
    return Security(
        tls_ca_file=str(cert),
        tls_client_cert=str(cert),
        tls_client_key=str(key),
        tls_scheduler_cert=str(cert),
        tls_scheduler_key=str(key),
        tls_worker_cert=str(cert),
        tls_worker_key=str(key),
        require_encryption=True,
    )


@contextlib.contextmanager
def temporary_security() -> Iterator[Any]:
    """TLS credentials valid for one private cluster, removed afterwards.

    ``Security.temporary()`` (in memory; needs the ``cryptography`` package) when available,
    else a self-signed certificate made with the ``openssl`` command in a private folder (mode
    0700, key 0600). Scheduler, workers and client all require it: a process without the
    certificate, e.g. another local user's, cannot connect.
    """
    import subprocess
    import tempfile

    from distributed.security import Security

    try:
        temporary = Security.temporary()
    except ImportError:
        temporary = None
    if temporary is not None:
        yield temporary
        return
    with tempfile.TemporaryDirectory(prefix="moorlife-dask-") as tmp:
        os.chmod(tmp, 0o700)
        try:
            sec = _openssl_security(Path(tmp))
        except (OSError, subprocess.SubprocessError) as exc:
            raise RuntimeError(
                "cannot make TLS credentials for the private Dask cluster: install the 'cryptography' package "
                f"or the 'openssl' command ({exc})"
            ) from exc
        yield sec


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

    Notes
    -----
    The private LocalCluster listens on 127.0.0.1 only and speaks TLS with temporary
    credentials (:func:`temporary_security`): a Dask scheduler runs any function a client
    sends, so without them any local user of a shared host could run code as the study's user.

    An external cluster is secured by its owner: start the scheduler and workers with TLS
    (``dask scheduler --tls-ca-file ca.pem --tls-cert cert.pem --tls-key key.pem``, the same
    for ``dask worker``) and give the client the same through Dask's configuration, which
    :class:`distributed.security.Security` reads: ``distributed.comm.require-encryption: true``
    and ``distributed.comm.tls.{ca-file, client.cert, client.key}`` in ``~/.config/dask/*.yaml``
    or the environment (``DASK_DISTRIBUTED__COMM__TLS__CA_FILE=...``); then set
    ``DASK_SCHEDULER_ADDRESS=tls://host:port``. A ``tcp://`` address is unauthenticated and
    logged as such.
    """
    from distributed import Client, LocalCluster
    from distributed.security import Security

    address = address or os.environ.get(SCHEDULER_ENV) or None
    if address:
        check_scheduler_address(address)
        if not address.startswith("tls://"):
            _log.warning(
                "the Dask scheduler at %s is not TLS-secured: anyone who can reach it can run code on it", address
            )
        _log.info("joining the Dask scheduler at %s", address)
        with Client(address, timeout="60s", security=Security()) as client:
            yield client
        return
    import dask

    old = pin_blas_threads()
    # the nanny puts these into this process's environment before it spawns a worker (glibc reads
    # them at process start): put them back afterwards, as the BLAS pins
    old.update({k: os.environ.get(k) for k in WORKER_MALLOC_ENV})
    spawn_env = {**dask.config.get("distributed.nanny.pre-spawn-environ", default={}), **WORKER_MALLOC_ENV}
    n = max(1, int(threads))
    env = {k: "1" for k in BLAS_ENV}
    try:
        with (
            dask.config.set({"distributed.nanny.pre-spawn-environ": spawn_env}),
            temporary_security() as security,
            LocalCluster(
                n_workers=n,
                threads_per_worker=1,
                processes=True,
                host="127.0.0.1",
                protocol="tls://",
                security=security,
                scheduler_port=0,
                dashboard_address="127.0.0.1:0",
                silence_logs=logging.WARNING,
                env=env,
            ) as cluster,
            Client(cluster, security=security) as client,
        ):
            _log.info(
                "LocalCluster (TLS) with %d worker(s) at %s, dashboard %s",
                n,
                cluster.scheduler_address,
                client.dashboard_link,
            )
            try:
                yield client
            finally:
                _close_workers(cluster)
    finally:
        restore_env(old)


def _close_workers(cluster: Any, timeout: float = 30.0) -> None:
    """Close a LocalCluster's workers before its scheduler.

    Closing the cluster stops the scheduler first; a worker whose heartbeat is under way then
    logs ``Failed to communicate with scheduler during heartbeat`` (``CommClosedError``) at
    ERROR level, after every result was written. Scaling to zero closes the workers through
    their nannies while the scheduler still answers.
    """
    cluster.scale(0)
    end = time.monotonic() + timeout
    while cluster.workers and time.monotonic() < end:
        time.sleep(0.05)


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


def format_duration(seconds: float) -> str:
    """``3725.0`` -> ``"1 h 02 min"``, ``75.0`` -> ``"1 min 15 s"``, ``8.2`` -> ``"8 s"``."""
    s = max(0, int(round(seconds)))
    if s >= 3600:
        return f"{s // 3600} h {s % 3600 // 60:02d} min"
    if s >= 60:
        return f"{s // 60} min {s % 60:02d} s"
    return f"{s} s"


class Progress:
    """States done, of how many, and the time left, for the log line of each finished batch.

    The estimate is the elapsed time of this run per state computed in this run, times the
    states still to do (states resumed from a partial store count as done and cost nothing).

    Parameters
    ----------
    total : int
        Every state of the store.
    todo : int
        The states this run computes (``total`` minus those already in the partial store).
    label : str
        What is computed, e.g. the store's path.
    clock : callable
        Seconds, monotonic (tests pass a fake one).
    """

    def __init__(self, total: int, todo: int, label: str = "", clock: Callable[[], float] = time.perf_counter):
        self.total, self.todo, self.label, self.clock = int(total), int(todo), label, clock
        self.done_here = 0
        self.t0 = clock()

    def advance(self, n: int) -> str:
        """Count ``n`` more states done in this run; the progress line."""
        self.done_here += int(n)
        elapsed = self.clock() - self.t0
        done = self.total - self.todo + self.done_here
        left = self.todo - self.done_here
        pct = 100.0 * done / self.total if self.total else 100.0
        eta = "done" if left <= 0 else f"about {format_duration(elapsed / self.done_here * left)} left"
        head = f"{self.label}: " if self.label else ""
        return f"{head}{done}/{self.total} states ({pct:.0f} %), {format_duration(elapsed)} elapsed, {eta}"


def _static_kwargs(kwargs: dict[str, Any]) -> dict[str, Any]:
    """The static arguments of every batch, as a task result the scheduler can recompute."""
    return kwargs


def _run_batch(
    func: Callable[..., Mapping[str, np.ndarray]],
    kwargs: Mapping[str, Any],
    case_vars: Mapping[str, np.ndarray],
    case_ids: np.ndarray,
) -> dict[str, np.ndarray]:
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
    label: str = "",
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
    label : str
        Names the work in the progress lines (e.g. the store's path).

    Notes
    -----
    After each finished batch one line goes to ``log`` (the rule's log): the batch, the states
    done of how many, the elapsed time and an estimate of the time left (:class:`Progress`).
    The same line goes to the ``moorlife.progress`` logger, which
    :func:`moorlife.io.logs.log_to` shows on the terminal at most every
    ``moorlife.io.logs.TERMINAL_EVERY`` seconds (and always the last one).

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
    progress = Progress(len(ids), sum(len(range(len(ids))[slices[b]]) for b in todo), label)

    def _submit_all(cl: Any) -> None:
        run = uuid.uuid4().hex[:12]
        # The static arguments are a task, not scattered data: when every worker holding them
        # is lost (a restart, a preempted node), the scheduler computes them again from the
        # task; scattered data would be gone for good and cancel every batch still to run.
        kw = cl.submit(_static_kwargs, dict(func_kwargs), key=f"moorlife-{run}-kwargs", pure=False)
        # ... and every worker holds a copy before the batches are submitted: the scheduler puts
        # a task where its data is, so with the arguments on one worker every batch queued there
        # (measured: 2 workers no faster than 1, 48 % efficiency; benchmarks/bench_parallel.py).
        from distributed import wait

        wait(kw)
        cl.replicate([kw])
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
            line = progress.advance(len(range(len(ids))[slices[b]]))
            log.info("batch %d/%d done (%d of %d this run); %s", b + 1, len(slices), k, len(todo), line)
            _progress.info(line, extra={"progress_final": k == len(todo)})
            fut.release()
        if failure is not None:
            raise failure

    if client is not None:
        _submit_all(client)
    else:
        with dask_client(threads) as cl:
            _submit_all(cl)
