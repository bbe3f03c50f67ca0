"""Chain properties: nominal stress area, R4S break load, corroded properties, and the
mean-stress correction."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

MEAN_STRESS_METHODS = ("none", "goodman", "soderberg", "gerber")


def _check_diameter(d: np.ndarray, name: str = "link_diameter") -> np.ndarray:
    d = np.asarray(d, dtype=float)
    if np.any(~np.isfinite(d)) or np.any(d <= 0):
        raise ValueError(f"{name} must be positive and finite (m), got {d!r}")
    if np.any(d > 1.0):
        raise ValueError(f"{name} = {np.max(d)!r} m is implausible for a chain link: pass metres, not mm")
    return d


def stress_area(link_diameter: npt.ArrayLike) -> np.ndarray:
    """Nominal cross-section of a chain link: the two legs, ``2 * pi * d**2 / 4``.

    Parameters
    ----------
    link_diameter : array_like
        Link bar diameter ``d`` in m.

    Returns
    -------
    ndarray
        Area in m**2, same shape.
    """
    d = _check_diameter(np.asarray(link_diameter, dtype=float))
    return 2.0 * np.pi * d**2 / 4.0


def r4s_break_load(link_diameter: npt.ArrayLike) -> np.ndarray:
    """R4S chain break load, manufacturer's formula (methodology Table 3).

    ``BL [kN] = 0.0304 * d**2 * (44 - 0.08 * d)`` with ``d`` in mm.

    Parameters
    ----------
    link_diameter : array_like
        ``d`` in m.

    Returns
    -------
    ndarray
        Break load in N.
    """
    dmm = _check_diameter(np.asarray(link_diameter, dtype=float)) * 1e3
    return 0.0304 * dmm**2 * (44.0 - 0.08 * dmm) * 1e3


def corroded_properties(
    link_diameter: npt.ArrayLike,
    mbs: npt.ArrayLike,
    years: npt.ArrayLike,
    rate: float = 0.2e-3,
) -> tuple[np.ndarray, np.ndarray]:
    """Link diameter and MBS after ``years`` of uniform corrosion.

    ``d(t) = d0 - rate * t``; the MBS scales with the R4S break-load formula,
    ``MBS(t) = MBS0 * BL(d(t)) / BL(d0)`` (the grade coefficient cancels).

    Parameters
    ----------
    link_diameter : array_like
        New link diameter ``d0`` in m.
    mbs : array_like
        New minimum breaking strength in N.
    years : array_like
        Age(s) in years (broadcast against the others).
    rate : float
        Diameter loss in m/year (the paper's 0.2 mm/year is ``0.2e-3``).

    Returns
    -------
    diameter, mbs : ndarray
        Broadcast shape; m and N.

    Raises
    ------
    ValueError
        If corrosion consumes the link (``d(t) <= 0``) or ``rate`` is negative.
    """
    if rate < 0:
        raise ValueError(f"corrosion rate must be >= 0 m/year, got {rate!r}")
    d0 = _check_diameter(np.asarray(link_diameter, dtype=float))
    t = np.asarray(years, dtype=float)
    if np.any(t < 0):
        raise ValueError(f"corrosion age must be >= 0 years, got {t!r}")
    d = d0 - rate * t
    if np.any(d <= 0) or np.any(44.0 - 0.08 * d * 1e3 <= 0):
        raise ValueError(f"corrosion of {rate * 1e3} mm/year over {np.max(t)} years consumes the {np.min(d0)} m link")
    return d, np.asarray(mbs, dtype=float) * r4s_break_load(d) / r4s_break_load(d0)


def mean_stress_factor(
    sigma_m: npt.ArrayLike,
    method: str = "goodman",
    ultimate: float = 960.0,
    yield_: float = 700.0,
) -> np.ndarray:
    """Ratio ``d_sigma / d_sigma_0`` of the allowable stress range at mean stress
    ``sigma_m`` to that at zero mean (paper section 4.4, methodology step 8).

    ``1 - (sigma_m / sigma_R)**n``: Goodman ``n = 1, sigma_R = ultimate``; Soderberg
    ``n = 1, sigma_R = yield``; Gerber ``n = 2, sigma_R = ultimate``; ``"none"`` gives 1.
    Compressive means (``sigma_m < 0``) are not credited: they give 1.

    Parameters
    ----------
    sigma_m : array_like
        Mean stress in MPa.
    method : {"none", "goodman", "soderberg", "gerber"}
    ultimate, yield_ : float
        Ultimate and yield strength in MPa (R4S: 960 and 700).

    Returns
    -------
    ndarray
        The ratio, same shape as ``sigma_m``, in ``(0, 1]``.

    Raises
    ------
    ValueError
        Unknown method, or a mean stress at or above ``sigma_R`` (ratio <= 0).
    """
    s = np.maximum(np.asarray(sigma_m, dtype=float), 0.0)
    if method == "none":
        return np.ones_like(s)
    if method == "goodman":
        r = 1.0 - s / ultimate
    elif method == "soderberg":
        r = 1.0 - s / yield_
    elif method == "gerber":
        r = 1.0 - (s / ultimate) ** 2
    else:
        raise ValueError(f"mean_stress method must be one of {MEAN_STRESS_METHODS}, got {method!r}")
    if np.any(r <= 0):
        raise ValueError(
            f"mean stress {float(np.max(s)):.1f} MPa reaches the {method} limit "
            f"(ultimate {ultimate} MPa, yield {yield_} MPa): no fatigue capacity left"
        )
    return r
