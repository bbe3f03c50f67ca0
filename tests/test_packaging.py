"""pyproject.toml, envs/moorlife.yaml and constraints.txt stay in step; layout rules hold."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[1]
#: PyPI name -> conda-forge name where they differ
CONDA_NAME = {
    "snakemake": "snakemake-minimal",
    "matplotlib": "matplotlib-base",
    "pyyaml": "pyyaml",
    "netcdf4": "netcdf4",
}


def _name(req: str) -> str:
    return re.split(r"[<>=!\[ ;]", req, maxsplit=1)[0].strip().lower()


@pytest.fixture(scope="module")
def project():
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]


def test_conda_env_mirrors_pyproject(project):
    env = yaml.safe_load((ROOT / "envs" / "moorlife.yaml").read_text())
    conda = {_name(d) for d in env["dependencies"] if isinstance(d, str)}
    pip = {_name(d) for d in next(d for d in env["dependencies"] if isinstance(d, dict))["pip"]}
    for req in project["dependencies"] + project["optional-dependencies"]["test"]:
        name = _name(req)
        assert CONDA_NAME.get(name, name) in conda | pip, f"{req} is missing from envs/moorlife.yaml"


def test_every_dependency_bounded_and_pinned(project):
    pins = {
        _name(l): l.split("==")[1].strip() for l in (ROOT / "constraints.txt").read_text().splitlines() if "==" in l
    }
    extras = project["optional-dependencies"]
    for req in project["dependencies"] + extras["test"] + extras["cluster"]:
        assert "<" in req, f"{req}: upper bound missing"
        assert _name(req) in pins, f"{req}: not pinned in constraints.txt"


def test_workflow_scripts_are_thin_adapters():
    for script in (ROOT / "workflow" / "scripts").glob("*.py"):
        lines = [l for l in script.read_text().splitlines() if l.strip() and not l.strip().startswith("#")]
        assert len(lines) <= 20, f"{script.name}: {len(lines)} lines; adapters must be 20 lines or fewer"
        assert 'if __name__ == "__main__"' in script.read_text(), f"{script.name}: needs a __main__ guard"


def test_every_rule_has_a_log():
    for smk in (ROOT / "workflow" / "rules").glob("*.smk"):
        text = smk.read_text()
        for rule, body in re.findall(r"^rule (\w+):\n((?:[ \t]+.*\n|\n)*)", text, flags=re.M):
            if rule == "all":
                continue
            assert re.search(r"^\s+log:", body, flags=re.M), f"{smk.name}: rule {rule} has no log:"


def test_kernels_do_no_io():
    """Only moorlife.io touches the disk (the stages too go through it); only moorlife.parallel
    imports Dask, and nothing imports Snakemake."""
    io_call = re.compile(r"\bopen\(|\.to_zarr\(|\.to_netcdf\(|open_dataset\(|read_csv\(|savefig\(")
    orchestration = re.compile(r"^\s*(import|from)\s+(snakemake|dask|distributed)\b")
    for py in (ROOT / "src" / "moorlife").rglob("*.py"):
        rel = py.relative_to(ROOT / "src" / "moorlife")
        for i, line in enumerate(py.read_text().splitlines(), 1):
            if rel.parts[0] not in {"io", "plots"}:
                assert not io_call.search(line), f"{rel}:{i} does I/O: {line.strip()}"
            if str(rel) != "parallel.py" or "snakemake" in line:
                assert not orchestration.search(line), f"{rel}:{i} does orchestration: {line.strip()}"
