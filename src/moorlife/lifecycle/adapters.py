"""The xarray/pandas adapters of the life-cycle stage, used by the workflow scripts.

:func:`reconstruct_lifecycle` rebuilds every output for every hindcast hour (``lifecycle.zarr``),
:func:`discrete_damage_table` gives the damage of the discrete matrix and :func:`summary_table`
compares both.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

from moorlife import fatigue, names
from moorlife.lifecycle.damage import (
    DAMAGE_VARS,
    HOURS_PER_YEAR,
    damage_per_year,
    design_check,
    difference_pct,
    discrete_damage,
    life_damage,
)
from moorlife.lifecycle.fit import (
    Reconstruction,
    fit_outputs,
    gp_input_names,
    loo_errors_in_units,
    predict_outputs,
)
from moorlife.lifecycle.outputs import (
    _label,
    output_columns,
    stack_outputs,
    unstack_outputs,
)
from moorlife.lifecycle.records import carried_shares, records_sum_cv
from moorlife.lifecycle.sensitivity import corrosion_evolution
from moorlife.lifecycle.settings import RBFSettings
from moorlife.lifecycle.spaces import ThrustCoordinate
from moorlife.lifecycle.uncertainty import band_sigma_of, error_indicator, life_band, suggest_states, sum_seed_cv
from moorlife.lifecycle.validation import R_INTERVAL_LEVEL, validation_metrics, validation_r_interval

__all__ = [
    "Fitted",
    "fit_reconstruction",
    "records_term",
    "reconstruct_lifecycle",
    "discrete_damage_table",
    "summary_table",
]

log = logging.getLogger("moorlife.lifecycle")

#: Fewest training states of a fit (:func:`fit_reconstruction`).
MIN_TRAIN: int = 8


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
        raise ValueError(
            f"cases.zarr: attributes norm_variables {order}, norm_lo, norm_span are inconsistent "
            f"(need {list(names.METOCEAN_VARS)})"
        )
    idx = [order.index(v) for v in names.METOCEAN_VARS]
    return np.asarray(lo, dtype=float)[idx], np.asarray(span, dtype=float)[idx]


def _a(long_name: str, units: str = "1") -> dict[str, str]:
    return {"units": units, "long_name": long_name}


def _fit_vars(out: xr.Dataset, model: Reconstruction, x_train: np.ndarray, ids: np.ndarray) -> xr.Dataset:
    """Shape parameters, input spaces, transforms and leave-one-out residuals of the fit."""
    out = out.assign_coords(train=("train", ids))
    out["shape_parameter"] = ("output", model.shape, _a("RBF shape parameter q0 (normalised distance; NaN: GP)"))
    out["smoothing"] = (
        "output",
        model.smoothing,
        _a("RBF ridge term on the kernel diagonal (0: exact; GP: s_n^2/s_f^2)"),
    )
    out["loo_rmse"] = (
        "output",
        np.sqrt(np.mean(model.loo_error**2, axis=0)),
        _a("Rippa leave-one-out RMSE (transformed space)"),
    )
    out["log_transform"] = ("output", model.log_output.astype(np.int8), _a("1 if interpolated as log10"))
    transform = np.where(model.log_output, names.RBF_TRANSFORMS[1], names.RBF_TRANSFORMS[0])
    for key, val in (
        (names.RBF_INPUT_SPACE, model.input_space),
        (names.RBF_TRANSFORM, transform),
        (names.RBF_LOG_FACTOR, model.log_factor),
        (names.RBF_LOO_RMSE_UNITS, model.loo_rmse_units),
    ):
        out[key] = ("output", val, dict(names.RBF_CHOICE_ATTRS[key]))
    out["train_points"] = (("train", "metocean_var"), x_train, _a("training sea states (physical units)"))
    out["loo_error"] = (("train", "output"), model.loo_error, _a("leave-one-out residual per training state"))
    if model.method == "gp":
        inputs, ls, sig, noise = _gp_records(model)
        out = out.assign_coords(gp_input=inputs)
        out["gp_length_scale"] = (
            ("output", "gp_input"),
            ls,
            _a("GP length scale (normalised input units; NaN: not an input of the output's space)"),
        )
        out["gp_signal_sd"] = ("output", sig, _a("GP signal standard deviation (transformed units)"))
        out["gp_noise_sd"] = ("output", noise, _a("GP noise standard deviation (transformed units)"))
        wind = _gp_wind_records(model)
        if wind is not None:  # lifecycle.rbf.gp.wind_term
            out["gp_wind_length_scale"] = (
                ("output", "gp_input"),
                wind[0],
                _a(
                    "GP wind term's length scale (normalised input units; inf: not seen by the term; NaN: not an input)"
                ),
            )
            out["gp_wind_sd"] = (
                "output",
                wind[1],
                _a("GP wind term's standard deviation (transformed units; 0: none)"),
            )
            out["gp_wind_gate"] = (
                "output",
                wind[2],
                _a("GP wind term's sea-gate scale, exp(-hs / scale) (normalised hs units; inf: no term)"),
            )
    return out


def _gp_layout(model: Reconstruction) -> tuple[list[str], list[list[int]]]:
    """The union of the GPs' embedded inputs (the thrust space's hold the paper space's), and
    where each GP's own inputs sit in it (:func:`moorlife.lifecycle.fit.gp_input_names`)."""
    own = [gp_input_names(g.space.is_direction) for g in model.models]
    inputs = max(own, key=len)
    return inputs, [[inputs.index(k) for k in names_g] for names_g in own]


def _gp_records(model: Reconstruction) -> tuple[list[str], np.ndarray, np.ndarray, np.ndarray]:
    """Every output's GP length scales on the union of the inputs in use, signal and noise sd."""
    inputs, where = _gp_layout(model)
    n = model.n_outputs
    ls = np.full((n, len(inputs)), np.nan)
    sig, noise = np.empty(n), np.empty(n)
    for g, cols, w, own in zip(model.models, model.columns, where, model.dominant()):
        ls[np.ix_(cols[own], w)] = g.length_scale[own]
        sig[cols[own]], noise[cols[own]] = np.sqrt(g.signal_var[own]), np.sqrt(g.noise_var[own])
    return inputs, ls, sig, noise


def _gp_wind_records(model: Reconstruction) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """The wind term's length scales (on :func:`_gp_records`'s inputs), sd and sea-gate scale of
    every output (``lifecycle.rbf.gp.wind_term``); None when no model has the term."""
    if all(g.wind_var is None for g in model.models):
        return None
    inputs, where = _gp_layout(model)
    n = model.n_outputs
    wls, wsd, gate = np.full((n, len(inputs)), np.nan), np.zeros(n), np.full(n, np.inf)
    for g, cols, w, own in zip(model.models, model.columns, where, model.dominant()):
        if g.wind_var is not None:
            wls[np.ix_(cols[own], w)] = g.wind_length_scale[own]
            wsd[cols[own]], gate[cols[own]] = np.sqrt(g.wind_var[own]), g.wind_gate[own]
    return wls, wsd, gate


def _validation_vars(
    out: xr.Dataset, model: Reconstruction, x_val: np.ndarray, y_val: np.ndarray, ids: np.ndarray
) -> xr.Dataset:
    """Rebuilt vs simulated values on the validation states and their metrics."""
    pv = predict_outputs(model, x_val)
    for k, v in validation_metrics(pv, y_val).items():
        out[f"validation_{k}"] = ("output", v, _a(f"validation {k} on {len(ids)} states"))
    low, high, se = validation_r_interval(pv, y_val)
    text = f"{R_INTERVAL_LEVEL:.0%} BCa bootstrap interval of validation r over its {len(ids)} states"
    out["validation_r_low"] = ("output", low, _a(f"lower bound of the {text}"))
    out["validation_r_high"] = ("output", high, _a(f"upper bound of the {text}"))
    out["validation_r_se"] = ("output", se, _a(f"bootstrap standard error of validation r ({len(ids)} states)"))
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


def _uncertainty_vars(
    out: xr.Dataset,
    model: Reconstruction,
    hp: np.ndarray,
    y_train: np.ndarray,
    cols: Sequence[tuple[str, str | None]],
    n_suggest: int,
) -> xr.Dataset:
    """Error indicator per hour (leave-one-out errors in units) and the adaptive-selection suggestions."""
    ind, dist = error_indicator(
        model, hp, np.std(y_train, axis=0), loo_errors_in_units(model, y_train, cols), population=True
    )
    out["nearest_distance"] = (names.TIME, dist, _a("normalised distance to the nearest training state"))
    out["error_indicator"] = (names.TIME, ind, _a("LOO error of the nearest training state x relative distance"))
    picks = suggest_states(model, hp, ind, n_suggest, distance=dist)
    out = out.assign_coords(suggestion=("suggestion", np.arange(picks.size)))
    out["suggested_hour"] = ("suggestion", picks, _a("hindcast index to simulate next (adaptive selection)"))
    return out


@dataclass(frozen=True)
class Fitted:
    """A fitted reconstruction with the states and values it was fitted on (:func:`fit_reconstruction`).

    ``case`` the simulated case ids (sorted), ``points`` (n, 5) and ``values`` (n, n_out) of each,
    ``train`` and ``valid`` their roles, ``records`` the simulated records averaged in each
    training value (None: one each), ``lo`` and ``span`` the selection's normalisation.
    """

    model: Reconstruction
    cols: list[tuple[str, str | None]]
    case: np.ndarray
    points: np.ndarray
    values: np.ndarray
    train: np.ndarray
    valid: np.ndarray
    records: np.ndarray | None
    lo: np.ndarray | None
    span: np.ndarray | None

    @property
    def train_case(self) -> np.ndarray:
        """The case ids fitted, in the order of the model's centres."""
        return self.case[self.train]

    @property
    def train_points(self) -> np.ndarray:
        """The training states (physical units), in the order of the model's centres."""
        return self.points[self.train]

    @property
    def train_values(self) -> np.ndarray:
        """The simulated values fitted, one column per output of ``cols``."""
        return self.values[self.train]


def fit_reconstruction(
    cases: xr.Dataset,
    sims: xr.Dataset,
    *,
    settings: RBFSettings,
    thrust: ThrustCoordinate | None = None,
    context: str = "lifecycle",
) -> Fitted:
    """The reconstruction of every output, fitted on the simulated training states.

    The fit of :func:`reconstruct_lifecycle`, of the adaptive rounds' and the replicates' picks
    (:mod:`moorlife.selection`), and what the truth stage refits to take a window's records' term
    (:func:`moorlife.lifecycle.records.carried_shares`). Only the cases of both stores are
    taken; those with ``role == "train"`` are fitted, with the selection's normalisation from
    ``cases``. Deterministic: the same stores and settings give the same model, bit for bit.

    Parameters
    ----------
    cases, sims : xarray.Dataset
        As :func:`reconstruct_lifecycle`'s (``sims`` may hold ``n_records``, the seed replicates
        averaged per case).
    settings : RBFSettings
    thrust : ThrustCurve, optional
    context : str
        The caller, named in the errors.

    Raises
    ------
    ValueError
        If fewer than 8 training cases are simulated, or a simulated output (of a training or a
        validation case) is not finite.
    """
    dim = names.CASE
    common = np.intersect1d(cases[dim].values, sims[dim].values)
    cases = cases.sel({dim: common})
    sims = sims.sel({dim: common})
    role = np.array([str(v) for v in cases["role"].values])
    train, valid = role == "train", role == "validate"
    if train.sum() < MIN_TRAIN:
        raise ValueError(
            f"{context}: only {int(train.sum())} training cases are simulated; the RBF needs at least {MIN_TRAIN}"
        )
    cols = output_columns(sims, dim, settings.outputs)
    y = stack_outputs(sims, dim, cols)
    bad = ~np.isfinite(y)
    if bad.any():
        i, j = np.argwhere(bad)[0]
        raise ValueError(f"simulations: {_label(cols[j])} is not finite for case {int(common[i])} ({y[i, j]!r})")
    x = _points(cases, dim)
    lo, span = _selection_scaling(cases)
    model = fit_outputs(x[train], y[train], cols, settings, lo=lo, span=span, thrust=thrust)
    records = np.asarray(sims["n_records"].values[train], dtype=float) if "n_records" in sims else None
    return Fitted(model, list(cols), common, x, y, train, valid, records, lo, span)


def records_term(fitted: Fitted, points: np.ndarray, predicted: np.ndarray, chunk_rows: int = 8192) -> np.ndarray:
    """Per output, the relative seed sd of its sum over ``points`` per unit record CV (NaN: not a damage).

    :func:`moorlife.lifecycle.records.records_sum_cv` of the damage outputs'
    :func:`~moorlife.lifecycle.records.carried_shares`, with the seed replicates of each training state.
    A GP with a linear prior mean (its slope is fitted to the records too) has none: all NaN, logged.
    """
    cols = fitted.cols
    dmg = [j for j, c in enumerate(cols) if c[0].startswith("damage")]
    out = np.full(len(cols), np.nan)
    if fitted.model.method == "gp" and any(getattr(m, "slope", None) is not None for m in fitted.model.models):
        log.warning("the GP's linear prior mean has no records' term: the life band leaves it out")
        return out
    if dmg:
        g = carried_shares(
            fitted.model, points, predicted, fitted.train_values, fitted.train_points, dmg, chunk_rows=chunk_rows
        )
        out[dmg] = records_sum_cv(g, fitted.records)
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
    thrust: ThrustCoordinate | None = None,
    fitted: Fitted | None = None,
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
        Also validate the other damage transform (linear vs log10; with ``per_output``, the
        other of each damage output's chosen transform) and store its metrics.
    thrust : ThrustCurve, optional
        The turbine's thrust curve (:func:`moorlife.lifecycle.spaces.thrust_curve`), required
        when ``settings.choose`` is ``per_output`` with the ``thrust`` space among the candidates.
    fitted : Fitted, optional
        :func:`fit_reconstruction` of these ``cases``, ``sims``, ``settings`` and ``thrust``,
        when the caller has it (a harness that also takes a window's records' term); by default
        the fit is made here. Refused if it holds other cases than the stores.

    Returns
    -------
    xarray.Dataset
        Dims ``time``, ``line``, ``curve``, ``output``, ``train``, ``suggestion``: every
        rebuilt output on ``time`` (and ``line``); per output the shape parameter, input space,
        transform, back-transform factor, LOO RMSE and validation metrics; per line and curve
        the life-cycle damage, yearly and design-life damage, fatigue life, DFF and verdict;
        the adaptive-selection suggestions.
    """
    if fitted is None:
        fitted = fit_reconstruction(cases, sims, settings=settings, thrust=thrust)
    else:
        common = np.intersect1d(cases[names.CASE].values, sims[names.CASE].values)
        if not np.array_equal(fitted.case, common):
            raise ValueError(
                f"reconstruct_lifecycle: the fit given holds cases {fitted.case.size} "
                f"({fitted.case[:3].tolist()} ...), the stores {common.size} ({common[:3].tolist()} ...)"
            )
    model, cols, x, y, common = fitted.model, fitted.cols, fitted.points, fitted.values, fitted.case
    train, valid, lo, span = fitted.train, fitted.valid, fitted.lo, fitted.span
    labels = [_label(c) for c in cols]
    if model.method == "gp":
        inputs, ls_all, sig, noise = _gp_records(model)
        log.info(
            "GP per output: length scales on %s, signal sd, noise sd (transformed units):\n%s",
            inputs,
            "\n".join(
                f"  {lab:<18} {np.array2string(ls, precision=3)} {sv:.4g} {nv:.4g}"
                for lab, ls, sv, nv in zip(labels, ls_all, sig, noise)
            ),
        )
        wind = _gp_wind_records(model)
        if wind is not None:
            log.info(
                "GP wind term per output: length scales on %s (inf: not seen), sd, sea-gate scale:\n%s",
                inputs,
                "\n".join(
                    f"  {lab:<18} {np.array2string(ls, precision=3)} {sd:.4g} {gs:.4g}"
                    for lab, ls, sd, gs in zip(labels, *wind)
                    if sd > 0
                ),
            )
    log.info(
        "RBF fitted on %d training states, %d outputs; shapes %s",
        int(train.sum()),
        len(cols),
        {lab: round(float(q), 4) for lab, q in zip(labels, model.shape)},
    )
    log.info(
        "RBF choice (%s, retransform %s), per output: space, transform, q0, smoothing, factor, LOO RMSE in its units:\n%s",
        settings.choose,
        settings.retransform,
        "\n".join(
            f"  {lab:<18} {sp:<6} {'log10' if lg else 'linear':<6} {q:.4g} {lam:.3g} {c:.4f} {r:.4g}"
            for lab, sp, lg, q, lam, c, r in zip(
                labels,
                model.input_space,
                model.log_output,
                model.shape,
                model.smoothing,
                model.log_factor,
                model.loo_rmse_units,
            )
        ),
    )

    hp = _points(hindcast, names.TIME)
    pred = predict_outputs(model, hp, chunk_rows=settings.chunk_rows)
    out = unstack_outputs(pred, cols, names.TIME, {names.TIME: hindcast[names.TIME].values})
    for v in names.METOCEAN_VARS:
        out[v] = hindcast[v].astype(float)
    is_dmg = np.array([c[0].startswith("damage") for c in cols])
    if is_dmg.any():
        neg = pred[:, is_dmg] < 0
        if neg.any():
            log.warning(
                "%d rebuilt hourly damages are negative (RBF undershoot); clipped to 0 in the sums", int(neg.sum())
            )

    out = out.assign_coords(output=labels, metocean_var=list(names.METOCEAN_VARS))
    out = _fit_vars(out, model, x[train], common[train])
    if valid.any():
        out = _validation_vars(out, model, x[valid], y[valid], common[valid])
        if compare_transforms and is_dmg.any():
            per_output = settings.choose == "per_output"
            alt = fit_outputs(
                x[train],
                y[train][:, is_dmg],
                [c for c, d in zip(cols, is_dmg) if d],
                settings,
                lo=lo,
                span=span,
                log_damage=~model.log_output[is_dmg] if per_output else not settings.log_damage,
                thrust=thrust,
            )
            am = validation_metrics(predict_outputs(alt, x[valid]), y[valid][:, is_dmg])
            other = "linear" if settings.log_damage else "log10"
            other = "each output's other transform" if per_output else f"{other}-interpolated"
            for k in ("r", "rmse", "sum_error"):
                arr = np.full(len(cols), np.nan)
                arr[is_dmg] = am[k]
                text = f"validation {k}, damage {other}"
                out[f"validation_{k}_other_transform"] = ("output", arr, _a(text))
    if is_dmg.any():
        rc = records_term(fitted, hp, pred, chunk_rows=settings.chunk_rows)
        text = "seed sd of the life-cycle sum from the training records, per unit seed CV of one record"
        out["records_sum_cv"] = ("output", rc, _a(text))
    n_hours = hindcast.sizes[names.TIME]
    out = _damage_vars(out, n_hours, fatigue.fatigue_settings(fatigue_cfg))
    out = _uncertainty_vars(out, model, hp, y[train], cols, n_suggest)
    out.attrs.update(
        {
            "n_hours": int(n_hours),
            "n_years": float(n_hours / HOURS_PER_YEAR),
            "n_train": int(train.sum()),
            "n_validate": int(valid.sum()),
            "rbf_shape_mode": settings.shape_mode,
            "rbf_log_damage": int(settings.log_damage),
            "rbf_choose": settings.choose,
            "rbf_retransform": settings.retransform,
            "mooring_system": str(sims.attrs.get("mooring_system", "")),
        }
    )
    if settings.method == "gp":  # the default study's attributes stay as they were
        g = settings.gp
        out.attrs.update({"rbf_method": "gp", "gp_kernel": g.kernel, "gp_retransform": g.retransform})
        out.attrs.update({"gp_subsample": g.subsample, "gp_thrust": int(g.thrust), "gp_indicator": g.indicator})
        out.attrs.update({"gp_share": g.share, "gp_mean": g.mean, "gp_covariance": g.covariance})
        if g.wind_term != "none":  # the GP stores without the term stay as they were
            out.attrs["gp_wind_term"] = g.wind_term
            out.attrs["gp_wind_subsample"] = g.wind_subsample
            out.attrs["gp_wind_start"] = g.wind_start
    if thrust is not None and settings.thrust_statistic != "steady":  # the steady curve's stores as they were
        out.attrs.update(
            {
                "rbf_thrust_statistic": settings.thrust_statistic,
                "rbf_thrust_averaging_s": settings.thrust_averaging_time,
            }
        )
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
    vals = np.stack(
        [
            discrete_damage(p, discrete_sims[DAMAGE_VARS[c]].sel({b: common}).transpose(b, names.LINE).values, n_hours)
            for c in curves
        ]
    )
    return xr.Dataset(
        {"discrete_damage": ((names.CURVE, names.LINE), vals, {"units": "1", "long_name": "sum_b p_b d_b hours"})},
        coords={names.CURVE: curves, names.LINE: discrete_sims[names.LINE].values},
    )


def validation_sum_term(lc: xr.Dataset, curve: str) -> float:
    """The reconstruction term of the band: the largest ``|validation_sum_error|`` of a curve.

    Over the curve's damage outputs (one per line) in ``lc``; 0 when ``lc`` has none.
    """
    o_idx = [lab for lab in lc["output"].values if str(lab).startswith(DAMAGE_VARS[curve])] if "output" in lc else []
    if "validation_sum_error" not in lc or not o_idx:
        return 0.0
    return float(np.nanmax(np.abs(lc["validation_sum_error"].sel(output=o_idx).values)))


def band_sigma(lc: xr.Dataset, curve: str, seed_cv: Mapping[str, float] | None = None) -> float:
    """Relative standard deviation of one curve's life-cycle damage, the half-width of the life band over k.

    ``sqrt(seed scatter^2 + records' scatter^2 + max |validation sum error|^2)``, the largest
    over the lines of the curve:

    - the seed scatter of the life-cycle sum, :func:`sum_seed_cv` of the line's hourly damage in
      ``lc`` with the seed CV of one hour (``seed_cv[curve]``, 0 when absent). A sum over many
      hours averages the seed error of each: over a 30-year hindcast it is a fraction of a per
      cent where one hour's CV is 15-20 %. When ``lc`` has no hourly damage, one hour's CV itself
      (an upper bound);
    - the training records' seed scatter in the reconstructed sum, the same CV times ``lc``'s
      ``records_sum_cv`` of the line (:mod:`moorlife.lifecycle.records`; left out of a store
      written without it): the reconstruction's hours share their training records, whose
      errors do not average out;
    - :func:`validation_sum_term`, the error of the fit.
    """
    cv = float((seed_cv or {}).get(curve, 0.0))
    var = DAMAGE_VARS[curve]
    seed = cv
    if cv > 0 and var in lc and names.TIME in lc[var].dims:
        h = lc[var].transpose(names.TIME, ...)
        per_line = sum_seed_cv(h.values.reshape(lc.sizes[names.TIME], -1), cv)
        if "records_sum_cv" in lc and h.ndim == 2:
            labels = [f"{var}/{ln}" for ln in h[h.dims[1]].values]
            rc = lc["records_sum_cv"].sel(output=labels).values
            per_line = np.hypot(per_line, cv * np.nan_to_num(rc))
        seed = float(np.max(per_line))
    return float(band_sigma_of(seed, validation_sum_term(lc, curve)))


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
            sigma = band_sigma(lc, curve, seed_cv)
            for line in [str(v) for v in lc[names.LINE].values]:
                sel = {names.CURVE: curve, names.LINE: line}
                life = float(lc["fatigue_life_years"].sel(sel))
                low, high = life_band(life, sigma, coverage)
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
                    "tension_mpm_max": (
                        float(lc["tension_mpm"].sel({names.LINE: line}).max()) if "tension_mpm" in lc else np.nan
                    ),
                }
                if corrosion is not None:
                    life_years = float(lc.attrs.get("design_life_years", corrosion.design_life))
                    mean_t = (
                        float(lc["tension_mean"].sel({names.LINE: line}).mean())
                        if "tension_mean" in lc
                        else float(row0["pretension_kN"]) * 1e3
                    )
                    ev = corrosion_evolution(
                        row["damage_per_year"],
                        float(row0["link_diameter_mm"]) * 1e-3,
                        life_years,
                        curve=curve,
                        settings=corrosion,
                        mean_tension=mean_t,
                    )
                    row["design_life_damage_corroded"] = float(ev["corroded"][-1])
                    row["utilisation_corroded"] = row["design_fatigue_factor"] * row["design_life_damage_corroded"]
                    row["passes"] = bool(row["utilisation_corroded"] <= 1.0)
                rows.append(row)
    return pd.DataFrame(rows)
