"""Gaussian radial basis function interpolation on the normalised sea-state space.

The method of Barrera et al. (2019, eq. 15) and Camus et al. (2011): every output of the
simulated sea states is rebuilt at any hindcast hour by

.. math::

    f(x) = \\sum_j w_j \\, \\exp\\big(-(r(x, x_j) / q_0)^2\\big) + p(x),

with ``r`` the normalised 5-D distance of the selection (each scalar divided by its range,
each direction compared on the circle: folded difference, at most 180 deg, divided by 180),
``q0`` the shape parameter and ``p`` a first-degree polynomial. For a direction the
first-degree trend is ``cos`` and ``sin`` of the angle (a linear term in the angle itself
would jump at north); scalar-only data get exactly the classical linear polynomial, so the
interpolant is the one of :class:`scipy.interpolate.RBFInterpolator` with
``kernel="gaussian", epsilon=1/q0, degree=1``.

The weights solve the augmented system ``[[K, P], [P^T, 0]] [w; c] = [y; 0]``. The shape
parameter is chosen per output by Rippa's (1999) leave-one-out criterion in closed form,
``e_k = a_k / (M^{-1})_{kk}`` for the augmented matrix ``M`` (Fasshauer & Zhang 2007), over
a geometric grid, or fixed (the paper: 0.1 for damage, 0.175 for tension). An optional ridge
``lambda`` on the kernel diagonal (``K + lambda I``) is chosen the same way, jointly with
``q0``: the closed form is the exact leave-one-out residual of the smoothed system too, and a
one-hour record's maximum or light-line damage carries seed noise that exact interpolation
would reproduce. Outputs whose leave-one-out curve is flat can share a grid value
(``share_tol``), so prediction evaluates one kernel block per *distinct* shape parameter.

Prediction runs in row chunks (bounded memory), float64, in numba kernels (distance, kernel
block, weighted sums); every row is computed independently in a fixed order, so the numbers do
not depend on chunk size or thread count. The fit uses LAPACK (Cholesky, LU), whose last bit can
depend on the number of BLAS threads: the workflow's ``lifecycle`` rule pins BLAS to one thread.

The normalised space, its distance and its :class:`Space` record live in :mod:`moorlife.space`
(shared with the selection); :func:`normalise` here is :func:`moorlife.space.embed`.

Outputs interpolated as ``log10`` are predicted as ``c 10**f``, with ``c = 1`` or a
retransformation-bias correction from the leave-one-out residuals (:mod:`moorlife.rbf.transform`).
:func:`choose_per_output` chooses, per output and from the training states alone, the input
space, the transform, ``q0`` and ``lambda`` by the leave-one-out error in the output's units;
:func:`fit_rbf_fixed` fits such a choice.

A :class:`Trend` adds piecewise-linear columns in one coordinate (optionally times harmonics of
a direction) to the first-degree polynomial: universal kriging with a spline drift, for a
feature narrower than the kernel along that coordinate (:mod:`moorlife.rbf.trend`).

Modules: :mod:`~moorlife.rbf.kernels` (Gaussian kernel, weighted sums, polynomial basis),
:mod:`~moorlife.rbf.trend` (the piecewise-linear trend), :mod:`~moorlife.rbf.system` (the
augmented system), :mod:`~moorlife.rbf.loocv` (Rippa's leave-one-out choice of shape and
ridge), :mod:`~moorlife.rbf.transform` (back-transform of ``log10`` outputs),
:mod:`~moorlife.rbf.choose` (the per-output choice), :mod:`~moorlife.rbf.fit` and
:mod:`~moorlife.rbf.predict` (values, the nearest centre, and the weight each training value
carries in a weighted sum of the values, :func:`training_weights`).
"""

from __future__ import annotations

from moorlife.rbf.choose import OutputChoice, choose_per_output
from moorlife.rbf.fit import RBFModel, centre_geometry, fit_rbf, fit_rbf_fixed, model_basis
from moorlife.rbf.kernels import gaussian, polynomial_basis
from moorlife.rbf.loocv import (
    MIN_RCOND,
    LOOCurve,
    choose_candidates,
    choose_shapes,
    choose_shapes_and_smoothing,
    loo_curve,
    loo_residuals,
    rippa_errors,
    shape_grid,
)
from moorlife.rbf.predict import nearest_centre, predict_rbf, training_weights
from moorlife.rbf.system import augmented_matrix, kernel_block_inverse, solve_weights
from moorlife.rbf.transform import RETRANSFORMS, loo_error_in_units, retransform_factor
from moorlife.rbf.trend import Trend, supported_trend, trend_basis
from moorlife.space import Space, fit_space, squared_distances
from moorlife.space import embed as normalise

__all__ = [
    "MIN_RCOND",
    "Space",
    "RBFModel",
    "LOOCurve",
    "fit_space",
    "normalise",
    "squared_distances",
    "gaussian",
    "polynomial_basis",
    "augmented_matrix",
    "solve_weights",
    "kernel_block_inverse",
    "rippa_errors",
    "loo_residuals",
    "choose_candidates",
    "choose_shapes_and_smoothing",
    "loo_curve",
    "choose_shapes",
    "shape_grid",
    "fit_rbf",
    "fit_rbf_fixed",
    "centre_geometry",
    "model_basis",
    "Trend",
    "supported_trend",
    "trend_basis",
    "RETRANSFORMS",
    "retransform_factor",
    "loo_error_in_units",
    "OutputChoice",
    "choose_per_output",
    "predict_rbf",
    "training_weights",
    "nearest_centre",
]
