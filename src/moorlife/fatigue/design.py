"""Design fatigue factors (DNV from the adjacent-line damage ratio, or API's constant)."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt


def design_fatigue_factor(
    damage_ratio: npt.ArrayLike,
    *,
    base: float = 5.0,
    threshold: float = 0.8,
    increment: float = 3.0,
    span: float = 0.2,
) -> np.ndarray:
    """DNVGL-OS-E301 design fatigue factor for mooring lines not regularly inspected.

    ``DFF = 5`` if ``dF <= 0.8`` else ``5 + 3 (dF - 0.8) / 0.2`` (so 8 at ``dF = 1``).

    Parameters
    ----------
    damage_ratio : array_like
        ``dF``: the ratio of the characteristic fatigue damage of the adjacent line to
        that of the most loaded line (in ``[0, 1]``), see :func:`adjacent_damage_ratio`.
    base, threshold, increment, span : float
        The rule's constants (config ``fatigue.design_factor.dnv``).

    Returns
    -------
    ndarray
        Same shape as ``damage_ratio``.
    """
    r = np.asarray(damage_ratio, dtype=float)
    if np.any((r < 0) | (r > 1)) or np.any(~np.isfinite(r)):
        raise ValueError(f"damage ratio dF must lie in [0, 1], got {r!r}")
    return np.where(r <= threshold, base, base + increment * (r - threshold) / span)


def adjacent_damage_ratio(damage: npt.ArrayLike, axis: int = -1) -> np.ndarray:
    """``dF`` for a spread of lines in which every line is adjacent to the others.

    For three lines at 120 deg (OC4) each line neighbours both others, so the line
    adjacent to the most damaged one that matters is the second most damaged:
    ``dF = D_(2nd) / D_max``.

    Parameters
    ----------
    damage : array_like, shape (..., nline, ...)
        Damage per line along ``axis`` (at least two lines).

    Returns
    -------
    ndarray
        Ratio in ``[0, 1]``, the shape without ``axis`` (0 where all damage is zero).
    """
    d = np.sort(np.asarray(damage, dtype=float), axis=axis)
    if d.shape[axis] < 2:
        raise ValueError("adjacent_damage_ratio needs at least two lines")
    top = np.take(d, -1, axis=axis)
    second = np.take(d, -2, axis=axis)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(top > 0, second / np.where(top > 0, top, 1.0), 0.0)
