"""The only module of moorlife that touches the disk.

Stores are Zarr (format 3, ``consolidated=False`` on both write and read, so zarr 3 emits
no warning). A store is *complete* only when its root attribute ``moorlife_complete`` is
true; :func:`write_zarr` writes into a temporary sibling and renames it into place, so a
killed run never leaves a half-written store under the declared name.
"""

from __future__ import annotations

import errno
import os
import shutil
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
    "save_figure",
    "storable",
    "write_csv",
    "read_csv_table",
    "write_yaml",
]

#: Root attribute set last on every store this package writes.
COMPLETE_ATTR = "moorlife_complete"
ZARR_KW: dict[str, Any] = {"consolidated": False}


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


def write_zarr(
    ds: xr.Dataset,
    path: str | os.PathLike[str],
    *,
    encoding: Mapping[str, Any] | None = None,
) -> Path:
    """Write a Dataset as a complete Zarr store, atomically.

    The store is written to a temporary sibling, flagged complete, then renamed to ``path``.

    Parameters
    ----------
    ds : xarray.Dataset
        The data; every variable should carry ``units``.
    path : path-like
        The declared output.
    encoding : mapping, optional
        Per-variable Zarr encoding (chunks, compressors).
    """
    dst = Path(path)
    dst.parent.mkdir(parents=True, exist_ok=True)
    tmp = dst.parent / f".{dst.name}.tmp-{uuid.uuid4().hex[:8]}"
    try:
        storable(ds).to_zarr(tmp, mode="w", encoding=dict(encoding or {}), **ZARR_KW)
        _mark_complete(tmp)
        promote(tmp, dst)
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


def read_mooring_systems(path: str | os.PathLike[str]) -> pd.DataFrame:
    """Read the mooring-system table (one row per system, indexed by ``mooring_system``)."""
    from moorlife.tables import validate_mooring_systems

    p = Path(path)
    try:
        df = pd.read_csv(p, sep="\t", comment="#", dtype={"mooring_system": str, "chain": str})
    except pd.errors.EmptyDataError as exc:
        raise ValueError(f"{p}: the mooring-system table is empty") from exc
    return validate_mooring_systems(df, source=str(p))
