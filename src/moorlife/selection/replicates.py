"""Seed replicates of the training states that hold the damage (issue 22, the storm peak).

One simulated hour is one realisation of its sea state. Its damage scatters from seed to seed,
little in moderate seas and much in a storm: at the largest storm of the default hindcast the
coefficient of variation of one hour's damage is 0.21-0.34 for MS6, against 0.02-0.07 in most
states (``validation/reconstruction.md`` section 10). The RBF interpolates each training record
exactly, so the noise of one storm record becomes the damage of every hour around it: on MS6's
truth year one record, 1.5x the mean of six seeds, made most of a +8 to +18 % overestimate.

``lifecycle.replicates: {states: n, seeds: k}`` spends ``n x k`` of the ``selection.n_train``
simulations on ``k`` more seeds of the ``n`` training states whose cells hold the most damage,
and fits the mean of their ``1 + k`` records. Per mooring system:

1. :func:`pick_replicates` (rule ``replicate_picks``): fit the RBF on the training states (the
   MDA states and the adaptive rounds), predict every hindcast hour, and give each training
   state the share of each line's life-cycle damage of the hours whose nearest training state
   it is (:func:`damage_shares`); keep the ``n`` states of the largest share over the lines;
2. the rule ``simulate_replicate`` simulates them ``k`` times with the simulate stage as it is,
   under their own case ids and the random streams ``replicate1`` .. ``replicatek``
   (:func:`replicate_stream`), so no phases are shared with any other simulation;
3. :func:`average_replicates` (the ``lifecycle`` stage) replaces the outputs of those states by
   the mean of their records, the life-cycle damage's expected value.

The picks depend on the data only (no random draw, ties to the lowest case id); the mean is
taken in a fixed order (the study's record, then replicates 1 .. k), so the bits do not depend
on the worker count, the batch size or the resume history.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt
import xarray as xr

from moorlife import lifecycle, names, rbf
from moorlife.selection.adapters import hindcast_points

__all__ = [
    "REPLICATE_STREAM",
    "replicate_stream",
    "damage_shares",
    "records_variance_shares",
    "largest_shares",
    "pick_replicates",
    "average_replicates",
]

log = logging.getLogger("moorlife.selection")

#: The rankings of ``lifecycle.replicates.rank`` (:func:`pick_replicates`).
RANKS: tuple[str, ...] = ("damage", "life", "years")

#: Prefix of the replicates' random streams: ``replicate1`` .. (:func:`replicate_stream`).
REPLICATE_STREAM: str = "replicate"


def replicate_stream(j: int) -> str:
    """The random stream of replicate ``j`` (1-based): ``"replicate{j}"``."""
    j = int(j)
    if j < 1:
        raise ValueError(f"replicate number {j} must be >= 1")
    return f"{REPLICATE_STREAM}{j}"


def damage_shares(nearest: npt.ArrayLike, damage: npt.ArrayLike, n_train: int) -> np.ndarray:
    """Each training state's share of the life-cycle damage: the hours whose nearest state it is.

    Parameters
    ----------
    nearest : array_like of int, shape (n_hours,)
        The nearest training state of every hindcast hour (0 .. ``n_train`` - 1).
    damage : array_like, shape (n_hours, k)
        The reconstructed damage of every hour, one column per line (and curve).
    n_train : int

    Returns
    -------
    numpy.ndarray, shape (n_train, k)
        Column sums 1 (a column of zero damage: all zero).
    """
    idx = np.asarray(nearest, dtype=np.int64)
    d = np.atleast_2d(np.asarray(damage, dtype=float).T).T
    if idx.shape[0] != d.shape[0]:
        raise ValueError(f"nearest has {idx.shape[0]} hours, damage {d.shape[0]}")
    if idx.size and (idx.min() < 0 or idx.max() >= n_train):
        raise ValueError(f"nearest indices {idx.min()} .. {idx.max()} outside 0 .. {n_train - 1}")
    if not np.isfinite(d).all() or (d < 0).any():
        raise ValueError("damage must be finite and >= 0")
    out = np.stack([np.bincount(idx, weights=d[:, j], minlength=n_train) for j in range(d.shape[1])], axis=1)
    total = out.sum(axis=0)
    return np.divide(out, total, out=np.zeros_like(out), where=total > 0)


def records_variance_shares(
    model: lifecycle.Reconstruction,
    points: np.ndarray,
    predicted: np.ndarray,
    train_values: np.ndarray,
    train_points: np.ndarray,
    outputs: Sequence[int],
    groups: Sequence[np.ndarray],
) -> np.ndarray:
    """Each training state's share of the records' seed variance in a set of damage sums.

    ``sum_g (G_ig / S_g)^2`` over the sums ``g`` (each a group of rows of ``points``: the whole
    hindcast, or each calendar year), with ``G_ig / S_g`` the share of sum ``g`` that record ``i``
    carries (:func:`moorlife.lifecycle.records.carried_shares`): with one seed CV for every
    record, the part of the sums' seed variance that averaging record ``i`` would remove.

    Returns
    -------
    numpy.ndarray, shape (n_train, len(outputs))
        Column sums 1 (a column of no damage: all zero).
    """
    from moorlife.lifecycle.records import carried_shares

    var = np.zeros((np.asarray(train_values).shape[0], len(outputs)))
    for g in groups:
        sh = carried_shares(model, points[g], predicted[g], train_values, train_points, outputs)
        var += np.nan_to_num(sh) ** 2
    total = var.sum(axis=0)
    return np.divide(var, total, out=np.zeros_like(var), where=total > 0)


def largest_shares(shares: npt.ArrayLike, n: int) -> np.ndarray:
    """Indices of the ``n`` rows of the largest share over the columns, largest first.

    Ties go to the lowest index (a stable sort), so the pick is deterministic.
    """
    s = np.max(np.atleast_2d(np.asarray(shares, dtype=float)), axis=1)
    n = int(n)
    if not 0 < n <= s.size:
        raise ValueError(f"lifecycle.replicates.states = {n}: must be 1 .. {s.size}, the training states fitted")
    return np.argsort(-s, kind="stable")[:n]


def pick_replicates(
    hindcast: xr.Dataset,
    cases: xr.Dataset,
    sims: xr.Dataset,
    *,
    settings: lifecycle.RBFSettings,
    n: int,
    seeds: int,
    thrust: lifecycle.ThrustCurve | None = None,
    rank: str = "damage",
) -> xr.Dataset:
    """The ``n`` training states to simulate again, as a cases-like store.

    Parameters
    ----------
    hindcast : xarray.Dataset
        ``results/metocean/hindcast.zarr``.
    cases, sims : xarray.Dataset
        The sea states and their simulations (:func:`moorlife.selection.rounds.with_rounds` of
        the selection and the adaptive rounds). Only ``role == "train"`` states are fitted.
    settings : moorlife.lifecycle.RBFSettings
        ``lifecycle.rbf``.
    n, seeds : int
        ``lifecycle.replicates.states`` and ``seeds`` (recorded in the attributes).
    rank : {"damage", "life", "years"}
        ``lifecycle.replicates.rank``: the states of the largest share of a line's life-cycle
        damage in their cells (:func:`damage_shares`), or of the records' seed variance in the
        life-cycle sum or in the calendar years' sums (:func:`records_variance_shares`).

    Returns
    -------
    xarray.Dataset
        Dim ``case``: the picked states' rows of ``cases`` (their own case ids), in pick order,
        with ``damage_share (case, line)`` (the S-N damage), ``cell_hours`` (the hindcast hours
        whose nearest training state it is), ``records_variance_share (case, line)`` (with
        ``rank`` ``life`` or ``years``) and ``pick_order``; attributes ``replicate_seeds``,
        ``n_fit``, the selection's normalisation and, with ``rank`` not ``damage``, ``replicate_rank``.
    """
    dim = names.CASE
    if rank not in RANKS:
        raise ValueError(f"lifecycle.replicates.rank = {rank!r}: must be one of {list(RANKS)}")
    fitted = lifecycle.fit_reconstruction(cases, sims, settings=settings, thrust=thrust, context="replicates")
    model, cols, train_ids = fitted.model, fitted.cols, fitted.train_case
    dmg = [j for j, (v, line) in enumerate(cols) if v == "damage_sn" and line is not None]
    if not dmg:
        raise ValueError("lifecycle.replicates: the reconstruction has no damage_sn output (lifecycle.rbf.outputs)")
    hp = hindcast_points(hindcast, source="hindcast")
    pred = lifecycle.predict_outputs(model, hp, chunk_rows=settings.chunk_rows)
    _, nearest = rbf.nearest_centre(model, hp)
    shares = damage_shares(nearest, np.maximum(pred[:, dmg], 0.0), train_ids.size)
    ranked = shares
    if rank != "damage":
        if rank == "life":
            groups = [np.arange(hp.shape[0])]
        else:
            year = hindcast[names.TIME].dt.year.values
            groups = [np.flatnonzero(year == v) for v in np.unique(year)]
        ranked = records_variance_shares(model, hp, pred, fitted.train_values, fitted.train_points, dmg, groups)
    order = largest_shares(ranked, n)
    ids = train_ids[order]
    out = cases.sel({dim: ids})
    if rank != "damage":
        text = f"share of the records' seed variance in the line's {rank} S-N damage sum(s)"
        out["records_variance_share"] = ((dim, names.LINE), ranked[order], {"units": "1", "long_name": text})
    out = out.assign(
        damage_share=(
            (dim, names.LINE),
            shares[order],
            {"units": "1", "long_name": "share of the line's life-cycle S-N damage in the state's cell"},
        ),
        pick_order=(dim, np.arange(ids.size, dtype=np.int64), {"units": "1", "long_name": "order of the pick"}),
        cell_hours=(
            dim,
            np.bincount(nearest, minlength=train_ids.size)[order].astype(np.int64),
            {"units": "1", "long_name": "hindcast hours whose nearest training state it is"},
        ),
    ).assign_coords({names.LINE: [cols[j][1] for j in dmg]})
    out.attrs.update(
        {
            "selection_method": "seed replicates: the training states of the largest share of the life-cycle "
            "damage in their cells (moorlife.selection.replicates)",
            "replicate_seeds": int(seeds),
            "n_fit": int(train_ids.size),
        }
    )
    if rank != "damage":  # the default's picks keep their attributes
        out.attrs["replicate_rank"] = rank
        out.attrs["selection_method"] = (
            f"seed replicates: the training states of the largest share of the records' seed variance in the "
            f"{'life-cycle damage sum' if rank == 'life' else 'damage sum of each calendar year'} "
            "(moorlife.selection.replicates)"
        )
    log.info(
        "replicates (rank %s): %d of %d training states hold %.1f %% of the damage and %.1f %% of its "
        "ranking (largest line share summed); cases %s",
        rank,
        ids.size,
        train_ids.size,
        100 * float(np.max(shares[order], axis=1).sum()),
        100 * float(np.max(ranked[order], axis=1).sum()),
        ids.tolist(),
    )
    return out


def average_replicates(sims: xr.Dataset, replicates: Sequence[xr.Dataset]) -> xr.Dataset:
    """``sims`` with every replicated state's outputs the mean of its records.

    Parameters
    ----------
    sims : xarray.Dataset
        The training (and validation) simulations, dim ``case``.
    replicates : sequence of xarray.Dataset
        The stores of replicates 1 .. k, each over the same cases, all of them in ``sims``.

    Returns
    -------
    xarray.Dataset
        A copy of ``sims``: every floating-point variable along ``case`` that differs between
        the records of the replicated states is the mean of the study's record and the
        replicates', summed in that order (the sea state's own variables are kept as they are);
        ``n_records`` (case) counts the records (1 elsewhere). ``sims`` itself when
        ``replicates`` is empty.

    Raises
    ------
    ValueError
        If the replicate stores differ in their cases, or hold a case ``sims`` does not.
    """
    if not replicates:
        return sims
    dim = names.CASE
    ids = np.asarray(replicates[0][dim].values)
    for j, r in enumerate(replicates[1:], start=2):
        if not np.array_equal(np.asarray(r[dim].values), ids):
            raise ValueError(f"replicate {j} holds cases {r[dim].values.tolist()}, replicate 1 {ids.tolist()}")
    missing = np.setdiff1d(ids, sims[dim].values)
    if missing.size:
        raise ValueError(f"replicated cases {missing.tolist()} are not among the simulations")
    out = sims.copy(deep=True)
    pos = {int(c): i for i, c in enumerate(sims[dim].values)}
    rows = np.array([pos[int(c)] for c in ids], dtype=np.int64)
    for v in sims.data_vars:
        da = sims[v]
        if dim not in da.dims or da.dtype.kind != "f":
            continue
        if any(v not in r.data_vars for r in replicates):
            raise ValueError(f"replicate stores lack the output {v!r} of the simulations")
        axis = da.dims.index(dim)
        records = [np.take(da.values, rows, axis=axis)] + [r[v].transpose(*da.dims).values for r in replicates]
        if all(np.array_equal(records[0], rec) for rec in records[1:]):
            continue  # the sea state itself (hs, tp, ...): the same in every record, kept to the bit
        total = records[0].astype(float)
        for rec in records[1:]:
            total = total + rec
        values = out[v].values.copy()
        idx = [slice(None)] * values.ndim
        idx[axis] = rows
        values[tuple(idx)] = total / (1 + len(replicates))
        out[v] = (da.dims, values, da.attrs)
    n = np.ones(sims.sizes[dim], dtype=np.int64)
    n[rows] = 1 + len(replicates)
    out["n_records"] = (dim, n, {"units": "1", "long_name": "simulated records averaged (seed replicates)"})
    return out
