"""Rainflow counting: compiled (numba) kernels on the exact turning points.

Rainflow counting follows ASTM E1049-85 section 5.4.4 (three-point rule) on the exact
turning points, with no binning; the residue counts as half cycles (``residue="half"``)
or is closed as if the record repeated (``residue="close"``: the residue is joined with
itself and its closed cycles are counted, as Marsh et al. 2016 / fatpack).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
from numba import njit

RESIDUE_METHODS = ("half", "close")


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
