"""Dask efficiency of the simulate stage from 1 to 2 workers, against the standard library's process pool.

Runs, in one process on the same sea states:

* the simulate stage itself (:func:`moorlife.stages.simulate.run`: model preparation, the TLS
  LocalCluster, the batches, the resumable partial store, the final store) with 1 worker and with
  2 workers, each into a fresh store; the two stores must be bit-identical;
* the peer: ``concurrent.futures.ProcessPoolExecutor`` (spawn, BLAS pinned to one thread, the
  same :func:`moorlife.simulate.simulate_batch` on the same batches, results gathered in memory,
  nothing written) with 1 and 2 processes.

The stage's time includes its fixed start (the cluster, the workers' first compile or cache
load, the stores), as a rule run does; the pool's does not (it is started and warmed first).
It prints the wall time of each, the efficiency ``T(1) / (2 T(2))`` of both, and the ratio of the
stage's 2-worker wall time to the pool's. Wall time is the figure here: run it on an idle machine.
It also prints the CPU time of each stage run, of this process (the driver: scheduler, store) and
of its finished children (the workers): equal CPU at 1 and 2 workers means the fan-out adds no
work, and a low efficiency with it is the host (two runs of the same 2-worker stage took 201 and
173 s on 2026-12-03).
The sea states are the first ``--states`` training states of ``cases.zarr`` (or the maximum
dissimilarity states of one year of the default hindcast when it does not exist). Usage::

    .venv/bin/python benchmarks/bench_parallel.py --platform results/hydro/platform.nc \\
        [--cases results/selection/cases.zarr] [--states 96] [--ms MS2] [--duration 3600]

The stage alone on every case of a study, as its rule runs them (a system's 1,225 states: about
8 min with 2 workers and 16 with 1 on the host of 2026-12-03)::

    .venv/bin/python benchmarks/bench_parallel.py --platform results/hydro/platform.nc \\
        --states 0 --ms MS1 --workers 1 2 --no-pool
"""

from __future__ import annotations

import argparse
import concurrent.futures as cf
import multiprocessing as mp
import resource
import tempfile
import time
from pathlib import Path

import numpy as np

from moorlife import names, simulate
from moorlife.io import open_zarr, read_mooring_systems, read_yaml, write_zarr
from moorlife.io.platform import open_platform_nc, read_platform_config
from moorlife.parallel import batch_slices, pin_blas_threads
from moorlife.stages import result_settings
from moorlife.stages import simulate as stage
from moorlife.stages.check import check_study

ROOT = Path(__file__).resolve().parents[1]


def _cases(path: Path | None, n: int, config: dict):
    if path is not None and path.exists():
        cs = open_zarr(path)
        if n == 0:  # every case, as the simulate_cases rule runs them
            return cs
        train = np.flatnonzero(cs["role"].values.astype(object).astype(str) == "train")[:n]
        return cs.isel(case=train)
    from moorlife import selection
    from moorlife.stages.metocean import build_hindcast

    h = dict(config["hindcast"], end="1985-12-31T23:00")
    hc = build_hindcast(h, seed=config["seed"])
    return selection.select_cases(hc, n_train=n, n_validate=1, seed=config["seed"]).isel(case=slice(0, n))


def _cpu() -> tuple[float, float]:
    """User + system CPU seconds of this process and of its finished (waited-for) children."""
    me, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime, kids.ru_utime + kids.ru_stime


def _pool_batch(args):
    case_vars, ids, kwargs = args
    return simulate.simulate_batch(case_vars, case_ids=ids, **kwargs)


def _pool_init(warm) -> None:
    """Pin BLAS, then one short record, so that Numba's compile or cache load is not timed."""
    pin_blas_threads()
    if warm is not None:
        _pool_batch(warm)


def run_pool(cs, kwargs: dict, batch: int, workers: int) -> tuple[float, float]:
    """Wall time of the batches on a started and warmed pool, and the time to start and warm it."""
    ids = cs["case"].values
    vars_ = [k for k, v in cs.data_vars.items() if v.dims == ("case",) and v.dtype.kind in "fiub"]
    jobs = [({k: cs[k].values[sl] for k in vars_}, ids[sl], kwargs) for sl in batch_slices(ids.size, batch)]
    short = dict(kwargs, sim_cfg={**kwargs["sim_cfg"], "duration": 300.0, "transient": 0.0})
    warm = ({k: v[:1] for k, v in jobs[0][0].items()}, ids[:1], short)
    t0 = time.perf_counter()
    with cf.ProcessPoolExecutor(
        workers, mp_context=mp.get_context("spawn"), initializer=_pool_init, initargs=(warm,)
    ) as ex:
        list(ex.map(time.sleep, [2.0] * workers))  # every process started and warmed
        t1 = time.perf_counter()
        list(ex.map(_pool_batch, jobs))
        t2 = time.perf_counter()
    return t2 - t1, t1 - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--platform", type=Path, required=True, help="results/hydro/platform.nc")
    ap.add_argument("--cases", type=Path, default=ROOT / "results/selection/cases.zarr")
    ap.add_argument("--states", type=int, default=96, help="the first N training states; 0: every case of --cases")
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2], help="worker counts of the stage (default 1 2)")
    ap.add_argument("--no-pool", action="store_true", help="time the stage only (not the ProcessPoolExecutor peer)")
    ap.add_argument("--ms", default="MS2")
    ap.add_argument("--duration", type=float, default=None, help="record length in s (default: the config's)")
    ap.add_argument("--batch", type=int, default=None, help="states per task (default: the config's)")
    a = ap.parse_args()
    config = check_study(
        read_yaml(ROOT / "config/config.yaml"), read_yaml(ROOT / "workflow/schemas/config.schema.yaml")
    )
    config = config.config
    if a.duration is not None:
        config["simulation"]["duration"] = float(a.duration)
    batch = int(a.batch or config["simulation"]["batch_size"])
    row = read_mooring_systems(ROOT / config["mooring_systems"]).loc[a.ms]
    row = {k: (v.item() if hasattr(v, "item") else v) for k, v in row.items()}
    sim = result_settings(config, "simulation")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        cs = _cases(a.cases, a.states, config)
        write_zarr(cs, tmp / "cases.zarr")
        n = cs.sizes["case"]
        print(
            f"{n} sea states of {a.ms}, {sim['transient']:.0f} + {sim['duration']:.0f} s records, "
            f"batches of {batch}, {mp.cpu_count()} CPUs"
        )
        wall = {}
        for w in a.workers:
            t0, c0 = time.perf_counter(), _cpu()
            stage.run(
                cases=tmp / "cases.zarr",
                platform=a.platform,
                platform_cfg=ROOT / config["platform"],
                store=tmp / f"sims_{w}.zarr",
                dim="case",
                ms=a.ms,
                row=row,
                seed=config["seed"],
                simulation=sim,
                mooring=config["mooring"],
                fatigue=config["fatigue"],
                statistics=config["statistics"],
                batch_size=batch,
                threads=w,
                log=tmp / f"sims_{w}.log",
            )
            wall["stage", w] = time.perf_counter() - t0
            time.sleep(2.0)  # the workers' processes reaped: their CPU counts among the children
            drv, kids = (b - a for a, b in zip(c0, _cpu()))
            print(
                f"simulate stage, Dask, {w} worker(s): {wall['stage', w]:7.1f} s wall; "
                f"CPU {drv + kids:.1f} s (driver {drv:.1f} s, workers {kids:.1f} s)"
            )
        if len(a.workers) > 1:
            s1, s2 = (open_zarr(tmp / f"sims_{w}.zarr") for w in a.workers[:2])
            same = all(np.array_equal(s1[v].values, s2[v].values, equal_nan=True) for v in s1.data_vars)
            print(f"{a.workers[0]}-worker and {a.workers[1]}-worker stores bit-identical: {same}")
        if a.no_pool:
            if {1, 2} <= set(a.workers):
                print(f"efficiency 1 -> 2 workers, stage: {100 * wall['stage', 1] / (2 * wall['stage', 2]):.1f} %")
            return
        model = simulate.prepare_model(
            open_platform_nc(a.platform),
            read_platform_config(ROOT / config["platform"]),
            {**row, "mooring_system": a.ms},
            config["mooring"],
            sim,
        )
        kwargs = dict(
            mooring_system=a.ms,
            seed=int(config["seed"]),
            stream=names.CASE,
            model_inputs=model,
            sim_cfg=sim,
            fatigue_cfg=config["fatigue"],
            stats_cfg=config["statistics"],
        )
        for w in (1, 2):
            wall["pool", w], start = run_pool(cs, kwargs, batch, w)
            print(
                f"peer, ProcessPoolExecutor, {w} process(es): {wall['pool', w]:7.1f} s wall "
                f"(after {start:.1f} s to start and warm the processes, not counted)"
            )
    for who in ("stage", "pool"):
        print(f"efficiency 1 -> 2 workers, {who}: {100 * wall[who, 1] / (2 * wall[who, 2]):.1f} %")
    print(f"ratio stage (Dask, 2 workers) / peer pool (2 processes): {wall['stage', 2] / wall['pool', 2]:.3f}")


if __name__ == "__main__":
    main()
