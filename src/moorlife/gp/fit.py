"""The fit: hyperparameters by scikit-learn's marginal likelihood, then the exact conditioning on every state."""

from __future__ import annotations

import logging
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np
import numpy.typing as npt
import scipy.linalg as sla

from moorlife.gp.covariance import MATERN_NU, correlation, covariance_code, gate
from moorlife.space import Space, as_points, fit_space

__all__ = [
    "GPModel",
    "GP_KERNELS",
    "GP_MEANS",
    "GP_RETRANSFORMS",
    "chord_embed",
    "embedded_names",
    "fit_gp",
    "select_outputs",
]

log = logging.getLogger("moorlife.gp")

#: Kernels: one length scale per embedded coordinate (``ard``), or one for all (``isotropic``).
GP_KERNELS: tuple[str, ...] = ("ard", "isotropic")
#: Prior means: the training mean (``constant``), or a first-degree polynomial of the embedded
#: inputs estimated by generalised least squares with the process's covariance (``linear``:
#: universal kriging).
GP_MEANS: tuple[str, ...] = ("constant", "linear")
#: Back-transforms of a ``log10`` output (module :mod:`moorlife.gp`).
GP_RETRANSFORMS: tuple[str, ...] = ("none", "noise", "predictive")
#: How the outputs with the additive term start their hyperparameter fit (``fit_gp``'s
#: ``additive_start``).
GP_ADDITIVE_STARTS: tuple[str, ...] = ("joint", "warm", "frozen")

_LN10_SQ = float(np.log(10.0) ** 2)


@dataclass(frozen=True)
class GPModel:
    """A fitted multi-output Gaussian process (one set of hyperparameters per output; immutable arrays).

    The posterior mean of output ``j`` at a point ``x`` (embedded by :func:`chord_embed`) is
    ``mean_j + x . slope_j + sum_i rho_j(x, c_i) w_ij`` (no slope with a constant prior mean), with
    ``rho_j`` the unit-amplitude correlation of the model's ``covariance``
    (:mod:`moorlife.gp.covariance`; by default the Gaussian ``exp(-|(x - c) / l_j|^2 / 2)``); its
    latent variance is ``signal_var_j (1 - rho^T B_j^-1 rho)`` with
    ``B_j = R_j + (noise_var_j / signal_var_j) I`` (``R_j`` the correlation matrix of the training
    states), whose Cholesky factor is ``chol[j]``.

    Attributes
    ----------
    space : moorlife.space.Space
        The normalisation of the physical inputs (scalars by range, directions in degrees).
    centres : numpy.ndarray, shape (m, p)
        Embedded training states (:func:`chord_embed`).
    length_scale : numpy.ndarray, shape (n_out, p)
        Length scale of every output along every embedded coordinate.
    signal_var, noise_var : numpy.ndarray, shape (n_out,)
        Signal and noise variances in the interpolated (transformed) units.
    mean : numpy.ndarray, shape (n_out,)
        The constant prior mean (the training mean of the transformed values), or the intercept
        of the linear one.
    weights : numpy.ndarray, shape (m, n_out)
        ``B_j^-1 (y_j - prior mean_j)``.
    chol : numpy.ndarray, shape (n_out, m, m)
        Lower Cholesky factor of every ``B_j``.
    log_output : numpy.ndarray of bool, shape (n_out,)
    loo_error : numpy.ndarray, shape (m, n_out)
        Closed-form leave-one-out residuals in the transformed units.
    loo_var : numpy.ndarray, shape (m, n_out)
        Leave-one-out predictive variance of a new realisation (noise included) at each training state.
    log_factor : numpy.ndarray, shape (n_out,)
        The constant back-transform factor of the ``log10`` outputs (1.0 for linear outputs and
        ``retransform="none"``): ``exp((ln 10)^2 noise_var / 2)``.
    retransform : str
        One of :data:`GP_RETRANSFORMS`.
    slope : numpy.ndarray, shape (p, n_out), or None
        The slopes of a linear prior mean along the embedded coordinates (``None``: constant).
    covariance : str
        One of :data:`~moorlife.gp.covariance.GP_COVARIANCES`.
    wind_length_scale : numpy.ndarray, shape (n_out, p), or None
        The length scales of the additive term (:func:`fit_gp`'s ``additive_columns``):
        ``inf`` along the coordinates it does not see, and along every coordinate of an output
        without it (``None``: no output has it).
    wind_var : numpy.ndarray, shape (n_out,), or None
        The additive term's signal variance (0 for an output without it). With it the
        correlation of output ``j`` is ``rho_j + (wind_var_j / signal_var_j) g_j g_j' rho_w,j``
        and its prior variance ``signal_var_j + wind_var_j g_j^2``: ``B_j`` and the posterior
        mean and latent variance above use that sum.
    wind_gate : numpy.ndarray, shape (n_out,), or None
        The scale of the term's sea gate ``g_j(x) = exp(-z_hs / wind_gate_j)``
        (:func:`moorlife.gp.covariance.gate`; ``z_hs`` the embedded column ``gate_column``; ``inf``:
        no gate, ``g = 1``).
    gate_column : int
        The embedded column of the gate (-1: none).
    """

    space: Space
    centres: np.ndarray
    length_scale: np.ndarray
    signal_var: np.ndarray
    noise_var: np.ndarray
    mean: np.ndarray
    weights: np.ndarray
    chol: np.ndarray
    log_output: np.ndarray
    loo_error: np.ndarray
    loo_var: np.ndarray
    log_factor: np.ndarray
    retransform: str
    slope: np.ndarray | None = None
    covariance: str = "gaussian"
    wind_length_scale: np.ndarray | None = None
    wind_var: np.ndarray | None = None
    wind_gate: np.ndarray | None = None
    gate_column: int = -1

    @property
    def n_outputs(self) -> int:
        return int(self.weights.shape[1])

    @property
    def wind_ratio(self) -> np.ndarray:
        """``wind_var / signal_var`` per output (zeros without the additive term)."""
        if self.wind_var is None:
            return np.zeros(self.n_outputs)
        return self.wind_var / self.signal_var

    def gates(self, z: np.ndarray, outputs: npt.ArrayLike) -> np.ndarray:
        """The sea gate of some outputs at embedded points ``z``: shape ``(n, len(outputs))``."""
        o = np.asarray(outputs, dtype=np.int64)
        if self.wind_gate is None or self.gate_column < 0:
            return np.ones((z.shape[0], o.size))
        return gate(z[:, self.gate_column, None], self.wind_gate[o][None, :])


def select_outputs(model: GPModel, columns: npt.ArrayLike) -> GPModel:
    """The :class:`GPModel` of some of ``model``'s outputs (each output's process is its own).

    Parameters
    ----------
    model : GPModel
    columns : array_like of int
        Output indices, in the order wanted.

    Returns
    -------
    GPModel
        Every per-output field sliced; the shared fields (normalisation, training states) kept.
    """
    c = np.asarray(columns, dtype=np.int64)
    if c.ndim != 1 or c.size == 0 or c.min() < 0 or c.max() >= model.n_outputs:
        raise ValueError(f"select_outputs: columns {c.tolist()} out of the model's {model.n_outputs} outputs")
    return replace(
        model,
        length_scale=model.length_scale[c],
        signal_var=model.signal_var[c],
        noise_var=model.noise_var[c],
        mean=model.mean[c],
        weights=model.weights[:, c],
        chol=model.chol[c],
        log_output=model.log_output[c],
        loo_error=model.loo_error[:, c],
        loo_var=model.loo_var[:, c],
        log_factor=model.log_factor[c],
        slope=None if model.slope is None else model.slope[:, c],
        wind_length_scale=None if model.wind_length_scale is None else model.wind_length_scale[c],
        wind_var=None if model.wind_var is None else model.wind_var[c],
        wind_gate=None if model.wind_gate is None else model.wind_gate[c],
    )


def chord_embed(points: npt.ArrayLike, space: Space) -> np.ndarray:
    """Physical points in the GP's input space: scalars by range, each direction as ``(cos, sin) / pi``.

    A direction on the circle of radius ``1 / pi`` has the chord distance ``(2 / pi) sin(d / 2)``
    to another at angle ``d``: the folded difference of :mod:`moorlife.space` (``d / pi``, 180 deg
    -> 1) to first order, and a Euclidean distance, so that the Gaussian kernel stays positive
    definite (the folded difference does not guarantee it).

    Parameters
    ----------
    points : array_like, shape (n, d)
        Physical units, directions in degrees.
    space : moorlife.space.Space

    Returns
    -------
    numpy.ndarray, shape (n, d + n_directions)
        The scalars in their order, then ``cos`` and ``sin`` of each direction.
    """
    x = as_points(points)
    if x.shape[1] != space.scale.size:
        raise ValueError(f"points have {x.shape[1]} columns, the space has {space.scale.size}")
    isdir = space.is_direction
    scal = (x[:, ~isdir] - space.lower[~isdir]) / space.scale[~isdir]
    ang = np.deg2rad(x[:, isdir])
    return np.ascontiguousarray(np.hstack([scal, np.cos(ang) / np.pi, np.sin(ang) / np.pi]))


def embedded_names(variables: Sequence[str], is_direction: npt.ArrayLike) -> list[str]:
    """Names of the coordinates of :func:`chord_embed`: the scalars, then ``cos_<dir>`` and ``sin_<dir>``."""
    isdir = np.asarray(is_direction, dtype=bool)
    v = list(variables)
    dirs = [n for n, d in zip(v, isdir) if d]
    return [n for n, d in zip(v, isdir) if not d] + [f"cos_{n}" for n in dirs] + [f"sin_{n}" for n in dirs]


def fit_gp(
    points: npt.ArrayLike,
    values: npt.ArrayLike,
    *,
    is_direction: npt.ArrayLike,
    log_output: bool | npt.ArrayLike = False,
    lo: npt.ArrayLike | None = None,
    span: npt.ArrayLike | None = None,
    kernel: str = "ard",
    length_scale: tuple[float, float, float] = (0.3, 0.01, 100.0),
    signal: tuple[float, float, float] = (1.0, 1e-3, 1e3),
    noise: tuple[float, float, float] = (1e-2, 1e-8, 1.0),
    restarts: int = 0,
    seed: int = 0,
    subsample: int = 0,
    retransform: str = "noise",
    groups: npt.ArrayLike | None = None,
    prior_mean: str = "constant",
    covariance: str = "gaussian",
    additive_columns: Sequence[int] | None = None,
    additive_outputs: bool | npt.ArrayLike = True,
    gate_column: int | None = None,
    gate_scale: tuple[float, float, float] = (0.2, 0.02, 2.0),
    additive_subsample: int | None = None,
    additive_start: str = "joint",
) -> GPModel:
    """Fit one Gaussian process with a noise term per output column.

    For each output, scikit-learn's :class:`~sklearn.gaussian_process.GaussianProcessRegressor`
    (``normalize_y=True``, kernel ``C * RBF(l) + WhiteKernel``, or ``Matern(l, nu)`` in place of
    ``RBF``) maximises the log marginal likelihood over the amplitude, the length scales and the
    noise, on ``subsample`` training states (drawn with ``seed``; 0 or ``>= m``: all of them)
    with ``restarts`` extra starts (drawn with ``seed``). With those hyperparameters the process
    is conditioned on every training state (one Cholesky factorisation per output), which also
    gives the leave-one-out residuals in closed form (Rasmussen & Williams 2006, eq. 5.12):
    ``r_i = [B^-1 (y - mean)]_i / [B^-1]_ii`` with the noise in ``B``.

    The hyperparameter fit sees the standardised values only, so an output whose standardised
    fit data equal an earlier output's (to 1e-9: a constant factor apart, or after ``log10`` a
    constant apart, as the S-N and T-N damage of a line with equal slopes) takes that fit's
    hyperparameters instead of repeating it.

    Parameters
    ----------
    points : array_like, shape (m, d)
        Training states, physical units (directions in degrees).
    values : array_like, shape (m, n_out) or (m,)
    is_direction : array_like of bool, shape (d,)
    log_output : bool or array_like of bool (n_out,)
        Model ``log10`` of these outputs (they must be positive).
    lo, span : array_like (d,), optional
        Normalisation of the scalars (:func:`moorlife.space.fit_space`); default the points'.
    kernel : {"ard", "isotropic"}
        One length scale per embedded coordinate, or one for all.
    length_scale, signal, noise : tuple of float
        ``(initial, min, max)`` of the length scales (embedded units, see :func:`chord_embed`),
        of the signal variance and of the noise variance (both as fractions of the variance of
        the subsample's transformed values).
    restarts : int
        Extra optimiser starts (``n_restarts_optimizer``).
    seed : int
        The subsample and the restarts (``random_state``).
    subsample : int
        Training states of the hyperparameter fit (0: all).
    retransform : {"none", "noise", "predictive"}
        Back-transform of the ``log10`` outputs (:mod:`moorlife.gp`).
    groups : array_like of int, shape (n_out,), optional
        Outputs with the same label share their hyperparameters: one scikit-learn fit of the
        group's columns together (``normalize_y`` standardises each column, and the log marginal
        likelihood is summed over them), so they share the length scales and the signal and noise
        variances as fractions of each column's variance; the prediction then evaluates one
        kernel row per group. Default: every output its own.
    prior_mean : {"constant", "linear"}
        ``constant``: the training mean. ``linear``: a first-degree polynomial of the embedded
        inputs (universal kriging): the hyperparameters are fitted on the residuals of its
        ordinary least-squares fit, then its coefficients are estimated by generalised least
        squares with the process's covariance, jointly with the weights. The leave-one-out
        residuals re-estimate the coefficients without each state (Dubrule 1983). The latent
        variance (``retransform="predictive"``) is not available with it.
    covariance : {"gaussian", "matern52", "matern32"}
        The correlation family (:mod:`moorlife.gp.covariance`): scikit-learn's ``RBF``, or its
        ``Matern`` with ``nu`` 2.5 or 1.5.
    additive_columns : sequence of int, optional
        The embedded coordinates (:func:`chord_embed`'s columns) of an additive term: the
        outputs of ``additive_outputs`` get the kernel ``C * k(l) + C_w * k_w(l_w) + White``,
        ``k_w`` of the same family seeing these coordinates only (:class:`~moorlife.gp.kernels.OnColumns`),
        with its own amplitude and length scales (the bounds of ``signal`` and ``length_scale``).
        A line's tension variance is nearly a wind part plus a wave part; the term lets the
        output follow the wind where the waves are small (``validation/reconstruction.md``,
        section 20). Default: no such term.
    additive_outputs : bool or array_like of bool (n_out,)
        The outputs with the additive term (when ``additive_columns`` is given). The outputs of a
        ``groups`` label must all have it or all not.
    gate_column : int, optional
        The embedded column of the normalised wave height: the additive term is multiplied by
        the sea gate ``g(x) g(x')``, ``g = exp(-z_hs / scale)`` (:class:`~moorlife.gp.kernels.SeaGate`),
        so that it fades where the waves drive the output. Without it the term holds
        everywhere, storms included (section 21 of ``validation/reconstruction.md``: it then
        loses the storm hours).
    gate_scale : tuple of float
        ``(initial, min, max)`` of the gate's scale (embedded units: a fraction of the wave
        height's normalisation span), fitted with the other hyperparameters.
    additive_subsample : int, optional
        Training states of the hyperparameter fit of the outputs with the additive term (0: all;
        default ``subsample``), drawn as ``subsample``'s: its five more hyperparameters want
        more states than the plain kernel's, and the other outputs need not pay for them.
    additive_start : {"joint", "warm", "frozen"}
        How the outputs with the additive term find their hyperparameters. ``joint``: all of
        them together from their initial values. ``warm``: the plain kernel is fitted first on
        ``subsample`` states, and the joint fit starts from its amplitude, length scales and
        noise. ``frozen``: as ``warm``, with the full kernel's length scales kept at that fit's
        (the amplitudes, the term's length scales, the gate and the noise are fitted).

    Returns
    -------
    GPModel

    Raises
    ------
    ValueError
        On non-finite values, a non-positive value of a ``log10`` output, an unknown kernel,
        covariance, back-transform or ``additive_start``, inconsistent bounds, additive columns
        out of range or repeated, or a group mixing outputs with and without the additive term.
    """
    from sklearn.gaussian_process.kernels import RBF, Matern, WhiteKernel
    from sklearn.gaussian_process.kernels import ConstantKernel as C

    if kernel not in GP_KERNELS:
        raise ValueError(f"unknown GP kernel {kernel!r}; expected one of {list(GP_KERNELS)}")
    if prior_mean not in GP_MEANS:
        raise ValueError(f"unknown GP prior mean {prior_mean!r}; expected one of {list(GP_MEANS)}")
    if prior_mean == "linear" and retransform == "predictive":
        raise ValueError("GP prior mean 'linear' has no latent variance: retransform 'predictive' is not available")
    covariance_code(covariance)  # refuses an unknown family
    if additive_start not in GP_ADDITIVE_STARTS:
        raise ValueError(f"unknown GP additive_start {additive_start!r}; expected one of {list(GP_ADDITIVE_STARTS)}")
    if retransform not in GP_RETRANSFORMS:
        raise ValueError(f"unknown GP back-transform {retransform!r}; expected one of {list(GP_RETRANSFORMS)}")
    bounded = (("length_scale", length_scale), ("signal", signal), ("noise", noise), ("gate_scale", gate_scale))
    for name, (init, low, high) in bounded:
        if not 0 < low <= init <= high:
            raise ValueError(f"GP {name}: need 0 < min <= initial <= max, got {init}, {low}, {high}")
    x = as_points(points)
    y = _checked(values, x.shape[0])
    logs = np.broadcast_to(np.asarray(log_output, dtype=bool), (y.shape[1],)).copy()
    if logs.any():
        if np.any(y[:, logs] <= 0):
            row, col = np.argwhere(y[:, logs] <= 0)[0]
            raise ValueError(
                f"output {int(np.flatnonzero(logs)[col])} is log-transformed but row {row} is not positive"
            )
        y[:, logs] = np.log10(y[:, logs])
    space = fit_space(x, is_direction, lo=lo, span=span)
    z = chord_embed(x, space)
    m, p = z.shape
    n_out = y.shape[1]
    sub = _subsample(m, subsample, seed)
    sub_add = sub if additive_subsample is None else _subsample(m, additive_subsample, seed)

    def shape_of(n_dims: int):  # the correlation family, one length scale per coordinate (ard) or one
        ls0 = np.full(n_dims, length_scale[0]) if kernel == "ard" else length_scale[0]
        if covariance == "gaussian":
            return RBF(ls0, length_scale[1:])
        return Matern(ls0, length_scale[1:], nu=MATERN_NU[covariance])

    ls = np.empty((n_out, p))
    sig, noi, ratio, mean = np.empty(n_out), np.empty(n_out), np.empty(n_out), y.mean(axis=0)
    h = np.column_stack([np.ones(m), z]) if prior_mean == "linear" else None
    # the hyperparameters' data: the values, or their residuals from the least-squares linear mean
    yh = y if h is None else y - h @ np.linalg.lstsq(h, y, rcond=None)[0]
    shape = shape_of(p)
    k = C(signal[0], signal[1:]) * shape + WhiteKernel(noise[0], noise[1:])  # cloned by every fit
    add_cols, has_add = _additive(additive_columns, additive_outputs, p, n_out)
    k_add = None
    if add_cols is not None:
        from moorlife.gp.kernels import OnColumns, SeaGate

        term = OnColumns(shape_of(add_cols.size), tuple(add_cols.tolist()))
        if gate_column is not None:
            if not 0 <= gate_column < p or gate_column in add_cols:
                raise ValueError(
                    f"GP gate_column {gate_column}: need one of the {p} embedded coordinates, not the term's"
                )
            term = SeaGate(term, int(gate_column), gate_scale[0], (gate_scale[1], gate_scale[2]))
        k_add = C(signal[0], signal[1:]) * shape + C(signal[0], signal[1:]) * term + WhiteKernel(noise[0], noise[1:])
    wls = np.full((n_out, p), np.inf) if add_cols is not None else None
    wvar = np.zeros(n_out) if add_cols is not None else None
    wgate = np.full(n_out, np.inf) if add_cols is not None else None
    fitted: list[_Fitted] = []
    for cols in _output_groups(groups, n_out):
        with_add = bool(has_add[cols[0]])
        if has_add[cols].any() and not has_add[cols].all():
            raise ValueError(
                f"GP outputs {cols.tolist()} share their hyperparameters but not all have the additive term"
            )
        rows = sub_add if with_add else sub
        data = _group_data(yh, rows, cols)
        std, unit = _standardised(data)
        twin = _twin_of(fitted, with_add, unit)
        if twin is None:
            kern = k_add if with_add else k
            if with_add and additive_start != "joint":  # start from the plain kernel's fit on the subsample
                plain, plain_std = _fit(k, z[sub], _group_data(yh, sub, cols), restarts, seed, cols)
                ratio0 = plain_std.flat[0] / std.flat[0]  # sd of the plain fit's data over this fit's
                kern = _started(kern, plain, ratio0, frozen=additive_start == "frozen")
            kf, std = _fit(kern, z[rows], data, restarts, seed, cols)
        else:  # the same standardised data as an earlier fit (a constant factor apart): its hyperparameters
            kf = twin.kernel
            log.info(
                "GP outputs %s: the hyperparameters of an earlier fit on the same standardised data", cols.tolist()
            )
        scale2 = np.broadcast_to(std**2, (cols.size,))
        full = kf.k1.k1 if with_add else kf.k1  # C * k(l)
        ls[cols] = np.broadcast_to(full.k2.length_scale, (p,))
        sig[cols] = full.k1.constant_value * scale2
        noi[cols] = kf.k2.noise_level * scale2
        ratio[cols] = noi[cols[0]] / sig[cols[0]] if twin is None else twin.ratio  # one per group: its outputs share B
        if twin is None:
            fitted.append(_Fitted(with_add, unit, kf, float(ratio[cols[0]])))
        if with_add:
            w = kf.k1.k2  # C_w * [SeaGate of] OnColumns(k_w(l_w))
            on = w.k2.base if gate_column is not None else w.k2
            wls[np.ix_(cols, add_cols)] = np.broadcast_to(on.base.length_scale, (add_cols.size,))
            wvar[cols] = w.k1.constant_value * scale2
            if gate_column is not None:
                wgate[cols] = w.k2.scale
    return _condition(
        space,
        z,
        y,
        ls,
        sig,
        noi,
        ratio,
        mean,
        logs,
        retransform,
        h,
        covariance,
        wind_ls=wls,
        wind_var=wvar,
        wind_gate=wgate,
        gate_column=-1 if gate_column is None or add_cols is None else int(gate_column),
    )


def _additive(
    columns: Sequence[int] | None, outputs: bool | npt.ArrayLike, p: int, n_out: int
) -> tuple[np.ndarray | None, np.ndarray]:
    """The additive term's embedded columns (None: no term) and which outputs have it."""
    if columns is None:
        return None, np.zeros(n_out, dtype=bool)
    c = np.asarray(columns, dtype=np.int64).reshape(-1)
    if c.size == 0 or c.min() < 0 or c.max() >= p or np.unique(c).size != c.size:
        raise ValueError(f"GP additive_columns {c.tolist()}: need distinct columns of the {p} embedded coordinates")
    has = np.broadcast_to(np.asarray(outputs, dtype=bool), (n_out,)).copy()
    return (c, has) if has.any() else (None, has)


def _group_data(yh: np.ndarray, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
    """A hyperparameter group's fit data on some rows: a vector for one output, else a matrix."""
    return yh[rows, cols[0]] if cols.size == 1 else yh[np.ix_(rows, cols)]


def _fit(kernel, z: np.ndarray, y: np.ndarray, restarts: int, seed: int, cols: np.ndarray):
    """scikit-learn's fit of ``y`` (``normalize_y``, ``restarts`` seeded restarts): the fitted kernel
    and the data's sd; convergence warnings logged against the output columns ``cols``."""
    from sklearn.exceptions import ConvergenceWarning
    from sklearn.gaussian_process import GaussianProcessRegressor

    gpr = GaussianProcessRegressor(
        kernel, alpha=0.0, normalize_y=True, n_restarts_optimizer=restarts, random_state=seed
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ConvergenceWarning)
        gpr.fit(z, y)
    for w in caught:
        if issubclass(w.category, ConvergenceWarning):
            log.info("GP outputs %s: %s", cols.tolist(), str(w.message).splitlines()[0])
    return gpr.kernel_, np.asarray(gpr._y_train_std, dtype=float)


class _Fitted(NamedTuple):
    """An earlier hyperparameter fit of ``fit_gp``: its kernel kind, standardised data, fitted
    kernel and noise over signal ratio."""

    with_add: bool
    unit: np.ndarray
    kernel: object
    ratio: float


def _started(k_add, plain, std_ratio: float, *, frozen: bool):
    """The additive kernel ``C * k(l) + C_w * term + White`` started at a plain fit ``C * k(l) + White``.

    ``std_ratio`` is the plain fit's data sd over the additive fit's: the amplitude and the noise
    are fractions of the data variance. Initial values are clipped to the bounds; ``frozen`` fixes
    the length scales ``l``."""
    from sklearn.base import clone

    out = clone(k_add)
    full, white = out.k1.k1, out.k2
    amp = plain.k1.k1.constant_value * std_ratio**2
    noise = plain.k2.noise_level * std_ratio**2
    full.k1.constant_value = float(np.clip(amp, *np.ravel(full.k1.constant_value_bounds)))
    white.noise_level = float(np.clip(noise, *np.ravel(white.noise_level_bounds)))
    full.k2.length_scale = plain.k1.k2.length_scale
    if frozen:
        full.k2.length_scale_bounds = "fixed"
    return out


def _standardised(data: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The standard deviation (zero as one, as ``normalize_y``) and the standardised values of a fit's data."""
    std = np.std(data, axis=0)
    std = np.where(std < 10 * np.finfo(float).eps, 1.0, std)
    return std, (data - data.mean(axis=0)) / std


def _twin_of(fitted: list[_Fitted], with_add: bool, unit: np.ndarray, atol: float = 1e-9) -> _Fitted | None:
    """An earlier fit of the same kernel on the same standardised data (to ``atol``), or None.

    ``normalize_y`` makes the hyperparameter fit see only the standardised values, so outputs a
    constant factor apart (after ``log10``, a constant apart) have the same optimum: the damage of
    the S-N and T-N curves of a line where both slopes are equal, for example."""
    for twin in fitted:
        same_shape = twin.with_add == with_add and twin.unit.shape == unit.shape
        if same_shape and np.max(np.abs(twin.unit - unit), initial=0.0) <= atol:
            return twin
    return None


def _subsample(m: int, n: int, seed: int) -> np.ndarray:
    """The rows of the hyperparameter fit: ``n`` of ``m`` drawn with ``seed``, sorted (0 or ``>= m``: all)."""
    if 0 < n < m:
        return np.sort(np.random.default_rng(seed).choice(m, int(n), replace=False))
    return np.arange(m)


def _output_groups(groups: npt.ArrayLike | None, n_out: int) -> list[np.ndarray]:
    """The output columns of each hyperparameter group, in order of first output."""
    if groups is None:
        return [np.array([j]) for j in range(n_out)]
    g = np.asarray(groups)
    if g.shape != (n_out,):
        raise ValueError(f"groups has shape {g.shape}, expected ({n_out},): one label per output")
    _, first, inverse = np.unique(g, return_index=True, return_inverse=True)
    return [np.flatnonzero(inverse.reshape(-1) == k) for k in np.argsort(first)]


def _checked(values: npt.ArrayLike, m: int) -> np.ndarray:
    """The values as a finite float64 ``(m, n_out)`` copy."""
    y = np.array(values, dtype=float)
    if y.ndim == 1:
        y = y[:, None]
    if y.shape[0] != m:
        raise ValueError(f"values have {y.shape[0]} rows, points have {m}")
    if not np.all(np.isfinite(y)):
        row, col = np.argwhere(~np.isfinite(y))[0]
        raise ValueError(f"values are not finite: output {col}, row {row} = {y[row, col]!r}")
    return y


def _condition(
    space: Space,
    z: np.ndarray,
    y: np.ndarray,
    ls: np.ndarray,
    sig: np.ndarray,
    noi: np.ndarray,
    ratio: np.ndarray,
    mean: np.ndarray,
    logs: np.ndarray,
    retransform: str,
    h: np.ndarray | None = None,
    covariance: str = "gaussian",
    *,
    wind_ls: np.ndarray | None = None,
    wind_var: np.ndarray | None = None,
    wind_gate: np.ndarray | None = None,
    gate_column: int = -1,
) -> GPModel:
    """Condition every output's process on all training states: weights, Cholesky factors, leave-one-out.

    ``B = R + ratio I`` (``R`` the correlation, ``ratio`` the noise over the signal variance;
    with the additive term ``R + (wind_var / sig) (g g') R_w + ratio I``, ``g`` the sea gate) is
    factored once per distinct ``(length scales, ratio)``: the outputs of a group share it. With
    ``h`` (the linear prior mean's basis at the training states) the mean's coefficients are the
    generalised least-squares estimate ``(h' B^-1 h)^-1 h' B^-1 y`` and the leave-one-out
    residuals divide by the diagonal of ``B^-1 - B^-1 h (h' B^-1 h)^-1 h' B^-1``."""
    m, n_out = y.shape
    weights = np.empty_like(y)
    loo = np.empty_like(y)
    loo_var = np.empty_like(y)
    chol = np.empty((n_out, m, m))
    mean = mean.copy()
    slope = None if h is None else np.empty((h.shape[1] - 1, n_out))
    done: dict[bytes, tuple] = {}  # outputs of one group share B: factor it once
    wr = np.zeros(n_out) if wind_var is None else wind_var / sig
    for j in range(n_out):
        key = ls[j].tobytes() + np.float64(ratio[j]).tobytes()
        if wr[j] > 0:
            key += wind_ls[j].tobytes() + np.float64(wr[j]).tobytes() + np.float64(wind_gate[j]).tobytes()
        if key in done:
            first, d, bih, s_inv = done[key]
            chol[j] = chol[first]
        else:
            b = correlation(z, z, ls[j], covariance)
            if wr[j] > 0:
                g = _gate_of(z, gate_column, wind_gate[j])
                b += wr[j] * np.outer(g, g) * correlation(z, z, wind_ls[j], covariance)
            b[np.diag_indices(m)] += ratio[j]
            chol[j] = sla.cholesky(b, lower=True, check_finite=False)
            l_inv, info = sla.lapack.dtrtri(chol[j], lower=1)
            if info != 0:
                raise np.linalg.LinAlgError(f"output {j}: the GP's Cholesky factor is singular (dtrtri info {info})")
            d = np.einsum("ij,ij->j", l_inv, l_inv)  # diag(B^-1) = column sums of squares of L^-1
            bih = s_inv = None
            if h is not None:  # universal kriging: the mean's GLS normal matrix, and diag of the projected B^-1
                bih = sla.cho_solve((chol[j], True), h, check_finite=False)
                s_inv = np.linalg.inv(h.T @ bih)
                d = d - np.einsum("ik,kl,il->i", bih, s_inv, bih)
            done[key] = (j, d, bih, s_inv)
        if h is not None:
            beta = s_inv @ (bih.T @ y[:, j])
            mean[j], slope[:, j] = beta[0], beta[1:]
            weights[:, j] = sla.cho_solve((chol[j], True), y[:, j] - h @ beta, check_finite=False)
        else:
            weights[:, j] = sla.cho_solve((chol[j], True), y[:, j] - mean[j], check_finite=False)
        loo[:, j] = weights[:, j] / d
        loo_var[:, j] = sig[j] / d
    factor = np.ones(n_out)
    if retransform != "none":
        factor[logs] = np.exp(0.5 * _LN10_SQ * noi[logs])
    return GPModel(
        space=space,
        centres=z,
        length_scale=ls,
        signal_var=sig,
        noise_var=noi,
        mean=mean,
        weights=weights,
        chol=chol,
        log_output=logs,
        loo_error=loo,
        loo_var=loo_var,
        log_factor=factor,
        retransform=retransform,
        slope=slope,
        covariance=covariance,
        wind_length_scale=wind_ls,
        wind_var=wind_var,
        wind_gate=wind_gate,
        gate_column=gate_column,
    )


def _gate_of(z: np.ndarray, column: int, scale: float) -> np.ndarray:
    """The sea gate at the embedded points (ones without a gate)."""
    return np.ones(z.shape[0]) if column < 0 else gate(z[:, column], scale)
