"""moorlife.parallel: Dask fan-out into a resumable, single-writer Zarr store."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from moorlife import io as mio
from moorlife import parallel


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
    ds = parallel.map_cases(noisy_case, cases, out, dim="case", func_kwargs={"scale": 2.0},
                            batch_size=5, fingerprint="fp1", client=client)
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
        parallel.map_cases(noisy_case, cases, out, dim="case", func_kwargs={"scale": 1.5},
                           batch_size=bs, fingerprint="fp", threads=threads)
        runs.append(mio.open_zarr(out))
    for other in runs[1:]:
        xr.testing.assert_identical(runs[0].drop_attrs(), other.drop_attrs())


def test_resume_computes_only_missing(tmp_path, cases, client):
    out = tmp_path / "results" / "MS2" / "sim.zarr"
    rec = tmp_path / "rec"
    rec.mkdir()
    with pytest.raises(RuntimeError, match="planted failure on case 12"):
        parallel.map_cases(noisy_case, cases, out, dim="case",
                           func_kwargs={"scale": 3.0, "record_dir": str(rec), "fail_on": 12},
                           batch_size=5, fingerprint="fpR", client=client)
    assert not out.exists(), "a failed run must not leave the declared output"
    part = mio.partial_path(out)
    assert part.exists()
    first = set(computed(rec))
    for p in rec.iterdir():
        p.unlink()
    parallel.map_cases(noisy_case, cases, out, dim="case",
                       func_kwargs={"scale": 3.0, "record_dir": str(rec)},
                       batch_size=5, fingerprint="fpR", client=client)
    second = set(computed(rec))
    assert 12 in second and 10 in second  # the failed batch (10-14) is redone
    done_before = first - {10, 11, 12, 13, 14}
    assert not (second & done_before), "finished batches must be reused, not recomputed"
    fresh = tmp_path / "fresh" / "results" / "sim.zarr"
    parallel.map_cases(noisy_case, cases, fresh, dim="case", func_kwargs={"scale": 3.0},
                       batch_size=5, fingerprint="x", client=client)
    xr.testing.assert_identical(mio.open_zarr(out).drop_attrs(), mio.open_zarr(fresh).drop_attrs())


def test_changed_fingerprint_starts_afresh(tmp_path, cases, client):
    out = tmp_path / "results" / "sim.zarr"
    rec = tmp_path / "rec"
    rec.mkdir()
    with pytest.raises(RuntimeError):
        parallel.map_cases(noisy_case, cases, out, dim="case",
                           func_kwargs={"scale": 1.0, "record_dir": str(rec), "fail_on": 22},
                           batch_size=5, fingerprint="old", client=client)
    for p in rec.iterdir():
        p.unlink()
    parallel.map_cases(noisy_case, cases, out, dim="case",
                       func_kwargs={"scale": 2.0, "record_dir": str(rec)},
                       batch_size=5, fingerprint="new", client=client)
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
    ds = parallel.map_cases(noisy_case, cases, out, dim="case", func_kwargs={"scale": 1.0},
                            batch_size=7, fingerprint="fpC", client=client)
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
    before = {k: os.environ.get(k) for k in parallel.BLAS_ENV}
    with parallel.dask_client(1) as client:
        assert set(client.run(lambda: os.environ.get("NUMBA_NUM_THREADS")).values()) == {"1"}
    assert {k: os.environ.get(k) for k in parallel.BLAS_ENV} == before


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
