"""Gaussian-process regression with a noise term on the sea-state space (issue 22, item 3).

An opt-in alternative to the RBF of :mod:`moorlife.rbf` (``lifecycle.rbf.method: gp``). Each
output ``y`` (or ``log10 y``) of the simulated sea states is modelled as ``f(x) + e``: ``f`` a
Gaussian process with a constant mean (the training mean), a squared-exponential covariance
``s_f^2 exp(-|(x - x') / l|^2 / 2)`` or a Matérn one (``covariance``,
:mod:`~moorlife.gp.covariance`) with one length scale per input coordinate (``ard``) or one for
all (``isotropic``), and ``e`` independent noise of variance ``s_n^2``: the seed noise of a
one-hour record, which an exact interpolant reproduces.

Inputs
    The paper's normalised space (:mod:`moorlife.space`: each scalar by its range), with each
    direction embedded as ``(cos, sin) / pi`` (:func:`chord_embed`): a Euclidean embedding, so the
    kernel is positive definite on the circle, with the folded distance of the RBF to first
    order. Optionally the rotor thrust ``T(W)`` as one more scalar (:mod:`moorlife.lifecycle.spaces`).
Additive wind term (``lifecycle.rbf.gp.wind_term``, opt-in)
    ``f = f_all + f_wind``: beside the kernel of every coordinate, a second one of the same family
    on the wind speed and direction alone, with its own amplitude ``s_w`` and length scales,
    faded by the sea gate ``exp(-z_hs / scale)`` (:class:`~moorlife.gp.kernels.OnColumns` and
    :class:`~moorlife.gp.kernels.SeaGate` in the fit). A line's tension variance is nearly a
    wind part plus a wave part; a product kernel cannot keep the damage flat in Hs where the
    wind drives the line and steep where the waves do.
Hyperparameters
    ``s_f``, ``l`` and ``s_n`` (and ``s_w``, ``l_w``, the gate's scale) per output by the maximum of the log marginal likelihood,
    scikit-learn's :class:`~sklearn.gaussian_process.GaussianProcessRegressor` (L-BFGS-B, optional
    seeded restarts), on all training states or a seeded subsample of them (the cost is cubic).
Conditioning
    With those hyperparameters the process is conditioned on every training state
    (:func:`fit_gp`); the leave-one-out residuals come in closed form (Rasmussen & Williams 2006,
    eq. 5.12), ``r_i = [K^-1 y]_i / [K^-1]_ii`` with the noise in ``K``: the same criterion,
    in the same units, as Rippa's for the RBF.
Back-transform of a ``log10`` output
    The GP gives a Gaussian predictive distribution of ``log10 y`` at ``x``, mean ``mu(x)``,
    variance ``s_n^2 + s^2(x)`` (noise plus the latent posterior variance), so
    ``E[y | x] = 10**mu exp((ln 10)^2 (s_n^2 + s^2(x)) / 2)``. The truth of one hour is one
    realisation, and a life-cycle sum is a sum of such expectations, so the noise belongs in it.
    ``retransform``: ``none`` (``10**mu``, the median), ``noise`` (the factor of ``s_n^2``,
    constant per output) or ``predictive`` (both terms; ``s^2(x)`` costs a triangular solve per
    point and output, see :mod:`moorlife.gp.predict`).

Modules: :mod:`~moorlife.gp.covariance` (the correlation families and the sea gate),
:mod:`~moorlife.gp.kernels` (scikit-learn kernels of some input columns, and gated by the sea),
:mod:`~moorlife.gp.fit` (embedding, hyperparameters, conditioning, leave-one-out, the
models of some outputs) and
:mod:`~moorlife.gp.predict` (mean, latent variance, back-transform, and the weight each training
value carries in a weighted sum of the means, :func:`training_weights`).
"""

from __future__ import annotations

from moorlife.gp.covariance import GP_COVARIANCES, correlation
from moorlife.gp.fit import (
    GP_ADDITIVE_STARTS,
    GP_KERNELS,
    GP_RETRANSFORMS,
    GPModel,
    chord_embed,
    embedded_names,
    fit_gp,
    select_outputs,
)
from moorlife.gp.predict import predict_gp, predict_latent, training_weights

__all__ = [
    "GP_COVARIANCES",
    "GP_KERNELS",
    "GP_ADDITIVE_STARTS",
    "GP_RETRANSFORMS",
    "GPModel",
    "chord_embed",
    "embedded_names",
    "correlation",
    "fit_gp",
    "predict_gp",
    "predict_latent",
    "training_weights",
    "select_outputs",
]
