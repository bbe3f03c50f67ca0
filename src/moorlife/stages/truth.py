"""Stage 'truth': simulate every hour of a window and compare the life-cycle method with it.

Rules (``workflow/rules/truth.smk``), opt-in, outside ``rule all``:

* ``truth_hours``: ``results/metocean/hindcast.zarr`` -> ``results/truth/hours.zarr``, the
  window's sea states as a cases-like store (dim ``case`` = the hour's ``hindcast_index``, so
  the hour keeps its random stream whatever the window), :func:`hours_store`;
* ``truth_hours_seed2``: ``truth.n_second_seed`` of them, evenly spaced or with a storm stratum
  of ``truth.second_seed_storm`` hours, :func:`seed2_store`;
* ``truth_simulate`` / ``truth_simulate_seed2``: the simulate stage as it is
  (``use rule simulate_cases``, :func:`moorlife.stages.simulate.run`) on those stores, streams
  ``"truth"`` and ``"truth_seed2"``;
* ``truth_compare``: :func:`run`, the store, the CSV and the two figures. It refits the
  system's reconstruction from the lifecycle rule's inputs (checked against ``lifecycle.zarr``
  on the window) for the training records' seed scatter of the window's sums
  (:func:`window_records`), in the bias test and the band.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

from moorlife import lifecycle as lc_mod
from moorlife import names
from moorlife import truth as kernels
from moorlife.io import open_zarr, save_figure, write_zarr

__all__ = ["hours_store", "seed2_store", "comparison_table", "window_records", "run"]

PathLike = str | os.PathLike[str]
log = logging.getLogger(__name__)


def hours_store(hindcast: PathLike, output: PathLike, *, start: str, end: str, stride: int) -> xr.Dataset:
    """``results/truth/hours.zarr``: every ``stride``-th hindcast hour of the window.

    Dim ``case`` whose coordinate is the hour's position in the hindcast (also stored as
    ``hindcast_index``), the five sea-state variables, the ``time`` coordinate and
    ``role = "truth"``.
    """
    hc = open_zarr(hindcast)
    times = hc[names.TIME].values
    idx = kernels.window_indices(
        times, np.datetime64(pd.Timestamp(start)), np.datetime64(pd.Timestamp(end)), int(stride), source=str(hindcast)
    )
    data: dict[str, Any] = {
        v: (names.CASE, np.asarray(hc[v].values[idx], dtype=float), names.attrs_for(v)) for v in names.METOCEAN_VARS
    }
    data["hindcast_index"] = (
        names.CASE,
        idx,
        {"units": "1", "long_name": "position of the hour along the hindcast 'time'"},
    )
    data["role"] = (names.CASE, np.array(["truth"] * idx.size), {"long_name": "truth: an hour of the truth window"})
    ds = xr.Dataset(data, coords={names.CASE: idx, names.TIME: (names.CASE, times[idx])})
    ds.attrs.update(
        {
            "window_start": str(start),
            "window_end": str(end),
            "stride": int(stride),
            "description": "every stride-th hindcast hour of the truth window (case id = hindcast index)",
        }
    )
    log.info("truth window %s .. %s, stride %d: %d hours", start, end, int(stride), idx.size)
    write_zarr(ds, output)
    return ds


def seed2_store(hours: PathLike, output: PathLike, *, n: int, storm: int = 0) -> xr.Dataset:
    """``results/truth/hours_seed2.zarr``: ``n`` hours of ``hours.zarr``, evenly spaced, or the
    ``storm`` hours of largest Hs and ``n - storm`` evenly spaced (:func:`moorlife.truth.second_seed_subset`)."""
    ds = open_zarr(hours)
    pick = kernels.second_seed_subset(ds.sizes[names.CASE], int(n), hs=ds["hs"].values, storm=int(storm))
    sub = ds.isel({names.CASE: pick})
    how = f"the {int(storm)} of largest Hs and {int(n) - int(storm)} evenly spaced" if storm else "evenly spaced"
    sub.attrs["description"] = f"{int(n)} truth hours ({how}) simulated with a second seed (the noise floor)"
    sub.attrs["second_seed_storm"] = int(storm)
    write_zarr(sub, output)
    return sub


def comparison_table(cmp: xr.Dataset) -> pd.DataFrame:
    """The CSV of the comparison: one row per output, then one per (curve, line).

    Output rows: ``r``, ``rmse``, ``bias``, ``sum_error``, ``noise_r``, ``ceiling_r``. Damage rows:
    ``truth_damage``, ``reconstruction_damage``, ``bins_damage``, the signed errors in % and
    the seed scatter of the sum in %.
    """
    rows: list[dict[str, Any]] = []
    for j, lab in enumerate(cmp["output"].values):
        row = {"kind": "output", "output": str(lab)}
        for k in ("r", "rmse", "bias", "sum_error", "noise_r", "ceiling_r"):
            if k in cmp:
                row[k] = float(cmp[k].values[j])
        rows.append(row)
    if names.CURVE in cmp.dims:
        for cv in cmp[names.CURVE].values:
            for ln in cmp[names.LINE].values:
                sel = {names.CURVE: cv, names.LINE: ln}
                row = {"kind": "damage", "output": f"damage_{cv}/{ln}", "curve": str(cv), "line": str(ln)}
                for k in kernels.WINDOW_DAMAGE_VARS:
                    if k in cmp:
                        row[k] = float(cmp[k].sel(sel))
                rows.append(row)
    return pd.DataFrame(rows)


def window_records(fitted: lc_mod.Fitted, lc: xr.Dataset, hours: np.ndarray, *, source: str) -> dict[str, float]:
    """Per damage output, the window sum's seed sd from its training records per unit record CV.

    :func:`moorlife.lifecycle.records_term` of the refitted reconstruction on the window's hours
    (``hours``, positions along ``lc``'s time), weighted by ``lc``'s own hourly damage.

    Raises
    ------
    ValueError
        If the refit does not reproduce ``lc``'s damage on the window (to 1e-9 relative): the store
        was not built from these simulations and settings.
    """
    idx = np.asarray(hours, dtype=np.int64)
    sub = lc.isel({names.TIME: idx})
    points = np.column_stack([sub[v].values for v in names.METOCEAN_VARS])
    pred = lc_mod.predict_outputs(fitted.model, points)
    labels = [lc_mod._label(c) for c in fitted.cols]
    stored = pred.copy()
    for j, (var, line) in enumerate(fitted.cols):
        if var in lc_mod.DAMAGE_VARS.values() and var in sub:
            stored[:, j] = sub[var].sel({names.LINE: line}).values  # a damage output is per line
            bad = ~np.isclose(pred[:, j], stored[:, j], rtol=1e-9, atol=0.0)
            if bad.any():
                h = int(np.flatnonzero(bad)[0])
                raise ValueError(
                    f"{source}: {labels[j]} at hindcast hour {int(idx[h])} is {stored[h, j]!r}, a refit from the "
                    f"lifecycle rule's inputs gives {pred[h, j]!r}: the store was built from other simulations or settings"
                )
    term = lc_mod.records_term(fitted, points, stored)
    return {lab: float(v) for lab, v in zip(labels, term) if np.isfinite(v)}


def run(
    truth: PathLike,
    truth_seed2: PathLike | None,
    lifecycle: PathLike,
    discrete_states: PathLike,
    discrete_sims: PathLike,
    outputs: Mapping[str, PathLike],
    *,
    compared: Sequence[str],
    mooring_system: str,
    second_seed_storm: int = 0,
    fit: Mapping[str, Any] | None = None,
) -> xr.Dataset:
    """Compare ``lifecycle.zarr`` with the truth; write the store, the CSV and the figures.

    ``outputs`` maps ``store``, ``csv``, ``scatter`` and ``cumulative`` to their paths;
    ``compared`` lists the outputs (``lifecycle.rbf.outputs``); ``second_seed_storm`` is
    ``truth.second_seed_storm``, the second seed's storm stratum. ``fit`` holds the arguments of
    :func:`moorlife.stages.lifecycle.refit` (the lifecycle rule's inputs and settings): with it the
    window's records' term (:func:`window_records`) enters the bias test and the band.
    """
    from moorlife.plots import truth as plots

    lc = open_zarr(lifecycle, load=False)
    keep = [v for v in lc.data_vars if names.TIME in lc[v].dims and (v in compared or v in names.METOCEAN_VARS)]
    keep += [v for v in ("validation_sum_error",) if v in lc]  # the band's reconstruction term
    lc = lc[keep].load()
    tr = open_zarr(truth)
    records = None
    if fit is not None:
        from moorlife.stages.lifecycle import refit

        records = window_records(refit(**fit), lc, tr["hindcast_index"].values, source=str(lifecycle))
        log.info("records' term of the window's sums, per unit CV of one record: %s", records)
    cmp = kernels.compare_window(
        tr,
        lc,
        open_zarr(discrete_states),
        open_zarr(discrete_sims),
        outputs=list(compared),
        seed2=open_zarr(truth_seed2) if truth_seed2 else None,
        second_seed_storm=second_seed_storm,
        records=records,
    )
    table = comparison_table(cmp)
    log.info("truth comparison of %s on %d hours:\n%s", mooring_system, cmp.attrs["n_hours"], table.to_string())
    write_zarr(cmp, outputs["store"])
    p = Path(outputs["csv"])
    p.parent.mkdir(parents=True, exist_ok=True)
    table.to_csv(p, index=False, float_format="%.6g")
    save_figure(plots.truth_scatter(cmp, title=mooring_system), outputs["scatter"])
    save_figure(
        plots.cumulative_damage(cmp, title=f"{mooring_system}, {cmp.attrs['n_hours']} truth hours"),
        outputs["cumulative"],
    )
    return cmp
