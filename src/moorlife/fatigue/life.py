"""Mooring-line fatigue: rainflow counting, S-N and T-N Miner damage, corrosion,
mean-stress corrections and design fatigue factors (paper section 2.4 and section 4).

Everything here is a pure numerical kernel: numpy in, numpy out, SI units unless a
name says otherwise (stresses in MPa, as the S-N curves are written).

Conventions
-----------
* Tension in N, link (bar) diameter ``d`` in **m**, time in s, ages in years.
* S-N (DNVGL-OS-E301): ``N = a_D * S**-m`` with ``S`` the stress range in MPa on the
  nominal area of the two legs of a link, ``A_c = 2 * pi * d**2 / 4``.
* T-N (API RP 2SK): ``N * R**M = K`` with ``R = tension range / RBS`` (reference
  breaking strength = the chain's MBS).
* Miner's sum ``D = sum(n_i / N_i)``, no endurance limit (every cycle counts).
* Damage of a simulated record is reported **per hour of sea state**: the record's
  damage times ``3600 / duration``.

Rainflow counting follows ASTM E1049-85 section 5.4.4 (three-point rule) on the exact
turning points, with no binning; the residue counts as half cycles (``residue="half"``)
or is closed as if the record repeated (``residue="close"``: the residue is joined with
itself and its closed cycles are counted, as Marsh et al. 2016 / fatpack).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt
from numba import njit

__all__ = [
    "SNCurve",
    "TNCurve",
    "DEFAULT_CURVES",
    "FatigueSettings",
    "fatigue_settings",
    "get_curves",
    "turning_points",
    "rainflow",
    "stress_area",
    "r4s_break_load",
    "corroded_properties",
    "mean_stress_factor",
    "sn_damage",
    "tn_damage",
    "cycle_damage",
    "hourly_damage",
    "hourly_damage_xr",
    "corrosion_damage_factor",
    "lifetime_damage_with_corrosion",
    "fatigue_life",
    "design_fatigue_factor",
    "adjacent_damage_ratio",
    "annual_damage",
    "life_summary",
    "spectral_moments",
    "narrowband_damage",
    "dirlik_damage",
    "dirlik_pdf",
]

SECONDS_PER_HOUR = 3600.0
HOURS_PER_YEAR = 8766.0  # 365.25 days
MEAN_STRESS_METHODS = ("none", "goodman", "soderberg", "gerber")
RESIDUE_METHODS = ("half", "close")
CHAINS = ("studless", "stud")


# ---------------------------------------------------------------------------------------
# curves and settings
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class SNCurve:
    """S-N curve ``N = a_d * S**-m`` (``S`` stress range in MPa)."""

    a_d: float
    m: float

    def __post_init__(self) -> None:
        if not (self.a_d > 0 and self.m > 0):
            raise ValueError(f"S-N curve needs a_d > 0 and m > 0, got a_d={self.a_d!r}, m={self.m!r}")


@dataclass(frozen=True)
class TNCurve:
    """T-N curve ``N * (T_range / RBS)**m = k``."""

    k: float
    m: float

    def __post_init__(self) -> None:
        if not (self.k > 0 and self.m > 0):
            raise ValueError(f"T-N curve needs k > 0 and m > 0, got k={self.k!r}, m={self.m!r}")


#: DNVGL-OS-E301 (Ch.2 Sec.2) S-N and API RP 2SK T-N curves for chain; also the
#: ``fatigue.curves`` defaults of ``config/config.yaml``.
DEFAULT_CURVES: dict[str, dict[str, dict[str, float]]] = {
    "sn": {"studless": {"a_d": 6.0e10, "m": 3.0}, "stud": {"a_d": 1.2e11, "m": 3.0}},
    "tn": {"studless": {"k": 316.0, "m": 3.0}, "stud": {"k": 1000.0, "m": 3.0}},
}


def get_curves(chain: str = "studless", curves: Mapping[str, Any] | None = None) -> tuple[SNCurve, TNCurve]:
    """The S-N and T-N curves of a chain type.

    Parameters
    ----------
    chain : {"studless", "stud"}
        Chain type (column ``chain`` of ``config/mooring_systems.tsv``).
    curves : mapping, optional
        ``{"sn": {chain: {"a_d", "m"}}, "tn": {chain: {"k", "m"}}}`` as in the
        ``fatigue.curves`` config section; :data:`DEFAULT_CURVES` if omitted.

    Raises
    ------
    ValueError
        If the chain type or a curve entry is missing or invalid.
    """
    curves = DEFAULT_CURVES if curves is None else curves
    try:
        sn = curves["sn"][chain]
        tn = curves["tn"][chain]
    except KeyError as exc:
        raise ValueError(
            f"fatigue curves: no entry for chain {chain!r} ({exc.args[0]!r} missing); "
            f"available S-N: {sorted(curves.get('sn', {}))}, T-N: {sorted(curves.get('tn', {}))}"
        ) from None
    if isinstance(sn, SNCurve) and isinstance(tn, TNCurve):
        return sn, tn
    try:
        return SNCurve(float(sn["a_d"]), float(sn["m"])), TNCurve(float(tn["k"]), float(tn["m"]))
    except KeyError as exc:
        raise ValueError(f"fatigue curves for chain {chain!r}: key {exc.args[0]!r} missing") from None


@dataclass(frozen=True)
class FatigueSettings:
    """The ``fatigue:`` config section, in the units the kernels take.

    Build it with :func:`fatigue_settings`. ``corrosion_rate`` is in m/year here
    (``mm/year`` in the config file).
    """

    curves: Mapping[str, Any] = field(default_factory=lambda: DEFAULT_CURVES)
    design_life: float = 25.0
    corrosion_rate: float = 0.2e-3
    corrosion_step: float = 5.0
    mean_stress: str = "none"
    ultimate: float = 960.0
    yield_: float = 700.0
    residue: str = "half"
    dnv_base: float = 5.0
    dnv_threshold: float = 0.8
    dnv_increment: float = 3.0
    dnv_span: float = 0.2
    api_factor: float = 3.0
    rule_sn: str = "dnv"
    rule_tn: str = "api"

    def damage_kwargs(self) -> dict[str, Any]:
        """Keyword arguments of :func:`hourly_damage` (without corrosion age)."""
        return {
            "curves": self.curves,
            "mean_stress": self.mean_stress,
            "ultimate": self.ultimate,
            "yield_": self.yield_,
            "residue": self.residue,
            "corrosion_rate": self.corrosion_rate,
        }

    def design_factor(self, curve: str, damage_ratio: npt.ArrayLike = 0.0) -> np.ndarray:
        """Design fatigue factor for a curve family (``"sn"`` or ``"tn"``), see
        :func:`design_fatigue_factor`; the rule per family is ``design_factor.sn|tn``."""
        rule = {"sn": self.rule_sn, "tn": self.rule_tn}.get(curve)
        if rule is None:
            raise ValueError(f"curve must be 'sn' or 'tn', got {curve!r}")
        if rule == "api":
            return np.broadcast_to(np.float64(self.api_factor), np.shape(damage_ratio)).copy()
        return design_fatigue_factor(
            damage_ratio,
            base=self.dnv_base,
            threshold=self.dnv_threshold,
            increment=self.dnv_increment,
            span=self.dnv_span,
        )


def fatigue_settings(section: Mapping[str, Any] | None = None, source: str = "config.yaml") -> FatigueSettings:
    """Build :class:`FatigueSettings` from the ``fatigue:`` config section.

    Parameters
    ----------
    section : mapping, optional
        The validated ``config["fatigue"]`` (schema defaults filled in). Missing keys
        take the defaults of the schema.
    source : str
        Quoted in error messages.
    """
    s = dict(section or {})
    cor = dict(s.get("corrosion", {}))
    ms = dict(s.get("mean_stress", {}))
    df = dict(s.get("design_factor", {}))
    dnv = dict(df.get("dnv", {}))
    method = ms.get("method", "none")
    if method not in MEAN_STRESS_METHODS:
        raise ValueError(f"{source}: fatigue.mean_stress.method = {method!r}; expected one of {MEAN_STRESS_METHODS}")
    residue = s.get("residue", "half")
    if residue not in RESIDUE_METHODS:
        raise ValueError(f"{source}: fatigue.residue = {residue!r}; expected one of {RESIDUE_METHODS}")
    curves = s.get("curves", DEFAULT_CURVES)
    for chain in CHAINS:  # fail early with the key named
        try:
            get_curves(chain, curves)
        except ValueError as exc:
            raise ValueError(f"{source}: fatigue.curves: {exc}") from None
    return FatigueSettings(
        curves=curves,
        design_life=float(s.get("design_life", 25.0)),
        corrosion_rate=float(cor.get("rate", 0.2)) * 1e-3,
        corrosion_step=float(cor.get("step", 5.0)),
        mean_stress=method,
        ultimate=float(ms.get("ultimate", 960.0)),
        yield_=float(ms.get("yield", 700.0)),
        residue=residue,
        dnv_base=float(dnv.get("base", 5.0)),
        dnv_threshold=float(dnv.get("threshold", 0.8)),
        dnv_increment=float(dnv.get("increment", 3.0)),
        dnv_span=float(dnv.get("span", 0.2)),
        api_factor=float(df.get("api", 3.0)),
        rule_sn=str(df.get("sn", "dnv")),
        rule_tn=str(df.get("tn", "api")),
    )


# ---------------------------------------------------------------------------------------
# rainflow counting (numba kernels)
# ---------------------------------------------------------------------------------------
@njit(cache=True)
def _turning_indices(x):  # pragma: no cover - compiled
    """First point, every strict reversal (plateaus collapsed to their last sample), last point."""
    n = x.shape[0]
    out = np.empty(max(n, 1), np.int64)
    if n == 0:
        return out[:0]
    out[0] = 0
    k = 1
    if n == 1:
        return out[:1]
    last = x[0]
    last_i = 0
    sgn = 0
    for i in range(1, n):
        d = x[i] - last
        if d == 0.0:
            last_i = i
            continue
        s = 1 if d > 0.0 else -1
        if sgn != 0 and s != sgn:
            out[k] = last_i
            k += 1
        sgn = s
        last = x[i]
        last_i = i
    out[k] = n - 1
    k += 1
    return out[:k]


@njit(cache=True)
def _count_turning(rev, close):  # pragma: no cover - compiled
    """ASTM E1049-85 5.4.4 on turning-point values ``rev``; returns (range, mean, count)."""
    nr = rev.shape[0]
    cap = 2 * nr + 2
    rng = np.empty(cap)
    mean = np.empty(cap)
    cnt = np.empty(cap)
    nc = 0
    buf = np.empty(max(nr, 1))
    lo = 0
    hi = 0
    for j in range(nr):
        buf[hi] = rev[j]
        hi += 1
        while hi - lo >= 3:
            x_rng = abs(buf[hi - 1] - buf[hi - 2])
            y_rng = abs(buf[hi - 2] - buf[hi - 3])
            if x_rng < y_rng:
                break
            if hi - lo == 3:
                # Y contains the starting point: a half cycle, counted with the residue below
                lo += 1
            else:
                rng[nc] = y_rng
                mean[nc] = 0.5 * (buf[hi - 2] + buf[hi - 3])
                cnt[nc] = 1.0
                nc += 1
                buf[hi - 3] = buf[hi - 1]
                hi -= 2
    # buf[:hi] is the full residue: points discarded as half cycles, then the stack
    if not close:
        for j in range(hi - 1):
            rng[nc] = abs(buf[j + 1] - buf[j])
            mean[nc] = 0.5 * (buf[j + 1] + buf[j])
            cnt[nc] = 0.5
            nc += 1
        return rng[:nc], mean[:nc], cnt[:nc]
    if hi < 2:
        return rng[:nc], mean[:nc], cnt[:nc]
    # close the residue: join it with itself (keeping the peak-valley condition at the
    # join) and extract the closed cycles with the four-point rule
    res = buf[:hi]
    if hi == 2 and res[1] == res[0]:
        return rng[:nc], mean[:nc], cnt[:nc]
    joined = np.empty(2 * hi)
    nj = 0
    d_end = res[hi - 1] - res[hi - 2]
    d_start = res[1] - res[0]
    d_join = res[0] - res[hi - 1]
    t1 = d_end * d_start
    t2 = d_end * d_join
    # t2 < 0: the residue's last point is a reversal; the first point of the repeat is
    # one only if the repeat starts in the direction the residue ended (t1 > 0).
    # t2 > 0: the last point is not a reversal; the first of the repeat is one iff t1 < 0.
    # t2 = 0: the two coincide; keep one, and only if the direction turns there (t1 < 0).
    if t2 < 0.0:
        drop_end = False
        drop_start = t1 < 0.0
    elif t2 > 0.0:
        drop_end = True
        drop_start = t1 > 0.0
    else:
        drop_end = t1 > 0.0
        drop_start = True
    n1 = hi - 1 if drop_end else hi
    for j in range(n1):
        joined[nj] = res[j]
        nj += 1
    for j in range(1 if drop_start else 0, hi):
        joined[nj] = res[j]
        nj += 1
    st = np.empty(nj)
    ns = 0
    for j in range(nj):
        st[ns] = joined[j]
        ns += 1
        while ns >= 4:
            s0 = st[ns - 4]
            s1 = st[ns - 3]
            s2 = st[ns - 2]
            s3 = st[ns - 1]
            d1 = abs(s1 - s0)
            d2 = abs(s2 - s1)
            d3 = abs(s3 - s2)
            if d2 <= d1 and d2 <= d3:
                rng[nc] = d2
                mean[nc] = 0.5 * (s1 + s2)
                cnt[nc] = 1.0
                nc += 1
                st[ns - 3] = s3
                ns -= 2
            else:
                break
    return rng[:nc], mean[:nc], cnt[:nc]


@njit(cache=True)
def _damage_records(x2d, area, mbs, a_d, m_sn, k_tn, m_tn, ms_n, ms_r, close):  # pragma: no cover - compiled
    """Rainflow + S-N / T-N Miner sums of each row of ``x2d`` (tension in N).

    ``ms_n`` = 0 (no mean-stress correction), 1 (Goodman / Soderberg) or 2 (Gerber) with
    ``ms_r`` the reference strength in MPa. A cycle whose mean stress reaches ``ms_r``
    makes the S-N damage ``inf`` (reported by the caller).
    """
    nrec = x2d.shape[0]
    dsn = np.empty(nrec)
    dtn = np.empty(nrec)
    cube_sn = m_sn == 3.0
    cube_tn = m_tn == 3.0
    for i in range(nrec):
        x = x2d[i]
        r, mu, c = _count_turning(x[_turning_indices(x)], close)
        inv_a = 1e-6 / area[i]
        inv_b = 1.0 / mbs[i]
        acc_sn = 0.0
        acc_tn = 0.0
        for j in range(r.shape[0]):
            s = r[j] * inv_a
            if ms_n > 0:
                sm = mu[j] * inv_a
                if sm > 0.0:
                    f = 1.0 - (sm / ms_r) ** ms_n
                    if f <= 0.0:
                        acc_sn = np.inf
                        continue
                    s = s / f
            t = r[j] * inv_b
            acc_sn += c[j] * (s * s * s if cube_sn else s**m_sn)
            acc_tn += c[j] * (t * t * t if cube_tn else t**m_tn)
        dsn[i] = acc_sn / a_d
        dtn[i] = acc_tn / k_tn
    return dsn, dtn


@njit(cache=True)
def _first_nonfinite(x):  # pragma: no cover - compiled
    for i in range(x.shape[0]):
        if not np.isfinite(x[i]):
            return i
    return -1


def _as_series(series: npt.ArrayLike, name: str = "series") -> np.ndarray:
    x = np.ascontiguousarray(series, dtype=np.float64)
    if x.ndim != 1:
        raise ValueError(f"{name} must be one-dimensional (nt,), got shape {x.shape}")
    bad = ~np.isfinite(x)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ValueError(f"{name}: non-finite value {x[i]!r} at sample {i}")
    return x


def turning_points(series: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Exact turning points (reversals) of a record.

    Parameters
    ----------
    series : array_like, shape (nt,)
        The record.

    Returns
    -------
    values : ndarray, shape (nr,)
        The first sample, every local extremum (a plateau counts once), the last sample.
    indices : ndarray of int64, shape (nr,)
        Their positions in ``series`` (the last sample of a plateau).
    """
    x = _as_series(series)
    idx = _turning_indices(x)
    return x[idx], idx


def rainflow(series: npt.ArrayLike, *, residue: str = "half") -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rainflow cycles of a record (ASTM E1049-85, section 5.4.4), with no binning.

    Parameters
    ----------
    series : array_like, shape (nt,)
        Load record (any unit).
    residue : {"half", "close"}
        ``"half"`` (ASTM): every range left in the residue counts as a half cycle.
        ``"close"``: the record is treated as repeating; the residue is joined with
        itself and its closed cycles are added as full cycles (no half cycles remain).

    Returns
    -------
    ranges : ndarray, shape (nc,)
        Cycle ranges (peak to valley), same unit as ``series``.
    means : ndarray, shape (nc,)
        Cycle means.
    counts : ndarray, shape (nc,)
        1.0 for full cycles, 0.5 for half cycles.

    Notes
    -----
    Two samples ``[a, b]`` give one half cycle of range ``|b - a|``; a constant record
    gives one half cycle of range 0. (The ``rainflow`` package returns no cycle for a
    two-sample record; for three samples or more both agree.)

    Examples
    --------
    The ASTM E1049-85 example (its Fig. 6):

    >>> r, m, c = rainflow([-2, 1, -3, 5, -1, 3, -4, 4, -2])
    >>> sorted(zip(r.tolist(), c.tolist()))
    [(3.0, 0.5), (4.0, 0.5), (4.0, 1.0), (6.0, 0.5), (8.0, 0.5), (8.0, 0.5), (9.0, 0.5)]
    """
    if residue not in RESIDUE_METHODS:
        raise ValueError(f"residue must be one of {RESIDUE_METHODS}, got {residue!r}")
    x = _as_series(series)
    if x.size < 2:
        empty = np.empty(0)
        return empty, empty.copy(), empty.copy()
    rev = x[_turning_indices(x)]
    return _count_turning(rev, residue == "close")


# ---------------------------------------------------------------------------------------
# chain properties, corrosion, mean stress
# ---------------------------------------------------------------------------------------
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


# ---------------------------------------------------------------------------------------
# Miner damage
# ---------------------------------------------------------------------------------------
def sn_damage(ranges_mpa: npt.ArrayLike, counts: npt.ArrayLike, curve: SNCurve | Mapping[str, float]) -> np.ndarray:
    """Miner damage on an S-N curve, ``sum(n_i * S_i**m) / a_d``, no endurance limit.

    Parameters
    ----------
    ranges_mpa : array_like, shape (..., nc)
        Stress ranges in MPa.
    counts : array_like, shape (..., nc)
        Cycle counts (1 or 0.5 from :func:`rainflow`, or any weights).
    curve : SNCurve or mapping with ``a_d`` and ``m``

    Returns
    -------
    ndarray, shape (...)
    """
    c = curve if isinstance(curve, SNCurve) else SNCurve(float(curve["a_d"]), float(curve["m"]))
    s = np.asarray(ranges_mpa, dtype=float)
    return np.sum(np.asarray(counts, dtype=float) * s**c.m, axis=-1) / c.a_d


def tn_damage(
    ranges_n: npt.ArrayLike, counts: npt.ArrayLike, rbs: npt.ArrayLike, curve: TNCurve | Mapping[str, float]
) -> np.ndarray:
    """Miner damage on a T-N curve, ``sum(n_i * (T_i / RBS)**m) / k``.

    Parameters
    ----------
    ranges_n : array_like, shape (..., nc)
        Tension ranges in N.
    counts : array_like, shape (..., nc)
    rbs : array_like, broadcastable to (...)
        Reference breaking strength (MBS) in N.
    curve : TNCurve or mapping with ``k`` and ``m``

    Returns
    -------
    ndarray, shape (...)
    """
    c = curve if isinstance(curve, TNCurve) else TNCurve(float(curve["k"]), float(curve["m"]))
    r = np.asarray(ranges_n, dtype=float) / np.asarray(rbs, dtype=float)[..., None]
    return np.sum(np.asarray(counts, dtype=float) * r**c.m, axis=-1) / c.k


def cycle_damage(
    ranges_n: np.ndarray,
    means_n: np.ndarray,
    counts: np.ndarray,
    *,
    link_diameter: float,
    mbs: float,
    chain: str = "studless",
    curves: Mapping[str, Any] | None = None,
    mean_stress: str = "none",
    ultimate: float = 960.0,
    yield_: float = 700.0,
) -> tuple[float, float]:
    """S-N and T-N Miner damage of a set of tension cycles (of one record, not scaled).

    Parameters
    ----------
    ranges_n, means_n, counts : ndarray, shape (nc,)
        Output of :func:`rainflow` on a tension record in N.
    link_diameter : float
        Link diameter in m (already corroded if relevant).
    mbs : float
        Minimum breaking strength in N (already corroded if relevant).
    chain, curves
        See :func:`get_curves`.
    mean_stress, ultimate, yield_
        See :func:`mean_stress_factor`. The correction applies to the S-N damage only,
        cycle by cycle (equivalent zero-mean range ``S / factor(mean stress of the
        cycle)``); the T-N curves of API RP 2SK carry no mean-load correction.

    Returns
    -------
    damage_sn, damage_tn : float
    """
    sn, tn = get_curves(chain, curves)
    area = float(stress_area(link_diameter))
    s = ranges_n / area * 1e-6
    if mean_stress != "none":
        s = s / mean_stress_factor(means_n / area * 1e-6, mean_stress, ultimate, yield_)
    d_sn = float(np.dot(counts, s**sn.m)) / sn.a_d
    d_tn = float(np.dot(counts, (ranges_n / float(mbs)) ** tn.m)) / tn.k
    return d_sn, d_tn


def hourly_damage(
    tension: npt.ArrayLike,
    duration: float,
    *,
    link_diameter: npt.ArrayLike,
    mbs: npt.ArrayLike,
    chain: str = "studless",
    curves: Mapping[str, Any] | None = None,
    mean_stress: str = "none",
    corrosion_years: float = 0.0,
    corrosion_rate: float = 0.2e-3,
    ultimate: float = 960.0,
    yield_: float = 700.0,
    residue: str = "half",
) -> tuple[np.ndarray, np.ndarray]:
    """Miner damage per hour of sea state from simulated fairlead tension records.

    Parameters
    ----------
    tension : array_like, shape (..., nt)
        Tension records in N (any leading dims, e.g. ``(case, line, nt)``).
    duration : float
        Duration in s that each record represents (``nt * dt``); damage is scaled by
        exactly ``3600 / duration``.
    link_diameter : array_like, broadcastable to (...)
        New link diameter in m.
    mbs : array_like, broadcastable to (...)
        New minimum breaking strength (the T-N reference breaking strength) in N.
    chain : {"studless", "stud"}
    curves : mapping, optional
        The ``fatigue.curves`` config section (default :data:`DEFAULT_CURVES`).
    mean_stress : {"none", "goodman", "soderberg", "gerber"}
        Mean-stress correction of the S-N ranges (see :func:`cycle_damage`).
    corrosion_years : float
        Age of the chain; diameter and MBS are reduced by :func:`corroded_properties`.
    corrosion_rate : float
        Diameter loss in m/year.
    ultimate, yield_ : float
        MPa, for the mean-stress correction.
    residue : {"half", "close"}
        Rainflow residue handling, see :func:`rainflow`.

    Returns
    -------
    damage_sn, damage_tn : ndarray, shape (...)
        Dimensionless Miner damage per hour.
    """
    t = np.asarray(tension, dtype=np.float64)
    if t.ndim < 1 or t.shape[-1] < 2:
        raise ValueError(f"tension must have shape (..., nt) with nt >= 2, got {t.shape}")
    if not (np.isfinite(duration) and duration > 0):
        raise ValueError(f"duration must be a positive number of seconds, got {duration!r}")
    if residue not in RESIDUE_METHODS:
        raise ValueError(f"residue must be one of {RESIDUE_METHODS}, got {residue!r}")
    if mean_stress not in MEAN_STRESS_METHODS:
        raise ValueError(f"mean_stress must be one of {MEAN_STRESS_METHODS}, got {mean_stress!r}")
    lead = t.shape[:-1]
    d, m = corroded_properties(link_diameter, mbs, corrosion_years, corrosion_rate)
    area = np.ascontiguousarray(np.broadcast_to(stress_area(d), lead), dtype=np.float64).reshape(-1)
    rbs = np.ascontiguousarray(np.broadcast_to(m, lead), dtype=np.float64).reshape(-1)
    if np.any(~(rbs > 0)):
        raise ValueError(f"mbs must be positive (N), got {mbs!r}")
    flat = np.ascontiguousarray(t.reshape(-1, t.shape[-1]))
    first_bad = _first_nonfinite(flat.reshape(-1))
    if first_bad >= 0:
        row, col = divmod(first_bad, flat.shape[1])
        rec = tuple(int(v) for v in np.unravel_index(int(row), lead))
        raise ValueError(f"tension: non-finite value at record {rec}, sample {int(col)}")
    sn, tn = get_curves(chain, curves)
    ms_n, ms_r = {"none": (0, 1.0), "goodman": (1, ultimate), "soderberg": (1, yield_), "gerber": (2, ultimate)}[
        mean_stress
    ]
    out_sn, out_tn = _damage_records(
        flat, area, rbs, sn.a_d, sn.m, tn.k, tn.m, ms_n, float(ms_r), residue == "close"
    )
    if np.any(np.isinf(out_sn)):
        i = int(np.flatnonzero(np.isinf(out_sn))[0])
        rec = tuple(int(v) for v in np.unravel_index(i, lead))
        raise ValueError(
            f"tension record {rec}: a cycle mean stress reaches the {mean_stress} limit "
            f"({ms_r} MPa): no fatigue capacity left"
        )
    scale = SECONDS_PER_HOUR / float(duration)
    return (out_sn * scale).reshape(lead), (out_tn * scale).reshape(lead)


def hourly_damage_xr(tension: Any, *, dim: str = "t", **kwargs: Any) -> Any:
    """xarray adapter of :func:`hourly_damage`.

    Parameters
    ----------
    tension : xarray.DataArray
        Tension in N with a uniformly spaced time coordinate ``dim`` in s.
    dim : str
        The time dimension (core dimension, removed from the result).
    **kwargs
        Keyword arguments of :func:`hourly_damage` (``link_diameter``, ``mbs``, ...);
        ``duration`` defaults to ``n * dt`` from the coordinate.

    Returns
    -------
    xarray.Dataset
        ``damage_sn`` and ``damage_tn`` (per hour of sea state) over the other dimensions.
    """
    import xarray as xr

    if "duration" not in kwargs:
        t = np.asarray(tension[dim].values, dtype=float)
        dt = np.diff(t)
        if t.size < 2 or not np.allclose(dt, dt[0], rtol=1e-6):
            raise ValueError(f"tension: coordinate {dim!r} must be uniformly spaced seconds to infer the duration")
        kwargs["duration"] = float(t.size * dt[0])
    duration = kwargs.pop("duration")
    sn, tn = xr.apply_ufunc(
        lambda x: hourly_damage(x, duration, **kwargs),
        tension,
        input_core_dims=[[dim]],
        output_core_dims=[[], []],
        dask="parallelized",
        output_dtypes=[float, float],
    )
    ds = xr.Dataset({"damage_sn": sn, "damage_tn": tn})
    ds["damage_sn"].attrs = {"units": "1", "long_name": "S-N (DNVGL-OS-E301) Miner damage per hour of sea state"}
    ds["damage_tn"].attrs = {"units": "1", "long_name": "T-N (API RP 2SK) Miner damage per hour of sea state"}
    return ds


# ---------------------------------------------------------------------------------------
# corrosion over the life, fatigue life, design factors
# ---------------------------------------------------------------------------------------
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
    st = settings or FatigueSettings()
    d = np.moveaxis(np.asarray(damage_per_year, dtype=float), line_axis, -1)
    if np.any(~np.isfinite(d)) or np.any(d < 0):
        raise ValueError("damage_per_year must be finite and >= 0")
    sn, tn = get_curves(chain, st.curves)
    m = {"sn": sn.m, "tn": tn.m}.get(curve)
    if m is None:
        raise ValueError(f"curve must be 'sn' or 'tn', got {curve!r}")
    ratio = adjacent_damage_ratio(d, axis=-1) if d.shape[-1] >= 2 else np.zeros(d.shape[:-1])
    dff = st.design_factor(curve, ratio)
    mt = None if mean_tension is None else np.moveaxis(np.broadcast_to(mean_tension, np.shape(damage_per_year)), line_axis, -1)
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
        _, cum = lifetime_damage_with_corrosion(lambda a: d[None] * rate_factor(a), st.design_life, step=st.corrosion_step)
        life_damage = cum[-1]
    life = fatigue_life(d, rate_factor=rate_factor, step=st.corrosion_step)
    design_life = fatigue_life(d, design_factor=dff[..., None], rate_factor=rate_factor, step=st.corrosion_step)
    back = (lambda a: np.moveaxis(a, -1, line_axis))  # noqa: E731
    return {
        "lifecycle_damage": back(life_damage),
        "fatigue_life_years": back(life),
        "damage_ratio": ratio,
        "design_fatigue_factor": dff,
        "design_life_years": back(design_life),
        "passes": back(dff[..., None] * life_damage <= 1.0),
    }


# ---------------------------------------------------------------------------------------
# spectral (frequency-domain) estimates
# ---------------------------------------------------------------------------------------
def spectral_moments(frequency: npt.ArrayLike, psd: npt.ArrayLike, orders=(0, 1, 2, 4)) -> np.ndarray:
    """Spectral moments ``m_n = integral f**n S(f) df`` (trapezoidal rule).

    Parameters
    ----------
    frequency : array_like, shape (nf,)
        Frequencies in Hz, increasing.
    psd : array_like, shape (..., nf)
        One-sided power spectral density, unit**2 / Hz.
    orders : sequence of float

    Returns
    -------
    ndarray, shape (norders, ...)
    """
    f = np.asarray(frequency, dtype=float)
    s = np.asarray(psd, dtype=float)
    return np.stack([np.trapezoid(f**n * s, f, axis=-1) for n in orders])


def narrowband_damage(m0: npt.ArrayLike, m2: npt.ArrayLike, duration: float, a: float, m: float) -> np.ndarray:
    """Closed-form narrow-band (Rayleigh) Miner damage of a Gaussian process.

    ``D = nu0 * T * (2 sqrt(2 m0))**m * Gamma(1 + m/2) / a``, ``nu0 = sqrt(m2/m0)``
    (Bendat 1964): cycles at the mean up-crossing rate, ranges twice a Rayleigh
    amplitude.

    Parameters
    ----------
    m0, m2 : array_like
        Spectral moments (unit**2, unit**2/s**2) of the load in the S-N curve's unit.
    duration : float
        s.
    a, m : float
        S-N curve ``N = a S**-m``.

    Returns
    -------
    ndarray
        Damage over ``duration``.
    """
    m0 = np.asarray(m0, dtype=float)
    nu0 = np.sqrt(np.asarray(m2, dtype=float) / m0)
    return nu0 * duration * (2.0 * np.sqrt(2.0 * m0)) ** m * math.gamma(1.0 + m / 2.0) / a


def _dirlik_coefficients(frequency: npt.ArrayLike, psd: npt.ArrayLike) -> tuple[np.ndarray, ...]:
    m0, m1, m2, m4 = spectral_moments(frequency, psd, (0, 1, 2, 4))
    xm = m1 / m0 * np.sqrt(m2 / m4)
    g = m2 / np.sqrt(m0 * m4)
    d1 = 2.0 * (xm - g**2) / (1.0 + g**2)
    r = (g - xm - d1**2) / (1.0 - g - d1 + d1**2)
    d2 = (1.0 - g - d1 + d1**2) / (1.0 - r)
    d3 = 1.0 - d1 - d2
    q = 1.25 * (g - d3 - d2 * r) / d1
    return m0, np.sqrt(m4 / m2), d1, d2, d3, q, r


def dirlik_pdf(ranges: npt.ArrayLike, frequency: npt.ArrayLike, psd: npt.ArrayLike) -> np.ndarray:
    """Dirlik (1985) probability density of rainflow ranges of a Gaussian process.

    Parameters
    ----------
    ranges : array_like, shape (nr,)
        Ranges ``S`` (unit of the load).
    frequency : array_like, shape (nf,)
        Hz.
    psd : array_like, shape (nf,)
        One-sided PSD of the load per Hz.

    Returns
    -------
    ndarray, shape (nr,)
        ``p(S)`` in 1/unit; integrates to 1 over ``S >= 0``.
    """
    m0, _, d1, d2, d3, q, r = _dirlik_coefficients(frequency, psd)
    z = np.asarray(ranges, dtype=float) / (2.0 * np.sqrt(m0))
    dens = d1 / q * np.exp(-z / q) + d2 * z / r**2 * np.exp(-(z**2) / (2.0 * r**2)) + d3 * z * np.exp(-(z**2) / 2.0)
    return dens / (2.0 * np.sqrt(m0))


def dirlik_damage(
    frequency: npt.ArrayLike, psd: npt.ArrayLike, duration: float, a: float, m: float
) -> np.ndarray:
    """Dirlik (1985) spectral estimate of rainflow Miner damage of a Gaussian process.

    Parameters
    ----------
    frequency : array_like, shape (nf,)
        Hz.
    psd : array_like, shape (..., nf)
        One-sided PSD of the load (in the S-N curve's unit) per Hz.
    duration : float
        s.
    a, m : float
        S-N curve ``N = a S**-m``.

    Returns
    -------
    ndarray, shape (...)
        Damage over ``duration``.

    Notes
    -----
    With ``x_m = m1/m0 sqrt(m2/m4)``, ``gamma = m2/sqrt(m0 m4)``, ``Z = S / (2 sqrt(m0))``
    the range density is a mixture of an exponential and two Rayleigh terms with weights
    ``D1, D2, D3`` and scales ``Q, R, 1``; the damage is
    ``nu_p T / a (2 sqrt m0)**m [D1 Q**m Gamma(1+m) + sqrt(2)**m Gamma(1+m/2) (D2 |R|**m + D3)]``
    with ``nu_p = sqrt(m4/m2)`` the rate of peaks.
    """
    m0, nu_p, d1, d2, d3, q, r = _dirlik_coefficients(frequency, psd)
    moment = d1 * q**m * math.gamma(1.0 + m) + np.sqrt(2.0) ** m * math.gamma(1.0 + m / 2.0) * (
        d2 * np.abs(r) ** m + d3
    )
    return nu_p * duration / a * (2.0 * np.sqrt(m0)) ** m * moment
