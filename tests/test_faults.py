"""Fault tolerance and security: failing writes, corrupted stores, no unsafe loading or shells."""

from __future__ import annotations

import errno
import re
import uuid
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from moorlife import io as mio
from moorlife.io import partial
from moorlife.stages.fanout import map_cases

ROOT = Path(__file__).resolve().parents[1]


def small_ds() -> xr.Dataset:
    return xr.Dataset({"hs": ("time", np.arange(5.0), {"units": "m"})}, coords={"time": np.arange(5)})


def disk_full(*args, **kwargs):
    raise OSError(errno.ENOSPC, "No space left on device (simulated)")


def test_write_zarr_disk_full_leaves_nothing(tmp_path, monkeypatch):
    out = tmp_path / "results" / "metocean" / "hindcast.zarr"
    monkeypatch.setattr(xr.Dataset, "to_zarr", disk_full)
    with pytest.raises(OSError, match="No space left on device"):
        mio.write_zarr(small_ds(), out)
    assert not out.exists()
    assert list(out.parent.iterdir()) == [], "no temporary store may be left behind"


def test_write_zarr_replaces_atomically(tmp_path):
    out = tmp_path / "results" / "a.zarr"
    mio.write_zarr(small_ds(), out)
    mio.write_zarr(small_ds() * 2, out)
    np.testing.assert_array_equal(mio.open_zarr(out)["hs"].values, np.arange(5.0) * 2)


def _case(case_vars, *, case_ids):
    return {"surge_mpm": case_vars["hs"] * 2.0}


def test_map_cases_disk_full_never_promotes(tmp_path, monkeypatch):
    cases = xr.Dataset({"hs": ("case", np.arange(6.0))}, coords={"case": np.arange(6)})
    out = tmp_path / "results" / "MS1" / "simulations.zarr"
    calls = {"n": 0}
    real = partial._write_batch

    def flaky(*args, **kwargs):
        calls["n"] += 1
        if calls["n"] == 2:
            disk_full()
        return real(*args, **kwargs)

    monkeypatch.setattr(partial, "_write_batch", flaky)
    with pytest.raises(OSError, match="No space left on device"):
        map_cases(_case, cases, out, dim="case", func_kwargs={}, batch_size=2, fingerprint="d", threads=1)
    assert not out.exists(), "a failed write must never be promoted to the declared output"
    monkeypatch.setattr(partial, "_write_batch", real)
    ds = map_cases(_case, cases, out, dim="case", func_kwargs={}, batch_size=2, fingerprint="d", threads=1)
    np.testing.assert_array_equal(ds["surge_mpm"].values, np.arange(6.0) * 2)


def _recorded_case(case_vars, *, case_ids, record_dir):
    for c in case_ids:
        Path(record_dir, f"{int(c)}-{uuid.uuid4().hex[:6]}").touch()
    return {"surge_mpm": case_vars["hs"] * 2.0}


def exdev(*args, **kwargs):
    raise OSError(errno.EXDEV, "Invalid cross-device link (simulated)")


def test_failed_promote_then_rerun_computes_nothing(tmp_path, monkeypatch):
    """A rename that fails (EXDEV) after every batch is done: the rerun promotes, computing nothing.

    The fingerprint used to be lost when the case variables were appended (the append replaces
    the root attributes), so the rerun saw 'another fingerprint' and recomputed every batch.
    """
    cases = xr.Dataset({"hs": ("case", np.arange(6.0))}, coords={"case": np.arange(6)}, attrs={"note": "cases"})
    out = tmp_path / "results" / "MS1" / "simulations.zarr"
    rec = tmp_path / "rec"
    rec.mkdir()
    kw = dict(
        dim="case",
        func_kwargs={"record_dir": str(rec)},
        batch_size=2,
        fingerprint="fp-x",
        threads=1,
        attrs={"mooring_system": "MS1"},
    )
    monkeypatch.setattr(mio, "promote", exdev)
    with pytest.raises(OSError, match="cross-device"):
        map_cases(_recorded_case, cases, out, **kw)
    monkeypatch.undo()
    assert not out.exists() and mio.partial_path(out).exists()
    assert len(list(rec.iterdir())) == 6
    for p in rec.iterdir():
        p.unlink()
    ds = map_cases(_recorded_case, cases, out, **kw)
    assert list(rec.iterdir()) == [], "every batch was done: the rerun must only promote the store"
    assert not mio.partial_path(out).exists()
    np.testing.assert_array_equal(ds["surge_mpm"].values, np.arange(6.0) * 2)
    assert "_batch_done" not in ds and "batch_size" not in ds.attrs
    assert ds.attrs["mooring_system"] == "MS1" and ds.attrs[mio.COMPLETE_ATTR] is True
    fresh = map_cases(_recorded_case, cases, tmp_path / "fresh" / "results" / "s.zarr", **kw)
    xr.testing.assert_identical(ds, fresh)


def test_promote_across_filesystems_copies_then_renames(tmp_path, monkeypatch):
    """EXDEV (partial store and output on different filesystems): copy beside the output, rename."""
    import os

    real = os.replace

    def cross_device(src, dst):
        if Path(src).parent != Path(dst).parent:
            exdev()
        return real(src, dst)

    out = tmp_path / "results" / "MS1" / "a.zarr"
    part = mio.partial_path(out)
    mio.write_zarr(small_ds(), part)
    monkeypatch.setattr(mio.os, "replace", cross_device)
    mio.promote(part, out)
    monkeypatch.undo()
    assert not part.exists()
    np.testing.assert_array_equal(mio.open_zarr(out)["hs"].values, np.arange(5.0))
    assert [p.name for p in out.parent.iterdir()] == ["a.zarr"], "no temporary copy may be left behind"


@pytest.mark.parametrize("damage", ["no_flag", "bad_metadata", "missing_chunks"])
def test_corrupted_store_detected(tmp_path, damage):
    out = tmp_path / "results" / "selection" / "cases.zarr"
    big = xr.Dataset({"hs": ("case", np.arange(1000.0))}, coords={"case": np.arange(1000)})
    mio.write_zarr(big, out, encoding={"hs": {"chunks": (100,)}})
    if damage == "no_flag":
        big.to_zarr(out, mode="w", consolidated=False)  # written by something else, never flagged
    elif damage == "bad_metadata":
        (out / "zarr.json").write_text('{"zarr_format": 3, "node_type": "gr')
    else:
        chunks = sorted(p for p in (out / "hs").rglob("*") if p.is_file() and p.name != "zarr.json")
        chunks[-1].write_bytes(b"\x00garbage")
    with pytest.raises(mio.IncompleteStoreError, match=r"cases\.zarr.*(incomplete|not a readable|corrupted)"):
        mio.open_zarr(out)


def _source_files() -> list[Path]:
    files = list((ROOT / "src").rglob("*.py")) + list((ROOT / "workflow").rglob("*.py"))
    return files + list((ROOT / "workflow").rglob("*.smk")) + [ROOT / "Snakefile"]


@pytest.mark.parametrize(
    "pattern",
    [
        r"\bpickle\.loads?\(",
        r"\beval\(",
        r"\bexec\(",
        r"yaml\.load\((?![^)]*SafeLoader)",
        r"shell\s*=\s*True",
        r"allow_pickle\s*=\s*True",
        r"os\.system\(",
    ],
)
def test_no_unsafe_loading_or_shell(pattern):
    hits = [
        f"{p.relative_to(ROOT)}:{i}"
        for p in _source_files()
        for i, line in enumerate(p.read_text().splitlines(), 1)
        if re.search(pattern, line)
    ]
    assert hits == [], f"unsafe construct {pattern!r} at {hits}"


def test_shell_rules_quote_every_value():
    """Config values never reach a shell unquoted: every {placeholder} in a shell: block uses :q."""
    for smk in list((ROOT / "workflow").rglob("*.smk")) + [ROOT / "Snakefile"]:
        text = smk.read_text()
        for block in re.findall(r"shell:\s*\n?\s*((?:\"\"\".*?\"\"\")|(?:\".*?\"))", text, flags=re.S):
            for field in re.findall(r"(?<!\{)\{([^{}]+)\}(?!\})", block):
                assert field.endswith(":q") or field in {"threads", "log", "log[0]"}, (
                    f"{smk.name}: shell placeholder {{{field}}} is not quoted with :q"
                )
