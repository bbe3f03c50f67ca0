"""The normalised sea-state space shared by the selection and the RBF reconstruction.

Methodology step 2 (Barrera et al. 2019, section 3.2): the five sea-state variables
``names.METOCEAN_VARS`` (wind speed and direction, Hs, Tp, wave direction) are embedded in one
normalised space, and one distance measures them. The selection (maximum dissimilarity,
:mod:`moorlife.selection`) and the reconstruction (:mod:`moorlife.rbf`) both use this module,
so the RBF distance is exactly the maximum-dissimilarity distance.

The normalised distance
-----------------------
Every scalar variable is scaled by its range, ``(x - lo) / span`` with ``span = max - min``
over the hindcast (a constant column gets ``span = 1``). A direction (degrees, nautical) is
mapped to ``deg / 180`` in ``[0, 2)`` and two directions are compared on the circle: the
absolute difference is folded to at most 1 (180 deg), i.e.
``moorlife.conventions.circular_difference(a, b) / 180``. The distance between two states
is the Euclidean norm of these per-variable differences. :func:`scaling_from` gives
``(lo, span)``, :func:`normalise` embeds points, :func:`pairwise_distance`,
:func:`nearest_distance` and :func:`squared_distances` measure them. :class:`Space` records one
normalisation (:func:`fit_space`) and :func:`embed` applies it. The ranges used by the
selection are stored in the attributes of ``results/selection/cases.zarr`` (``norm_lo`` /
``norm_span``), so that later stages use exactly the same metric.

The distances are computed by compiled kernels (:func:`sq_dist_block`, :func:`nearest_block`),
float64, each row by one thread in a fixed order, so the numbers do not depend on the thread
count.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numba as nb
import numpy as np
import numpy.typing as npt

from moorlife import names

__all__ = [
    "DIRECTION_SPAN",
    "direction_mask",
    "check_points",
    "scaling_from",
    "normalise",
    "pairwise_distance",
    "nearest_distance",
    "Space",
    "fit_space",
    "embed",
    "as_points",
    "sq_dist_block",
    "nearest_block",
    "squared_distances",
]

#: Normalised span of a direction: deg / 180, so the folded difference is at most 1.
DIRECTION_SPAN = 180.0
_BLOCK = 4096  # rows per block in the O(M*K) distance helpers (bounds memory)


def direction_mask(variables: Sequence[str] = names.METOCEAN_VARS) -> np.ndarray:
    """Which of ``variables`` are directions (``names.DIRECTION_VARS``), as a bool array.

    Parameters
    ----------
    variables : sequence of str
        Variable names; default the five sea-state variables in ``names.METOCEAN_VARS`` order.

    Returns
    -------
    numpy.ndarray of bool, shape (len(variables),)
    """
    return np.array([v in names.DIRECTION_VARS for v in variables])


def check_points(points: npt.ArrayLike, is_direction: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Validate ``(N, D)`` points and a ``(D,)`` direction mask; return float64 and bool arrays."""
    pts = np.asarray(points, dtype=float)
    if pts.ndim != 2:
        raise ValueError(f"points must be a 2-D array (N states, D variables), got shape {pts.shape}")
    if pts.shape[0] == 0:
        raise ValueError("points is empty: no sea states to select from")
    mask = np.asarray(is_direction, dtype=bool).reshape(-1)
    if mask.shape[0] != pts.shape[1]:
        raise ValueError(f"is_direction has {mask.shape[0]} entries but points have {pts.shape[1]} columns")
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
    pts, mask = check_points(points, is_direction)
    lo = pts.min(axis=0)
    span = pts.max(axis=0) - lo
    span[span == 0.0] = 1.0
    lo[mask] = 0.0
    span[mask] = DIRECTION_SPAN
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
    pts, mask = check_points(points, is_direction)
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
    out[:, mask] = np.mod(pts[:, mask], 360.0) / DIRECTION_SPAN
    # mod can return exactly 360.0 for tiny negative inputs: fold it back to 0
    out[:, mask] = np.where(out[:, mask] >= 2.0, 0.0, out[:, mask])
    return out.astype(dtype, copy=False)


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
        i.e. 180 deg). Float64: the square root of :func:`squared_distances`.
    """
    a = np.atleast_2d(np.asarray(a, dtype=float))
    b = np.atleast_2d(np.asarray(b, dtype=float))
    mask = np.asarray(is_direction, dtype=bool).reshape(-1)
    if a.shape[1] != b.shape[1] or a.shape[1] != mask.shape[0]:
        raise ValueError(f"dimension mismatch: a {a.shape}, b {b.shape}, is_direction {mask.shape}")
    return np.sqrt(squared_distances(a, b, mask))


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


# --------------------------------------------------------------------------- Space
@dataclass(frozen=True)
class Space:
    """Normalisation of the input space.

    Attributes
    ----------
    lower : numpy.ndarray, shape (d,)
        Subtracted from each scalar coordinate (0 for directions).
    scale : numpy.ndarray, shape (d,)
        Each scalar's range; 180 for directions (degrees).
    is_direction : numpy.ndarray of bool, shape (d,)
        Which coordinates are directions in degrees (compared on the circle).
    """

    lower: np.ndarray
    scale: np.ndarray
    is_direction: np.ndarray


def fit_space(
    points: npt.ArrayLike,
    is_direction: npt.ArrayLike,
    *,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
) -> Space:
    """The normalisation of methodology step 2: scalars by range, directions by 180 deg.

    The embedding of :func:`scaling_from` and :func:`normalise`, recorded in a :class:`Space`.

    Parameters
    ----------
    points : array_like, shape (n, d)
        Points in physical units (directions in degrees).
    is_direction : array_like of bool, shape (d,)
        Which columns are directions.
    lo, span : array_like, shape (d,), optional
        Offset and range of each scalar, e.g. the hindcast's as stored in
        ``cases.zarr`` (``norm_lo``, ``norm_span``); default from ``points``.

    Returns
    -------
    Space

    Raises
    ------
    ValueError
        If a scalar span is not positive and finite, or shapes disagree.
    """
    x = as_points(points)
    isdir = np.asarray(is_direction, dtype=bool)
    if isdir.shape != (x.shape[1],):
        raise ValueError(f"is_direction has shape {isdir.shape}, expected ({x.shape[1]},)")
    lo_d, span_d = scaling_from(x, isdir)
    lo_a = lo_d if lo is None else np.broadcast_to(np.asarray(lo, dtype=float), isdir.shape).copy()
    span_a = span_d if span is None else np.broadcast_to(np.asarray(span, dtype=float), isdir.shape).copy()
    lo_a[isdir] = 0.0
    span_a[isdir] = DIRECTION_SPAN
    bad = ~(np.isfinite(span_a) & (span_a > 0))
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise ValueError(f"input column {k} has span {span_a[k]!r}; a scalar needs a positive range")
    return Space(lower=lo_a, scale=span_a, is_direction=isdir)


def embed(points: npt.ArrayLike, space: Space) -> np.ndarray:
    """Map physical points to the normalised space of ``space`` (:func:`normalise`).

    Scalars become ``(x - lower) / range``; directions become ``(x mod 360) / 180`` in
    ``[0, 2)``, so that the folded circular difference divided by 180 is
    ``min(|a - b|, 2 - |a - b|)``. :func:`moorlife.rbf.normalise` is this function.

    Parameters
    ----------
    points : array_like, shape (n, d)
    space : Space

    Returns
    -------
    numpy.ndarray, shape (n, d), C-contiguous float64
    """
    x = as_points(points)
    if x.shape[1] != space.scale.size:
        raise ValueError(f"points have {x.shape[1]} columns, the space has {space.scale.size}")
    z = normalise(x, space.is_direction, space.lower, space.scale, dtype=np.float64)
    return np.ascontiguousarray(z)


def as_points(points: npt.ArrayLike) -> np.ndarray:
    """Points as a finite float64 ``(n, d)`` array (a 1-D input is one column).

    Raises
    ------
    ValueError
        If the array is not 1-D or 2-D or holds a non-finite value (naming row and column).
    """
    x = np.asarray(points, dtype=float)
    if x.ndim == 1:
        x = x[:, None]
    if x.ndim != 2:
        raise ValueError(f"points must be a 2-D array (n, d), got shape {x.shape}")
    if not np.all(np.isfinite(x)):
        row, col = np.argwhere(~np.isfinite(x))[0]
        raise ValueError(f"points are not finite: row {row}, column {col} = {x[row, col]!r}")
    return x


# --------------------------------------------------------------------------- kernels
@nb.njit(parallel=True, cache=True)
def sq_dist_block(
    zq: np.ndarray, zc_t: np.ndarray, isdir: np.ndarray, out: np.ndarray
) -> None:  # pragma: no cover - numba
    """Squared normalised distances into ``out`` (n, m): ``zq`` (n, d), ``zc_t`` (d, m), ``isdir`` (d,)."""
    n, d = zq.shape
    m = zc_t.shape[1]
    for i in nb.prange(n):
        for j in range(m):
            out[i, j] = 0.0
        for k in range(d):
            a = zq[i, k]
            if isdir[k]:
                for j in range(m):
                    t = abs(a - zc_t[k, j])
                    t = min(t, 2.0 - t)
                    out[i, j] += t * t
            else:
                for j in range(m):
                    t = a - zc_t[k, j]
                    out[i, j] += t * t


@nb.njit(parallel=True, cache=True)
def nearest_block(
    zq: np.ndarray, zc_t: np.ndarray, isdir: np.ndarray, dmin: np.ndarray, imin: np.ndarray
) -> None:  # pragma: no cover - numba
    """Distance ``dmin`` (n,) to, and index ``imin`` (n,) of, the nearest column of ``zc_t`` (d, m)."""
    n, d = zq.shape
    m = zc_t.shape[1]
    for i in nb.prange(n):
        row = np.zeros(m)
        for k in range(d):  # dimension-outer, like sq_dist_block, so the j loop vectorises
            a = zq[i, k]
            if isdir[k]:
                for j in range(m):
                    t = abs(a - zc_t[k, j])
                    t = min(t, 2.0 - t)
                    row[j] += t * t
            else:
                for j in range(m):
                    t = a - zc_t[k, j]
                    row[j] += t * t
        ib = 0
        for j in range(1, m):
            if row[j] < row[ib]:
                ib = j
        dmin[i] = math.sqrt(row[ib])
        imin[i] = ib


def squared_distances(zq: npt.ArrayLike, zc: npt.ArrayLike, is_direction: npt.ArrayLike) -> np.ndarray:
    """Squared normalised distances between two sets of normalised points.

    Parameters
    ----------
    zq : array_like, shape (n, d)
        Normalised query points (see :func:`normalise`).
    zc : array_like, shape (m, d)
        Normalised centres.
    is_direction : array_like of bool, shape (d,)

    Returns
    -------
    numpy.ndarray, shape (n, m)
        ``r^2``: scalar differences squared plus, for directions,
        ``min(|a - b|, 2 - |a - b|)^2``.
    """
    a = np.ascontiguousarray(zq, dtype=float)
    b_t = np.ascontiguousarray(np.asarray(zc, dtype=float).T)
    out = np.empty((a.shape[0], b_t.shape[1]))
    sq_dist_block(a, b_t, np.asarray(is_direction, dtype=np.bool_), out)
    return out
