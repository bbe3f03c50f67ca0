"""Rainflow counting: compiled (numba) kernels on the exact turning points.

Rainflow counting follows ASTM E1049-85 section 5.4.4 (three-point rule) on the exact
turning points, with no binning; the residue counts as half cycles (``residue="half"``)
or is closed as if the record repeated (``residue="close"``: the cycles the residue still
closes are counted once, then the residue is joined with itself and the cycles that span
the join are counted, as Marsh et al. 2016 / fatpack). :func:`rainflow_reference` is a
plain-Python reading of the standard (5.4.4, and 5.4.5 for repeating histories) that the
compiled kernels are tested against.
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
    # The residue can still hold closed cycles: on exactly equal ranges (X = Y) the rule
    # above discards the starting point, which stays in the residue with a range that
    # closes later (3, 1, 3, 0: the range 1-3). Count them here, once; joined with itself
    # such a residue would give each of them twice (issue 20 item 12).
    hi, nc = _four_point(buf, hi, rng, mean, cnt, nc)
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
    _, nc = _four_point(joined, nj, rng, mean, cnt, nc)
    return rng[:nc], mean[:nc], cnt[:nc]


@njit(cache=True)
def _four_point(seq, n, rng, mean, cnt, nc):  # pragma: no cover - compiled
    """Four-point rule over ``seq[:n]``, in place: each closed cycle is appended to
    ``rng, mean, cnt`` from index ``nc``; returns ``(n_left, nc)``, ``seq[:n_left]`` the
    points left (a sequence in which no range is closed)."""
    ns = 0
    for j in range(n):
        seq[ns] = seq[j]
        ns += 1
        while ns >= 4:
            s0 = seq[ns - 4]
            s1 = seq[ns - 3]
            s2 = seq[ns - 2]
            s3 = seq[ns - 1]
            d1 = abs(s1 - s0)
            d2 = abs(s2 - s1)
            d3 = abs(s3 - s2)
            if d2 <= d1 and d2 <= d3:
                rng[nc] = d2
                mean[nc] = 0.5 * (s1 + s2)
                cnt[nc] = 1.0
                nc += 1
                seq[ns - 3] = s3
                ns -= 2
            else:
                break
    return ns, nc


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

    With ``"close"`` a record of ``k`` periods of a periodic signal has ``k`` times the
    cycles of one period, ties included (a sampled cosine: one cycle per period); the
    cycles are those of ASTM E1049-85 5.4.5 (:func:`rainflow_reference`).

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
# plain-Python reference (the compiled kernels above are tested against it)
# ---------------------------------------------------------------------------------------
def rainflow_reference(series: npt.ArrayLike, *, residue: str = "half") -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rainflow cycles by a literal, plain-Python reading of ASTM E1049-85; slow, for tests.

    The same cycles as :func:`rainflow`, written to be read rather than fast (as fatpack's
    pure-Python counter is): no compiled code, no shared helper but the input check.

    Parameters
    ----------
    series : array_like, shape (nt,)
        Load record.
    residue : {"half", "close"}
        ``"half"``: section 5.4.4, *Rainflow Counting* (three-point rule, the starting point
        discarded as a half cycle, the residue counted as half cycles). ``"close"``: section
        5.4.5, *Simplified Rainflow Counting for Repeating Histories*: the record, treated as
        one period of a periodic signal, is rearranged to start (and end) at its maximum
        peak, and every range is counted as a full cycle.

    Returns
    -------
    ranges, means, counts : ndarray
        As :func:`rainflow`, in the order ASTM counts them.
    """
    if residue not in RESIDUE_METHODS:
        raise ValueError(f"residue must be one of {RESIDUE_METHODS}, got {residue!r}")
    x = _as_series(series).tolist()
    cycles: list[tuple[float, float, float]] = []
    if len(x) >= 2 and residue == "half":
        _astm_5_4_4(_reversal_values(x), cycles)
    elif len(x) >= 2:
        k = x.index(max(x))
        _astm_5_4_5(_reversal_values(x[k:] + x[:k] + [x[k]]), cycles)
    out = np.array(cycles, dtype=float).reshape(-1, 3)
    return out[:, 0].copy(), out[:, 1].copy(), out[:, 2].copy()


def _reversal_values(x: list[float]) -> list[float]:
    """The first sample, every peak and valley (a plateau once), the last sample."""
    points = [x[0]]
    for v in x[1:]:
        if v == points[-1]:
            continue  # plateau
        if len(points) >= 2 and (points[-1] > points[-2]) == (v > points[-1]):
            points[-1] = v  # still rising (or falling): the last point was no reversal
        else:
            points.append(v)
    if len(points) == 1:
        points.append(x[-1])  # a constant record: its first and last samples
    return points


def _cycle(a: float, b: float, count: float) -> tuple[float, float, float]:
    return abs(b - a), 0.5 * (a + b), count


def _astm_5_4_4(points: list[float], cycles: list[tuple[float, float, float]]) -> None:
    # X: the range of the two most recent points; Y: the range before it; S: stack[0]
    stack: list[float] = []
    for p in points:
        stack.append(p)  # (1) read the next peak or valley
        while len(stack) >= 3:  # (2) fewer than three points: read on
            x_range = abs(stack[-1] - stack[-2])
            y_range = abs(stack[-2] - stack[-3])
            if x_range < y_range:  # (3a)
                break
            if len(stack) == 3:  # (4) Y contains S -> (5): a half cycle, S moves on
                cycles.append(_cycle(stack[0], stack[1], 0.5))
                del stack[0]
            else:  # (4) one cycle; discard both points of Y
                cycles.append(_cycle(stack[-3], stack[-2], 1.0))
                del stack[-3:-1]
    for a, b in zip(stack[:-1], stack[1:]):  # (6) every range not counted: a half cycle
        cycles.append(_cycle(a, b, 0.5))


def _astm_5_4_5(points: list[float], cycles: list[tuple[float, float, float]]) -> None:
    # points start and end at the maximum peak (step 1 is done by the caller)
    stack: list[float] = []
    for p in points:
        stack.append(p)  # (2) read the next peak or valley
        while len(stack) >= 3:  # (3) fewer than three points: read on
            x_range = abs(stack[-1] - stack[-2])
            y_range = abs(stack[-2] - stack[-3])
            if x_range < y_range:  # (4a)
                break
            cycles.append(_cycle(stack[-3], stack[-2], 1.0))  # (5) count Y; discard its points
            del stack[-3:-1]
    if len(stack) > 2:
        raise AssertionError(f"ASTM 5.4.5 left {stack} uncounted")  # cannot happen from a maximum peak
