"""Bad input through the workflow's own adapters: a clear message, and no declared output.

Every class of bad hindcast (issue 3), a corrupted or partial upstream store, and one real
Snakemake run. The loaders' messages are tested in detail in tests/test_hindcast_io.py; here
the point is what a user of the workflow sees and what is left in results/.
"""

from __future__ import annotations

import importlib.util
import os
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
from snakemake.iocontainers import Namedlist
from test_hindcast_io import NORA3_HEADER, nora3_frame, write_csv

from moorlife import io as mio
from moorlife.config import ConfigError, check_against_table, deep_merge, validate_config
from moorlife.io import read_mooring_systems, read_study_config, read_yaml
from moorlife.metocean import HindcastError

ROOT = Path(__file__).resolve().parents[1]
SCRIPTS = ROOT / "workflow" / "scripts"


def adapter(name: str):
    spec = importlib.util.spec_from_file_location(f"rule_{name}", SCRIPTS / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.main


def hindcast_params(path: Path) -> dict:
    cfg = read_study_config(ROOT / "config/config.yaml", schema=ROOT / "workflow/schemas/config.schema.yaml")
    return {
        **cfg["hindcast"],
        "source": "file",
        "path": str(path),
        "start": "2000-01-01T00:00",
        "end": "2000-01-02T23:00",
    }


def run_metocean(tmp_path: Path, csv: Path):
    out = tmp_path / "results" / "metocean" / "hindcast.zarr"
    smk = SimpleNamespace(
        params=Namedlist(fromdict={"hindcast": hindcast_params(csv), "seed": 1}),
        output=Namedlist(fromdict={"store": str(out)}),
        log=[str(tmp_path / "logs" / "metocean.log")],
        input=Namedlist(),
    )
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
    "unsorted_time": (
        lambda df: df.iloc[[0, 1, 3, 2] + list(range(4, len(df)))].reset_index(drop=True),
        r"(unsorted|not increasing|order)",
    ),
    "non_hourly": (
        lambda df: df.assign(
            time=pd.date_range("2000-01-01", periods=len(df), freq="30min").strftime("%Y-%m-%d %H:%M:%S")
        ),
        r"(non-hourly|hourly|step)",
    ),
    "missing_column": (
        lambda df: df.drop(columns=["tp"]),
        r"(tp|peak period).*(missing|not found|no column)|(missing|no column).*(tp|peak period)",
    ),
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
    ds = xr.Dataset(
        {v: ("time", np.linspace(1, 2, 200)) for v in ("hs", "tp", "wind_speed", "wind_dir", "wave_dir")},
        coords={"time": t},
    )
    if damage == "not_flagged":
        ds.to_zarr(store, mode="w", consolidated=False)
    else:
        mio.write_zarr(ds, store)
        shutil.rmtree(store / "tp")
    out = tmp_path / "results" / "selection" / "cases.zarr"
    smk = SimpleNamespace(
        input=Namedlist(fromdict={"hindcast": str(store)}),
        output=Namedlist(fromdict={"store": str(out)}),
        log=[str(tmp_path / "sel.log")],
        params=Namedlist(fromdict={"n_train": 10, "n_validate": 3, "rule": "random", "seed": 1}),
    )
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
        f"hindcast:\n  source: file\n  path: {csv}\n  start: '2000-01-01T00:00'\n  end: '2000-01-02T23:00'\n"
        # 48 hours hold at most 48 states (checked at parse time since issue 20)
        "selection:\n  n_train: 10\n  n_validate: 4\n"
    )
    snakemake = str(Path(sys.executable).parent / "snakemake")
    res = subprocess.run(
        [snakemake, "--cores", "1", "results/metocean/hindcast.zarr", "--configfile", "config/quick.yaml", "bad.yaml"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert res.returncode != 0
    log = (tmp_path / "logs" / "metocean" / "hindcast.log").read_text()
    for text in (res.stderr + res.stdout, log):
        assert re.search(r"bad\.csv.*'hs'.*value -2 is not > 0", text, flags=re.S), text[-3000:]
    assert not (tmp_path / "results" / "metocean" / "hindcast.zarr").exists()


# ============================================================================================
# Issue 20: more bad input. Every case asserts what the workflow does with it:
#  * "exit code": the error class that the rule or the parse-time check raises (Snakemake turns
#    any exception of a script or of the Snakefile into exit code 1; the `snakemake` cases at the
#    end check that end to end);
#  * that the message names the file or the config key and the offending value;
#  * that no declared output (and no temporary store) is left.
# ============================================================================================

SCHEMA = ROOT / "workflow" / "schemas" / "config.schema.yaml"


def _no_output(out: Path) -> None:
    assert not out.exists(), "no declared output after a bad input"
    if out.parent.exists():
        assert [p.name for p in out.parent.iterdir()] == [], "no temporary store left behind"


def _rows(col, values):
    def edit(df):
        df[col] = df[col].astype(object)
        for row, v in values.items():
            df.loc[row, col] = v
        return df

    return edit


def _times(fmt_row):
    """Replace the time column: fmt_row(k, timestamp) -> text."""

    def edit(df):
        t = pd.date_range("2000-01-01", periods=len(df), freq="h")
        df["time"] = [fmt_row(k, x) for k, x in enumerate(t)]
        return df

    return edit


def _dup_hs(df):
    return df.assign(hs_sea=df["hs"]).rename(columns={"hs_sea": "hs"})


# (edit of the NORA3 frame, pattern of the message); each names the file (checked below)
BAD_ISSUE20 = {
    # item 4: physically impossible sea states
    "tp_0.01": (_set("tp", 0.01), r"row 11 .*tp = 0\.01 s .*below the floor of 1 s"),
    "hs20_tp3": (
        lambda df: _set("tp", 3.0)(_set("hs", 20.0)(df)),
        r"row 11 .*hs = 20 m, tp = 3 s .*steepness .* = 1\.42 exceeds the breaking limit",
    ),
    "hs5_tp4": (lambda df: _set("tp", 4.0)(_set("hs", 5.0)(df)), r"hs = 5 m, tp = 4 s .*breaking limit 0\.1429"),
    "tp_0.5_small_hs": (lambda df: _set("tp", 0.5)(_set("hs", 0.01)(df)), r"tp = 0\.5 s .*floor"),
    # item 6: a constant input coordinate (all-zero wind)
    "all_zero_wind": (
        lambda df: df.assign(wind_speed_10m=0.0, wind_speed_100m=0.0, wind_speed_250m=0.0),
        r"column 'wind_speed_100m' \(variable wind_speed\) is constant, 0,",
    ),
    "constant_tp": (lambda df: df.assign(tp=7.0), r"column 'tp' \(variable tp\) is constant, 7,"),
    # item 7: raw exceptions
    "mixed_tz": (
        _times(lambda k, x: x.strftime("%Y-%m-%d %H:%M:%S") + ("+01:00" if k % 2 else "")),
        r"column 'time' mixes timestamps with a UTC offset \(row \d+: '2000-01-01 01:00:00\+01:00'\)",
    ),
    "ragged_row": (lambda df: df, r"line 10 has 13 comma-separated fields, the header row 12 \(a ragged row"),
    "duplicated_columns": (_dup_hs, r"duplicated column name\(s\) \['hs'\]"),
    "not_a_time": (_set("time", "yesterday", row=5), r"column 'time', row 9: 'yesterday' is not a timestamp"),
    "text_value": (_set("hs", "abc"), r"column 'hs', row 11 .*'abc' is not a number"),
    # item 8: infinite values (a wrapped inf direction became NaN in a complete store)
    "inf_direction": (_set("Pdir", np.inf), r"column 'Pdir' \(variable wave_dir\), row 11: value inf is not finite"),
    "minus_inf_wind": (
        _set("wind_direction_100m", -np.inf),
        r"column 'wind_direction_100m' .*row 11: value -inf is not finite",
    ),
    "inf_hs": (_set("hs", np.inf), r"column 'hs' .*row 11: value inf is not finite"),
    # the validation's other classes, through the same adapter
    "negative_wind": (_set("wind_speed_100m", -3.0), r"'wind_speed_100m'.*value -3 is negative"),
    "wind_in_kmh": (
        lambda df: df.assign(wind_speed_100m=df["wind_speed_100m"] * 10.0),
        r"'wind_speed_100m'.*exceeds the plausible maximum 80 \(wind speed in km/h",
    ),
    "negative_direction": (
        _set("wind_direction_100m", -10.0),
        r"'wind_direction_100m'.*direction -10 is outside \[0, 360\)",
    ),
    "tp_in_tenths": (lambda df: df.assign(tp=df["tp"] * 10.0), r"'tp'.*exceeds the plausible maximum 40"),
}


def _write_case(tmp_path: Path, case: str, edit) -> Path:
    csv = write_csv(tmp_path / f"{case}.csv", edit(nora3_frame()))
    if case == "ragged_row":
        lines = csv.read_text().splitlines(keepends=True)
        lines[9] = lines[9].rstrip("\n") + ",1.0\n"  # one field too many on file line 10
        csv.write_text("".join(lines))
    return csv


@pytest.mark.parametrize("case", sorted(BAD_ISSUE20))
def test_issue20_bad_hindcast_rejected(tmp_path, case):
    edit, pattern = BAD_ISSUE20[case]
    csv = _write_case(tmp_path, case, edit)
    out, smk = run_metocean(tmp_path, csv)
    with pytest.raises(HindcastError) as err:
        adapter("metocean")(smk)
    msg = str(err.value)
    assert str(csv) in msg, msg
    assert re.search(pattern, msg, flags=re.S), msg
    _no_output(out)
    assert msg in Path(smk.log[0]).read_text(), "the rule log holds the error"


@pytest.mark.parametrize(
    ("case", "content", "pattern"),
    [
        ("binary", b"\x89HDF\r\n\x1a\n\x00\x00\xff\xfe\x00\x01" * 20, r"not a CSV text file"),
        # item 11: a wrong path to a file with secrets: its content is never echoed
        (
            "secret",
            b"root:*:19000:0:99999:7:::\ndaemon:*:19000:0:99999:7:::\n",
            r"missing column 'time': expected a header row",
        ),
        ("text", b"just some notes\nnothing tabular, here\n", r"missing column 'time'"),
    ],
)
def test_issue20_not_a_hindcast(tmp_path, case, content, pattern):
    csv = tmp_path / f"{case}.csv"
    csv.write_bytes(content)
    out, smk = run_metocean(tmp_path, csv)
    with pytest.raises(HindcastError) as err:
        adapter("metocean")(smk)
    msg = str(err.value)
    assert str(csv) in msg and re.search(pattern, msg), msg
    for secret in ("root", "19000", "daemon", "notes", "HDF"):
        assert secret not in msg.replace(str(csv), ""), f"the message echoes the file's content: {msg}"
    _no_output(out)


@pytest.mark.parametrize(
    ("patch", "pattern"),
    [
        ({"start": "yesterday"}, r"config key 'hindcast\.start' = 'yesterday' is not an ISO 8601 time"),
        ({"end": "2000-13-45"}, r"config key 'hindcast\.end' = '2000-13-45' is not an ISO 8601 time"),
        ({"start": "1999-01-01T00:00"}, r"study period 1999-01-01 00:00:00 .* not inside the file's span"),
        (
            {"cleaning": {"wrap_directions": True}, "_inf": True},
            r"'Pdir' \(variable wave_dir\), row 11: value inf is not finite",
        ),
    ],
    ids=["start_yesterday", "end_not_a_date", "period_outside_file", "inf_with_wrap_directions"],
)
def test_issue20_bad_hindcast_settings(tmp_path, patch, pattern):
    patch = dict(patch)
    df = nora3_frame()
    if patch.pop("_inf", False):
        df = _set("Pdir", np.inf)(df)
    csv = write_csv(tmp_path / "h.csv", df)
    out, smk = run_metocean(tmp_path, csv)
    smk.params.hindcast = deep_merge(smk.params.hindcast, patch)
    with pytest.raises(HindcastError) as err:
        adapter("metocean")(smk)
    msg = str(err.value)
    assert re.search(pattern, msg), msg
    if "config key" not in msg:
        assert str(csv) in msg, msg
    _no_output(out)


# ----------------------------------------------------------------- config, at parse time
def _base(*overlays):
    cfg = read_yaml(ROOT / "config" / "config.yaml")
    for ov in overlays:
        cfg = deep_merge(cfg, ov)
    return cfg


QUICK = read_yaml(ROOT / "config" / "quick.yaml")

BAD_CONFIG = {
    # item 5: a time step that cannot resolve the waves
    "dt_1": (
        {"simulation": {"dt": 1.0}},
        r"'simulation\.dt' = 1\.0 s cannot resolve the shortest wave period, 2 pi / 'hydro\.omega\.max' = 2 pi / 2\.5 = 2\.51 s",
    ),
    "dt_0.3": ({"simulation": {"dt": 0.3}}, r"'simulation\.dt' = 0\.3 s .*dt <= 0\.251 s"),
    "dt_vs_omega_max": (
        {"hydro": {"omega": {"max": 6.0}}, "simulation": {"dt": 0.2}},
        r"'simulation\.dt' = 0\.2 s .*'hydro\.omega\.max' = 2 pi / 6\.0",
    ),
    "kinematics_dt_1": (
        {"simulation": {"kinematics_dt": 1.0}},
        r"'simulation\.kinematics_dt' = 1\.0 s \(sampled every 1 s",
    ),
    # item 6: cross-key checks that ran on the workers
    "block_100_in_120s": (
        {"simulation": {"duration": 120.0}, "statistics": {"block": 100.0}},
        r"'statistics\.block' = 100\.0 s: the kept record 'simulation\.duration' = 120\.0 s holds 1 block\(s\); the GEV fit needs at least 5: statistics\.block <= 24 s",
    ),
    "block_200_in_600s": (
        {"statistics": {"block": 200.0}},
        r"'statistics\.block' = 200\.0 s: the kept record 'simulation\.duration' = 600\.0 s holds 3 block\(s\)",
    ),
    "block_one_step": (
        {"statistics": {"block": 0.1}},
        r"'statistics\.block' = 0\.1 s is shorter than two steps of 'simulation\.dt' = 0\.1 s",
    ),
    "too_many_states": (
        {"hindcast": {"end": "1985-01-02T00:00"}},
        r"'selection\.n_train' = 40 \+ 'selection\.n_validate' = 12 sea states exceed the 25 hour",
    ),
    "omega_min_above_max": (
        {"hydro": {"omega": {"min": 3.0}}},
        r"'hydro\.omega\.min' = 3\.0 must be below 'hydro\.omega\.max' = 2\.5",
    ),
    "rbf_grid_reversed": (
        {"lifecycle": {"rbf": {"grid": {"min": 2.0}}}},
        r"'lifecycle\.rbf\.grid\.min' = 2\.0 must be below 'lifecycle\.rbf\.grid\.max' = 1\.0",
    ),
    "synthetic_tp_clip_reversed": (
        {"hindcast": {"synthetic": {"tp_min": 30.0}}},
        r"'hindcast\.synthetic\.tp_min' = 30\.0 must be below 'hindcast\.synthetic\.tp_max' = 22\.0",
    ),
    "hs_edges_not_increasing": (
        {"selection": {"discrete": {"hs_edges": [0.0, 3.0, 1.5]}}},
        r"'selection\.discrete\.hs_edges' = \[0\.0, 3\.0, 1\.5\]: the class edges must increase",
    ),
    "heading_step_7": ({"hydro": {"heading_step": 7.0}}, r"'hydro\.heading_step' = 7\.0 deg must divide 360"),
    "direction_sector_7": (
        {"selection": {"discrete": {"direction_sector": 7.0}}},
        r"'selection\.discrete\.direction_sector' = 7\.0 deg must divide 360",
    ),
    "regime_lists_differ": (
        {"hindcast": {"synthetic": {"wind": {"regime_spreads": [20.0, 20.0]}}}},
        r"hindcast\.synthetic\.wind\.regime_spreads \(2 values\)",
    ),
    "fetch_lists_differ": (
        {"hindcast": {"synthetic": {"wind_sea": {"fetch_km": [100.0]}}}},
        r"hindcast\.synthetic\.wind_sea\.fetch_km \(1 values\)",
    ),
    "file_source_no_path": (
        {"hindcast": {"source": "file"}},
        r"'hindcast\.path' = None: a path is required when 'hindcast\.source' is 'file'",
    ),
    "wamit_no_prefix": ({"hydro": {"source": "wamit"}}, r"'hydro\.wamit_prefix' = None: a path prefix is required"),
    "sensitivity_steep_state": (
        {"lifecycle": {"sensitivity": {"sea_state": {"hs": 20.0, "tp": 3.0}}}},
        r"'lifecycle\.sensitivity\.sea_state\.hs' = 20\.0, '\.tp' = 3\.0: not a possible sea state",
    ),
    # item 7: a date that is not one, a time off the hour
    "start_yesterday": (
        {"hindcast": {"start": "yesterday"}},
        r"'hindcast\.start' = 'yesterday' is not an ISO 8601 time",
    ),
    "start_off_the_hour": (
        {"hindcast": {"start": "1985-01-01T00:30"}},
        r"'hindcast\.start' = '1985-01-01T00:30' is not on a whole hour",
    ),
    "end_before_start": (
        {"hindcast": {"end": "1984-12-31T23:00"}},
        r"'hindcast\.end' = '1984-12-31T23:00' is before 'hindcast\.start' = '1985-01-01T00:00'",
    ),
}


@pytest.mark.parametrize("case", sorted(BAD_CONFIG))
def test_issue20_bad_config_refused_before_any_job(tmp_path, case):
    patch, pattern = BAD_CONFIG[case]
    with pytest.raises(ConfigError) as err:
        validate_config(_base(QUICK, patch), read_yaml(SCHEMA), source="bad.yaml")
    msg = str(err.value)
    assert msg.startswith("bad.yaml: "), msg
    assert re.search(pattern, msg), msg


def test_issue20_default_and_overlay_configs_pass_the_cross_key_checks():
    """The checks refuse only what is wrong: config.yaml, quick.yaml and tiny.yaml pass."""
    schema = read_yaml(SCHEMA)
    tiny = read_yaml(ROOT / "tests" / "data" / "tiny.yaml")
    for cfg in (_base(), _base(QUICK), _base(QUICK, tiny)):
        validate_config(cfg, schema)


def test_issue20_sensitivity_system_not_in_table():
    """item 8: `lifecycle.sensitivity.mooring_system: MS9` used to drop the sensitivities silently."""
    cfg = _base(QUICK, {"lifecycle": {"sensitivity": {"mooring_system": "MS9"}}})
    ids = list(read_mooring_systems(ROOT / "config" / "mooring_systems.tsv").index)
    with pytest.raises(
        ConfigError,
        match=r"bad\.yaml: config key 'lifecycle\.sensitivity\.mooring_system' = 'MS9' "
        r"is not a mooring system of the table config/mooring_systems\.tsv \(MS1, ",
    ):
        check_against_table(cfg, ids, "bad.yaml")
    check_against_table(_base(QUICK), ids, "good.yaml")


def test_issue20_corrosion_consumes_the_link():
    """A corrosion rate that eats a link within the design life failed only at the end of lifecycle."""
    table = read_mooring_systems(ROOT / "config" / "mooring_systems.tsv")
    d = dict(table["link_diameter_mm"])
    cfg = validate_config(_base(QUICK, {"fatigue": {"corrosion": {"rate": 5.0}}}), read_yaml(SCHEMA))
    with pytest.raises(
        ConfigError,
        match=r"bad\.yaml: config keys 'fatigue\.corrosion\.rate' = 5\.0 mm/year over "
        r"'fatigue\.design_life' = 25\.0 years remove 125 mm, the whole \d+ mm link of MS1",
    ):
        check_against_table(cfg, list(table.index), "bad.yaml", d)
    check_against_table(validate_config(_base(QUICK), read_yaml(SCHEMA)), list(table.index), "good.yaml", d)


# ----------------------------------------------------------------- the mooring table
TSV = (ROOT / "config" / "mooring_systems.tsv").read_text()


def _tsv_edit(kind: str) -> str:
    lines = [ln for ln in TSV.splitlines() if ln.strip() and not ln.startswith("#")]
    if kind == "comma":
        return "\n".join(ln.replace("\t", ",") for ln in lines) + "\n"
    if kind == "semicolon":
        return "\n".join(ln.replace("\t", ";") for ln in lines) + "\n"
    if kind == "mbs_below_pretension":
        head, rows = lines[0].split("\t"), [ln.split("\t") for ln in lines[1:]]
        rows[1][head.index("MBS_N")] = "1000000"  # MS2: 1 MN against a pretension of 1,000+ kN
        return "\n".join(["\t".join(head)] + ["\t".join(r) for r in rows]) + "\n"
    if kind == "duplicated_column":
        return "\n".join(ln + "\t" + ln.split("\t")[5] for ln in lines) + "\n"
    if kind == "ragged":
        return "\n".join(lines[:3] + [lines[3] + "\t42"] + lines[4:]) + "\n"
    if kind == "secret":
        return "root:*:19000:0:99999:7:::\nbin:*:19000:0:99999:7:::\n"
    if kind == "empty":
        return "# nothing but a comment\n"
    raise KeyError(kind)


@pytest.mark.parametrize(
    ("kind", "pattern"),
    [
        ("comma", r"is comma-separated; the columns must be separated by tabs"),
        ("semicolon", r"is semicolon-separated"),
        ("mbs_below_pretension", r"row 3 \(MS2\): MBS_N = 1e\+06 N is not above the pretension pretension_kN = \d+ kN"),
        ("duplicated_column", r"duplicated column name\(s\) \['EA_N'\]"),
        ("ragged", r"not a tab-separated table .*\(line \d+: another number of fields"),
        ("secret", r"missing column\(s\) \['mooring_system'.*expected the tab-separated columns"),
        ("empty", r"the mooring-system table is empty"),
    ],
)
def test_issue20_bad_mooring_table(tmp_path, kind, pattern):
    p = tmp_path / f"{kind}.tsv"
    p.write_text(_tsv_edit(kind))
    with pytest.raises(ValueError) as err:
        read_mooring_systems(p)
    msg = str(err.value)
    assert msg.startswith(f"{p}: ") and re.search(pattern, msg), msg
    for secret in ("root", "19000", "bin:"):
        assert secret not in msg.replace(str(p), ""), f"the message echoes the file's content: {msg}"


def test_issue20_mooring_table_missing(tmp_path):
    p = tmp_path / "nope.tsv"
    with pytest.raises(
        ValueError, match=re.escape(str(p)) + r": no such mooring-system table \(config key 'mooring_systems'\)"
    ):
        read_mooring_systems(p)


# ----------------------------------------------------------------- platform.yaml
@pytest.mark.parametrize(
    ("path", "value", "pattern"),
    [
        (
            ("platform", "cm"),
            [0.0, -13.46],
            r"platform\.cm = \[0\.0, -13\.46\] must be a list of 3 numbers \(x, y, z in m\)",
        ),
        (("rna", "inertia_cm"), [1.0, 2.0], r"rna\.inertia_cm = \[1\.0, 2\.0\] must be a list of 3 numbers"),
        (
            ("mooring_stiffness_diag",),
            [1.0] * 5,
            r"mooring_stiffness_diag = \[1\.0, 1\.0, 1\.0, 1\.0, 1\.0\] must be a list of 6",
        ),
        (("tower", "mass"), "2.5e5", r"tower\.mass\[0\] = '2\.5e5' is not a number"),
    ],
    ids=["cm_of_length_2", "inertia_of_length_2", "stiffness_of_length_5", "mass_as_text"],
)
def test_issue20_bad_platform_yaml(tmp_path, path, value, pattern):
    import yaml

    from moorlife.io.platform import read_platform_config

    cfg = read_yaml(ROOT / "config" / "platform.yaml")
    node = cfg
    for k in path[:-1]:
        node = node[k]
    node[path[-1]] = value
    p = tmp_path / "platform.yaml"
    p.write_text(yaml.safe_dump(cfg))
    with pytest.raises(ValueError) as err:
        read_platform_config(p)
    msg = str(err.value)
    assert msg.startswith(f"{p}: ") and re.search(pattern, msg), msg


# ----------------------------------------------------------------- the environment
@pytest.mark.parametrize("address", ["foo:bar", "tcp://127.0.0.1:99999", "http://example.org:8786"])
def test_issue20_bad_scheduler_address(monkeypatch, address):
    """`DASK_SCHEDULER_ADDRESS=foo:bar` raised a bare int() error; now it names the variable."""
    from moorlife import parallel

    monkeypatch.setenv(parallel.SCHEDULER_ENV, address)
    with pytest.raises(ValueError) as err, parallel.dask_client(1):
        pass
    msg = str(err.value)
    assert f"environment variable DASK_SCHEDULER_ADDRESS = {address!r} is not a Dask scheduler address" in msg, msg


def test_issue20_disk_full_names_the_store(tmp_path, monkeypatch):
    """ENOSPC: the error names the store, and neither the store nor a temporary is left."""
    import errno

    def full(self, store, *a, **k):
        Path(store).mkdir(parents=True)
        (Path(store) / "chunk").write_bytes(b"x")
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(xr.Dataset, "to_zarr", full)
    out = tmp_path / "results" / "metocean" / "hindcast.zarr"
    with pytest.raises(OSError) as err:
        mio.write_zarr(xr.Dataset({"a": ("x", np.arange(3.0))}), out)
    assert err.value.errno == errno.ENOSPC
    assert f"{out}: writing the Zarr store failed (No space left on device)" in str(err.value), str(err.value)
    _no_output(out)


# ----------------------------------------------------------------- end to end, with snakemake
def _copy_workflow(tmp_path: Path) -> None:
    for item in ("Snakefile", "workflow", "config", "envs", "tests/data"):
        src = ROOT / item
        (shutil.copytree if src.is_dir() else shutil.copy2)(src, tmp_path / item)


E2E = {
    "dt_1": ("simulation:\n  dt: 1.0\n", r"bad\.yaml.*config key 'simulation\.dt' = 1\.0 s cannot resolve"),
    "block_150": (
        "statistics:\n  block: 150.0\n",
        r"bad\.yaml.*config key 'statistics\.block' = 150\.0 s: the kept record",
    ),
    "sensitivity_MS9": (
        "lifecycle:\n  sensitivity:\n    mooring_system: MS9\n",
        r"'lifecycle\.sensitivity\.mooring_system' = 'MS9' is not a mooring system",
    ),
    "comma_table": ("mooring_systems: comma.tsv\n", r"comma\.tsv: the mooring-system table is comma-separated"),
    "platform_cm": (
        "platform: platform2.yaml\n",
        r"platform2\.yaml: platform\.cm = \[0\.0, 0\.0\] must be a list of 3",
    ),
}


@pytest.mark.workflow
@pytest.mark.parametrize("case", sorted(E2E))
def test_issue20_snakemake_refuses_at_parse_time(tmp_path, case):
    """The real command: exit code non-zero before any job, the key and value in the message."""
    _copy_workflow(tmp_path)
    (tmp_path / "comma.tsv").write_text(_tsv_edit("comma"))
    plat = (tmp_path / "config" / "platform.yaml").read_text()
    (tmp_path / "platform2.yaml").write_text(plat.replace("cm: [0.0, 0.0, -13.46]", "cm: [0.0, 0.0]"))
    text, pattern = E2E[case]
    (tmp_path / "bad.yaml").write_text(text)
    snakemake = str(Path(sys.executable).parent / "snakemake")
    res = subprocess.run(
        [snakemake, "--cores", "1", "--configfile", "config/quick.yaml", "bad.yaml"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert res.returncode == 1, res.stderr[-2000:]
    assert re.search(pattern, res.stderr + res.stdout, flags=re.S), res.stderr[-3000:]
    assert not (tmp_path / "results").exists(), "no job ran, nothing was written"
    assert not (tmp_path / "logs").exists()


# ----------------------------------------------------------------- item 10: the private cluster
def test_issue20_local_cluster_refuses_clients_without_credentials(tmp_path):
    """Another local user could connect to the unauthenticated scheduler and run code as us."""
    from distributed import Client

    from moorlife import parallel

    with parallel.dask_client(1) as client:
        addr = client.scheduler.address
        assert addr.startswith("tls://127.0.0.1:"), addr
        assert client.submit(int, "41").result() == 41  # the study's own client works
        for attempt in ("plain", "foreign"):
            if attempt == "plain":  # no TLS at all
                kw, target = {}, addr.replace("tls://", "tcp://")
            else:  # TLS, with a certificate of its own
                kw, target = {"security": parallel._openssl_security(tmp_path)}, addr
            with pytest.raises((OSError, TimeoutError)):
                Client(target, timeout=3, **kw).close()


# ----------------------------------------------------------------- item 3: killed writers
_CHILD = """
import sys, time
import numpy as np, xarray as xr
import moorlife.io as mio
def hang(path):  # the store is on disk, the flag not yet set: wait for the SIGKILL
    print("written", flush=True)
    time.sleep(600)
mio._mark_complete = hang
mio.write_zarr(xr.Dataset({"a": ("x", np.arange(1000.0))}), sys.argv[1])
"""


def test_issue20_sigkill_during_write_zarr_leaves_nothing_after_the_next_write(tmp_path):
    """A SIGKILL mid-write left `.<store>.tmp-*` for ever; the next write of that store removes it."""
    import os
    import signal

    out = tmp_path / "results" / "hindcast.zarr"
    child = subprocess.Popen([sys.executable, "-c", _CHILD, str(out)], stdout=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "written"
        left = [p.name for p in out.parent.iterdir()]
        assert len(left) == 1 and left[0].startswith(".hindcast.zarr.tmp-") and f"-{child.pid}-" in left[0], left
        # a live writer's temporary is not touched by another writer of the same store
        assert mio.stale_temporaries(out) == []
    finally:
        child.send_signal(signal.SIGKILL)
        child.wait(timeout=60)
    assert [p.name for p in out.parent.iterdir()] == left, "SIGKILL skips every clean-up"
    assert mio.stale_temporaries(out) == [out.parent / left[0]]
    mio.write_zarr(xr.Dataset({"a": ("x", np.arange(3.0))}), out)
    assert [p.name for p in out.parent.iterdir()] == ["hindcast.zarr"], "the stale temporary was removed"
    assert mio.open_zarr(out)["a"].size == 3
    assert not os.path.exists(out.parent / left[0])


def test_issue20_stale_temporaries_of_other_stores_and_live_writers_are_kept(tmp_path):
    host = mio._host()
    folder = tmp_path / "results"
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    names = {
        f".a.zarr.tmp-{host}-{dead.pid}-0123abcd": "stale",  # this store, dead writer
        ".a.zarr.tmp-89abcdef": "stale",  # this store, the old naming (no writer recorded)
        f".a.zarr.tmp-{host}-{os.getppid()}-00ff00ff": "keep",  # this store, a live writer
        f".a.zarr.tmp-otherhost-{dead.pid}-11111111": "keep",  # another host: cannot be checked
        f".b.zarr.tmp-{host}-{dead.pid}-22222222": "keep",  # another store (a concurrent writer)
        f".a.zarr2.tmp-{host}-{dead.pid}-33333333": "keep",
    }
    for n in names:
        (folder / n).mkdir(parents=True)
    mio.write_zarr(xr.Dataset({"a": ("x", np.arange(3.0))}), folder / "a.zarr")
    kept = sorted(p.name for p in folder.iterdir())
    assert kept == sorted(["a.zarr"] + [n for n, v in names.items() if v == "keep"]), kept
