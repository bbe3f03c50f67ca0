"""Logging of workflow rules to their ``log:`` file."""

from __future__ import annotations

import contextlib
import logging
import os
import sys
import traceback
from collections.abc import Iterator
from pathlib import Path

__all__ = ["log_to"]


@contextlib.contextmanager
def log_to(
    path: str | os.PathLike[str], level: int = logging.INFO, *, blas_threads: int | None = 1, capture_fds: bool = True
) -> Iterator[logging.Logger]:
    """Send the ``moorlife`` logger (and warnings) to a rule's log file.

    With ``capture_fds`` the block's standard output and error (file descriptors 1 and 2) go to
    the same file, and so do those of every process started inside it, which inherit them:
    Capytaine's warnings from the BEM's spawned solver processes ("water_depth >
    5*wavelength", printed by its own Rich handler) land in the log, not on the terminal.

    An exception raised inside the block is written to the log with its traceback and to
    standard error as one clear line, then re-raised so Snakemake marks the job failed.

    Inside the block BLAS/OpenMP pools are limited to ``blas_threads`` (None: no limit).
    Snakemake exports ``OMP_NUM_THREADS`` equal to the rule's threads, and multi-threaded
    BLAS changes the round-off (measured: 4e-9 relative in the prepared simulation model
    between 1 and 2 threads), so without the limit the numbers would depend on ``--cores``.
    Parallelism comes from Dask or joblib worker processes instead.
    """
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_bytes(b"")  # a fresh log; then append only, so the handler and fds 1/2 interleave
    handler = logging.FileHandler(p, mode="a", encoding="utf-8")
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(name)s: %(message)s"))
    logger = logging.getLogger("moorlife")
    logger.setLevel(level)
    logger.addHandler(handler)
    logging.captureWarnings(True)
    logging.getLogger("py.warnings").addHandler(handler)
    limits = contextlib.nullcontext()
    if blas_threads is not None:
        from threadpoolctl import threadpool_limits

        limits = threadpool_limits(limits=int(blas_threads))
    fds = _fds_to(p) if capture_fds else contextlib.nullcontext()
    try:
        with limits, fds:
            yield logger
    except BaseException as exc:  # fds 1 and 2 are back on the terminal here
        logger.error("failed: %s\n%s", exc, traceback.format_exc())
        print(f"moorlife error: {exc}", file=sys.stderr)
        raise
    finally:
        logger.removeHandler(handler)
        logging.getLogger("py.warnings").removeHandler(handler)
        handler.close()


def _flush_std() -> None:
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (AttributeError, ValueError, OSError):
            pass


@contextlib.contextmanager
def _fds_to(path: Path) -> Iterator[None]:
    """Point file descriptors 1 and 2 at ``path`` (append mode) for the block, then restore them.

    Child processes started in the block inherit the redirected descriptors. Where 1 or 2 is
    not open (a daemon), nothing is redirected.
    """
    try:
        saved = (os.dup(1), os.dup(2))
    except OSError:
        yield
        return
    _flush_std()
    fd = os.open(path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
    try:
        os.dup2(fd, 1)
        os.dup2(fd, 2)
        yield
    finally:
        _flush_std()
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for f in (fd, *saved):
            os.close(f)
