"""Back-transform of ``log10`` outputs: the retransformation-bias factor and errors in the output's units.

An output interpolated as ``log10 y`` is predicted as ``10**f(x)``. If the interpolation error
``e = log10 y - f`` has a symmetric distribution, ``10**f`` is the *median* of ``y`` given the
inputs, not its mean: by Jensen's inequality ``E[10**e] >= 1``, so summing ``10**f`` over many
hours underestimates the sum of ``y`` (the retransformation bias; Duan 1983, Newman 1993). A
multiplicative factor ``c`` turns the median into an estimate of the mean, ``c 10**f(x)``:

``"none"``
    ``c = 1`` (the plain back-transform, the paper's).
``"smearing"``
    Duan's (1983) smearing estimate ``c = mean_k 10**e_k`` over the training states, with
    ``e_k`` Rippa's leave-one-out residuals in ``log10`` space (an exact interpolant has zero
    in-sample residuals; the leave-one-out residual is the error at a state the fit has not
    seen). It assumes the residual distribution does not depend on the inputs, and, as every
    smearing estimate, that the interpolant's own error is small against the scatter of ``y``.
``"ratio"``
    ``c = sum_k y_k / sum_k 10**(log10 y_k - e_k)``: the training values' sum over the sum of
    their leave-one-out predictions. It weights the states by their value, as a sum over the
    hindcast does (the quantity of a life-cycle damage), where smearing weights every state
    equally.

Every factor uses the training states only. :func:`loo_error_in_units` gives the leave-one-out
error of a ``log10`` output in the output's own units, with its factor, so that ``log10`` and
linear candidates can be compared on the same scale (:func:`moorlife.rbf.choose_per_output`).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = ["RETRANSFORMS", "retransform_factor", "loo_error_in_units"]

#: The back-transform corrections of a ``log10`` output (see the module docstring).
RETRANSFORMS: tuple[str, ...] = ("none", "smearing", "ratio")


def retransform_factor(log_values: npt.ArrayLike, loo_error: npt.ArrayLike, method: str = "none") -> np.ndarray:
    """The multiplicative back-transform factor of ``log10`` outputs.

    Parameters
    ----------
    log_values : array_like, shape (m, n_out)
        ``log10`` of the training values.
    loo_error : array_like, shape (m, n_out)
        Leave-one-out residuals ``log10 y_k - f^{(-k)}(x_k)`` (Rippa's closed form).
    method : {"none", "smearing", "ratio"}

    Returns
    -------
    numpy.ndarray, shape (n_out,)
        ``c`` of ``c 10**f(x)``; exactly 1.0 for ``"none"``.

    Raises
    ------
    ValueError
        On an unknown method or mismatched shapes.
    """
    ly = np.asarray(log_values, dtype=float)
    e = np.asarray(loo_error, dtype=float)
    if ly.ndim == 1:
        ly, e = ly[:, None], e.reshape(-1, 1)
    if ly.shape != e.shape:
        raise ValueError(f"log_values {ly.shape} and loo_error {e.shape} differ in shape")
    if method == "none":
        return np.ones(ly.shape[1])
    if method == "smearing":
        return np.mean(10.0**e, axis=0)
    if method == "ratio":
        return np.sum(10.0**ly, axis=0) / np.sum(10.0 ** (ly - e), axis=0)
    raise ValueError(f"unknown back-transform correction {method!r}; expected one of {list(RETRANSFORMS)}")


def loo_error_in_units(
    values: npt.ArrayLike, log_values: npt.ArrayLike, loo_error: npt.ArrayLike, factor: npt.ArrayLike
) -> np.ndarray:
    """Leave-one-out error of ``log10`` outputs in the outputs' own units.

    Parameters
    ----------
    values : array_like, shape (m, n_out)
        Training values in their units (the reference of the error).
    log_values : array_like, shape (m, n_out)
        The ``log10`` values that were interpolated.
    loo_error : array_like, shape (m, n_out)
        Leave-one-out residuals in ``log10`` space.
    factor : array_like, shape (n_out,)
        Back-transform factor (:func:`retransform_factor`).

    Returns
    -------
    numpy.ndarray, shape (m, n_out)
        ``y_k - c 10**(log10 y_k - e_k)``: the value minus the back-transformed prediction of
        the interpolant built without state ``k``.
    """
    ly = np.asarray(log_values, dtype=float)
    return np.asarray(values, dtype=float) - np.asarray(factor, dtype=float) * 10.0 ** (ly - np.asarray(loo_error))
