"""The RBF of every output column (:func:`fit_outputs`, :func:`predict_outputs`).

Two ways to choose each output's interpolant (``lifecycle.rbf.choose``):

``global`` (the default, the paper's method)
    Every output in one input space (``lifecycle.rbf.space``; the paper's normalised 5-D space
    by default, :mod:`moorlife.lifecycle.spaces`); the damage interpolated as ``log10``
    when ``log_damage``; ``q0`` (and the smoothing) per output by Rippa's leave-one-out error
    in the interpolated (transformed) values.
``per_output``
    Every output takes, among the candidate input spaces (``lifecycle.rbf.spaces``: the paper
    space, or with the rotor thrust ``T(W)`` as a sixth coordinate, :mod:`moorlife.lifecycle.spaces`),
    the candidate transforms (``lifecycle.rbf.transforms``; ``lifecycle.rbf.damage_transforms``
    for the damage), the ``q0`` candidates and the smoothing candidates, the one with the
    smallest leave-one-out RMS error in its own units (:func:`moorlife.rbf.choose_per_output`),
    from the training states alone. The leave-one-out errors are those of the training states,
    which maximum dissimilarity puts on the boundary of the sea-state space: they weight the
    extremes more than the hindcast hours do.

In both, ``lifecycle.rbf.retransform`` sets the back-transform correction of the ``log10``
outputs (:mod:`moorlife.rbf.transform`). The result is a :class:`Reconstruction`: one
:class:`moorlife.rbf.RBFModel` per input space in use.

``lifecycle.rbf.method: gp`` replaces the RBF by a Gaussian process with a noise term per output
(:mod:`moorlife.gp`, the settings of ``lifecycle.rbf.gp``), the damage transformed by
``log_damage``, with its closed-form leave-one-out residuals in ``loo_error``. ``global``: in the
paper space or with the thrust (``gp.thrust``), one :class:`moorlife.gp.GPModel`.
``per_output``: one GP per candidate space (``lifecycle.rbf.spaces``: ``paper``, ``thrust``), and
each output keeps the one with the smaller leave-one-out RMS error in its own units: one
:class:`moorlife.gp.GPModel` per space in use, each of its outputs. ``stack``: the same fits,
and every output is a weighted blend of the candidates' predictions (stacking), its weight
chosen from the training states' leave-one-out predictions alone
(:func:`moorlife.lifecycle.stacking.stack_weights`). The validation metrics are
:mod:`moorlife.lifecycle.validation`'s.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from moorlife import gp, names, rbf
from moorlife.lifecycle.outputs import _label
from moorlife.lifecycle.settings import RBFSettings
from moorlife.lifecycle.spaces import ThrustCoordinate, space_inputs, space_points, space_trend
from moorlife.lifecycle.stacking import stack_weights
from moorlife.space import Space, embed, fit_space

__all__ = [
    "Reconstruction",
    "fit_outputs",
    "predict_outputs",
    "loo_errors_in_units",
]

log = logging.getLogger("moorlife.lifecycle")


@dataclass(frozen=True)
class Reconstruction:
    """The fitted RBF of every output column: one model per input space in use.

    Attributes
    ----------
    models : tuple of moorlife.rbf.RBFModel, or of one moorlife.gp.GPModel
        One per input space in use (``method`` ``"gp"``: the one Gaussian process).
    columns : tuple of numpy.ndarray of int
        The output columns of each model.
    spaces : tuple of str
        The input space of each model (``names.RBF_SPACES``).
    thrust : ThrustCurve, TurbulentThrust or None
        The thrust coordinate of the ``"thrust"`` space (:mod:`moorlife.lifecycle.spaces`).
    space : moorlife.space.Space
        The paper's 5-D normalisation, and ``centres`` the training states in it: the distances of
        the error indicator and of the adaptive suggestions (:mod:`moorlife.lifecycle.uncertainty`).
    centres : numpy.ndarray, shape (m, 5)
    choose : str
        ``lifecycle.rbf.choose``.
    input_space : numpy.ndarray of str, shape (n_out,)
    shape, smoothing, log_factor, loo_rmse_units : numpy.ndarray, shape (n_out,)
        Per output: ``q0``, ridge, back-transform factor, leave-one-out RMSE in its own units.
        For the GP: ``q0`` NaN, the ridge its analogue ``s_n^2 / s_f^2``, the constant factor.
    log_output : numpy.ndarray of bool, shape (n_out,)
    loo_error : numpy.ndarray, shape (m, n_out)
        Leave-one-out residuals in the interpolated (transformed) values.
    method : {"rbf", "gp"}
    indicator : {"loo", "sd"}
        The error indicator of :func:`moorlife.lifecycle.error_indicator`.
    weights : tuple of numpy.ndarray, optional
        ``choose: stack``: the weight of each model in each of its ``columns`` (the columns of
        the models overlap; an output's weights sum to 1). The blend is arithmetic for a
        linear output and geometric for a ``log10`` one, i.e. arithmetic in the interpolated
        values (:func:`predict_outputs`). None: each output is one model's.
    """

    models: tuple[rbf.RBFModel, ...]
    columns: tuple[np.ndarray, ...]
    spaces: tuple[str, ...]
    thrust: ThrustCoordinate | None
    space: Space
    centres: np.ndarray
    choose: str
    input_space: np.ndarray
    shape: np.ndarray
    smoothing: np.ndarray
    log_factor: np.ndarray
    loo_rmse_units: np.ndarray
    log_output: np.ndarray
    loo_error: np.ndarray
    method: str = "rbf"
    indicator: str = "loo"
    weights: tuple[np.ndarray, ...] | None = None

    @property
    def n_outputs(self) -> int:
        return int(self.shape.size)

    def dominant(self) -> tuple[np.ndarray, ...]:
        """Per model, a mask of its ``columns`` where it holds the largest weight (the first on a
        tie): each output's one model for records such as the GP's hyperparameters."""
        if self.weights is None:
            return tuple(np.ones(c.size, dtype=bool) for c in self.columns)
        best = np.full(self.n_outputs, -1.0)
        owner = np.full(self.n_outputs, -1)
        for k, (c, w) in enumerate(zip(self.columns, self.weights)):
            take = w > best[c]
            best[c[take]], owner[c[take]] = w[take], k
        return tuple(owner[c] == k for k, c in enumerate(self.columns))


def fit_outputs(
    points: np.ndarray,
    values: np.ndarray,
    cols: Sequence[tuple[str, str | None]],
    settings: RBFSettings,
    *,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
    log_damage: bool | npt.ArrayLike | None = None,
    thrust: ThrustCoordinate | None = None,
) -> Reconstruction:
    """Fit the RBF of every output column with the configured choice (module docstring).

    Parameters
    ----------
    points : numpy.ndarray, shape (m, 5)
        Training sea states in ``names.METOCEAN_VARS`` order.
    values : numpy.ndarray, shape (m, k)
    cols : sequence of (name, line)
    settings : RBFSettings
    lo, span : array_like (5,), optional
        Normalisation of the selection (``cases.zarr`` attributes ``norm_lo``/``norm_span``).
    log_damage : bool or array_like of bool, optional
        Forces the transform of the damage columns (one value, or one per damage column in
        order), overriding ``settings.log_damage`` and, with ``per_output``, the choice of
        their transform (used to compare both transforms).
    thrust : ThrustCurve or TurbulentThrust, optional
        Required when the ``"thrust"`` space is in use or among the candidates.

    Returns
    -------
    Reconstruction

    Raises
    ------
    ValueError
        On bad values, or the thrust space without a thrust curve.
    """
    is_dmg = np.array([c[0].startswith("damage") for c in cols])
    forced = None
    if log_damage is not None:
        forced = np.broadcast_to(np.asarray(log_damage, dtype=bool), (int(is_dmg.sum()),))
    if settings.method == "gp":
        return _fit_gp(points, values, cols, settings, lo, span, is_dmg, forced, thrust)
    if settings.choose == "per_output":
        return _fit_per_output(points, values, cols, settings, lo, span, is_dmg, forced, thrust)
    logs = np.zeros(len(cols), dtype=bool)
    logs[is_dmg] = bool(settings.log_damage) if forced is None else forced
    if logs.any():
        values = values.copy()
        for j in np.flatnonzero(logs):
            values[:, j] = _floored(values[:, j], cols[j])
    x, mask, lo_s, span_s = space_inputs(settings.space, points, lo, span, thrust, settings.weights)
    common = dict(
        is_direction=mask,
        log_output=logs,
        smoothing=settings.smoothing,
        lo=lo_s,
        span=span_s,
        retransform=settings.retransform,
        trend=space_trend(settings.space, settings.trend_knots, settings.trend_harmonics),
    )
    if settings.shape_mode == "fixed":
        model = rbf.fit_rbf(x, values, shape=_fixed_shapes(cols, settings), **common)
    else:
        grid = rbf.shape_grid(settings.grid_min, settings.grid_max, settings.grid_n)
        model = rbf.fit_rbf(x, values, shapes=grid, share_tol=settings.share_tol, **common)
    rmse = _rmse_units(values, model.loo_error, logs, model.log_factor)
    if settings.space == names.RBF_SPACE_PAPER:
        space, centres = model.space, model.centres
    else:
        space, centres = _paper_space(points, lo, span)
    return _combine([model], [np.arange(len(cols))], [settings.space], thrust, space, centres, "global", rmse)


def _paper_space(points: np.ndarray, lo: npt.ArrayLike | None, span: npt.ArrayLike | None) -> tuple[Space, np.ndarray]:
    """The paper's 5-D normalisation of the training states, and the states in it."""
    x5, mask5, lo5, span5 = space_inputs(names.RBF_SPACE_PAPER, points, lo, span)
    space = fit_space(x5, mask5, lo=lo5, span=span5)
    return space, embed(x5, space)


def predict_outputs(model: Reconstruction, points: npt.ArrayLike, *, chunk_rows: int = 8192) -> np.ndarray:
    """Every output of a :class:`Reconstruction` at sea states ``points`` (n, 5).

    Parameters
    ----------
    model : Reconstruction
    points : array_like, shape (n, 5)
        ``names.METOCEAN_VARS`` order, physical units.
    chunk_rows : int
        Rows per prediction block (memory only).

    Returns
    -------
    numpy.ndarray, shape (n, n_out)
        Back-transformed (with the correction) for ``log10`` outputs.
    """
    if model.method == "rbf" and len(model.models) == 1 and model.spaces[0] == names.RBF_SPACE_PAPER:
        return rbf.predict_rbf(model.models[0], points, chunk_rows=chunk_rows)
    x = np.asarray(points, dtype=float)
    predict = gp.predict_gp if model.method == "gp" else rbf.predict_rbf
    if model.weights is not None:  # choose: stack, blended in the interpolated values
        acc = np.zeros((x.shape[0], model.n_outputs))
        for m, cols, name, w in zip(model.models, model.columns, model.spaces, model.weights):
            p = predict(m, space_points(name, x, model.thrust), chunk_rows=chunk_rows)
            logs = model.log_output[cols]
            p[:, logs] = np.log10(p[:, logs])
            acc[:, cols] += w * p
        acc[:, model.log_output] = 10.0 ** acc[:, model.log_output]
        return acc
    out = np.empty((x.shape[0], model.n_outputs))
    for m, cols, name in zip(model.models, model.columns, model.spaces):
        out[:, cols] = predict(m, space_points(name, x, model.thrust), chunk_rows=chunk_rows)
    return out


def _fixed_shapes(cols: Sequence[tuple[str, str | None]], settings: RBFSettings) -> np.ndarray:
    """The fixed ``q0`` of every column (``lifecycle.rbf.fixed``)."""
    return np.array(
        [
            settings.fixed_damage
            if c[0].startswith("damage")
            else settings.fixed_tension
            if c[0].startswith("tension")
            else settings.fixed_other
            for c in cols
        ]
    )


def _floored(column: np.ndarray, col: tuple[str, str | None] | None = None) -> np.ndarray:
    """A damage column for the log transform: non-positive values floored at the smallest positive one.

    Logged when ``col`` is given (the transform chosen, not a candidate).
    """
    bad = ~(column > 0)
    if not bad.any():
        return column
    # a calm state with no counted cycle: floor at the smallest positive damage
    pos = column[column > 0]
    floor = pos.min() if pos.size else 1e-30
    if col is not None:
        log.warning(
            "%s: %d non-positive damage value(s) floored at %.3g for the log transform",
            _label(col),
            int(bad.sum()),
            floor,
        )
    out = column.copy()
    out[bad] = floor
    return out


def _errors_units(values: np.ndarray, loo: np.ndarray, logs: np.ndarray, factor: np.ndarray) -> np.ndarray:
    """Leave-one-out residuals of every column in its own units (log columns back-transformed)."""
    e = loo.copy()
    if logs.any():
        ly = np.log10(values[:, logs])
        e[:, logs] = rbf.loo_error_in_units(values[:, logs], ly, loo[:, logs], factor[logs])
    return e


def _rmse_units(values: np.ndarray, loo: np.ndarray, logs: np.ndarray, factor: np.ndarray) -> np.ndarray:
    """Leave-one-out RMSE of every column in its own units (log columns back-transformed)."""
    e = _errors_units(values, loo, logs, factor)
    return np.sqrt(np.mean(e * e, axis=0))


def loo_errors_in_units(
    model: Reconstruction, values: npt.ArrayLike, cols: Sequence[tuple[str, str | None]]
) -> np.ndarray:
    """Leave-one-out residuals of a fitted :class:`Reconstruction` in each output's own units.

    Parameters
    ----------
    model : Reconstruction
    values : array_like, shape (m, n_out)
        The training values the model was fitted on, in their units.
    cols : sequence of (name, line)
        The output columns (damage columns are floored as for the fit before their ``log10``).

    Returns
    -------
    numpy.ndarray, shape (m, n_out)
        ``y_k`` minus the back-transformed prediction at state ``k`` of the fit without ``k``.
    """
    y = np.array(values, dtype=float)
    for j in np.flatnonzero(model.log_output):
        if cols[j][0].startswith("damage"):
            y[:, j] = _floored(y[:, j])
    return _errors_units(y, model.loo_error, model.log_output, model.log_factor)


def _combine(
    models: Sequence[rbf.RBFModel],
    columns: Sequence[np.ndarray],
    spaces: Sequence[str],
    thrust: ThrustCoordinate | None,
    space: Space,
    centres: np.ndarray,
    choose: str,
    rmse_units: np.ndarray,
) -> Reconstruction:
    """The :class:`Reconstruction` of per-space models, with the per-output records assembled."""
    n_out = int(sum(c.size for c in columns))
    m = centres.shape[0]
    per = {k: np.empty(n_out) for k in ("shape", "smoothing", "log_factor")}
    logs = np.zeros(n_out, dtype=bool)
    loo = np.empty((m, n_out))
    where = np.empty(n_out, dtype=object)
    for model, cols, name in zip(models, columns, spaces):
        per["shape"][cols] = model.shape
        per["smoothing"][cols] = model.smoothing
        per["log_factor"][cols] = model.log_factor
        logs[cols] = model.log_output
        loo[:, cols] = model.loo_error
        where[cols] = name
    return Reconstruction(
        models=tuple(models),
        columns=tuple(np.asarray(c, dtype=np.int64) for c in columns),
        spaces=tuple(spaces),
        thrust=thrust,
        space=space,
        centres=centres,
        choose=choose,
        input_space=where.astype(str),
        shape=per["shape"],
        smoothing=per["smoothing"],
        log_factor=per["log_factor"],
        loo_rmse_units=np.asarray(rmse_units, dtype=float),
        log_output=logs,
        loo_error=loo,
    )


def _fit_per_output(
    points: np.ndarray,
    values: np.ndarray,
    cols: Sequence[tuple[str, str | None]],
    settings: RBFSettings,
    lo: npt.ArrayLike | None,
    span: npt.ArrayLike | None,
    is_dmg: np.ndarray,
    forced: np.ndarray | None,
    thrust: ThrustCoordinate | None,
) -> Reconstruction:
    """``choose: per_output``: the leave-one-out choice per output, then one fit per space in use."""
    y = np.asarray(values, dtype=float)
    # log10 candidates: every positive output, and the damage (zeros floored, as with log_damage)
    cands = [settings.damage_transforms if d else settings.transforms for d in is_dmg]
    log_ok = (np.all(y > 0, axis=0) | is_dmg) & np.array(["log10" in c for c in cands])
    lin_ok = np.array(["linear" in c for c in cands]) | ~log_ok
    if forced is not None:
        log_ok[is_dmg] = forced
        lin_ok[is_dmg] = ~forced
    y_log = y.copy()
    for j in np.flatnonzero(log_ok & is_dmg):
        y_log[:, j] = _floored(y[:, j])
    ly = np.full_like(y, np.nan)
    ly[:, log_ok] = np.log10(y_log[:, log_ok])
    inputs = [space_inputs(sp, points, lo, span, thrust, settings.weights) for sp in settings.spaces]
    trends = [space_trend(sp, settings.trend_knots, settings.trend_harmonics) for sp in settings.spaces]
    geometry = [
        rbf.centre_geometry(x, mask, lo=lo_s, span=span_s, trend=t)
        for (x, mask, lo_s, span_s), t in zip(inputs, trends)
    ]
    if settings.shape_mode == "fixed":
        shapes = _fixed_shapes(cols, settings)[:, None]
    else:
        shapes = rbf.shape_grid(settings.grid_min, settings.grid_max, settings.grid_n)
    choice = rbf.choose_per_output(
        geometry,
        y,
        shapes=shapes,
        smoothings=settings.smoothing,
        log_values=ly,
        log_candidate=log_ok,
        linear_candidate=lin_ok,
        retransform=settings.retransform,
        share_tol=settings.share_tol,
    )
    models, columns, used = [], [], []
    for si in np.unique(choice.space):
        c = np.flatnonzero(choice.space == si)
        x, mask, lo_s, span_s = inputs[int(si)]
        vals = y[:, c].copy()
        for k, j in enumerate(c):
            if choice.log_output[j]:
                vals[:, k] = _floored(y[:, j], cols[j]) if is_dmg[j] else y[:, j]
        models.append(
            rbf.fit_rbf_fixed(
                x,
                vals,
                is_direction=mask,
                shape=choice.shape[c],
                smoothing=choice.smoothing[c],
                log_output=choice.log_output[c],
                lo=lo_s,
                span=span_s,
                retransform=settings.retransform,
                trend=trends[int(si)],
            )
        )
        columns.append(c)
        used.append(settings.spaces[int(si)])
    space, centres = _paper_space(points, lo, span)
    return _combine(models, columns, used, thrust, space, centres, "per_output", choice.loo_rmse)


def gp_groups(cols: Sequence[tuple[str, str | None]], share: str) -> np.ndarray | None:
    """The hyperparameter group of every output column under ``lifecycle.rbf.gp.share``.

    ``none``: no groups (every output its own); ``variable``: one group per variable, the damage
    of every line and curve being one variable; ``all``: one group.
    """
    if share == "none":
        return None
    if share == "all":
        return np.zeros(len(cols), dtype=np.int64)
    if share != "variable":
        raise ValueError(f"lifecycle.rbf.gp.share = {share!r}; expected none, variable or all")
    keys = ["damage" if c[0].startswith("damage") else c[0] for c in cols]
    return np.unique(keys, return_inverse=True)[1].reshape(-1).astype(np.int64)


def gp_input_names(is_direction: npt.ArrayLike) -> list[str]:
    """The GP's embedded coordinates of a space, by its mask: ``names.METOCEAN_VARS`` then, in
    the thrust space, the thrust (:func:`moorlife.lifecycle.spaces.space_inputs`)."""
    mask = np.asarray(is_direction, dtype=bool)
    variables = list(names.METOCEAN_VARS) + [names.RBF_SPACE_THRUST] * (mask.size - len(names.METOCEAN_VARS))
    return gp.embedded_names(variables, mask)


def wind_columns(is_direction: npt.ArrayLike) -> tuple[int, ...]:
    """The GP's embedded coordinates of the wind speed and direction (``gp.wind_term``)."""
    emb = gp_input_names(is_direction)
    speed, direction = names.METOCEAN_VARS[:2]
    return tuple(emb.index(k) for k in (speed, f"cos_{direction}", f"sin_{direction}"))


def wave_height_column(is_direction: npt.ArrayLike) -> int:
    """The GP's embedded coordinate of the significant wave height (the wind term's sea gate)."""
    return gp_input_names(is_direction).index(names.METOCEAN_VARS[2])


def _fit_gp(
    points: np.ndarray,
    values: np.ndarray,
    cols: Sequence[tuple[str, str | None]],
    settings: RBFSettings,
    lo: npt.ArrayLike | None,
    span: npt.ArrayLike | None,
    is_dmg: np.ndarray,
    forced: np.ndarray | None,
    thrust: ThrustCoordinate | None,
) -> Reconstruction:
    """``method: gp``: one Gaussian process per output (:func:`moorlife.gp.fit_gp`).

    ``choose: global``: in the paper or thrust space (``gp.thrust``). ``per_output``: one fit
    per candidate of ``spaces``, and every output keeps the fit with the smallest closed-form
    leave-one-out RMS error in its own units (the first candidate on a tie).
    """
    g = settings.gp
    logs = np.zeros(len(cols), dtype=bool)
    logs[is_dmg] = bool(settings.log_damage) if forced is None else forced
    y = np.array(values, dtype=float)
    for j in np.flatnonzero(logs):
        y[:, j] = _floored(y[:, j], cols[j])
    if settings.choose in ("per_output", "stack"):
        candidates = tuple(settings.spaces)
    else:
        candidates = (names.RBF_SPACE_THRUST if g.thrust else names.RBF_SPACE_PAPER,)
    fits = [_gp_in(name, points, y, cols, settings, lo, span, logs, thrust) for name in candidates]
    space, centres = _paper_space(points, lo, span)
    if settings.choose == "stack" and len(candidates) == 2:
        return _stack_gp(
            fits,
            y,
            cols,
            logs,
            candidates,
            thrust=thrust,
            space=space,
            centres=centres,
            indicator=g.indicator,
            resamples=settings.stack_resamples,
            seed=settings.stack_seed,
        )
    rmse = np.array([np.sqrt(np.mean(e * e, axis=0)) for _, e in fits])  # (candidates, n_out)
    pick = _pick_finite(rmse, cols, candidates)
    if len(candidates) > 1:
        log.info(
            "GP space per output by leave-one-out RMS in units: %s",
            {_label(c): candidates[int(k)] for c, k in zip(cols, pick)},
        )
    models, columns, used = [], [], []
    for k in np.unique(pick):
        c = np.flatnonzero(pick == k).astype(np.int64)
        model = fits[int(k)][0]
        models.append(model if c.size == len(cols) else gp.select_outputs(model, c))
        columns.append(c)
        used.append(candidates[int(k)])
    n_out, m = len(cols), y.shape[0]
    smoothing, factor, loo = np.empty(n_out), np.empty(n_out), np.empty((m, n_out))
    for model, c in zip(models, columns):
        smoothing[c] = model.noise_var / model.signal_var
        factor[c] = model.log_factor
        loo[:, c] = model.loo_error
    return Reconstruction(
        models=tuple(models),
        columns=tuple(columns),
        spaces=tuple(used),
        thrust=thrust,
        space=space,
        centres=centres,
        choose=settings.choose,
        input_space=np.array(candidates)[pick].astype(str),
        shape=np.full(n_out, np.nan),
        smoothing=smoothing,
        log_factor=factor,
        loo_rmse_units=rmse[pick, np.arange(n_out)],
        log_output=logs,
        loo_error=loo,
        method="gp",
        indicator=g.indicator,
    )


def _stack_gp(
    fits: Sequence[tuple[gp.GPModel, np.ndarray]],
    y: np.ndarray,
    cols: Sequence[tuple[str, str | None]],
    logs: np.ndarray,
    candidates: Sequence[str],
    *,
    thrust: ThrustCoordinate | None,
    space: Space,
    centres: np.ndarray,
    indicator: str,
    resamples: int,
    seed: int,
) -> Reconstruction:
    """``choose: stack`` with ``method: gp``: every output blended from the two candidate spaces'
    GPs (``fits``: each GP and its leave-one-out residuals in units, :func:`_gp_in`), with the
    weight of :func:`stack_weights` on their leave-one-out predictions (``resamples`` and
    ``seed`` its bootstrap); ``space``, ``centres`` and ``indicator`` go to the
    :class:`Reconstruction` as they are."""
    (ma, ea), (mb, eb) = fits
    w, rmse = stack_weights(y, y - ea, y - eb, logs, resamples=resamples, seed=seed)
    bad = ~np.isfinite(rmse)
    if bad.any():
        j = int(np.flatnonzero(bad)[0])
        raise ValueError(
            f"lifecycle.rbf.choose = 'stack': output {_label(cols[j])} has no finite leave-one-out "
            f"RMS in any blend of {list(candidates)}"
        )
    n_out = len(cols)
    models, columns, used, weights = [], [], [], []
    for model, wk, name in ((ma, w, candidates[0]), (mb, 1.0 - w, candidates[1])):
        c = np.flatnonzero(wk > 0).astype(np.int64)
        if c.size:
            models.append(model if c.size == n_out else gp.select_outputs(model, c))
            columns.append(c)
            used.append(name)
            weights.append(wk[c])
    log.info(
        "GP blend per output, weight of %s (the rest %s) by leave-one-out RMS in units%s: %s",
        candidates[0],
        candidates[1],
        f", mean over {resamples} bootstrap resamples" if resamples else "",
        {_label(c): round(float(v), 2) for c, v in zip(cols, w)},
    )
    label = np.array([f"{candidates[0]}:{v:.2f}+{candidates[1]}:{1 - v:.2f}" for v in w], dtype=object)
    label[w >= 1.0], label[w <= 0.0] = candidates[0], candidates[1]
    return Reconstruction(
        models=tuple(models),
        columns=tuple(columns),
        spaces=tuple(used),
        thrust=thrust,
        space=space,
        centres=centres,
        choose="stack",
        input_space=label.astype(str),
        shape=np.full(n_out, np.nan),
        smoothing=np.where(w >= 0.5, ma.noise_var / ma.signal_var, mb.noise_var / mb.signal_var),
        log_factor=ma.log_factor**w * mb.log_factor ** (1.0 - w),
        loo_rmse_units=rmse,
        log_output=logs,
        loo_error=w * ma.loo_error + (1.0 - w) * mb.loo_error,
        method="gp",
        indicator=indicator,
        weights=tuple(weights),
    )


def _pick_finite(rmse: np.ndarray, cols: Sequence[tuple[str, str | None]], candidates: Sequence[str]) -> np.ndarray:
    """Per output, the candidate with the smallest finite leave-one-out RMS (the first on a tie).

    ``np.argmin`` would pick a NaN (it propagates through the minimum); a candidate whose RMS is
    not finite is never picked, and an output with no finite RMS stops the fit, named.
    """
    bad = ~np.isfinite(rmse).any(axis=0)
    if bad.any():
        j = int(np.flatnonzero(bad)[0])
        raise ValueError(
            f"lifecycle.rbf.choose = 'per_output': output {_label(cols[j])} has no finite leave-one-out "
            f"RMS in any space of {list(candidates)} (got {rmse[:, j].tolist()})"
        )
    return np.argmin(np.where(np.isfinite(rmse), rmse, np.inf), axis=0)


def _gp_in(
    name: str,
    points: np.ndarray,
    y: np.ndarray,
    cols: Sequence[tuple[str, str | None]],
    settings: RBFSettings,
    lo: npt.ArrayLike | None,
    span: npt.ArrayLike | None,
    logs: np.ndarray,
    thrust: ThrustCoordinate | None,
) -> tuple[gp.GPModel, np.ndarray]:
    """The GP of every output in the space ``name``, and its leave-one-out residuals in units (m, n_out)."""
    g = settings.gp
    x, mask, lo_s, span_s = space_inputs(name, points, lo, span, thrust)
    model = gp.fit_gp(
        x,
        y,
        is_direction=mask,
        log_output=logs,
        lo=lo_s,
        span=span_s,
        kernel=g.kernel,
        length_scale=g.length_scale.astuple(),
        signal=g.signal.astuple(),
        noise=g.noise.astuple(),
        restarts=g.restarts,
        seed=g.seed,
        subsample=g.subsample,
        retransform=g.retransform,
        groups=gp_groups(cols, g.share),
        prior_mean=g.mean,
        covariance=g.covariance,
        additive_columns=None if g.wind_term == "none" else wind_columns(mask),
        additive_outputs=[g.wind_term == "all" or c[0].startswith("damage") for c in cols],
        gate_column=wave_height_column(mask),
        gate_scale=g.wind_gate.astuple(),
        additive_subsample=g.wind_subsample,
        additive_start=g.wind_start,
    )
    e = model.loo_error.copy()
    if logs.any():
        ly = np.log10(y[:, logs])
        if g.retransform == "predictive":  # the leave-one-out predictive variance holds the noise already
            factor = np.exp(0.5 * np.log(10.0) ** 2 * model.loo_var[:, logs])
        else:
            factor = model.log_factor[logs]
        e[:, logs] = y[:, logs] - factor * 10.0 ** (ly - model.loo_error[:, logs])
    return model, e
