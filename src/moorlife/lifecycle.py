"""Life-cycle reconstruction, life-cycle damage, the conventional baseline and the comparison.

Methodology steps 6-9 (Barrera et al. 2019, sections 3.4-4): the outputs of the simulated
training states are rebuilt for every hindcast hour with :mod:`moorlife.rbf`, validated on
the states kept aside, and the rebuilt hourly damage is summed over the hindcast. That sum is
compared with the damage of the discrete scatter matrix (probability x hourly damage x hours),
turned into a fatigue life and a design check (DNVGL-OS-E301 / API RP 2SK factors from
:mod:`moorlife.fatigue`), and the mooring systems are ranked by a recommendation rule.

Kernels take and return numpy arrays; :func:`reconstruct_lifecycle`,
:func:`discrete_damage_table` and :func:`summary_table` are the xarray/pandas adapters used
by the workflow scripts. Conventions:

* ``lifecycle damage`` is the sum of the hourly damage over every hour of the hindcast;
  per year it is divided by the hindcast length in years (hours / 8766), and over the design
  life it is the yearly damage times the design life.
* ``difference_pct = 100 (D_lifecycle - D_discrete) / D_lifecycle``: positive when the
  discrete matrix underestimates (the sign of the paper's Table 7).
* ``passes``: ``DFF x D_design_life <= 1`` with the design fatigue factor of the curve
  family's rule (``fatigue.design_factor``) and, for DNV, ``dF`` = the damage of the line
  adjacent to the most damaged one over the most damaged (:func:`fatigue.adjacent_damage_ratio`).
"""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
import pandas as pd
import xarray as xr

from moorlife import fatigue, names, rbf

__all__ = [
    "HOURS_PER_YEAR",
    "DEFAULT_OUTPUTS",
    "DAMAGE_VARS",
    "RBFSettings",
    "rbf_settings",
    "output_columns",
    "stack_outputs",
    "unstack_outputs",
    "validation_metrics",
    "fit_outputs",
    "life_damage",
    "damage_per_year",
    "design_check",
    "discrete_damage",
    "difference_pct",
    "recommend",
    "error_indicator",
    "suggest_states",
    "life_band",
    "reconstruct_lifecycle",
    "discrete_damage_table",
    "summary_table",
    "seed_lives",
    "corrosion_evolution",
    "mean_stress_table",
]

log = logging.getLogger(__name__)

#: Hours in a mean Julian year (365.25 days).
HOURS_PER_YEAR = 8766.0
#: Outputs rebuilt by default: the contract outputs of simulations.zarr.
DEFAULT_OUTPUTS: tuple[str, ...] = names.SIM_SCALAR_VARS + names.SIM_LINE_VARS
DAMAGE_VARS: dict[str, str] = {"sn": "damage_sn", "tn": "damage_tn"}


# --------------------------------------------------------------------------- settings


@dataclass(frozen=True)
class RBFSettings:
    """The ``lifecycle.rbf`` config section.

    Attributes
    ----------
    shape_mode : {"rippa", "fixed"}
    fixed_damage, fixed_tension, fixed_other : float
        Fixed ``q0`` (paper: 0.1 damage, 0.175 tension).
    grid_min, grid_max : float
    grid_n : int
        Rippa's search grid (geometric).
    share_tol : float
        See :func:`moorlife.rbf.choose_shapes`.
    log_damage : bool
        Interpolate ``log10`` of the damage outputs.
    smoothing : tuple of float
        Ridge candidates on the kernel diagonal; with several, each output takes the one with
        the smallest leave-one-out error, jointly with its shape (``(0.0,)``: exact
        interpolation, the paper's choice).
    chunk_rows : int
    outputs : tuple of str
        Variables of ``simulations.zarr`` to rebuild.
    """

    shape_mode: str = "rippa"
    fixed_damage: float = 0.1
    fixed_tension: float = 0.175
    fixed_other: float = 0.175
    grid_min: float = 0.05
    grid_max: float = 1.0
    grid_n: int = 10
    share_tol: float = 0.0
    log_damage: bool = True
    smoothing: tuple[float, ...] = (0.0,)
    chunk_rows: int = 8192
    outputs: tuple[str, ...] = DEFAULT_OUTPUTS + ("tension_mean", "surge_mean", "sway_mean")


def rbf_settings(section: Mapping[str, Any] | None = None, source: str = "config.yaml") -> RBFSettings:
    """Build :class:`RBFSettings` from ``config["lifecycle"]["rbf"]``.

    Raises
    ------
    ValueError
        Naming the key and value of an invalid setting.
    """
    s = dict(section or {})
    fixed = dict(s.get("fixed", {}))
    grid = dict(s.get("grid", {}))
    mode = str(s.get("shape", "rippa"))
    if mode not in ("rippa", "fixed"):
        raise ValueError(f"{source}: lifecycle.rbf.shape = {mode!r}; expected 'rippa' or 'fixed'")
    d = RBFSettings()
    out = RBFSettings(
        shape_mode=mode,
        fixed_damage=float(fixed.get("damage", d.fixed_damage)),
        fixed_tension=float(fixed.get("tension", d.fixed_tension)),
        fixed_other=float(fixed.get("other", d.fixed_other)),
        grid_min=float(grid.get("min", d.grid_min)),
        grid_max=float(grid.get("max", d.grid_max)),
        grid_n=int(grid.get("n", d.grid_n)),
        share_tol=float(s.get("share_tol", d.share_tol)),
        log_damage=bool(s.get("log_damage", d.log_damage)),
        smoothing=_smoothing(s.get("smoothing", d.smoothing), source),
        chunk_rows=int(s.get("chunk_rows", d.chunk_rows)),
        outputs=tuple(s.get("outputs", d.outputs)),
    )
    if not 0 < out.grid_min < out.grid_max:
        raise ValueError(f"{source}: lifecycle.rbf.grid needs 0 < min < max, got {out.grid_min}, {out.grid_max}")
    return out


def _smoothing(value: Any, source: str) -> tuple[float, ...]:
    """``lifecycle.rbf.smoothing`` as a tuple of candidates (a number or a list of numbers >= 0)."""
    vals = list(value) if isinstance(value, (list, tuple)) else [value]
    try:
        out = tuple(float(v) for v in vals)
    except (TypeError, ValueError):
        raise ValueError(f"{source}: lifecycle.rbf.smoothing = {value!r}; expected numbers >= 0") from None
    if not out or any(not (v >= 0) for v in out):
        raise ValueError(f"{source}: lifecycle.rbf.smoothing = {value!r}; expected numbers >= 0")
    return out


# --------------------------------------------------------------------------- outputs <-> matrices


def output_columns(ds: xr.Dataset, dim: str, wanted: Sequence[str]) -> list[tuple[str, str | None]]:
    """The (variable, line) columns of a simulation store that are rebuilt.

    Parameters
    ----------
    ds : xarray.Dataset
        ``simulations.zarr`` (dims ``case``, ``line``) or ``discrete.zarr``.
    dim : str
        ``"case"`` or ``"bin"``.
    wanted : sequence of str
        Variable names; missing ones are skipped (logged), so optional extras do not fail.

    Returns
    -------
    list of (name, line or None)
    """
    cols: list[tuple[str, str | None]] = []
    for v in wanted:
        if v not in ds:
            log.info("output %r not in the simulation store: not rebuilt", v)
            continue
        dims = ds[v].dims
        if dims == (dim,):
            cols.append((v, None))
        elif set(dims) == {dim, names.LINE}:
            cols += [(v, str(line)) for line in ds[names.LINE].values]
        else:
            raise ValueError(f"variable {v!r} has dims {dims}; expected ({dim!r},) or ({dim!r}, 'line')")
    return cols


def _label(col: tuple[str, str | None]) -> str:
    return col[0] if col[1] is None else f"{col[0]}/{col[1]}"


def stack_outputs(ds: xr.Dataset, dim: str, cols: Sequence[tuple[str, str | None]]) -> np.ndarray:
    """Matrix ``(n, k)`` of the columns of :func:`output_columns` along ``dim``."""
    out = np.empty((ds.sizes[dim], len(cols)))
    for j, (v, line) in enumerate(cols):
        da = ds[v] if line is None else ds[v].sel({names.LINE: line})
        out[:, j] = da.transpose(dim).to_numpy()
    return out


def unstack_outputs(
    values: np.ndarray, cols: Sequence[tuple[str, str | None]], dim: str, coords: Mapping[str, Any], attrs_of=None
) -> xr.Dataset:
    """Inverse of :func:`stack_outputs`: a Dataset with ``(dim,)`` and ``(dim, line)`` variables."""
    data: dict[str, Any] = {}
    by_var: dict[str, list[tuple[int, str | None]]] = {}
    for j, (v, line) in enumerate(cols):
        by_var.setdefault(v, []).append((j, line))
    for v, items in by_var.items():
        attrs = (attrs_of or _attrs)(v)
        if items[0][1] is None:
            data[v] = xr.Variable((dim,), values[:, items[0][0]], attrs)
        else:
            idx = [j for j, _ in items]
            data[v] = xr.DataArray(
                values[:, idx], dims=(dim, names.LINE), coords={names.LINE: [ln for _, ln in items]}, attrs=attrs
            )
    return xr.Dataset(data, coords=dict(coords))


def _attrs(name: str) -> dict[str, str]:
    try:
        return names.attrs_for(name)
    except KeyError:
        from moorlife.simulate import output_attrs

        try:
            return output_attrs(name)
        except KeyError:
            return {"units": "1"}


# --------------------------------------------------------------------------- fit / validate


def validation_metrics(predicted: npt.ArrayLike, simulated: npt.ArrayLike) -> dict[str, np.ndarray]:
    """Per-output agreement of rebuilt and simulated values (paper Figs. 10-13).

    Parameters
    ----------
    predicted, simulated : array_like, shape (n, k)

    Returns
    -------
    dict
        ``r`` (Pearson correlation), ``rmse``, ``bias`` (mean of predicted - simulated),
        ``nrmse`` (RMSE / standard deviation of simulated), ``slope`` and ``intercept``
        of the least-squares line simulated -> predicted, ``sum_error`` (relative error of
        the sum, the quantity that matters for life damage); each shape (k,).
    """
    p = np.atleast_2d(np.asarray(predicted, dtype=float).T).T
    s = np.atleast_2d(np.asarray(simulated, dtype=float).T).T
    if p.shape != s.shape:
        raise ValueError(f"predicted {p.shape} and simulated {s.shape} differ in shape")
    pc = p - p.mean(axis=0)
    sc = s - s.mean(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        r = (pc * sc).sum(axis=0) / np.sqrt((pc**2).sum(axis=0) * (sc**2).sum(axis=0))
        slope = (pc * sc).sum(axis=0) / (sc**2).sum(axis=0)
        nrmse = np.sqrt(np.mean((p - s) ** 2, axis=0)) / s.std(axis=0)
        sum_err = p.sum(axis=0) / s.sum(axis=0) - 1.0
    return {
        "r": r,
        "rmse": np.sqrt(np.mean((p - s) ** 2, axis=0)),
        "bias": np.mean(p - s, axis=0),
        "nrmse": nrmse,
        "slope": slope,
        "intercept": p.mean(axis=0) - slope * s.mean(axis=0),
        "sum_error": sum_err,
    }


def fit_outputs(
    points: np.ndarray,
    values: np.ndarray,
    cols: Sequence[tuple[str, str | None]],
    settings: RBFSettings,
    *,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
    log_damage: bool | None = None,
) -> rbf.RBFModel:
    """Fit the RBF of every output column with the configured shape rule.

    Parameters
    ----------
    points : numpy.ndarray, shape (m, 5)
        Training sea states in ``names.METOCEAN_VARS`` order.
    values : numpy.ndarray, shape (m, k)
    cols : sequence of (name, line)
    settings : RBFSettings
    lo, span : array_like (5,), optional
        Normalisation of the selection (``cases.zarr`` attributes ``norm_lo``/``norm_span``).
    log_damage : bool, optional
        Overrides ``settings.log_damage`` (used to compare both transforms).

    Returns
    -------
    moorlife.rbf.RBFModel
    """
    is_dmg = np.array([c[0].startswith("damage") for c in cols])
    use_log = settings.log_damage if log_damage is None else log_damage
    logs = is_dmg & bool(use_log)
    if logs.any():
        values = values.copy()
        for j in np.flatnonzero(logs):
            bad = ~(values[:, j] > 0)
            if bad.any():  # a calm state with no counted cycle: floor at the smallest positive damage
                pos = values[values[:, j] > 0, j]
                floor = pos.min() if pos.size else 1e-30
                log.warning("%s: %d non-positive damage value(s) floored at %.3g for the log transform",
                            _label(cols[j]), int(bad.sum()), floor)
                values[bad, j] = floor
    mask = np.array([v in names.DIRECTION_VARS for v in names.METOCEAN_VARS])
    common = dict(is_direction=mask, log_output=logs, smoothing=settings.smoothing, lo=lo, span=span)
    if settings.shape_mode == "fixed":
        q = np.array([
            settings.fixed_damage if c[0].startswith("damage")
            else settings.fixed_tension if c[0].startswith("tension") else settings.fixed_other
            for c in cols
        ])
        return rbf.fit_rbf(points, values, shape=q, **common)
    grid = rbf.shape_grid(settings.grid_min, settings.grid_max, settings.grid_n)
    return rbf.fit_rbf(points, values, shapes=grid, share_tol=settings.share_tol, **common)


# --------------------------------------------------------------------------- damage arithmetic


def life_damage(hourly: npt.ArrayLike, axis: int = 0) -> np.ndarray:
    """Life-cycle damage: the sum of the hourly damage over every hour (paper eq. 13).

    Parameters
    ----------
    hourly : array_like, shape (n_hours, ...)
        Damage per hour of sea state.

    Returns
    -------
    numpy.ndarray, shape (...)

    Raises
    ------
    ValueError
        If any hourly damage is negative or not finite (naming the first bad hour).
    """
    h = np.asarray(hourly, dtype=float)
    bad = ~np.isfinite(h) | (h < 0)
    if bad.any():
        idx = np.argwhere(bad)[0]
        raise ValueError(f"hourly damage at index {tuple(int(i) for i in idx)} is {h[tuple(idx)]!r}; must be >= 0")
    return h.sum(axis=axis)


def damage_per_year(total: npt.ArrayLike, n_hours: float) -> np.ndarray:
    """Damage per (Julian) year from the damage of ``n_hours`` hours."""
    if not n_hours > 0:
        raise ValueError(f"n_hours must be positive, got {n_hours!r}")
    return np.asarray(total, dtype=float) * (HOURS_PER_YEAR / float(n_hours))


def design_check(
    per_year: npt.ArrayLike, design_life: float, curve: str, settings: fatigue.FatigueSettings, line_axis: int = -1
) -> dict[str, np.ndarray]:
    """Design fatigue factor, design-life damage and verdict for each line.

    Parameters
    ----------
    per_year : array_like, shape (..., n_line)
        Yearly damage of each line (one curve family).
    design_life : float
        Years.
    curve : {"sn", "tn"}
        Selects the rule (``settings.rule_sn`` / ``rule_tn``: ``dnv`` or ``api``).
    settings : moorlife.fatigue.FatigueSettings
    line_axis : int

    Returns
    -------
    dict
        ``damage_ratio`` dF (shape ``(...)``), ``design_fatigue_factor`` (...),
        ``design_life_damage`` (..., n_line), ``utilisation`` = DFF x design-life damage,
        ``passes`` (utilisation <= 1), ``fatigue_life_years`` (characteristic, 1 / yearly)
        and ``design_fatigue_life_years`` (1 / (DFF x yearly)).
    """
    d = np.asarray(per_year, dtype=float)
    ratio = fatigue.adjacent_damage_ratio(d, axis=line_axis)
    dff = settings.design_factor(curve, ratio)
    dff_b = np.expand_dims(dff, line_axis)
    dl = d * float(design_life)
    util = dff_b * dl
    return {
        "damage_ratio": ratio,
        "design_fatigue_factor": dff,
        "design_life_damage": dl,
        "utilisation": util,
        "passes": util <= 1.0,
        "fatigue_life_years": fatigue.fatigue_life(d),
        "design_fatigue_life_years": fatigue.fatigue_life(d, design_factor=dff_b),
    }


def discrete_damage(probability: npt.ArrayLike, hourly: npt.ArrayLike, n_hours: float) -> np.ndarray:
    """Damage of the conventional method: ``sum_b probability_b x hourly damage_b x hours``.

    Parameters
    ----------
    probability : array_like, shape (n_bin,)
        Occurrence probability of each bin (sums to 1).
    hourly : array_like, shape (n_bin, ...)
        Hourly damage of each bin's representative state.
    n_hours : float
        Hours of the period (the hindcast's, for a like-for-like comparison).

    Returns
    -------
    numpy.ndarray, shape (...)

    Raises
    ------
    ValueError
        If the probabilities are negative or do not sum to 1 (to 1e-6).
    """
    p = np.asarray(probability, dtype=float)
    h = np.asarray(hourly, dtype=float)
    if p.ndim != 1 or p.shape[0] != h.shape[0]:
        raise ValueError(f"probability {p.shape} and hourly damage {h.shape} do not match along the bins")
    if np.any(p < 0) or abs(p.sum() - 1.0) > 1e-6:
        raise ValueError(f"bin probabilities must be >= 0 and sum to 1, got sum {p.sum()!r}")
    life_damage(h)  # same checks as the hourly damage of the hindcast
    return np.tensordot(p, h, axes=(0, 0)) * float(n_hours)


def difference_pct(lifecycle: npt.ArrayLike, discrete: npt.ArrayLike) -> np.ndarray:
    """``100 (lifecycle - discrete) / lifecycle``: > 0 when the discrete matrix underestimates."""
    lc = np.asarray(lifecycle, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return 100.0 * (lc - np.asarray(discrete, dtype=float)) / lc


def recommend(
    table: pd.DataFrame, *, curves: Sequence[str] = ("sn", "tn"), mass_column: str = "mass_kg_per_m"
) -> str | None:
    """The lightest mooring system that passes the design check on every line and curve.

    Parameters
    ----------
    table : pandas.DataFrame
        One row per (``mooring_system``, ``line``, ``curve``) with ``passes`` and the mass.
    curves : sequence of str
        Curve families that must pass (default both S-N and T-N).
    mass_column : str
        Column ranking the systems (lightest first; ties by id).

    Returns
    -------
    str or None
        The system id, or None when no system passes.
    """
    for col in ("mooring_system", "curve", "passes", mass_column):
        if col not in table.columns:
            raise ValueError(f"comparison table: column {col!r} missing")
    sub = table[table["curve"].isin(list(curves))]
    if sub.empty:
        raise ValueError(f"comparison table has no rows for curves {list(curves)}")
    ok = sub.groupby("mooring_system")["passes"].all()
    mass = sub.groupby("mooring_system")[mass_column].first()
    order = sorted(ok.index, key=lambda m: (float(mass[m]), str(m)))
    for ms in order:
        if bool(ok[ms]):
            return str(ms)
    return None


# --------------------------------------------------------------------------- uncertainty


def error_indicator(model: rbf.RBFModel, points: npt.ArrayLike, scale: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Where the RBF is least certain: nearest training state's LOO error x distance.

    ``indicator = max_k |e_k(nearest)| / scale_k x (d_nearest / d_typical)``, with ``e``
    Rippa's leave-one-out residuals (:attr:`RBFModel.loo_error`), ``scale`` a per-output
    normaliser (e.g. the standard deviation of the training values) and ``d_typical`` the
    median nearest-neighbour spacing of the training states. High where the surface varies
    fast (large LOO error) and training states are sparse.

    Parameters
    ----------
    model : moorlife.rbf.RBFModel
    points : array_like, shape (n, 5)
    scale : array_like, shape (k,)

    Returns
    -------
    indicator : numpy.ndarray, shape (n,)
    distance : numpy.ndarray, shape (n,)
        Normalised distance to the nearest training state.
    """
    dist, idx = rbf.nearest_centre(model, points)
    typical = _typical_spacing(model)
    s = np.asarray(scale, dtype=float)
    s = np.where(s > 0, s, 1.0)
    loo = np.max(np.abs(model.loo_error) / s, axis=1)  # (m,)
    return loo[idx] * dist / typical, dist


def _typical_spacing(model: rbf.RBFModel) -> float:
    z = model.centres
    d2 = rbf.squared_distances(z, z, model.space.is_direction)
    np.fill_diagonal(d2, np.inf)
    t = float(np.median(np.sqrt(d2.min(axis=1))))
    return t if t > 0 else 1.0


def suggest_states(
    model: rbf.RBFModel, points: npt.ArrayLike, indicator: npt.ArrayLike, n: int,
    distance: npt.ArrayLike | None = None,
) -> np.ndarray:
    """Adaptive selection: the ``n`` hours to simulate next, greedily, most uncertain first.

    Each pick maximises ``indicator x min(1, d_set / d_nearest)`` where ``d_set`` is the
    distance to the training states and the picks so far, so that one uncertain region does
    not take every pick (the running-minimum update of maximum dissimilarity).

    Parameters
    ----------
    model : moorlife.rbf.RBFModel
    points : array_like, shape (n_hours, 5)
    indicator : array_like, shape (n_hours,)
        From :func:`error_indicator`.
    n : int
    distance : array_like, shape (n_hours,), optional
        Distance to the nearest training state (from :func:`error_indicator`); computed if omitted.

    Returns
    -------
    numpy.ndarray of int64, shape (n,)
        Row indices into ``points``, in pick order (ties: lowest index).
    """
    z = rbf.normalise(points, model.space)
    ind = np.asarray(indicator, dtype=float)
    d0 = rbf.nearest_centre(model, points)[0] if distance is None else np.asarray(distance, dtype=float)
    dset = d0.copy()
    picks: list[int] = []
    with np.errstate(invalid="ignore", divide="ignore"):
        for _ in range(min(int(n), z.shape[0])):
            score = ind * np.where(d0 > 0, np.minimum(1.0, dset / d0), 0.0)
            k = int(np.argmax(score))
            if score[k] <= 0:
                break
            picks.append(k)
            dk = np.sqrt(rbf.squared_distances(z, z[k : k + 1], model.space.is_direction)[:, 0])
            dset = np.minimum(dset, dk)
    return np.asarray(picks, dtype=np.int64)


def life_band(life_years: npt.ArrayLike, rel_sigma: npt.ArrayLike, k: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """Band on fatigue life from a relative damage uncertainty.

    ``life / (1 + k sigma)`` to ``life / max(1 - k sigma, 0)`` (infinite when ``k sigma >= 1``).

    Parameters
    ----------
    life_years : array_like
    rel_sigma : array_like
        Relative standard uncertainty of the damage, e.g. ``sqrt(cv_seed^2 + err_rbf^2)``.
    k : float
        Coverage factor (1: one standard deviation).
    """
    life = np.asarray(life_years, dtype=float)
    s = k * np.asarray(rel_sigma, dtype=float)
    with np.errstate(divide="ignore"):
        hi = np.where(s < 1, life / np.where(s < 1, 1 - s, 1.0), np.inf)
    return life / (1 + s), hi


# --------------------------------------------------------------------------- xarray adapters


def _points(ds: xr.Dataset, dim: str) -> np.ndarray:
    missing = [v for v in names.METOCEAN_VARS if v not in ds]
    if missing:
        raise ValueError(f"dataset along {dim!r} lacks the sea-state variable(s) {missing}")
    return np.column_stack([ds[v].transpose(dim).to_numpy().astype(float) for v in names.METOCEAN_VARS])


def _selection_scaling(cases: xr.Dataset) -> tuple[np.ndarray | None, np.ndarray | None]:
    """The selection's normalisation (``norm_lo``/``norm_span`` attributes) in METOCEAN_VARS order."""
    lo, span = cases.attrs.get("norm_lo"), cases.attrs.get("norm_span")
    if lo is None or span is None:
        log.info("cases store has no norm_lo/norm_span: normalising by the training states' range")
        return None, None
    order = list(cases.attrs.get("norm_variables", names.METOCEAN_VARS))
    missing = [v for v in names.METOCEAN_VARS if v not in order]
    if missing or len(order) != len(lo) or len(order) != len(span):
        raise ValueError(f"cases.zarr: attributes norm_variables {order}, norm_lo, norm_span are inconsistent "
                         f"(need {list(names.METOCEAN_VARS)})")
    idx = [order.index(v) for v in names.METOCEAN_VARS]
    return np.asarray(lo, dtype=float)[idx], np.asarray(span, dtype=float)[idx]


def _a(long_name: str, units: str = "1") -> dict[str, str]:
    return {"units": units, "long_name": long_name}


def _fit_vars(out: xr.Dataset, model: rbf.RBFModel, x_train: np.ndarray, ids: np.ndarray) -> xr.Dataset:
    """Shape parameters, transforms and leave-one-out residuals of the fit."""
    out = out.assign_coords(train=("train", ids))
    out["shape_parameter"] = ("output", model.shape, _a("RBF shape parameter q0 (normalised distance)"))
    out["smoothing"] = ("output", model.smoothing, _a("RBF ridge term on the kernel diagonal (0: exact)"))
    out["loo_rmse"] = ("output", np.sqrt(np.mean(model.loo_error**2, axis=0)),
                       _a("Rippa leave-one-out RMSE (transformed space)"))
    out["log_transform"] = ("output", model.log_output.astype(np.int8), _a("1 if interpolated as log10"))
    out["train_points"] = (("train", "metocean_var"), x_train, _a("training sea states (physical units)"))
    out["loo_error"] = (("train", "output"), model.loo_error, _a("leave-one-out residual per training state"))
    return out


def _validation_vars(out: xr.Dataset, model: rbf.RBFModel, x_val: np.ndarray, y_val: np.ndarray,
                     ids: np.ndarray) -> xr.Dataset:
    """Rebuilt vs simulated values on the validation states and their metrics."""
    pv = rbf.predict_rbf(model, x_val)
    for k, v in validation_metrics(pv, y_val).items():
        out[f"validation_{k}"] = ("output", v, _a(f"validation {k} on {len(ids)} states"))
    out = out.assign_coords(validate=("validate", ids))
    out["validate_points"] = (("validate", "metocean_var"), x_val, _a("validation sea states"))
    out["validation_predicted"] = (("validate", "output"), pv, _a("rebuilt value at validation states"))
    out["validation_simulated"] = (("validate", "output"), y_val, _a("simulated value at validation states"))
    return out


def _damage_vars(out: xr.Dataset, n_hours: int, fs: fatigue.FatigueSettings) -> xr.Dataset:
    """Life-cycle damage, yearly and design-life damage, fatigue life and design check per line and curve."""
    curves = [c for c in names.CURVES if DAMAGE_VARS[c] in out]
    if not curves:
        return out
    hourly = [np.clip(out[DAMAGE_VARS[c]].transpose(names.TIME, names.LINE).values, 0, None) for c in curves]
    total = np.stack([life_damage(h) for h in hourly])  # (curve, line)
    py = damage_per_year(total, n_hours)
    checks = [design_check(py[i], fs.design_life, c, fs) for i, c in enumerate(curves)]
    cd = (names.CURVE, names.LINE)
    out = out.assign_coords({names.CURVE: curves})
    out["lifecycle_damage"] = (cd, total, _a(f"damage summed over the {n_hours} hindcast hours"))
    out["damage_per_year"] = (cd, py, _a("life-cycle damage per year", "year-1"))
    for key, dims, text, units in (
        ("design_life_damage", cd, f"damage over the {fs.design_life:g} year design life", "1"),
        ("fatigue_life_years", cd, "characteristic fatigue life (D = 1)", "year"),
        ("design_fatigue_factor", (names.CURVE,), "design fatigue factor (DNVGL-OS-E301 or API)", "1"),
        ("damage_ratio", (names.CURVE,), "dF: adjacent-line over most-damaged-line damage", "1"),
        ("utilisation", cd, "DFF x design-life damage (passes if <= 1)", "1"),
    ):
        out[key] = (dims, np.stack([c[key] for c in checks]), _a(text, units))
    passes = np.stack([c["passes"] for c in checks]).astype(np.int8)
    out["passes"] = (cd, passes, _a("1 if DFF x design-life damage <= 1"))
    out.attrs["design_life_years"] = float(fs.design_life)
    return out


def _uncertainty_vars(out: xr.Dataset, model: rbf.RBFModel, hp: np.ndarray, scale: np.ndarray,
                      n_suggest: int) -> xr.Dataset:
    """Error indicator per hour and the adaptive-selection suggestions."""
    ind, dist = error_indicator(model, hp, scale)
    out["nearest_distance"] = (names.TIME, dist, _a("normalised distance to the nearest training state"))
    out["error_indicator"] = (names.TIME, ind, _a("LOO error of the nearest training state x relative distance"))
    picks = suggest_states(model, hp, ind, n_suggest, distance=dist)
    out = out.assign_coords(suggestion=("suggestion", np.arange(picks.size)))
    out["suggested_hour"] = ("suggestion", picks, _a("hindcast index to simulate next (adaptive selection)"))
    return out


def reconstruct_lifecycle(
    hindcast: xr.Dataset,
    cases: xr.Dataset,
    sims: xr.Dataset,
    *,
    settings: RBFSettings,
    fatigue_cfg: Mapping[str, Any] | None = None,
    n_suggest: int = 50,
    compare_transforms: bool = True,
) -> xr.Dataset:
    """Rebuild every output for every hindcast hour, with validation and life damage.

    Parameters
    ----------
    hindcast : xarray.Dataset
        ``results/metocean/hindcast.zarr`` (dim ``time``).
    cases : xarray.Dataset
        ``results/selection/cases.zarr`` (dim ``case``, ``role``, optional ``norm_lo``/``norm_span``
        attributes).
    sims : xarray.Dataset
        ``results/{ms}/simulations.zarr`` (dims ``case``, ``line``).
    settings : RBFSettings
    fatigue_cfg : mapping, optional
        The ``fatigue:`` section (design life, design-factor rules).
    n_suggest : int
        Number of adaptive-selection suggestions.
    compare_transforms : bool
        Also validate the other damage transform (linear vs log10) and store its metrics.

    Returns
    -------
    xarray.Dataset
        Dims ``time``, ``line``, ``curve``, ``output``, ``train``, ``suggestion``: every
        rebuilt output on ``time`` (and ``line``); per output the shape parameter, LOO RMSE and
        validation metrics; per line and curve the life-cycle damage, yearly and design-life
        damage, fatigue life, DFF and verdict; the adaptive-selection suggestions.
    """
    dim = names.CASE
    common = np.intersect1d(cases[dim].values, sims[dim].values)
    cases = cases.sel({dim: common})
    sims = sims.sel({dim: common})
    role = np.array([str(v) for v in cases["role"].values])
    train, valid = role == "train", role == "validate"
    if train.sum() < 8:
        raise ValueError(f"only {int(train.sum())} training cases are simulated; the RBF needs at least 8")
    cols = output_columns(sims, dim, settings.outputs)
    y = stack_outputs(sims, dim, cols)
    bad = ~np.isfinite(y)
    if bad.any():
        i, j = np.argwhere(bad)[0]
        raise ValueError(f"simulations: {_label(cols[j])} is not finite for case {int(common[i])} ({y[i, j]!r})")
    x = _points(cases, dim)
    lo, span = _selection_scaling(cases)
    model = fit_outputs(x[train], y[train], cols, settings, lo=lo, span=span)
    labels = [_label(c) for c in cols]
    log.info("RBF fitted on %d training states, %d outputs; shapes %s", int(train.sum()), len(cols),
             {lab: round(float(q), 4) for lab, q in zip(labels, model.shape)})

    hp = _points(hindcast, names.TIME)
    pred = rbf.predict_rbf(model, hp, chunk_rows=settings.chunk_rows)
    out = unstack_outputs(pred, cols, names.TIME, {names.TIME: hindcast[names.TIME].values})
    for v in names.METOCEAN_VARS:
        out[v] = hindcast[v].astype(float)
    is_dmg = np.array([c[0].startswith("damage") for c in cols])
    if is_dmg.any():
        neg = pred[:, is_dmg] < 0
        if neg.any():
            log.warning("%d rebuilt hourly damages are negative (RBF undershoot); clipped to 0 in the sums",
                        int(neg.sum()))

    out = out.assign_coords(output=labels, metocean_var=list(names.METOCEAN_VARS))
    out = _fit_vars(out, model, x[train], common[train])
    if valid.any():
        out = _validation_vars(out, model, x[valid], y[valid], common[valid])
        if compare_transforms and is_dmg.any():
            alt = fit_outputs(x[train], y[train][:, is_dmg], [c for c, d in zip(cols, is_dmg) if d], settings,
                              lo=lo, span=span, log_damage=not settings.log_damage)
            am = validation_metrics(rbf.predict_rbf(alt, x[valid]), y[valid][:, is_dmg])
            other = "linear" if settings.log_damage else "log10"
            for k in ("r", "rmse", "sum_error"):
                arr = np.full(len(cols), np.nan)
                arr[is_dmg] = am[k]
                text = f"validation {k}, damage {other}-interpolated"
                out[f"validation_{k}_other_transform"] = ("output", arr, _a(text))
    n_hours = hindcast.sizes[names.TIME]
    out = _damage_vars(out, n_hours, fatigue.fatigue_settings(fatigue_cfg))
    scale = np.where(model.log_output, 1.0, np.std(y[train], axis=0))
    out = _uncertainty_vars(out, model, hp, scale, n_suggest)
    out.attrs.update({
        "n_hours": int(n_hours),
        "n_years": float(n_hours / HOURS_PER_YEAR),
        "n_train": int(train.sum()),
        "n_validate": int(valid.sum()),
        "rbf_shape_mode": settings.shape_mode,
        "rbf_log_damage": int(settings.log_damage),
        "mooring_system": str(sims.attrs.get("mooring_system", "")),
    })
    return out


def discrete_damage_table(discrete_states: xr.Dataset, discrete_sims: xr.Dataset, n_hours: float) -> xr.Dataset:
    """Conventional damage per line and curve from the scatter-matrix bins.

    Parameters
    ----------
    discrete_states : xarray.Dataset
        ``results/selection/discrete.zarr`` (dim ``bin``, ``probability``).
    discrete_sims : xarray.Dataset
        ``results/{ms}/discrete.zarr`` (dims ``bin``, ``line``; ``damage_sn``, ``damage_tn``).
    n_hours : float
        Hours of the hindcast.

    Returns
    -------
    xarray.Dataset
        ``discrete_damage`` on (``curve``, ``line``).
    """
    b = names.BIN
    common = np.intersect1d(discrete_states[b].values, discrete_sims[b].values)
    if common.size < discrete_states.sizes[b]:
        raise ValueError(f"discrete.zarr: {discrete_states.sizes[b] - common.size} bin(s) were not simulated")
    p = discrete_states["probability"].sel({b: common}).values
    curves = [c for c in names.CURVES if DAMAGE_VARS[c] in discrete_sims]
    vals = np.stack([
        discrete_damage(p, discrete_sims[DAMAGE_VARS[c]].sel({b: common}).transpose(b, names.LINE).values, n_hours)
        for c in curves
    ])
    return xr.Dataset(
        {"discrete_damage": ((names.CURVE, names.LINE), vals, {"units": "1", "long_name": "sum_b p_b d_b hours"})},
        coords={names.CURVE: curves, names.LINE: discrete_sims[names.LINE].values},
    )


def summary_table(
    lifecycles: Mapping[str, xr.Dataset],
    discretes: Mapping[str, xr.Dataset],
    mooring: pd.DataFrame,
    *,
    seed_cv: Mapping[str, float] | None = None,
    coverage: float = 1.0,
    corrosion: fatigue.FatigueSettings | None = None,
) -> pd.DataFrame:
    """One row per (mooring system, line, curve): the comparison table of the study.

    Parameters
    ----------
    lifecycles : mapping of id -> Dataset
        ``results/{ms}/lifecycle.zarr``.
    discretes : mapping of id -> Dataset
        :func:`discrete_damage_table` of each system.
    mooring : pandas.DataFrame
        ``config/mooring_systems.tsv`` indexed by ``mooring_system``.
    seed_cv : mapping of curve -> float, optional
        Relative scatter of the hourly damage across random seeds (seed sensitivity), used with
        the validation sum error for the fatigue-life band.
    coverage : float
        Coverage factor of the band (:func:`life_band`).
    corrosion : moorlife.fatigue.FatigueSettings, optional
        If given, the verdict uses the design-life damage of the corroding chain
        (:func:`corrosion_evolution` with its corrosion rate and step) instead of the intact one;
        the columns ``design_life_damage_corroded`` and ``utilisation_corroded`` are added.

    Returns
    -------
    pandas.DataFrame
        Columns ``mooring_system, line, curve, mass_kg_per_m, link_diameter_mm, lifecycle_damage,
        damage_per_year, design_life_damage, discrete_damage, difference_pct, fatigue_life_years,
        fatigue_life_low, fatigue_life_high, design_fatigue_factor, utilisation, passes,
        surge_mpm_max, tension_mpm_max`` (+ the corroded columns).
    """
    rows = []
    for ms, lc in lifecycles.items():
        dd = discretes.get(ms)
        row0 = mooring.loc[ms]
        for curve in [str(c) for c in lc[names.CURVE].values]:
            o_idx = [lab for lab in lc["output"].values if str(lab).startswith(DAMAGE_VARS[curve])]
            rel_err = float(np.nanmax(np.abs(lc["validation_sum_error"].sel(output=o_idx).values))) if (
                "validation_sum_error" in lc and o_idx) else 0.0
            cv = float((seed_cv or {}).get(curve, 0.0))
            for line in [str(v) for v in lc[names.LINE].values]:
                sel = {names.CURVE: curve, names.LINE: line}
                life = float(lc["fatigue_life_years"].sel(sel))
                low, high = life_band(life, np.hypot(cv, rel_err), coverage)
                total = float(lc["lifecycle_damage"].sel(sel))
                disc = float(dd["discrete_damage"].sel(sel)) if dd is not None else np.nan
                row = {
                    "mooring_system": ms,
                    "line": line,
                    "curve": curve,
                    "mass_kg_per_m": float(row0["mass_kg_per_m"]),
                    "link_diameter_mm": float(row0["link_diameter_mm"]),
                    "lifecycle_damage": total,
                    "damage_per_year": float(lc["damage_per_year"].sel(sel)),
                    "design_life_damage": float(lc["design_life_damage"].sel(sel)),
                    "discrete_damage": disc,
                    "difference_pct": float(difference_pct(total, disc)),
                    "fatigue_life_years": life,
                    "fatigue_life_low": float(low),
                    "fatigue_life_high": float(high),
                    "design_fatigue_factor": float(lc["design_fatigue_factor"].sel({names.CURVE: curve})),
                    "utilisation": float(lc["utilisation"].sel(sel)),
                    "passes": bool(lc["passes"].sel(sel)),
                    "surge_mpm_max": float(lc["surge_mpm"].max()) if "surge_mpm" in lc else np.nan,
                    "tension_mpm_max": (float(lc["tension_mpm"].sel({names.LINE: line}).max())
                                        if "tension_mpm" in lc else np.nan),
                }
                if corrosion is not None:
                    life_years = float(lc.attrs.get("design_life_years", corrosion.design_life))
                    mean_t = (float(lc["tension_mean"].sel({names.LINE: line}).mean()) if "tension_mean" in lc
                              else float(row0["pretension_kN"]) * 1e3)
                    ev = corrosion_evolution(row["damage_per_year"], float(row0["link_diameter_mm"]) * 1e-3, life_years,
                                             curve=curve, settings=corrosion, mean_tension=mean_t)
                    row["design_life_damage_corroded"] = float(ev["corroded"][-1])
                    row["utilisation_corroded"] = row["design_fatigue_factor"] * row["design_life_damage_corroded"]
                    row["passes"] = bool(row["utilisation_corroded"] <= 1.0)
                rows.append(row)
    return pd.DataFrame(rows)


# --------------------------------------------------------------------------- sensitivities


def seed_lives(hourly_damage: npt.ArrayLike) -> np.ndarray:
    """Fatigue life in years if one sea state repeats for ever (paper section 4.2).

    Parameters
    ----------
    hourly_damage : array_like, shape (n_seed, ...)
        Hourly damage of each random-phase realisation.

    Returns
    -------
    numpy.ndarray, shape (n_seed, ...)
        ``1 / (hourly damage x 8766)``.
    """
    return fatigue.fatigue_life(damage_per_year(np.asarray(hourly_damage, dtype=float), 1.0))


def corrosion_evolution(
    per_year: float,
    link_diameter: float,
    years: float,
    *,
    curve: str,
    settings: fatigue.FatigueSettings,
    mean_tension: float | None = None,
) -> dict[str, np.ndarray]:
    """Accumulated damage of a corroding line vs a new one (paper section 4.3, Fig. 22).

    Parameters
    ----------
    per_year : float
        Yearly damage of the new line.
    link_diameter : float
        New link diameter in m.
    years : float
        Horizon in years.
    curve : {"sn", "tn"}
    settings : moorlife.fatigue.FatigueSettings
        Corrosion rate and step, mean-stress settings.
    mean_tension : float, optional
        N; needed with a mean-stress correction.

    Returns
    -------
    dict
        ``years`` (nstep + 1,), ``corroded`` and ``intact`` cumulative damage (nstep + 1,),
        ``factor`` (nstep,) the corrosion multiplier per step.
    """
    sn, tn = fatigue.get_curves("studless", settings.curves)
    m = sn.m if curve == "sn" else tn.m

    def factor(ages: np.ndarray) -> np.ndarray:
        return fatigue.corrosion_damage_factor(
            link_diameter, ages, curve=curve, m=m, rate=settings.corrosion_rate,
            mean_stress=settings.mean_stress, mean_tension=mean_tension,
            ultimate=settings.ultimate, yield_=settings.yield_,
        )

    ages, cum = fatigue.lifetime_damage_with_corrosion(
        lambda a: per_year * factor(a), years, step=settings.corrosion_step
    )
    return {"years": ages, "corroded": cum, "intact": per_year * ages, "factor": np.asarray(factor(ages[:-1]))}


def mean_stress_table(mooring: pd.DataFrame, mean_tension: Mapping[str, float] | None = None,
                      *, ultimate: float = 960.0, yield_: float = 700.0) -> pd.DataFrame:
    """Mean-stress correction ratios per mooring system (paper Table 8).

    Parameters
    ----------
    mooring : pandas.DataFrame
        ``config/mooring_systems.tsv`` (``pretension_kN``, ``link_diameter_mm``).
    mean_tension : mapping of id -> N, optional
        A second block at another mean tension (e.g. the life-cycle mean tension of the most
        loaded line); omitted systems get NaN.
    ultimate, yield_ : float
        MPa.

    Returns
    -------
    pandas.DataFrame
        ``mooring_system, block, mean_tension_kN, mean_stress_mpa, goodman, soderberg, gerber``.
    """
    rows = []
    blocks = [("static", {ms: float(r["pretension_kN"]) * 1e3 for ms, r in mooring.iterrows()})]
    if mean_tension:
        blocks.append(("lifecycle mean", dict(mean_tension)))
    for block, tens in blocks:
        for ms, r in mooring.iterrows():
            t = tens.get(ms, np.nan)
            s = float(t / fatigue.stress_area(float(r["link_diameter_mm"]) * 1e-3) * 1e-6) if np.isfinite(t) else np.nan
            row = {"mooring_system": ms, "block": block, "mean_tension_kN": t / 1e3, "mean_stress_mpa": s}
            for meth in ("goodman", "soderberg", "gerber"):
                row[meth] = float(fatigue.mean_stress_factor(s, meth, ultimate, yield_)) if np.isfinite(s) else np.nan
            rows.append(row)
    return pd.DataFrame(rows)
