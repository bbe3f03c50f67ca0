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
def log_to(path: str | os.PathLike[str], level: int = logging.INFO, *,
           blas_threads: int | None = 1) -> Iterator[logging.Logger]:
    """Send the ``moorlife`` logger (and warnings) to a rule's log file.

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
    handler = logging.FileHandler(p, mode="w", encoding="utf-8")
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
    try:
        with limits:
            yield logger
    except BaseException as exc:
        logger.error("failed: %s\n%s", exc, traceback.format_exc())
        print(f"moorlife error: {exc}", file=sys.stderr)
        raise
    finally:
        logger.removeHandler(handler)
        logging.getLogger("py.warnings").removeHandler(handler)
        handler.close()
