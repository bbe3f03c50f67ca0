"""Choice of the sea states to simulate, and the conventional scatter matrix.

Two things live here (Barrera et al. 2019, section 3.2 and section 4.1):

* **Maximum dissimilarity** (MDA, Camus et al. 2011) over the 5-D sea-state points
  ``(W, beta, Hs, Tp, alpha)``: the training states are picked greedily so that each new
  state is the one farthest from its nearest already-selected state. A further, disjoint
  set of *validation* states is kept only to check the reconstruction.
* **The discrete matrix** the paper compares against: the hindcast binned by Hs, then W,
  then Tp; each non-empty bin is represented by the mean Hs, W, Tp of its hours, the most
  likely wave and wind directions, and its probability of occurrence.

The normalised distance
-----------------------
Every scalar variable is scaled by its range, ``(x - lo) / span`` with ``span = max - min``
over the hindcast (a constant column gets ``span = 1``). A direction (degrees, nautical) is
mapped to ``deg / 180`` in ``[0, 2)`` and two directions are compared on the circle: the
absolute difference is folded to at most 1 (180 deg), i.e.
``moorlife.conventions.circular_difference(a, b) / 180``. The distance between two states
is the Euclidean norm of these per-variable differences. The same distance is used by the
RBF reconstruction: :func:`scaling_from` gives ``(lo, span)``, :func:`normalise` embeds
points, :func:`pairwise_distance` and :func:`nearest_distance` measure them. The ranges
used by the selection are stored in the attributes of ``results/selection/cases.zarr``
(``norm_lo`` / ``norm_span``), so that later stages use exactly the same metric.

Kernels take numpy arrays and return numpy arrays; :func:`select_cases` and
:func:`discrete_states` are thin xarray adapters producing the stores of the output
contract (``results/selection/cases.zarr`` and ``results/selection/discrete.zarr``).
"""

from __future__ import annotations

import logging
import time as _time
import zlib
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
import numpy.typing as npt
import pandas as pd
import xarray as xr

from moorlife import names

__all__ = [
    "VALIDATION_RULES",
    "VALIDATION_STREAM_KEY",
    "DEFAULT_HS_EDGES",
    "DEFAULT_WIND_EDGES",
    "DEFAULT_TP_EDGES",
    "scaling_from",
    "normalise",
    "pairwise_distance",
    "nearest_distance",
    "mda",
    "mda_bruteforce",
    "select_validation",
    "modal_direction",
    "class_labels",
    "ScatterMatrix",
    "scatter_matrix",
    "hindcast_points",
    "select_cases",
    "discrete_states",
]

_log = logging.getLogger(__name__)

#: Rules for choosing the validation states (``config.yaml: selection.validation_rule``).
VALIDATION_RULES: tuple[str, ...] = ("random", "mda")

#: Lower class edges of the paper's scatter matrix (section 4.1); the last class is open.
DEFAULT_HS_EDGES: tuple[float, ...] = (0.0, 1.5, 3.0, 4.5)  # m
DEFAULT_WIND_EDGES: tuple[float, ...] = (0.0, 7.0, 14.0)  # m/s
DEFAULT_TP_EDGES: tuple[float, ...] = (0.0, 6.0, 9.0, 12.0)  # s

#: Normalised span of a direction: deg / 180, so the folded difference is at most 1.
_DIR_SPAN = 180.0
#: Label of the random stream of the "random" validation rule: ``SeedSequence([seed, key])``,
#: so it cannot coincide with another stage's stream drawn from the same global seed.
VALIDATION_STREAM_KEY = zlib.crc32(b"moorlife.selection.validate")
_BLOCK = 4096  # rows per block in the O(M*K) distance helpers (bounds memory)


# --------------------------------------------------------------------------- normalisation
def _check_points(points: npt.ArrayLike, is_direction: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Validate ``(N, D)`` points and a ``(D,)`` direction mask; return float64 and bool arrays."""
    pts = np.asarray(points, dtype=float)
    if pts.ndim != 2:
        raise ValueError(f"points must be a 2-D array (N states, D variables), got shape {pts.shape}")
    if pts.shape[0] == 0:
        raise ValueError("points is empty: no sea states to select from")
    mask = np.asarray(is_direction, dtype=bool).reshape(-1)
    if mask.shape[0] != pts.shape[1]:
        raise ValueError(
            f"is_direction has {mask.shape[0]} entries but points have {pts.shape[1]} columns"
        )
    bad = ~np.isfinite(pts)
    if bad.any():
        row, col = np.argwhere(bad)[0]
        raise ValueError(f"points column {col}, row {row}: value {float(pts[row, col])!r} is not finite")
    return pts, mask


def scaling_from(points: npt.ArrayLike, is_direction: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """The offsets and spans that normalise each variable.

    Parameters
    ----------
    points : array_like, shape (N, D)
        Sea states in physical units (directions in degrees).
    is_direction : array_like of bool, shape (D,)
        Which columns are directions.

    Returns
    -------
    lo, span : numpy.ndarray, shape (D,)
        Scalars: ``lo = min``, ``span = max - min`` (``1`` for a constant column, so that it
        normalises to 0 instead of dividing by zero). Directions: ``lo = 0``, ``span = 180``.
    """
    pts, mask = _check_points(points, is_direction)
    lo = pts.min(axis=0)
    span = pts.max(axis=0) - lo
    span[span == 0.0] = 1.0
    lo[mask] = 0.0
    span[mask] = _DIR_SPAN
    return lo, span


def normalise(
    points: npt.ArrayLike,
    is_direction: npt.ArrayLike,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
    *,
    dtype: npt.DTypeLike = np.float64,
) -> np.ndarray:
    """Embed sea states in the normalised space of the selection and RBF distance.

    Parameters
    ----------
    points : array_like, shape (N, D)
        Sea states in physical units (directions in degrees, any turn).
    is_direction : array_like of bool, shape (D,)
        Which columns are directions.
    lo, span : array_like, shape (D,), optional
        Offsets and spans of the scalar columns (ignored for directions), e.g. from
        :func:`scaling_from` on the whole hindcast. Default: from ``points`` itself.
    dtype : dtype
        Floating type of the result.

    Returns
    -------
    numpy.ndarray, shape (N, D)
        Scalars ``(x - lo) / span`` (in ``[0, 1]`` on the data that defined the range);
        directions ``(deg mod 360) / 180`` in ``[0, 2)``. Compare them with
        :func:`pairwise_distance`, which folds direction differences on the circle.
    """
    pts, mask = _check_points(points, is_direction)
    if lo is None or span is None:
        lo_d, span_d = scaling_from(pts, mask)
        lo = lo_d if lo is None else lo
        span = span_d if span is None else span
    lo_a = np.broadcast_to(np.asarray(lo, dtype=float), (pts.shape[1],))
    span_a = np.broadcast_to(np.asarray(span, dtype=float), (pts.shape[1],))
    if np.any(span_a[~mask] <= 0.0) or not np.all(np.isfinite(span_a[~mask])):
        raise ValueError(f"span must be finite and > 0 for every scalar column, got {span_a.tolist()}")
    out = np.empty(pts.shape, dtype=float)
    out[:, ~mask] = (pts[:, ~mask] - lo_a[~mask]) / span_a[~mask]
    out[:, mask] = np.mod(pts[:, mask], 360.0) / _DIR_SPAN
    # mod can return exactly 360.0 for tiny negative inputs: fold it back to 0
    out[:, mask] = np.where(out[:, mask] >= 2.0, 0.0, out[:, mask])
    return out.astype(dtype, copy=False)


def _fold(diff: np.ndarray) -> np.ndarray:
    """Fold normalised direction differences (``|a - b|`` in ``[0, 2)``) to ``[0, 1]``, exactly."""
    return np.minimum(diff, 2.0 - diff)


def pairwise_distance(a: npt.ArrayLike, b: npt.ArrayLike, is_direction: npt.ArrayLike) -> np.ndarray:
    """Distances between normalised sea states (outputs of :func:`normalise`).

    Parameters
    ----------
    a : array_like, shape (M, D)
    b : array_like, shape (K, D)
        Normalised points.
    is_direction : array_like of bool, shape (D,)

    Returns
    -------
    numpy.ndarray, shape (M, K)
        Euclidean distance with direction differences folded on the circle (at most 1,
        i.e. 180 deg). Float64.
    """
    a = np.atleast_2d(np.asarray(a, dtype=float))
    b = np.atleast_2d(np.asarray(b, dtype=float))
    mask = np.asarray(is_direction, dtype=bool).reshape(-1)
    if a.shape[1] != b.shape[1] or a.shape[1] != mask.shape[0]:
        raise ValueError(f"dimension mismatch: a {a.shape}, b {b.shape}, is_direction {mask.shape}")
    sq = np.zeros((a.shape[0], b.shape[0]))
    for k in range(a.shape[1]):
        d = np.abs(a[:, k, None] - b[None, :, k])
        if mask[k]:
            d = _fold(d)
        sq += d * d
    return np.sqrt(sq)


def nearest_distance(
    query: npt.ArrayLike,
    reference: npt.ArrayLike,
    is_direction: npt.ArrayLike,
    *,
    exclude_same_index: bool = False,
) -> np.ndarray:
    """Distance from each normalised query point to its nearest reference point.

    Parameters
    ----------
    query : array_like, shape (M, D)
    reference : array_like, shape (K, D)
        Normalised points (:func:`normalise`).
    is_direction : array_like of bool, shape (D,)
    exclude_same_index : bool
        When ``query`` and ``reference`` are the same set, ignore each point's distance to
        itself (leave-one-out nearest neighbour).

    Returns
    -------
    numpy.ndarray, shape (M,)
        Float64 distances. Computed in blocks, so memory stays ``O(block * K)``.
    """
    q = np.atleast_2d(np.asarray(query, dtype=float))
    r = np.atleast_2d(np.asarray(reference, dtype=float))
    out = np.empty(q.shape[0])
    for s in range(0, q.shape[0], _BLOCK):
        d = pairwise_distance(q[s : s + _BLOCK], r, is_direction)
        if exclude_same_index:
            rows = np.arange(d.shape[0])
            cols = rows + s
            keep = cols < d.shape[1]
            d[rows[keep], cols[keep]] = np.inf
        out[s : s + _BLOCK] = d.min(axis=1)
    return out


# --------------------------------------------------------------------------- MDA
def _start_indices(
    start: int | Sequence[int] | np.ndarray | None, x: np.ndarray, mask: np.ndarray, n: int
) -> list[int]:
    """Resolve the ``start`` argument of :func:`mda` to a list of preselected rows."""
    n_points = x.shape[0]
    if start is None:
        # the most extreme state: largest sum of normalised scalar coordinates
        score = x[:, ~mask].astype(np.float64).sum(axis=1) if (~mask).any() else np.zeros(n_points)
        return [int(np.argmax(score))]
    seq = [int(start)] if np.ndim(start) == 0 else [int(i) for i in np.asarray(start).reshape(-1)]
    if not seq:
        raise ValueError("start is an empty sequence: give at least one preselected index")
    for i in seq:
        if not 0 <= i < n_points:
            raise ValueError(f"start index {i} is outside 0..{n_points - 1}")
    if len(set(seq)) != len(seq):
        raise ValueError(f"start indices are not unique: {seq}")
    if len(seq) > n:
        raise ValueError(f"{len(seq)} start indices but only n = {n} states requested")
    return seq


def _prepare(
    points: npt.ArrayLike,
    n: int,
    is_direction: npt.ArrayLike,
    lo: npt.ArrayLike | None,
    span: npt.ArrayLike | None,
    dtype: npt.DTypeLike,
) -> tuple[np.ndarray, np.ndarray]:
    pts, mask = _check_points(points, is_direction)
    if int(n) != n or n < 1:
        raise ValueError(f"n must be a positive integer, got {n!r}")
    if n > pts.shape[0]:
        raise ValueError(f"cannot select n = {n} states out of {pts.shape[0]}")
    if np.dtype(dtype) not in (np.dtype(np.float32), np.dtype(np.float64)):
        raise ValueError(f"dtype must be float32 or float64, got {np.dtype(dtype)}")
    return normalise(pts, mask, lo, span, dtype=dtype), mask


def mda(
    points: npt.ArrayLike,
    n: int,
    *,
    is_direction: npt.ArrayLike,
    start: int | Sequence[int] | np.ndarray | None = None,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
    dtype: npt.DTypeLike = np.float32,
) -> np.ndarray:
    """Maximum dissimilarity selection with a running minimum distance, ``O(N * n)``.

    Each step adds the state whose distance to its nearest already-selected state is the
    largest (Camus et al. 2011; Barrera et al. 2019, section 3.2). The distance is the one of
    :func:`pairwise_distance` on :func:`normalise`-d points; squared distances are compared
    (same order, no square root).

    Parameters
    ----------
    points : array_like, shape (N, D)
        Sea states in physical units, directions in degrees.
    n : int
        Number of states to return (including any preselected ``start`` states).
    is_direction : array_like of bool, shape (D,)
        Which columns are directions (compared on the circle).
    start : int or sequence of int, optional
        First state (the paper: the one with the largest Hs), or an ordered sequence of
        already-selected states to continue from (they are returned first, as given).
        Default: the state with the largest sum of normalised scalar coordinates.
    lo, span : array_like, shape (D,), optional
        Normalisation (:func:`scaling_from`); default from ``points``.
    dtype : {float32, float64}
        Arithmetic precision. float32 halves the memory traffic; picks can differ from
        float64 only where two candidates' distances agree to about 1e-7 relative.

    Returns
    -------
    numpy.ndarray of int64, shape (n,)
        Row indices in selection order.

    Notes
    -----
    Ties are broken deterministically: among equally distant candidates the lowest row index
    wins (``numpy.argmax`` returns the first maximum). Exact duplicates of a selected state
    have distance 0 and are picked only after every distinct state. Results are identical,
    pick by pick, to :func:`mda_bruteforce` with the same ``dtype``.
    """
    x, mask = _prepare(points, n, is_direction, lo, span, dtype)
    dt = x.dtype.type
    picks = _start_indices(start, x, mask, n)
    cols = np.ascontiguousarray(x.T)  # (D, N): each variable contiguous
    n_points = cols.shape[1]
    mind = np.full(n_points, np.inf, dtype=dt)
    acc = np.empty(n_points, dtype=dt)
    tmp = np.empty(n_points, dtype=dt)
    tmp2 = np.empty(n_points, dtype=dt)
    two = dt(2.0)

    def update(i: int) -> None:
        p = cols[:, i]
        for k in range(cols.shape[0]):
            out = acc if k == 0 else tmp
            np.subtract(cols[k], p[k], out=out)
            if mask[k]:  # fold on the circle; a scalar difference is squared as is
                np.abs(out, out=out)
                np.subtract(two, out, out=tmp2)
                np.minimum(out, tmp2, out=out)
            np.multiply(out, out, out=out)
            if k:
                np.add(acc, tmp, out=acc)
        np.minimum(mind, acc, out=mind)

    for i in picks:
        update(i)
    mind[picks] = -1.0  # never pick a selected state again (min with >= 0 keeps it at -1)
    while len(picks) < n:
        i = int(np.argmax(mind))
        picks.append(i)
        update(i)
        mind[i] = -1.0
    return np.asarray(picks, dtype=np.int64)


def mda_bruteforce(
    points: npt.ArrayLike,
    n: int,
    *,
    is_direction: npt.ArrayLike,
    start: int | Sequence[int] | np.ndarray | None = None,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
    dtype: npt.DTypeLike = np.float32,
) -> np.ndarray:
    """Strict reference for :func:`mda`: recompute every distance at every step, ``O(N * n^2)``.

    Same parameters, normalisation, distance, start rule and tie rule as :func:`mda`, but no
    running minimum: at each step the full ``(N, j)`` distance matrix to the ``j`` selected
    states is rebuilt and minimised. For tests and small problems only.
    """
    x, mask = _prepare(points, n, is_direction, lo, span, dtype)
    dt = x.dtype.type
    picks = _start_indices(start, x, mask, n)
    while len(picks) < n:
        sel = x[picks]  # (j, D)
        sq = np.zeros((x.shape[0], len(picks)), dtype=dt)
        for k in range(x.shape[1]):
            d = np.abs(x[:, k, None] - sel[None, :, k])
            if mask[k]:
                d = np.minimum(d, dt(2.0) - d)
            sq = sq + d * d
        nearest = sq.min(axis=1)
        nearest[picks] = -1.0
        best = nearest.max()
        picks.append(int(np.flatnonzero(nearest == best)[0]))
    return np.asarray(picks, dtype=np.int64)


def _row_keys(points: np.ndarray) -> np.ndarray:
    """One opaque key per row, equal exactly when the rows are bitwise equal."""
    pts = np.ascontiguousarray(points, dtype=np.float64) + 0.0  # -0.0 -> 0.0
    return pts.view(np.dtype((np.void, pts.dtype.itemsize * pts.shape[1]))).reshape(-1)


def select_validation(
    points: npt.ArrayLike,
    n: int,
    *,
    exclude: npt.ArrayLike,
    is_direction: npt.ArrayLike,
    rule: Literal["random", "mda"] = "random",
    seed: int | np.random.SeedSequence = 0,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
) -> np.ndarray:
    """Pick states kept only to validate the reconstruction, disjoint from the training set.

    Parameters
    ----------
    points : array_like, shape (N, D)
        Sea states in physical units.
    n : int
        Number of validation states.
    exclude : array_like of int, shape (J,)
        The training states (row indices, in MDA order for ``rule="mda"``).
    is_direction : array_like of bool, shape (D,)
    rule : {"random", "mda"}
        ``"random"`` (default): a seeded uniform sample, without replacement, of the hours
        that are not training states *and* whose 5-D point differs from every training
        state (an exact copy would validate nothing); returned in increasing row order.
        This measures the error a typical hour sees. ``"mda"``: continue the maximum
        dissimilarity selection after the training states (the next ``n`` picks, in
        selection order); this stresses the reconstruction where the training set is
        sparsest.
    seed : int or numpy.random.SeedSequence
        Seed of the ``"random"`` rule (ignored by ``"mda"``).
    lo, span : array_like, shape (D,), optional
        Normalisation for ``"mda"`` (:func:`scaling_from`).

    Returns
    -------
    numpy.ndarray of int64, shape (n,)
        Row indices, none of them in ``exclude``.
    """
    pts, mask = _check_points(points, is_direction)
    train = np.asarray(exclude, dtype=np.int64).reshape(-1)
    if train.size and (train.min() < 0 or train.max() >= pts.shape[0]):
        raise ValueError(f"exclude holds indices outside 0..{pts.shape[0] - 1}")
    if int(n) != n or n < 0:
        raise ValueError(f"n must be a non-negative integer, got {n!r}")
    if rule == "mda":
        if train.size == 0:
            return mda(pts, n, is_direction=mask, lo=lo, span=span) if n else np.empty(0, np.int64)
        return mda(pts, train.size + n, is_direction=mask, start=train, lo=lo, span=span)[train.size :]
    if rule != "random":
        raise ValueError(f"validation rule {rule!r} is not one of {VALIDATION_RULES}")
    keys = _row_keys(pts)
    taken = np.isin(keys, keys[train]) if train.size else np.zeros(pts.shape[0], bool)
    candidates = np.flatnonzero(~taken)
    if n > candidates.size:
        raise ValueError(
            f"cannot pick {n} validation states: only {candidates.size} states differ from the "
            f"{train.size} training states"
        )
    rng = np.random.default_rng(seed)
    return np.sort(rng.choice(candidates, size=int(n), replace=False)).astype(np.int64)


# --------------------------------------------------------------------------- scatter matrix
def _check_edges(edges: npt.ArrayLike, name: str) -> np.ndarray:
    e = np.asarray(edges, dtype=float).reshape(-1)
    if e.size == 0:
        raise ValueError(f"{name}: at least one class edge is needed")
    if not np.all(np.isfinite(e)):
        raise ValueError(f"{name}: edges must be finite lower class bounds (the last class is open), got {e.tolist()}")
    if np.any(np.diff(e) <= 0):
        raise ValueError(f"{name}: edges must increase strictly, got {e.tolist()}")
    return e


def _classify(values: np.ndarray, edges: np.ndarray, name: str) -> np.ndarray:
    """Class of each value: ``k`` where ``edges[k] <= value < edges[k + 1]`` (last class open)."""
    below = values < edges[0]
    if below.any():
        row = int(np.flatnonzero(below)[0])
        raise ValueError(
            f"{name}: value {float(values[row])!r} at row {row} is below the first class edge {float(edges[0])!r}"
        )
    return np.searchsorted(edges, values, side="right") - 1


def class_labels(edges: npt.ArrayLike) -> list[str]:
    """Human-readable labels of classes given by their lower edges: ``"0-1.5"``, ..., ``">=4.5"``."""
    e = np.asarray(edges, dtype=float).reshape(-1)
    labels = [f"{lo:g}-{hi:g}" for lo, hi in zip(e[:-1], e[1:], strict=True)]
    return labels + [f">={e[-1]:g}"]


def _sector_index(directions: np.ndarray, sector: float) -> tuple[np.ndarray, int]:
    n_sec = int(round(360.0 / sector))
    if sector <= 0 or not np.isclose(n_sec * sector, 360.0):
        raise ValueError(f"direction sector width must divide 360 deg, got {sector!r}")
    k = np.floor(np.mod(directions + 0.5 * sector, 360.0) / sector).astype(np.int64)
    return np.minimum(k, n_sec - 1), n_sec


def modal_direction(directions: npt.ArrayLike, sector: float = 10.0) -> float:
    """Most likely direction of a sample: the centre of its most populated sector.

    Parameters
    ----------
    directions : array_like, shape (M,)
        Degrees (nautical, any turn).
    sector : float
        Sector width in degrees; must divide 360. Sectors are centred on ``0, w, 2w, ...``
        (the one centred on 0 covers ``[360 - w/2, w/2)``).

    Returns
    -------
    float
        The centre, in ``[0, 360)`` degrees; on a tie, the lowest centre.
    """
    d = np.asarray(directions, dtype=float).reshape(-1)
    if d.size == 0:
        raise ValueError("no directions given")
    k, n_sec = _sector_index(d, float(sector))
    return float(np.argmax(np.bincount(k, minlength=n_sec)) * sector)


@dataclass(frozen=True)
class ScatterMatrix:
    """The non-empty bins of a discrete (Hs, W, Tp) scatter matrix, Hs-major order.

    All arrays have shape ``(K,)`` for ``K`` non-empty bins.

    Attributes
    ----------
    hs_class, wind_class, tp_class : numpy.ndarray of int
        Class index of the bin along each axis (into the edges).
    hs, wind_speed, tp : numpy.ndarray
        Mean of the bin's hours (m, m/s, s).
    wave_dir, wind_dir : numpy.ndarray
        Most likely direction of the bin's hours (sector centre, degrees).
    hours : numpy.ndarray of int64
        Number of hindcast hours in the bin.
    probability : numpy.ndarray
        ``hours / total``; sums to 1.
    """

    hs_class: np.ndarray
    wind_class: np.ndarray
    tp_class: np.ndarray
    hs: np.ndarray
    wind_speed: np.ndarray
    tp: np.ndarray
    wave_dir: np.ndarray
    wind_dir: np.ndarray
    hours: np.ndarray
    probability: np.ndarray


def scatter_matrix(
    hs: npt.ArrayLike,
    wind_speed: npt.ArrayLike,
    tp: npt.ArrayLike,
    wave_dir: npt.ArrayLike,
    wind_dir: npt.ArrayLike,
    *,
    hs_edges: npt.ArrayLike = DEFAULT_HS_EDGES,
    wind_edges: npt.ArrayLike = DEFAULT_WIND_EDGES,
    tp_edges: npt.ArrayLike = DEFAULT_TP_EDGES,
    sector: float = 10.0,
) -> ScatterMatrix:
    """Bin sea states by Hs, then W, then Tp (Barrera et al. 2019, section 4.1).

    Parameters
    ----------
    hs, wind_speed, tp, wave_dir, wind_dir : array_like, shape (N,)
        Hourly sea states: m, m/s, s, degrees, degrees.
    hs_edges, wind_edges, tp_edges : array_like
        Lower class edges, strictly increasing; class ``k`` is ``[e[k], e[k+1])`` and the
        last class is open (``>= e[-1]``). Defaults: the paper's Hs 0/1.5/3/4.5 m,
        W 0/7/14 m/s, Tp 0/6/9/12 s (48 classes).
    sector : float
        Width in degrees of the direction sectors used for the most likely directions.

    Returns
    -------
    ScatterMatrix
        The non-empty bins, ordered by Hs class, then W class, then Tp class. Empty bins
        are dropped.

    Raises
    ------
    ValueError
        If the inputs differ in length, hold a non-finite value, or a value lies below the
        first edge of its variable (the message names the variable, value and row).
    """
    arrays = {
        "hs": np.asarray(hs, dtype=float).reshape(-1),
        "wind_speed": np.asarray(wind_speed, dtype=float).reshape(-1),
        "tp": np.asarray(tp, dtype=float).reshape(-1),
        "wave_dir": np.asarray(wave_dir, dtype=float).reshape(-1),
        "wind_dir": np.asarray(wind_dir, dtype=float).reshape(-1),
    }
    n = arrays["hs"].size
    for name, a in arrays.items():
        if a.size != n:
            raise ValueError(f"{name} has {a.size} values but hs has {n}")
        bad = ~np.isfinite(a)
        if bad.any():
            row = int(np.flatnonzero(bad)[0])
            raise ValueError(f"{name}: value {float(a[row])!r} at row {row} is not finite")
    if n == 0:
        raise ValueError("no sea states to bin")
    e_hs = _check_edges(hs_edges, "hs_edges")
    e_w = _check_edges(wind_edges, "wind_edges")
    e_tp = _check_edges(tp_edges, "tp_edges")
    c_hs = _classify(arrays["hs"], e_hs, "hs")
    c_w = _classify(arrays["wind_speed"], e_w, "wind_speed")
    c_tp = _classify(arrays["tp"], e_tp, "tp")
    shape = (e_hs.size, e_w.size, e_tp.size)
    flat = np.ravel_multi_index((c_hs, c_w, c_tp), shape)
    n_bins = int(np.prod(shape))
    counts = np.bincount(flat, minlength=n_bins)
    full = np.flatnonzero(counts)  # non-empty bins, Hs-major (C order)
    # compact bin id per hour
    compact = np.full(n_bins, -1, dtype=np.int64)
    compact[full] = np.arange(full.size)
    bid = compact[flat]
    hours = counts[full].astype(np.int64)

    def mean(a: np.ndarray) -> np.ndarray:
        return np.bincount(bid, weights=a, minlength=full.size) / hours

    def mode(a: np.ndarray) -> np.ndarray:
        k, n_sec = _sector_index(a, float(sector))
        table = np.bincount(bid * n_sec + k, minlength=full.size * n_sec).reshape(full.size, n_sec)
        return np.argmax(table, axis=1) * float(sector)

    i_hs, i_w, i_tp = np.unravel_index(full, shape)
    return ScatterMatrix(
        hs_class=i_hs.astype(np.int64),
        wind_class=i_w.astype(np.int64),
        tp_class=i_tp.astype(np.int64),
        hs=mean(arrays["hs"]),
        wind_speed=mean(arrays["wind_speed"]),
        tp=mean(arrays["tp"]),
        wave_dir=mode(arrays["wave_dir"]),
        wind_dir=mode(arrays["wind_dir"]),
        hours=hours,
        probability=hours / float(n),
    )


# --------------------------------------------------------------------------- xarray adapters
def hindcast_points(hindcast: xr.Dataset, *, source: str = "hindcast") -> np.ndarray:
    """The ``(N, 5)`` sea-state points of a hindcast, columns in ``names.METOCEAN_VARS`` order.

    Checks that every variable exists along ``time``, is finite, that Hs, Tp and wind speed
    are not negative and that directions lie in ``[0, 360]`` degrees.

    Raises
    ------
    ValueError
        Naming ``source``, the variable, the value and its first bad time stamp.
    """
    if names.TIME not in hindcast.dims:
        raise ValueError(f"{source}: no '{names.TIME}' dimension (dims: {tuple(hindcast.dims)})")
    cols = []
    times = hindcast[names.TIME].values if names.TIME in hindcast.coords else None
    for var in names.METOCEAN_VARS:
        if var not in hindcast:
            raise ValueError(f"{source}: variable '{var}' is missing (have {sorted(hindcast.data_vars)})")
        da = hindcast[var]
        if da.dims != (names.TIME,):
            raise ValueError(f"{source}: variable '{var}' has dims {da.dims}, expected ('{names.TIME}',)")
        a = np.asarray(da.values, dtype=float)
        if var in names.DIRECTION_VARS:
            bad = ~((a >= 0.0) & (a <= 360.0))
            rule = "a finite direction in [0, 360] degrees"
        else:
            bad = ~(np.isfinite(a) & (a >= 0.0))
            rule = "finite and >= 0"
        if bad.any():
            row = int(np.flatnonzero(bad)[0])
            when = f" ({names.TIME} {times[row]})" if times is not None else ""
            raise ValueError(f"{source}: variable '{var}' row {row}{when}: value {float(a[row])!r} is not {rule}")
        cols.append(a)
    return np.stack(cols, axis=1)


def _direction_mask() -> np.ndarray:
    return np.array([v in names.DIRECTION_VARS for v in names.METOCEAN_VARS])


def select_cases(
    hindcast: xr.Dataset,
    *,
    n_train: int,
    n_validate: int,
    rule: Literal["random", "mda"] = "random",
    seed: int = 0,
    source: str = "hindcast",
) -> xr.Dataset:
    """The sea states to simulate: ``n_train`` MDA states, then ``n_validate`` validation states.

    Parameters
    ----------
    hindcast : xarray.Dataset
        Dim ``time``; variables ``names.METOCEAN_VARS``.
    n_train, n_validate : int
        Numbers of training (MDA) and validation states.
    rule : {"random", "mda"}
        Validation rule, see :func:`select_validation`.
    seed : int
        The study's global seed; the ``"random"`` validation rule draws from
        ``SeedSequence([seed, VALIDATION_STREAM_KEY])``.
    source : str
        Name of the hindcast (a path) quoted in error messages.

    Returns
    -------
    xarray.Dataset
        Dim ``case`` (integer coordinate ``0..N-1``: training states first, in MDA order,
        then validation states); the five variables; ``hindcast_index`` (int64 position in
        ``time``), coordinate ``time`` (that hour), ``role`` (``"train"``/``"validate"``),
        ``nearest_train_distance`` (normalised distance to the nearest *other* training
        state). Attributes record the rule, seed, start state and the normalisation
        (``norm_variables``, ``norm_lo``, ``norm_span``, ``norm_is_direction``); each
        variable also carries its own ``norm_lo``/``norm_span``.
    """
    if rule not in VALIDATION_RULES:
        raise ValueError(f"{source}: validation rule {rule!r} is not one of {VALIDATION_RULES}")
    pts = hindcast_points(hindcast, source=source)
    mask = _direction_mask()
    if n_train + n_validate > pts.shape[0]:
        raise ValueError(
            f"{source}: n_train + n_validate = {n_train + n_validate} exceeds the {pts.shape[0]} hours"
        )
    lo, span = scaling_from(pts, mask)
    i_hs = names.METOCEAN_VARS.index("hs")
    start = int(np.argmax(pts[:, i_hs]))  # the paper: start from the largest Hs
    t0 = _time.perf_counter()
    train = mda(pts, n_train, is_direction=mask, start=start, lo=lo, span=span)
    _log.info("%s: MDA picked %d of %d states in %.2f s (start: largest hs, row %d)",
              source, n_train, pts.shape[0], _time.perf_counter() - t0, start)
    stream = np.random.SeedSequence([int(seed), VALIDATION_STREAM_KEY])
    valid = select_validation(
        pts, n_validate, exclude=train, is_direction=mask, rule=rule, seed=stream, lo=lo, span=span
    )
    _log.info("%s: %d validation states by rule %r (seed %d)", source, valid.size, rule, seed)
    index = np.concatenate([train, valid]).astype(np.int64)
    x = normalise(pts, mask, lo, span)
    x_train = x[train]
    dist = np.concatenate(
        [
            nearest_distance(x_train, x_train, mask, exclude_same_index=True),
            nearest_distance(x[valid], x_train, mask) if valid.size else np.empty(0),
        ]
    )
    case = np.arange(index.size, dtype=np.int64)
    data_vars: dict[str, tuple[str, np.ndarray, dict[str, object]]] = {}
    for k, var in enumerate(names.METOCEAN_VARS):
        attrs = {**names.attrs_for(var), "norm_lo": float(lo[k]), "norm_span": float(span[k])}
        data_vars[var] = (names.CASE, pts[index, k], attrs)
    data_vars["hindcast_index"] = (
        names.CASE,
        index,
        {"units": "1", "long_name": f"position of the sea state along the hindcast '{names.TIME}' dimension"},
    )
    data_vars["role"] = (
        names.CASE,
        np.array(["train"] * train.size + ["validate"] * valid.size),
        {"long_name": "train: used to fit the reconstruction; validate: kept only to check it"},
    )
    data_vars["nearest_train_distance"] = (
        names.CASE,
        dist,
        {"units": "1", "long_name": "normalised 5-D distance to the nearest other training state"},
    )
    coords: dict[str, object] = {names.CASE: case}
    if names.TIME in hindcast.coords:
        coords[names.TIME] = (names.CASE, hindcast[names.TIME].values[index])
    ds = xr.Dataset(data_vars, coords=coords)
    ds.attrs.update(
        {
            "selection_method": "maximum dissimilarity (Camus et al. 2011), running minimum distance",
            "distance": "Euclidean; scalars (x - norm_lo) / norm_span, directions folded on the circle / 180",
            "start_rule": "largest hs",
            "start_index": start,
            "n_train": int(train.size),
            "n_validate": int(valid.size),
            "validation_rule": rule,
            "seed": int(seed),
            "validation_stream": f"numpy SeedSequence([seed, {VALIDATION_STREAM_KEY}]) (crc32 of 'moorlife.selection.validate')",
            "n_hindcast": int(pts.shape[0]),
            "norm_variables": list(names.METOCEAN_VARS),
            "norm_lo": [float(v) for v in lo],
            "norm_span": [float(v) for v in span],
            "norm_is_direction": [bool(v) for v in mask],
        }
    )
    return ds


def discrete_states(
    hindcast: xr.Dataset,
    *,
    hs_edges: Sequence[float] = DEFAULT_HS_EDGES,
    wind_edges: Sequence[float] = DEFAULT_WIND_EDGES,
    tp_edges: Sequence[float] = DEFAULT_TP_EDGES,
    sector: float = 10.0,
    source: str = "hindcast",
) -> xr.Dataset:
    """The conventional discrete sea states (paper Table 6) of a hindcast.

    Parameters
    ----------
    hindcast : xarray.Dataset
        Dim ``time``; variables ``names.METOCEAN_VARS``.
    hs_edges, wind_edges, tp_edges : sequence of float
        Lower class edges (m, m/s, s); the last class is open. See :func:`scatter_matrix`.
    sector : float
        Direction sector width in degrees for the most likely directions.
    source : str
        Name of the hindcast quoted in error messages.

    Returns
    -------
    xarray.Dataset
        Dim ``bin`` (integer coordinate ``0..K-1``, non-empty bins, Hs-major order); the
        five variables (means for Hs, W, Tp; sector centres for directions);
        ``probability`` (sums to 1); ``hours``; class labels ``hs_bin``, ``wind_bin``,
        ``tp_bin`` (strings such as ``"1.5-3"``) and class indices ``hs_class``,
        ``wind_class``, ``tp_class``. Attributes hold the edges and sector width.
    """
    pts = hindcast_points(hindcast, source=source)
    col = {v: pts[:, k] for k, v in enumerate(names.METOCEAN_VARS)}
    sm = scatter_matrix(
        col["hs"],
        col["wind_speed"],
        col["tp"],
        col["wave_dir"],
        col["wind_dir"],
        hs_edges=hs_edges,
        wind_edges=wind_edges,
        tp_edges=tp_edges,
        sector=sector,
    )
    labels = {
        "hs": np.array(class_labels(hs_edges)),
        "wind": np.array(class_labels(wind_edges)),
        "tp": np.array(class_labels(tp_edges)),
    }
    rep = {
        "hs": "mean of the bin's hours",
        "tp": "mean of the bin's hours",
        "wind_speed": "mean of the bin's hours",
        "wave_dir": f"most likely {sector:g}-degree sector of the bin's hours (sector centre)",
        "wind_dir": f"most likely {sector:g}-degree sector of the bin's hours (sector centre)",
    }
    data_vars: dict[str, tuple[str, np.ndarray, dict[str, object]]] = {}
    for var in names.METOCEAN_VARS:
        data_vars[var] = (names.BIN, getattr(sm, var), {**names.attrs_for(var), "representative": rep[var]})
    data_vars["probability"] = (names.BIN, sm.probability, {"units": "1", "long_name": "probability of occurrence"})
    data_vars["hours"] = (names.BIN, sm.hours, {"units": "h", "long_name": "hindcast hours in the bin"})
    for axis, cls, unit in (("hs", sm.hs_class, "m"), ("wind", sm.wind_class, "m s-1"), ("tp", sm.tp_class, "s")):
        data_vars[f"{axis}_bin"] = (names.BIN, labels[axis][cls], {"long_name": f"{axis} class ({unit})"})
        data_vars[f"{axis}_class"] = (names.BIN, cls, {"units": "1", "long_name": f"{axis} class index"})
    ds = xr.Dataset(data_vars, coords={names.BIN: np.arange(sm.hours.size, dtype=np.int64)})
    _log.info("%s: %d non-empty bins of %d", source, sm.hours.size, len(hs_edges) * len(wind_edges) * len(tp_edges))
    ds.attrs.update(
        {
            "method": "scatter matrix binned by hs, then wind_speed, then tp (Barrera et al. 2019, section 4.1)",
            "hs_edges": [float(v) for v in hs_edges],
            "wind_edges": [float(v) for v in wind_edges],
            "tp_edges": [float(v) for v in tp_edges],
            "edges_meaning": "lower class edges; the last class of each variable is open",
            "direction_sector": float(sector),
            "n_bins_total": int(len(hs_edges) * len(wind_edges) * len(tp_edges)),
            "n_hindcast": int(pts.shape[0]),
            "total_hours": int(pts.shape[0]),
        }
    )
    if names.TIME in hindcast.coords and hindcast.sizes[names.TIME] > 1:
        t = pd.DatetimeIndex(hindcast[names.TIME].values)
        ds.attrs["period"] = f"{t[0].isoformat()} / {t[-1].isoformat()}"
    return ds
