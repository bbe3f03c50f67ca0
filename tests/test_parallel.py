"""moorlife.parallel: Dask fan-out into a resumable, single-writer Zarr store."""

from __future__ import annotations

import os
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from moorlife import io as mio
from moorlife import parallel
from moorlife.stages.fanout import map_cases


def noisy_case(case_vars, *, case_ids, scale, record_dir=None, fail_on=None):
    """A pure per-case function: outputs depend only on (case id, inputs, scale)."""
    if fail_on is not None and fail_on in set(int(c) for c in case_ids):
        raise RuntimeError(f"planted failure on case {fail_on}")
    if record_dir is not None:
        for c in case_ids:
            Path(record_dir, f"{int(c)}-{os.getpid()}").touch()
    rows = [np.random.default_rng([7, int(c)]).normal(size=3) for c in case_ids]
    lines = np.array(rows) * scale
    return {
        "tension_mpm": lines,
        "surge_mpm": case_vars["hs"] * scale + lines[:, 0],
    }


@pytest.fixture(scope="module")
def client():
    with parallel.dask_client(2) as c:
        yield c


@pytest.fixture()
def cases():
    n = 23
    return xr.Dataset(
        {
            "hs": ("case", np.linspace(0.5, 9.0, n)),
            "role": ("case", np.array(["train"] * 18 + ["validate"] * 5)),
        },
        coords={"case": np.arange(n)},
    )


def computed(record_dir: Path) -> list[int]:
    return sorted(int(p.name.split("-")[0]) for p in record_dir.iterdir())


def test_batch_slices_cover_all():
    sl = parallel.batch_slices(10, 4)
    assert [(s.start, s.stop) for s in sl] == [(0, 4), (4, 8), (8, 10)]
    with pytest.raises(ValueError, match="batch_size"):
        parallel.batch_slices(10, 0)


def test_store_is_complete_and_carries_cases(tmp_path, cases, client):
    out = tmp_path / "results" / "MS1" / "sim.zarr"
    ds = map_cases(
        noisy_case, cases, out, dim="case", func_kwargs={"scale": 2.0}, batch_size=5, fingerprint="fp1", client=client
    )
    assert out.exists() and not mio.partial_path(out).exists()
    back = mio.open_zarr(out)
    assert back.attrs[mio.COMPLETE_ATTR] is True
    assert back["tension_mpm"].dims == ("case", "line")
    assert list(back["line"].values) == ["M1", "M2", "M3"]
    assert back["tension_mpm"].attrs["units"] == "N"
    np.testing.assert_array_equal(back["hs"].values, cases["hs"].values)
    assert list(back["role"].values) == list(cases["role"].values)
    expected = noisy_case({"hs": cases["hs"].values}, case_ids=cases["case"].values, scale=2.0)
    np.testing.assert_array_equal(back["surge_mpm"].values, expected["surge_mpm"])
    np.testing.assert_array_equal(ds["tension_mpm"].values, expected["tension_mpm"])


def test_identical_whatever_workers_and_batches(tmp_path, cases):
    runs = []
    for threads, bs in [(1, 23), (2, 4), (2, 1)]:
        out = tmp_path / f"w{threads}b{bs}" / "results" / "sim.zarr"
        map_cases(
            noisy_case,
            cases,
            out,
            dim="case",
            func_kwargs={"scale": 1.5},
            batch_size=bs,
            fingerprint="fp",
            threads=threads,
        )
        runs.append(mio.open_zarr(out))
    for other in runs[1:]:
        xr.testing.assert_identical(runs[0].drop_attrs(), other.drop_attrs())


def test_resume_computes_only_missing(tmp_path, cases, client):
    out = tmp_path / "results" / "MS2" / "sim.zarr"
    rec = tmp_path / "rec"
    rec.mkdir()
    with pytest.raises(RuntimeError, match="planted failure on case 12"):
        map_cases(
            noisy_case,
            cases,
            out,
            dim="case",
            func_kwargs={"scale": 3.0, "record_dir": str(rec), "fail_on": 12},
            batch_size=5,
            fingerprint="fpR",
            client=client,
        )
    assert not out.exists(), "a failed run must not leave the declared output"
    part = mio.partial_path(out)
    assert part.exists()
    first = set(computed(rec))
    for p in rec.iterdir():
        p.unlink()
    map_cases(
        noisy_case,
        cases,
        out,
        dim="case",
        func_kwargs={"scale": 3.0, "record_dir": str(rec)},
        batch_size=5,
        fingerprint="fpR",
        client=client,
    )
    second = set(computed(rec))
    assert 12 in second and 10 in second  # the failed batch (10-14) is redone
    done_before = first - {10, 11, 12, 13, 14}
    assert not (second & done_before), "finished batches must be reused, not recomputed"
    fresh = tmp_path / "fresh" / "results" / "sim.zarr"
    map_cases(
        noisy_case, cases, fresh, dim="case", func_kwargs={"scale": 3.0}, batch_size=5, fingerprint="x", client=client
    )
    xr.testing.assert_identical(mio.open_zarr(out).drop_attrs(), mio.open_zarr(fresh).drop_attrs())


def test_changed_fingerprint_starts_afresh(tmp_path, cases, client):
    out = tmp_path / "results" / "sim.zarr"
    rec = tmp_path / "rec"
    rec.mkdir()
    with pytest.raises(RuntimeError):
        map_cases(
            noisy_case,
            cases,
            out,
            dim="case",
            func_kwargs={"scale": 1.0, "record_dir": str(rec), "fail_on": 22},
            batch_size=5,
            fingerprint="old",
            client=client,
        )
    for p in rec.iterdir():
        p.unlink()
    map_cases(
        noisy_case,
        cases,
        out,
        dim="case",
        func_kwargs={"scale": 2.0, "record_dir": str(rec)},
        batch_size=5,
        fingerprint="new",
        client=client,
    )
    assert computed(rec) == list(range(23))
    np.testing.assert_array_equal(
        mio.open_zarr(out)["surge_mpm"].values,
        noisy_case({"hs": cases["hs"].values}, case_ids=np.arange(23), scale=2.0)["surge_mpm"],
    )


def test_corrupted_partial_is_not_trusted(tmp_path, cases, client):
    out = tmp_path / "results" / "sim.zarr"
    part = mio.partial_path(out)
    part.mkdir(parents=True)
    (part / "zarr.json").write_text("{ this is not json")
    ds = map_cases(
        noisy_case, cases, out, dim="case", func_kwargs={"scale": 1.0}, batch_size=7, fingerprint="fpC", client=client
    )
    assert ds.sizes["case"] == 23 and np.isfinite(ds["surge_mpm"]).all()


def test_blas_threads_pinned(monkeypatch):
    monkeypatch.setenv("OMP_NUM_THREADS", "2")
    monkeypatch.delenv("MKL_NUM_THREADS", raising=False)
    before = {k: os.environ.get(k) for k in parallel.BLAS_ENV}
    old = parallel.pin_blas_threads()
    assert old["OMP_NUM_THREADS"] == "2"
    assert all(os.environ[k] == "1" for k in parallel.BLAS_ENV)
    parallel.restore_env(old)
    assert {k: os.environ.get(k) for k in parallel.BLAS_ENV} == before
    assert "MKL_NUM_THREADS" not in os.environ


def test_local_cluster_leaves_the_driver_environment_as_found(monkeypatch):
    monkeypatch.delenv(parallel.SCHEDULER_ENV, raising=False)
    keys = (*parallel.BLAS_ENV, *parallel.WORKER_MALLOC_ENV)
    before = {k: os.environ.get(k) for k in keys}
    with parallel.dask_client(1) as client:
        assert set(client.run(lambda: os.environ.get("NUMBA_NUM_THREADS")).values()) == {"1"}
        # the workers' allocator keeps freed memory (set before their process started)
        got = client.run(lambda: {k: os.environ.get(k) for k in parallel.WORKER_MALLOC_ENV})
        assert list(got.values()) == [parallel.WORKER_MALLOC_ENV]
    assert {k: os.environ.get(k) for k in keys} == before


def test_workers_close_before_the_scheduler(monkeypatch):
    """The workers go first, so that none logs a failed heartbeat to a scheduler already gone."""
    seen = []
    real = parallel._close_workers

    def spy(cluster, timeout=30.0):
        seen.append(("scheduler", str(cluster.scheduler.status), "workers", len(cluster.workers)))
        real(cluster, timeout)
        seen.append(("scheduler", str(cluster.scheduler.status), "workers", len(cluster.workers)))

    monkeypatch.setattr(parallel, "_close_workers", spy)
    with parallel.dask_client(2) as c:
        assert sum(c.run(lambda: 1).values()) == 2
    assert seen == [
        ("scheduler", "Status.running", "workers", 2),
        ("scheduler", "Status.running", "workers", 0),
    ]


def test_workers_run_single_threaded(client):
    env = client.run(lambda: os.environ.get("OMP_NUM_THREADS"))
    assert set(env.values()) == {"1"}
    hosts = {addr.split("://")[1].rsplit(":", 1)[0] for addr in env}
    assert hosts == {"127.0.0.1"}, "workers must bind to loopback only"
    assert client.scheduler_info()["address"].startswith("tls://127.0.0.1:"), "TLS with temporary credentials"
    assert client.dashboard_link.startswith("http://127.0.0.1:"), client.dashboard_link


def test_dataset_digest_sensitive_to_values(cases):
    a = parallel.dataset_digest(cases)
    b = parallel.dataset_digest(cases.assign(hs=cases["hs"] + 1e-12))
    assert a != b and a == parallel.dataset_digest(cases.copy(deep=True))


def test_resume_with_another_batch_size_reuses_every_finished_batch(tmp_path, cases, client):
    """simulation.batch_size is scheduling only: a partial store keeps its own batch size, so a
    rerun with another one recomputes only the missing cases, and the bits do not change."""
    out = tmp_path / "results" / "MS2" / "sim.zarr"
    rec = tmp_path / "rec"
    rec.mkdir()
    with pytest.raises(RuntimeError, match="planted failure on case 12"):
        map_cases(
            noisy_case,
            cases,
            out,
            dim="case",
            func_kwargs={"scale": 3.0, "record_dir": str(rec), "fail_on": 12},
            batch_size=5,
            fingerprint="fpB",
            client=client,
        )
    for p in rec.iterdir():
        p.unlink()
    map_cases(
        noisy_case,
        cases,
        out,
        dim="case",
        func_kwargs={"scale": 3.0, "record_dir": str(rec)},
        batch_size=3,
        fingerprint="fpB",
        client=client,
    )
    assert computed(rec) == [10, 11, 12, 13, 14], "only the failed batch of the stored batch size is redone"
    fresh = tmp_path / "fresh" / "results" / "sim.zarr"
    map_cases(
        noisy_case, cases, fresh, dim="case", func_kwargs={"scale": 3.0}, batch_size=7, fingerprint="y", client=client
    )
    xr.testing.assert_identical(mio.open_zarr(out).drop_attrs(), mio.open_zarr(fresh).drop_attrs())


class _ListSink:
    """An in-memory sink: map_batches needs no file."""

    def __init__(self, n, batch_size):
        self.slices = parallel.batch_slices(n, batch_size)
        self.results = {}

    def todo(self):
        return [b for b in range(len(self.slices)) if b not in self.results]

    def write(self, b, result):
        self.results[b] = result


def test_map_batches_hands_every_batch_to_the_sink(cases, client):
    sink = _ListSink(cases.sizes["case"], 4)
    parallel.map_batches(noisy_case, cases, sink, dim="case", func_kwargs={"scale": 1.0}, client=client)
    assert sorted(sink.results) == list(range(6))
    got = np.concatenate([sink.results[b]["surge_mpm"] for b in range(6)])
    expected = noisy_case({"hs": cases["hs"].values}, case_ids=cases["case"].values, scale=1.0)["surge_mpm"]
    np.testing.assert_array_equal(got, expected)


def test_store_fingerprint_ignores_scheduling_settings(cases):
    from moorlife.stages import result_settings
    from moorlife.stages.simulate import store_fingerprint

    platform = xr.Dataset({"mass": ("dof", np.arange(6.0))})
    base = dict(
        dim="case",
        ms="MS1",
        row={"mooring_system": "MS1", "EA_N": 1.0},
        seed=3,
        mooring={},
        fatigue={},
        statistics={},
        platform_cfg={"a": 1},
        cases=cases,
        platform=platform,
    )
    fp = store_fingerprint(simulation={"dt": 0.1, "batch_size": 8}, **base)
    assert fp == store_fingerprint(simulation={"dt": 0.1, "batch_size": 2}, **base)
    assert fp == store_fingerprint(simulation={"dt": 0.1}, **base)
    assert fp != store_fingerprint(simulation={"dt": 0.05, "batch_size": 8}, **base)
    cfg = {"simulation": {"dt": 0.1, "batch_size": 8}, "lifecycle": {"rbf": {"chunk_rows": 10, "shape": "fixed"}}}
    assert result_settings(cfg, "simulation") == {"dt": 0.1}
    assert result_settings(cfg, "lifecycle") == {"rbf": {"shape": "fixed"}}
    assert cfg["lifecycle"]["rbf"]["chunk_rows"] == 10, "the config itself is left as it was"


def test_progress_counts_states_and_estimates_the_time_left():
    """Resumed states count as done and cost nothing; the estimate uses this run's rate only."""
    t = iter([100.0, 110.0, 130.0])
    p = parallel.Progress(total=40, todo=30, label="results/MS1/x.zarr", clock=lambda: next(t))
    assert p.advance(10) == "results/MS1/x.zarr: 20/40 states (50 %), 10 s elapsed, about 20 s left"
    assert p.advance(20) == "results/MS1/x.zarr: 40/40 states (100 %), 30 s elapsed, done"
    assert parallel.format_duration(3725) == "1 h 02 min"
    assert parallel.format_duration(75) == "1 min 15 s"


def test_progress_lines_reach_the_log_and_a_throttled_terminal(tmp_path, cases, client, capfd):
    """Every batch line goes to the rule's log; the terminal (fd 2 as it was before log_to
    redirected it) gets the throttled lines, always the last one."""
    from moorlife.io.logs import log_to

    n = cases.sizes["case"]
    with log_to(tmp_path / "rule.log") as log:
        sink = _ListSink(n, 4)
        parallel.map_batches(
            noisy_case, cases, sink, dim="case", func_kwargs={"scale": 1.0}, client=client, log=log, label="x.zarr"
        )
    logged = (tmp_path / "rule.log").read_text()
    assert logged.count(" states (") == 6 and f"{n}/{n} states (100 %)" in logged
    terminal = [ln for ln in capfd.readouterr().err.splitlines() if ln.startswith("moorlife: x.zarr: ")]
    assert terminal[-1].startswith(f"moorlife: x.zarr: {n}/{n} states (100 %)"), terminal
    assert 1 <= len(terminal) <= 2, terminal  # the first line, then only the last one within 30 s


def _slow_case(case_vars, *, case_ids, scale):
    time.sleep(0.2)  # long enough for batches to be running when the workers go
    return noisy_case(case_vars, case_ids=case_ids, scale=scale)


class _RestartingSink(_ListSink):
    """Restarts every worker after the first batch arrives: all their data is lost."""

    def __init__(self, n, batch_size, client):
        super().__init__(n, batch_size)
        self.client = client
        self.restarts = 0

    def write(self, b, result):
        super().write(b, result)
        if not self.restarts:
            self.restarts += 1
            self.client.restart_workers(list(self.client.scheduler_info()["workers"]))


def test_losing_every_worker_mid_run_loses_no_batch(cases, client):
    """A worker restart (a preempted node, a missed heartbeat) must not cancel the run: the
    static arguments are recomputed, the running batches rerun, and the bits are unchanged."""
    n = cases.sizes["case"]
    sink = _RestartingSink(n, 2, client)
    parallel.map_batches(_slow_case, cases, sink, dim="case", func_kwargs={"scale": 1.0}, client=client)
    assert sink.restarts == 1
    assert sorted(sink.results) == list(range(len(sink.slices)))
    got = np.concatenate([sink.results[b]["tension_mpm"] for b in range(len(sink.slices))])
    expected = noisy_case({"hs": cases["hs"].values}, case_ids=cases["case"].values, scale=1.0)["tension_mpm"]
    np.testing.assert_array_equal(got, expected)


def _echo_spec(case_vars, *, case_ids, spec):
    return {"ok": np.array([spec == (len, [1, 2])] * len(case_ids))}


def test_static_arguments_arrive_as_given(cases, client):
    """A static argument shaped like a legacy Dask task (a tuple led by a callable) is data."""
    sink = _ListSink(cases.sizes["case"], 8)
    parallel.map_batches(_echo_spec, cases, sink, dim="case", func_kwargs={"spec": (len, [1, 2])}, client=client)
    assert all(r["ok"].all() for r in sink.results.values())


def _pid_case(case_vars, *, case_ids, blob):
    time.sleep(0.3)  # each batch long enough that an idle worker would take some
    return {"pid": np.full(len(case_ids), os.getpid()), "n": np.full(len(case_ids), blob.size)}


def test_batches_run_on_every_worker(cases, client):
    """A batch goes where its inputs are: the static arguments must reach every worker, or
    every batch queues behind the one worker that computed them (2 workers as slow as 1)."""
    sink = _ListSink(cases.sizes["case"], 2)  # 12 batches
    blob = np.zeros(2_000_000)  # 16 MB of static arguments, like a platform model
    parallel.map_batches(_pid_case, cases, sink, dim="case", func_kwargs={"blob": blob}, client=client)
    pids = {int(r["pid"][0]) for r in sink.results.values()}
    assert len(pids) == 2, f"every batch ran in one worker process ({pids})"
