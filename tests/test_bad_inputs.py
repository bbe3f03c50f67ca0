"""Bad input through the workflow's own adapters: a clear message, and no declared output.

Every class of bad hindcast (issue 3), a corrupted or partial upstream store, and one real
Snakemake run. The loaders' messages are tested in detail in tests/test_hindcast_io.py; here
the point is what a user of the workflow sees and what is left in results/.
"""

from __future__ import annotations

import importlib.util
import re
import shutil
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from moorlife import io as mio
from moorlife.io import read_study_config

from test_hindcast_io import NORA3_HEADER, nora3_frame, write_csv

ROOT = Path(__file__).resolve().parents[1]
SCRIPTS = ROOT / "workflow" / "scripts"


def adapter(name: str):
    spec = importlib.util.spec_from_file_location(f"rule_{name}", SCRIPTS / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.main


def hindcast_params(path: Path) -> dict:
    cfg = read_study_config(ROOT / "config/config.yaml", schema=ROOT / "workflow/schemas/config.schema.yaml")
    return {**cfg["hindcast"], "source": "file", "path": str(path),
            "start": "2000-01-01T00:00", "end": "2000-01-02T23:00"}


def run_metocean(tmp_path: Path, csv: Path):
    out = tmp_path / "results" / "metocean" / "hindcast.zarr"
    smk = SimpleNamespace(params=SimpleNamespace(hindcast=hindcast_params(csv), seed=1),
                          output=[str(out)], log=[str(tmp_path / "logs" / "metocean.log")], input=[])
    return out, smk


def _set(col, value, row=7):
    def edit(df):
        df[col] = df[col].astype(object)
        df.loc[row, col] = value
        return df
    return edit


BAD = {
    "nan": (_set("hs", np.nan), r"'hs'.*(NaN|missing)"),
    "missing_rows": (lambda df: df.drop(index=[10, 11]).reset_index(drop=True), r"(missing|gap|non-hourly)"),
    "zero_hs": (_set("hs", 0.0), r"'hs'.*value 0 is not > 0"),
    "negative_tp": (_set("tp", -4.0), r"'tp'.*value -4 is not > 0"),
    "direction_out_of_range": (_set("Pdir", 400.0), r"'Pdir'.*direction 400 is outside \[0, 360\)"),
    "duplicated_time": (lambda df: pd.concat([df.iloc[:5], df.iloc[4:]]).reset_index(drop=True), r"duplicat"),
    "unsorted_time": (lambda df: df.iloc[[0, 1, 3, 2] + list(range(4, len(df)))].reset_index(drop=True), r"(unsorted|not increasing|order)"),
    "non_hourly": (lambda df: df.assign(time=pd.date_range("2000-01-01", periods=len(df), freq="30min").strftime("%Y-%m-%d %H:%M:%S")), r"(non-hourly|hourly|step)"),
    "missing_column": (lambda df: df.drop(columns=["tp"]), r"(tp|peak period).*(missing|not found|no column)|(missing|no column).*(tp|peak period)"),
    "hs_in_cm": (lambda df: df.assign(hs=df["hs"] * 100.0), r"'hs'.*(cm|unit|implausible|absurd)"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_hindcast_rejected_and_nothing_written(tmp_path, case):
    edit, pattern = BAD[case]
    csv = write_csv(tmp_path / f"{case}.csv", edit(nora3_frame()))
    out, smk = run_metocean(tmp_path, csv)
    with pytest.raises(ValueError) as err:
        adapter("metocean")(smk)
    msg = str(err.value)
    assert str(csv) in msg, msg
    assert re.search(pattern, msg, flags=re.I | re.S), msg
    assert not out.exists(), "no declared output after a bad input"
    assert not out.parent.exists() or list(out.parent.iterdir()) == [], "no temporary store left behind"
    assert msg in Path(smk.log[0]).read_text(), "the rule log holds the error"


@pytest.mark.parametrize("case", ["empty", "header_only"])
def test_empty_hindcast_files(tmp_path, case):
    csv = tmp_path / f"{case}.csv"
    csv.write_text("" if case == "empty" else NORA3_HEADER + ",".join(nora3_frame().columns) + "\n")
    out, smk = run_metocean(tmp_path, csv)
    with pytest.raises(ValueError, match=re.escape(str(csv)) + r".*(empty|no data|no rows)"):
        adapter("metocean")(smk)
    assert not out.exists()


def test_good_file_through_the_same_adapter(tmp_path):
    """The adapter itself works: the same path with a clean file writes a complete store."""
    csv = write_csv(tmp_path / "good.csv", nora3_frame())
    out, smk = run_metocean(tmp_path, csv)
    adapter("metocean")(smk)
    ds = mio.open_zarr(out)
    assert ds.sizes["time"] == 48 and ds.attrs["hub_height"] == 90.0


@pytest.mark.parametrize("damage", ["not_flagged", "deleted_array"])
def test_corrupted_upstream_store_not_trusted(tmp_path, damage):
    """A hindcast store left in results/ by a killed or foreign writer stops the next rule."""
    store = tmp_path / "results" / "metocean" / "hindcast.zarr"
    t = pd.date_range("1985-01-01", periods=200, freq="h")
    ds = xr.Dataset({v: ("time", np.linspace(1, 2, 200)) for v in ("hs", "tp", "wind_speed", "wind_dir", "wave_dir")},
                    coords={"time": t})
    if damage == "not_flagged":
        ds.to_zarr(store, mode="w", consolidated=False)
    else:
        mio.write_zarr(ds, store)
        shutil.rmtree(store / "tp")
    out = tmp_path / "results" / "selection" / "cases.zarr"
    smk = SimpleNamespace(input=[str(store)], output=[str(out)], log=[str(tmp_path / "sel.log")],
                          params=SimpleNamespace(n_train=10, n_validate=3, rule="random", seed=1))
    with pytest.raises((mio.IncompleteStoreError, KeyError, ValueError)) as err:
        adapter("selection")(smk)
    assert "hindcast.zarr" in str(err.value) or "tp" in str(err.value), str(err.value)
    assert not out.exists()


@pytest.mark.workflow
def test_snakemake_reports_bad_hindcast_and_writes_nothing(tmp_path):
    for item in ("Snakefile", "workflow", "config", "envs", "tests/data"):
        src = ROOT / item
        (shutil.copytree if src.is_dir() else shutil.copy2)(src, tmp_path / item)
    csv = write_csv(tmp_path / "bad.csv", _set("hs", -2.0)(nora3_frame()))
    (tmp_path / "bad.yaml").write_text(
        f"hindcast:\n  source: file\n  path: {csv}\n  start: '2000-01-01T00:00'\n  end: '2000-01-02T23:00'\n")
    snakemake = str(Path(sys.executable).parent / "snakemake")
    res = subprocess.run([snakemake, "--cores", "1", "results/metocean/hindcast.zarr", "--configfile",
                          "config/quick.yaml", "bad.yaml"], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert res.returncode != 0
    log = (tmp_path / "logs" / "metocean" / "hindcast.log").read_text()
    for text in (res.stderr + res.stdout, log):
        assert re.search(r"bad\.csv.*'hs'.*value -2 is not > 0", text, flags=re.S), text[-3000:]
    assert not (tmp_path / "results" / "metocean" / "hindcast.zarr").exists()
