"""Adaptive selection in rounds: after the maximum-dissimilarity states, simulate where the
reconstruction is least sure, refit, and repeat (issue 22, item 1).

Round ``r`` (``1 .. lifecycle.adaptive.rounds``) of one mooring system:

1. fit the RBF of every output (:func:`moorlife.lifecycle.fit_outputs`, the settings of
   ``lifecycle.rbf``) on the training states simulated so far: the MDA states of
   ``cases.zarr`` and the picks of the rounds before ``r``;
2. score every hindcast hour by the error indicator of :func:`moorlife.lifecycle.error_indicator`
   (the leave-one-out error of the nearest training state x the distance to it) and pick
   ``per_round`` hours greedily (:func:`moorlife.lifecycle.suggest_states`: the running-minimum
   distance of maximum dissimilarity spreads the picks), never an hour already simulated nor a
   validation hour (nor an hour whose 5-D point equals one of theirs);
3. the picks are simulated like any training state (``results/{ms}/rounds/simulations_{r}.zarr``)
   under their own case ids (:data:`ROUND_CASE_OFFSET` + the hindcast index) and their own
   random stream (:data:`ROUND_STREAM`), so no phases are shared with any other simulation.

The picks depend on the data only (the hindcast, the selection, the simulations, the RBF
settings): no random draw, ties to the lowest hour, nothing that depends on the worker count
or the batch size. The budget: ``selection.n_train`` is the total number of training
simulations; maximum dissimilarity picks :func:`mda_budget` of them.

Kernels take numpy arrays (:func:`pick_hours`); :func:`with_rounds`, :func:`pick_round` and
:func:`annotate_lifecycle` are the xarray adapters of the workflow.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence

import numpy as np
import xarray as xr

from moorlife import lifecycle, names, rbf
from moorlife.selection.adapters import hindcast_points

__all__ = [
    "ROUND_CASE_OFFSET",
    "ROUND_STREAM",
    "mda_budget",
    "round_case_ids",
    "pick_hours",
    "with_rounds",
    "pick_round",
    "annotate_lifecycle",
]

log = logging.getLogger("moorlife.selection")

#: Case ids of the adaptive picks: this offset + the hour's position in the hindcast. The MDA
#: and validation cases are numbered 0 .. n_train + n_validate - 1 (fewer than the hindcast's
#: hours), so the ids never collide and the merged training set has unique case ids.
ROUND_CASE_OFFSET: int = 1_000_000_000
#: The random stream of the picks' simulations (:func:`moorlife.conventions.case_seed_sequence`).
ROUND_STREAM: str = "adaptive"


def mda_budget(n_train: int, rounds: int, per_round: int) -> int:
    """The states maximum dissimilarity picks: ``n_train - rounds x per_round``.

    Raises
    ------
    ValueError
        If the rounds take the whole budget (``rounds x per_round >= n_train``).
    """
    n_train, rounds, per_round = int(n_train), int(rounds), int(per_round)
    if rounds < 0 or per_round < 1:
        raise ValueError(f"lifecycle.adaptive: rounds = {rounds} must be >= 0 and per_round = {per_round} >= 1")
    if rounds and rounds * per_round >= n_train:
        raise ValueError(
            f"lifecycle.adaptive.rounds = {rounds} x per_round = {per_round} = {rounds * per_round} reach "
            f"selection.n_train = {n_train}: maximum dissimilarity would pick none"
        )
    return n_train - rounds * per_round


def round_case_ids(hindcast_index: np.ndarray) -> np.ndarray:
    """Case ids of picked hours: :data:`ROUND_CASE_OFFSET` + their hindcast index (int64)."""
    return ROUND_CASE_OFFSET + np.asarray(hindcast_index, dtype=np.int64)


def pick_hours(
    model: rbf.RBFModel,
    points: np.ndarray,
    scale: np.ndarray,
    n: int,
    exclude: np.ndarray,
    loo: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The ``n`` hours where the fitted reconstruction is least sure, none of them excluded.

    Parameters
    ----------
    model : moorlife.rbf.RBFModel
        The fit on the training states simulated so far.
    points : numpy.ndarray, shape (n_hours, 5)
        Every hindcast hour, ``names.METOCEAN_VARS`` order.
    scale : numpy.ndarray, shape (k,)
        Per-output normaliser of the leave-one-out errors (see
        :func:`moorlife.lifecycle.error_indicator`).
    n : int
        Hours to pick.
    exclude : numpy.ndarray of bool, shape (n_hours,)
        Hours that may not be picked (simulated or validation hours).
    loo : numpy.ndarray, shape (m, k), optional
        Leave-one-out residuals of the training states in the outputs' units
        (:func:`moorlife.lifecycle.loo_errors_in_units`); default the model's own.

    Returns
    -------
    picks : numpy.ndarray of int64, shape (n,)
        Row indices into ``points``, in pick order.
    indicator, distance : numpy.ndarray, shape (n,)
        The error indicator and the normalised distance to the nearest training state of
        each pick, before the round.

    Raises
    ------
    ValueError
        If fewer than ``n`` hours can be picked (every other hour excluded, or on a training
        state, or of zero indicator).
    """
    ind, dist = lifecycle.error_indicator(model, points, scale, loo, population=True)
    ind = np.where(np.asarray(exclude, dtype=bool), 0.0, ind)  # a zero score is never picked
    picks = lifecycle.suggest_states(model, points, ind, int(n), distance=dist)
    if picks.size < int(n):
        raise ValueError(
            f"adaptive round: only {picks.size} of the {int(n)} hours asked (lifecycle.adaptive.per_round) can be "
            f"picked: the other hours of the hindcast are simulated, validation states or of zero error indicator"
        )
    return picks, ind[picks], dist[picks]


def _same_points(points: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """Mask of the rows of ``points`` equal (every coordinate) to one of ``rows``."""
    seen = {tuple(r) for r in np.asarray(rows, dtype=float).tolist()}
    return np.fromiter((tuple(p) in seen for p in points.tolist()), dtype=bool, count=points.shape[0])


def with_rounds(base: xr.Dataset, rounds: Sequence[xr.Dataset]) -> xr.Dataset:
    """``cases.zarr`` (or ``simulations.zarr``) followed by the stores of the adaptive rounds.

    Concatenated along ``case`` on the variables every store has (and the base's coordinates),
    plus ``round`` (0 for the base, the round's number for its states); the base's attributes
    are kept (the selection's normalisation, the mooring system). With no rounds, ``base``
    itself is returned.

    Raises
    ------
    ValueError
        If a case id appears twice.
    """
    if not rounds:
        return base
    dim = names.CASE
    parts = [base, *rounds]
    keep = [v for v in base.data_vars if all(v in p.data_vars for p in rounds) and v != "round"]
    out = []
    for i, p in enumerate(parts):
        if i and "round" not in p.data_vars and "round" not in p.attrs:
            raise ValueError(f"adaptive round store {i} has neither a 'round' variable nor attribute")
        number = (p["round"].values if "round" in p.data_vars else int(p.attrs["round"])) if i else 0
        rnd = np.array(np.broadcast_to(np.asarray(number, dtype=np.int64), (p.sizes[dim],)))
        extra = [c for c in p.coords if c not in base.coords]  # e.g. time of a picks store, absent in sims
        out.append(p[keep].reset_coords(extra, drop=True).assign(round=(dim, rnd)))
    ds = xr.concat(out, dim=dim, data_vars="minimal", coords="different", compat="equals", combine_attrs="override")
    ids = ds[dim].values
    if np.unique(ids).size != ids.size:
        raise ValueError(f"adaptive rounds: case ids repeat across the stores ({ids.size - np.unique(ids).size} twice)")
    ds["round"].attrs = {"units": "1", "long_name": "adaptive round that picked the state (0: the selection)"}
    return ds


def pick_round(
    hindcast: xr.Dataset,
    cases: xr.Dataset,
    sims: xr.Dataset,
    *,
    settings: lifecycle.RBFSettings,
    n: int,
    number: int,
    thrust: lifecycle.ThrustCurve | None = None,
) -> xr.Dataset:
    """Round ``number``: the ``n`` hours to simulate next, as a cases-like store.

    Parameters
    ----------
    hindcast : xarray.Dataset
        ``results/metocean/hindcast.zarr``.
    cases, sims : xarray.Dataset
        The sea states and their simulations so far: :func:`with_rounds` of ``cases.zarr`` and
        of ``simulations.zarr`` with the rounds before ``number``. Only ``role == "train"``
        states are fitted; the validation states are never fitted, only excluded.
    settings : moorlife.lifecycle.RBFSettings
        ``lifecycle.rbf``.
    n : int
        ``lifecycle.adaptive.per_round``.
    number : int
        The round (1-based).

    Returns
    -------
    xarray.Dataset
        Dim ``case`` (ids :func:`round_case_ids`, in pick order): the five variables,
        ``hindcast_index``, coordinate ``time``, ``role = "train"``, ``round``, ``pick_order``,
        ``error_indicator`` and ``nearest_train_distance`` before the round; the selection's
        normalisation attributes and ``round``, ``n_fit``.
    """
    fitted = lifecycle.fit_reconstruction(
        cases, sims, settings=settings, thrust=thrust, context=f"adaptive round {number}"
    )
    model, cols, y, train_ids = fitted.model, fitted.cols, fitted.train_values, fitted.train_case
    scale = np.std(y, axis=0)
    loo = lifecycle.loo_errors_in_units(model, y, cols)

    hp = hindcast_points(hindcast, source="hindcast")
    known = np.asarray(cases["hindcast_index"].values, dtype=np.int64)  # every simulated or validation hour
    exclude = np.zeros(hp.shape[0], dtype=bool)
    exclude[known] = True
    exclude |= _same_points(hp, hp[known])
    picks, ind, dist = pick_hours(model, hp, scale, n, exclude, loo)
    log.info(
        "adaptive round %d: fitted on %d training states (%d outputs), picked %d hours; indicator %.3g .. %.3g",
        number,
        train_ids.size,
        len(cols),
        picks.size,
        float(ind.min()),
        float(ind.max()),
    )
    return _picks_dataset(hindcast, hp, picks, ind, dist, cases.attrs, number, train_ids.size)


def _picks_dataset(
    hindcast: xr.Dataset,
    hp: np.ndarray,
    picks: np.ndarray,
    ind: np.ndarray,
    dist: np.ndarray,
    case_attrs: dict,
    number: int,
    n_fit: int,
) -> xr.Dataset:
    dim = names.CASE
    data: dict[str, tuple] = {}
    for k, v in enumerate(names.METOCEAN_VARS):
        data[v] = (dim, hp[picks, k], names.attrs_for(v))
    data["hindcast_index"] = (
        dim,
        picks.astype(np.int64),
        {"units": "1", "long_name": f"position of the sea state along the hindcast '{names.TIME}' dimension"},
    )
    data["role"] = (dim, np.array(["train"] * picks.size), {"long_name": "train: used to fit the reconstruction"})
    data["round"] = (
        dim,
        np.full(picks.size, int(number), dtype=np.int64),
        {"units": "1", "long_name": "adaptive round"},
    )
    data["pick_order"] = (dim, np.arange(picks.size, dtype=np.int64), {"units": "1", "long_name": "order of the pick"})
    data["error_indicator"] = (
        dim,
        ind,
        {"units": "1", "long_name": "LOO error of the nearest training state x relative distance, before the round"},
    )
    data["nearest_train_distance"] = (
        dim,
        dist,
        {"units": "1", "long_name": "normalised 5-D distance to the nearest training state, before the round"},
    )
    coords: dict[str, object] = {dim: round_case_ids(picks)}
    if names.TIME in hindcast.coords:
        coords[names.TIME] = (dim, hindcast[names.TIME].values[picks])
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update({k: v for k, v in case_attrs.items() if str(k).startswith("norm_")})
    ds.attrs.update(
        {
            "selection_method": "adaptive round: largest LOO error x sparsity of the fit so far, greedy, spread by the "
            "running minimum distance (moorlife.selection.rounds)",
            "round": int(number),
            "n_fit": int(n_fit),
            "case_offset": ROUND_CASE_OFFSET,
            "random_stream": ROUND_STREAM,
        }
    )
    return ds


def annotate_lifecycle(ds: xr.Dataset, cases: xr.Dataset) -> xr.Dataset:
    """Record in ``lifecycle.zarr`` which adaptive round each training state comes from.

    Adds ``train_round`` on ``train`` and the attributes ``adaptive_rounds`` and ``n_train_mda``.
    """
    rnd = cases["round"].sel({names.CASE: ds["train"].values}).values.astype(np.int64)
    ds = ds.assign(train_round=("train", rnd, {"units": "1", "long_name": "adaptive round (0: maximum dissimilarity)"}))
    ds.attrs.update({"adaptive_rounds": int(rnd.max(initial=0)), "n_train_mda": int((rnd == 0).sum())})
    return ds
