"""Damage arithmetic: life-cycle and discrete damage, the design check and the recommendation.

* ``lifecycle damage`` is the sum of the hourly damage over every hour of the hindcast;
  per year it is divided by the hindcast length in years (hours / 8766), and over the design
  life it is the yearly damage times the design life.
* ``difference_pct = 100 (D_lifecycle - D_discrete) / D_lifecycle``: positive when the
  discrete matrix underestimates (the sign of the paper's Table 7).
* ``passes``: ``DFF x D_design_life <= 1`` with the design fatigue factor of the curve
  family's rule (``fatigue.design_factor``) and, for DNV, ``dF`` = the damage of the line
  adjacent to the most damaged one over the most damaged (:func:`fatigue.adjacent_damage_ratio`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt
import pandas as pd

from moorlife import fatigue

__all__ = [
    "HOURS_PER_YEAR",
    "DAMAGE_VARS",
    "life_damage",
    "damage_per_year",
    "design_check",
    "discrete_damage",
    "difference_pct",
    "recommend",
]

#: Hours in a mean Julian year (365.25 days).
HOURS_PER_YEAR = 8766.0
DAMAGE_VARS: dict[str, str] = {"sn": "damage_sn", "tn": "damage_tn"}


def life_damage(hourly: npt.ArrayLike, axis: int = 0) -> np.ndarray:
    """Life-cycle damage: the sum of the hourly damage over every hour (paper eq. 13).

    Parameters
    ----------
    hourly : array_like, shape (n_hours, ...)
        Damage per hour of sea state.

    Returns
    -------
    numpy.ndarray, shape (...)

    Raises
    ------
    ValueError
        If any hourly damage is negative or not finite (naming the first bad hour).
    """
    h = np.asarray(hourly, dtype=float)
    bad = ~np.isfinite(h) | (h < 0)
    if bad.any():
        idx = np.argwhere(bad)[0]
        raise ValueError(f"hourly damage at index {tuple(int(i) for i in idx)} is {h[tuple(idx)]!r}; must be >= 0")
    return h.sum(axis=axis)


def damage_per_year(total: npt.ArrayLike, n_hours: float) -> np.ndarray:
    """Damage per (Julian) year from the damage of ``n_hours`` hours."""
    if not n_hours > 0:
        raise ValueError(f"n_hours must be positive, got {n_hours!r}")
    return np.asarray(total, dtype=float) * (HOURS_PER_YEAR / float(n_hours))


def design_check(
    per_year: npt.ArrayLike, design_life: float, curve: str, settings: fatigue.FatigueSettings, line_axis: int = -1
) -> dict[str, np.ndarray]:
    """Design fatigue factor, design-life damage and verdict for each line.

    Parameters
    ----------
    per_year : array_like, shape (..., n_line)
        Yearly damage of each line (one curve family).
    design_life : float
        Years.
    curve : {"sn", "tn"}
        Selects the rule (``settings.rule_sn`` / ``rule_tn``: ``dnv`` or ``api``).
    settings : moorlife.fatigue.FatigueSettings
    line_axis : int

    Returns
    -------
    dict
        ``damage_ratio`` dF (shape ``(...)``), ``design_fatigue_factor`` (...),
        ``design_life_damage`` (..., n_line), ``utilisation`` = DFF x design-life damage,
        ``passes`` (utilisation <= 1), ``fatigue_life_years`` (characteristic, 1 / yearly)
        and ``design_fatigue_life_years`` (1 / (DFF x yearly)).
    """
    d = np.asarray(per_year, dtype=float)
    ratio = fatigue.adjacent_damage_ratio(d, axis=line_axis)
    dff = settings.design_factor(curve, ratio)
    dff_b = np.expand_dims(dff, line_axis)
    dl = d * float(design_life)
    util = dff_b * dl
    return {
        "damage_ratio": ratio,
        "design_fatigue_factor": dff,
        "design_life_damage": dl,
        "utilisation": util,
        "passes": util <= 1.0,
        "fatigue_life_years": fatigue.fatigue_life(d),
        "design_fatigue_life_years": fatigue.fatigue_life(d, design_factor=dff_b),
    }


def discrete_damage(probability: npt.ArrayLike, hourly: npt.ArrayLike, n_hours: float) -> np.ndarray:
    """Damage of the conventional method: ``sum_b probability_b x hourly damage_b x hours``.

    Parameters
    ----------
    probability : array_like, shape (n_bin,)
        Occurrence probability of each bin (sums to 1).
    hourly : array_like, shape (n_bin, ...)
        Hourly damage of each bin's representative state.
    n_hours : float
        Hours of the period (the hindcast's, for a like-for-like comparison).

    Returns
    -------
    numpy.ndarray, shape (...)

    Raises
    ------
    ValueError
        If the probabilities are negative or do not sum to 1 (to 1e-6).
    """
    p = np.asarray(probability, dtype=float)
    h = np.asarray(hourly, dtype=float)
    if p.ndim != 1 or p.shape[0] != h.shape[0]:
        raise ValueError(f"probability {p.shape} and hourly damage {h.shape} do not match along the bins")
    if np.any(p < 0) or abs(p.sum() - 1.0) > 1e-6:
        raise ValueError(f"bin probabilities must be >= 0 and sum to 1, got sum {p.sum()!r}")
    life_damage(h)  # same checks as the hourly damage of the hindcast
    return np.tensordot(p, h, axes=(0, 0)) * float(n_hours)


def difference_pct(lifecycle: npt.ArrayLike, discrete: npt.ArrayLike) -> np.ndarray:
    """``100 (lifecycle - discrete) / lifecycle``: > 0 when the discrete matrix underestimates."""
    lc = np.asarray(lifecycle, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return 100.0 * (lc - np.asarray(discrete, dtype=float)) / lc


def recommend(
    table: pd.DataFrame, *, curves: Sequence[str] = ("sn", "tn"), mass_column: str = "mass_kg_per_m"
) -> str | None:
    """The lightest mooring system that passes the design check on every line and curve.

    Parameters
    ----------
    table : pandas.DataFrame
        One row per (``mooring_system``, ``line``, ``curve``) with ``passes`` and the mass.
    curves : sequence of str
        Curve families that must pass (default both S-N and T-N).
    mass_column : str
        Column ranking the systems (lightest first; ties by id).

    Returns
    -------
    str or None
        The system id, or None when no system passes.
    """
    for col in ("mooring_system", "curve", "passes", mass_column):
        if col not in table.columns:
            raise ValueError(f"comparison table: column {col!r} missing")
    sub = table[table["curve"].isin(list(curves))]
    if sub.empty:
        raise ValueError(f"comparison table has no rows for curves {list(curves)}")
    ok = sub.groupby("mooring_system")["passes"].all()
    mass = sub.groupby("mooring_system")[mass_column].first()
    order = sorted(ok.index, key=lambda m: (float(mass[m]), str(m)))
    for ms in order:
        if bool(ok[ms]):
            return str(ms)
    return None
