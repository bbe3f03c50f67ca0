"""Shared fixtures: the study configuration, read and validated once per session.

Under pytest-xdist (``make test`` runs ``-n 2 --dist loadfile``: the tests of one file on one
worker, so a module-scoped fixture is built once) the session ``study`` is built once for all
workers: the first worker that needs it builds it under a file lock in the run's shared
temporary root, the others wait for it and read the same copy.

``study_config`` is ``config/config.yaml``; ``quick_config`` adds ``config/quick.yaml`` and
``tiny_config`` adds ``tests/data/tiny.yaml`` on top (the workflow tests' overlays), each
validated against the schema with its defaults filled in. Every test gets its own deep copy,
so a test may edit it freely.
"""

from __future__ import annotations

import copy
import functools
import os
import shutil
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = ROOT / "workflow" / "schemas" / "config.schema.yaml"
CONFIG = ROOT / "config" / "config.yaml"
QUICK = ROOT / "config" / "quick.yaml"
TINY = ROOT / "tests" / "data" / "tiny.yaml"


#: Files run first under xdist (``--no-loadscope-reorder`` keeps this order): the one that builds
#: the tiny study, then files that need no study on the other worker while it builds, then the
#: other study files; the rest follow in their usual order. The longest first keeps the two
#: workers busy to the end (measured idle: the study 158 s, the numba cache test 47 s).
FIRST_FILES = (
    "test_workflow",
    "test_numba_cache",
    "test_hydro",
    "test_simulate",
    "test_mooring_dynamic",
    "test_truth",
    "test_rounds",
    "test_bad_inputs",
    "test_parallel",
    "test_lifecycle",
)


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Order the files as :data:`FIRST_FILES`, then the rest as collected (a stable sort)."""
    rank = {name: k for k, name in enumerate(FIRST_FILES)}
    items.sort(key=lambda item: rank.get(item.path.stem, len(rank)))


@functools.cache
def _study_config(*overlays: Path) -> dict[str, Any]:
    from moorlife.io import read_study_config

    return read_study_config(CONFIG, overlays, schema=SCHEMA)


def study_config_with(*overlays: Path) -> dict[str, Any]:
    """config.yaml plus ``overlays``, validated, defaults filled (a fresh deep copy)."""
    return copy.deepcopy(_study_config(*overlays))


@pytest.fixture()
def study_config() -> dict[str, Any]:
    """config/config.yaml, validated, defaults filled."""
    return study_config_with()


@pytest.fixture()
def quick_config() -> dict[str, Any]:
    """config/config.yaml + config/quick.yaml, validated, defaults filled."""
    return study_config_with(QUICK)


@pytest.fixture()
def tiny_config() -> dict[str, Any]:
    """config/config.yaml + config/quick.yaml + tests/data/tiny.yaml, validated, defaults filled."""
    return study_config_with(QUICK, TINY)


@pytest.fixture(scope="session")
def study_config_factory():
    """:func:`study_config_with` for module- or session-scoped fixtures: ``factory(*overlays)``."""
    return study_config_with


#: Short coupled simulations of each line kind (the kernels of the tiny study's simulations).
_WARM = "import sys; sys.path.insert(0, {tests!r}); import test_simulate; test_simulate.short_coupled_runs()"


def _warm_numba_cache() -> None:
    """Compile the simulation kernels into the package's Numba cache before the study's jobs run.

    The study runs two jobs at a time (``smk``'s ``--max-threads 1``), and on a cold cache (a fresh
    clone) its first two simulation jobs would each compile the same kernels (about 50 CPU-s
    each) at once. Compiled here once, in a child process (the cache directory every process of
    this source derives, :mod:`moorlife._numba_cache`), they are loaded by both. The numbers do
    not depend on it (``tests/test_numba_cache.py``)."""
    import subprocess
    import sys

    script = _WARM.format(tests=str(Path(__file__).parent))
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr[-3000:]


@pytest.fixture(scope="session")
def study(tmp_path_factory) -> Path:
    """The tiny study (``config/quick.yaml`` + ``tests/data/tiny.yaml``), the full DAG built once
    in a temporary copy of the repo, shared by every xdist worker; tests that change it copy it
    first (``clone_study``)."""
    import fcntl

    from test_workflow import copy_repo, smk

    root = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        root = root.parent  # the run's root, shared by the workers
    work, built = root / "study", root / "study.built"
    with open(root / "study.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not built.exists():
            if work.exists():
                shutil.rmtree(work)
            work.mkdir()
            copy_repo(work)
            _warm_numba_cache()
            smk(work)
            built.touch()
    return work
