"""External Dask scheduler (DASK_SCHEDULER_ADDRESS) and worker loss."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from moorlife import io as mio
from moorlife import parallel
from moorlife.stages.fanout import map_cases

HERE = Path(__file__).resolve().parent
BIN = Path(sys.executable).parent


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def slow_case(case_vars, *, case_ids, scale, pause=0.0):
    """Pure, seeded by case id only; sleeps to keep the run alive long enough to kill a worker."""
    time.sleep(pause)
    rows = [np.random.default_rng([11, int(c)]).normal(size=3) for c in case_ids]
    t = np.array(rows) * scale
    return {"tension_mpm": t, "surge_mpm": case_vars["hs"] + t[:, 1], "pid": np.full(len(case_ids), os.getpid())}


@pytest.fixture()
def cases():
    n = 16
    return xr.Dataset({"hs": ("case", np.linspace(1.0, 8.0, n))}, coords={"case": np.arange(n)})


@pytest.fixture()
def external_cluster(tmp_path):
    """`dask scheduler` plus two `dask worker` processes on 127.0.0.1; stops exactly those PIDs."""
    port = free_port()
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(HERE), os.environ.get("PYTHONPATH", "")])}
    procs: list[subprocess.Popen] = []
    addr = f"tcp://127.0.0.1:{port}"
    try:
        procs.append(
            subprocess.Popen(
                [
                    str(BIN / "dask"),
                    "scheduler",
                    "--host",
                    "127.0.0.1",
                    "--port",
                    str(port),
                    "--dashboard-address",
                    "127.0.0.1:0",
                ],
                env=env,
                stdout=subprocess.DEVNULL,
                stderr=open(tmp_path / "scheduler.log", "w"),
            )
        )
        for i in range(2):
            procs.append(
                subprocess.Popen(
                    [
                        str(BIN / "dask"),
                        "worker",
                        addr,
                        "--nthreads",
                        "1",
                        "--no-nanny",
                        "--host",
                        "127.0.0.1",
                        "--name",
                        f"w{i}",
                        "--no-dashboard",
                    ],
                    env=env,
                    stdout=subprocess.DEVNULL,
                    stderr=open(tmp_path / f"worker{i}.log", "w"),
                )
            )
        from distributed import Client

        deadline = time.time() + 60
        while True:
            try:
                with Client(addr, timeout="5s") as c:
                    if len(c.scheduler_info()["workers"]) == 2:
                        break
            except OSError:
                pass
            if time.time() > deadline:
                raise RuntimeError("external Dask cluster did not start")
            time.sleep(0.5)
        yield addr, procs
    finally:
        # workers first, while their scheduler is still there to take their goodbye (a worker
        # whose scheduler is gone retries for about 20 s before it exits), then the scheduler
        for p in procs[1:] + procs[:1]:
            if p.poll() is None:
                p.terminate()
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()


def test_external_scheduler_matches_local_cluster(tmp_path, cases, external_cluster, monkeypatch):
    addr, procs = external_cluster
    local = tmp_path / "local" / "results" / "sim.zarr"
    map_cases(slow_case, cases, local, dim="case", func_kwargs={"scale": 2.0}, batch_size=3, fingerprint="f", threads=1)
    monkeypatch.setenv(parallel.SCHEDULER_ENV, addr)
    remote = tmp_path / "remote" / "results" / "sim.zarr"
    map_cases(
        slow_case, cases, remote, dim="case", func_kwargs={"scale": 2.0}, batch_size=3, fingerprint="f", threads=1
    )
    a, b = mio.open_zarr(local), mio.open_zarr(remote)
    worker_pids = {p.pid for p in procs[1:]}
    assert set(np.unique(b["pid"].values)) <= worker_pids, "the external workers must do the work"
    xr.testing.assert_identical(a.drop_vars("pid").drop_attrs(), b.drop_vars("pid").drop_attrs())


def test_worker_killed_mid_run_is_rescheduled(tmp_path, cases, external_cluster, monkeypatch):
    addr, procs = external_cluster
    monkeypatch.setenv(parallel.SCHEDULER_ENV, addr)
    out = tmp_path / "results" / "sim.zarr"
    victim = procs[1]

    import threading

    def kill_when_started():
        part = mio.partial_path(out)
        deadline = time.time() + 60
        while not part.exists() and time.time() < deadline:
            time.sleep(0.05)
        os.kill(victim.pid, signal.SIGKILL)

    killer = threading.Thread(target=kill_when_started)
    killer.start()
    ds = map_cases(
        slow_case,
        cases,
        out,
        dim="case",
        func_kwargs={"scale": 2.0, "pause": 0.4},
        batch_size=2,
        fingerprint="k",
        threads=1,
    )
    killer.join()
    assert victim.poll() is not None, "the victim worker should be dead"
    survivor = procs[2].pid
    assert survivor in set(ds["pid"].values.tolist())
    expected = slow_case({"hs": cases["hs"].values}, case_ids=cases["case"].values, scale=2.0)
    np.testing.assert_array_equal(ds["tension_mpm"].values, expected["tension_mpm"])
    np.testing.assert_array_equal(ds["surge_mpm"].values, expected["surge_mpm"])
