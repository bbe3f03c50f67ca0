"""The only module of moorlife that touches the disk.

Stores are Zarr (format 3, ``consolidated=False`` on both write and read, so zarr 3 emits
no warning). A store is *complete* only when its root attribute ``moorlife_complete`` is
true; :func:`write_zarr` writes into a temporary sibling and renames it into place, so a
killed run never leaves a half-written store under the declared name.
"""

from __future__ import annotations

import errno
import logging
import os
import re
import shutil
import socket
import uuid
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import pandas as pd
import xarray as xr
import yaml

from moorlife.io.logs import log_to

__all__ = [
    "log_to",
    "COMPLETE_ATTR",
    "IncompleteStoreError",
    "write_zarr",
    "open_zarr",
    "read_yaml",
    "read_study_config",
    "read_mooring_systems",
    "promote",
    "partial_path",
    "stale_temporaries",
    "save_figure",
    "storable",
    "write_csv",
    "read_csv_table",
    "write_yaml",
]

#: Root attribute set last on every store this package writes.
COMPLETE_ATTR = "moorlife_complete"
ZARR_KW: dict[str, Any] = {"consolidated": False}
_log = logging.getLogger("moorlife.io")
#: ``.<store>.tmp-<host>-<pid>-<hex>``: the writer's host and process, so that a later write
#: can tell a temporary left by a killed writer from one being written right now.
_TMP = re.compile(r"^\.(?P<store>.+)\.tmp-(?:(?P<host>[A-Za-z0-9_.-]+?)-(?P<pid>\d+)-)?(?P<hex>[0-9a-f]{8})$")


class IncompleteStoreError(RuntimeError):
    """A Zarr store exists but was not completed by moorlife; it must not be trusted."""


def partial_path(output: str | os.PathLike[str]) -> Path:
    """Where the partial (in-progress) version of a declared output lives.

    ``results/MS1/simulations.zarr`` -> ``results/.partial/MS1/simulations.zarr``: outside
    the declared output, so Snakemake never mistakes it for a finished one, and beside it
    on the same filesystem, so :func:`promote` is an atomic rename.
    """
    out = Path(output)
    parts = out.parts
    if "results" in parts:
        i = parts.index("results")
        return Path(*parts[: i + 1], ".partial", *parts[i + 1 :])
    return out.parent / ".partial" / out.name


def promote(partial: str | os.PathLike[str], output: str | os.PathLike[str]) -> Path:
    """Rename a finished partial store into its declared place (atomic on one filesystem).

    When the two sit on different filesystems (``EXDEV``: e.g. ``results/MS1`` is a link to
    another disk), the store is copied into a temporary sibling of ``output`` first and that
    is renamed, so the declared output still appears whole or not at all.
    """
    src, dst = Path(partial), Path(output)
    dst.parent.mkdir(parents=True, exist_ok=True)
    if dst.exists():
        shutil.rmtree(dst) if dst.is_dir() else dst.unlink()
    try:
        os.replace(src, dst)
    except OSError as exc:
        if exc.errno != errno.EXDEV:
            raise
        tmp = dst.parent / f".{dst.name}.tmp-{uuid.uuid4().hex[:8]}"
        try:
            shutil.copytree(src, tmp) if src.is_dir() else shutil.copy2(src, tmp)
            os.replace(tmp, dst)
        finally:
            if tmp.exists():
                shutil.rmtree(tmp, ignore_errors=True) if tmp.is_dir() else tmp.unlink()
        shutil.rmtree(src) if src.is_dir() else src.unlink()
    return dst


def storable(ds: xr.Dataset) -> xr.Dataset:
    """Fixed-width unicode variables become variable-length strings.

    Zarr 3 has no specification for numpy's fixed-width ``<U`` dtype (it warns and other
    readers may fail); variable-length UTF-8 strings are specified.
    """
    fix = {k: v.astype(object) for k, v in ds.variables.items() if v.dtype.kind == "U"}
    return ds.assign_coords({k: v for k, v in fix.items() if k in ds.coords}).assign(
        {k: v for k, v in fix.items() if k not in ds.coords}
    )


def _mark_complete(path: Path) -> None:
    import zarr

    group = zarr.open_group(str(path), mode="r+")
    group.attrs[COMPLETE_ATTR] = True


def _host() -> str:
    return re.sub(r"[^A-Za-z0-9_.]", "_", socket.gethostname()) or "host"


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's live process
        return True
    return True


def tmp_path(dst: Path) -> Path:
    """The temporary sibling of ``dst`` for this process: ``.<name>.tmp-<host>-<pid>-<hex>``."""
    return dst.parent / f".{dst.name}.tmp-{_host()}-{os.getpid()}-{uuid.uuid4().hex[:8]}"


def stale_temporaries(dst: str | os.PathLike[str]) -> list[Path]:
    """Temporaries of the store ``dst`` left by writers that are gone (e.g. after a SIGKILL).

    Only temporaries of this very store name are considered; one is stale when its writer ran
    on this host and its process no longer exists, or when it carries no writer at all (the
    naming of moorlife before the writer was recorded). A temporary whose writer is alive, or
    ran on another host (shared filesystem: its liveness cannot be checked here), is kept.
    """
    d = Path(dst)
    out: list[Path] = []
    if not d.parent.is_dir():
        return out
    host = _host()
    for p in d.parent.iterdir():
        m = _TMP.match(p.name)
        if m is None or m["store"] != d.name:
            continue
        if m["pid"] is None or (m["host"] == host and int(m["pid"]) != os.getpid() and not _pid_alive(int(m["pid"]))):
            out.append(p)
    return sorted(out)


def _remove_stale(dst: Path) -> None:
    for p in stale_temporaries(dst):
        _log.warning("%s: removing the stale temporary %s left by a killed writer", dst, p.name)
        shutil.rmtree(p, ignore_errors=True) if p.is_dir() else p.unlink(missing_ok=True)


def write_zarr(
    ds: xr.Dataset,
    path: str | os.PathLike[str],
    *,
    encoding: Mapping[str, Any] | None = None,
) -> Path:
    """Write a Dataset as a complete Zarr store, atomically.

    The store is written to a temporary sibling ``.<name>.tmp-<host>-<pid>-<hex>``, flagged
    complete, then renamed to ``path``. Temporaries of the same store left by a writer that no
    longer runs (a SIGKILL skips every clean-up) are removed first (:func:`stale_temporaries`).

    Parameters
    ----------
    ds : xarray.Dataset
        The data; every variable should carry ``units``.
    path : path-like
        The declared output.
    encoding : mapping, optional
        Per-variable Zarr encoding (chunks, compressors).

    Raises
    ------
    OSError
        Naming the store, when the disk refuses the write (e.g. ENOSPC); nothing is left.
    """
    dst = Path(path)
    dst.parent.mkdir(parents=True, exist_ok=True)
    _remove_stale(dst)
    tmp = tmp_path(dst)
    try:
        storable(ds).to_zarr(tmp, mode="w", encoding=dict(encoding or {}), **ZARR_KW)
        _mark_complete(tmp)
        promote(tmp, dst)
    except OSError as exc:
        reason = os.strerror(exc.errno) if exc.errno else str(exc)
        hint = ": free some space, or point results/ elsewhere" if exc.errno in (errno.ENOSPC, errno.EDQUOT) else ""
        raise OSError(exc.errno, f"{dst}: writing the Zarr store failed ({reason}){hint}") from exc
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)
    return dst


def open_zarr(path: str | os.PathLike[str], *, load: bool = True) -> xr.Dataset:
    """Open a store written by moorlife, refusing one that is incomplete or corrupted.

    Raises
    ------
    FileNotFoundError
        If there is no store at ``path``.
    IncompleteStoreError
        If the store lacks the completion flag or cannot be read.
    """
    p = Path(path)
    if not p.exists():
        raise FileNotFoundError(f"{p}: no such Zarr store")
    try:
        with warnings.catch_warnings():
            # Snakemake drops a `.snakemake_timestamp` file into directory() outputs
            warnings.filterwarnings("ignore", message=r"Object at \.snakemake_timestamp", category=UserWarning)
            ds = xr.open_zarr(p, **ZARR_KW)
    except Exception as exc:  # corrupted metadata, missing arrays, ...
        raise IncompleteStoreError(f"{p}: not a readable Zarr store ({exc}); delete it and rerun") from exc
    if not ds.attrs.get(COMPLETE_ATTR, False):
        raise IncompleteStoreError(
            f"{p}: store is incomplete (attribute {COMPLETE_ATTR!r} missing): it was not finished "
            "by moorlife; delete it and rerun"
        )
    if load:
        try:
            ds = ds.load()
        except Exception as exc:
            raise IncompleteStoreError(f"{p}: store is corrupted ({exc}); delete it and rerun") from exc
    return ds


def save_figure(fig: Any, path: str | os.PathLike[str], *, dpi: int = 150) -> Path:
    """Save a matplotlib figure as PNG (atomically) and close it."""
    import matplotlib.pyplot as plt

    dst = Path(path)
    dst.parent.mkdir(parents=True, exist_ok=True)
    tmp = dst.parent / f".{dst.stem}.tmp-{uuid.uuid4().hex[:8]}{dst.suffix}"
    try:
        fig.savefig(tmp, dpi=dpi, bbox_inches="tight")
        os.replace(tmp, dst)
    finally:
        plt.close(fig)
        tmp.unlink(missing_ok=True)
    return dst


def read_yaml(path: str | os.PathLike[str]) -> dict[str, Any]:
    """Read a YAML mapping (safe loader only: no Python objects are constructed)."""
    p = Path(path)
    with p.open("r", encoding="utf-8") as fh:
        data = yaml.safe_load(fh)
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise ValueError(f"{p}: expected a YAML mapping at the top level, got {type(data).__name__}")
    return data


def write_yaml(data: Mapping[str, Any], path: str | os.PathLike[str]) -> Path:
    """Write a mapping as YAML (safe dumper, keys in the given order)."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    with p.open("w", encoding="utf-8") as fh:
        yaml.safe_dump(dict(data), fh, sort_keys=False)
    return p


def write_csv(df: pd.DataFrame, path: str | os.PathLike[str]) -> Path:
    """A results table as CSV (no index, 6 significant digits), creating the folder."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    df.to_csv(p, index=False, float_format="%.6g")
    return p


def read_csv_table(path: str | os.PathLike[str]) -> pd.DataFrame:
    """A results table written by :func:`write_csv`."""
    return pd.read_csv(Path(path))


def read_study_config(
    config: str | os.PathLike[str],
    overlays: tuple[str | os.PathLike[str], ...] = (),
    schema: str | os.PathLike[str] = "workflow/schemas/config.schema.yaml",
) -> dict[str, Any]:
    """Read ``config.yaml`` plus overlays, validate against the schema and fill defaults."""
    from moorlife.config import deep_merge, validate_config

    merged = read_yaml(config)
    for ov in overlays:
        merged = deep_merge(merged, read_yaml(ov))
    names = ", ".join(str(p) for p in (config, *overlays))
    return validate_config(merged, read_yaml(schema), source=names)


def _header_fields(p: Path) -> list[str] | None:
    """The tab-separated fields of the first line that is neither blank nor a ``#`` comment."""
    with p.open("r", encoding="utf-8-sig", errors="replace") as fh:
        for line in fh:
            if line.strip() and not line.lstrip().startswith("#"):
                return [f.strip() for f in line.rstrip("\r\n").split("\t")]
    return None


def read_mooring_systems(path: str | os.PathLike[str]) -> pd.DataFrame:
    """Read the mooring-system table (one row per system, indexed by ``mooring_system``).

    Raises
    ------
    ValueError
        Naming the file and, never quoting the file's content beyond the expected column names:
        an empty file, another delimiter than tab, duplicated or missing columns, a ragged row,
        or a bad value (:func:`moorlife.tables.validate_mooring_systems`).
    """
    from moorlife.tables import MOORING_COLUMNS, validate_mooring_systems

    p = Path(path)
    if not p.is_file():
        raise ValueError(f"{p}: no such mooring-system table (config key 'mooring_systems')")
    expected = list(MOORING_COLUMNS)
    try:
        fields = _header_fields(p)
    except OSError as exc:
        raise ValueError(f"{p}: the mooring-system table cannot be read ({exc.strerror})") from exc
    if not fields:
        raise ValueError(f"{p}: the mooring-system table is empty")
    if len(fields) == 1:
        for name, sep in (("comma", ","), ("semicolon", ";"), ("space", " ")):
            if sum(c in fields[0].split(sep) for c in expected) >= 2:
                raise ValueError(
                    f"{p}: the mooring-system table is {name}-separated; the columns must be separated by tabs "
                    f"(expected {expected})"
                )
    dup = sorted({f for f in fields if fields.count(f) > 1})
    if dup:
        shown = [f for f in dup if f in MOORING_COLUMNS]
        raise ValueError(
            f"{p}: duplicated column name(s) {shown or f'({len(dup)} name(s))'}; each of {expected} must appear once"
        )
    try:
        df = pd.read_csv(p, sep="\t", comment="#", dtype={"mooring_system": str, "chain": str}, encoding="utf-8-sig")
    except pd.errors.EmptyDataError as exc:
        raise ValueError(f"{p}: the mooring-system table is empty") from exc
    except (pd.errors.ParserError, UnicodeDecodeError) as exc:
        line = re.search(r"line (\d+)", str(exc))
        where = f" (line {line.group(1)}: another number of fields than the header)" if line else ""
        raise ValueError(f"{p}: not a tab-separated table with the columns {expected}{where}") from None
    return validate_mooring_systems(df, source=str(p))
