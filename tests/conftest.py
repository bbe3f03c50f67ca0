"""Shared fixtures: the study configuration, read and validated once per session.

Under pytest-xdist (``make test`` runs ``-n 2 --dist loadgroup``) every test file is one group,
so a module-scoped fixture is built once, and the files that use the session ``study`` (the tiny
DAG, built once per worker) are one group together, so the tiny DAG is built once in all.

``study_config`` is ``config/config.yaml``; ``quick_config`` adds ``config/quick.yaml`` and
``tiny_config`` adds ``tests/data/tiny.yaml`` on top (the workflow tests' overlays), each
validated against the schema with its defaults filled in. Every test gets its own deep copy,
so a test may edit it freely.
"""

from __future__ import annotations

import copy
import functools
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[1]
SCHEMA = ROOT / "workflow" / "schemas" / "config.schema.yaml"
CONFIG = ROOT / "config" / "config.yaml"
QUICK = ROOT / "config" / "quick.yaml"
TINY = ROOT / "tests" / "data" / "tiny.yaml"


#: Test files that use the session ``study``: one xdist group, one worker, one build of the DAG.
STUDY_GROUP = "study"


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Give every test its xdist group: its file, or ``study`` for every file that uses it."""
    study_files = {item.path for item in items if "study" in getattr(item, "fixturenames", ())}
    for item in items:
        group = STUDY_GROUP if item.path in study_files else item.path.stem
        item.add_marker(pytest.mark.xdist_group(group))


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


@pytest.fixture(scope="session")
def study(tmp_path_factory) -> Path:
    """The tiny study (``config/quick.yaml`` + ``tests/data/tiny.yaml``), the full DAG built once
    in a temporary copy of the repo; tests that change it copy it first (``clone_study``)."""
    from test_workflow import copy_repo, smk

    work = copy_repo(tmp_path_factory.mktemp("study"))
    smk(work)
    return work
