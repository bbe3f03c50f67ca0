"""A piecewise-linear trend in one scalar coordinate, beside the RBF's first-degree polynomial.

The paper's interpolant carries a first-degree polynomial ``p(x)`` fitted jointly with the
kernel weights (the augmented system of :mod:`moorlife.rbf.system`). A :class:`Trend` adds
columns to that basis: the hinges ``max(0, x_c - k) / s`` of one scalar coordinate ``x_c`` at
knots ``k`` (``s`` the knots' range), optionally times ``cos(h theta)`` and ``sin(h theta)`` of
one direction ``theta`` for ``h = 1 .. harmonics`` (and ``x_c`` itself times them, and the
harmonics above the first alone: the polynomial holds the first). With the
polynomial's constant and linear terms, the hinges span every continuous piecewise-linear
function of ``x_c`` with those knots: a feature narrower than the kernel's length scale along
``x_c`` but shared by the whole space (the damage of a lightly loaded line peaks in a band of
wind speed about 1.5 m/s wide just above rated) is fitted by the trend from every training
state, and the kernel interpolates what is left. This is universal kriging with a spline drift;
Rippa's leave-one-out closed form holds unchanged for the larger basis.

Only knots with at least :data:`MIN_SIDE` training values of ``x_c`` strictly on each side are
kept (:func:`supported_trend`), so that every column is determined by the data; the fitted model
records the knots it kept.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = ["MIN_SIDE", "Trend", "supported_trend", "trend_basis"]

#: Training values needed strictly below and strictly above a knot for it to be kept.
MIN_SIDE = 10


@dataclass(frozen=True)
class Trend:
    """The extra trend columns of an RBF (module docstring).

    Attributes
    ----------
    column : int
        Index of the scalar coordinate of the hinges (physical units).
    knots : tuple of float
        Hinge locations in that coordinate's units, strictly increasing.
    direction : int or None
        Index of the direction coordinate (degrees) whose harmonics multiply the hinges.
    harmonics : int
        Number of harmonics of ``direction`` (0: the hinges alone).
    """

    column: int
    knots: tuple[float, ...]
    direction: int | None = None
    harmonics: int = 0

    def __post_init__(self) -> None:
        k = np.asarray(self.knots, dtype=float)
        if k.ndim != 1 or not np.all(np.isfinite(k)) or np.any(np.diff(k) <= 0):
            raise ValueError(f"trend knots must be finite and strictly increasing, got {list(self.knots)}")
        if self.harmonics < 0 or (self.harmonics > 0 and self.direction is None):
            raise ValueError(f"trend harmonics = {self.harmonics} needs a direction coordinate (got {self.direction})")

    @property
    def n_columns(self) -> int:
        """Number of basis columns the trend adds."""
        h = 1 + 2 * self.harmonics
        return len(self.knots) * h + (h - 1) + 2 * max(0, self.harmonics - 1)


def supported_trend(trend: Trend, points: npt.ArrayLike) -> Trend:
    """``trend`` with only the knots that have :data:`MIN_SIDE` training values on each side.

    Parameters
    ----------
    trend : Trend
    points : array_like, shape (m, d)
        The training states (physical units).

    Returns
    -------
    Trend
        The same trend on the supported knots (possibly none: then only the harmonics of the
        coordinate itself remain).
    """
    x = np.asarray(points, dtype=float)[:, trend.column]
    keep = tuple(
        float(k) for k in trend.knots if np.count_nonzero(x < k) >= MIN_SIDE and np.count_nonzero(x > k) >= MIN_SIDE
    )
    return Trend(column=trend.column, knots=keep, direction=trend.direction, harmonics=trend.harmonics)


def trend_basis(points: npt.ArrayLike, trend: Trend) -> np.ndarray:
    """The trend columns at ``points`` (physical units).

    Parameters
    ----------
    points : array_like, shape (n, d)
    trend : Trend

    Returns
    -------
    numpy.ndarray, shape (n, trend.n_columns)
        For each knot, the hinge and then its products with ``cos(h theta)``, ``sin(h theta)``;
        then the coordinate (divided by the knots' range) times each harmonic; last, the
        harmonics from the second on.
    """
    x = np.asarray(points, dtype=float)
    k = np.asarray(trend.knots, dtype=float)
    scale = float(k[-1] - k[0]) if k.size > 1 else 1.0
    xc = x[:, trend.column]
    harm = [np.ones(x.shape[0])]
    if trend.harmonics:
        th = np.deg2rad(x[:, trend.direction])
        for h in range(1, trend.harmonics + 1):
            harm += [np.cos(h * th), np.sin(h * th)]
    cols = [np.maximum(0.0, xc - kk) / scale * g for kk in k for g in harm]
    cols += [xc / scale * g for g in harm[1:]] + harm[3:]
    if not cols:
        return np.empty((x.shape[0], 0))
    return np.column_stack(cols)
