"""The per-output choice of input space, transform, shape and smoothing by leave-one-out.

Every output takes, among the candidates

* input space: each of the given candidate spaces (e.g. the paper's normalised 5-D space and
  the same with a sixth coordinate),
* transform: linear, or ``log10`` (positive outputs only),
* shape parameter ``q0`` and ridge ``lambda``: the grids of :func:`moorlife.rbf.fit_rbf`,

the one with the smallest leave-one-out RMS error **in the output's own units**. The
leave-one-out residuals come from Rippa's closed form (:func:`moorlife.rbf.loo_residuals`,
one Cholesky factorisation per space and ``(q0, lambda)``, shared by every output and both
transforms). For a ``log10`` candidate the leave-one-out prediction ``log10 y_k - e_k`` is
back-transformed, with the back-transform factor of the configured correction
(:func:`moorlife.rbf.retransform_factor`, itself from the same residuals), before it is
compared with ``y_k``: so ``log10`` and linear candidates compete on the same scale, and the
score is that of the predictor actually used. Only the training values enter: states kept
aside for validation never steer a choice.

Ties go to the first candidate in the order space, transform (linear first), ``lambda``
(ascending), ``q0`` (ascending). Candidates whose kernel matrix is not numerically positive
definite or is worse conditioned than :data:`moorlife.rbf.MIN_RCOND` are skipped.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from moorlife.rbf.kernels import gaussian
from moorlife.rbf.loocv import MIN_RCOND, choose_candidates, loo_residuals
from moorlife.rbf.transform import RETRANSFORMS, loo_error_in_units, retransform_factor

__all__ = ["OutputChoice", "choose_per_output"]


@dataclass(frozen=True)
class OutputChoice:
    """The leave-one-out choice of every output (:func:`choose_per_output`).

    Attributes
    ----------
    space : numpy.ndarray of int, shape (n_out,)
        Index of the chosen input space among the candidates.
    log_output : numpy.ndarray of bool, shape (n_out,)
        ``log10`` chosen.
    shape, smoothing : numpy.ndarray, shape (n_out,)
        Chosen ``q0`` and ``lambda``.
    loo_rmse : numpy.ndarray, shape (n_out,)
        Leave-one-out RMS error of the chosen candidate, in the output's units.
    best : numpy.ndarray, shape (n_space, 2, n_out)
        Smallest leave-one-out RMS (output's units) per space and transform (0 linear,
        1 ``log10``) over ``q0`` and ``lambda``; ``inf`` where not a candidate.
    """

    space: np.ndarray
    log_output: np.ndarray
    shape: np.ndarray
    smoothing: np.ndarray
    loo_rmse: np.ndarray
    best: np.ndarray


def choose_per_output(
    spaces: Sequence[tuple[np.ndarray, np.ndarray]],
    values: npt.ArrayLike,
    *,
    shapes: npt.ArrayLike,
    smoothings: npt.ArrayLike = (0.0,),
    log_values: npt.ArrayLike | None = None,
    log_candidate: npt.ArrayLike | None = None,
    linear_candidate: npt.ArrayLike | None = None,
    retransform: str = "none",
    share_tol: float = 0.0,
) -> OutputChoice:
    """Choose space, transform, ``q0`` and ``lambda`` per output by leave-one-out (module docstring).

    Parameters
    ----------
    spaces : sequence of (d2, basis)
        For each candidate input space: the squared normalised distances ``(m, m)`` between
        the training states and the polynomial basis ``(m, p)`` at them.
    values : array_like, shape (m, n_out)
        Training values in their units (the linear candidates, and the reference of every score).
    shapes : array_like, shape (g,) or (n_out, g)
        Candidate ``q0``: one grid for every output, or one row per output (e.g. one fixed
        value per output, ``(n_out, 1)``).
    smoothings : array_like, shape (s,)
        Candidate ridge terms (non-negative).
    log_values : array_like, shape (m, n_out), optional
        ``log10`` of the values interpolated by the ``log10`` candidates (finite in the columns
        of ``log_candidate``; e.g. floored where a damage is 0). Required with ``log_candidate``.
    log_candidate, linear_candidate : array_like of bool, shape (n_out,), optional
        Which outputs have a ``log10`` / linear candidate (default: none / all).
    retransform : {"none", "smearing", "ratio"}
        Back-transform correction of the ``log10`` candidates (:func:`moorlife.rbf.retransform_factor`).
    share_tol : float
        See :func:`moorlife.rbf.choose_shapes`.

    Returns
    -------
    OutputChoice

    Raises
    ------
    ValueError
        If an output has no candidate, or none gives a well-conditioned system.
    """
    y = np.asarray(values, dtype=float)
    m, n_out = y.shape
    lin_ok = np.ones(n_out, bool) if linear_candidate is None else np.asarray(linear_candidate, bool).copy()
    log_ok = np.zeros(n_out, bool) if log_candidate is None else np.asarray(log_candidate, bool).copy()
    if retransform not in RETRANSFORMS:
        raise ValueError(f"unknown back-transform correction {retransform!r}; expected one of {list(RETRANSFORMS)}")
    ly = np.full_like(y, np.nan) if log_values is None else np.asarray(log_values, dtype=float)
    if log_ok.any() and not np.all(np.isfinite(ly[:, log_ok])):
        raise ValueError("log_values must be finite in every column with a log10 candidate")
    if not (lin_ok | log_ok).all():
        raise ValueError(f"output {int(np.flatnonzero(~(lin_ok | log_ok))[0])} has no transform candidate")
    q_rows = np.asarray(shapes, dtype=float)
    q_rows = np.broadcast_to(q_rows, (n_out, q_rows.shape[-1])) if q_rows.ndim <= 1 else q_rows
    if q_rows.shape[0] != n_out or np.any(~(q_rows > 0)):
        raise ValueError(f"shapes must be positive, one grid or one row per output; got shape {q_rows.shape}")
    lams = np.sort(np.atleast_1d(np.asarray(smoothings, dtype=float)))
    if lams.size == 0 or np.any(~(lams >= 0)):
        raise ValueError(f"smoothing candidates must be non-negative, got {lams}")
    qs = np.unique(q_rows)
    n_sp = len(spaces)
    rms = np.full((n_sp, 2, lams.size, qs.size, n_out), np.inf)
    diag = np.arange(m)
    for si, (d2, basis) in enumerate(spaces):
        for li, lam in enumerate(lams):
            for qi, q in enumerate(qs):
                has_q = (q_rows == q).any(axis=1)
                c_lin, c_log = np.flatnonzero(has_q & lin_ok), np.flatnonzero(has_q & log_ok)
                if c_lin.size + c_log.size == 0:
                    continue
                k = gaussian(d2, float(q))
                if lam:
                    k[diag, diag] += lam
                e, rc = loo_residuals(k, basis, np.concatenate([y[:, c_lin], ly[:, c_log]], axis=1))
                if e is None or rc < MIN_RCOND:
                    continue
                e_lin, e_log = e[:, : c_lin.size], e[:, c_lin.size :]
                rms[si, 0, li, qi, c_lin] = np.sqrt(np.mean(e_lin * e_lin, axis=0))
                if c_log.size:
                    c = retransform_factor(ly[:, c_log], e_log, retransform)
                    eu = loo_error_in_units(y[:, c_log], ly[:, c_log], e_log, c)
                    rms[si, 1, li, qi, c_log] = np.sqrt(np.mean(eu * eu, axis=0))
    flat = rms.reshape(-1, n_out)
    if not np.isfinite(flat).any(axis=0).all():
        bad = int(np.flatnonzero(~np.isfinite(flat).any(axis=0))[0])
        raise ValueError(
            f"output {bad}: no candidate (space, transform, q0 in [{qs[0]:.4g}, {qs[-1]:.4g}], smoothing) "
            "gives a well-conditioned RBF system; lower the shape grid or add smoothing"
        )
    idx = choose_candidates(flat, share_tol)
    si, ti, li, qi = np.unravel_index(idx, rms.shape[:4])
    return OutputChoice(
        space=si.astype(np.int64),
        log_output=ti == 1,
        shape=qs[qi],
        smoothing=lams[li],
        loo_rmse=flat[idx, np.arange(n_out)],
        best=rms.min(axis=(2, 3)),
    )
