"""The fit: a multi-output Gaussian RBF with a first-degree polynomial (:func:`fit_rbf`).

An optional :class:`moorlife.rbf.Trend` adds piecewise-linear columns to the polynomial.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from moorlife.rbf.kernels import polynomial_basis
from moorlife.rbf.loocv import choose_shapes_and_smoothing, rippa_errors, shape_grid
from moorlife.rbf.system import (
    _inverse,
    augmented_matrix,
    kernel_block_inverse,
    solve_weights,
)
from moorlife.rbf.transform import RETRANSFORMS, retransform_factor
from moorlife.rbf.trend import Trend, supported_trend, trend_basis
from moorlife.space import Space, as_points, embed, fit_space, squared_distances

__all__ = ["RBFModel", "fit_rbf", "fit_rbf_fixed", "centre_geometry", "model_basis"]


@dataclass(frozen=True)
class RBFModel:
    """A fitted multi-output Gaussian RBF interpolant (immutable arrays).

    Attributes
    ----------
    space : Space
        The input normalisation.
    centres : numpy.ndarray, shape (m, d)
        Normalised training points.
    shape : numpy.ndarray, shape (n_out,)
        Shape parameter ``q0`` per output (normalised distance units).
    weights : numpy.ndarray, shape (m, n_out)
        Kernel weights.
    poly_coef : numpy.ndarray, shape (p, n_out)
        Coefficients on :func:`model_basis` (the polynomial, then any trend columns).
    log_output : numpy.ndarray of bool, shape (n_out,)
        Outputs interpolated as ``log10`` (back-transformed on prediction).
    loo_error : numpy.ndarray, shape (m, n_out)
        Leave-one-out residuals at the chosen shape, in the transformed space
        (``log10`` units for log outputs).
    smoothing : numpy.ndarray, shape (n_out,)
        Ridge term added to the kernel diagonal per output (0: exact interpolation).
    log_factor : numpy.ndarray, shape (n_out,)
        Back-transform factor ``c`` of the log outputs, predicted as ``c 10**f``
        (:func:`moorlife.rbf.retransform_factor`); 1.0 for linear outputs and without correction.
    trend : Trend or None
        The trend columns beside the polynomial, on the knots the training states support.
    """

    space: Space
    centres: np.ndarray
    shape: np.ndarray
    weights: np.ndarray
    poly_coef: np.ndarray
    log_output: np.ndarray
    loo_error: np.ndarray
    smoothing: np.ndarray
    log_factor: np.ndarray
    trend: Trend | None = None

    @property
    def n_outputs(self) -> int:
        return int(self.weights.shape[1])


def fit_rbf(
    points: npt.ArrayLike,
    values: npt.ArrayLike,
    *,
    is_direction: npt.ArrayLike,
    shape: float | npt.ArrayLike | None = None,
    shapes: npt.ArrayLike | None = None,
    log_output: bool | npt.ArrayLike = False,
    smoothing: float | npt.ArrayLike = 0.0,
    share_tol: float = 0.0,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
    retransform: str = "none",
    trend: Trend | None = None,
) -> RBFModel:
    """Fit a multi-output Gaussian RBF with a first-degree polynomial.

    Parameters
    ----------
    points : array_like, shape (m, d)
        Training sea states in physical units (directions in degrees).
    values : array_like, shape (m, n_out) or (m,)
        Simulated outputs.
    is_direction : array_like of bool, shape (d,)
    shape : float or array_like (n_out,), optional
        Fixed ``q0`` per output. If omitted, Rippa's criterion picks it from ``shapes``.
    shapes : array_like, optional
        Candidate grid for Rippa; default ``shape_grid(0.02, 1.0, 20)``.
    log_output : bool or array_like of bool (n_out,)
        Interpolate ``log10`` of these outputs (they must be positive).
    smoothing : float or array_like
        Ridge term (0: exact interpolation, the paper's choice). Several values are candidates:
        each output then takes the one with the smallest leave-one-out error, jointly with its
        shape (:func:`choose_shapes_and_smoothing`).
    share_tol : float
        See :func:`choose_shapes`.
    lo, span : array_like (d,), optional
        Normalisation offset and range of the scalars (e.g. the hindcast's, see
        :func:`fit_space`); default from the points.
    retransform : {"none", "smearing", "ratio"}
        Back-transform correction of the log outputs (:mod:`moorlife.rbf.transform`), from the
        leave-one-out residuals of the fit; "none" predicts ``10**f``.
    trend : Trend, optional
        Piecewise-linear trend columns beside the polynomial (:mod:`moorlife.rbf.trend`); only
        the knots the training states support are kept.

    Returns
    -------
    RBFModel

    Raises
    ------
    ValueError
        On non-finite values, non-positive values of a log output (naming output and row),
        or mismatched shapes.
    """
    space, z, d2, basis, y, logs, trend = _prepare(points, values, is_direction, log_output, lo, span, trend)
    n_out = y.shape[1]
    lam_grid = np.atleast_1d(np.asarray(smoothing, dtype=float))
    if lam_grid.size == 0 or np.any(~(lam_grid >= 0)):
        raise ValueError(f"smoothing must be non-negative, got {smoothing!r}")
    if shape is None:
        grid = shape_grid(0.02, 1.0, 20) if shapes is None else np.asarray(shapes, dtype=float)
        q, lam = choose_shapes_and_smoothing(d2, basis, y, grid, lam_grid, share_tol)
    else:
        q = np.broadcast_to(np.asarray(shape, dtype=float), (n_out,)).copy()
        if np.any(~(q > 0)):
            raise ValueError(f"shape parameters must be positive, got {q}")
        lam = np.full(n_out, lam_grid[0])
        if lam_grid.size > 1:  # fixed shapes, smoothing by leave-one-out per shape
            for qi in np.unique(q):
                cols = np.flatnonzero(q == qi)
                lam[cols] = choose_shapes_and_smoothing(d2, basis, y[:, cols], [qi], lam_grid, share_tol)[1]
    return _assemble(space, z, d2, basis, y, q, lam, logs, retransform, trend)


def fit_rbf_fixed(
    points: npt.ArrayLike,
    values: npt.ArrayLike,
    *,
    is_direction: npt.ArrayLike,
    shape: float | npt.ArrayLike,
    smoothing: float | npt.ArrayLike = 0.0,
    log_output: bool | npt.ArrayLike = False,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
    retransform: str = "none",
    trend: Trend | None = None,
) -> RBFModel:
    """Fit with a given shape parameter and smoothing per output (no search).

    The fit of a choice made elsewhere, e.g. by :func:`moorlife.rbf.choose_per_output`.

    Parameters
    ----------
    points, values, is_direction, log_output, lo, span, retransform, trend
        As :func:`fit_rbf`.
    shape : float or array_like (n_out,)
        ``q0`` per output (positive).
    smoothing : float or array_like (n_out,)
        Ridge term per output (non-negative).

    Returns
    -------
    RBFModel

    Raises
    ------
    ValueError
        As :func:`fit_rbf`, and on a non-positive shape or a negative smoothing.
    """
    space, z, d2, basis, y, logs, trend = _prepare(points, values, is_direction, log_output, lo, span, trend)
    n_out = y.shape[1]
    q = np.broadcast_to(np.asarray(shape, dtype=float), (n_out,)).copy()
    lam = np.broadcast_to(np.asarray(smoothing, dtype=float), (n_out,)).copy()
    if np.any(~(q > 0)):
        raise ValueError(f"shape parameters must be positive, got {q}")
    if np.any(~(lam >= 0)):
        raise ValueError(f"smoothing must be non-negative, got {lam}")
    return _assemble(space, z, d2, basis, y, q, lam, logs, retransform, trend)


def model_basis(points: np.ndarray, z: np.ndarray, is_direction: np.ndarray, trend: Trend | None) -> np.ndarray:
    """The trend basis of a model: :func:`polynomial_basis` of ``z``, then the trend's columns.

    Parameters
    ----------
    points : numpy.ndarray, shape (n, d)
        Physical units (the trend's knots are in them).
    z : numpy.ndarray, shape (n, d)
        The same points normalised.
    is_direction : numpy.ndarray of bool, shape (d,)
    trend : Trend or None

    Returns
    -------
    numpy.ndarray, shape (n, p)
    """
    basis = polynomial_basis(z, is_direction)
    if trend is None:
        return basis
    return np.hstack([basis, trend_basis(points, trend)])


def centre_geometry(
    points: npt.ArrayLike,
    is_direction: npt.ArrayLike,
    *,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
    trend: Trend | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Squared normalised distances between the training points and their trend basis.

    The inputs of :func:`moorlife.rbf.loo_residuals` and :func:`moorlife.rbf.choose_per_output`,
    computed exactly as :func:`fit_rbf` computes them.

    Parameters
    ----------
    points : array_like, shape (m, d)
    is_direction : array_like of bool, shape (d,)
    lo, span, trend : optional
        As :func:`fit_rbf`.

    Returns
    -------
    d2 : numpy.ndarray, shape (m, m)
    basis : numpy.ndarray, shape (m, p)
    """
    x = as_points(points)
    space = fit_space(x, is_direction, lo=lo, span=span)
    z = embed(x, space)
    trend = None if trend is None else supported_trend(trend, x)
    return squared_distances(z, z, space.is_direction), model_basis(x, z, space.is_direction, trend)


def _prepare(
    points: npt.ArrayLike,
    values: npt.ArrayLike,
    is_direction: npt.ArrayLike,
    log_output: bool | npt.ArrayLike,
    lo: npt.ArrayLike | None,
    span: npt.ArrayLike | None,
    trend: Trend | None,
) -> tuple[Space, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, Trend | None]:
    """Checked, transformed values and the embedded centres: ``space, z, d2, basis, y, logs, trend``."""
    x = as_points(points)
    y = np.asarray(values, dtype=float)
    if y.ndim == 1:
        y = y[:, None]
    if y.shape[0] != x.shape[0]:
        raise ValueError(f"values have {y.shape[0]} rows, points have {x.shape[0]}")
    if not np.all(np.isfinite(y)):
        row, col = np.argwhere(~np.isfinite(y))[0]
        raise ValueError(f"values are not finite: output {col}, row {row} = {y[row, col]!r}")
    n_out = y.shape[1]
    logs = np.broadcast_to(np.asarray(log_output, dtype=bool), (n_out,)).copy()
    if logs.any():
        sub = y[:, logs]
        if np.any(sub <= 0):
            row, col = np.argwhere(sub <= 0)[0]
            out = int(np.flatnonzero(logs)[col])
            raise ValueError(f"output {out} is log-transformed but row {row} = {sub[row, col]!r} is not positive")
        y = y.copy()
        y[:, logs] = np.log10(sub)
    space = fit_space(x, is_direction, lo=lo, span=span)
    z = embed(x, space)
    d2 = squared_distances(z, z, space.is_direction)
    trend = None if trend is None else supported_trend(trend, x)
    basis = model_basis(x, z, space.is_direction, trend)
    if z.shape[0] < basis.shape[1] + 1:
        raise ValueError(f"{z.shape[0]} training points are too few for {basis.shape[1]} polynomial terms")
    return space, z, d2, basis, y, logs, trend


def _assemble(
    space: Space,
    z: np.ndarray,
    d2: np.ndarray,
    basis: np.ndarray,
    y: np.ndarray,
    q: np.ndarray,
    lam: np.ndarray,
    logs: np.ndarray,
    retransform: str,
    trend: Trend | None = None,
) -> RBFModel:
    """Weights, polynomial and leave-one-out residuals at the chosen ``(q0, lambda)`` per output."""
    if retransform not in RETRANSFORMS:
        raise ValueError(f"unknown back-transform correction {retransform!r}; expected one of {list(RETRANSFORMS)}")
    n_out = y.shape[1]
    m = z.shape[0]
    weights = np.empty_like(y)
    poly = np.empty((basis.shape[1], n_out))
    loo = np.empty_like(y)
    for qi, li in sorted(set(zip(q.tolist(), lam.tolist()))):
        cols = np.flatnonzero((q == qi) & (lam == li))
        mat = augmented_matrix(d2, basis, float(qi), float(li))
        w, c = solve_weights(mat, y[:, cols])
        weights[:, cols] = w
        poly[:, cols] = c
        h, _ = kernel_block_inverse(mat[:m, :m], basis)
        if h is None:  # not numerically positive definite: fall back on the full inverse
            h, _ = _inverse(mat)
        loo[:, cols] = rippa_errors(h, y[:, cols])
    factor = np.ones(n_out)
    if logs.any():
        factor[logs] = retransform_factor(y[:, logs], loo[:, logs], retransform)
    return RBFModel(
        space=space,
        centres=z,
        shape=q,
        weights=weights,
        poly_coef=poly,
        log_output=logs,
        loo_error=loo,
        smoothing=lam,
        log_factor=factor,
        trend=trend,
    )
