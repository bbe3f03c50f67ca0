"""Logging of workflow rules to their ``log:`` file."""

from __future__ import annotations

import contextlib
import logging
import os
import sys
import time
import traceback
from collections.abc import Iterator
from pathlib import Path

__all__ = ["log_to", "TERMINAL_EVERY", "ThrottleFilter"]

#: Seconds between two progress lines on the terminal (the rule's log gets every one).
TERMINAL_EVERY = 30.0


class ThrottleFilter(logging.Filter):
    """Pass a record at most every ``every`` seconds, and always one marked ``progress_final``."""

    def __init__(self, every: float = TERMINAL_EVERY, clock=time.monotonic) -> None:
        super().__init__()
        self.every, self.clock, self.last = float(every), clock, -float("inf")

    def filter(self, record: logging.LogRecord) -> bool:
        now = self.clock()
        if getattr(record, "progress_final", False) or now - self.last >= self.every:
            self.last = now
            return True
        return False


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

    The progress lines of the Dask fan-out (logger ``moorlife.progress``: states done, of how
    many, time left) go to the terminal, the standard error Snakemake shows, at most every
    :data:`TERMINAL_EVERY` seconds; the log gets every batch.

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
    terminal = _terminal_handler(capture_fds)
    progress = logging.getLogger("moorlife.progress")
    progress.setLevel(level)
    progress.addHandler(terminal)
    fds = _fds_to(p) if capture_fds else contextlib.nullcontext()
    try:
        with limits, fds:
            yield logger
    except BaseException as exc:  # fds 1 and 2 are back on the terminal here
        logger.error("failed: %s\n%s", exc, traceback.format_exc())
        print(f"moorlife error: {exc}", file=sys.stderr)
        raise
    finally:
        progress.removeHandler(terminal)
        terminal.close()
        logger.removeHandler(handler)
        logging.getLogger("py.warnings").removeHandler(handler)
        handler.close()


def _terminal_handler(own_stream: bool) -> logging.Handler:
    """A throttled handler on the terminal's standard error, opened before fd 2 is redirected."""
    stream = sys.stderr
    if own_stream:
        try:
            stream = os.fdopen(os.dup(2), "w", buffering=1, encoding="utf-8", closefd=True)
        except OSError:
            stream = sys.stderr
    handler: logging.Handler = _OwnedStreamHandler(stream, own=stream is not sys.stderr)
    handler.setFormatter(logging.Formatter("moorlife: %(message)s"))
    handler.addFilter(ThrottleFilter())
    return handler


class _OwnedStreamHandler(logging.StreamHandler):
    def __init__(self, stream, own: bool) -> None:
        super().__init__(stream)
        self.own = own

    def close(self) -> None:
        try:
            if self.own:
                self.stream.close()
        finally:
            super().close()


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
