"""Bad input: the exit code, a clear message naming the file or key and the value, no output.

Every class of bad hindcast (issue 3), bad config keys, tables and platform files (issue 20), a
corrupted or partial upstream store, and real Snakemake runs. The loaders' messages are tested
in detail in tests/test_hindcast_io.py; here the point is what a user of the workflow sees and
what is left in results/.

The exit code: a case that fails at parse time runs the pre-flight command
(``python -m moorlife.stages.check``, :func:`moorlife.stages.check.check_study`, which
``workflow/rules/common.smk`` calls when Snakemake parses the workflow) as a real child process
and asserts its exit status, its stderr and that nothing was written. A bad hindcast file fails
in the ``metocean`` rule: the command's ``--inputs`` loads it with the rule's own loader (exit
status, stderr), and the rule's adapter runs in-process on the same file (no declared output,
the rule log holds the message). A few cases run ``snakemake`` itself.
"""

from __future__ import annotations

import importlib.util
import multiprocessing
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
import yaml
from snakemake.iocontainers import Namedlist
from test_hindcast_io import NORA3_HEADER, nora3_frame, write_csv

from moorlife import io as mio
from moorlife.config import deep_merge
from moorlife.io import read_study_config, read_yaml
from moorlife.metocean import HindcastError
from moorlife.parallel import SCHEDULER_ENV
from moorlife.stages import check as preflight

ROOT = Path(__file__).resolve().parents[1]
SCRIPTS = ROOT / "workflow" / "scripts"


def adapter(name: str):
    spec = importlib.util.spec_from_file_location(f"rule_{name}", SCRIPTS / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.main


def hindcast_params(path: Path) -> dict:
    cfg = read_study_config(ROOT / "config/config.yaml", schema=ROOT / "workflow/schemas/config.schema.yaml")
    return {**cfg["hindcast"], **HINDCAST_FILE, "path": str(path)}


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


# ----------------------------------------------------------------- the pre-flight command
def study_dir(work: Path) -> Path:
    """A working directory holding the study's ``config/`` and ``tests/data/`` (what the command reads)."""
    shutil.copytree(ROOT / "config", work / "config")
    shutil.copytree(ROOT / "tests" / "data", work / "tests" / "data")
    return work


def _files(work: Path) -> list[tuple[str, int, int]]:
    return sorted((str(p.relative_to(work)), p.stat().st_mtime_ns, p.stat().st_size) for p in work.rglob("*"))


def _check_child(work: str, argv: list[str], env: dict[str, str], out: str, err: str) -> None:
    os.chdir(work)
    os.environ.pop(SCHEDULER_ENV, None)
    os.environ.update(env)
    for fd, path in ((1, out), (2, err)):
        os.dup2(os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600), fd)
    sys.stdout, sys.stderr = open(1, "w", closefd=False), open(2, "w", closefd=False)
    sys.exit(preflight.main(argv))


def run_check(work: Path, *argv: str, env: dict[str, str] | None = None) -> SimpleNamespace:
    """``python -m moorlife.stages.check ARGV`` in ``work``, as a child process: exit code and output.

    The child is forked from this process, where moorlife is imported already (a fork costs
    milliseconds, a fresh interpreter with these imports more than a second), and exits with the
    status of the command's ``main(argv)``, as ``python -m`` does
    (:func:`test_check_command_runs_as_python_m` runs that too). Also asserts that the command
    wrote nothing: every file of ``work`` is as it was, and there is no ``results/``.
    """
    before = _files(work)
    out, err = work.parent / f".{work.name}.stdout", work.parent / f".{work.name}.stderr"
    child = multiprocessing.get_context("fork").Process(
        target=_check_child, args=(str(work), list(argv), dict(env or {}), str(out), str(err))
    )
    child.start()
    child.join(timeout=120)
    if child.is_alive():
        child.kill()
        child.join()
        pytest.fail(f"the check {argv} did not finish in 120 s")
    res = SimpleNamespace(returncode=child.exitcode, stdout=out.read_text(), stderr=err.read_text())
    assert _files(work) == before and not (work / "results").exists(), "the check must write nothing"
    return res


def assert_refused(res: SimpleNamespace, *texts: str, pattern: str | None = None) -> str:
    """Exit status 1, the message on stderr holding every text and matching ``pattern``; the message."""
    assert res.returncode == 1, f"exit code {res.returncode}, stderr: {res.stderr[-3000:]}"
    assert res.stderr.startswith("moorlife check: refused: "), res.stderr[-3000:]
    for text in texts:
        assert text in res.stderr, f"{text!r} not in {res.stderr[-3000:]}"
    if pattern is not None:
        assert re.search(pattern, res.stderr, flags=re.S), res.stderr[-3000:]
    return res.stderr


HINDCAST_FILE = {"source": "file", "start": "2000-01-01T00:00", "end": "2000-01-02T23:00"}


def check_hindcast(tmp_path: Path, csv: Path, patch: dict | None = None) -> SimpleNamespace:
    """The command with ``--inputs`` on the study whose hindcast is ``csv`` (the params of run_metocean)."""
    work = study_dir(tmp_path / "check")
    hindcast = deep_merge({**HINDCAST_FILE, "path": str(csv)}, patch or {})
    # 48 hours hold at most 48 states (checked at parse time since issue 20)
    overlay = {"hindcast": hindcast, "selection": {"n_train": 10, "n_validate": 4}}
    (work / "hc.yaml").write_text(yaml.safe_dump(overlay))
    return run_check(work, "--configfile", "hc.yaml", "--inputs")


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
    assert_refused(check_hindcast(tmp_path, csv), msg)


@pytest.mark.parametrize("case", ["empty", "header_only"])
def test_empty_hindcast_files(tmp_path, case):
    csv = tmp_path / f"{case}.csv"
    csv.write_text("" if case == "empty" else NORA3_HEADER + ",".join(nora3_frame().columns) + "\n")
    out, smk = run_metocean(tmp_path, csv)
    pattern = re.escape(str(csv)) + r".*(empty|no data|no rows)"
    with pytest.raises(ValueError, match=pattern) as err:
        adapter("metocean")(smk)
    assert not out.exists()
    assert_refused(check_hindcast(tmp_path, csv), str(err.value))


def test_good_file_through_the_same_adapter(tmp_path):
    """The adapter itself works: the same path with a clean file writes a complete store."""
    csv = write_csv(tmp_path / "good.csv", nora3_frame())
    out, smk = run_metocean(tmp_path, csv)
    adapter("metocean")(smk)
    ds = mio.open_zarr(out)
    assert ds.sizes["time"] == 48 and ds.attrs["hub_height"] == 90.0
    res = check_hindcast(tmp_path, csv)
    assert res.returncode == 0 and res.stderr == "", res.stderr[-3000:]
    assert res.stdout.endswith(": ok, 6 mooring systems (MS1, MS2, MS3, MS4, MS5, MS6), hindcast file of 48 hours\n")


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
#  * the exit code: 1 from the pre-flight command run as a child process (run_check), which
#    runs the Snakefile's parse-time check (and, with --inputs, the metocean rule's loader); the
#    `snakemake` cases check that Snakemake itself exits 1 with the same message;
#  * that the message names the file or the config key and the offending value;
#  * that no declared output (and no temporary store) is left: the command writes nothing
#    (run_check), and the rule's adapter, run on the same bad file, leaves nothing either.
# ============================================================================================


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
    assert_refused(check_hindcast(tmp_path, csv), msg)


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
    res = check_hindcast(tmp_path, csv)
    assert_refused(res, msg)
    for secret in ("root", "19000", "daemon", "notes", "HDF"):
        assert secret not in res.stderr.replace(str(csv), ""), f"the command echoes the file's content: {res.stderr}"


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
    # the command refuses a bad date at parse time already (naming the overlay), the rest on loading
    res = check_hindcast(tmp_path, csv, patch)
    assert_refused(res, "hc.yaml: " if "config key" in msg else msg, pattern=pattern)


# ----------------------------------------------------------------- config, at parse time
# (a patch over config/quick.yaml, written as the overlay bad.yaml; the pattern of the message)
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
    # the schema itself: a value out of range, a misspelt key
    "n_train_negative": ({"selection": {"n_train": -3}}, r"config key 'selection\.n_train' = -3 is invalid"),
    "unknown_key": ({"simulation": {"durration": 10}}, r"unknown config key 'simulation\.durration'"),
    # item 8: `lifecycle.sensitivity.mooring_system: MS9` used to drop the sensitivities silently
    "sensitivity_system_not_in_table": (
        {"lifecycle": {"sensitivity": {"mooring_system": "MS9"}}},
        r"config key 'lifecycle\.sensitivity\.mooring_system' = 'MS9' "
        r"is not a mooring system of the table config/mooring_systems\.tsv \(MS1, ",
    ),
    # a corrosion rate that eats a link within the design life failed only at the end of lifecycle
    "corrosion_consumes_the_link": (
        {"fatigue": {"corrosion": {"rate": 5.0}}},
        r"config keys 'fatigue\.corrosion\.rate' = 5\.0 mm/year over "
        r"'fatigue\.design_life' = 25\.0 years remove 125 mm, the whole \d+ mm link of MS1",
    ),
}

QUICK_SOURCE = "config/config.yaml, config/quick.yaml, bad.yaml: "


@pytest.mark.parametrize("case", sorted(BAD_CONFIG))
def test_issue20_bad_config_refused_before_any_job(tmp_path, case):
    """The parse-time check as a command: exit code 1, the files, the key and the value; nothing written."""
    patch, pattern = BAD_CONFIG[case]
    work = study_dir(tmp_path)
    (work / "bad.yaml").write_text(yaml.safe_dump(patch))
    assert_refused(run_check(work, "--configfile", "config/quick.yaml", "bad.yaml"), QUICK_SOURCE, pattern=pattern)


def test_issue20_default_and_overlay_configs_pass_the_checks(tmp_path):
    """The checks refuse only what is wrong: config.yaml, quick.yaml and tiny.yaml pass (exit code 0)."""
    work = study_dir(tmp_path)
    for overlays, systems in (
        ((), "6 mooring systems (MS1, MS2, MS3, MS4, MS5, MS6)"),
        (("config/quick.yaml",), "6 mooring systems"),
        (("config/quick.yaml", "tests/data/tiny.yaml"), "2 mooring systems (MS1, MS3)"),
    ):
        res = run_check(work, *(["--configfile", *overlays] if overlays else []), "--truth")
        assert res.returncode == 0 and res.stderr == "", res.stderr[-3000:]
        assert f": ok, {systems}" in res.stdout and "truth hours" in res.stdout, res.stdout


def test_check_command_runs_as_python_m(tmp_path):
    """The real command line, in a fresh interpreter: `python -m moorlife.stages.check`."""
    work = study_dir(tmp_path)
    (work / "bad.yaml").write_text("simulation:\n  dt: 1.0\n")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in sys.path if p)}
    env.pop(SCHEDULER_ENV, None)
    cmd = [sys.executable, "-m", "moorlife.stages.check", "--configfile", "config/quick.yaml", "bad.yaml"]
    res = subprocess.run(cmd, cwd=work, capture_output=True, text=True, timeout=300, env=env)
    assert_refused(res, QUICK_SOURCE, pattern=r"config key 'simulation\.dt' = 1\.0 s cannot resolve")
    assert not (work / "results").exists()
    usage = subprocess.run([*cmd[:3], "--no-such-flag"], cwd=work, capture_output=True, text=True, env=env)
    assert usage.returncode == 2 and "unrecognized arguments: --no-such-flag" in usage.stderr, usage.stderr


TRUTH_CASES = {
    # the schema refuses this one for every target
    "stride0": ("truth:\n  stride: 0\n", r"config key 'truth\.stride' = 0 is invalid"),
    # the others need the hindcast period: checked when a truth target is in the DAG
    "outside": (
        'truth:\n  window: {start: "1984-12-01T00:00", end: "1985-01-02T00:00"}\n',
        r"config key 'truth\.window\.start' = '1984-12-01T00:00' is outside the hindcast",
    ),
    "end_before_start": (
        'truth:\n  window: {start: "1985-03-02T00:00", end: "1985-03-01T00:00"}\n',
        r"'truth\.window\.end' = '1985-03-01T00:00' is before .* empty",
    ),
    "too_many_second_seed": (
        'truth:\n  window: {start: "1985-03-01T00:00", end: "1985-03-01T09:00"}\n  n_second_seed: 11\n',
        r"'truth\.n_second_seed' = 11 is larger than the 10 hours",
    ),
}


@pytest.mark.parametrize("case", sorted(TRUTH_CASES))
def test_issue20_bad_truth_config(tmp_path, case):
    """``--truth`` runs the check a truth target runs when the DAG is built; without it (the
    default targets, which hold no truth rule) the same study passes, as in Snakemake."""
    text, pattern = TRUTH_CASES[case]
    work = study_dir(tmp_path)
    (work / "bad.yaml").write_text(text)
    argv = ["--configfile", "config/quick.yaml", "tests/data/tiny.yaml", "bad.yaml"]
    assert_refused(run_check(work, *argv, "--truth"), "tiny.yaml, bad.yaml: ", pattern=pattern)
    assert run_check(work, *argv).returncode == (1 if case == "stride0" else 0)


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
    work = study_dir(tmp_path)
    (work / f"{kind}.tsv").write_text(_tsv_edit(kind))
    (work / "bad.yaml").write_text(f"mooring_systems: {kind}.tsv\n")
    msg = assert_refused(run_check(work, "--configfile", "bad.yaml"), f"refused: {kind}.tsv: ", pattern=pattern)
    for secret in ("root", "19000", "bin:"):
        assert secret not in msg.replace(f"{kind}.tsv", ""), f"the message echoes the file's content: {msg}"


def test_issue20_mooring_table_missing(tmp_path):
    work = study_dir(tmp_path)
    (work / "bad.yaml").write_text("mooring_systems: nope.tsv\n")
    expected = "refused: nope.tsv: no such mooring-system table (config key 'mooring_systems')"
    assert_refused(run_check(work, "--configfile", "bad.yaml"), expected)


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
    work = study_dir(tmp_path)
    cfg = read_yaml(work / "config" / "platform.yaml")
    node = cfg
    for k in path[:-1]:
        node = node[k]
    node[path[-1]] = value
    (work / "platform2.yaml").write_text(yaml.safe_dump(cfg))
    (work / "bad.yaml").write_text("platform: platform2.yaml\n")
    assert_refused(run_check(work, "--configfile", "bad.yaml"), "refused: platform2.yaml: ", pattern=pattern)


# ----------------------------------------------------------------- the environment
@pytest.mark.parametrize("address", ["foo:bar", "tcp://127.0.0.1:99999", "http://example.org:8786"])
def test_issue20_bad_scheduler_address(tmp_path, monkeypatch, address):
    """`DASK_SCHEDULER_ADDRESS=foo:bar` raised a bare int() error; now it names the variable."""
    from moorlife import parallel

    expected = f"environment variable DASK_SCHEDULER_ADDRESS = {address!r} is not a Dask scheduler address"
    # at parse time (the check of common.smk), before any job
    assert_refused(run_check(study_dir(tmp_path), env={SCHEDULER_ENV: address}), expected)
    # and in the simulate stages, which may run under another environment than the parse
    monkeypatch.setenv(SCHEDULER_ENV, address)
    with pytest.raises(ValueError) as err, parallel.dask_client(1):
        pass
    assert expected in str(err.value), str(err.value)


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
    # a config key (the schema's cross-key checks) and a file (platform.yaml, read at parse time)
    "dt_1": ("simulation:\n  dt: 1.0\n", r"bad\.yaml.*config key 'simulation\.dt' = 1\.0 s cannot resolve"),
    "platform_cm": (
        "platform: platform2.yaml\n",
        r"platform2\.yaml: platform\.cm = \[0\.0, 0\.0\] must be a list of 3",
    ),
}


@pytest.mark.workflow
@pytest.mark.parametrize("case", sorted(E2E))
def test_issue20_snakemake_refuses_at_parse_time(tmp_path, case):
    """Snakemake itself: exit code 1 before any job, with the message of the pre-flight command
    (the Snakefile calls the same check; the other parse-time cases run the command only)."""
    _copy_workflow(tmp_path)
    plat = (tmp_path / "config" / "platform.yaml").read_text()
    (tmp_path / "platform2.yaml").write_text(plat.replace("cm: [0.0, 0.0, -13.46]", "cm: [0.0, 0.0]"))
    text, pattern = E2E[case]
    (tmp_path / "bad.yaml").write_text(text)
    check = assert_refused(run_check(tmp_path, "--configfile", "config/quick.yaml", "bad.yaml"), pattern=pattern)
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
    # the same message, whatever the order in which each names the config files
    same = check.removeprefix("moorlife check: refused: ").removeprefix(QUICK_SOURCE).strip()
    assert same in res.stderr + res.stdout, (same, res.stderr[-3000:])
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
