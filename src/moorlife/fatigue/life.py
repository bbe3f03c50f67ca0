"""Damage over the life: corrosion, the fatigue life, annual damage and the life summary
with its design-factor check."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from moorlife.fatigue.chain import _check_diameter, corroded_properties, mean_stress_factor, r4s_break_load, stress_area
from moorlife.fatigue.curves import FatigueSettings, get_curves
from moorlife.fatigue.design import adjacent_damage_ratio

HOURS_PER_YEAR = 8766.0  # 365.25 days


def corrosion_damage_factor(
    link_diameter: npt.ArrayLike,
    years: npt.ArrayLike,
    *,
    curve: str,
    m: float = 3.0,
    rate: float = 0.2e-3,
    mean_stress: str = "none",
    mean_tension: npt.ArrayLike | None = None,
    ultimate: float = 960.0,
    yield_: float = 700.0,
) -> np.ndarray:
    """Factor by which corrosion multiplies the damage rate at age ``years``.

    Cycle ranges in N do not change with corrosion; only the area (S-N) or the
    MBS (T-N) does, so without mean-stress correction the factor is exact:
    S-N ``(d0 / d)**(2 m)``, T-N ``(BL(d0) / BL(d))**m`` (R4S break load).

    With a mean-stress correction (S-N only) the cycle means' stress also rises;
    the factor then includes ``(r(sigma_m0) / r(sigma_m(t)))**m`` evaluated at
    ``mean_tension`` (e.g. the pretension or the record mean), exact when every cycle
    has that mean and a close approximation otherwise (cycle means of mooring tension
    stay near the mean tension).

    Parameters
    ----------
    link_diameter : array_like
        New link diameter in m.
    years : array_like
        Ages in years (broadcast against ``link_diameter`` and ``mean_tension``).
    curve : {"sn", "tn"}
    m : float
        The curve's exponent.
    rate : float
        Diameter loss in m/year.
    mean_stress, mean_tension, ultimate, yield_
        Mean-stress correction settings (``mean_tension`` in N, required unless
        ``mean_stress == "none"``).

    Returns
    -------
    ndarray
        Factor >= 1 (1 at age 0), broadcast shape.
    """
    d0 = _check_diameter(np.asarray(link_diameter, dtype=float))
    d, _ = corroded_properties(d0, 1.0, years, rate)
    if curve == "tn":
        return (r4s_break_load(d0) / r4s_break_load(d)) ** m
    if curve != "sn":
        raise ValueError(f"curve must be 'sn' or 'tn', got {curve!r}")
    f = (d0 / d) ** (2.0 * m)
    if mean_stress != "none":
        if mean_tension is None:
            raise ValueError("corrosion_damage_factor: mean_tension (N) is required with a mean-stress correction")
        tm = np.asarray(mean_tension, dtype=float)
        r0 = mean_stress_factor(tm / stress_area(d0) * 1e-6, mean_stress, ultimate, yield_)
        rt = mean_stress_factor(tm / stress_area(d) * 1e-6, mean_stress, ultimate, yield_)
        f = f * (r0 / rt) ** m
    return f


def _step_ages(years: float, step: float) -> tuple[np.ndarray, np.ndarray]:
    if not (years > 0 and step > 0):
        raise ValueError(f"years and step must be positive, got years={years!r}, step={step!r}")
    n = int(math.ceil(years / step - 1e-12))
    starts = np.arange(n) * step
    widths = np.minimum(step, years - starts)
    return starts, widths


def lifetime_damage_with_corrosion(
    damage_rate: Callable[[np.ndarray], npt.ArrayLike],
    years: float,
    *,
    step: float = 5.0,
) -> tuple[np.ndarray, np.ndarray]:
    """Accumulated damage over a life in which the damage rate changes with age.

    The rate is re-evaluated every ``step`` years and held constant over the step,
    at its value at the start of the step (the paper's section 4.3: damage recomputed
    every 5 years with the diameter reached at that time). The last step is shortened
    to end exactly at ``years``.

    Parameters
    ----------
    damage_rate : callable
        ``damage_rate(ages)`` with ``ages`` of shape ``(nstep,)`` returns the damage per
        year at each age, shape ``(nstep, ...)`` (or broadcastable to it). Typically
        ``lambda a: d_year0 * corrosion_damage_factor(d0, a[:, None], curve="sn")``.
    years : float
        Life in years.
    step : float
        Re-evaluation interval in years.

    Returns
    -------
    ages : ndarray, shape (nstep + 1,)
        ``0, step, 2 step, ..., years``.
    cumulative : ndarray, shape (nstep + 1, ...)
        Damage accumulated at each age (0 at age 0).
    """
    starts, widths = _step_ages(float(years), float(step))
    rate = np.asarray(damage_rate(starts), dtype=float)
    if rate.ndim == 0:
        rate = np.broadcast_to(rate, starts.shape)
    if rate.shape[0] != starts.size:
        raise ValueError(f"damage_rate must return shape ({starts.size}, ...), got {rate.shape}")
    inc = rate * widths.reshape((-1,) + (1,) * (rate.ndim - 1))
    cum = np.concatenate([np.zeros((1,) + rate.shape[1:]), np.cumsum(inc, axis=0)], axis=0)
    return np.append(starts, float(years)), cum


def fatigue_life(
    damage_per_year: npt.ArrayLike,
    *,
    design_factor: npt.ArrayLike = 1.0,
    rate_factor: Callable[[np.ndarray], npt.ArrayLike] | None = None,
    step: float = 5.0,
    max_years: float = 200.0,
) -> np.ndarray:
    """Fatigue life in years: the age at which ``design_factor * D`` reaches 1.

    Parameters
    ----------
    damage_per_year : array_like, shape (...)
        Damage rate of the new chain, per year.
    design_factor : array_like, broadcastable to (...)
        1 for the characteristic life, or a design fatigue factor
        (:func:`design_fatigue_factor`, API 3).
    rate_factor : callable, optional
        ``rate_factor(ages)`` with ``ages`` shape ``(nstep,)`` returns the corrosion
        multiplier of the rate, shape ``(nstep, ...)`` or broadcastable (see
        :func:`corrosion_damage_factor`); piecewise constant over ``step`` years as in
        :func:`lifetime_damage_with_corrosion`. Without it the rate is constant and the
        life is ``1 / (design_factor * damage_per_year)``.
    step : float
        Corrosion re-evaluation interval in years.
    max_years : float
        Search horizon with corrosion; lives beyond it are returned as ``inf``.

    Returns
    -------
    ndarray, shape (...)
        Years (``inf`` for zero damage).
    """
    dy = np.asarray(damage_per_year, dtype=float) * np.asarray(design_factor, dtype=float)
    if np.any(dy < 0):
        raise ValueError("damage_per_year must be >= 0")
    if rate_factor is None:
        with np.errstate(divide="ignore"):
            return np.where(dy > 0, 1.0 / np.where(dy > 0, dy, 1.0), np.inf)
    starts, widths = _step_ages(float(max_years), float(step))
    f = np.asarray(rate_factor(starts), dtype=float)
    f = np.broadcast_to(f.reshape(f.shape + (1,) * max(0, 1 + dy.ndim - f.ndim)), (starts.size,) + dy.shape)
    rate = dy[None] * f  # (nstep, ...)
    cum_end = np.cumsum(rate * widths.reshape((-1,) + (1,) * dy.ndim), axis=0)
    cum_start = cum_end - rate * widths.reshape((-1,) + (1,) * dy.ndim)
    reached = cum_end >= 1.0
    k = np.argmax(reached, axis=0)
    ok = reached.any(axis=0)
    r_k = np.take_along_axis(rate, k[None], axis=0)[0]
    c_k = np.take_along_axis(cum_start, k[None], axis=0)[0]
    with np.errstate(divide="ignore", invalid="ignore"):
        life = starts[k] + (1.0 - c_k) / r_k
    return np.where(ok, life, np.inf)


def annual_damage(hourly: npt.ArrayLike, axis: int = 0, hours_per_year: float = HOURS_PER_YEAR) -> np.ndarray:
    """Mean damage per year from damage per hour of a chronological hindcast.

    Parameters
    ----------
    hourly : array_like, shape (..., ntime, ...)
        Damage of every hindcast hour along ``axis`` (NaN not allowed).
    axis : int
        The time axis.
    hours_per_year : float
        8766 (365.25 days).

    Returns
    -------
    ndarray
        ``sum(hourly) / (ntime / hours_per_year)``, the shape without ``axis``.
    """
    h = np.asarray(hourly, dtype=float)
    if not np.all(np.isfinite(h)):
        raise ValueError("hourly damage contains non-finite values")
    return h.sum(axis=axis) * hours_per_year / h.shape[axis]


def life_summary(
    damage_per_year: npt.ArrayLike,
    *,
    curve: str,
    link_diameter: float,
    chain: str = "studless",
    settings: FatigueSettings | None = None,
    corrosion: bool = False,
    mean_tension: npt.ArrayLike | None = None,
    line_axis: int = -1,
) -> dict[str, np.ndarray]:
    """Life-cycle damage, fatigue life and the design-factor check of a set of lines.

    Parameters
    ----------
    damage_per_year : array_like, shape (..., nline)
        Damage rate of the new chain per line (lines along ``line_axis``).
    curve : {"sn", "tn"}
        Curve family; selects the design-factor rule (``settings.rule_sn|rule_tn``) and the
        corrosion exponent.
    link_diameter : float
        New link diameter in m.
    chain : {"studless", "stud"}
    settings : FatigueSettings, optional
        From :func:`fatigue_settings` (defaults if omitted): design life, corrosion rate and
        step, mean-stress correction, design-factor constants.
    corrosion : bool
        Apply the corrosion rate with its step rule (paper section 4.3); otherwise the
        rate is constant (the paper's main results).
    mean_tension : array_like, optional
        Mean tension in N broadcastable to ``damage_per_year``; needed with corrosion and a
        mean-stress correction (see :func:`corrosion_damage_factor`).
    line_axis : int
        Axis of the lines, for the DNV damage ratio ``dF`` (:func:`adjacent_damage_ratio`).

    Returns
    -------
    dict of ndarray
        ``lifecycle_damage`` (..., nline): damage accumulated over the design life;
        ``fatigue_life_years`` (..., nline): age at which the damage reaches 1;
        ``damage_ratio`` (...): ``dF``;
        ``design_fatigue_factor`` (...): DFF of the system (DNV from ``dF``, or API);
        ``design_life_years`` (..., nline): age at which DFF x damage reaches 1;
        ``passes`` (..., nline): ``DFF x lifecycle_damage <= 1``.
    """
    st = settings or FatigueSettings.from_config({})
    d = np.moveaxis(np.asarray(damage_per_year, dtype=float), line_axis, -1)
    if np.any(~np.isfinite(d)) or np.any(d < 0):
        raise ValueError("damage_per_year must be finite and >= 0")
    sn, tn = get_curves(chain, st.curves)
    m = {"sn": sn.m, "tn": tn.m}.get(curve)
    if m is None:
        raise ValueError(f"curve must be 'sn' or 'tn', got {curve!r}")
    ratio = adjacent_damage_ratio(d, axis=-1) if d.shape[-1] >= 2 else np.zeros(d.shape[:-1])
    dff = st.design_factor(curve, ratio)
    mt = (
        None
        if mean_tension is None
        else np.moveaxis(np.broadcast_to(mean_tension, np.shape(damage_per_year)), line_axis, -1)
    )
    rate_factor = None
    if corrosion and st.corrosion_rate > 0:
        horizon = 0.95 * link_diameter / st.corrosion_rate

        def rate_factor(ages: np.ndarray) -> np.ndarray:
            a = np.minimum(ages, horizon).reshape((-1,) + (1,) * d.ndim)
            return corrosion_damage_factor(
                link_diameter, a, curve=curve, m=m, rate=st.corrosion_rate, mean_stress=st.mean_stress,
                mean_tension=mt, ultimate=st.ultimate, yield_=st.yield_,
            ) * np.ones(d.shape)  # fmt: skip

    if rate_factor is None:
        life_damage = d * st.design_life
    else:
        _, cum = lifetime_damage_with_corrosion(
            lambda a: d[None] * rate_factor(a), st.design_life, step=st.corrosion_step
        )
        life_damage = cum[-1]
    life = fatigue_life(d, rate_factor=rate_factor, step=st.corrosion_step)
    design_life = fatigue_life(d, design_factor=dff[..., None], rate_factor=rate_factor, step=st.corrosion_step)
    back = lambda a: np.moveaxis(a, -1, line_axis)  # noqa: E731
    return {
        "lifecycle_damage": back(life_damage),
        "fatigue_life_years": back(life),
        "damage_ratio": ratio,
        "design_fatigue_factor": dff,
        "design_life_years": back(design_life),
        "passes": back(dff[..., None] * life_damage <= 1.0),
    }
