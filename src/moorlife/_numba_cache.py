"""Numba's on-disk cache, keyed by the package's whole source.

Numba (``cache=True``) invalidates a cached function only when *its own* file changes: a
compiled kernel that calls or inlines a kernel of another module keeps the old machine code
after that other module is edited (numba/numba#1833, open; the limitation is stated in
Numba's documentation, "Cache invalidation fails to recognize changes in functions defined in
a different file"). The record loop of ``moorlife.simulate.kernel`` inlines the line steps of
``moorlife.mooring``: an edit there would silently keep the old results.

:func:`pin` gives the package's cache a directory named by a digest of every ``.py`` file of
the package, so any edit of the source starts a fresh cache (one full compilation) and a cache
can never serve code older than the source. Nothing else changes: Numba still checks each
file's own time stamp within that directory.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

__all__ = ["source_digest", "cache_dir", "pin"]

#: the prefix of the cache directories (``__pycache__/numba-<digest>``)
PREFIX = "numba-"


def source_digest(package_dir: Path) -> str:
    """SHA-256 over the relative path and the bytes of every ``.py`` file under ``package_dir``."""
    h = hashlib.sha256()
    for path in sorted(Path(package_dir).rglob("*.py")):
        h.update(path.relative_to(package_dir).as_posix().encode())
        h.update(b"\0")
        h.update(path.read_bytes())
        h.update(b"\0")
    return h.hexdigest()[:16]


def cache_dir(package_dir: Path, user_dir: str | None = None) -> Path:
    """The cache directory of the package's current source.

    ``<user_dir>/numba-<digest>`` when the user set ``NUMBA_CACHE_DIR`` (``user_dir``), else
    ``<package_dir>/__pycache__/numba-<digest>``, or under ``$XDG_CACHE_HOME/moorlife`` (by
    default ``~/.cache/moorlife``) when the package directory is not writable.
    """
    tag = PREFIX + source_digest(package_dir)
    if user_dir:
        base = Path(user_dir)
        return base if base.name == tag else base / tag
    if os.access(package_dir, os.W_OK):
        return Path(package_dir) / "__pycache__" / tag
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "moorlife" / tag


def pin(package_dir: Path) -> Path:
    """Point Numba's cache at :func:`cache_dir`; call before any cached kernel is defined.

    Sets ``numba.config.CACHE_DIR`` of this process only (not the environment): every process
    that imports the package (the Dask workers too) derives the same directory itself.
    """
    from numba.core import config

    target = cache_dir(package_dir, os.environ.get("NUMBA_CACHE_DIR"))
    config.CACHE_DIR = str(target)
    return target
