"""Sensitivities of the paper's section 4: seed lives, corrosion, mean-stress correction."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import numpy.typing as npt
import pandas as pd

from moorlife import fatigue
from moorlife.lifecycle.damage import damage_per_year

__all__ = ["seed_lives", "corrosion_evolution", "mean_stress_table"]


def seed_lives(hourly_damage: npt.ArrayLike) -> np.ndarray:
    """Fatigue life in years if one sea state repeats for ever (paper section 4.2).

    Parameters
    ----------
    hourly_damage : array_like, shape (n_seed, ...)
        Hourly damage of each random-phase realisation.

    Returns
    -------
    numpy.ndarray, shape (n_seed, ...)
        ``1 / (hourly damage x 8766)``.
    """
    return fatigue.fatigue_life(damage_per_year(np.asarray(hourly_damage, dtype=float), 1.0))


def corrosion_evolution(
    per_year: float,
    link_diameter: float,
    years: float,
    *,
    curve: str,
    settings: fatigue.FatigueSettings,
    mean_tension: float | None = None,
) -> dict[str, np.ndarray]:
    """Accumulated damage of a corroding line vs a new one (paper section 4.3, Fig. 22).

    Parameters
    ----------
    per_year : float
        Yearly damage of the new line.
    link_diameter : float
        New link diameter in m.
    years : float
        Horizon in years.
    curve : {"sn", "tn"}
    settings : moorlife.fatigue.FatigueSettings
        Corrosion rate and step, mean-stress settings.
    mean_tension : float, optional
        N; needed with a mean-stress correction.

    Returns
    -------
    dict
        ``years`` (nstep + 1,), ``corroded`` and ``intact`` cumulative damage (nstep + 1,),
        ``factor`` (nstep,) the corrosion multiplier per step.
    """
    sn, tn = fatigue.get_curves("studless", settings.curves)
    m = sn.m if curve == "sn" else tn.m

    def factor(ages: np.ndarray) -> np.ndarray:
        return fatigue.corrosion_damage_factor(
            link_diameter,
            ages,
            curve=curve,
            m=m,
            rate=settings.corrosion_rate,
            mean_stress=settings.mean_stress,
            mean_tension=mean_tension,
            ultimate=settings.ultimate,
            yield_=settings.yield_,
        )

    ages, cum = fatigue.lifetime_damage_with_corrosion(
        lambda a: per_year * factor(a), years, step=settings.corrosion_step
    )
    return {"years": ages, "corroded": cum, "intact": per_year * ages, "factor": np.asarray(factor(ages[:-1]))}


def mean_stress_table(
    mooring: pd.DataFrame,
    mean_tension: Mapping[str, float] | None = None,
    *,
    ultimate: float = 960.0,
    yield_: float = 700.0,
) -> pd.DataFrame:
    """Mean-stress correction ratios per mooring system (paper Table 8).

    Parameters
    ----------
    mooring : pandas.DataFrame
        ``config/mooring_systems.tsv`` (``pretension_kN``, ``link_diameter_mm``).
    mean_tension : mapping of id -> N, optional
        A second block at another mean tension (e.g. the life-cycle mean tension of the most
        loaded line); omitted systems get NaN.
    ultimate, yield_ : float
        MPa.

    Returns
    -------
    pandas.DataFrame
        ``mooring_system, block, mean_tension_kN, mean_stress_mpa, goodman, soderberg, gerber``.
    """
    rows = []
    blocks = [("static", {ms: float(r["pretension_kN"]) * 1e3 for ms, r in mooring.iterrows()})]
    if mean_tension:
        blocks.append(("lifecycle mean", dict(mean_tension)))
    for block, tens in blocks:
        for ms, r in mooring.iterrows():
            t = tens.get(ms, np.nan)
            s = float(t / fatigue.stress_area(float(r["link_diameter_mm"]) * 1e-3) * 1e-6) if np.isfinite(t) else np.nan
            row = {"mooring_system": ms, "block": block, "mean_tension_kN": t / 1e3, "mean_stress_mpa": s}
            for meth in ("goodman", "soderberg", "gerber"):
                row[meth] = float(fatigue.mean_stress_factor(s, meth, ultimate, yield_)) if np.isfinite(s) else np.nan
            rows.append(row)
    return pd.DataFrame(rows)
