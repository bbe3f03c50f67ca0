"""The xarray adapters of the selection stage: ``cases.zarr`` and ``discrete.zarr``.

:func:`select_cases` and :func:`discrete_states` produce the stores of the output contract
(``results/selection/cases.zarr`` and ``results/selection/discrete.zarr``) from the hindcast.
"""

from __future__ import annotations

import logging
import time as _time
from collections.abc import Sequence
from typing import Literal

import numpy as np
import pandas as pd
import xarray as xr

from moorlife import names
from moorlife.selection.dissimilarity import (
    VALIDATION_RULES,
    VALIDATION_STREAM_KEY,
    mda,
    select_validation,
)
from moorlife.selection.scatter import (
    DEFAULT_HS_EDGES,
    DEFAULT_TP_EDGES,
    DEFAULT_WIND_EDGES,
    class_labels,
    scatter_matrix,
)
from moorlife.space import direction_mask, nearest_distance, normalise, scaling_from

__all__ = ["hindcast_points", "select_cases", "discrete_states"]

_log = logging.getLogger("moorlife.selection")


def hindcast_points(hindcast: xr.Dataset, *, source: str = "hindcast") -> np.ndarray:
    """The ``(N, 5)`` sea-state points of a hindcast, columns in ``names.METOCEAN_VARS`` order.

    Checks that every variable exists along ``time``, is finite, that Hs, Tp and wind speed
    are not negative and that directions lie in ``[0, 360]`` degrees.

    Raises
    ------
    ValueError
        Naming ``source``, the variable, the value and its first bad time stamp.
    """
    if names.TIME not in hindcast.dims:
        raise ValueError(f"{source}: no '{names.TIME}' dimension (dims: {tuple(hindcast.dims)})")
    cols = []
    times = hindcast[names.TIME].values if names.TIME in hindcast.coords else None
    for var in names.METOCEAN_VARS:
        if var not in hindcast:
            raise ValueError(f"{source}: variable '{var}' is missing (have {sorted(hindcast.data_vars)})")
        da = hindcast[var]
        if da.dims != (names.TIME,):
            raise ValueError(f"{source}: variable '{var}' has dims {da.dims}, expected ('{names.TIME}',)")
        a = np.asarray(da.values, dtype=float)
        if var in names.DIRECTION_VARS:
            bad = ~((a >= 0.0) & (a <= 360.0))
            rule = "a finite direction in [0, 360] degrees"
        else:
            bad = ~(np.isfinite(a) & (a >= 0.0))
            rule = "finite and >= 0"
        if bad.any():
            row = int(np.flatnonzero(bad)[0])
            when = f" ({names.TIME} {times[row]})" if times is not None else ""
            raise ValueError(f"{source}: variable '{var}' row {row}{when}: value {float(a[row])!r} is not {rule}")
        cols.append(a)
    return np.stack(cols, axis=1)


def select_cases(
    hindcast: xr.Dataset,
    *,
    n_train: int,
    n_validate: int,
    rule: Literal["random", "mda"] = "random",
    seed: int = 0,
    source: str = "hindcast",
) -> xr.Dataset:
    """The sea states to simulate: ``n_train`` MDA states, then ``n_validate`` validation states.

    Parameters
    ----------
    hindcast : xarray.Dataset
        Dim ``time``; variables ``names.METOCEAN_VARS``.
    n_train, n_validate : int
        Numbers of training (MDA) and validation states.
    rule : {"random", "mda"}
        Validation rule, see :func:`select_validation`.
    seed : int
        The study's global seed; the ``"random"`` validation rule draws from
        ``SeedSequence([seed, VALIDATION_STREAM_KEY])``.
    source : str
        Name of the hindcast (a path) quoted in error messages.

    Returns
    -------
    xarray.Dataset
        Dim ``case`` (integer coordinate ``0..N-1``: training states first, in MDA order,
        then validation states); the five variables; ``hindcast_index`` (int64 position in
        ``time``), coordinate ``time`` (that hour), ``role`` (``"train"``/``"validate"``),
        ``nearest_train_distance`` (normalised distance to the nearest *other* training
        state). Attributes record the rule, seed, start state and the normalisation
        (``norm_variables``, ``norm_lo``, ``norm_span``, ``norm_is_direction``); each
        variable also carries its own ``norm_lo``/``norm_span``.
    """
    if rule not in VALIDATION_RULES:
        raise ValueError(f"{source}: validation rule {rule!r} is not one of {VALIDATION_RULES}")
    pts = hindcast_points(hindcast, source=source)
    mask = direction_mask()
    if n_train + n_validate > pts.shape[0]:
        raise ValueError(f"{source}: n_train + n_validate = {n_train + n_validate} exceeds the {pts.shape[0]} hours")
    lo, span = scaling_from(pts, mask)
    i_hs = names.METOCEAN_VARS.index("hs")
    start = int(np.argmax(pts[:, i_hs]))  # the paper: start from the largest Hs
    t0 = _time.perf_counter()
    train = mda(pts, n_train, is_direction=mask, start=start, lo=lo, span=span)
    _log.info(
        "%s: MDA picked %d of %d states in %.2f s (start: largest hs, row %d)",
        source,
        n_train,
        pts.shape[0],
        _time.perf_counter() - t0,
        start,
    )
    stream = np.random.SeedSequence([int(seed), VALIDATION_STREAM_KEY])
    valid = select_validation(
        pts, n_validate, exclude=train, is_direction=mask, rule=rule, seed=stream, lo=lo, span=span
    )
    _log.info("%s: %d validation states by rule %r (seed %d)", source, valid.size, rule, seed)
    index = np.concatenate([train, valid]).astype(np.int64)
    x = normalise(pts, mask, lo, span)
    x_train = x[train]
    dist = np.concatenate(
        [
            nearest_distance(x_train, x_train, mask, exclude_same_index=True),
            nearest_distance(x[valid], x_train, mask) if valid.size else np.empty(0),
        ]
    )
    case = np.arange(index.size, dtype=np.int64)
    data_vars: dict[str, tuple[str, np.ndarray, dict[str, object]]] = {}
    for k, var in enumerate(names.METOCEAN_VARS):
        attrs = {**names.attrs_for(var), "norm_lo": float(lo[k]), "norm_span": float(span[k])}
        data_vars[var] = (names.CASE, pts[index, k], attrs)
    data_vars["hindcast_index"] = (
        names.CASE,
        index,
        {"units": "1", "long_name": f"position of the sea state along the hindcast '{names.TIME}' dimension"},
    )
    data_vars["role"] = (
        names.CASE,
        np.array(["train"] * train.size + ["validate"] * valid.size),
        {"long_name": "train: used to fit the reconstruction; validate: kept only to check it"},
    )
    data_vars["nearest_train_distance"] = (
        names.CASE,
        dist,
        {"units": "1", "long_name": "normalised 5-D distance to the nearest other training state"},
    )
    coords: dict[str, object] = {names.CASE: case}
    if names.TIME in hindcast.coords:
        coords[names.TIME] = (names.CASE, hindcast[names.TIME].values[index])
    ds = xr.Dataset(data_vars, coords=coords)
    ds.attrs.update(
        {
            "selection_method": "maximum dissimilarity (Camus et al. 2011), running minimum distance",
            "distance": "Euclidean; scalars (x - norm_lo) / norm_span, directions folded on the circle / 180",
            "start_rule": "largest hs",
            "start_index": start,
            "n_train": int(train.size),
            "n_validate": int(valid.size),
            "validation_rule": rule,
            "seed": int(seed),
            "validation_stream": f"numpy SeedSequence([seed, {VALIDATION_STREAM_KEY}]) (crc32 of 'moorlife.selection.validate')",
            "n_hindcast": int(pts.shape[0]),
            "norm_variables": list(names.METOCEAN_VARS),
            "norm_lo": [float(v) for v in lo],
            "norm_span": [float(v) for v in span],
            "norm_is_direction": [bool(v) for v in mask],
        }
    )
    return ds


def discrete_states(
    hindcast: xr.Dataset,
    *,
    hs_edges: Sequence[float] = DEFAULT_HS_EDGES,
    wind_edges: Sequence[float] = DEFAULT_WIND_EDGES,
    tp_edges: Sequence[float] = DEFAULT_TP_EDGES,
    sector: float = 10.0,
    source: str = "hindcast",
) -> xr.Dataset:
    """The conventional discrete sea states (paper Table 6) of a hindcast.

    Parameters
    ----------
    hindcast : xarray.Dataset
        Dim ``time``; variables ``names.METOCEAN_VARS``.
    hs_edges, wind_edges, tp_edges : sequence of float
        Lower class edges (m, m/s, s); the last class is open. See :func:`scatter_matrix`.
    sector : float
        Direction sector width in degrees for the most likely directions.
    source : str
        Name of the hindcast quoted in error messages.

    Returns
    -------
    xarray.Dataset
        Dim ``bin`` (integer coordinate ``0..K-1``, non-empty bins, Hs-major order); the
        five variables (means for Hs, W, Tp; sector centres for directions);
        ``probability`` (sums to 1); ``hours``; class labels ``hs_bin``, ``wind_bin``,
        ``tp_bin`` (strings such as ``"1.5-3"``) and class indices ``hs_class``,
        ``wind_class``, ``tp_class``. Attributes hold the edges and sector width.
    """
    pts = hindcast_points(hindcast, source=source)
    col = {v: pts[:, k] for k, v in enumerate(names.METOCEAN_VARS)}
    sm = scatter_matrix(
        col["hs"],
        col["wind_speed"],
        col["tp"],
        col["wave_dir"],
        col["wind_dir"],
        hs_edges=hs_edges,
        wind_edges=wind_edges,
        tp_edges=tp_edges,
        sector=sector,
    )
    labels = {
        "hs": np.array(class_labels(hs_edges)),
        "wind": np.array(class_labels(wind_edges)),
        "tp": np.array(class_labels(tp_edges)),
    }
    rep = {
        "hs": "mean of the bin's hours",
        "tp": "mean of the bin's hours",
        "wind_speed": "mean of the bin's hours",
        "wave_dir": f"most likely {sector:g}-degree sector of the bin's hours (sector centre)",
        "wind_dir": f"most likely {sector:g}-degree sector of the bin's hours (sector centre)",
    }
    data_vars: dict[str, tuple[str, np.ndarray, dict[str, object]]] = {}
    for var in names.METOCEAN_VARS:
        data_vars[var] = (names.BIN, getattr(sm, var), {**names.attrs_for(var), "representative": rep[var]})
    data_vars["probability"] = (names.BIN, sm.probability, {"units": "1", "long_name": "probability of occurrence"})
    data_vars["hours"] = (names.BIN, sm.hours, {"units": "h", "long_name": "hindcast hours in the bin"})
    for axis, cls, unit in (("hs", sm.hs_class, "m"), ("wind", sm.wind_class, "m s-1"), ("tp", sm.tp_class, "s")):
        data_vars[f"{axis}_bin"] = (names.BIN, labels[axis][cls], {"long_name": f"{axis} class ({unit})"})
        data_vars[f"{axis}_class"] = (names.BIN, cls, {"units": "1", "long_name": f"{axis} class index"})
    ds = xr.Dataset(data_vars, coords={names.BIN: np.arange(sm.hours.size, dtype=np.int64)})
    _log.info("%s: %d non-empty bins of %d", source, sm.hours.size, len(hs_edges) * len(wind_edges) * len(tp_edges))
    ds.attrs.update(
        {
            "method": "scatter matrix binned by hs, then wind_speed, then tp (Barrera et al. 2019, section 4.1)",
            "hs_edges": [float(v) for v in hs_edges],
            "wind_edges": [float(v) for v in wind_edges],
            "tp_edges": [float(v) for v in tp_edges],
            "edges_meaning": "lower class edges; the last class of each variable is open",
            "direction_sector": float(sector),
            "n_bins_total": int(len(hs_edges) * len(wind_edges) * len(tp_edges)),
            "n_hindcast": int(pts.shape[0]),
            "total_hours": int(pts.shape[0]),
        }
    )
    if names.TIME in hindcast.coords and hindcast.sizes[names.TIME] > 1:
        t = pd.DatetimeIndex(hindcast[names.TIME].values)
        ds.attrs["period"] = f"{t[0].isoformat()} / {t[-1].isoformat()}"
    return ds
