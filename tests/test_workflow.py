"""The Snakemake workflow end to end, on tests/data/tiny.yaml, in a temporary copy of the repo.

One session-scoped study is built once (the full DAG); the other tests copy it (with its
.snakemake metadata, so nothing is rebuilt needlessly) and exercise one behaviour each.
"""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from moorlife import io as mio

pytestmark = pytest.mark.workflow

ROOT = Path(__file__).resolve().parents[1]
SNAKEMAKE = str(Path(sys.executable).parent / "snakemake")
OVERLAYS = ["config/quick.yaml", "tests/data/tiny.yaml"]
COPY = ["Snakefile", "workflow", "config", "tests/data"]


def copy_repo(dst: Path) -> Path:
    for item in COPY:
        src = ROOT / item
        if src.is_dir():
            shutil.copytree(src, dst / item, ignore=shutil.ignore_patterns("__pycache__"))
        else:
            (dst / item).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dst / item)
    return dst


def smk(workdir: Path, *args: str, cores: int = 2, check: bool = True, overlays=OVERLAYS,
        timeout: float = 900) -> subprocess.CompletedProcess:
    cmd = [SNAKEMAKE, "--cores", str(cores), "--configfile", *overlays, *args]
    env = {**os.environ, "PYTHONWARNINGS": "ignore"}
    env.pop("DASK_SCHEDULER_ADDRESS", None)
    res = subprocess.run(cmd, cwd=workdir, capture_output=True, text=True, timeout=timeout, env=env)
    if check and res.returncode != 0:
        raise AssertionError(f"snakemake {' '.join(args)} failed ({res.returncode}):\n{res.stderr[-6000:]}")
    return res


def stores(workdir: Path) -> dict[str, float]:
    """Every complete-or-not store or file under results/ with its mtime."""
    out = {}
    for p in sorted((workdir / "results").glob("**/*")):
        if p.suffix in {".zarr", ".nc", ".csv", ".png"} and ".partial" not in p.parts:
            out[str(p.relative_to(workdir))] = p.stat().st_mtime
    return out


@pytest.fixture(scope="session")
def study(tmp_path_factory) -> Path:
    work = copy_repo(tmp_path_factory.mktemp("study"))
    smk(work)
    return work


def clone_study(study: Path, dst: Path) -> Path:
    shutil.copytree(study, dst, symlinks=True, dirs_exist_ok=True)
    return dst


def test_full_run_then_noop(study):
    built = stores(study)
    assert "results/metocean/hindcast.zarr" in built
    for p in built:
        if p.endswith(".zarr"):
            mio.open_zarr(study / p, load=False)  # complete, trusted
    dry = smk(study, "-n")
    assert "Nothing to be done" in dry.stdout + dry.stderr
    again = smk(study)
    assert stores(study) == built, "a rerun must not rebuild anything"
    assert "Nothing to be done" in again.stdout + again.stderr


def test_lint_clean(tmp_path):
    work = copy_repo(tmp_path)
    res = smk(work, "--lint", check=False)
    assert res.returncode == 0, res.stdout + res.stderr
    assert "Lints for" not in res.stdout + res.stderr


def test_bad_config_rejected_before_any_work(tmp_path):
    work = copy_repo(tmp_path)
    (work / "bad.yaml").write_text("selection:\n  n_train: -3\n")
    res = smk(work, check=False, overlays=[*OVERLAYS, "bad.yaml"])
    assert res.returncode != 0
    assert re.search(r"'selection\.n_train' = -3", res.stdout + res.stderr), res.stderr[-2000:]
    assert not (work / "results").exists(), "no work may start with a bad config"


def test_unknown_config_key_named(tmp_path):
    work = copy_repo(tmp_path)
    (work / "bad.yaml").write_text("simulation:\n  durration: 10\n")
    res = smk(work, "-n", check=False, overlays=[*OVERLAYS, "bad.yaml"])
    assert res.returncode != 0
    assert "unknown config key 'simulation.durration'" in res.stdout + res.stderr
