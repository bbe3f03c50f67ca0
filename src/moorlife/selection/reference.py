"""Reference implementations, for tests and small problems only.

:func:`mda_bruteforce` recomputes every distance at every step; :func:`moorlife.selection.mda`
must agree with it pick by pick.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from moorlife.selection.dissimilarity import _prepare, _start_indices

__all__ = ["mda_bruteforce"]


def mda_bruteforce(
    points: npt.ArrayLike,
    n: int,
    *,
    is_direction: npt.ArrayLike,
    start: int | Sequence[int] | np.ndarray | None = None,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
    dtype: npt.DTypeLike = np.float32,
) -> np.ndarray:
    """Strict reference for :func:`mda`: recompute every distance at every step, ``O(N * n^2)``.

    Same parameters, normalisation, distance, start rule and tie rule as :func:`mda`, but no
    running minimum: at each step the full ``(N, j)`` distance matrix to the ``j`` selected
    states is rebuilt and minimised. For tests and small problems only.
    """
    x, mask = _prepare(points, n, is_direction, lo, span, dtype)
    dt = x.dtype.type
    picks = _start_indices(start, x, mask, n)
    while len(picks) < n:
        sel = x[picks]  # (j, D)
        sq = np.zeros((x.shape[0], len(picks)), dtype=dt)
        for k in range(x.shape[1]):
            d = np.abs(x[:, k, None] - sel[None, :, k])
            if mask[k]:
                d = np.minimum(d, dt(2.0) - d)
            sq = sq + d * d
        nearest = sq.min(axis=1)
        nearest[picks] = -1.0
        best = nearest.max()
        picks.append(int(np.flatnonzero(nearest == best)[0]))
    return np.asarray(picks, dtype=np.int64)
