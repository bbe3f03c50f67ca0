"""Compare the outputs of two runs of the workflow, bit for bit.

    python .ci/compare_runs.py REFERENCE OTHER

Every file under REFERENCE/results must exist under OTHER/results, and:
- every Zarr store: the same variables and coordinates, each with the same dtype, shape, bytes
  (NaNs included) and attributes, and the same root attributes;
- every other data file (CSV, YAML, TSV, NetCDF, rst): the same bytes;
- every PNG figure: the same decoded pixels (the PNG metadata, e.g. the Matplotlib version
  string, is not compared).
Exits 1 listing every difference; prints what it compared.
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np
import zarr


def _same_array(a: np.ndarray, b: np.ndarray) -> bool:
    if a.dtype != b.dtype or a.shape != b.shape:
        return False
    if a.dtype.kind == "O":
        return a.tolist() == b.tolist()
    return np.ascontiguousarray(a).tobytes() == np.ascontiguousarray(b).tobytes()


def _attrs(node) -> dict:
    return dict(node.attrs)


def compare_zarr(ref: Path, other: Path) -> tuple[list[str], int]:
    """Differences between two Zarr stores (raw arrays and attributes, via zarr itself)."""
    diffs, n = [], 0
    ga, gb = zarr.open_group(str(ref), mode="r"), zarr.open_group(str(other), mode="r")
    if _attrs(ga) != _attrs(gb):
        diffs.append(f"{ref.name}: root attributes differ")
    na = {k: v for k, v in ga.members(max_depth=None) if isinstance(v, zarr.Array)}
    nb = {k: v for k, v in gb.members(max_depth=None) if isinstance(v, zarr.Array)}
    if sorted(na) != sorted(nb):
        diffs.append(f"{ref.name}: variables {sorted(na)} vs {sorted(nb)}")
    for name in sorted(set(na) & set(nb)):
        n += 1
        a, b = na[name][...], nb[name][...]
        if not _same_array(np.asarray(a), np.asarray(b)):
            diffs.append(f"{ref.name}/{name}: values differ")
        if _attrs(na[name]) != _attrs(nb[name]):
            diffs.append(f"{ref.name}/{name}: attributes differ")
    return diffs, n


def compare_png(ref: Path, other: Path) -> list[str]:
    import matplotlib.image as mpimg

    a, b = mpimg.imread(ref), mpimg.imread(other)
    return [] if _same_array(a, b) else [f"{ref}: pixels differ"]


def main(ref_root: str, other_root: str) -> int:
    warnings.filterwarnings("ignore", message=".*not recognized as a component of a Zarr")  # .snakemake_timestamp
    ref, other = Path(ref_root) / "results", Path(other_root) / "results"
    diffs: list[str] = []
    counts = {"zarr stores": 0, "zarr arrays": 0, "files (bytes)": 0, "figures (pixels)": 0}
    stores = sorted(p for p in ref.rglob("*.zarr") if p.is_dir() and ".partial" not in p.parts)
    for s in stores:
        t = other / s.relative_to(ref)
        if not t.is_dir():
            diffs.append(f"missing store {t}")
            continue
        d, n = compare_zarr(s, t)
        diffs += d
        counts["zarr stores"] += 1
        counts["zarr arrays"] += n
    for f in sorted(ref.rglob("*")):
        if not f.is_file() or any(p.suffix == ".zarr" for p in f.parents):
            continue
        t = other / f.relative_to(ref)
        if not t.is_file():
            diffs.append(f"missing file {t}")
        elif f.suffix == ".png":
            diffs += compare_png(f, t)
            counts["figures (pixels)"] += 1
        else:
            counts["files (bytes)"] += 1
            if f.read_bytes() != t.read_bytes():
                diffs.append(f"{f.relative_to(ref)}: bytes differ")
    print(f"compare {other_root} against {ref_root}: " + ", ".join(f"{v} {k}" for k, v in counts.items()))
    for d in diffs:
        print("  DIFFERENT:", d)
    if not stores:
        diffs.append("no stores")
        print("  no Zarr store under", ref)
    return 1 if diffs else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
