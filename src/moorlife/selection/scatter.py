"""The conventional discrete scatter matrix the paper compares against (section 4.1).

The hindcast is binned by Hs, then W, then Tp; each non-empty bin is represented by the mean
Hs, W, Tp of its hours, the most likely wave and wind directions, and its probability of
occurrence.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = [
    "DEFAULT_HS_EDGES",
    "DEFAULT_WIND_EDGES",
    "DEFAULT_TP_EDGES",
    "check_edges",
    "classify",
    "class_labels",
    "modal_direction",
    "ScatterMatrix",
    "scatter_matrix",
]

#: Lower class edges of the paper's scatter matrix (section 4.1); the last class is open.
DEFAULT_HS_EDGES: tuple[float, ...] = (0.0, 1.5, 3.0, 4.5)  # m
DEFAULT_WIND_EDGES: tuple[float, ...] = (0.0, 7.0, 14.0)  # m/s
DEFAULT_TP_EDGES: tuple[float, ...] = (0.0, 6.0, 9.0, 12.0)  # s


def check_edges(edges: npt.ArrayLike, name: str) -> np.ndarray:
    """Class edges as a float array: finite lower class bounds, strictly increasing (the last
    class is open); ``name`` is quoted in the error."""
    e = np.asarray(edges, dtype=float).reshape(-1)
    if e.size == 0:
        raise ValueError(f"{name}: at least one class edge is needed")
    if not np.all(np.isfinite(e)):
        raise ValueError(f"{name}: edges must be finite lower class bounds (the last class is open), got {e.tolist()}")
    if np.any(np.diff(e) <= 0):
        raise ValueError(f"{name}: edges must increase strictly, got {e.tolist()}")
    return e


def classify(values: np.ndarray, edges: np.ndarray, name: str) -> np.ndarray:
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
    e_hs = check_edges(hs_edges, "hs_edges")
    e_w = check_edges(wind_edges, "wind_edges")
    e_tp = check_edges(tp_edges, "tp_edges")
    c_hs = classify(arrays["hs"], e_hs, "hs")
    c_w = classify(arrays["wind_speed"], e_w, "wind_speed")
    c_tp = classify(arrays["tp"], e_tp, "tp")
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
