"""Maximum dissimilarity selection (MDA, Camus et al. 2011) and the validation states.

The training states are picked greedily over the 5-D sea-state points so that each new state
is the one farthest from its nearest already-selected state (Barrera et al. 2019, section
3.2), in the normalised space of :mod:`moorlife.space`. A further, disjoint set of
*validation* states is kept only to check the reconstruction (:func:`select_validation`).
"""

from __future__ import annotations

import zlib
from collections.abc import Sequence
from typing import Literal

import numpy as np
import numpy.typing as npt

from moorlife.space import check_points, normalise

__all__ = ["VALIDATION_RULES", "VALIDATION_STREAM_KEY", "mda", "select_validation"]

#: Rules for choosing the validation states (``config.yaml: selection.validation_rule``).
VALIDATION_RULES: tuple[str, ...] = ("random", "mda")
#: Label of the random stream of the "random" validation rule: ``SeedSequence([seed, key])``,
#: so it cannot coincide with another stage's stream drawn from the same global seed.
VALIDATION_STREAM_KEY = zlib.crc32(b"moorlife.selection.validate")


def _start_indices(
    start: int | Sequence[int] | np.ndarray | None, x: np.ndarray, mask: np.ndarray, n: int
) -> list[int]:
    """Resolve the ``start`` argument of :func:`mda` to a list of preselected rows."""
    n_points = x.shape[0]
    if start is None:
        # the most extreme state: largest sum of normalised scalar coordinates
        score = x[:, ~mask].astype(np.float64).sum(axis=1) if (~mask).any() else np.zeros(n_points)
        return [int(np.argmax(score))]
    seq = [int(start)] if np.ndim(start) == 0 else [int(i) for i in np.asarray(start).reshape(-1)]
    if not seq:
        raise ValueError("start is an empty sequence: give at least one preselected index")
    for i in seq:
        if not 0 <= i < n_points:
            raise ValueError(f"start index {i} is outside 0..{n_points - 1}")
    if len(set(seq)) != len(seq):
        raise ValueError(f"start indices are not unique: {seq}")
    if len(seq) > n:
        raise ValueError(f"{len(seq)} start indices but only n = {n} states requested")
    return seq


def _prepare(
    points: npt.ArrayLike,
    n: int,
    is_direction: npt.ArrayLike,
    lo: npt.ArrayLike | None,
    span: npt.ArrayLike | None,
    dtype: npt.DTypeLike,
) -> tuple[np.ndarray, np.ndarray]:
    pts, mask = check_points(points, is_direction)
    if int(n) != n or n < 1:
        raise ValueError(f"n must be a positive integer, got {n!r}")
    if n > pts.shape[0]:
        raise ValueError(f"cannot select n = {n} states out of {pts.shape[0]}")
    if np.dtype(dtype) not in (np.dtype(np.float32), np.dtype(np.float64)):
        raise ValueError(f"dtype must be float32 or float64, got {np.dtype(dtype)}")
    return normalise(pts, mask, lo, span, dtype=dtype), mask


def mda(
    points: npt.ArrayLike,
    n: int,
    *,
    is_direction: npt.ArrayLike,
    start: int | Sequence[int] | np.ndarray | None = None,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
    dtype: npt.DTypeLike = np.float32,
) -> np.ndarray:
    """Maximum dissimilarity selection with a running minimum distance, ``O(N * n)``.

    Each step adds the state whose distance to its nearest already-selected state is the
    largest (Camus et al. 2011; Barrera et al. 2019, section 3.2). The distance is the one of
    :func:`pairwise_distance` on :func:`normalise`-d points; squared distances are compared
    (same order, no square root).

    Parameters
    ----------
    points : array_like, shape (N, D)
        Sea states in physical units, directions in degrees.
    n : int
        Number of states to return (including any preselected ``start`` states).
    is_direction : array_like of bool, shape (D,)
        Which columns are directions (compared on the circle).
    start : int or sequence of int, optional
        First state (the paper: the one with the largest Hs), or an ordered sequence of
        already-selected states to continue from (they are returned first, as given).
        Default: the state with the largest sum of normalised scalar coordinates.
    lo, span : array_like, shape (D,), optional
        Normalisation (:func:`scaling_from`); default from ``points``.
    dtype : {float32, float64}
        Arithmetic precision. float32 halves the memory traffic; picks can differ from
        float64 only where two candidates' distances agree to about 1e-7 relative.

    Returns
    -------
    numpy.ndarray of int64, shape (n,)
        Row indices in selection order.

    Notes
    -----
    Ties are broken deterministically: among equally distant candidates the lowest row index
    wins (``numpy.argmax`` returns the first maximum). Exact duplicates of a selected state
    have distance 0 and are picked only after every distinct state. Results are identical,
    pick by pick, to :func:`mda_bruteforce` with the same ``dtype``.
    """
    x, mask = _prepare(points, n, is_direction, lo, span, dtype)
    dt = x.dtype.type
    picks = _start_indices(start, x, mask, n)
    cols = np.ascontiguousarray(x.T)  # (D, N): each variable contiguous
    n_points = cols.shape[1]
    mind = np.full(n_points, np.inf, dtype=dt)
    acc = np.empty(n_points, dtype=dt)
    tmp = np.empty(n_points, dtype=dt)
    tmp2 = np.empty(n_points, dtype=dt)
    two = dt(2.0)

    def update(i: int) -> None:
        p = cols[:, i]
        for k in range(cols.shape[0]):
            out = acc if k == 0 else tmp
            np.subtract(cols[k], p[k], out=out)
            if mask[k]:  # fold on the circle; a scalar difference is squared as is
                np.abs(out, out=out)
                np.subtract(two, out, out=tmp2)
                np.minimum(out, tmp2, out=out)
            np.multiply(out, out, out=out)
            if k:
                np.add(acc, tmp, out=acc)
        np.minimum(mind, acc, out=mind)

    for i in picks:
        update(i)
    mind[picks] = -1.0  # never pick a selected state again (min with >= 0 keeps it at -1)
    while len(picks) < n:
        i = int(np.argmax(mind))
        picks.append(i)
        update(i)
        mind[i] = -1.0
    return np.asarray(picks, dtype=np.int64)


def _row_keys(points: np.ndarray) -> np.ndarray:
    """One opaque key per row, equal exactly when the rows are bitwise equal."""
    pts = np.ascontiguousarray(points, dtype=np.float64) + 0.0  # -0.0 -> 0.0
    return pts.view(np.dtype((np.void, pts.dtype.itemsize * pts.shape[1]))).reshape(-1)


def select_validation(
    points: npt.ArrayLike,
    n: int,
    *,
    exclude: npt.ArrayLike,
    is_direction: npt.ArrayLike,
    rule: Literal["random", "mda"] = "random",
    seed: int | np.random.SeedSequence = 0,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
) -> np.ndarray:
    """Pick states kept only to validate the reconstruction, disjoint from the training set.

    Parameters
    ----------
    points : array_like, shape (N, D)
        Sea states in physical units.
    n : int
        Number of validation states.
    exclude : array_like of int, shape (J,)
        The training states (row indices, in MDA order for ``rule="mda"``).
    is_direction : array_like of bool, shape (D,)
    rule : {"random", "mda"}
        ``"random"`` (default): a seeded uniform sample, without replacement, of the hours
        that are not training states *and* whose 5-D point differs from every training
        state (an exact copy would validate nothing); returned in increasing row order.
        This measures the error a typical hour sees. ``"mda"``: continue the maximum
        dissimilarity selection after the training states (the next ``n`` picks, in
        selection order); this stresses the reconstruction where the training set is
        sparsest.
    seed : int or numpy.random.SeedSequence
        Seed of the ``"random"`` rule (ignored by ``"mda"``).
    lo, span : array_like, shape (D,), optional
        Normalisation for ``"mda"`` (:func:`scaling_from`).

    Returns
    -------
    numpy.ndarray of int64, shape (n,)
        Row indices, none of them in ``exclude``.
    """
    pts, mask = check_points(points, is_direction)
    train = np.asarray(exclude, dtype=np.int64).reshape(-1)
    if train.size and (train.min() < 0 or train.max() >= pts.shape[0]):
        raise ValueError(f"exclude holds indices outside 0..{pts.shape[0] - 1}")
    if int(n) != n or n < 0:
        raise ValueError(f"n must be a non-negative integer, got {n!r}")
    if rule == "mda":
        if train.size == 0:
            return mda(pts, n, is_direction=mask, lo=lo, span=span) if n else np.empty(0, np.int64)
        return mda(pts, train.size + n, is_direction=mask, start=train, lo=lo, span=span)[train.size :]
    if rule != "random":
        raise ValueError(f"validation rule {rule!r} is not one of {VALIDATION_RULES}")
    keys = _row_keys(pts)
    taken = np.isin(keys, keys[train]) if train.size else np.zeros(pts.shape[0], bool)
    candidates = np.flatnonzero(~taken)
    if n > candidates.size:
        raise ValueError(
            f"cannot pick {n} validation states: only {candidates.size} states differ from the "
            f"{train.size} training states"
        )
    rng = np.random.default_rng(seed)
    return np.sort(rng.choice(candidates, size=int(n), replace=False)).astype(np.int64)
