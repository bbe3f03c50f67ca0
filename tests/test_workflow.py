"""The Snakemake workflow end to end, on tests/data/tiny.yaml, in a temporary copy of the repo.

One session-scoped study (``study`` in conftest.py) is built once (the full DAG); the other
tests, here and in test_truth.py, copy it (with its .snakemake metadata, so nothing is rebuilt
needlessly). Each Snakemake run costs seconds, so one run may serve several properties: the
single-system rebuild is also the killed and resumed run, resumed with one worker. Bad configs
are refused by the pre-flight check that the Snakefile calls (tests/test_bad_inputs.py).
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
COPY = ["Snakefile", "workflow", "config", "envs", "tests/data"]


def copy_repo(dst: Path) -> Path:
    for item in COPY:
        src = ROOT / item
        if src.is_dir():
            shutil.copytree(src, dst / item, ignore=shutil.ignore_patterns("__pycache__"))
        else:
            (dst / item).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dst / item)
    return dst


def smk(
    workdir: Path,
    *args: str,
    cores: int = 2,
    max_threads: int | None = 1,
    check: bool = True,
    overlays=OVERLAYS,
    timeout: float = 900,
    env_extra: dict | None = None,
) -> subprocess.CompletedProcess:
    # targets and flags first: --configfile takes every following word as a file. The tiny
    # study's jobs are start-up bound (a simulation job: about 5 s of imports and Dask cluster
    # around 2 s of work), so by default every job gets one thread and two run at once (about
    # 40 % less wall time than one two-thread job at a time); the bits do not depend on it
    # (test_parallel, and the resumed runs below with two workers against the study's one).
    cap = [] if max_threads is None else ["--max-threads", str(max_threads)]
    cmd = [SNAKEMAKE, "--cores", str(cores), *cap, *args, "--configfile", *overlays]
    env = {**os.environ, "PYTHONWARNINGS": "ignore"}
    env.pop("DASK_SCHEDULER_ADDRESS", None)
    env.update(env_extra or {})
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


def clone_study(study: Path, dst: Path) -> Path:
    # not Snakemake's locks: another xdist worker may be running snakemake in the shared study
    shutil.copytree(study, dst, symlinks=True, dirs_exist_ok=True, ignore=shutil.ignore_patterns("locks"))
    return dst


def test_full_run_then_noop(study):
    built = stores(study)
    assert "results/metocean/hindcast.zarr" in built
    for p in built:
        if p.endswith(".zarr"):
            mio.open_zarr(study / p, load=False)  # complete, trusted
    again = smk(study)
    assert stores(study) == built, "a rerun must not rebuild anything"
    assert "Nothing to be done" in again.stdout + again.stderr


def test_scheduling_settings_rerun_nothing(study, tmp_path):
    """simulation.batch_size and lifecycle.rbf.chunk_rows change scheduling or memory only: no
    rule's params hold them, so changing them reruns nothing (issue 20 item 2); nor does another
    scheduler address. One dry run with all three changed: any of them would schedule jobs."""
    sched = tmp_path / "sched.yaml"
    sched.write_text("simulation:\n  batch_size: 3\nlifecycle:\n  rbf:\n    chunk_rows: 100\n")
    env = {"DASK_SCHEDULER_ADDRESS": "tcp://127.0.0.1:1"}
    dry = smk(study, "-n", overlays=[*OVERLAYS, str(sched)], env_extra=env)
    assert "Nothing to be done" in dry.stdout + dry.stderr, dry.stdout[-3000:]


def test_band_and_recommendation_settings_rerun_only_the_comparison(study, tmp_path):
    """lifecycle.uncertainty and lifecycle.recommendation are read by the compare stage only: a
    change reruns the comparison and its figures, and no fit of lifecycle.zarr."""
    band = tmp_path / "band.yaml"
    band.write_text("lifecycle:\n  uncertainty: {coverage: 1.7}\n  recommendation: {curves: [sn]}\n")
    dry = smk(study, "-n", overlays=[*OVERLAYS, str(band)])
    jobs = set(re.findall(r"^rule (\w+):", dry.stdout, flags=re.M))
    assert "compare" in jobs, dry.stdout[-3000:]
    assert not jobs & {"lifecycle", "simulate_cases", "truth_compare", "sensitivity"}, jobs


def test_lint_clean(tmp_path):
    work = copy_repo(tmp_path)
    res = smk(work, "--lint", check=False)
    assert res.returncode == 0, res.stdout + res.stderr
    assert "Lints for" not in res.stdout + res.stderr


def _furthest(ms: str, work: Path) -> str:
    """The furthest per-system output the DAG has."""
    for name in ("lifecycle.zarr", "simulations.zarr"):
        if (work / "results" / ms / name).exists():
            return f"results/{ms}/{name}"
    raise AssertionError(f"no per-system output for {ms}")


def done_batches(part: Path) -> int:
    """Batches finished in a partial store (0 while it does not exist yet)."""
    try:
        import zarr

        return int(np.asarray(zarr.open_group(str(part), mode="r")["_batch_done"][:]).sum())
    except Exception:
        return 0


def kill_during_fanout(
    work: Path, cmd: list[str], part: Path, n: int, *, log: Path | None = None, poll: float = 0.02
) -> int:
    """Run ``cmd`` (snakemake) in ``work``, SIGKILL its process group once the partial store
    ``part`` holds ``n`` finished batches (or the run ended, or 600 s passed); the batches done.

    The driver writes the batches after the workers computed them, so on a slow disk they can
    all be flagged between two polls. When the kill finds every batch flagged but the store not
    yet promoted, the last batch's flag is cleared: the state a kill between that batch's data
    and its flag leaves (:meth:`moorlife.io.partial.PartialStore.write`), so the resume always
    computes at least one batch whatever the timing.
    """
    env = {**os.environ, "PYTHONWARNINGS": "ignore"}
    env.pop("DASK_SCHEDULER_ADDRESS", None)
    with open(log, "w") if log is not None else open(os.devnull, "w") as out:
        proc = subprocess.Popen(cmd, cwd=work, stdout=out, stderr=out, start_new_session=True, env=env)
        deadline = time.time() + 600
        while done_batches(part) < n and proc.poll() is None and time.time() < deadline:
            time.sleep(poll)
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
    _unflag_last_if_all_done(part)
    return done_batches(part)


def _unflag_last_if_all_done(part: Path) -> None:
    import zarr

    try:
        group = zarr.open_group(str(part), mode="r+")
    except Exception:
        return
    if group.attrs.get(mio.COMPLETE_ATTR, False) or "_batch_done" not in group:
        return
    flags = group["_batch_done"]
    n = flags.shape[0]
    if n > 1 and bool(np.all(flags[:] == 1)):
        flags[n - 1] = 0


def _identical(a: Path, b: Path) -> None:
    xr.testing.assert_identical(mio.open_zarr(a).drop_attrs(), mio.open_zarr(b).drop_attrs())


def test_single_system_target_killed_resumed_with_one_worker(study, tmp_path):
    """One MS3 target, SIGKILLed during its fan-out, resumed with one worker, bit for bit.

    With MS1 and MS3 removed, the MS3 target builds only the MS3 chain (no MS1 job, no shared
    rule rebuilt). Snakemake is killed once two batches of simulate_cases are in the partial
    store; the rerun (after ``--unlock``) reuses them and computes the rest with ``--cores 1``
    (one Dask worker, batch size 1), after the killed run's two workers, where the study ran one
    worker per job and batches of 2: every store equals the study's, so the numbers depend on
    neither the resume history, the worker count nor the batch size.
    """
    work = clone_study(study, tmp_path / "w")
    target = _furthest("MS3", work)
    sims = "results/MS3/simulations.zarr"
    shutil.rmtree(work / "results" / "MS1")
    shutil.rmtree(work / "results" / "MS3")
    (work / "slow.yaml").write_text("simulation:\n  batch_size: 1\n")
    overlays = [*OVERLAYS, "slow.yaml"]
    part = mio.partial_path(work / sims)
    cmd = [SNAKEMAKE, "--cores", "2", target, "--configfile", *overlays]
    n_before = kill_during_fanout(work, cmd, part, 2, log=tmp_path / "killed.log")
    assert not (work / sims).exists(), "the run was not killed during the fan-out"
    assert n_before >= 2
    smk(work, "--unlock", overlays=overlays)
    res = smk(work, target, overlays=overlays, cores=1)
    log = (tmp_path / "killed.log").read_text() + res.stdout + res.stderr
    assert (work / target).exists()
    assert not (work / "results" / "MS1").exists(), "MS1 must not be built for an MS3 target"
    assert "ms=MS1" not in log and "ms=MS3" in log
    for shared in ("metocean", "selection", "hydro"):
        assert not re.search(rf"^rule {shared}:", log, flags=re.M), f"{shared} was rebuilt"
    resumed = (work / "logs" / "MS3" / "simulate_cases.log").read_text()
    m = re.search(r"resuming .*: (\d+) of (\d+) batches already done", resumed)
    assert m and int(m.group(1)) >= n_before, "finished sea states must be reused"
    assert int(m.group(1)) < int(m.group(2)), "the one worker computed no sea state"
    xr.testing.assert_identical(mio.open_zarr(work / target), mio.open_zarr(study / target))
    _identical(work / sims, study / sims)


def test_unlock_needs_no_cores(tmp_path):
    """`snakemake --unlock` as the README writes it: no --cores (threads sized by all_cores())."""
    work = copy_repo(tmp_path)
    env = {**os.environ, "PYTHONWARNINGS": "ignore"}
    res = subprocess.run(
        [SNAKEMAKE, "--unlock", "--configfile", *OVERLAYS],
        cwd=work,
        capture_output=True,
        text=True,
        timeout=300,
        env=env,
    )
    assert res.returncode == 0, res.stderr[-3000:]
    assert "Unlocked working directory" in res.stdout + res.stderr


def test_report_opens_on_the_answer(study, tmp_path):
    """The report's global description carries the recommendation and the tables of this run."""
    html_path = tmp_path / "report.html"
    smk(study, "--report", str(html_path))
    html = html_path.read_text(encoding="utf-8")
    rec = mio.read_yaml(study / "results" / "comparison" / "recommendation.yaml")
    answer = f"Recommended mooring system: {rec['recommended']}" if rec["recommended"] else "No mooring system passes"
    assert answer in html
    for heading in (
        "Life-cycle fatigue per mooring system, line and curve",
        "Matrix vs life-cycle damage, mean difference (%)",
        "The answer",
    ):
        assert heading in html, heading
    assert "has not run yet" not in html
    # the numbers are this run's: every row of summary.csv, by its life-cycle damage
    summary = (study / "results" / "comparison" / "summary.csv").read_text().splitlines()
    header = summary[0].split(",")
    col = header.index("lifecycle_damage")
    for line in summary[1:]:
        assert f"{float(line.split(',')[col]):.3g}" in html, line
